//! Embedding a crane in a program: declare it with the macro, sweep a
//! parameter, and compute the feedforward torques of a rest-to-rest move for
//! each value, the way a planning tool would. Depends on `crane` only.

use crane::prelude::*;

crane_model! {
    /// Planar gantry crane: trolley on a rail, hoist winch, load on one rope.
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
    let path = Poly9::new(0.0, 5.0, SVector::from([0.0, -5.0]), SVector::from([4.0, -3.0]))?;
    println!("load mass [kg]   peak trolley force [N]   peak winch torque [N m]   min rope tension [N]");
    for load in [100.0, 200.0, 400.0] {
        let mut crane = Gantry::default();
        crane.set_parameter("m_l", load)?;
        let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0])?;
        let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0)?)?;
        let peak = |k: usize| run.states.iter().map(|s| s.u[k].abs()).fold(0.0, f64::max);
        let min_tension = run.tensions.iter().copied().fold(f64::INFINITY, f64::min);
        if min_tension <= 0.0 {
            return Err(format!("the rope goes slack for m_l = {load} kg").into());
        }
        println!("{load:14.0} {:24.1} {:25.1} {:22.1}", peak(0), peak(1), min_tension);
    }
    Ok(())
}
