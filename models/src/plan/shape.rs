//! The fastest move with its shape optimised, not only its duration
//! ([`fastest_shape`]): for a flat crane the load path is the flat output,
//! so every smooth path has unique inputs, and the fastest rest-to-rest move
//! under the limits is a finite-dimensional programme over path shapes,
//! with the exact inverse run as the constraint evaluator.
//!
//! **Variables**: the duration `T` and the free control points of a
//! clamped B-spline of the normalised time `s = (t - t0) / T` per load
//! coordinate: degree `p + 2` for the crane's path order `p`, uniform
//! knots, the first and the last `p + 1` control points the start and the
//! end (at rest to order `p` at both ends, continuous to order `p + 1`
//! inside, so the inputs are continuous).
//!
//! **Constraints**: every limited `|u_k| <= limit` and every tension floor,
//! at fixed samples of `s` (the steps of the exact run, at least thirty
//! per knot span). **Objective**: `T`.
//!
//! **Method**: sequential linear programming with a trust region (each
//! linear programme solved by clarabel's interior point method), on the
//! exact merit `T + mu max(0, worst violation)`; the constraints'
//! Jacobian by forward differences of the inverse run, one run per
//! variable, in parallel. It starts from the spline's own time-scaled
//! optimum (feasible), and ends with the shaped path's time-scaled
//! optimum found by [`fastest`](super::fastest) (so the answer is checked
//! as any `fastest` answer is: between the steps, with the audit).
//!
//! On gantry-3d's case the sequential programming reaches 1.046 times the
//! rigid-body bound in about 1,600 inverse runs, where OpEn's augmented
//! Lagrangian with PANOC on the same programme had not converged after
//! 70,000 (the measurement is this module's ignored test).

use std::sync::Arc;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus};
use rayon::prelude::*;
use serde::Serialize;

use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, Solution};

use super::{Binding, Fastest, Limits, PlanError, Settings, evaluate, fastest, run};
use crate::case::Case;
use crate::crane::{Crane, LowerBound};
use crate::path::{Path, PathSpec, Profile, SplineShape};

/// How the shape is searched.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShapeSettings {
    /// Free control points per load coordinate (between the `p + 1` held
    /// at each end).
    pub control_points: usize,
    /// Samples of the constraints per move, at least (more where the knot
    /// spans need them: thirty per span).
    pub samples: usize,
    /// Most iterations of the sequential programming.
    pub iterations: usize,
}

impl Default for ShapeSettings {
    /// 20 free control points per coordinate, 200 samples, 150 iterations.
    fn default() -> Self {
        Self {
            control_points: 20,
            samples: 200,
            iterations: 150,
        }
    }
}

/// The most free control points per coordinate: beyond them a move's
/// shape gains little and each iteration costs a run per point.
pub const MAX_CONTROL_POINTS: usize = 40;

/// One iteration of the search, for a progress display.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeProgress {
    /// The iteration.
    pub iteration: usize,
    /// The duration of the current shape, s.
    pub duration: f64,
    /// Its worst sampled violation, relative to the limit (0: none).
    pub violation: f64,
    /// The trust region's radius, in normalised variables.
    pub radius: f64,
}

/// The fastest shaped move.
#[derive(Debug, Clone)]
pub struct Shaped<const N: usize, const M: usize, const A: usize> {
    /// The duration, s: the optimised shape at it is feasible, checked as
    /// a `fastest` answer is (between the steps, with the audit), on steps
    /// four times finer than the samples.
    pub duration: f64,
    /// The answer's path: the optimised shape, lasting `duration`.
    pub path: PathSpec<A>,
    /// Every limit at the answer.
    pub at_answer: Vec<Binding>,
    /// The run at the answer.
    pub solution: Solution<N, M, A>,
    /// The margin the samples kept below each limit (relative), so that
    /// the check between the steps holds.
    pub margin: f64,
    /// The time-scaled optimum of the spline the search started from, s.
    pub start: f64,
    /// Iterations of the sequential programming.
    pub iterations: usize,
    /// Inverse runs of the search (its own and the final `fastest`'s).
    pub runs: usize,
    /// The crane's lower bound on the duration, where it has one.
    pub lower_bound: Option<LowerBound>,
}

