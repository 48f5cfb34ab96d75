//! Three-dimensional US Navy crane with nonzero pulley mass (paper, sect. 6.2).
//!
//! - [`model`]: the crane declared with `crane_model!` in redundant
//!   coordinates (eqs. 89-96 with ERRATA (92), (94) and the implicit
//!   parameters `beta2 = 3/2`, `z3 = (k + l) cos(alpha)`);
//! - [`case`]: the paper's maneuver (eqs. 97-100 with the three-phase path of
//!   eqs. 85-86, ERRATA (86), (99)) as a [`Case`](crate::Case), and the same
//!   maneuver on the C6 profile [`SmoothThreePhase`](crane_runtime::trajectory::SmoothThreePhase)
//!   (ERRATA, "Smoothness needed by the 3D crane with pulley mass").
//!
//! No analytical reference: the paper gives none for the 3D cranes.

pub mod case;
pub mod model;

pub use case::{PaperCase, Path, Profile, TAU0, TF, paper_p0, paper_path, slewing_angle};
pub use model::Navy3dPulley;
