//! Stable inversion of a crane with unstable internal dynamics, checked
//! against a closed form: the coupled trolley on a level move.
//!
//! With the load at a constant height `z = -h` the rope's multiplier is
//! constant, `lambda = m g / h` (row `z`: `m z'' = -m g - lambda z`), and the
//! load's row `x`, `c s'' + m x'' = -lambda (x - s)`, is a linear ODE for
//! the trolley's offset `w = s - x`:
//!
//! `c w'' - lambda w = -(m + c) x''`, eigenvalues `+-k`, `k = sqrt(lambda / c)`
//!
//! (9.9045 1/s for the default crane with the load 5 m below). Its only
//! solution bounded on the whole time axis is the two-sided Green's
//! function's,
//!
//! `w(t) = (m + c) / (2 c k) * integral exp(-k |t - tau|) x''(tau) dtau`,
//!
//! evaluated here by Gauss-Legendre quadrature of the poly9 path's `x''`
//! written out (eqs. 41-45), independently of the code under test. Before
//! the move the trolley already moves (pre-actuation, `w ~ exp(k t)`), after
//! it settles (`w ~ exp(-k t)`).

use crane_models::Case;
use crane_models::coupled_trolley::{DefaultCase, Description};
use crane_runtime::internal::internal_dynamics;
use crane_runtime::stable_inversion::{StableInversion, StableInversionOptions, horizons, stable_inversion};
use crane_runtime::{Trajectory, init};
use crane_tests::kit;
use nalgebra::vector;

/// The level move: 4 m in 5 s at 5 m below the rail.
const TRAVEL: f64 = 4.0;
const DURATION: f64 = 5.0;
const HEIGHT: f64 = 5.0;

/// The default crane's parameters (`mt`, `m`, `c`, `g`).
const M: f64 = 100.0;
const C: f64 = 2.0;
const G: f64 = 9.81;

/// The poly9 profile's second derivative, `x''(t)`, written out.
fn x_accel(t: f64) -> f64 {
    if !(0.0..=DURATION).contains(&t) {
        return 0.0;
    }
    let s = t / DURATION;
    let p2 = 2520.0 * s.powi(3) - 12600.0 * s.powi(4) + 22680.0 * s.powi(5) - 17640.0 * s.powi(6) + 5040.0 * s.powi(7);
    TRAVEL * p2 / (DURATION * DURATION)
}

/// `integral_a^b f` by 5-point Gauss-Legendre on `panels` equal panels.
fn gauss(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    const X: [f64; 5] = [
        0.0,
        -0.538_469_310_105_683_1,
        0.538_469_310_105_683_1,
        -0.906_179_845_938_664,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.568_888_888_888_888_9,
        0.478_628_670_499_366_5,
        0.478_628_670_499_366_5,
        0.236_926_885_056_189_1,
        0.236_926_885_056_189_1,
    ];
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|i| {
            let mid = a + (i as f64 + 0.5) * h;
            X.iter().zip(W).map(|(x, w)| w * f(mid + 0.5 * h * x)).sum::<f64>() * 0.5 * h
        })
        .sum()
}

/// The bounded offset `w(t) = s - x` of the closed form (quadrature split
/// at the kink `tau = t`; 2000 panels on the move: error far below 1e-12 m).
fn bounded_offset(t: f64) -> f64 {
    let k = (M * G / HEIGHT / C).sqrt();
    let kernel = |tau: f64| (-k * (t - tau).abs()).exp() * x_accel(tau);
    let split = t.clamp(0.0, DURATION);
    let panels = |len: f64| ((len / DURATION * 2000.0).ceil() as usize).max(1);
    let integral = gauss(kernel, 0.0, split, panels(split)) + gauss(kernel, split, DURATION, panels(DURATION - split));
    (M + C) / (2.0 * C * k) * integral
}

fn level_move() -> Case<Description, 4, 1, 2> {
    let default = DefaultCase::maneuver().unwrap();
    let path = kit::stand_in_path(vector![0.0, -HEIGHT], vector![TRAVEL, -HEIGHT], DURATION);
    Case::from_parts(*default.model(), path, vec![0.0, HEIGHT], DURATION)
}

/// The largest `|w - w_exact|` over the nodes in [-1, 6] s and `max |w|`,
/// with the fitted pre-actuation rate on [-1, -0.3] s.
fn offset_error(dt: f64) -> (f64, f64, f64) {
    let inversion = invert(&level_move(), dt);
    let states = &inversion.solution.states;
    assert!(states[0].t <= -1.0 && states.last().unwrap().t >= 6.0);
    let (mut error, mut size) = (0.0f64, 0.0f64);
    for state in states.iter().filter(|s| (-1.0..=6.0).contains(&s.t)) {
        let w = state.q[0] - state.q[2];
        error = error.max((w - bounded_offset(state.t)).abs());
        size = size.max(w.abs());
    }
    let at = |t: f64| {
        let state = inversion.solution.state_near(t).unwrap();
        assert!((state.t - t).abs() < 1e-9);
        state.q[0] - state.q[2]
    };
    let rate = (at(-0.3) / at(-1.0)).ln() / 0.7;
    (error, size, rate)
}

