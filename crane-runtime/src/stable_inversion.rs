//! Stable (non-causal) inversion: the bounded inputs of a crane whose
//! internal dynamics are unstable, as one boundary value problem on the
//! whole time axis.
//!
//! Where the load path leaves states free that grow (a trolley coupled to
//! its load: eigenvalues `+-9.9 1/s` at rest), the causal inverse of eqs.
//! (22a-d) explodes like `exp(9.9 t)`. The equations still have exactly one
//! solution that stays bounded on the whole time axis (Devasia, Chen and
//! Paden, IEEE TAC 41(7), 1996): it acts before the load moves
//! (pre-actuation) and settles after it stops (post-actuation). Here it is
//! solved on `[t0 - T_pre, tf + T_post]` as one Newton system with every
//! step's unknowns (Bastos, Seifried and Bruls solve the servo problem so):
//!
//! - nodes `s_k = t0 + k dt`, `k = -n_pre ..= n_move + n_post`; at each the
//!   robot coordinates `p_k`, `dt^2 u_k` and `dt^2 lambda_k` (the scaling
//!   of eqs. 22), the load on its path, `x_k = gamma(s_k)`;
//! - at the inner nodes the equations of motion (eq. 22b) with central
//!   differences, `p'' ~ (p_(k+1) - 2 p_k + p_(k-1)) / dt^2` and
//!   `p' ~ (p_(k+1) - p_(k-1)) / (2 dt)`, and the constraints (eq. 22d):
//!   symmetric in time, so growing and decaying modes are treated alike,
//!   and second order in `dt`;
//! - at the two end nodes the crane at rest (`p'' = p' = 0`): the bounded
//!   solution approaches the rest states as `exp(-|Re lambda| T)`, and
//!   [`horizons`] picks `T_pre`, `T_post` so that this is at most
//!   [`HORIZON_DECAY`].
//!
//! The Jacobian is block tridiagonal; faer's sparse LU solves it (O(K) in
//! the number of nodes). Newton starts from the quasi-static motion (the
//! static equilibrium with the load's acceleration at each node).

use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use nalgebra::{DVector, SVector};

use crate::error::Error;
use crate::init;
use crate::internal::InternalDynamics;
use crate::model::CraneModel;
use crate::solution::{Solution, State};
use crate::stepper::{Advance, StepReport};
use crate::trajectory::Trajectory;

/// How far the bounded solution may still be from rest at the ends of the
/// extended interval, relative to its size: `exp(-|Re lambda| T)` at most.
pub const HORIZON_DECAY: f64 = 1e-10;

/// Largest real part (in 1/s, relative to the eigenvalues' size) counted as
/// on the imaginary axis: such internal dynamics have no unique bounded
/// solution.
const IMAGINARY_AXIS: f64 = 1e-8;

/// Newton iterations of the boundary value problem.
const MAX_ITERATIONS: usize = 30;

/// Relative update (per block of unknowns) at which Newton stops.
const UPDATE_TOLERANCE: f64 = 1e-11;

/// The time before the move and after it over which the bounded solution
/// decays to [`HORIZON_DECAY`] of its size: `ln(1 / HORIZON_DECAY) /
/// min |Re lambda|` over the internal dynamics at the start's rest state
/// (`T_pre`) and at the end's (`T_post`). Internal dynamics with an
/// eigenvalue on the imaginary axis (an undamped oscillation) have no
/// unique bounded solution: [`Error::NoBoundedSolution`].
pub fn horizons(start: &InternalDynamics, end: &InternalDynamics) -> Result<(f64, f64), Error> {
    let horizon = |d: &InternalDynamics| -> Result<f64, Error> {
        // the eigenvalue nearest the imaginary axis decays slowest
        let Some(&(re, im)) = d.eigenvalues.iter().min_by(|a, b| a.0.abs().total_cmp(&b.0.abs())) else {
            return Ok(0.0);
        };
        let size = d.eigenvalues.iter().map(|e| e.0.hypot(e.1)).fold(1.0, f64::max);
        if !(re.abs() > IMAGINARY_AXIS * size) {
            return Err(Error::NoBoundedSolution { t: d.t, re, im });
        }
        Ok((1.0 / HORIZON_DECAY).ln() / re.abs())
    };
    Ok((horizon(start)?, horizon(end)?))
}

