//! Three-dimensional US Navy crane with massless main pulley (paper, sect. 6.1).
//!
//! - [`model`]: the crane declared with `crane_model!` in redundant
//!   coordinates (eqs. 68-81 with ERRATA (72), (80));
//! - [`case`]: the paper's maneuver (eqs. 82-88, ERRATA (86)) as a
//!   [`Case`](crate::Case);
//! - [`reference`](mod@reference): an analytical flatness-based solution
//!   (not in the paper, which gives none for the 3D cranes): in the plane of
//!   the ropes the crane is the planar crane of Appendix A.

pub mod case;
pub mod model;
pub mod reference;

pub use case::{PaperCase, TAU0, TF, paper_p0, paper_path, slewing_angle};
pub use model::Navy3d;
