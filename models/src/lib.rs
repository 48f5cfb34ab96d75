//! The paper's cranes, declared with `crane_model!`, with their load paths,
//! starts and analytical flatness-based references.
//!
//! Each crane comes as a [`Case`]: model, path, consistent start and, where the
//! paper has one, the analytical reference solution, so that tests, the
//! benchmarks and the `crane` command run every crane through the same code.
//!
//! ```
//! use crane_models::{Case, navy_planar};
//! use crane_runtime::{simulate, Options};
//!
//! let case = navy_planar::PaperCase::new(4.0).unwrap();       // sect. 5.1.3, tf = 4 s
//! let start = case.start().unwrap();                            // eq. (46), checked
//! let solution = simulate(case.model(), case.path(), &start, &Options::new(0.01, case.tf())).unwrap();
//! let at = solution.state_near(1.5).unwrap();
//! let reference = case.reference(at.t).unwrap();                // Appendix A
//! let e_u = (at.u - reference.u).norm() / reference.u.norm(); // eq. (48)
//! assert!(e_u < 1e-2);
//! ```
#![warn(missing_docs)]

use crane_runtime::{CraneModel, Error, Options, Solution, State, Trajectory};

pub mod navy_planar;
pub mod navy_planar_pulley;
pub mod navy_3d;
pub mod navy_3d_pulley;

/// A crane with a load path, a start and optionally an analytical reference.
pub trait Case<const N: usize, const M: usize, const A: usize> {
    /// The crane.
    type Model: CraneModel<N, M, A>;
    /// The load path.
    type Path: Trajectory<A>;

    /// The crane with its parameters.
    fn model(&self) -> &Self::Model;
    /// The prescribed load path `gamma(t)`.
    fn path(&self) -> &Self::Path;
    /// Start time.
    fn t0(&self) -> f64;
    /// End time.
    fn tf(&self) -> f64;
    /// The consistent start at `t0`, checked against the model's equations.
    fn start(&self) -> Result<State<N, M, A>, Error>;
    /// The analytical reference at `t`, if the crane has one.
    fn reference(&self, t: f64) -> Option<State<N, M, A>>;

    /// Names of outputs derived from a state (e.g. the slewing angle `phi`
    /// of the 3D cranes); columns of the results after the tensions.
    fn derived_outputs(&self) -> &'static [&'static str] {
        &[]
    }

    /// The derived outputs of `state`, in the order of [`derived_outputs`](Self::derived_outputs).
    fn derived(&self, state: &State<N, M, A>) -> Vec<f64> {
        let _ = state;
        Vec::new()
    }

    /// Run the inverse dynamics in minimal coordinates (eqs. 24a-e) from
    /// `start`, if the crane declares a minimal-coordinate map; `None` if not.
    fn simulate_minimal(&self, start: &State<N, M, A>, options: &Options) -> Option<Result<Solution<N, M, A>, Error>> {
        self.simulate_minimal_with_progress(start, options, &mut |_, _| {})
    }

    /// [`simulate_minimal`](Self::simulate_minimal), calling
    /// `progress(step, steps)` after every step.
    fn simulate_minimal_with_progress(
        &self,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        let _ = (start, options, progress);
        None
    }
}

/// A built-in model, as `crane list` shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    /// Name on the command line.
    pub name: &'static str,
    /// One line on what it is.
    pub description: &'static str,
    /// Redundant coordinates `n`.
    pub n: usize,
    /// Holonomic constraints `m`.
    pub m: usize,
    /// Inputs = load coordinates `a`.
    pub a: usize,
    /// Whether an analytical reference exists.
    pub reference: bool,
}

impl Entry {
    /// Degrees of freedom `f = n - m`.
    pub fn dof(&self) -> usize {
        self.n - self.m
    }
}

/// The built-in models.
pub const CATALOG: &[Entry] = &[Entry {
    name: "navy-planar",
    description: "planar US Navy crane, massless pulley (paper sect. 5.1)",
    n: navy_planar::NavyPlanar::N,
    m: navy_planar::NavyPlanar::M,
    a: navy_planar::NavyPlanar::A,
    reference: true,
}, Entry {
    name: "navy-planar-pulley",
    description: "planar US Navy crane with pulley mass (paper sect. 5.2)",
    n: navy_planar_pulley::NavyPlanarPulley::N,
    m: navy_planar_pulley::NavyPlanarPulley::M,
    a: navy_planar_pulley::NavyPlanarPulley::A,
    reference: true,
}, Entry {
    name: "navy-3d",
    description: "3D US Navy crane, massless pulley, slewing (paper sect. 6.1)",
    n: navy_3d::Navy3d::N,
    m: navy_3d::Navy3d::M,
    a: navy_3d::Navy3d::A,
    reference: true,
}, Entry {
    name: "navy-3d-pulley",
    description: "3D US Navy crane with pulley mass, slewing (paper sect. 6.2)",
    n: navy_3d_pulley::Navy3dPulley::N,
    m: navy_3d_pulley::Navy3dPulley::M,
    a: navy_3d_pulley::Navy3dPulley::A,
    reference: false,
}];
