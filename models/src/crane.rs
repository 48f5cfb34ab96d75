//! [`Crane`]: everything the tool knows about one crane, built-in or a
//! user's, in one place: the model, its default manoeuvre as data, its analytical reference
//! on any path (where it has one), its minimal-coordinate run (where it has a
//! map), derived outputs and its drawing. The command line, planning,
//! replay, the FMU and the tests all reach a crane through this trait and a
//! [`Registry`](crate::registry::Registry). Only the model, the name and
//! the default manoeuvre are required; everything else has a default.

use crane_runtime::{Advance, CraneModel, Error, Options, Solution, State};

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
    /// Whether [`simulate_minimal`](Self::simulate_minimal) runs.
    const HAS_MINIMAL_MAP: bool = false;
    /// Whether [`simulate_dummy_derivative`](Self::simulate_dummy_derivative)
    /// runs (every crane without internal dynamics).
    const HAS_DUMMY_DERIVATIVES: bool = false;

    /// The default manoeuvre.
    fn maneuver() -> Maneuver<A>;

    /// The analytical reference at `t` on `path` for `model`'s parameters,
    /// if the crane has one (and it is finite there).
    fn reference(model: &Self::Model, path: &Path<A>, t: f64) -> Option<State<N, M, A>> {
        let _ = (model, path, t);
        None
    }

    /// The run in minimal coordinates (eqs. 24a-e) from `start`, if the crane
    /// declares a minimal map (with its rough guess of `mu` at the start).
    fn simulate_minimal(
        model: &Self::Model,
        path: &Path<A>,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        let _ = (model, path, start, options, progress);
        None
    }

    /// The run of the servo problem reduced by dummy derivatives
    /// ([`crane_runtime::dummy_derivative`]: exact at every step time for a
    /// flat crane, whatever the path order) from `start`, if the crane has
    /// no internal dynamics.
    fn simulate_dummy_derivative(
        model: &Self::Model,
        path: &Path<A>,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        let _ = (model, path, start, options, progress);
        None
    }

    /// A stepper of the dummy-derivative formulation that owns its model
    /// and path (for long-lived runs such as an FMU instance), if the crane
    /// has no internal dynamics.
    #[allow(clippy::type_complexity)]
    fn dummy_derivative_stepper(
        model: Box<Self::Model>,
        path: Path<A>,
        start: &State<N, M, A>,
        options: &Options,
    ) -> Option<Result<Box<dyn Advance<N, M, A, Model = Self::Model>>, Error>> {
        let _ = (model, path, start, options);
        None
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

/// The [`Crane::simulate_minimal`] of a crane that declares a minimal map:
/// `minimal_run!((N, M, A), |model, start| guess);` inside its `impl
/// Crane`, with `guess` a rough guess of `mu` at the redundant `start`
/// (the minimal stepper refines it by Gauss-Newton).
macro_rules! minimal_run {
    (($n:literal, $m:literal, $a:literal), |$model:ident, $start:ident| $guess:expr) => {
        fn simulate_minimal(
            $model: &Self::Model,
            path: &$crate::path::Path<$a>,
            $start: &crane_runtime::State<$n, $m, $a>,
            options: &crane_runtime::Options,
            progress: &mut dyn FnMut(usize, usize),
        ) -> Option<Result<crane_runtime::Solution<$n, $m, $a>, crane_runtime::Error>> {
            let guess = $guess;
            Some(crane_runtime::minimal::simulate_minimal_with_progress(
                $model, path, $start, &guess, options, progress,
            ))
        }
    };
}
pub(crate) use minimal_run;

/// [`Crane::HAS_DUMMY_DERIVATIVES`], [`Crane::simulate_dummy_derivative`] and
/// [`Crane::dummy_derivative_stepper`]
/// of a flat crane: `dummy_derivative_run!((N, M, A, J));` inside its `impl
/// Crane`, with `J` the size of its dummy-derivative system (the `J` of the
/// model's `DummyDerivatives` implementation).
macro_rules! dummy_derivative_run {
    (($n:literal, $m:literal, $a:literal, $j:literal)) => {
        const HAS_DUMMY_DERIVATIVES: bool = true;

        fn simulate_dummy_derivative(
            model: &Self::Model,
            path: &$crate::path::Path<$a>,
            start: &crane_runtime::State<$n, $m, $a>,
            options: &crane_runtime::Options,
            progress: &mut dyn FnMut(usize, usize),
        ) -> Option<Result<crane_runtime::Solution<$n, $m, $a>, crane_runtime::Error>> {
            Some(crane_runtime::dummy_derivative::simulate_dummy_derivative::<
                _,
                _,
                _,
                $n,
                $m,
                $a,
                $j,
            >(model, path, start, options, progress))
        }

        fn dummy_derivative_stepper(
            model: Box<Self::Model>,
            path: $crate::path::Path<$a>,
            start: &crane_runtime::State<$n, $m, $a>,
            options: &crane_runtime::Options,
        ) -> Option<Result<Box<dyn crane_runtime::Advance<$n, $m, $a, Model = Self::Model>>, crane_runtime::Error>> {
            let stepper = crane_runtime::dummy_derivative::DummyDerivativeStepper::<_, _, _, $n, $m, $a, $j>::new(
                model, path, start, options,
            );
            Some(stepper.map(|s| Box::new(s) as Box<dyn crane_runtime::Advance<$n, $m, $a, Model = Self::Model>>))
        }
    };
}
pub(crate) use dummy_derivative_run;
