//! Replay: drive a crane's forward dynamics ([`crate::forward`]) with the
//! inputs an inverse run computed, from the same start, on a finer step and
//! beyond the move's end with the inputs held, and measure how well the load
//! follows its path and how much it sways afterwards. The plant may differ
//! from the model the inputs were computed for (a heavier load, another
//! geometry): that is the question "what if my load is heavier".

use std::cell::Cell;

use nalgebra::SVector;

use crate::driver::run;
use crate::error::Error;
use crate::forward::{Forward, Inputs};
use crate::model::CraneModel;
use crate::newton::NewtonOptions;
use crate::options::{Options, step_count};
use crate::scheme::Scheme;
use crate::solution::Solution;
use crate::stepper::{StepReport, Stepper};
use crate::trajectory::Trajectory;

/// Most points of the interpolating polynomial (degree 5).
const MAX_POINTS: usize = 6;

/// The inputs of an inverse run between its steps: the Lagrange polynomial
/// through the `points` steps nearest to `t` (degree `points - 1`, error
/// `O(dt^points)` for smooth inputs), the last value held after the run.
#[derive(Debug, Clone, Copy)]
pub struct InterpolatedInputs<'a, const N: usize, const M: usize, const A: usize> {
    run: &'a Solution<N, M, A>,
    points: usize,
}

impl<'a, const N: usize, const M: usize, const A: usize> InterpolatedInputs<'a, N, M, A> {
    /// Interpolation of `run`'s inputs through `points` (2..=6, clamped) steps.
    pub fn new(run: &'a Solution<N, M, A>, points: usize) -> Self {
        Self {
            run,
            points: points.clamp(2, MAX_POINTS).min(run.states.len().max(1)),
        }
    }
}

impl<const N: usize, const M: usize, const A: usize> InterpolatedInputs<'_, N, M, A> {
    /// `field` of the run's states interpolated at `t` (held outside the run).
    fn interpolate<const K: usize>(
        &self,
        t: f64,
        field: impl Fn(&crate::solution::State<N, M, A>) -> SVector<f64, K>,
    ) -> SVector<f64, K> {
        let states = &self.run.states;
        let (first, last) = (&states[0], &states[states.len() - 1]);
        if t >= last.t {
            return field(last);
        }
        if t <= first.t || self.points < 2 {
            return field(first);
        }
        let dt = self.run.dt;
        let position = (t - first.t) / dt;
        // the window of `points` steps around t, inside the run
        let lowest = (position - 0.5 * (self.points as f64 - 1.0)).round().max(0.0) as usize;
        let start = lowest.min(states.len() - self.points);
        let mut value = SVector::<f64, K>::zeros();
        for j in 0..self.points {
            let tj = states[start + j].t;
            let mut weight = 1.0;
            for m in 0..self.points {
                if m != j {
                    let tm = states[start + m].t;
                    weight *= (t - tm) / (tj - tm);
                }
            }
            value += field(&states[start + j]) * weight;
        }
        value
    }
}

impl<const N: usize, const M: usize, const A: usize> Inputs<A> for InterpolatedInputs<'_, N, M, A> {
    fn at(&self, t: f64) -> SVector<f64, A> {
        self.interpolate(t, |s| s.u)
    }
}

/// The longest rope of a crane at one state as a pendulum: its length and
/// the model's parameter `g` (9.81 if it has none; at least 1 m, so that a
/// crane without ropes still gets finite gains and windows).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// The longest rope length, m (1 if shorter or if there is no rope).
    pub length: f64,
    /// Gravity, m/s^2.
    pub g: f64,
}

impl Pendulum {
    /// The longest rope of `model` at `state`.
    pub fn longest<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        model: &Mdl,
        state: &crate::solution::State<N, M, A>,
    ) -> Self {
        let mut lengths = vec![0.0; Mdl::INFO.ropes.len()];
        model.rope_lengths(&state.q, &mut lengths);
        let length = lengths.iter().fold(1.0f64, |m, &l| m.max(l));
        let g = Mdl::INFO
            .parameters
            .iter()
            .zip(model.parameter_values())
            .find(|(n, _)| **n == "g")
            .map_or(9.81, |(_, g)| g);
        Self { length, g }
    }

    /// Angular frequency `sqrt(g / L)`, rad/s.
    pub fn frequency(&self) -> f64 {
        (self.g / self.length).sqrt()
    }

    /// Period `2 pi sqrt(L / g)`, s.
    pub fn period(&self) -> f64 {
        std::f64::consts::TAU * (self.length / self.g).sqrt()
    }
}