/// The problem in normalised variables `y`: `T = T_s (1 + y_0)`, each free
/// control point coordinate `c_i = c0_i + D y_i` for the move's length `D`.
struct Problem<'a, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    case: &'a Case<C, N, M, A>,
    limits: &'a Limits,
    order: usize,
    free: usize,
    start_duration: f64,
    start_points: Vec<SVector<f64, A>>,
    length: f64,
    samples: usize,
    /// The scale of each rope's tension (its floor, or its largest value
    /// on the start's run): tension constraints are relative to it.
    tension_scale: Vec<f64>,
    /// The margin kept below each limit at the samples, relative.
    margin: f64,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> Problem<'_, C, N, M, A> {
    fn variables(&self) -> usize {
        1 + self.free * A
    }

    /// The degree, knots and all control points of the shape at `y`.
    fn shape(&self, y: &[f64]) -> Result<SplineShape, PlanError> {
        let spec = self.case.path().spec();
        let degree = self.order + 2;
        let held = self.order + 1;
        let mut points = vec![spec.start; held];
        for (i, base) in self.start_points.iter().enumerate() {
            points.push(base + SVector::from_fn(|c, _| self.length * y[1 + i * A + c]));
        }
        points.extend(std::iter::repeat_n(spec.end, held));
        let n = points.len();
        let spans = n - degree;
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..spans).map(|j| j as f64 / spans as f64));
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        SplineShape::new(degree, knots, &points).map_err(|e| PlanError::Settings(format!("the shape: {e}")))
    }

    fn duration(&self, y: &[f64]) -> f64 {
        self.start_duration * (1.0 + y[0])
    }

    /// The case of the shape at `y`, ending with the motion.
    fn case_at(&self, y: &[f64]) -> Result<Case<C, N, M, A>, String> {
        let spec = self.case.path().spec();
        let shape = self.shape(y).map_err(|e| e.to_string())?;
        let t1 = spec.t0 + self.duration(y);
        let path = Path::new(PathSpec {
            profile: Profile::Spline(Arc::new(shape)),
            t0: spec.t0,
            t1,
            start: spec.start,
            end: spec.end,
        })
        .map_err(|e| e.to_string())?;
        Ok(Case::from_parts(
            self.case.model().clone(),
            path,
            self.case.p0.clone(),
            t1,
        ))
    }

    /// The exact run of the shape at `y`, one step per sample.
    fn run(&self, y: &[f64]) -> Result<Solution<N, M, A>, String> {
        let duration = self.duration(y);
        if !(duration > 0.0 && duration.is_finite()) {
            return Err(format!("a duration of {duration} s"));
        }
        let case = self.case_at(y)?;
        let settings = Settings {
            dt: duration / self.samples as f64,
            ..Settings::default()
        };
        let solution = run(&case, &settings)?;
        if solution.states.len() != self.samples + 1 {
            return Err(format!(
                "{} steps, not the {} samples",
                solution.states.len() - 1,
                self.samples
            ));
        }
        Ok(solution)
    }

    /// The constraints `g <= 0` at `y`, relative to their limits: `u_k /
    /// limit - 1` and `-u_k / limit - 1` per limited input and sample,
    /// `(floor - N_r) / scale` per floored rope and sample.
    fn constraints(&self, y: &[f64]) -> Result<Vec<f64>, String> {
        let solution = self.run(y)?;
        let mut g = Vec::with_capacity(self.constraint_count());
        // the crane at rest at the start and at the end is the same whatever
        // the shape and the duration (a rope may carry nothing there, as
        // navy-planar's N1 at its start): those samples constrain nothing
        let last = solution.states.len() - 1;
        for (i, state) in solution.states.iter().enumerate().take(last).skip(1) {
            for &(k, limit) in &self.limits.torque {
                g.push(state.u[k] / limit - (1.0 - self.margin));
                g.push(-state.u[k] / limit - (1.0 - self.margin));
            }
            let tensions = solution.tensions_at(i);
            for (&(r, floor), scale) in self.limits.tension.iter().zip(&self.tension_scale) {
                g.push((floor - tensions[r]) / scale + self.margin);
            }
        }
        if g.iter().any(|v| !v.is_finite()) {
            return Err("an input or a tension is not finite".into());
        }
        Ok(g)
    }

    fn constraint_count(&self) -> usize {
        (self.samples - 1) * (2 * self.limits.torque.len() + self.limits.tension.len())
    }
}

