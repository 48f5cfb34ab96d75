//! The planar US Navy crane with neglected pulley mass, in redundant
//! coordinates (paper, sect. 5.1.1, eqs. 25-35).
//!
//! `n = 7` coordinates `q = [L1, L2, L0, x0, z0 | x, z]` (eqs. 25-26),
//! `m = 3` rope constraints (eq. 33), `a = 2` winch torques; the mass matrix
//! (eq. 29) is singular because the pulley is massless and `L0` carries no
//! inertia. `crane_model!` derives `G` (eq. 35), `M`, `f` and `B^T` (eq. 34).
//!
//! The `minimal` block is the map to the minimal coordinates of sect. 5.1.2,
//! `mu = [beta, gamma | theta, L]` (eqs. 36, 39), from the law of sines in
//! the triangle PAB: `phi_p` and `phi_x` are eqs. (37) and (38), and
//! `D2 phi_x` is eq. (40). Here `d = l sin(gamma - beta)/sin(gamma)` is `L0`,
//! the distance from the boom tip P to the pulley (not Appendix A's `d`, see
//! docs/errata.md, eq. 105), and `L = L2 - L0` is the length of the load rope.

use crane_macros::crane_model;

crane_model! {
    /// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
    ///
    /// Winch 1 (radius `r1`, inertia `J1`) at A pulls the main pulley
    /// `(x0, z0)` through rope `L1`; winch 2 at the boom tip P hoists the load
    /// `(x, z)` through rope `L2`, which runs over the pulley: `L0` is its part
    /// from P to the pulley (eqs. 25-35).
    pub struct NavyPlanar {
        params { m_l: positive = 100.0, J1: positive = 0.1, J2: positive = 0.1, r1: positive = 0.1, r2: positive = 0.1,
                 alpha = PI / 3.0, l: positive = 10.0, g: positive = 9.81 }
        robot  [L1, L2, L0, x0, z0]      // p: the first n-a coordinates
        load   [x, z]                    // x: outputs, prescribed by gamma(t)
        inputs [u1, u2]
        kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }
        constraints {
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 + l*sin(alpha))^2 + (z0 + l*cos(alpha))^2 - L1^2),
            rope0: 0.5*(x0^2 + z0^2 - L0^2),
            #[rope(N2 = L2 - L0)]
            hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L2 - L0)^2),
        }
        minimal [beta, gamma | theta, L] {           // mu1 | mu2 (eq. 39)
            let d = l*sin(gamma - beta)/sin(gamma);   // = L0, pulley to boom tip P
            L1 = l*sin(beta)/sin(gamma);  L2 = d + L;  L0 = d;     // eq. (37)
            x0 = -d*sin(alpha - beta);    z0 = -d*cos(alpha - beta);
            x  = x0 + L*sin(theta);       z  = z0 - L*cos(theta);  // eq. (38)
        }
        // Where `cargo test` checks the generated derivatives (a generated
        // self-test): around the paper's maneuver, all lengths positive.
        sample {
            L1 = 1.0 .. 20.0, L2 = 1.0 .. 20.0, L0 = 1.0 .. 20.0,
            x0 = -15.0 .. 15.0, z0 = -15.0 .. 0.0, x = -15.0 .. 15.0, z = -20.0 .. 0.0,
            beta = 0.2 .. 0.9, gamma = 1.2 .. 2.2, theta = -0.5 .. 0.5, L = 2.0 .. 10.0,
        }
    }
}