/// `|x - gamma(t)|` (infinity norm over the load coordinates) at `state`,
/// with the path `gamma` held at its end value after `tf`.
pub fn load_deviation<Tr: Trajectory<A>, const N: usize, const M: usize, const A: usize>(
    path: &Tr,
    tf: f64,
    state: &crate::solution::State<N, M, A>,
) -> f64 {
    let target = path.derivative(state.t.min(tf), 0);
    (0..A)
        .map(|k| (state.q[N - A + k] - target[k]).abs())
        .fold(0.0, f64::max)
}

/// A PD law on the robot coordinates about the inverse run's `p(t)`,
/// `p'(t)`, added to the computed torques: the generalized force
/// `F = Kp (p_ref - p) + Kd (p_ref' - p')` on the robot coordinates, turned
/// into inputs by least squares through the input matrix,
/// `u_fb = (B B^T)^-1 B F` with `B = (B^T)^T` at the current `q`. Sampled:
/// the step to `t_{n+1}` uses the state and the reference at `t_n` (a digital
/// controller at the forward rate, one step of delay).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feedback<const N: usize> {
    /// Stiffness per coordinate (0 on the load coordinates).
    pub kp: SVector<f64, N>,
    /// Damping per coordinate (0 on the load coordinates).
    pub kd: SVector<f64, N>,
}

impl<const N: usize> Feedback<N> {
    /// Default gains from the model: for each robot coordinate with inertia
    /// `M_ii > 0`, a critically damped second-order loop (`Kp = M_ii w^2`,
    /// `Kd = 2 M_ii w`) at `w = 4 sqrt(g / L)`, four times the frequency of
    /// the longest rope pendulum at the start (`g` the model's parameter of
    /// that name, else 9.81); massless coordinates get no feedback.
    pub fn from_model<Mdl: CraneModel<N, M, A>, const M: usize, const A: usize>(
        model: &Mdl,
        start: &crate::solution::State<N, M, A>,
    ) -> Self {
        let w = 4.0 * Pendulum::longest(model, start).frequency();
        let mass = model.mass_matrix::<f64>();
        let kp = SVector::from_fn(|i, _| if i < N - A { mass[(i, i)].max(0.0) * w * w } else { 0.0 });
        let kd = SVector::from_fn(|i, _| {
            if i < N - A {
                2.0 * mass[(i, i)].max(0.0) * w
            } else {
                0.0
            }
        });
        Self { kp, kd }
    }
}

/// The computed torques plus the sampled [`Feedback`].
struct ClosedLoop<'a, 'm, Mdl, const N: usize, const M: usize, const A: usize> {
    plan: InterpolatedInputs<'a, N, M, A>,
    plant: &'m Mdl,
    feedback: Feedback<N>,
    /// The last accepted state (updated by the replay loop).
    last: &'a Cell<crate::solution::State<N, M, A>>,
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> Inputs<A>
    for ClosedLoop<'_, '_, Mdl, N, M, A>
{
    fn at(&self, t: f64) -> SVector<f64, A> {
        let state = self.last.get();
        let (q_ref, v_ref) = (
            self.plan.interpolate(state.t, |s| s.q),
            self.plan.interpolate(state.t, |s| s.v),
        );
        let force =
            self.feedback.kp.component_mul(&(q_ref - state.q)) + self.feedback.kd.component_mul(&(v_ref - state.v));
        let bt = self.plant.input_matrix(&state.q);
        // (B B^T) u = B F, an a x a system, by Gaussian elimination with
        // partial pivoting on fixed-size arrays (no allocation)
        let mut system = [[0.0; A]; A];
        let mut rhs = [0.0; A];
        for k in 0..A {
            for l in 0..A {
                system[k][l] = (0..N).map(|i| bt[(i, k)] * bt[(i, l)]).sum();
            }
            rhs[k] = (0..N).map(|i| bt[(i, k)] * force[i]).sum();
        }
        for col in 0..A {
            let pivot = (col..A)
                .max_by(|&a, &b| system[a][col].abs().total_cmp(&system[b][col].abs()))
                .unwrap_or(col);
            system.swap(col, pivot);
            rhs.swap(col, pivot);
            let d = system[col][col];
            if d.abs() < 1e-300 {
                continue;
            }
            for row in col + 1..A {
                let f = system[row][col] / d;
                for c in col..A {
                    system[row][c] -= f * system[col][c];
                }
                rhs[row] -= f * rhs[col];
            }
        }
        let mut u_fb = [0.0; A];
        for row in (0..A).rev() {
            let d = system[row][row];
            let sum: f64 = (row + 1..A).map(|c| system[row][c] * u_fb[c]).sum();
            u_fb[row] = if d.abs() < 1e-300 { 0.0 } else { (rhs[row] - sum) / d };
        }
        self.plan.at(t) + SVector::from(u_fb)
    }
}

/// How to replay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplayOptions {
    /// Forward steps per inverse step (the forward step is `dt / refine`).
    pub refine: usize,
    /// Seconds beyond the move's end, with the inputs held at their last
    /// value: the settling window in which the residual sway is measured.
    pub settle: f64,
    /// The forward scheme.
    pub scheme: Scheme,
    /// Newton tolerances of the forward steps.
    pub newton: NewtonOptions,
}

