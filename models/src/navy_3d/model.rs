//! The three-dimensional US Navy crane with neglected pulley mass, in
//! redundant coordinates (paper, sect. 6.1, eqs. 68-81, with docs/errata.md).
//!
//! `n = 11` coordinates `q = [L1, L2, L0, x0, y0, z0, x2, y2 | x, y, z]`
//! (eqs. 68-69), `m = 4` constraints (eq. 78), `a = 3` inputs: the torques
//! `u1`, `u2` of the two winches and the slewing torque `u3` about the
//! vertical `Z`-axis; `f = 7` degrees of freedom.
//!
//! Geometry (docs/errata.md, "Implicit parameters"): the boom of length `k + l`
//! stands on the `Z`-axis at the origin `O` and makes the angle `alpha` with
//! the vertical. Its tip `P = (x2, y2, z2)`, where winch 2 hoists the load,
//! moves on the circle `x2^2 + y2^2 = r^2` (eq. 71) at the fixed height
//! `z2`, with
//! ```text
//! r = (k + l) sin(alpha),    z2 = (k + l) cos(alpha).
//! ```
//! Winch 1 sits at `A = beta1 P` on the boom (`beta1 = 1/2`). The crane's
//! rotation is carried by the redundant coordinates `(x2, y2)` of `P`
//! instead of the slewing angle `phi = atan2(y2, x2)`; the boom's kinetic
//! energy `1/2 J_b phi'^2` becomes `1/2 M (x2'^2 + y2'^2)` with
//! `M = J_b / r^2` (eqs. 70-72), a constant coefficient. The slewing torque
//! acts through the forces `F_x = -y2/r^2 u3`, `F_y = x2/r^2 u3` conjugate
//! to `(x2, y2)` (eq. 79), which is the slewing column of `B1^T` (eq. 80
//! with docs/errata.md: `-y2/r^2`, `x2/r^2`, not `-y2/r2`, `y2/r2`).
//!
//! The mass matrix (eq. 74) is singular: the pulley `(x0, y0, z0)` is
//! massless and `L0` carries no inertia. `crane_model!` derives `G` (eq. 81),
//! `M` (eq. 74), `f` and `B^T` (eq. 80 with docs/errata.md: 8 rows each).

use crane_macros::crane_model;

crane_model! {
    /// Three-dimensional US Navy crane with massless main pulley (paper,
    /// sect. 6.1).
    ///
    /// Winch 1 (radius `r1`, inertia `J1`) at `A = beta1 P` on the boom pulls
    /// the main pulley `(x0, y0, z0)` through rope `L1`; winch 2 at the boom
    /// tip `P = (x2, y2, z2)` hoists the load `(x, y, z)` through rope `L2`,
    /// which runs over the pulley: `L0` is its part from `P` to the pulley,
    /// `L2 - L0` the load rope. The slewing torque `u3` turns the crane
    /// (inertia `J_b` about the `Z`-axis) and with it `P` on its circle of
    /// radius `r = (k + l) sin(alpha)` at height `z2 = (k + l) cos(alpha)`.
    pub struct Navy3d {
        params {
            /// Load mass `m_l` in kg (sect. 6.1.1).
            m_l: positive = 100.0,
            /// Moment of inertia `J_b` of the crane without pulley and load about
            /// the `Z`-axis, kg m^2. The paper gives `M = J_b / r^2 = 6.4 kg`
            /// (sect. 6.1.1) with `r^2 = 75 m^2`, so `J_b = 480 kg m^2`.
            J_b: positive = 480.0,
            /// Inertia of winch 1, kg m^2 (sect. 6.1.1).
            J1: positive = 0.1,
            /// Inertia of winch 2, kg m^2 (sect. 6.1.1).
            J2: positive = 0.1,
            /// Radius of winch 1, m (sect. 6.1.1).
            r1: positive = 0.1,
            /// Radius of winch 2, m (sect. 6.1.1).
            r2: positive = 0.1,
            /// Boom angle to the vertical (sect. 6.1.1).
            alpha = PI / 3.0,
            /// Boom part `k` (boom length `k + l`), m (sect. 6.1.1).
            k: positive = 5.0,
            /// Boom part `l` (boom length `k + l`), m (sect. 6.1.1).
            l: positive = 5.0,
            /// Position of winch 1 on the boom, `A = beta1 P` (sect. 6.1).
            beta1 = 0.5,
            /// Gravity, m/s^2 (docs/errata.md: implicit, 9.81 throughout).
            g: positive = 9.81
        }
        robot  [L1, L2, L0, x0, y0, z0, x2, y2]   // p, eq. (68)
        load   [x, y, z]                          // x, eq. (69)
        inputs [u1, u2, u3]
        // eq. (72) with docs/errata.md (the load term includes y'^2), M = J_b / r^2
        kinetic = 0.5*J_b/((k + l)*sin(alpha))^2*(dot(x2)^2 + dot(y2)^2)
                + 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2
                + 0.5*m_l*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        // eq. (80) with docs/errata.md: slewing column -y2/r^2, x2/r^2 (eq. 79)
        forces {
            L1: u1/r1,
            L2: u2/r2,
            x2: -y2/((k + l)*sin(alpha))^2*u3,
            y2: x2/((k + l)*sin(alpha))^2*u3,
            z: -m_l*g,
        }
        // eq. (78), in the paper's order
        constraints {
            // (71): P on its circle of radius r
            slew: 0.5*(x2^2 + y2^2 - ((k + l)*sin(alpha))^2),
            // (76): rope L1 from A = beta1 P to the pulley
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 - beta1*x2)^2 + (y0 - beta1*y2)^2
                        + (z0 - beta1*(k + l)*cos(alpha))^2 - L1^2),
            // (75): the part L0 of rope L2 from P to the pulley
            rope0: 0.5*((x0 - x2)^2 + (y0 - y2)^2 + (z0 - (k + l)*cos(alpha))^2 - L0^2),
            // (77): the load rope L2 - L0 from the pulley to the load
            #[rope(N2 = L2 - L0)]
            hoist: 0.5*((x - x0)^2 + (y - y0)^2 + (z - z0)^2 - (L2 - L0)^2),
        }
    }
}
