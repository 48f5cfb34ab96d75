//! The servo problem of a flat crane reduced by dummy derivatives
//! ([`DummyDerivatives`]), as a [`Problem`] on the stepper seam.
//!
//! Eqs. (22a-d) differentiated by Pryce's offsets, every derivative an
//! algebraic unknown: at each step time `t` one square system
//! ```text
//! F(z, gamma(t), gamma'(t), ..., gamma^(PATH_ORDER)(t)) = 0,
//! z = [p^(0..=c_p); lambda^(0..=c_lambda); u^(0..=c_u)]
//! ```
//! whose Jacobian is block triangular with Pryce's system Jacobian on the
//! diagonal. Nothing is discretised: the scheme's history has no
//! coordinates (`K = 0`), the inputs are the exact inverse dynamics at `t`
//! up to Newton's tolerance and round-off, whatever the time step, and a
//! crane whose inputs need `gamma^(6)` (a double pendulum, a drive with an
//! elastic belt, the 3D crane with pulley mass) is solved as accurately as
//! one that needs `gamma''''`. Newton starts from the polynomial through
//! the last eight steps' unknowns (through as many as are known from four
//! on, the quadratic of three at first).
//!
//! ```
//! use crane_runtime::{Options, Stepper, init, trajectory::Poly9, nalgebra::vector};
//! use crane_runtime::dummy_derivative::DummyDerivative;
//! # crane_macros::crane_model! {
//! #     #[crane(runtime = crane_runtime)]
//! #     #[crane(no_self_test)]
//! #     pub struct Gantry {
//! #         params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
//! #         robot [s, L] load [x, z] inputs [u1, u2]
//! #         kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
//! #         forces { s: u1, L: u2/r, z: -m_l*g }
//! #         constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2), }
//! #     }
//! # }
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let crane = Gantry::default();
//! let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0])?;
//! let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0])?;
//! // the same time step and scheme vocabulary as every other problem
//! let options = Options::stepping(0.5)?;
//! let mut stepper = Stepper::new(DummyDerivative::new(&crane, &path), &start, &options)?;
//! for _ in 0..10 {
//!     stepper.step()?;
//! }
//! // at rest at the end: the trolley under the load, u1 = 0, u2 = -r m_l g
//! let state = stepper.state();
//! assert!((state.q[0] - 4.0).abs() < 1e-9 && state.u[0].abs() < 1e-7);
//! assert!((state.u[1] + 0.1 * 200.0 * 9.81).abs() < 1e-7);
//! # Ok(())
//! # }
//! ```

use std::ops::{Deref, Range};

use nalgebra::{DMatrix, DVector, SVector};

