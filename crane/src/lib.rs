//! Inverse dynamics of underactuated cranes: given a crane and a prescribed
//! load path `gamma(t)`, the motor torques `u(t)` that move the load exactly
//! along it.
//!
//! Declare the crane with [`crane_model!`]; the macro differentiates it at
//! compile time. The servo constraints `x = gamma(t)` make an index-5 DAE;
//! index reduction by minimal extension gives an index-3 DAE that backward
//! Euler (the paper's scheme, the default) or BDF-k, k = 2..5
//! ([`Scheme`](prelude::Scheme)), integrates (paper eqs. 22a-d in redundant
//! coordinates, 24a-e in minimal coordinates). For a flat crane whose inputs
//! need more derivatives of the path than the minimal extension reduces,
//! the servo problem reduced by dummy derivatives is solved exactly at each
//! step instead (below). This crate carries the whole API; depend on it
//! alone:
//!
//! | module | what |
//! |---|---|
//! | [`crane_model!`], [`prelude`] | declare a crane, run it |
//! | [`runtime`] | problems, schemes, the stepper, paths, starts, diagnosis |
//! | [`models`] | the built-in cranes with their references, [`Case`](models::Case), the [`Crane`](models::Crane) description |
//! | [`study`] | what a run means: summary, feasibility, warnings, convergence, replay policy |
//! | [`plan`] | the fastest feasible move, parameter sweeps |
//! | [`replay`], [`forward`] | the computed torques on the forward dynamics (another plant, feedback) |
//! | [`registry!`], [`registry`](mod@registry) | the cranes a tool knows, by name |
//! | [`fmi`] (feature `fmu`, on by default) | any crane as an FMI 2.0 co-simulation FMU |
//! | [`cli`] (feature `cli`, on by default) | the whole `crane` command line for a user's cranes |
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
//! // told here (`crane::runtime::internal`)
//! assert_eq!(<Gantry as CraneModel<4, 1, 2>>::STRUCTURE.map(|s| s.dimension), Some(0));
//! assert!(internal::diagnose(&crane, &run, 100).is_usable());
//! # Ok(())
//! # }
//! ```
//!
//! # One step at a time: the stepper
//!
//! For online use (a controller computing feedforward torques) the
//! [`Stepper`](prelude::Stepper) runs a problem (here the servo problem in
//! redundant coordinates, [`Redundant`](prelude::Redundant)) one step at a
//! time from the load target at the new time, without allocating
//! (`examples/control_loop.rs` drives it in a simulated 100 Hz loop). Any
//! [`Method`](prelude::Method) is a scheme for it: the built-in BDF-k or one
//! of your own.
//!
//! ```
//! use crane::models::navy_planar::PaperCase;
//! use crane::prelude::*;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let case = PaperCase::new(4.0)?;
//! let start = case.start()?;
//! let options = Options::stepping(0.01)?.with_scheme(Scheme::Bdf2);
//! let mut stepper = Stepper::new(Redundant::new(case.model(), case.path()), &start, &options)?;
//! for k in 1..=150 {
//!     let t = 0.01 * k as f64;
//!     // what a controller receives: gamma, gamma', gamma'' at the new time
//!     let target = [0, 1, 2].map(|d| case.path().derivative(t, d));
//!     stepper.step_to(t, &target)?;
//! }
//! let reference = case.reference(1.5).unwrap();
//! assert!((stepper.state().u - reference.u).norm() < 1e-3 * reference.u.norm()); // BDF-2 at dt = 0.01
//! # Ok(())
//! # }
//! ```
//!
//! # Any path order: dummy derivatives
//!
//! The minimal extension of eqs. (22, 24) reduces cranes whose inputs need
//! the load path's 4th derivative. For every flat crane it declares,
//! `crane_model!` also generates the servo problem differentiated by
//! Pryce's offsets with every derivative an unknown of its own
//! ([`DummyDerivatives`](prelude::DummyDerivatives)): one algebraic system
//! per time, which nothing discretises, so its inputs are exact at any step.
//! The double pendulum's inputs need the path's 6th derivative; eqs. (22)
//! approach them at the scheme's order, the reduced formulation matches
//! the analytical reference to round-off at every step:
//!
//! ```
//! use crane::models::double_pendulum::DefaultCase;
//! use crane::prelude::*;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let case = DefaultCase::maneuver()?;
//! let start = case.start()?;
//! let options = Options::new(0.05, case.tf())?; // 200 steps
//! let run = simulate_dummy_derivative(case.model(), case.path(), &start, &options, &mut |_, _| {})?;
//! for state in &run.states {
//!     assert!(case.relative_input_error(state).unwrap() < 1e-12);
//! }
//! # Ok(())
//! # }
//! ```
//!
//! # A run and what it means: [`study`]
//!
//! A built-in crane (or a [`Crane`](models::Crane) description of one's
//! own) on its default manoeuvre, with the summary `crane run` writes:
//! peaks, ropes, errors against the analytical reference, internal
//! dynamics, and the [`audit`](study::audit()) of what it found. Here in
//! the paper's eqs. (22a-d) with backward Euler (`RunSettings::default()`,
//! which knows no crane); `crane run` takes the crane's own default,
//! [`Formulation::default_for`](study::Formulation::default_for): for this
//! flat crane the reduced system, whose error is round-off.
//!
//! ```
//! use crane::models::navy_planar::PaperCase;
//! use crane::study::{self, RunSettings};
//!
//! let case = PaperCase::new(4.0).unwrap(); // the paper's sect. 5.1.3
//! let outcome = study::run(&case, &RunSettings::default(), &mut |_, _| {}).unwrap();
//! let reference = outcome.summary.reference.as_ref().unwrap();
//! assert!(reference.e_u_at_1_5s.unwrap() < 2e-3); // eq. (48), Fig. 7
//! assert!(study::audit(&outcome.summary).is_empty()); // on its constraints, taut, flat
//! ```
//!
//! # The fastest feasible move: [`plan`]
//!
//! ```
//! use crane::models::navy_planar::PaperCase;
//! use crane::plan::{Limits, Settings, fastest};
//!
//! let case = PaperCase::maneuver().unwrap();
//! // |u2| <= 150 N m, and both ropes taut
//! let limits = Limits { torque: vec![(1, 150.0)], tension: vec![] };
//! let limits = limits.with_taut_ropes::<crane::models::navy_planar::NavyPlanar, 7, 3, 2>();
//! let best = fastest(&case, &limits, &Settings::default()).unwrap();
//! println!("T* = {:.4} s, bound by {}", best.duration, best.binding.name);
//! assert!(best.duration < 4.0 && best.interval.holds);
//! ```
//!
//! # The torques on another plant: [`replay`]
//!
//! The computed torques (BDF-4) drive the forward dynamics ([`forward`]) of
//! the planned crane, whose load follows its path to the integration error
//! (3e-5 m), and of one whose load is 10 % heavier, which the winches do not
//! hold: it leaves the path by metres.
//!
//! ```
//! use crane::models::navy_planar_pulley::PaperCase;
//! use crane::prelude::*;
//! use crane::replay::{ReplayOptions, replay};
//!
//! let case = PaperCase::new(4.0).unwrap();
//! let start = case.start().unwrap();
//! let options = Options::new(0.01, 4.0).unwrap().with_scheme(Scheme::Bdf4);
//! let planned = case.simulate(&start, &options).unwrap();
//! let mut heavier = case.model().clone();
//! heavier.m_l *= 1.1;
//! let options = ReplayOptions::new(2.0, Scheme::Bdf2);
//! let on_planned = replay(case.model(), case.path(), &planned, &options).unwrap();
//! let on_heavier = replay(&heavier, case.path(), &planned, &options).unwrap();
//! assert!(on_planned.max_load_deviation < 1e-4);
//! assert!(on_heavier.max_load_deviation > 1.0);
//! ```
//!
//! # Any crane as an FMU: [`fmi`]
//!
//! A `cdylib` crate declares its crane, describes its default move (a
//! [`Crane`](models::Crane)) and exports the FMI functions with
//! `crane::fmi::export_fmu!(MyCrane);` (or `export_fmu!(registry =
//! MyCranes)`); `crane::fmi::package::package` writes the `.fmu`, as the
//! `fmu` command of a tool of one's own does (below). The state machine
//! behind the C functions runs in Rust too:
//!
//! ```
//! # #[cfg(feature = "fmu")] {
//! use crane::fmi::instance::{Component, Instance};
//! use crane::models::navy_planar;
//!
//! let mut fmu = Instance::<navy_planar::Description, 7, 3, 2>::new().unwrap();
//! fmu.setup_experiment(0.0).unwrap();
//! fmu.enter_initialization_mode().unwrap();
//! fmu.exit_initialization_mode().unwrap(); // the consistent start
//! fmu.do_step(0.0, 0.1).unwrap(); // ten internal steps of dt = 0.01 s
//! assert!((fmu.time() - 0.1).abs() < 1e-12);
//! # }
//! ```
//!
//! # A crane tool of your own: [`cli`]
//!
//! The whole `crane` command line (`list | run | bench | convergence |
//! fastest | sweep | fmu`, with scenario files, outputs and plots) for the
//! cranes of a [`registry!`]: the crane's one description is its
//! [`Crane`](models::Crane) implementation (model, name and default
//! manoeuvre required, the rest optional).
//!
//! ```no_run
//! use crane::prelude::*;
//!
//! crane_model! {
//!     /// Planar gantry crane: trolley, hoist winch, load on one rope.
//!     pub struct Gantry {
//!         params { m_t: positive = 50.0, m_l: positive = 200.0, J: positive = 0.05,
//!                  r: positive = 0.1, g: positive = 9.81 }
//!         robot  [s, L]
//!         load   [x, z]
//!         inputs [u1, u2]
//!         kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
//!         forces { s: u1, L: u2/r, z: -m_l*g }
//!         constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
//!     }
//! }
//!
//! /// The crane and its default move: 4 m across and 2 m up in 5 s.
//! pub struct PlanarGantry;
//!
//! impl Crane<4, 1, 2> for PlanarGantry {
//!     type Model = Gantry;
//!     const NAME: &'static str = "planar-gantry";
//!     fn maneuver() -> Maneuver<2> {
//!         let (start, end) = (SVector::from([0.0, -5.0]), SVector::from([4.0, -3.0]));
//!         Maneuver {
//!             path: PathSpec { profile: Profile::Poly9, t0: 0.0, t1: 5.0, start, end },
//!             p0: vec![0.0, 5.0], // the start guess [s, L]
//!         }
//!     }
//! }
//!
//! crane::registry! {
//!     /// The cranes of this tool.
//!     pub struct MyCranes { PlanarGantry }
//! }
//!
//! // the user's crane first, then the built-in ones
//! fn main() -> std::process::ExitCode {
//!     crane::cli::Tool::new((MyCranes, BuiltIn)).main()
//! }
//! ```
//!
//! `examples/user-cli/` is such a crate, with its FMU exported from the
//! same library.
#![warn(missing_docs)]

