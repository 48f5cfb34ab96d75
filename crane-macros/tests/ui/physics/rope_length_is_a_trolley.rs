// Mistake: the trolley's position declared as the rope's length. The
// constraint depends on `s`, but grows with it where the load is behind
// the trolley and shrinks where it is ahead: `-lambda dg/ds` is the
// rope's horizontal pull, not its tension.
use crane_macros::crane_model;

crane_model! {
    /// Gantry crane with the rope's length mistaken.
    pub struct Gantry {
        params { m_c = 10.0, m_l = 100.0, J = 0.1, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_c*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = s)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

fn main() {}