/// The settings of a stable inversion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StableInversionOptions {
    /// Node spacing, s.
    pub dt: f64,
    /// Start of the motion (the path at rest before it), s.
    pub t0: f64,
    /// End of the motion (the path at rest after it), s.
    pub tf: f64,
    /// Pre-actuation time before `t0`, s (rounded up to whole steps).
    pub t_pre: f64,
    /// Post-actuation time after `tf`, s (rounded up to whole steps).
    pub t_post: f64,
}

/// The bounded solution and how it was found.
#[derive(Debug, Clone)]
pub struct StableInversion<const N: usize, const M: usize, const A: usize> {
    /// The states at every node, from `t0 - T_pre` to `tf + T_post`.
    pub solution: Solution<N, M, A>,
    /// Pre-actuation time taken (whole steps), s.
    pub t_pre: f64,
    /// Post-actuation time taken (whole steps), s.
    pub t_post: f64,
    /// Newton iterations of the whole system.
    pub iterations: usize,
    /// The robot coordinates' largest rate at the first and last nodes'
    /// neighbours, relative to their largest rate over the run: how far
    /// from rest the solution is where the rest state was imposed.
    pub boundary_residual: f64,
}

/// The bounded solution of the servo problem on `[t0 - T_pre, tf +
/// T_post]` from the rest state `start` at `t0` (see the module docs).
pub fn stable_inversion<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: &Tr,
    start: &State<N, M, A>,
    options: &StableInversionOptions,
) -> Result<StableInversion<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    let StableInversionOptions {
        dt,
        t0,
        tf,
        t_pre,
        t_post,
    } = *options;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::InvalidTimeStep { dt });
    }
    if !(tf > t0 && t_pre >= 0.0 && t_post >= 0.0 && (tf - t0 + t_pre + t_post).is_finite()) {
        return Err(Error::InvalidTimeSpan {
            t0: t0 - t_pre.max(0.0),
            tf: tf + t_post.max(0.0),
        });
    }
    let n_move = ((tf - t0) / dt).round();
    if (n_move * dt - (tf - t0)).abs() > 1e-9 * (tf - t0) {
        return Err(Error::StepsDoNotFit { dt, span: tf - t0 });
    }
    let n_pre = (t_pre / dt - 1e-9).ceil().max(0.0) as usize;
    let n_post = (t_post / dt - 1e-9).ceil().max(0.0) as usize;
    let nodes = n_pre + n_move as usize + n_post + 1;
    let time = |k: usize| t0 + (k as f64 - n_pre as f64) * dt;
    let solution_capacity = Solution::<N, M, A>::with_capacity(Mdl::INFO, dt, "central-differences", nodes)?;

    let p = N - A;
    let block = N + M;
    let dim = block * nodes;
    // the path at every node: gamma, gamma', gamma''
    let mut path = Vec::new();
    path.try_reserve_exact(nodes).map_err(|_| Error::TooManySteps {
        steps: nodes as f64,
        bytes: (nodes * 3 * A * 8) as f64,
    })?;
    for k in 0..nodes {
        path.push([0, 1, 2].map(|order| trajectory.derivative(time(k), order)));
    }

    // Newton's start: the quasi-static motion, each node's static
    // equilibrium (with the load's acceleration) from its neighbour's
    let mut z = DVector::<f64>::zeros(dim);
    let dt2 = dt * dt;
    let mut guess: Vec<f64> = start.q.as_slice()[..p].to_vec();
    let mut last = *start;
    for k in 0..nodes {
        let state = if time(k) <= t0 {
            *start
        } else {
            init::static_equilibrium(model, trajectory, time(k), &guess).unwrap_or(last)
        };
        guess.copy_from_slice(&state.q.as_slice()[..p]);
        let at = k * block;
        z.rows_mut(at, p).copy_from(&state.q.rows(0, p));
        z.rows_mut(at + p, A).copy_from(&(state.u * dt2));
        z.rows_mut(at + N, M).copy_from(&(state.lambda * dt2));
        last = state;
    }

    let mut system = System {
        model,
        path: &path,
        dt,
        nodes,
        triplets: Vec::new(),
        residual: DVector::zeros(dim),
    };
    let mut iterations = 0;
    loop {
        crate::cancel::check()?;
        system.evaluate(&z, true);
        let norm = system.residual.amax();
        if !norm.is_finite() {
            return Err(Error::NonFinite {
                quantity: "stable inversion residual",
                t: t0,
            });
        }
        let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(dim, dim, &system.triplets).map_err(|_| {
            Error::NonFinite {
                quantity: "stable inversion matrix",
                t: t0,
            }
        })?;
        let lu = matrix.sp_lu().map_err(|_| Error::SingularIterationMatrix {
            t: t0,
            pivot_ratio: 0.0,
        })?;
        let rhs = Mat::<f64>::from_fn(dim, 1, |i, _| -system.residual[i]);
        let step = lu.solve(&rhs);
        let step = DVector::from_fn(dim, |i, _| step[(i, 0)]);
        if !step.iter().all(|x| x.is_finite()) {
            return Err(Error::SingularIterationMatrix {
                t: t0,
                pivot_ratio: 0.0,
            });
        }
        // converged when each kind of unknown moves by at most the
        // tolerance of its largest size (coordinates, inputs, multipliers):
        // the step is taken whole, its residual at round-off, where a line
        // search would see only noise
        let converged = [0..p, p..N, N..block].into_iter().all(|range| {
            let (mut size, mut moved) = (0.0f64, 0.0f64);
            for k in 0..nodes {
                for i in range.clone() {
                    size = size.max(z[k * block + i].abs());
                    moved = moved.max(step[k * block + i].abs());
                }
            }
            moved <= UPDATE_TOLERANCE * size.max(f64::MIN_POSITIVE)
        });
        iterations += 1;
        if converged {
            z += &step;
            break;
        }
        // backtracking on the residual: a full step where it does not grow
        let mut alpha = 1.0;
        let mut trial = &z + &step;
        loop {
            system.evaluate(&trial, false);
            let trial_norm = system.residual.amax();
            if trial_norm.is_finite() && (trial_norm <= norm || alpha < 1.0 / 64.0) {
                break;
            }
            alpha *= 0.5;
            trial = &z + &step * alpha;
        }
        z = trial;
        if iterations >= MAX_ITERATIONS {
            system.evaluate(&z, false);
            return Err(Error::StableInversionNotConverged {
                iterations,
                residual: system.residual.amax(),
            });
        }
    }

    // the states, with central rates inside and rest at the ends
    let mut solution = solution_capacity;
    let mut lengths = vec![0.0; Mdl::INFO.ropes.len()];
    let coordinate = |k: usize, i: usize| z[k * block + i];
    for k in 0..nodes {
        let [gamma, rate, _] = path[k];
        let q = SVector::<f64, N>::from_fn(|i, _| if i < p { coordinate(k, i) } else { gamma[i - p] });
        let v = SVector::<f64, N>::from_fn(|i, _| {
            if i >= p {
                rate[i - p]
            } else if k == 0 || k + 1 == nodes {
                0.0
            } else {
                (coordinate(k + 1, i) - coordinate(k - 1, i)) / (2.0 * dt)
            }
        });
        let state = State {
            t: time(k),
            q,
            v,
            u: SVector::from_fn(|i, _| coordinate(k, p + i) / dt2),
            lambda: SVector::from_fn(|i, _| coordinate(k, N + i) / dt2),
        };
        let report = StepReport {
            iterations: if k == 0 { 0 } else { iterations },
            ..StepReport::default()
        };
        solution.push(model, &state, report, &mut lengths);
    }
    Ok(StableInversion {
        boundary_residual: boundary_residual(&solution),
        solution,
        t_pre: n_pre as f64 * dt,
        t_post: n_post as f64 * dt,
        iterations,
    })
}