use crate::error::Error;
use crate::init;
use crate::linsolve::{DenseSolver, Stages, Triangular};
use crate::minimal::degenerate;
use crate::model::{CraneModel, DummyDerivatives, NoDummyDerivatives, VisitDummyDerivatives};
use crate::newton::{NonlinearSystem, RowPattern, normalised_residual_sparse};
use crate::options::Options;
use crate::problem::{Accepted, Follow, Predictor, Problem, Start};
use crate::redundant::Redundant;
use crate::scheme::{Method, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::{Advance, StepReport, Stepper, nearly_slack, rope_branch_left};
use crate::trajectory::Trajectory;

/// The highest derivative of the load path a [`PathJets`] holds.
pub const MAX_PATH_ORDER: usize = 10;

/// The load path's derivatives `gamma^(k)(t)`, `k = 0 ..= MAX_PATH_ORDER`
/// (those above the crane's path order are not read).
pub type PathJets<const A: usize> = [SVector<f64, A>; MAX_PATH_ORDER + 1];

/// The dummy-derivative system of one time, as a [`Problem`] in its jets
/// `z`, for the crane behind the handle `H` (`&Mdl`, `Box<Mdl>`,
/// `Arc<Mdl>`) on the path `Tr`; see the module docs.
#[derive(Clone)]
pub struct DummyDerivative<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> {
    pub(crate) model: H,
    trajectory: Tr,
    pub(crate) gamma: PathJets<A>,
    /// The slot in `z` of jet 0 of each unknown of `[q, lambda, u]` (the
    /// load coordinates' slots are unused).
    pub(crate) slots: Vec<usize>,
    /// One relative stopping test for all of `z` (the residual test decides
    /// for the small jets).
    blocks: Vec<Range<usize>>,
    /// The jets of the last accepted step.
    last: DVector<f64>,
    /// Solve the linear systems whole, not stage by stage.
    whole: bool,
    /// The Jacobian's entries not zero by structure, row by row
    /// (`JACOBIAN_NONZEROS`).
    nonzeros: RowPattern,
    /// Whether the model evaluates the system stage by stage in the order
    /// of [`stages`](Self::stages) (`SYSTEM_ROWS` and `SYSTEM_COLUMNS` its
    /// last block's labels).
    staged: bool,
    /// The residual of the stages, row by row as the system's.
    stage_residual: DVector<f64>,
    /// Pryce's system Jacobian, zeroed once, its entries zero by structure
    /// never written.
    system_jacobian: DMatrix<f64>,
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> DummyDerivative<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    const P: usize = N - A;

    /// The reduced servo problem of the crane behind `model` on `trajectory`.
    pub fn new(model: H, trajectory: Tr) -> Self {
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        let mut slots = vec![0; N + M + A];
        let mut next = 0;
        for (j, slot) in slots.iter_mut().enumerate() {
            if (Self::P..N).contains(&j) {
                continue;
            }
            *slot = next;
            next += usize::from(offsets.get(j).copied().unwrap_or(0)) + 1;
        }
        Self {
            model,
            trajectory,
            gamma: [SVector::zeros(); MAX_PATH_ORDER + 1],
            slots,
            blocks: vec![Range { start: 0, end: J }],
            last: DVector::zeros(J),
            whole: false,
            nonzeros: RowPattern::new(J, <H::Target as DummyDerivatives<N, M, A, J>>::JACOBIAN_NONZEROS),
            staged: Self::stages_match(),
            stage_residual: DVector::zeros(J),
            system_jacobian: DMatrix::zeros(N + M, N + M),
        }
    }

    /// Whether the model's stages (`SYSTEM_ROWS`, `SYSTEM_COLUMNS`) are the
    /// nested order of [`stages`](Self::stages).
    fn stages_match() -> bool {
        let labels = |labels: &[u16]| labels.iter().map(|&l| usize::from(l)).collect::<Vec<usize>>();
        let declared = (
            labels(<H::Target as DummyDerivatives<N, M, A, J>>::SYSTEM_ROWS),
            labels(<H::Target as DummyDerivatives<N, M, A, J>>::SYSTEM_COLUMNS),
        );
        declared.0.len() == N + M && Self::stages().and_then(|form| form.last_labels()) == Some(declared)
    }

    /// The same problem with its Newton matrices solved whole (one LU of
    /// all `J` unknowns), not stage by stage: the check of
    /// [`stages`](Self::stages), for tests.
    pub fn solved_whole(mut self) -> Self {
        self.whole = true;
        self
    }

    /// The stages of the system (Pryce's): the `k`-th derivative of
    /// equation `i`, differentiated `d_i` times, is in stage `k - d_i`, the
    /// `l`-th jet of an unknown with offset `c_j` in stage `l - c_j`; an
    /// equation of a stage involves the jets of that stage and of earlier
    /// ones only (`c_j - d_i` bounds the derivative of unknown `j` in
    /// equation `i`), so the Jacobian is block lower triangular, its
    /// diagonal blocks square blocks of Pryce's system Jacobian (rows and
    /// columns labelled by equation and unknown: the last stage's block is
    /// all of it, and one LU of it solves every stage,
    /// [`Triangular::with_labels`]). `None` for
    /// a crane without a structure, or one whose counts do not match.
    pub fn stages() -> Option<Triangular> {
        let structure = <H::Target as CraneModel<N, M, A>>::STRUCTURE?;
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        // (stage, equation or unknown) of each row and column
        let stage = |(label, offset): (usize, u8)| (0..=offset).map(move |k| (i32::from(k) - i32::from(offset), label));
        let (rows, row_labels): (Vec<i32>, Vec<usize>) = (structure.equations.get(..N + M)?.iter())
            .copied()
            .enumerate()
            .flat_map(stage)
            .unzip();
        let (cols, col_labels): (Vec<i32>, Vec<usize>) = (0..N + M + A)
            .filter(|j| !(Self::P..N).contains(j))
            .map(|j| offsets.get(j).map(|&c| (j, c)))
            .collect::<Option<Vec<(usize, u8)>>>()?
            .into_iter()
            .flat_map(stage)
            .unzip();
        (rows.len() == J && cols.len() == J)
            .then(|| Triangular::from_stages(&rows, &cols))?
            .map(|form| {
                form.with_nonzeros(<H::Target as DummyDerivatives<N, M, A, J>>::JACOBIAN_NONZEROS)
                    .with_labels(&row_labels, &col_labels)
            })
    }

    /// The load path.
    pub fn trajectory(&self) -> &Tr {
        &self.trajectory
    }

    /// The 2-norm condition number of the system's Jacobian at the jets `z`
    /// and the path's derivatives of the last step, equilibrated as Newton
    /// solves it ([`DenseSolver::equilibrated_condition`]). A diagnostic: it
    /// allocates.
    pub fn condition(&self, z: &DVector<f64>) -> f64 {
        let jets = SVector::<f64, J>::from_fn(|i, _| z[i]);
        let (_, jacobian) = self.model.dummy_derivative_system(&self.gamma, &jets);
        let jacobian = DMatrix::from_fn(J, J, |i, j| jacobian[(i, j)]);
        DenseSolver::new(J).equilibrated_condition(&jacobian)
    }

    /// The slot in `z` of derivative `order` of unknown `j` of `[q, lambda, u]`.
    pub(crate) fn slot(&self, j: usize, order: usize) -> usize {
        self.slots[j] + order
    }

    /// The jets of order 0 and 1 of `state` (coordinates, velocities,
    /// multipliers, inputs) into `z`; the higher jets are left as they are.
    pub(crate) fn write_state(&self, state: &State<N, M, A>, z: &mut DVector<f64>) {
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        for i in 0..Self::P {
            z[self.slot(i, 0)] = state.q[i];
            if offsets[i] >= 1 {
                z[self.slot(i, 1)] = state.v[i];
            }
        }
        for l in 0..M {
            z[self.slot(N + l, 0)] = state.lambda[l];
        }
        for r in 0..A {
            z[self.slot(N + M + r, 0)] = state.u[r];
        }
    }

    /// The crane's state at `t` from the jets `z`.
    pub(crate) fn state(&self, t: f64, z: &DVector<f64>) -> State<N, M, A> {
        let p = Self::P;
        let q = SVector::from_fn(|i, _| {
            if i < p {
                z[self.slot(i, 0)]
            } else {
                self.gamma[0][i - p]
            }
        });
        let v = SVector::from_fn(|i, _| {
            if i < p {
                z[self.slot(i, 1)]
            } else {
                self.gamma[1][i - p]
            }
        });
        let lambda = SVector::from_fn(|l, _| z[self.slot(N + l, 0)]);
        let u = SVector::from_fn(|r, _| z[self.slot(N + M + r, 0)]);
        State { t, q, v, u, lambda }
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> NonlinearSystem
    for DummyDerivative<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    fn dim(&self) -> usize {
        J
    }

    /// Into Newton's buffers: its Jacobian is zeroed when made and written
    /// by this alone, so the entries zero by structure stay zero.
    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        self.model
            .dummy_derivative_system_into(&self.gamma, z.as_slice(), r.as_mut_slice(), jac.as_mut_slice());
    }

    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        normalised_residual_sparse(r, jac, z, &self.nonzeros)
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }

    /// Stage by stage (unless [`solved_whole`](Self::solved_whole)): the
    /// system Jacobian and the lowest stage's residual at `z`, one LU, then
    /// each stage's residual at the stages before it as updated
    /// ([`DummyDerivatives::dummy_derivative_stages_into`]); the blocks left
    /// of the diagonal are neither evaluated nor multiplied.
    fn staged_update(&mut self, z: &mut DVector<f64>, dz: &mut DVector<f64>, mut stages: Stages<'_>) -> Option<bool> {
        if self.whole || !self.staged {
            return None;
        }
        let dz = dz.as_mut_slice();
        let mut solve = |k: usize, jacobian: &[f64], z: &mut [f64], r: &[f64]| {
            (k > 0 || stages.factor(jacobian)) && stages.solve(k, r, z, dz)
        };
        Some(self.model.dummy_derivative_stages_into(
            &self.gamma,
            z.as_mut_slice(),
            self.stage_residual.as_mut_slice(),
            self.system_jacobian.as_mut_slice(),
            &mut solve,
        ))
    }

    /// Stage by stage ([`stages`](Self::stages)) unless
    /// [`solved_whole`](Self::solved_whole).
    fn triangular(&self) -> Option<Triangular> {
        if self.whole { None } else { Self::stages() }
    }

    /// Yes: the jets are smooth in time and predicted through the last
    /// eight steps, and so are the Jacobian's entries (finding the stage
    /// blocks' scales anew at every step cost a tenth of it; a block whose
    /// LU finds it singular with the kept scales is solved with new ones).
    fn nearby_solves(&self) -> bool {
        true
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> Problem<N, M, A, 0>
    for DummyDerivative<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    type Model = H::Target;
    type Drive = PathJets<A>;

    /// The jets range from metres to N/s^6: equilibrate.
    const EQUILIBRATED: bool = true;

    fn model(&self) -> &H::Target {
        &self.model
    }

    /// The crane's own path order: the reduction is complete.
    fn path_order_covered(&self) -> Option<usize> {
        Some(<H::Target as DummyDerivatives<N, M, A, J>>::PATH_ORDER)
    }

    /// Jets are smooth in time and known exactly at each step (nothing is
    /// discretised): the polynomial through the last eight steps, whose
    /// prediction is often within the residual test already, or within an
    /// update whose error Newton's quadratic term puts at round-off, so
    /// that one Newton iteration ends the step (Newton iterations per step
    /// at dt = 0.01 through 4 and 8 steps: navy-planar 2.01 and 1.40,
    /// navy-3d-pulley 1.59 and 1.02, the double pendulum 1.60 and 1.35;
    /// with the quadratic term 1.18, 1.02 and 1.09; the inputs the same to
    /// round-off at every dt from 0.1 to 0.001).
    fn predictor(&self) -> Predictor {
        Predictor::Extrapolation { points: 8 }
    }

    fn drive(&self, t: f64) -> PathJets<A> {
        let order = <H::Target as DummyDerivatives<N, M, A, J>>::PATH_ORDER.min(MAX_PATH_ORDER);
        let mut gamma = [SVector::zeros(); MAX_PATH_ORDER + 1];
        self.trajectory.derivatives_into(t, &mut gamma[..=order]);
        gamma
    }

    fn check_drive(&self, gamma: &PathJets<A>, t: f64) -> Result<(), Error> {
        if !gamma.iter().all(|x| x.iter().all(|v| v.is_finite())) {
            return Err(Error::NonFinite {
                quantity: "load path derivatives gamma^(k)(t)",
                t,
            });
        }
        crate::redundant::check_path_position(&gamma[0], t, &H::Target::INFO.coordinates[N - A..])
    }

    /// The start's coordinates, velocities, multipliers and inputs as jets
    /// of order 0 and 1; higher jets 0 (exact for a crane at rest).
    fn start(&mut self, start: &State<N, M, A>, _dt: f64, z: &mut DVector<f64>) -> Result<Start<0>, Error> {
        let order = <H::Target as DummyDerivatives<N, M, A, J>>::PATH_ORDER;
        if order > MAX_PATH_ORDER {
            return Err(Error::PathOrderTooHigh {
                order,
                max: MAX_PATH_ORDER,
            });
        }
        z.fill(0.0);
        self.write_state(start, z);
        self.last.copy_from(z);
        Ok(Start {
            y0: SVector::zeros(),
            v0: SVector::zeros(),
            at_rest: init::at_rest(&self.trajectory, start),
        })
    }

    fn prepare(&mut self, gamma: &PathJets<A>, _formula: StepFormula<0>) {
        self.gamma = *gamma;
    }

    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, 0>, Error> {
        self.last.copy_from(z);
        Ok(Accepted {
            state: self.state(t, z),
            y: SVector::zeros(),
            v: SVector::zeros(),
            trailing: None,
        })
    }

    /// Where a rope's length or a taut rope's tension changed sign
    /// ([`rope_branch_left`]): the system is algebraic at each time, so the
    /// [`DummyDerivativeStepper`] follows its branch by shorter steps.
    fn leaves_branch(&self, before: &State<N, M, A>, after: &State<N, M, A>) -> bool {
        rope_branch_left(&*self.model, before, after)
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> Follow<N, M, A, 0>
    for DummyDerivative<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    /// Always: the system needs no history.
    fn can_take_over(&self, _state: &State<N, M, A>) -> bool {
        true
    }

    /// The state's jets of order 0 and 1, the higher ones of the last
    /// accepted step (Newton's start of the next step).
    fn follow(
        &mut self,
        state: &State<N, M, A>,
        _last: &SVector<f64, 0>,
        _formula: StepFormula<0>,
        z: &mut DVector<f64>,
    ) -> Result<(SVector<f64, 0>, SVector<f64, 0>), Error> {
        z.copy_from(&self.last);
        self.write_state(state, z);
        self.last.copy_from(z);
        Ok((SVector::zeros(), SVector::zeros()))
    }
}

/// The reduced servo problem one step at a time, on the scheme `S`.
///
/// Every step is the [`DummyDerivative`] problem's where its Newton
/// converges. At a degenerate state (a rope whose tension is below
/// [`DEGENERATE_TENSION_RATIO`](crate::minimal::DEGENERATE_TENSION_RATIO) of the largest, as at the paper's starts
/// with a slack rope, where the jets of the massless pulley are fixed only
/// to a few digits: equilibrated condition number 3.5e13 on `navy-3d` at
/// t = 0.01 s) where it does not, the step is the redundant problem's
/// (eqs. 22a-d on `S`), whose history follows every reduced step exactly.
/// From a state where a rope carries less than
/// [`HOLD_TENSION_RATIO`](crate::stepper::HOLD_TENSION_RATIO) of the largest
/// tension (after the first step), the step is the redundant problem's
/// too, which holds the directions such a rope leaves free (the slow move;
/// the reduced system's minimum-norm steps wander off there).
/// [`fallback_steps`](Self::fallback_steps) counts these steps. A step does
/// not allocate.
pub struct DummyDerivativeStepper<H, Tr, S: Method, const N: usize, const M: usize, const A: usize, const J: usize> {
    reduced: Stepper<DummyDerivative<H, Tr, N, M, A, J>, S, N, M, A, 0>,
    fallback: Stepper<Redundant<H, Tr, N, M, A>, S, N, M, A, N>,
    fallback_steps: usize,
}

impl<H, Tr, S, const N: usize, const M: usize, const A: usize, const J: usize>
    DummyDerivativeStepper<H, Tr, S, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized> + Clone,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    /// A stepper for the crane behind `model` on `trajectory` from the
    /// consistent `start`, with the step, scheme and tolerances of `options`.
    pub fn new(model: H, trajectory: Tr, start: &State<N, M, A>, options: &Options<S>) -> Result<Self, Error> {
        flat::<H::Target, N, M, A, J>()?;
        let fallback = Stepper::new(Redundant::new(model.clone(), trajectory.clone()), start, options)?;
        let reduced = Stepper::new(DummyDerivative::new(model, trajectory), start, options)?;
        Ok(Self {
            reduced,
            fallback,
            fallback_steps: 0,
        })
    }

    /// The state after the last step (the start before the first).
    pub fn state(&self) -> &State<N, M, A> {
        self.reduced.state()
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        self.reduced.dt()
    }

    /// How many steps were the redundant problem's.
    pub fn fallback_steps(&self) -> usize {
        self.fallback_steps
    }

    /// The stepper of the reduced problem.
    pub fn reduced(&self) -> &Stepper<DummyDerivative<H, Tr, N, M, A, J>, S, N, M, A, 0> {
        &self.reduced
    }

    /// The equilibrated condition number of the reduced system's Jacobian
    /// at the last step ([`DummyDerivative::condition`]); it does not depend
    /// on the time step.
    pub fn condition(&self) -> f64 {
        self.reduced.problem().condition(self.reduced.unknowns())
    }

    /// Advance one step with the path's derivatives from the problem's path.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let t = self.reduced.next_time();
        let jets = self.reduced.problem().drive(t);
        self.step_with(t, &jets, true)
    }

    /// Advance one step to `t` (`t_n + dt`) with the given path derivatives.
    pub fn step_to(&mut self, t: f64, jets: &PathJets<A>) -> Result<StepReport, Error> {
        self.step_with(t, jets, false)
    }

    /// One step to `t` with `jets`, the path's `own` or not.
    fn step_with(&mut self, t: f64, jets: &PathJets<A>, own: bool) -> Result<StepReport, Error> {
        // a rope nearly without tension leaves directions the reduced system
        // does not fix (its matrix singular to working precision, and its
        // minimum-norm steps wander off: inputs of 3e49 N m on a 1000 s
        // move); the redundant step holds them where the last step left
        // them, as a run in eqs. (22a-d) does (the first step is never held)
        if self.reduced.steps() > 0 && nearly_slack(self.reduced.problem().model(), self.reduced.state()) {
            return self.fallback_step(t, jets, None, own);
        }
        let report = match self.reduced.step_to(t, jets) {
            Ok(report) => report,
            Err(error @ (Error::NewtonNotConverged { .. } | Error::SingularIterationMatrix { .. }))
                if degenerate(self.reduced.problem().model(), self.reduced.state()) =>
            {
                // eqs. (22) hold what the degenerate state leaves free; a
                // step too long for their scheme is the reduced system's
                // by shorter steps
                match self.fallback_step(t, jets, None, own) {
                    Ok(report) => return Ok(report),
                    Err(_) => self.reduced.continue_to(t, jets).map_err(|_| error)?,
                }
            }
            // a step that left its branch, or whose Newton failed from the
            // prediction: the same solution by shorter steps along the path
            // (the system is algebraic at each time: they cost no accuracy)
            Err(Error::BranchLeft { .. }) => match self.reduced.continue_to(t, jets) {
                Ok(report) => report,
                // a rope going slack passes a singular configuration (no
                // tension leaves what it holds free), where Newton fails
                // at the shortest steps: the step across it, as found
                Err(_) => self.reduced.step_across(t, jets)?,
            },
            Err(error @ (Error::NewtonNotConverged { .. } | Error::SingularIterationMatrix { .. })) => {
                self.reduced.continue_to(t, jets).map_err(|_| error)?
            }
            Err(error) => return Err(error),
        };
        self.fallback.follow(self.reduced.state())?;
        Ok(report)
    }

    /// The step to `t` in eqs. (22a-d), which the reduced stepper follows;
    /// where it fails, `error` (the reduced step's) stands, if given. The
    /// path's `own` jets let eqs. (22) take its target beyond double
    /// precision.
    fn fallback_step(
        &mut self,
        t: f64,
        jets: &PathJets<A>,
        error: Option<Error>,
        own: bool,
    ) -> Result<StepReport, Error> {
        let report = if own {
            self.fallback.step_own_to(t)
        } else {
            self.fallback.step_to(t, &[jets[0], jets[1], jets[2]])
        };
        let report = report.map_err(|e| error.unwrap_or(e))?;
        self.reduced.follow(self.fallback.state())?;
        self.fallback_steps += 1;
        Ok(report)
    }
}