impl ReplayOptions {
    /// A replay on `dt / 4` with a settling window of `settle` seconds, with
    /// `scheme` for the forward steps (BDF-2 is the robust choice: its
    /// quadratic interpolation of the torques does not amplify the start-up
    /// transient of a high-order inverse run, which a quartic does).
    pub fn new(settle: f64, scheme: Scheme) -> Self {
        Self {
            refine: 4,
            settle,
            scheme,
            newton: NewtonOptions::default(),
        }
    }
}

/// What a replay measured.
#[derive(Debug, Clone)]
pub struct Replay<const N: usize, const M: usize, const A: usize> {
    /// The forward run: states, multipliers and rope tensions along the replay.
    pub solution: Solution<N, M, A>,
    /// The largest `|x(t) - gamma(t)|` (infinity norm over the load
    /// coordinates) on `[t0, tf]`.
    pub max_load_deviation: f64,
    /// `|x(tf) - gamma(tf)|`.
    pub deviation_at_tf: f64,
    /// The largest `|x(t) - gamma(tf)|` over the settling window.
    pub residual_sway: f64,
}

/// Replay `inverse` (a run of the inverse problem on `path`) on `plant`:
/// from the inverse run's start, with its inputs interpolated to the
/// forward scheme's order (`order + 1` points), on `inverse.dt /
/// options.refine`, to the run's end plus `options.settle`.
pub fn replay<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    plant: &Mdl,
    path: &Tr,
    inverse: &Solution<N, M, A>,
    options: &ReplayOptions,
) -> Result<Replay<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    replay_with_feedback(plant, path, inverse, options, None)
}

/// [`replay`] with a [`Feedback`] law on top of the computed torques.
pub fn replay_with_feedback<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    plant: &Mdl,
    path: &Tr,
    inverse: &Solution<N, M, A>,
    options: &ReplayOptions,
    feedback: Option<&Feedback<N>>,
) -> Result<Replay<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    // (the interpolation below reads the first and last state)
    let (Some(start), Some(end)) = (inverse.states.first(), inverse.states.last()) else {
        return Err(Error::NothingToReplay);
    };
    let refine = options.refine.max(1);
    let dt = inverse.dt / refine as f64;
    let settle_steps = (options.settle.max(0.0) / dt).round();
    let tf = end.t + settle_steps * dt;
    let plan = InterpolatedInputs::new(inverse, options.scheme.order() + 1);
    let forward = Options::new(dt, tf)?
        .with_scheme(options.scheme)
        .with_newton(options.newton)?;
    let steps = step_count(start.t, tf, dt)?;
    let last = Cell::new(*start);
    let gains = feedback.copied().unwrap_or(Feedback {
        kp: SVector::zeros(),
        kd: SVector::zeros(),
    });
    let inputs = ClosedLoop {
        plan,
        plant,
        feedback: gains,
        last: &last,
    };
    check_plant_start(plant, start)?;
    let mut stepper = Stepper::new(Forward::new(plant, inputs), start, &forward)?;
    let mut solution = Solution::with_capacity(Mdl::INFO, dt, options.scheme.name(), steps + 1)?;
    let mut lengths = vec![0.0; Mdl::INFO.ropes.len()];
    solution.push(plant, start, StepReport::default(), &mut lengths);
    let ran = run(&mut stepper, steps, |_, state, report| {
        last.set(*state);
        solution.push(plant, state, *report, &mut lengths);
        Ok(())
    });
    if let Err(error) = ran {
        return Err(rope_before(plant, &solution, error));
    }
    let (mut max_load_deviation, mut deviation_at_tf, mut residual_sway) = (0.0f64, 0.0f64, 0.0f64);
    for state in &solution.states {
        let deviation = load_deviation(path, end.t, state);
        if state.t <= end.t + 1e-9 * dt {
            max_load_deviation = max_load_deviation.max(deviation);
            if (state.t - end.t).abs() <= 0.5 * dt {
                deviation_at_tf = deviation;
            }
        } else {
            residual_sway = residual_sway.max(deviation);
        }
    }
    Ok(Replay {
        solution,
        max_load_deviation,
        deviation_at_tf,
        residual_sway,
    })
}

/// Refuse a replay whose plant cannot start at the inverse run's start:
/// a constraint of the plant violated there (a plant parameter that moves
/// the geometry, a longer boom, moves the start with it), checked as a
/// start is ([`CONSISTENCY_TOLERANCE`](crate::init::CONSISTENCY_TOLERANCE)).
fn check_plant_start<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    plant: &Mdl,
    start: &crate::solution::State<N, M, A>,
) -> Result<(), Error> {
    crate::init::constraints_hold(plant, &start.q).map_err(|error| match error {
        Error::InconsistentStart { equation, residual, .. } => Error::ReplayStartInconsistent { equation, residual },
        other => other,
    })
}

