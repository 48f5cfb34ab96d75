//! Results of an inverse-dynamics run: per step `t, q, v, u, lambda`, Newton
//! iterations and rope tensions.

use nalgebra::SVector;

use crate::error::Error;
use crate::model::{CraneModel, ModelInfo};
use crate::stepper::StepReport;

/// The crane's state at one time: what the scheme of eqs. (22a-d) computes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State<const N: usize, const M: usize, const A: usize> {
    /// Time.
    pub t: f64,
    /// Redundant coordinates `q = [p; x]`, with `x = gamma(t)`.
    pub q: SVector<f64, N>,
    /// Velocities `q' = [p'; gamma'(t)]`.
    pub v: SVector<f64, N>,
    /// Inputs `u` (winch torques).
    pub u: SVector<f64, A>,
    /// Lagrange multipliers `lambda`, in constraint order.
    pub lambda: SVector<f64, M>,
}

/// A complete run.
#[derive(Debug, Clone)]
pub struct Solution<const N: usize, const M: usize, const A: usize> {
    /// Names of the model's coordinates, inputs, constraints and ropes.
    pub info: ModelInfo,
    /// Time step.
    pub dt: f64,
    /// The name of the scheme that computed it (`backward-euler`, `bdf4`, ...).
    pub scheme: &'static str,
    /// States at `t0, t0 + dt, ..., tf`; the first is the consistent start.
    pub states: Vec<State<N, M, A>>,
    /// Newton iterations of each step (0 for the start).
    pub newton_iterations: Vec<usize>,
    /// Rope tensions ([`CraneModel::rope_tensions`]), `info.ropes.len()` per
    /// state, row-major.
    pub tensions: Vec<f64>,
    /// Time steps whose Newton iteration fell back to the minimum-norm solve
    /// at least once (singular iteration matrix, as at the paper's
    /// degenerate starts): at most the number of steps.
    pub min_norm_steps: usize,
    /// Time steps that held the direction a nearly slack rope leaves free
    /// ([`nearly_slack`](crate::stepper::nearly_slack)).
    pub held_steps: usize,
    /// Time steps taken by continuation, in shorter steps that kept the
    /// solution on its branch
    /// ([`Stepper::continue_to`](crate::stepper::Stepper::continue_to); the
    /// reduced formulation's long steps).
    pub continued_steps: usize,
    /// Time steps in which the solution changed branch where the path does
    /// ([`StepReport::crossed`](crate::stepper::StepReport::crossed): a
    /// rope going slack, a singular configuration), and the first one's
    /// time.
    pub crossings: usize,
    /// The time of the first of the [`crossings`](Self::crossings), s.
    pub first_crossing: Option<f64>,
    /// The highest path order the formulation that computed it covers
    /// ([`Problem::path_order_covered`](crate::problem::Problem::path_order_covered));
    /// `None` if not a servo problem's run.
    pub path_order_covered: Option<usize>,
    /// The shortest length of each rope over the run and when, `(L, t)` in
    /// the order of `info.ropes` (a length at or below 0 is outside the
    /// crane's workspace: the path asks for what no crane can do).
    pub shortest_ropes: Vec<(f64, f64)>,
    /// Of a minimal-coordinate run: how many of the first steps were taken
    /// in redundant coordinates because a rope was (nearly) slack at the
    /// start ([`crate::minimal::DEGENERATE_TENSION_RATIO`]). Of a reduced
    /// (dummy-derivative) run: how many steps were, at a degenerate start
    /// or wherever a rope was nearly slack, not only the first ones. 0
    /// otherwise.
    pub redundant_start_steps: usize,
    /// Of a run with state selection ([`crate::state_selection`]): the jets
    /// integrated as states (`phi`, `phi'`), empty otherwise.
    pub selected_states: Vec<String>,
    /// Of a run with state selection: when the states were selected anew
    /// along the move (the selection degenerated), and the new states.
    pub reselected_states: Vec<(f64, Vec<String>)>,
}

impl<const N: usize, const M: usize, const A: usize> Solution<N, M, A> {
    /// The bytes one state of a run with `ropes` ropes takes: the state,
    /// its Newton iterations and its tensions.
    pub fn bytes_per_state(ropes: usize) -> usize {
        std::mem::size_of::<State<N, M, A>>() + std::mem::size_of::<usize>() + ropes * std::mem::size_of::<f64>()
    }

