// Mistake: a `potential` section. The user's code that runs the crane
// compiles against the placeholder the macro leaves, so the declaration's
// error is the only one shown.
use crane_macros::crane_model;
use crane_runtime::nalgebra::vector;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{Options, init, simulate};

crane_model! {
    /// Planar gantry crane: trolley at s, rope of length L, load at (x, z).
    pub struct Gantry {
        params { m_c = 10.0, m_l = 100.0, J = 0.1, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        potential = m_l*g*z;
        kinetic = 0.5*m_c*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

fn main() {
    let crane = Gantry::default();
    let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
    let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0).unwrap()).unwrap();
    println!("{}", run.states.len());
}
