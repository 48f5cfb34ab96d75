//! A rotary tower crane, beyond the paper.
//!
//! - [`model`]: the crane declared with `crane_model!`, with its derivation;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): its
//!   default move, the slewing angle and the drawing.

pub mod description;
pub mod model;

pub use description::{DefaultCase, Description, TF, slewing_angle};
pub use model::TowerCrane;
