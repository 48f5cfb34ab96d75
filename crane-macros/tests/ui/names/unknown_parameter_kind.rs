// Mistake: `heavy` is not a parameter kind; the only one is `positive`.
use crane_macros::crane_model;

crane_model! {
    /// Planar gantry crane: trolley at s, rope of length L, load at (x, z).
    pub struct Gantry {
        params { mt: heavy = 10.0, m: positive = 100.0, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*mt*dot(s)^2 + 0.5*dot(L)^2 + 0.5*m*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2, z: -m*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

fn main() {}
