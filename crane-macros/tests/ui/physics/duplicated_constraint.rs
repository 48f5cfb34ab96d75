// Mistake: the rope written twice (once scaled): the constraints are
// dependent, `G` loses rank and the rope force is not unique.
use crane_macros::crane_model;

crane_model! {
    /// Gantry crane with two trolleys and the rope stated twice.
    pub struct Gantry {
        params { m_c = 10.0, m_l = 100.0, J = 0.1, r = 0.1, g = 9.81 }
        robot  [s, L, h]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_c*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_c*dot(h)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
            again: (x - s)^2 + z^2 - L^2,
        }
    }
}

fn main() {}
