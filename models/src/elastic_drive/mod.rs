//! An overhead crane whose trolley is driven through an elastic belt,
//! beyond the paper: the motor's angle is a coordinate of its own, coupled
//! to the trolley by the belt's stiffness. Its inputs need the load path's
//! 6th derivative, beyond what the paper's minimal extension (eqs. 22, 24)
//! reduces.
//!
//! - [`model`]: the crane declared with `crane_model!`, with its derivation;
//! - [`reference`](mod@reference): its analytical flatness-based solution;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): its
//!   default move, the reference on any path, the drawing.

pub mod description;
pub mod model;
pub mod reference;

pub use description::{DefaultCase, Description, TAU0, TF};
pub use model::ElasticDrive;