impl<H, Tr, S, const N: usize, const M: usize, const A: usize, const J: usize> Advance<N, M, A>
    for DummyDerivativeStepper<H, Tr, S, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized> + Clone,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    type Model = H::Target;
    fn model(&self) -> &H::Target {
        self.reduced.problem().model()
    }
    fn step(&mut self) -> Result<StepReport, Error> {
        DummyDerivativeStepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        DummyDerivativeStepper::state(self)
    }
    fn dt(&self) -> f64 {
        DummyDerivativeStepper::dt(self)
    }
    fn scheme_name(&self) -> &'static str {
        Advance::scheme_name(&self.reduced)
    }
    fn path_order_covered(&self) -> Option<usize> {
        self.reduced.problem().path_order_covered()
    }
}

/// Solve the reduced servo problem at every step time from `start` to
/// `options.tf()` ([`DummyDerivativeStepper`]), calling `progress(step,
/// steps)` after every step; the step loop does not allocate. Any crane
/// `crane_model!` declares without internal dynamics has the system (its
/// size is the declaration's, [`CraneModel::visit_dummy_derivatives`]);
/// for another, the error says why it has none.
pub fn simulate_dummy_derivative<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    // one run of the reduced system, which for a flat crane is this one
    flat_crane::<Mdl, N, M, A>()?;
    crate::state_selection::simulate(model, trajectory, start, options, progress)
}

