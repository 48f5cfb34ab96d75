// A valid crane: the generated code compiles in a user crate that depends
// on crane-runtime, and its functions can be called.
use crane_macros::crane_model;
use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, MinimalMap};

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
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        minimal [xs | theta, len] {
            s = xs;
            L = len;
            x = s + L*sin(theta);
            z = -L*cos(theta);
        }
    }
}

fn main() {
    let crane = Gantry::new();
    // the load hangs 5 m below the trolley at s = 1
    let q = SVector::<f64, 4>::from([1.0, 5.0, 1.0, -5.0]);
    assert!(crane.constraints(&q).norm() < 1e-12);
    assert_eq!(crane.mass_matrix::<f64>()[(2, 2)], 100.0);
    let mu = SVector::<f64, 3>::from([1.0, 0.0, 5.0]);
    assert!((crane.phi(&mu) - q).norm() < 1e-12);
    assert!((crane.constraint_jacobian(&q) * crane.null_space(&mu)).norm() < 1e-12);
}