/// The robot coordinates' largest rate at the nodes next to the two ends
/// of a stable inversion's `solution`, relative to their largest rate over
/// it (0 where nothing moves): how far from rest the solution is where rest
/// was imposed, about [`HORIZON_DECAY`] when the horizons are long enough.
pub fn boundary_residual<const N: usize, const M: usize, const A: usize>(solution: &Solution<N, M, A>) -> f64 {
    let states = &solution.states;
    let robot_rate = |s: &State<N, M, A>| s.v.rows(0, N - A).amax();
    let largest = states.iter().map(robot_rate).fold(0.0, f64::max);
    let n = states.len();
    let boundary = [1, n.saturating_sub(2)]
        .into_iter()
        .filter_map(|k| states.get(k))
        .map(robot_rate)
        .fold(0.0, f64::max);
    if largest > 0.0 { boundary / largest } else { 0.0 }
}

/// The residual and Jacobian of the whole boundary value problem.
struct System<'a, Mdl, const N: usize, const M: usize, const A: usize> {
    model: &'a Mdl,
    /// `gamma, gamma', gamma''` at every node.
    path: &'a [[SVector<f64, A>; 3]],
    dt: f64,
    nodes: usize,
    /// The Jacobian's entries (row, column, value), duplicates summed.
    triplets: Vec<Triplet<usize, usize, f64>>,
    residual: DVector<f64>,
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> System<'_, Mdl, N, M, A> {
    /// The residual at `z` (and the Jacobian's entries where `jacobian`):
    /// per node, `dt^2 (f + B^T u - G^T lambda - M q'')` (N rows) and
    /// `g(q)` (M rows), with `q'' = 0`, `p' = 0` at the end nodes.
    fn evaluate(&mut self, z: &DVector<f64>, jacobian: bool) {
        let (p, block, dt) = (N - A, N + M, self.dt);
        let dt2 = dt * dt;
        let mass = self.model.mass_matrix::<f64>();
        self.triplets.clear();
        for k in 0..self.nodes {
            let at = k * block;
            let inner = k > 0 && k + 1 < self.nodes;
            let [gamma, rate, accel] = self.path[k];
            let robot = |node: usize, i: usize| z[node * block + i];
            let q = SVector::<f64, N>::from_fn(|i, _| if i < p { robot(k, i) } else { gamma[i - p] });
            // dt q' and dt^2 q'' of the central differences (rest at the ends)
            let dt_v = SVector::<f64, N>::from_fn(|i, _| {
                if i >= p {
                    dt * rate[i - p]
                } else if inner {
                    0.5 * (robot(k + 1, i) - robot(k - 1, i))
                } else {
                    0.0
                }
            });
            let dt2_a = SVector::<f64, N>::from_fn(|i, _| {
                if i >= p {
                    dt2 * accel[i - p]
                } else if inner {
                    robot(k + 1, i) - 2.0 * robot(k, i) + robot(k - 1, i)
                } else {
                    0.0
                }
            });
            let v = dt_v / dt;
            let scaled_u = SVector::<f64, A>::from_fn(|i, _| z[at + p + i]);
            let scaled_lambda = SVector::<f64, M>::from_fn(|i, _| z[at + N + i]);
            let bt = self.model.input_matrix(&q);
            let jac_g = self.model.constraint_jacobian(&q);
            let balance = self.model.forces(&q, &v) * dt2 + bt * scaled_u - jac_g.tr_mul(&scaled_lambda) - mass * dt2_a;
            self.residual.rows_mut(at, N).copy_from(&balance);
            self.residual.rows_mut(at + N, M).copy_from(&self.model.constraints(&q));
            if !jacobian {
                continue;
            }
            let (df_dq, df_dv) = self.model.force_jacobians(&q, &v);
            let d_balance = df_dq * dt2 + self.model.input_jacobian(&q, &scaled_u)
                - self.model.constraint_hessian(&q, &scaled_lambda);
            let triplets = &mut self.triplets;
            for j in 0..p {
                for i in 0..N {
                    let own = d_balance[(i, j)] + if inner { 2.0 * mass[(i, j)] } else { 0.0 };
                    triplets.push(Triplet::new(at + i, at + j, own));
                    if inner {
                        // p_(k-1) and p_(k+1) through q'' and q'
                        let half_dt_damping = 0.5 * dt * df_dv[(i, j)];
                        triplets.push(Triplet::new(at + i, at - block + j, -mass[(i, j)] - half_dt_damping));
                        triplets.push(Triplet::new(at + i, at + block + j, -mass[(i, j)] + half_dt_damping));
                    }
                }
                for i in 0..M {
                    triplets.push(Triplet::new(at + N + i, at + j, jac_g[(i, j)]));
                }
            }
            for j in 0..A {
                for i in 0..N {
                    triplets.push(Triplet::new(at + i, at + p + j, bt[(i, j)]));
                }
            }
            for j in 0..M {
                for i in 0..N {
                    triplets.push(Triplet::new(at + i, at + N + j, -jac_g[(j, i)]));
                }
            }
        }
    }
}

