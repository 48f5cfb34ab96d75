//! A simulated 100 Hz control loop computing feedforward torques online.
//!
//! Every 10 ms the controller receives the load target at the next tick
//! (position, velocity, acceleration; here from a planned rest-to-rest path)
//! and asks the stepper for the torques that keep the load exactly on it
//! (backward Euler on eqs. 22a-d, one step per tick, no allocation).
//!
//! Run with `cargo run --release -p crane --example control_loop`.

use std::time::{Duration, Instant};

use crane::prelude::*;
use crane::runtime::redundant::Redundant;

crane_model! {
    /// Planar gantry crane: trolley, hoist winch, load on one rope.
    pub struct Gantry {
        params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    const RATE_HZ: f64 = 100.0;
    let dt = 1.0 / RATE_HZ;
    let crane = Gantry::default();
    // the planner's path: 4 m across, 2 m up, in 5 s
    let path = Poly9::new(0.0, 5.0, SVector::from([0.0, -5.0]), SVector::from([4.0, -3.0]))?;
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0])?;
    let mut stepper = Stepper::new(Redundant::new(&crane, &path), &start, &Options::stepping(dt)?)?;

    println!("   t [s]   trolley u1 [N]   winch u2 [N m]   rope tension [N]");
    let mut slowest = Duration::ZERO;
    for tick in 1..=600 {
        let t = tick as f64 * dt;
        // what the controller receives each tick: gamma, gamma', gamma'' at t
        let target = [path.derivative(t, 0), path.derivative(t, 1), path.derivative(t, 2)];
        let clock = Instant::now();
        stepper.step_to(t, &target)?;
        slowest = slowest.max(clock.elapsed());
        let state = stepper.state();
        if tick % 50 == 0 {
            let tension = state.lambda[0] * state.q[1]; // N = lambda L
            println!("{t:8.2} {:16.2} {:16.2} {:18.2}", state.u[0], state.u[1], tension);
        }
    }
    println!(
        "slowest step: {:.1} us (budget per tick: {:.0} us)",
        slowest.as_secs_f64() * 1e6,
        dt * 1e6
    );
    Ok(())
}
