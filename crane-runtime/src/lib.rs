//! Runtime for crane inverse dynamics by index reduction with minimal extension.
//!
//! A crane declared with `crane_model!` implements [`CraneModel`]. Given a
//! load path `gamma(t)` ([`trajectory`]), a consistent start ([`init`]) and a
//! time step, [`redundant::simulate`] integrates the minimally extended
//! index-3 DAEs of the paper in redundant coordinates with backward Euler
//! (eqs. 22a-d) and returns the inputs `u`, coordinates `q`, multipliers
//! `lambda` and rope tensions of every step ([`Solution`]).
#![warn(missing_docs)]

pub mod check;
pub mod error;
pub mod init;
pub mod linsolve;
pub mod model;
pub mod newton;
pub mod redundant;
pub mod solution;
pub mod trajectory;

pub use error::Error;
pub use model::{CraneModel, ModelInfo, Rope, Scalar, UnknownParameter};
pub use redundant::{Options, RedundantStepper, simulate};
pub use solution::{Solution, State};
pub use trajectory::Trajectory;

/// Re-exported so generated code and users name the same versions.
pub use nalgebra;
/// Re-exported so generated code and users name the same versions.
pub use num_dual;