/// The worst violation of `g` (0 where every constraint holds).
fn violation(g: &[f64]) -> f64 {
    g.iter().copied().fold(0.0, f64::max)
}

/// The penalty on the worst violation in the merit `y_0 + mu max(0, g)`: a
/// violation of 1 % of a limit weighs as a tenth of the duration.
const PENALTY: f64 = 10.0;

/// The linear programme of one iteration: minimise `d_0 + mu sigma` over
/// the step `d` and `sigma >= 0`, with `g + J d <= sigma` and `|d_i| <=
/// radius`. Returns the step, or `None` where clarabel finds no solution.
fn step(g: &[f64], jacobian: &[Vec<f64>], radius: f64) -> Option<Vec<f64>> {
    let n = jacobian.len(); // variables, each a column of partials
    let m = g.len();
    let columns = n + 1; // and sigma
    // rows: the m linearised constraints, then d_i <= r, -d_i <= r, -sigma <= 0
    let rows = m + 2 * n + 1;
    let mut colptr = Vec::with_capacity(columns + 1);
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    colptr.push(0);
    for (j, column) in jacobian.iter().enumerate() {
        for (i, &value) in column.iter().enumerate() {
            if value != 0.0 {
                rowval.push(i);
                nzval.push(value);
            }
        }
        rowval.extend([m + 2 * j, m + 2 * j + 1]);
        nzval.extend([1.0, -1.0]);
        colptr.push(rowval.len());
    }
    rowval.extend(0..m);
    nzval.extend(std::iter::repeat_n(-1.0, m));
    rowval.push(m + 2 * n);
    nzval.push(-1.0);
    colptr.push(rowval.len());
    let a = CscMatrix::new(rows, columns, colptr, rowval, nzval);
    let mut b: Vec<f64> = g.iter().map(|v| -v).collect();
    b.extend(std::iter::repeat_n(radius, 2 * n));
    b.push(0.0);
    let mut q = vec![0.0; columns];
    q[0] = 1.0;
    q[n] = PENALTY;
    let p = CscMatrix::zeros((columns, columns));
    let settings = DefaultSettingsBuilder::default().verbose(false).build().ok()?;
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &[NonnegativeConeT(rows)], settings).ok()?;
    solver.solve();
    matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    )
    .then(|| solver.solution.x[..n].to_vec())
}

/// The rest-to-rest rise of the built-in poly9 move from 0 to 1 over `s` in
/// `[0, 1]`: `126 s^5 - 420 s^6 + 540 s^7 - 315 s^8 + 70 s^9` (eqs. 41-45).
fn poly9_rise(s: f64) -> f64 {
    s.powi(5) * (126.0 + s * (-420.0 + s * (540.0 + s * (-315.0 + s * 70.0))))
}

/// Samples of the constraints per knot span, at least: the knot spans of
/// the optimised shapes are where their inputs turn.
const SAMPLES_PER_SPAN: usize = 30;

/// The margin below the limits at the samples in the first round, widened
/// threefold per round until the check between the steps holds (at thirty
/// samples per knot span the peaks of a shape near the optimum rise above
/// the samples by up to about 1e-3 of a limit), and the widest tried.
const FIRST_MARGIN: f64 = 1e-4;
const LAST_MARGIN: f64 = 1e-2;

