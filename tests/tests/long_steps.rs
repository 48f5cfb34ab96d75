//! The reduced formulation is exact at any step: its system is algebraic at
//! each step time, so a step of any length gives the inputs of a step of
//! 1 ms at the times both have. Its equations have other roots too (the
//! mirror configurations: a rope of negative length, a pushing rope, a
//! pulley above the boom), and a long step's prediction may land on one of
//! them (navy-planar at dt = 0.5 s once ended on u1 = +133.2 N m, N1 = -1332
//! N, for -43.3 N m and +433.5 N); such a step is followed along the path
//! by shorter steps that stay on its branch (`Stepper::continue_to`), and
//! only the step times are reported.
//!
//! The check, on every built-in crane with the reduced system, on its
//! default move: at dt in {0.25, 0.5, 0.8, 1, 2, 4, 10 s, the whole move}
//! (those that divide the move), every input at every step time equals the
//! run at dt = 0.001 s to 1e-9 of that input's peak. Both runs solve the
//! same equations at the same time to Newton's tolerance (an update below
//! 1e-10 relative, its error of the order of its square) and round-off
//! (the largest relative error against the analytical references,
//! `dummy_derivatives.rs`, is below 1e-13; measured here at most 9.3e-12,
//! tower-crane at dt = 0.5 s): 1e-9 is a hundred times that, and a billion
//! times less than a change of branch (the mirror's inputs are off by 0.1
//! to 10 of their peak: navy-planar's u1 by 4.07 at dt = 0.5 s).

use crane_models::registry::{BuiltIn, Registry, Visit};
use crane_models::study::Formulation;
use crane_models::{Case, Crane};
use crane_runtime::{Options, Solution};

/// The long steps tried, with the whole move appended per crane.
const LONG_STEPS: [f64; 7] = [0.25, 0.5, 0.8, 1.0, 2.0, 4.0, 10.0];

/// The fine step the long ones are compared with.
const FINE: f64 = 0.001;

/// Per long step: its size, the largest difference of an input at a common
/// step time relative to that input's peak in the fine run, where, and how
/// many steps the long run took by continuation.
struct LongSteps;

impl Visit for LongSteps {
    type Output = Option<Vec<(f64, f64, f64, usize)>>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        crane_runtime::dummy_derivative::system_size::<C::Model, N, M, A>().ok()?;
        let case = Case::<C, N, M, A>::maneuver().expect("the default move");
        let start = case.start().expect("the default start");
        let (t0, tf) = (case.t0(), case.tf());
        let run = |dt: f64| -> Solution<N, M, A> {
            let options = Options::new(dt, tf).expect("a step");
            Formulation::DummyDerivative
                .simulate(&case, &start, &options, &mut |_, _| {})
                .unwrap_or_else(|e| panic!("{} at dt = {dt}: {e}", C::NAME))
        };
        let fine = run(FINE);
        let peaks: [f64; A] = std::array::from_fn(|k| fine.states.iter().map(|s| s.u[k].abs()).fold(0.0, f64::max));
        let span = tf - t0;
        let steps = LONG_STEPS.iter().copied().filter(|&dt| dt < span).chain([span]);
        // only the steps that divide the move (the run ends on a step)
        let steps = steps.filter(|&dt| ((span / dt).round() * dt - span).abs() < 1e-9 * span);
        let rows = steps
            .map(|dt| {
                let long = run(dt);
                let mut worst = (0.0f64, t0);
                for state in &long.states[1..] {
                    let at = fine.state_near(state.t).expect("a fine step near every long one");
                    assert!(
                        (at.t - state.t).abs() < 1e-9,
                        "{} at dt = {dt}: no fine step at {}",
                        C::NAME,
                        state.t
                    );
                    for k in 0..A {
                        let difference = (state.u[k] - at.u[k]).abs() / peaks[k];
                        if !(difference <= worst.0) {
                            worst = (difference, state.t);
                        }
                    }
                }
                (dt, worst.0, worst.1, long.continued_steps)
            })
            .collect();
        Some(rows)
    }
}

#[test]
fn long_steps_give_the_inputs_of_short_ones_at_their_times() {
    let mut checked = 0;
    let mut continued = 0;
    for entry in BuiltIn.entries() {
        let Some(rows) = BuiltIn.visit(entry.name, LongSteps).expect("a built-in") else {
            continue;
        };
        checked += 1;
        for (dt, worst, at, steps) in rows {
            println!(
                "{} dt = {dt}: largest difference {worst:.2e} of the peak at t = {at} ({steps} steps continued)",
                entry.name
            );
            continued += steps;
            assert!(
                worst <= 1e-9,
                "{} at dt = {dt}: an input differs from dt = {FINE} by {worst:e} of its peak at t = {at}",
                entry.name
            );
        }
    }
    // every built-in but coupled-trolley, which has internal dynamics
    assert!(checked >= 8, "{checked} cranes checked");
    // the check must exercise the continuation it guards
    assert!(
        continued > 0,
        "no long step left its branch: the test no longer tests it"
    );
}
