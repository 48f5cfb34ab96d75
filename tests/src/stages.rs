//! The reduced (dummy-derivative) system solved stage by stage against the
//! same system solved whole (one LU of all the jets): a run of a crane's
//! default move both ways, with what they measured ([`Comparison`]) and the
//! checks ([`check`]).

use crane_models::registry::Visit;
use crane_models::{Case, Crane};
use crane_runtime::dummy_derivative::DummyDerivative;
use crane_runtime::linsolve::Triangular;
use crane_runtime::model::{DummyDerivatives, VisitDummyDerivatives};
use crane_runtime::nalgebra::{DMatrix, SVector};
use crane_runtime::{CraneModel, Options, Stepper, Trajectory};

/// What a run stage by stage and the same run solved whole measured.
#[derive(Debug)]
pub struct Comparison {
    /// The crane's name.
    pub crane: &'static str,
    /// The diagonal blocks' sizes, in the order they are solved.
    pub blocks: Vec<usize>,
    /// The largest Jacobian entry above the blocks over the run's states.
    pub above: f64,
    /// The largest difference of an input between the two runs, relative
    /// to the largest input.
    pub difference: f64,
    /// Newton iterations of the two runs.
    pub iterations: (usize, usize),
    /// LU factorisations of the two runs.
    pub factorisations: (usize, usize),
    /// Newton updates taken stage by stage (each stage's residual at the
    /// stages before it as updated) in the two runs.
    pub staged_updates: (usize, usize),
    /// Of the updates stage by stage, those that kept the factors of the
    /// update before (after an update below 1e-6 relative).
    pub chord_updates: usize,
    pub steps: usize,
}

/// The system stage by stage is the whole system where it is evaluated:
/// at made-up jets and the path's derivatives at t = 1.3 s, each stage's
/// residual, handed to the solve, equals the whole residual's rows of that
/// stage at the jets as they stand then (bit for bit: the same expressions,
/// bound differently), the system Jacobian equals the whole Jacobian's last
/// block, and the solves are called once per stage in order. Each "solve"
/// moves its stage's jets, so that a later stage evaluated at the earlier
/// stages' old jets, or at its own new ones, fails.
fn stages_as_whole<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize, const J: usize>(
    model: &C::Model,
    path: &impl Trajectory<A>,
    form: &Triangular,
) where
    C::Model: DummyDerivatives<N, M, A, J>,
{
    let gamma: Vec<SVector<f64, A>> = (0..=<C::Model as DummyDerivatives<N, M, A, J>>::PATH_ORDER)
        .map(|k| path.derivative(1.3, k))
        .collect();
    let mut z: Vec<f64> = (0..J).map(|i| 1.0 + 0.5 * (i as f64 * 0.37).sin()).collect();
    let (last_rows, last_cols) = form.block(form.block_sizes().count() - 1).unwrap();
    let size = last_rows.len();
    let (mut residual, mut system) = (vec![0.0; J], vec![0.0; size * size]);
    let mut called = Vec::new();
    let finished =
        model.dummy_derivative_stages_into(&gamma, &mut z, &mut residual, &mut system, &mut |k, jac, z, r| {
            let jets = SVector::<f64, J>::from_column_slice(z);
            let (whole, whole_jacobian) = model.dummy_derivative_system(&gamma, &jets);
            let (rows, cols) = form.block(k).unwrap();
            for &row in rows {
                assert_eq!(
                    r[row].to_bits(),
                    whole[row].to_bits(),
                    "{}: stage {k}, row {row}",
                    C::NAME
                );
            }
            if k == 0 {
                for (c, &col) in last_cols.iter().enumerate() {
                    for (i, &row) in last_rows.iter().enumerate() {
                        let entry = jac[c * size + i];
                        assert_eq!(
                            entry.to_bits(),
                            whole_jacobian[(row, col)].to_bits(),
                            "{}: ({row}, {col})",
                            C::NAME
                        );
                    }
                }
            }
            for &col in cols {
                z[col] += 0.01 * (1.0 + col as f64);
            }
            called.push(k);
            true
        });
    assert!(finished, "{}", C::NAME);
    assert_eq!(
        called,
        (0..form.block_sizes().count()).collect::<Vec<_>>(),
        "{}",
        C::NAME
    );
}

