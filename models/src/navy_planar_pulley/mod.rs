//! Planar US Navy crane with pulley mass (paper, sect. 5.2).
//!
//! - [`model`]: the crane declared with `crane_model!` (eqs. 49-58), with
//!   its map to the minimal coordinates of sect. 5.2.2 (eqs. 59-63, eq. (60)
//!   as corrected in docs/errata.md);
//! - [`reference`](mod@reference): the analytical flatness-based solution of
//!   Appendix B (eqs. 113-124, (124h) as corrected);
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): the
//!   paper's manoeuvre (eqs. 41, 44, 64-67, (66) as corrected), the
//!   reference on any path, minimal coordinates, the drawing.

pub mod description;
pub mod model;
pub mod reference;

pub use description::{Description, PaperCase, minimal_guess, paper_p0};
pub use model::NavyPlanarPulley;
