//! Runtime for crane inverse dynamics by index reduction with minimal extension.
#![warn(missing_docs)]

pub mod model;
pub mod trajectory;

pub use model::{CraneModel, ModelInfo, Rope, Scalar, UnknownParameter};
pub use trajectory::Trajectory;

/// Re-exported so generated code and users name the same versions.
pub use nalgebra;
/// Re-exported so generated code and users name the same versions.
pub use num_dual;