/// The comparison on one case, with the reduced system's size `J`.
struct Compare<'a, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    case: &'a Case<C, N, M, A>,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<C::Model, N, M, A>
    for Compare<'_, C, N, M, A>
{
    type Output = Comparison;
    fn visit<const J: usize>(self) -> Comparison
    where
        C::Model: DummyDerivatives<N, M, A, J>,
    {
        let (model, path) = (self.case.model(), self.case.path());
        let form = DummyDerivative::<&C::Model, &crane_models::Path<A>, N, M, A, J>::stages()
            .unwrap_or_else(|| panic!("{}: no stages", C::NAME));
        stages_as_whole::<C, N, M, A, J>(model, path, &form);
        let start = self.case.start().unwrap();
        let options = Options::new(0.01, self.case.tf()).unwrap();
        let mut staged = Stepper::new(DummyDerivative::new(model, path), &start, &options).unwrap();
        let mut whole = Stepper::new(DummyDerivative::new(model, path).solved_whole(), &start, &options).unwrap();
        let (mut above, mut difference, mut largest) = (0.0f64, 0.0f64, 0.0f64);
        let mut iterations = (0, 0);
        let mut steps = 0;
        while staged.state().t < self.case.tf() - 1e-9 {
            iterations.0 += staged.step().unwrap().iterations;
            iterations.1 += whole.step().unwrap().iterations;
            steps += 1;
            let (a, b) = (staged.state(), whole.state());
            largest = largest.max(b.u.amax());
            difference = difference.max((a.u - b.u).amax());
            // the Jacobian at the step's path derivatives and at jets whose
            // low orders are the state's and whose higher ones are made up:
            // the blocks above are zero whatever the jets
            let t = a.t;
            let gamma: Vec<SVector<f64, A>> = (0..=<C::Model as DummyDerivatives<N, M, A, J>>::PATH_ORDER)
                .map(|k| path.derivative(t, k))
                .collect();
            let jets = SVector::<f64, J>::from_fn(|i, _| 1.0 + (i as f64 * 0.37 + t).sin());
            let (_, jacobian) = model.dummy_derivative_system(&gamma, &jets);
            above = above.max(form.largest_above(&DMatrix::from_column_slice(J, J, jacobian.as_slice())));
        }
        let blocks: Vec<usize> = form.block_sizes().collect();
        Comparison {
            crane: C::NAME,
            blocks,
            above,
            difference: difference / largest,
            iterations,
            factorisations: (staged.factorisations(), whole.factorisations()),
            staged_updates: (staged.staged_updates(), whole.staged_updates()),
            chord_updates: staged.chord_updates(),
            steps,
        }
    }
}

/// The comparison on a crane's default move, if it has a reduced system
/// (a [`Visit`] of a registry, or `OnCrane.visit::<C, N, M, A>()`).
pub struct OnCrane;

impl Visit for OnCrane {
    type Output = Option<Comparison>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        // (a crane with internal dynamics has free jets: no stages)
        crane_runtime::dummy_derivative::system_size::<C::Model, N, M, A>().ok()?;
        let case = Case::<C, N, M, A>::maneuver().unwrap();
        <C::Model as CraneModel<N, M, A>>::visit_dummy_derivatives(Compare { case: &case }).ok()
    }
}

/// Bound on the difference of the inputs: both runs stop Newton at a
/// normalised residual of 1e-13 or a correction below 1e-10 relative, the
/// error left of the order of its square; what differs is the round-off of
/// the linear solves and of the residuals (each stage's at the stages before
/// it as updated, against all at one iterate), a few ulps of the condition
/// (below 10 equilibrated on the double pendulum): the crane's
/// [`exactness_bound`](crate::kit::exactness_bound), about ten times the
/// largest measured (5.7e-16 on navy-planar, 3.2e-14 on navy-3d-pulley).
pub fn round_off(crane: &str) -> f64 {
    crate::kit::exactness_bound(crane)
}

/// The comparison's checks: no entry above the blocks, the inputs the
/// same to [`round_off`], at most 1 % more Newton iterations stage by stage,
/// more than one stage, and the deterministic cost: one LU per iteration
/// solved whole, and one per iteration stage by stage too, of the system
/// Jacobian (the last stage's block), which holds every earlier stage's,
/// but for the chord updates that keep the factors of a small update
/// before, every update taken stage by stage (none fell back on the whole
/// evaluation, an LU per block or the whole solve).
pub fn check(c: &Comparison) {
    println!("{c:?}");
    assert_eq!(c.above, 0.0, "{}: entries above the stages' blocks", c.crane);
    assert!(
        c.difference <= round_off(c.crane),
        "{}: stage by stage and whole differ by {:e}",
        c.crane,
        c.difference
    );
    // Newton ends when its correction or residual reaches round-off, which
    // the two reach in their own last digits, and stage by stage each
    // stage's residual is taken at the stages before it as updated (the
    // whole solve takes them at the old iterate, through the blocks left of
    // the diagonal): a step may take one iteration more or less, and stage
    // by stage takes not more than 1 in 100 more over the run
    let (staged, whole) = (c.iterations.0 as f64, c.iterations.1 as f64);
    assert!(
        staged <= 1.01 * whole,
        "{}: Newton iterations {:?}",
        c.crane,
        c.iterations
    );
    assert!(c.blocks.len() >= 2, "{}: one stage", c.crane);
    assert_eq!(c.factorisations.1, c.iterations.1, "{}: LUs solved whole", c.crane);
    assert_eq!(
        c.staged_updates,
        (c.iterations.0, 0),
        "{}: updates stage by stage",
        c.crane
    );
    assert_eq!(
        c.factorisations.0 + c.chord_updates,
        c.iterations.0,
        "{}: LUs stage by stage, {} blocks nested in the last",
        c.crane,
        c.blocks.len()
    );
}
