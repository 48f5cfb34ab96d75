//! A 3D gantry (bridge) crane, beyond the paper.
//!
//! - [`model`]: the crane declared with `crane_model!`, with its derivation;
//! - [`reference`](mod@reference): its analytical flatness-based solution;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): its
//!   default move, the reference on any path, the drawing.

pub mod description;
pub mod model;
pub mod reference;

pub use description::{DefaultCase, Description, TF};
pub use model::Gantry3d;