/// Iterate the sequential linear programming from `y` (at most
/// `iterations`, until the trust region collapses); returns the iterations.
fn search<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    problem: &Problem<'_, C, N, M, A>,
    y: &mut Vec<f64>,
    iterations: usize,
    runs: &mut usize,
    progress: &mut dyn FnMut(ShapeProgress),
) -> Result<usize, PlanError> {
    let n = problem.variables();
    let mut g = problem.constraints(y).map_err(|e| PlanError::RunFailsFirst {
        duration: problem.duration(y),
        error: e,
    })?;
    *runs += 1;
    let merit = |y: &[f64], g: &[f64]| y[0] + PENALTY * violation(g);
    let mut radius: f64 = 0.1;
    let h = 1e-7;
    let mut done = 0;
    while done < iterations && radius > 1e-5 {
        done += 1;
        // the Jacobian, a column per variable, in parallel
        let jacobian: Vec<Vec<f64>> = (0..n)
            .into_par_iter()
            .map(|j| {
                let mut shifted = y.clone();
                shifted[j] += h;
                problem
                    .constraints(&shifted)
                    .map(|gj| gj.iter().zip(&g).map(|(a, b)| (a - b) / h).collect())
            })
            .collect::<Result<_, _>>()
            .map_err(|e| PlanError::RunFailsFirst {
                duration: problem.duration(y),
                error: e,
            })?;
        *runs += n;
        // trust-region steps until one is accepted or the region collapses
        loop {
            let Some(d) = step(&g, &jacobian, radius) else {
                radius /= 4.0;
                break;
            };
            let linear: Vec<f64> = (0..g.len())
                .map(|i| g[i] + (0..n).map(|j| jacobian[j][i] * d[j]).sum::<f64>())
                .collect();
            let trial: Vec<f64> = y.iter().zip(&d).map(|(a, b)| a + b).collect();
            let predicted = merit(y, &g) - merit(&trial, &linear);
            if !(predicted > 1e-9) {
                radius = 0.0;
                break;
            }
            *runs += 1;
            let actual = match problem.constraints(&trial) {
                Ok(gt) => {
                    let reduction = merit(y, &g) - merit(&trial, &gt);
                    if reduction >= 0.1 * predicted {
                        *y = trial;
                        g = gt;
                    }
                    reduction
                }
                Err(_) => f64::NEG_INFINITY,
            };
            let longest = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if actual >= 0.75 * predicted && longest >= 0.99 * radius {
                radius *= 2.0;
            } else if actual < 0.25 * predicted {
                radius = longest.min(radius) / 4.0;
            }
            if actual >= 0.1 * predicted || radius <= 1e-5 {
                break;
            }
        }
        progress(ShapeProgress {
            iteration: done,
            duration: problem.duration(y),
            violation: violation(&g),
            radius,
        });
    }
    Ok(done)
}

