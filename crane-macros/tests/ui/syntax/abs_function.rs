// Mistake: `abs` in a constraint (not a function of the DSL; a rope's
// length is written with a square root or squared).
use crane_macros::crane_model;

crane_model! {
    /// Planar gantry crane: trolley at s, rope of length L, load at (x, z).
    pub struct Gantry {
        params { m_c = 10.0, m_l = 100.0, J = 0.1, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_c*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: sqrt((x - s)^2 + z^2) - abs(L),
        }
    }
}

fn main() {}