/// A computed bounded solution played back one step at a time, behind
/// [`Advance`]: for a host that steps a crane along a path known in advance
/// (an FMU's built-in move). It starts `lead` steps before the solution's
/// first node, at its rest state there, and after its last node stays at
/// the last node's rest state, the time going on by whole steps. A step
/// does not allocate.
pub struct Playback<H, const N: usize, const M: usize, const A: usize> {
    model: H,
    states: Vec<State<N, M, A>>,
    /// The current state (its time counts the steps taken).
    state: State<N, M, A>,
    /// The start's time.
    t_first: f64,
    /// Steps taken.
    steps: usize,
    /// Steps before the solution's first node.
    lead: usize,
    dt: f64,
    path_order_covered: Option<usize>,
}

impl<H, const N: usize, const M: usize, const A: usize> Playback<H, N, M, A>
where
    H: std::ops::Deref<Target: CraneModel<N, M, A> + Sized>,
{
    /// The playback of `solution` (at least one state) from `lead` steps of
    /// its step before its first node; [`Error::NothingToReplay`] for an
    /// empty solution.
    pub fn new(model: H, solution: Solution<N, M, A>, lead: usize) -> Result<Self, Error> {
        let first = *solution.states.first().ok_or(Error::NothingToReplay)?;
        let t_first = first.t - lead as f64 * solution.dt;
        Ok(Self {
            model,
            state: State { t: t_first, ..first },
            states: solution.states,
            t_first,
            steps: 0,
            lead,
            dt: solution.dt,
            path_order_covered: solution.path_order_covered,
        })
    }
}