/// The programme of `case`'s move under `limits` with `shape`'s control
/// points, started at the poly9 move's spline time-scaled to its own
/// optimum (`y = 0`); that time-scaled answer and the runs it took.
fn programme<'a, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &'a Case<C, N, M, A>,
    limits: &'a Limits,
    settings: &Settings,
    shape: &ShapeSettings,
) -> Result<(Problem<'a, C, N, M, A>, Fastest<N, M, A>, usize), PlanError> {
    if limits.torque.is_empty() && limits.tension.is_empty() {
        return Err(PlanError::NoLimits);
    }
    if !(1..=MAX_CONTROL_POINTS).contains(&shape.control_points) {
        return Err(PlanError::Settings(format!(
            "control points {}: between 1 and {MAX_CONTROL_POINTS} per coordinate",
            shape.control_points
        )));
    }
    let order = <C::Model as CraneModel<N, M, A>>::STRUCTURE
        .filter(|s| s.dimension == 0)
        .map(|s| s.path_order(A))
        .ok_or_else(|| {
            PlanError::Settings(format!(
                "{} is not flat (or declares no structure): its path does not determine its inputs, so its \
                 shape cannot be optimised through them",
                C::NAME
            ))
        })?;
    let spec = case.path().spec();
    let (start, end) = (spec.start, spec.end);
    let length = (end - start).norm();
    if !(length > 0.0) {
        return Err(PlanError::Settings(
            "the move's start and end are the same point".into(),
        ));
    }
    let free = shape.control_points;
    // the knot spans: n - degree of n = 2 (p + 1) + free points
    let spans = order + free;
    // the start: the built-in poly9 move's shape, approximated by the
    // spline whose control points are its values at their Greville
    // abscissae (the mean of the `degree` knots after each point's first),
    // which keeps its monotone rise
    let degree = order + 2;
    let knot = |j: usize| (j.saturating_sub(degree) as f64 / spans as f64).min(1.0);
    let start_points: Vec<SVector<f64, A>> = (order + 1..order + 1 + free)
        .map(|i| {
            let greville = (i + 1..=i + degree).map(knot).sum::<f64>() / degree as f64;
            start + (end - start) * poly9_rise(greville)
        })
        .collect();
    let samples = shape.samples.max(SAMPLES_PER_SPAN * spans);
    // the start, time-scaled to its own optimum
    let mut problem = Problem {
        case,
        limits,
        order,
        free,
        start_duration: spec.t1 - spec.t0,
        start_points,
        length,
        samples,
        tension_scale: Vec::new(),
        margin: FIRST_MARGIN,
    };
    let zero = vec![0.0; problem.variables()];
    let initial = problem.case_at(&zero).map_err(PlanError::Settings)?;
    let scaled = fastest(&initial, limits, settings)?;
    let runs = scaled.evaluations + scaled.interval.points;
    problem.start_duration = scaled.duration;
    problem.tension_scale = limits
        .tension
        .iter()
        .map(|&(r, floor)| {
            let largest = (0..scaled.solution.states.len())
                .map(|i| scaled.solution.tensions_at(i)[r].abs())
                .fold(0.0, f64::max);
            floor.abs().max(largest).max(1.0)
        })
        .collect();
    Ok((problem, scaled, runs))
}

/// The fastest move of `case`'s start to its end with the shape optimised
/// (see the module docs), calling `progress` after every iteration.
pub fn fastest_shape<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    limits: &Limits,
    settings: &Settings,
    shape: &ShapeSettings,
    progress: &mut dyn FnMut(ShapeProgress),
) -> Result<Shaped<N, M, A>, PlanError> {
    let (mut problem, scaled, mut runs) = programme(case, limits, settings, shape)?;
    let (start, end) = {
        let spec = case.path().spec();
        (spec.start, spec.end)
    };
    let mut y = vec![0.0; problem.variables()];
    let mut iterations = 0;
    // rounds of the programme, each with a wider margin below the limits
    // at the samples until the check between the steps holds
    let (duration, path, at_answer, solution) = loop {
        iterations += search(&problem, &mut y, shape.iterations, &mut runs, progress)?;
        let duration = problem.duration(&y);
        let case = problem.case_at(&y).map_err(PlanError::Settings)?;
        // checked on steps four times finer than the samples (the peaks
        // between them then within about 2e-6 of a limit)
        let finer = Settings {
            dt: duration / (4 * problem.samples) as f64,
            ..*settings
        };
        let (evaluation, solution) = evaluate(&case, duration, &finer);
        runs += 1;
        match solution {
            Some(solution) if evaluation.feasible::<C::Model, N, M, A>(limits) => {
                let path = case.path().spec().clone();
                break (
                    duration,
                    path,
                    evaluation.bindings::<C::Model, N, M, A>(limits),
                    solution,
                );
            }
            _ if problem.margin < LAST_MARGIN => problem.margin *= 3.0,
            // the start, time-scaled, is feasible: never worse than it
            _ => break (scaled.duration, scaled.path, scaled.at_answer, scaled.solution),
        }
    };
    Ok(Shaped {
        duration,
        path,
        at_answer,
        solution,
        margin: problem.margin,
        start: problem.start_duration,
        iterations,
        runs,
        lower_bound: C::lower_bound(case.model(), &start, &end, &limits.torque),
    })
}

