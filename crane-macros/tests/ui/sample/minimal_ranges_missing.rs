// Mistake: the crane has a minimal map but `sample` gives no ranges for the
// minimal coordinates, so the self-test could not check the map.
use crane_macros::crane_model;

crane_model! {
    /// Overhead crane: cart s, winch beta (rope length r beta), load (xd, zd), z down.
    pub struct Overhead {
        params { mt = 10.0, J = 0.1, r = 0.1, m = 100.0, g = 9.81 }
        robot  [s, beta]
        load   [xd, zd]
        inputs [uF, uM]
        kinetic = 0.5*mt*dot(s)^2 + 0.5*J*dot(beta)^2 + 0.5*m*(dot(xd)^2 + dot(zd)^2);
        forces { s: uF, beta: uM, zd: m*g }
        constraints {
            rope: 0.5*((xd - s)^2 + zd^2 - (r*beta)^2),
        }
        minimal [c | a, b] {
            s = c;
            beta = sqrt((a - c)^2 + b^2)/r;
            xd = a;
            zd = b;
        }
        sample { s = -5.0 .. 5.0, beta = 10.0 .. 100.0, xd = -5.0 .. 5.0, zd = 1.0 .. 10.0 }
    }
}

fn main() {}