/// The size `J` of `Mdl`'s dummy-derivative system of a flat crane
/// ([`CraneModel::visit_dummy_derivatives`]), or why it has none (one with
/// internal dynamics has the system with free jets, which
/// [`crate::state_selection`] integrates).
pub fn system_size<Mdl, const N: usize, const M: usize, const A: usize>() -> Result<usize, NoDummyDerivatives>
where
    Mdl: CraneModel<N, M, A>,
{
    /// `J`.
    struct Size;
    impl<Mdl, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<Mdl, N, M, A> for Size {
        type Output = Result<usize, NoDummyDerivatives>;
        fn visit<const J: usize>(self) -> Self::Output
        where
            Mdl: DummyDerivatives<N, M, A, J>,
        {
            match Mdl::DIMENSION {
                0 => Ok(J),
                dimension => Err(NoDummyDerivatives::InternalDynamics { dimension }),
            }
        }
    }
    Mdl::visit_dummy_derivatives(Size)?
}

/// Refuse a crane without a flat dummy-derivative system ([`system_size`]):
/// one with internal dynamics, or none declared.
fn flat_crane<Mdl, const N: usize, const M: usize, const A: usize>() -> Result<(), Error>
where
    Mdl: CraneModel<N, M, A>,
{
    system_size::<Mdl, N, M, A>()
        .map(|_| ())
        .map_err(|reason| Error::NoDummyDerivatives {
            model: Mdl::INFO.name,
            reason,
        })
}

