//! Planar US Navy crane with massless main pulley (paper, sect. 5.1).
//!
//! - [`model`]: the crane declared with `crane_model!` (eqs. 25-35);
//! - [`reference`](mod@reference): the analytical flatness-based solution of Appendix A;
//! - [`description`]: the crane as a built-in [`Crane`](crate::Crane): the
//!   paper's manoeuvre (eqs. 41-47), the reference on any path, minimal
//!   coordinates, the drawing.

pub mod description;
pub mod model;
pub mod reference;

pub use description::{Description, PaperCase, minimal_guess, paper_p0};
pub use model::NavyPlanar;
