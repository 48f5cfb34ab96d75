//! [`Crane`]: everything the tool knows about one crane, built-in or a
//! user's, in one place: the model, its default manoeuvre as data, its analytical reference
//! on any path (where it has one), a guess of its minimal coordinates (where
//! its model has a map), derived outputs and its drawing. What formulations
//! a crane runs follows from its model's declaration alone
//! ([`simulate_minimal`], and the dummy-derivative run of
//! [`crane_runtime::dummy_derivative`]), for a built-in crane and a user's
//! alike. The command line, planning,
//! replay, the FMU and the tests all reach a crane through this trait and a
//! [`Registry`](crate::registry::Registry). Only the model, the name and
//! the default manoeuvre are required; everything else has a default.

use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, Error, MinimalMap, Options, Solution, State, VisitMinimalMap};

use crate::drawing::Drawing;
use crate::path::{Path, PathSpec};

/// A crane's default manoeuvre: the load path and the start of the robot
/// coordinates `p0` (checked for consistency when a run starts).
#[derive(Debug, Clone, PartialEq)]
pub struct Maneuver<const A: usize> {
    /// The load path.
    pub path: PathSpec<A>,
    /// The robot coordinates at `t0`, in the model's order.
    pub p0: Vec<f64>,
}

/// A lower bound on a move's duration, and its derivation in one line.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LowerBound {
    /// The duration no move under the limits beats, s.
    pub duration: f64,
    /// How it follows from the crane's mechanics.
    pub derivation: String,
}

/// The bang-bang time `2 sqrt(d m / f)` of a mass `m` moved `d` from rest
/// to rest by a force at most `f`: accelerating at `f / m` for half the
/// way, braking for the other half, the fastest any force history `|F| <=
/// f` moves it.
pub fn bang_bang(distance: f64, mass: f64, force: f64) -> f64 {
    2.0 * (distance.abs() * mass / force).sqrt()
}

/// One crane: the only description the command line, planning, replay and
/// the FMU need. Implemented by a unit type per crane
/// (`navy_planar::Description`, ... for the built-ins), listed once in a
/// [`Registry`](crate::registry::Registry).
pub trait Crane<const N: usize, const M: usize, const A: usize>: 'static {
    /// The crane declared with `crane_model!`; its `Default` has the paper's
    /// (or the example's) parameters.
    type Model: CraneModel<N, M, A> + Clone + Default + Send + Sync;

    /// The name on the command line, e.g. `navy-planar`.
    const NAME: &'static str;
    /// One line on what it is (`list` shows it; empty if not given).
    const DESCRIPTION: &'static str = "";
    /// Whether [`reference`](Self::reference) gives an analytical solution.
    const HAS_REFERENCE: bool = false;
    /// The default manoeuvre.
    fn maneuver() -> Maneuver<A>;

    /// The analytical reference at `t` on `path` for `model`'s parameters,
    /// if the crane has one (and it is finite there).
    fn reference(model: &Self::Model, path: &Path<A>, t: f64) -> Option<State<N, M, A>> {
        let _ = (model, path, t);
        None
    }

    /// A lower bound on the duration of any rest-to-rest move of the load
    /// from `start` to `end` under the limits `|u_k| <= limit` (`(k,
    /// limit)`), where the crane's mechanics give one (the rigid-body
    /// bang-bang time of a drive that alone moves a body of known mass);
    /// `None` (the default) where it gives none.
    fn lower_bound(
        model: &Self::Model,
        start: &SVector<f64, A>,
        end: &SVector<f64, A>,
        limits: &[(usize, f64)],
    ) -> Option<LowerBound> {
        let _ = (model, start, end, limits);
        None
    }

    /// A rough guess of the minimal coordinates `mu` (in the order of the
    /// model's `minimal` block) at the redundant `start`, which the minimal
    /// stepper refines by Gauss-Newton; empty (the default) for `mu = 0`.
    fn minimal_guess(model: &Self::Model, start: &State<N, M, A>) -> Vec<f64> {
        let _ = (model, start);
        Vec::new()
    }

    /// The unit of each input, in the model's order (`"N m"` for a winch or
    /// slewing torque, `"N"` for a trolley force); empty if not given, and
    /// then the command line prints the inputs without one.
    fn input_units() -> &'static [&'static str] {
        &[]
    }

    /// Names of outputs derived from a state (e.g. the slewing angle `phi`);
    /// columns of `results.csv` after the tensions.
    fn derived_outputs() -> &'static [&'static str] {
        &[]
    }

    /// The derived outputs of `state`, in the order of [`derived_outputs`](Self::derived_outputs).
    fn derived(model: &Self::Model, state: &State<N, M, A>) -> Vec<f64> {
        let _ = (model, state);
        Vec::new()
    }

    /// How the crane is drawn with `model`'s parameters.
    fn drawing(model: &Self::Model) -> Option<Drawing> {
        let _ = model;
        None
    }
}

/// A reference state if all of it is finite (the flatness formulas can
/// leave their domain on a user's path).
pub fn finite_state<const N: usize, const M: usize, const A: usize>(state: State<N, M, A>) -> Option<State<N, M, A>> {
    let finite = |s: &[f64]| s.iter().all(|x| x.is_finite());
    (finite(state.q.as_slice())
        && finite(state.v.as_slice())
        && finite(state.u.as_slice())
        && finite(state.lambda.as_slice()))
    .then_some(state)
}

/// The run in minimal coordinates (eqs. 24a-e) of crane `C` on `path` from
/// the redundant `start`, calling `progress(step, steps)` after every step;
/// `None` if its model declares no minimal map. The map's size is the
/// declaration's; the start of `mu` is refined from
/// [`Crane::minimal_guess`].
pub fn simulate_minimal<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &C::Model,
    path: &Path<A>,
    start: &State<N, M, A>,
    options: &Options,
    progress: &mut dyn FnMut(usize, usize),
) -> Option<Result<Solution<N, M, A>, Error>> {
    /// The run, with the map's size.
    struct Run<'a, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
        model: &'a C::Model,
        path: &'a Path<A>,
        start: &'a State<N, M, A>,
        options: &'a Options,
        progress: &'a mut dyn FnMut(usize, usize),
    }
    impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> VisitMinimalMap<C::Model, N, M, A>
        for Run<'_, C, N, M, A>
    {
        type Output = Result<Solution<N, M, A>, Error>;
        fn visit<const F: usize>(self) -> Self::Output
        where
            C::Model: MinimalMap<N, M, A, F>,
        {
            let guess = C::minimal_guess(self.model, self.start);
            let guess = if guess.is_empty() {
                SVector::<f64, F>::zeros()
            } else if guess.len() == F {
                SVector::<f64, F>::from_column_slice(&guess)
            } else {
                return Err(Error::MinimalGuessSize {
                    expected: F,
                    found: guess.len(),
                });
            };
            crane_runtime::minimal::simulate_minimal_with_progress(
                self.model,
                self.path,
                self.start,
                &guess,
                self.options,
                self.progress,
            )
        }
    }
    C::Model::visit_minimal_map(Run::<C, N, M, A> {
        model,
        path,
        start,
        options,
        progress,
    })
}