impl<H, const N: usize, const M: usize, const A: usize> Advance<N, M, A> for Playback<H, N, M, A>
where
    H: std::ops::Deref<Target: CraneModel<N, M, A> + Sized>,
{
    type Model = H::Target;
    fn model(&self) -> &H::Target {
        &self.model
    }
    /// The next state of the solution (its first before it, its last after
    /// it), at the next step's time.
    fn step(&mut self) -> Result<StepReport, Error> {
        self.steps += 1;
        let node = self.steps.saturating_sub(self.lead).min(self.states.len() - 1);
        self.state = State {
            t: self.t_first + self.steps as f64 * self.dt,
            ..self.states[node]
        };
        Ok(StepReport::default())
    }
    fn state(&self) -> &State<N, M, A> {
        &self.state
    }
    fn dt(&self) -> f64 {
        self.dt
    }
    fn scheme_name(&self) -> &'static str {
        "central-differences"
    }
    fn path_order_covered(&self) -> Option<usize> {
        self.path_order_covered
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dynamics(t: f64, eigenvalues: &[(f64, f64)]) -> InternalDynamics {
        InternalDynamics {
            t,
            dimension: eigenvalues.len(),
            eigenvalues: eigenvalues.to_vec(),
            max_real_part: eigenvalues.iter().map(|e| e.0).fold(f64::NEG_INFINITY, f64::max),
        }
    }

    /// `T = ln(1e10) / min |Re lambda|` on each side: 2.3248 s for the
    /// coupled trolley's +-9.9045 1/s, and the slowest eigenvalue decides.
    #[test]
    fn horizons_decay_the_slowest_mode_to_1e_minus_10() {
        let start = dynamics(0.0, &[(9.9045, 0.0), (-9.9045, 0.0)]);
        let end = dynamics(5.0, &[(2.0, 3.0), (2.0, -3.0), (-0.5, 0.0)]);
        let (pre, post) = horizons(&start, &end).unwrap();
        assert!((pre - 10f64.ln() * 10.0 / 9.9045).abs() < 1e-12, "{pre}");
        assert!((post - 10f64.ln() * 10.0 / 0.5).abs() < 1e-12, "{post}");
        assert!((pre * 9.9045).exp().recip() <= HORIZON_DECAY * (1.0 + 1e-12));
        // no internal dynamics: no horizon
        assert_eq!(horizons(&dynamics(0.0, &[]), &dynamics(5.0, &[])).unwrap(), (0.0, 0.0));
    }

    /// An undamped oscillation (eigenvalues on the imaginary axis) has no
    /// unique bounded solution: refused, naming the eigenvalue; a damping
    /// of 1e-6 1/s is not on the axis.
    #[test]
    fn an_undamped_oscillation_has_no_bounded_solution() {
        let rest = dynamics(0.0, &[(9.9, 0.0), (-9.9, 0.0)]);
        let undamped = dynamics(5.0, &[(0.0, 2.2147), (0.0, -2.2147)]);
        let error = horizons(&rest, &undamped).unwrap_err();
        assert!(matches!(error, Error::NoBoundedSolution { t: 5.0, .. }), "{error}");
        let message = error.to_string();
        assert!(message.contains("+ 2.2147i 1/s on the imaginary axis"), "{message}");
        assert!(message.contains("no unique bounded solution"), "{message}");
        let damped = dynamics(5.0, &[(-1e-6, 2.2147), (-1e-6, -2.2147)]);
        assert!(horizons(&rest, &damped).is_ok());
    }
}
