//! A planar trolley crane that is not flat, beyond the paper: a constant
//! coupling between trolley and load in the kinetic energy gives its inverse
//! problem unstable internal dynamics (see [`model`]). It is the built-in
//! example of what `crane run` reports for such a crane.
//!
//! - [`model`]: the crane declared with `crane_model!`, with its derivation;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): its
//!   default move and the drawing.

pub mod description;
pub mod model;

pub use description::{DefaultCase, Description, TF};
pub use model::CoupledTrolley;