/// The runtime: traits, problems, schemes, the stepper, load paths,
/// initialisation, results, diagnosis.
pub use crane_runtime as runtime;

/// The built-in cranes with their references, cases and descriptions.
pub use crane_models as models;

/// What a run means: summary, feasibility, warnings, convergence, replay policy.
pub use crane_models::study;

/// Planning: the fastest feasible move and parameter sweeps.
pub use crane_models::plan;

/// Replay: the computed torques on the forward dynamics of a plant.
pub use crane_runtime::replay;

/// The forward problem: a crane driven by given inputs.
pub use crane_runtime::forward;

/// FMI 2.0 co-simulation export (feature `fmu`).
#[cfg(feature = "fmu")]
pub use crane_fmi as fmi;

/// The command line of a crane tool as a library (feature `cli`): a
/// user's binary is `crane::cli::Tool::new(MyCranes).main()`.
#[cfg(feature = "cli")]
pub use crane_cli as cli;

#[cfg(feature = "python")]
pub mod python;

/// Registries of cranes by name, and the [`registry!`] macro that makes
/// one of a user's cranes.
pub use crane_models::registry;

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
    pub use crane_models::{BuiltIn, Case, Crane, Maneuver, Path, PathSpec, Profile, ProfileKind, Registry};
    pub use crane_runtime::check::{SampleBox, check_derivatives, check_minimal_map};
    pub use crane_runtime::dummy_derivative::{DummyDerivative, DummyDerivativeStepper, simulate_dummy_derivative};
    pub use crane_runtime::nalgebra::{SMatrix, SVector};
    pub use crane_runtime::trajectory::{FromFn, Poly9, SmoothThreePhase, ThreePhase, Trajectory};
    pub use crane_runtime::{
        Advance, CraneModel, DummyDerivatives, Error, ForwardStepper, Method, MinimalMap, MinimalStepper, Options,
        RedundantStepper, Scheme, Solution, State, Stepper, dummy_derivative, forward, init, internal, minimal,
        redundant, simulate, simulate_minimal,
    };
    pub use crane_runtime::{forward::Forward, minimal::Minimal, redundant::Redundant};
}
