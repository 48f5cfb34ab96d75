//! Three-dimensional US Navy crane with massless main pulley (paper, sect. 6.1).
//!
//! - [`model`]: the crane declared with `crane_model!` in redundant
//!   coordinates (eqs. 68-81 with (72), (80) as corrected in docs/errata.md);
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): the
//!   paper's manoeuvre (eqs. 82-88, (86) as corrected), the slewing angle,
//!   the drawing;
//! - [`reference`](mod@reference): an analytical flatness-based solution
//!   (not in the paper, which gives none for the 3D cranes): in the plane of
//!   the ropes the crane is the planar crane of Appendix A.

pub mod description;
pub mod model;
pub mod reference;

pub use description::{Description, PaperCase, TAU0, TF, paper_p0, slewing_angle};
pub use model::Navy3d;
