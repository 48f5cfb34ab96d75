//! Three-dimensional US Navy crane with nonzero pulley mass (paper, sect. 6.2).
//!
//! - [`model`]: the crane declared with `crane_model!` in redundant
//!   coordinates (eqs. 89-96 with (92), (94) as corrected in docs/errata.md
//!   and the implicit parameters `beta2 = 3/2`, `z3 = (k + l) cos(alpha)`);
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): the
//!   paper's manoeuvre (eqs. 97-100 with the three-phase path of eqs. 85-86,
//!   (86) and (99) as corrected), the same manoeuvre on the C6 profile, the
//!   slewing angle, the drawing.
//!
//! No analytical reference: the paper gives none for the 3D cranes.

pub mod description;
pub mod model;

pub use description::{Description, PaperCase, TAU0, TF, paper_p0, slewing_angle};
pub use model::Navy3dPulley;