#[cfg(test)]
mod tests {
    //! The programme's solver, chosen by measurement: the sequential linear
    //! programming above against OpEn's augmented Lagrangian with PANOC
    //! (`optimization_engine`) on the same programme, the same start and
    //! the same forward-difference Jacobian of the inverse runs.
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::time::{Duration, Instant};

    use optimization_engine::SolverError;
    use optimization_engine::alm::{AlmCache, AlmFactory, AlmOptimizer, AlmProblem, NO_JACOBIAN_MAPPING, NO_MAPPING};
    use optimization_engine::constraints::Rectangle;
    use optimization_engine::core::panoc::PANOCCache;

    use super::*;
    use crate::gantry_3d;

    /// gantry-3d's default move under |u1| <= 1000 N, 20 control points per
    /// coordinate, from the same time-scaled start: the SLP's first round
    /// (margin 1e-4) against OpEn given four times its inverse runs and
    /// two minutes. Prints both; asserts what each answer must be (never
    /// below the rigid-body bound 4.899 s where it holds the limit).
    /// By hand: `cargo test --release -p crane-models --lib
    /// plan::shape::tests -- --ignored --nocapture` (about three minutes).
    #[test]
    #[ignore = "a measurement of about three minutes, by hand"]
    fn sequential_linear_programming_against_open() {
        type D = gantry_3d::Description;
        let case = Case::<D, 6, 1, 3>::maneuver().unwrap();
        let limits = Limits {
            torque: vec![(0, 1000.0)],
            tension: vec![(0, 0.0)],
        };
        let settings = Settings::default();
        let (problem, scaled, _) = programme(&case, &limits, &settings, &ShapeSettings::default()).unwrap();
        let bound = 2.0 * (6.0f64 * 1000.0 / 1000.0).sqrt();
        let n = problem.variables();

        // the SLP's first round
        let clock = Instant::now();
        let mut y = vec![0.0; n];
        let mut slp_runs = 0;
        let iterations = search(&problem, &mut y, 150, &mut slp_runs, &mut |_| {}).unwrap();
        let slp_wall = clock.elapsed();
        let slp = (problem.duration(&y), violation(&problem.constraints(&y).unwrap()));
        println!(
            "SLP + clarabel: T = {:.4} s ({:.4}x the bound), worst violation {:.1e}, {iterations} iterations, \
             {slp_runs} inverse runs, {:.1} s",
            slp.0,
            slp.0 / bound,
            slp.1,
            slp_wall.as_secs_f64()
        );
        assert!(slp.1 <= 1e-6 && slp.0 >= bound && slp.0 < scaled.duration, "{slp:?}");

        // OpEn: minimise y_0 (T / T_s - 1) subject to g(y) in C = (-inf, 0]
        let runs = AtomicUsize::new(0);
        let m = problem.constraint_count();
        let h = 1e-7;
        // the Jacobian at the last point asked for (the point, then a
        // column per variable)
        type Known = Option<(Vec<f64>, Vec<Vec<f64>>)>;
        let jacobian: Mutex<Known> = Mutex::new(None);
        // a shape whose run fails (PANOC's steps go far) violates every
        // constraint by ten times its limit: its line search backs off, as
        // an error would end the solve
        let constraints = |u: &[f64]| problem.constraints(u).unwrap_or_else(|_| vec![10.0; m]);
        let g = |u: &[f64], out: &mut [f64]| -> Result<(), SolverError> {
            runs.fetch_add(1, Ordering::Relaxed);
            out.copy_from_slice(&constraints(u));
            Ok(())
        };
        let jacobian_transpose = |u: &[f64], d: &[f64], out: &mut [f64]| -> Result<(), SolverError> {
            let mut known = jacobian.lock().unwrap();
            if known.as_ref().is_none_or(|(at, _)| at != u) {
                let g0 = constraints(u);
                let columns: Vec<Vec<f64>> = (0..n)
                    .into_par_iter()
                    .map(|j| {
                        let mut shifted = u.to_vec();
                        shifted[j] += h;
                        let gj = constraints(&shifted);
                        gj.iter().zip(&g0).map(|(a, b)| (a - b) / h).collect()
                    })
                    .collect();
                runs.fetch_add(n + 1, Ordering::Relaxed);
                *known = Some((u.to_vec(), columns));
            }
            let (_, columns) = known.as_ref().unwrap();
            for (o, column) in out.iter_mut().zip(columns) {
                *o = column.iter().zip(d).map(|(a, b)| a * b).sum();
            }
            Ok(())
        };
        let cost = |u: &[f64], c: &mut f64| -> Result<(), SolverError> {
            *c = u[0];
            Ok(())
        };
        let gradient = |_: &[f64], out: &mut [f64]| -> Result<(), SolverError> {
            out.fill(0.0);
            out[0] = 1.0;
            Ok(())
        };
        let zeros = vec![0.0; m];
        let set_c = Rectangle::new(None, Some(&zeros));
        let factory = AlmFactory::new(
            cost,
            gradient,
            Some(g),
            Some(jacobian_transpose),
            NO_MAPPING,
            NO_JACOBIAN_MAPPING,
            Some(set_c),
            0,
        );
        // a box of the SLP's reach (its trust region starts at 0.1)
        let lower: Vec<f64> = (0..n).map(|i| if i == 0 { -0.5 } else { -0.3 }).collect();
        let upper: Vec<f64> = (0..n).map(|i| if i == 0 { 0.5 } else { 0.3 }).collect();
        let bounds = Rectangle::new(Some(&lower), Some(&upper));
        let big = vec![1e12; m];
        let set_y = Rectangle::new(Some(&zeros), Some(&big));
        let alm = AlmProblem::new(
            bounds,
            Some(set_c),
            Some(set_y),
            |u: &[f64], xi: &[f64], c: &mut f64| factory.psi(u, xi, c),
            |u: &[f64], xi: &[f64], grad: &mut [f64]| factory.d_psi(u, xi, grad),
            Some(g),
            NO_MAPPING,
            m,
            0,
        );
        let mut cache = AlmCache::new(PANOCCache::new(n, 1e-5, 10), m, 0);
        let clock = Instant::now();
        let mut u = vec![0.0; n];
        let status = AlmOptimizer::new(&mut cache, alm)
            .with_max_duration(Duration::from_secs(120))
            .with_max_outer_iterations(40)
            .with_max_inner_iterations(1000)
            .with_delta_tolerance(1e-5)
            .with_epsilon_tolerance(1e-4)
            .with_initial_inner_tolerance(1e-3)
            .with_inner_tolerance_update_factor(0.2)
            .with_initial_penalty(100.0)
            .with_penalty_update_factor(2.0)
            .with_sufficient_decrease_coefficient(0.1)
            .solve(&mut u);
        let open_wall = clock.elapsed();
        let open_runs = runs.load(Ordering::Relaxed);
        let open = (problem.duration(&u), violation(&constraints(&u)));
        println!(
            "OpEn (ALM + PANOC): T = {:.4} s ({:.4}x the bound), worst violation {:.1e}, {open_runs} inverse runs, \
             {:.1} s, {}",
            open.0,
            open.0 / bound,
            open.1,
            open_wall.as_secs_f64(),
            match &status {
                Ok(s) => format!(
                    "{:?} after {} outer and {} inner iterations",
                    s.exit_status(),
                    s.num_outer_iterations(),
                    s.num_inner_iterations()
                ),
                Err(e) => format!("error {e:?}"),
            }
        );
        // an answer that holds the limits is never below the bound
        assert!(open.1 > 1e-3 || open.0 >= bound, "{open:?}");
    }
}
