//! Planar US Navy crane with massless main pulley (paper, sect. 5.1).
//!
//! - [`model`]: the crane declared with `crane_model!` (eqs. 25-35);
//! - [`reference`](mod@reference): the analytical flatness-based solution of Appendix A;
//! - [`case`]: the paper's maneuver (eqs. 41-47) as a [`Case`](crate::Case).

pub mod case;
pub mod model;
pub mod reference;

pub use case::{PaperCase, minimal_guess, paper_p0, paper_path};
pub use model::NavyPlanar;
