//! Runtime for crane inverse dynamics by index reduction with minimal extension.
//!
//! A crane declared with `crane_model!` implements [`CraneModel`]. Given a
//! load path `gamma(t)` ([`trajectory`]), a consistent start ([`init`]) and a
//! time step, [`redundant::simulate`] integrates the minimally extended
//! index-3 DAEs of the paper in redundant coordinates (eqs. 22a-d) and
//! returns the inputs `u`, coordinates `q`, multipliers `lambda` and rope
//! tensions of every step ([`Solution`]); [`minimal::simulate_minimal`] does
//! the same in minimal coordinates (eqs. 24a-e).
//!
//! Problems and schemes sit on separate axes. A [`Problem`](problem::Problem)
//! ([`redundant`], [`minimal`], [`forward`]) says which unknowns, residual
//! and iteration matrix a step has; a [`Method`] ([`scheme`]: backward Euler,
//! the paper's and the default, or BDF-2..5, or one's own) says how the
//! rates at the new time follow from the new value and the history; one
//! [`Stepper`] ([`stepper`]) runs any problem on any method, and
//! [`options`] says what a run is ([`Options`], validated once) and
//! [`driver`] runs it (the run loop with its observers). A new scheme
//! touches no problem and a new problem no scheme.
//! [`forward`] is the crane driven by given inputs, and [`replay`] drives
//! it with the torques an inverse run computed (on the planned or another
//! plant).
//!
//! # Worked example: a planar gantry crane
//!
//! A trolley at `(s, 0)` driven by a force `u1`, a hoist winch (inertia `J`,
//! radius `r`, torque `u2`) paying out the rope length `L`, and the load at
//! `(x, z)` on the rope: `n = 4` coordinates, `m = 1` constraint, `f = 3`
//! degrees of freedom, `a = 2` inputs: underactuated, so the inputs that move
//! the load along a path without swinging come from the index-reduced DAE.
//!
//! ```
//! use crane_macros::crane_model;
//! use crane_runtime::{init, simulate, Options};
//! use crane_runtime::trajectory::Poly9;
//! use crane_runtime::nalgebra::vector;
//!
//! crane_model! {
//!     /// Planar gantry crane: trolley, hoist winch, load on one rope.
//!     pub struct Gantry {
//!         params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
//!         robot  [s, L]
//!         load   [x, z]
//!         inputs [u1, u2]
//!         kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
//!         forces { s: u1, L: u2/r, z: -m_l*g }
//!         constraints {
//!             #[rope(N = L)]
//!             rope: 0.5*((x - s)^2 + z^2 - L^2),
//!         }
//!     }
//! }
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let crane = Gantry::default();
//! // move the load 4 m across and 2 m up in 5 s, rest to rest (eqs. 41-45)
//! let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0])?;
//! // consistent start from a rough guess of p = [s, L]
//! let start = init::static_equilibrium(&crane, &path, 0.0, &[0.3, 4.5])?;
//! assert!((start.q[0] - 0.0).abs() < 1e-9 && (start.q[1] - 5.0).abs() < 1e-9);
//!
//! let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0)?)?;
//! let mid = run.state_near(2.5).unwrap();
//! println!("u(2.5 s) = {} (trolley force N, winch torque N m)", mid.u);
//! // the rope holds the load: tension N = lambda L stays positive
//! assert!(run.tensions.iter().all(|&n| n > 0.0));
//! // at rest at the end the winch holds the load's weight: u2 = -m_l g r
//! let end = run.states.last().unwrap();
//! assert!((end.u[1] + 200.0 * 9.81 * 0.1).abs() < 1.0);
//! # Ok(())
//! # }
//! ```
#![warn(missing_docs)]

pub mod check;
pub mod driver;
pub mod dummy_derivative;
pub mod error;
pub mod forward;
pub mod init;
pub mod internal;
pub mod linsolve;
pub mod minimal;
pub mod model;
pub mod newton;
pub mod options;
pub mod problem;
pub mod redundant;
pub mod replay;
pub mod scheme;
pub mod solution;
pub mod stepper;
pub mod trajectory;

#[cfg(test)]
mod test_support;

pub use error::Error;
pub use forward::ForwardStepper;
pub use minimal::{MinimalStepper, simulate_minimal};
pub use model::{
    CraneModel, DummyDerivatives, MapDerivatives, MinimalMap, ModelInfo, Rope, Scalar, Structure, UnknownParameter,
};
pub use options::Options;
pub use redundant::{RedundantStepper, simulate};
pub use scheme::{Method, Scheme};
pub use solution::{Solution, State};
pub use stepper::{Advance, StepReport, Stepper};
pub use trajectory::Trajectory;

/// Re-exported so generated code and users name the same versions.
pub use nalgebra;
/// Re-exported so generated code and users name the same versions.
pub use num_dual;
