//! Inverse dynamics of underactuated cranes: given a crane and a prescribed
//! load path `gamma(t)`, the motor torques `u(t)` that move the load exactly
//! along it.
//!
//! Declare the crane with [`crane_model!`]; the macro differentiates it at
//! compile time. The servo constraints `x = gamma(t)` make an index-5 DAE;
//! index reduction by minimal extension gives an index-3 DAE that backward
//! Euler (the paper's scheme, the default) or BDF-k, k = 2..5
//! ([`Scheme`](prelude::Scheme)), integrates (paper eqs. 22a-d in redundant
//! coordinates, 24a-e in minimal coordinates). This crate re-exports the macro (`crane-macros`) and
//! the runtime (`crane-runtime`): depend on it alone.
//!
//! # Worked example: a planar gantry crane
//!
//! A trolley at `(s, 0)` pulled by a force `u1`, a hoist winch (inertia `J`,
//! radius `r`, torque `u2`) paying out rope `L`, the load at `(x, z)`: four
//! coordinates, one rope constraint, three degrees of freedom, two inputs.
//!
//! ```
//! use crane::prelude::*;
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
//! // 4 m across and 2 m up in 5 s, rest to rest (eqs. 41-45)
//! let path = Poly9::new(0.0, 5.0, SVector::from([0.0, -5.0]), SVector::from([4.0, -3.0]))?;
//! // a consistent start from a rough guess of the robot coordinates [s, L]
//! let start = init::static_equilibrium(&crane, &path, 0.0, &[0.3, 4.5])?;
//! let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0)?)?;
//!
//! let mid = run.state_near(2.5).unwrap();
//! println!("u(2.5 s) = [{:.1} N, {:.1} N m]", mid.u[0], mid.u[1]);
//! assert!(run.tensions.iter().all(|&n| n > 0.0)); // the rope only pulls
//! // at rest at the end the winch holds the load: u2 = -m_l g r
//! assert!((run.states.last().unwrap().u[1] + 200.0 * 9.81 * 0.1).abs() < 1.0);
//!
//! // the same move with BDF-4: order 4 instead of 1, at the cost per step of
//! // backward Euler; the two agree to backward Euler's O(dt) error
//! let bdf4 = simulate(&crane, &path, &start, &Options::new(0.01, 5.0)?.with_scheme(Scheme::Bdf4))?;
//! let (a, b) = (run.state_near(2.5).unwrap(), bdf4.state_near(2.5).unwrap());
//! assert!((a.u - b.u).norm() < 0.05 * b.u.norm());
//!
//! // flat (the path fixes every state: the declaration says so), so the
//! // torques are the unique ones; a crane with internal dynamics would be
//! // told here (`crane_runtime::internal`)
//! assert_eq!(<Gantry as CraneModel<4, 1, 2>>::STRUCTURE.map(|s| s.dimension), Some(0));
//! assert!(internal::diagnose(&crane, &run, 100).is_usable());
//! # Ok(())
//! # }
//! ```
//!
//! For online use (a controller computing feedforward torques), a
//! [`RedundantStepper`](prelude::RedundantStepper) advances one step at a time
//! from the load target at the new time and does not allocate: see
//! `examples/control_loop.rs`.
#![warn(missing_docs)]

/// The runtime: traits, load paths, initialisation, integrators, results.
pub use crane_runtime as runtime;

/// Declare a crane: see the crate docs and `crane_macros::crane_model!` for
/// the DSL. Generated code refers to this crate's [`runtime`], so depending on
/// `crane` alone is enough.
#[macro_export]
macro_rules! crane_model {
    ($($declaration:tt)*) => {
        $crate::__private::crane_model! { #[crane(runtime = $crate::runtime)] $($declaration)* }
    };
}

#[doc(hidden)]
pub mod __private {
    pub use crane_macros::crane_model;
}

/// Everything a typical program needs: `use crane::prelude::*;`.
pub mod prelude {
    pub use crate::crane_model;
    pub use crane_runtime::check::{SampleBox, check_derivatives, check_minimal_map};
    pub use crane_runtime::nalgebra::{SMatrix, SVector};
    pub use crane_runtime::trajectory::{FromFn, Poly9, ThreePhase, Trajectory};
    pub use crane_runtime::{
        CraneModel, Error, MinimalMap, MinimalStepper, Options, RedundantStepper, Scheme, Solution, State, Stepper,
        init, internal, simulate, simulate_minimal,
    };
}