    /// An empty solution with room for `states` states, or
    /// [`Error::TooManySteps`] if that much cannot be reserved.
    pub fn with_capacity(info: ModelInfo, dt: f64, scheme: &'static str, states: usize) -> Result<Self, Error> {
        let ropes = info.ropes.len();
        let per_state = Self::bytes_per_state(ropes);
        let too_many = || Error::TooManySteps {
            steps: states.saturating_sub(1) as f64,
            bytes: states as f64 * per_state as f64,
        };
        let mut solution = Solution {
            info,
            dt,
            scheme,
            states: Vec::new(),
            newton_iterations: Vec::new(),
            tensions: Vec::new(),
            min_norm_steps: 0,
            held_steps: 0,
            continued_steps: 0,
            crossings: 0,
            first_crossing: None,
            path_order_covered: None,
            shortest_ropes: vec![(f64::INFINITY, f64::NAN); ropes],
            redundant_start_steps: 0,
            selected_states: Vec::new(),
            reselected_states: Vec::new(),
        };
        solution.states.try_reserve_exact(states).map_err(|_| too_many())?;
        solution
            .newton_iterations
            .try_reserve_exact(states)
            .map_err(|_| too_many())?;
        solution
            .tensions
            .try_reserve_exact(states.checked_mul(ropes).ok_or_else(too_many)?)
            .map_err(|_| too_many())?;
        Ok(solution)
    }

    /// Append a state with its Newton counts and rope tensions
    /// ([`CraneModel::rope_tensions`]),
    /// and keep the ropes' shortest lengths (`lengths` is scratch space, one
    /// entry per rope). Does not allocate within the reserved capacity.
    pub fn push<Mdl: CraneModel<N, M, A>>(
        &mut self,
        model: &Mdl,
        state: &State<N, M, A>,
        report: StepReport,
        lengths: &mut [f64],
    ) {
        self.states.push(*state);
        self.newton_iterations.push(report.iterations);
        // a step counts once however many of its iterations were singular
        self.min_norm_steps += usize::from(report.min_norm_steps > 0);
        self.held_steps += usize::from(report.held);
        self.continued_steps += usize::from(report.substeps > 0);
        if report.crossed {
            self.crossings += 1;
            self.first_crossing.get_or_insert(state.t);
        }
        let ropes = self.info.ropes.len();
        let first = self.tensions.len();
        self.tensions.resize(first + ropes, 0.0);
        model.rope_tensions(&state.q, &state.lambda, &mut self.tensions[first..]);
        model.rope_lengths(&state.q, lengths);
        for (&length, shortest) in lengths.iter().zip(&mut self.shortest_ropes) {
            if !(length >= shortest.0) {
                *shortest = (length, state.t);
            }
        }
    }

    /// Number of time steps taken (states minus the start).
    pub fn steps(&self) -> usize {
        self.states.len().saturating_sub(1)
    }

    /// Tensions of all ropes at state `i`, in the order of `info.ropes`.
    pub fn tensions_at(&self, i: usize) -> &[f64] {
        let r = self.info.ropes.len();
        &self.tensions[i * r..(i + 1) * r]
    }

    /// The largest `|N|` of any rope over the run (0 without ropes): the
    /// scale of the round-off in every tension, which comes from one solve
    /// for all multipliers.
    pub fn largest_tension(&self) -> f64 {
        self.tensions.iter().fold(0.0f64, |m, n| m.max(n.abs()))
    }

    /// Mean Newton iterations per step.
    pub fn mean_newton_iterations(&self) -> f64 {
        let steps = self.steps().max(1);
        self.newton_iterations.iter().sum::<usize>() as f64 / steps as f64
    }

    /// Self-convergence without a reference: per input, the largest
    /// `|u_k(dt) - u_k(dt/2)|` between this run and `finer`, a run of the
    /// same case with half the step, over this run's times `t` with
    /// `include(t)`, and the time where it occurs. For backward Euler it
    /// halves with dt (`u(dt) = u + C(t) dt + O(dt^2)`). `None` if `finer`
    /// does not have exactly twice the steps on the same time grid.
    pub fn input_difference(
        &self,
        finer: &Solution<N, M, A>,
        include: impl Fn(f64) -> bool,
    ) -> Option<[(f64, f64); A]> {
        if finer.steps() != 2 * self.steps() {
            return None;
        }
        let mut worst = [(0.0, 0.0); A];
        for (i, coarse) in self.states.iter().enumerate() {
            let fine = &finer.states[2 * i];
            if (coarse.t - fine.t).abs() > 1e-9 * coarse.t.abs().max(1.0) {
                return None;
            }
            if !include(coarse.t) {
                continue;
            }
            for (k, w) in worst.iter_mut().enumerate() {
                let d = (coarse.u[k] - fine.u[k]).abs();
                if d > w.0 {
                    *w = (d, coarse.t);
                }
            }
        }
        Some(worst)
    }

    /// The state whose time is nearest to `t`.
    pub fn state_near(&self, t: f64) -> Option<&State<N, M, A>> {
        self.states
            .iter()
            .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
    }
}