/// Refuse a system with free jets (internal dynamics), which this module's
/// problem, algebraic at each time, cannot solve.
fn flat<Mdl, const N: usize, const M: usize, const A: usize, const J: usize>() -> Result<(), Error>
where
    Mdl: DummyDerivatives<N, M, A, J>,
{
    match Mdl::DIMENSION {
        0 => Ok(()),
        dimension => Err(Error::NoDummyDerivatives {
            model: Mdl::INFO.name,
            reason: NoDummyDerivatives::InternalDynamics { dimension },
        }),
    }
}

/// A [`DummyDerivativeStepper`] of the crane behind `model` (`Box<Mdl>`,
/// `Arc<Mdl>`) that owns its model and path, behind [`Advance`], for
/// long-lived runs such as an FMU instance; the system's size is the
/// declaration's (see [`simulate_dummy_derivative`]).
#[allow(clippy::type_complexity)]
pub fn boxed_stepper<H, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: H,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
) -> Result<Box<dyn Advance<N, M, A, Model = H::Target> + Send>, Error>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized> + Clone + Send + 'static,
    Tr: Trajectory<A> + Clone + Send + 'static,
    S: Method + 'static,
{
    // the reduced system's stepper, which for a flat crane is this one
    flat_crane::<H::Target, N, M, A>()?;
    crate::state_selection::boxed_stepper(model, trajectory, start, options)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{central_difference_error, uniform};

    crane_macros::crane_model! {
        #[crane(runtime = crate)]
        #[crane(no_self_test)]
        /// A planar gantry with viscous trolley friction and a winch whose
        /// effective radius grows with the rope paid out: forces that depend
        /// on velocities and an input matrix that depends on a coordinate.
        pub struct FrictionGantry {
            params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, c = 30.0, g = 9.81 }
            robot [s, L] load [x, z] inputs [u1, u2]
            kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
            forces { s: u1 - c*dot(s), L: u2/(r + 0.01*L), z: -m_l*g }
            constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2), }
        }
    }

    /// The generated Jacobian of the dummy-derivative system is the
    /// derivative of its residual: against central differences at random
    /// jets and path derivatives of the crane's size, entry by entry to 1e-6
    /// of the largest entry (central differences of a smooth residual:
    /// ~1e-9).
    #[test]
    fn jacobian_matches_central_differences() {
        fn size<Mdl: DummyDerivatives<4, 1, 2, J>, const J: usize>(_: &Mdl) -> usize {
            J
        }
        let crane = FrictionGantry::default();
        let j = size(&crane);
        let path = crate::trajectory::FromFn(|_t: f64, _k: usize| SVector::<f64, 2>::zeros());
        let mut rnd = uniform(7);
        for _ in 0..20 {
            let mut problem = DummyDerivative::new(&crane, &path);
            let gamma: PathJets<2> = std::array::from_fn(|k| {
                let scale = if k == 0 { 5.0 } else { 1.0 };
                SVector::from_fn(|i, _| if k == 0 && i == 1 { -5.0 + rnd() } else { scale * rnd() })
            });
            problem.prepare(&gamma, StepFormula::unprepared());
            let z = DVector::from_fn(j, |_, _| 3.0 + rnd());
            let (worst, largest) = central_difference_error(&mut problem, &z);
            assert!(worst <= 1e-6 * largest, "worst {worst:e} of {largest:e}");
        }
    }
}