/// The slack rule of a replay: its tensions come from a forward
/// integration whose error is far above the inverse run's round-off (the
/// nominal replay of the paper's move leaves its path by 1e-5 m relative
/// and more), so a rope counts as pushing only below `-1e-6` of the
/// largest tension: the paper's rope N1, which starts at exactly zero
/// tension, dips to -1.2e-5 N (1e-8 of the 1228 N peak) in the first
/// forward steps.
pub const SLACK_TOLERANCE: f64 = 1e-6;

/// A replay's step `error` where a rope of the plant left what the forward
/// dynamics can follow before it, in `solution` (the replay so far): it
/// pushed (below [`SLACK_TOLERANCE`] of the largest tension,
/// [`Error::ReplayRopeSlack`]) or reached zero length (the load reeled
/// into its pulley, [`Error::ReplayRopeLength`]), whichever came first:
/// that, not the step, is what failed. Other errors as they are.
fn rope_before<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    plant: &Mdl,
    solution: &Solution<N, M, A>,
    error: Error,
) -> Error {
    let (Error::NewtonNotConverged { t: failed_at, .. }
    | Error::SingularIterationMatrix { t: failed_at, .. }
    | Error::NonFinite { t: failed_at, .. }) = error
    else {
        return error;
    };
    let ropes = Mdl::INFO.ropes;
    let slack = (0..ropes.len())
        .filter_map(|r| first_slack(solution, r).map(|i| (i, r)))
        .min();
    let mut lengths = [0.0; M];
    let lengths = &mut lengths[..ropes.len().min(M)];
    let short = solution.states.iter().enumerate().find_map(|(i, state)| {
        plant.rope_lengths(&state.q, lengths);
        (0..lengths.len()).find(|&r| !(lengths[r] > 0.0)).map(|r| (i, r))
    });
    let at = |i: usize| solution.states[i].t;
    match (short, slack) {
        (Some((i, r)), slack) if slack.is_none_or(|(j, _)| i <= j) => Error::ReplayRopeLength {
            rope: ropes[r].tension,
            t: at(i),
            failed_at,
        },
        (_, Some((i, r))) => Error::ReplayRopeSlack {
            rope: ropes[r].tension,
            t: at(i),
            failed_at,
        },
        _ => error,
    }
}

/// The first state of a replay's `solution` at which rope `r` pushes:
/// its tension below [`SLACK_TOLERANCE`] of the largest of the replay.
pub fn first_slack<const N: usize, const M: usize, const A: usize>(
    solution: &Solution<N, M, A>,
    r: usize,
) -> Option<usize> {
    let floor = -SLACK_TOLERANCE * solution.largest_tension();
    (0..solution.states.len()).find(|&i| solution.tensions_at(i)[r] < floor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ModelInfo;
    use crate::solution::State;

    /// The interpolation through `k + 1` points reproduces a polynomial of
    /// degree `k` in the inputs exactly, between steps and at them.
    #[test]
    fn interpolation_is_exact_for_polynomials_of_its_degree() {
        const INFO: ModelInfo = ModelInfo {
            name: "T",
            description: "",
            coordinates: &["q"],
            inputs: &["u"],
            constraints: &[],
            ropes: &[],
            parameters: &[],
            positive: &[],
        };
        let u = |t: f64| 1.0 + 2.0 * t - 0.5 * t * t + 0.25 * t.powi(3);
        let states: Vec<State<1, 0, 1>> = (0..=20)
            .map(|i| {
                let t = 0.1 * i as f64;
                State {
                    t,
                    q: SVector::zeros(),
                    v: SVector::zeros(),
                    u: SVector::from([u(t)]),
                    lambda: SVector::zeros(),
                }
            })
            .collect();
        let run = Solution {
            info: INFO,
            dt: 0.1,
            scheme: "bdf3",
            states,
            newton_iterations: vec![0; 21],
            tensions: vec![],
            min_norm_steps: 0,
            held_steps: 0,
            continued_steps: 0,
            crossings: 0,
            first_crossing: None,
            path_order_covered: None,
            shortest_ropes: vec![],
            redundant_start_steps: 0,
            selected_states: Vec::new(),
            reselected_states: Vec::new(),
        };
        let inputs = InterpolatedInputs::new(&run, 4);
        for t in [0.0, 0.03, 0.55, 1.234, 1.999, 2.0] {
            assert!(
                (inputs.at(t)[0] - u(t)).abs() < 1e-12,
                "t = {t}: {} vs {}",
                inputs.at(t)[0],
                u(t)
            );
        }
        assert_eq!(inputs.at(5.0)[0], u(2.0), "held after the run");
    }
}