#[test]
fn the_level_move_matches_the_two_sided_greens_function() {
    // the rest state's eigenvalues: +-sqrt(m g / (h c))
    let case = level_move();
    let start = case.start().unwrap();
    let diagnosis = internal_dynamics(case.model(), &start).unwrap();
    let k = (M * G / HEIGHT / C).sqrt();
    for (re, im) in &diagnosis.eigenvalues {
        assert!(
            (re.abs() - k).abs() < 1e-9 * k && im.abs() < 1e-9,
            "{:?}",
            diagnosis.eigenvalues
        );
    }
    let dts = [0.01, 0.005];
    let results: Vec<(f64, f64, f64)> = dts.iter().map(|&dt| offset_error(dt)).collect();
    for ((error, size, rate), dt) in results.iter().zip(dts) {
        eprintln!("dt = {dt}: |w - w_exact| = {error:.3e} of max |w| = {size:.3e}; rate {rate:.6}");
    }
    // central differences: second order
    let order = (results[0].0 / results[1].0).log2();
    assert!((1.9..2.1).contains(&order), "order {order}: {results:?}");
    // the discretisation's error at dt = 0.005: measured 3.3e-7 of the
    // offset (the forcing x'' is smooth on the scale 1/k)
    assert!(results[1].0 < 1e-6 * results[1].1, "{results:?}");
    // pre-actuation decays at the unstable eigenvalue (the discrete rate
    // differs from k by (k dt)^2 / 24 = 1e-4 relative at dt = 0.005)
    let rate = results[1].2;
    assert!((rate - k).abs() < 1e-3 * k, "rate {rate} against {k}");
}

/// The stable inversion of the coupled trolley's default move (from
/// `(0, -5)` to `(4, -3)` in 5 s, the load lifted as it travels: the
/// multiplier, and with it the internal dynamics, change along the move).
fn default_move(dt: f64) -> StableInversion<4, 1, 2> {
    invert(&DefaultCase::maneuver().unwrap(), dt)
}

/// The stable inversion of `case`'s move (5 s from rest to rest) through
/// the runtime's API: the horizons from the internal dynamics at the two
/// rest states (the end's found from the path's end point, the trolley
/// above the load), then the boundary value problem on nodes `dt` apart.
fn invert(case: &Case<Description, 4, 1, 2>, dt: f64) -> StableInversion<4, 1, 2> {
    let start = case.start().unwrap();
    let end_point = case.path().derivative(DURATION, 0);
    let end = init::static_equilibrium(case.model(), case.path(), DURATION, &[end_point[0], -end_point[1]]).unwrap();
    let (t_pre, t_post) = horizons(
        &internal_dynamics(case.model(), &start).unwrap(),
        &internal_dynamics(case.model(), &end).unwrap(),
    )
    .unwrap();
    let options = StableInversionOptions {
        dt,
        t0: 0.0,
        tf: DURATION,
        t_pre,
        t_post,
    };
    stable_inversion(case.model(), case.path(), &start, &options).unwrap()
}

/// The nonlinear default move: bounded inputs (the causal inverse reaches
/// 1.4e18 N at dt = 0.01), second order in dt (the differences of successive halvings
/// at the common nodes fall by 4), pre-actuation at the rest state's
/// unstable eigenvalue 9.9045 1/s.
#[test]
fn the_default_move_has_bounded_inputs_of_second_order() {
    let runs: Vec<_> = [0.02, 0.01, 0.005].iter().map(|&dt| default_move(dt)).collect();
    for run in &runs {
        let peak = run.solution.states.iter().map(|s| s.u[0].abs()).fold(0.0, f64::max);
        eprintln!(
            "dt = {}: {} nodes from {} s, peak |u1| = {peak:.3} N, {} Newton iterations, boundary {:.2e}",
            run.solution.dt,
            run.solution.states.len(),
            run.solution.states[0].t,
            run.iterations,
            run.boundary_residual
        );
        assert!(peak < 200.0, "peak |u1| = {peak}");
        assert!(run.solution.states[0].t <= -1.0 && run.solution.states.last().unwrap().t >= 6.0);
    }
    // |u(dt) - u(dt/2)| at the coarse nodes both grids hold (their
    // horizons are rounded up to whole steps)
    let difference = |coarse: &StableInversion<4, 1, 2>, fine: &StableInversion<4, 1, 2>| {
        let (first, last) = (fine.solution.states[0].t, fine.solution.states.last().unwrap().t);
        coarse
            .solution
            .states
            .iter()
            .filter(|s| (first..=last).contains(&s.t))
            .map(|s| {
                let other = fine.solution.state_near(s.t).unwrap();
                assert!((other.t - s.t).abs() < 1e-9);
                (s.u - other.u).amax()
            })
            .fold(0.0, f64::max)
    };
    let (d1, d2) = (difference(&runs[0], &runs[1]), difference(&runs[1], &runs[2]));
    let order = (d1 / d2).log2();
    eprintln!("differences {d1:.3e}, {d2:.3e}: order {order:.3}");
    assert!(order >= 1.8, "order {order}");
    let fine = &runs[2].solution;
    let at = |t: f64| {
        let state = fine.state_near(t).unwrap();
        state.q[0] - state.q[2]
    };
    let rate = (at(-0.3) / at(-1.0)).ln() / 0.7;
    eprintln!("pre-actuation rate {rate:.6} 1/s");
    assert!((rate - 9.9045).abs() < 1e-3 * 9.9045, "rate {rate}");
}

