//! The paper's cranes, declared with `crane_model!`, with their load paths,
//! starts and analytical flatness-based references.
//!
//! Each built-in crane has one home, a module with its declaration
//! (`model`), its analytical reference where there is one (`reference`,
//! reading the parameters from the generated struct) and its
//! [`Crane`] description (`description`: the default manoeuvre as data, the
//! reference on any path, the minimal-coordinate run, derived outputs, the
//! drawing). The [`registry`](mod@registry) lists them once; the `crane` command, the tests
//! and the benchmarks reach every crane through it. A [`Case`] is a crane on
//! a path from a start: the default manoeuvre, or what a scenario makes of it.
//!
//! ```
//! use crane_models::navy_planar;
//! use crane_runtime::Options;
//!
//! let case = navy_planar::PaperCase::new(4.0).unwrap();       // sect. 5.1.3, tf = 4 s
//! let start = case.start().unwrap();                            // eq. (46), checked
//! let solution = case.simulate(&start, &Options::new(0.01, case.tf()).unwrap()).unwrap();
//! let at = solution.state_near(1.5).unwrap();
//! let e_u = case.relative_input_error(at).unwrap();             // eq. (48), Appendix A
//! assert!(e_u < 1e-2);
//! ```
#![warn(missing_docs)]

pub mod case;
pub mod crane;
pub mod drawing;
pub mod files;
pub mod path;
pub mod plan;
pub mod registry;
pub mod study;

#[cfg(test)]
mod test_support;

pub mod coupled_trolley;
pub mod double_pendulum;
pub mod elastic_drive;
pub mod gantry_3d;
pub mod navy_3d;
pub mod navy_3d_pulley;
pub mod navy_planar;
pub mod navy_planar_pulley;
pub mod tower_crane;

pub use case::Case;
pub use crane::{Crane, Maneuver};
pub use path::{Path, PathSpec, Profile, ProfileKind};
pub use registry::{BuiltIn, CATALOG, Entry, Registry, Visit};
