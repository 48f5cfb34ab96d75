//! A 3D gantry (bridge) crane, beyond the paper.
//!
//! - [`model`]: the crane declared with `crane_model!`, with its derivation;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): its
//!   default move and drawing.

pub mod description;
pub mod model;

pub use description::{DefaultCase, Description, TF};
pub use model::Gantry3d;