/// Faster and slower moves of the coupled trolley (3 s and 2 s instead of
/// 5 s): Newton converges from the quasi-static motion (a 3 s move once
/// ended at a residual of 7e-15, its round-off, with every full step
/// refused by the line search) and the inputs stay bounded; a faster move
/// needs larger ones.
#[test]
fn faster_moves_converge_with_larger_bounded_inputs() {
    let default = DefaultCase::maneuver().unwrap();
    let mut peaks = Vec::new();
    for duration in [5.0, 3.0, 2.0] {
        let path = kit::stand_in_path(vector![0.0, -5.0], vector![4.0, -3.0], duration);
        let case = Case::<Description, 4, 1, 2>::from_parts(*default.model(), path, vec![0.0, 5.0], duration);
        let start = case.start().unwrap();
        let options = crane_runtime::Options::new(0.01, duration).unwrap();
        let inversion = case
            .simulate_stable_inversion(&start, &options)
            .unwrap_or_else(|e| panic!("{duration} s: {e}"));
        let peak = inversion
            .solution
            .states
            .iter()
            .map(|s| s.u[0].abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{duration} s: peak |u1| = {peak:.3} N, {} iterations",
            inversion.iterations
        );
        assert!(
            inversion.iterations <= 10,
            "{duration} s: {} iterations",
            inversion.iterations
        );
        peaks.push(peak);
    }
    // measured 154.6, 349.7 and 825.0 N
    assert!(
        peaks[0] < peaks[1] && peaks[1] < peaks[2] && peaks[2] < 1e3,
        "{peaks:?}"
    );
}

/// A level move longer than the rope, 8 m across at 5 m below the rail,
/// through `Case::simulate_stable_inversion` (what `crane run` and the FMU
/// call): the rest state at the move's end is continued along the path.
/// Solved at once from the start's coordinates it landed on the rope's
/// mirror branch (length -5) and the move was refused ("the start gives
/// rope `N` the length -5"). The offset `w` is the closed form's scaled by
/// the travel (its equation is linear in `x''`), to the bound the 4 m move
/// meets at dt = 0.005 (1e-6 of the offset: the relative error does not
/// change with the scale).
#[test]
fn a_move_longer_than_the_rope_ends_on_the_ropes_branch() {
    let travel = 8.0;
    let default = DefaultCase::maneuver().unwrap();
    let path = kit::stand_in_path(vector![0.0, -HEIGHT], vector![travel, -HEIGHT], DURATION);
    let case = Case::<Description, 4, 1, 2>::from_parts(*default.model(), path, vec![0.0, HEIGHT], DURATION);
    let start = case.start().unwrap();
    let options = crane_runtime::Options::new(0.005, DURATION).unwrap();
    let inversion = case.simulate_stable_inversion(&start, &options).unwrap();
    let states = &inversion.solution.states;
    assert!(states.iter().all(|s| s.q[1] > 0.0), "a rope length at or below zero");
    let last = states.last().unwrap();
    assert!(
        (last.q[0] - travel).abs() < 1e-6 && (last.q[1] - HEIGHT).abs() < 1e-6,
        "{:?}",
        last.q
    );
    let (mut error, mut size) = (0.0f64, 0.0f64);
    for state in states.iter().filter(|s| (-1.0..=6.0).contains(&s.t)) {
        let w = state.q[0] - state.q[2];
        error = error.max((w - travel / TRAVEL * bounded_offset(state.t)).abs());
        size = size.max(w.abs());
    }
    eprintln!("|w - w_exact| = {error:.3e} of max |w| = {size:.3e}");
    assert!(error < 1e-6 * size, "{error} of {size}");
}
