//! Planar US Navy crane with pulley mass (paper, sect. 5.2).
//!
//! - [`model`]: the crane declared with `crane_model!` (eqs. 49-58), with
//!   its map to the minimal coordinates of sect. 5.2.2 (eqs. 59-63, ERRATA (60));
//! - [`reference`](mod@reference): the analytical flatness-based solution of
//!   Appendix B (eqs. 113-124, with ERRATA (124h));
//! - [`case`]: the paper's maneuver (eqs. 41, 44, 64-67, ERRATA (66)) as a
//!   [`Case`](crate::Case), also in minimal coordinates (eqs. 24a-e).

pub mod case;
pub mod model;
pub mod reference;

pub use case::{PaperCase, minimal_guess, paper_p0, paper_path};
pub use model::NavyPlanarPulley;
