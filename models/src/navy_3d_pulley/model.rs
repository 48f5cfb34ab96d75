//! The three-dimensional US Navy crane with nonzero pulley mass, in
//! redundant coordinates (paper, sect. 6.2, eqs. 89-96, with docs/errata.md).
//!
//! `n = 12` coordinates `q = [L1, L2, L3, L0, x0, y0, x3, y3 | x, y, z, z0]`
//! (eqs. 89-90), `m = 5` constraints (eq. 93), `a = 4` inputs: the torques
//! `u1`, `u2`, `u3` of the three winches and the slewing torque `u4` about
//! the vertical `Z`-axis; `f = 7` degrees of freedom. As for the planar crane
//! with pulley mass (sect. 5.2) the pulley's height `z0` is the fourth flat
//! output, so `m0` sits in `M1` (rows `x0`, `y0`) and in `M2` (row `z0`).
//!
//! Geometry (sect. 6.2 and docs/errata.md, "Implicit parameters"): the boom stands on
//! the `Z`-axis at the origin and makes the angle `alpha` with the vertical;
//! the point `P = (x3, y3, z3)` at distance `k + l` from the origin, where
//! winch 3 sits, moves on the circle `x3^2 + y3^2 = r^2` at the fixed height
//! ```text
//! r = (k + l) sin(alpha),    z3 = (k + l) cos(alpha).
//! ```
//! Winch 1 sits at `A = beta1 P` (`beta1 = 1/2`), winch 2 at `S = beta2 P`
//! (`beta2 = 3/2`, i.e. `|PS| = s = 5 m` beyond `P`). Ropes `L1` (from `A`)
//! and `L2` (from `S`) hold the main pulley `(x0, y0, z0)` of mass `m0`;
//! rope `L3` runs from `P` over the pulley (`L0 = |P B|`) to the load
//! `(x, y, z)` (`L3 - L0 = |B C|`). The boom's slewing inertia enters as
//! `1/2 M (x3'^2 + y3'^2)`, `M = J_b / r^2 = 6.4 kg` (as in sect. 6.1), and
//! the slewing torque through `F_x = -y3/r^2 u4`, `F_y = x3/r^2 u4` (eq. 79).
//!
//! Corrections used (docs/errata.md): the load entries of `M2` (eq. 92) are `m_l`,
//! not `m`; `B1^T` and `f1` (eq. 94) have 8 rows, the slewing column is
//! `-y3/r^2`, `x3/r^2`, and `f2 = [0, 0, -m_l g, -m0 g]`. `crane_model!`
//! derives `G` (eqs. 95-96), `M`, `f` and `B^T` from the declarations below.

use crane_macros::crane_model;

crane_model! {
    /// Three-dimensional US Navy crane with pulley mass (paper, sect. 6.2).
    ///
    /// Three winches (radii `r1..r3`, inertias `J1..J3`, torques `u1..u3`) at
    /// `A = beta1 P`, `S = beta2 P` and `P` on the boom, and the slewing
    /// torque `u4` turning the crane (inertia `J_b` about `Z`), `P` on its
    /// circle of radius `r = (k + l) sin(alpha)` at height
    /// `z3 = (k + l) cos(alpha)`. Coordinates eqs. (89)-(90), kinetic energy
    /// (91)-(92), constraints (93), forces (94), all with docs/errata.md.
    pub struct Navy3dPulley {
        params {
            /// Load mass `m_l`, kg (sect. 6.2.1).
            m_l: positive = 100.0,
            /// Mass `m0` of the main pulley, kg (sect. 6.2.1).
            m0: positive = 20.0,
            /// Moment of inertia `J_b` of the crane about the `Z`-axis, kg m^2.
            /// The paper gives `M = J_b / r^2 = 6.4 kg` (sect. 6.2.1) with
            /// `r^2 = 75 m^2`, so `J_b = 480 kg m^2`.
            J_b: positive = 480.0,
            /// Inertia of winch 1 (rope `L1`, at `A`), kg m^2 (sect. 6.2.1).
            J1: positive = 0.1,
            /// Inertia of winch 2 (rope `L2`, at `S`), kg m^2 (sect. 6.2.1).
            J2: positive = 0.1,
            /// Inertia of winch 3 (rope `L3`, at `P`), kg m^2 (sect. 6.2.1).
            J3: positive = 0.1,
            /// Radius of winch 1, m (sect. 6.2.1).
            r1: positive = 0.1,
            /// Radius of winch 2, m (sect. 6.2.1).
            r2: positive = 0.1,
            /// Radius of winch 3, m (sect. 6.2.1).
            r3: positive = 0.1,
            /// Boom angle to the vertical (sect. 6.2.1).
            alpha = PI / 3.0,
            /// Boom part `k` (`|OP| = k + l`), m (sect. 6.2.1).
            k: positive = 5.0,
            /// Boom part `l` (`|OP| = k + l`), m (sect. 6.2.1).
            l: positive = 5.0,
            /// Position of winch 1 on the boom, `A = beta1 P` (sect. 6.2).
            beta1 = 0.5,
            /// Position of winch 2 on the boom, `S = beta2 P` (sect. 6.2,
            /// docs/errata.md: `beta2 = 3/2`, so `|PS| = s = 5 m`).
            beta2 = 1.5,
            /// Gravity, m/s^2 (docs/errata.md: implicit, 9.81 throughout).
            g: positive = 9.81,
        }
        robot  [L1, L2, L3, L0, x0, y0, x3, y3]   // p, eq. (89)
        load   [x, y, z, z0]                      // x, eq. (90)
        inputs [u1, u2, u3, u4]
        // eqs. (91)-(92) with docs/errata.md (m_l for the load), M = J_b / r^2
        kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*J3/r3^2*dot(L3)^2
                + 0.5*m0*(dot(x0)^2 + dot(y0)^2 + dot(z0)^2)
                + 0.5*J_b/((k + l)*sin(alpha))^2*(dot(x3)^2 + dot(y3)^2)
                + 0.5*m_l*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        // eq. (94) with docs/errata.md: slewing column -y3/r^2, x3/r^2; f2 = [0, 0, -m_l g, -m0 g]
        forces {
            L1: u1/r1,
            L2: u2/r2,
            L3: u3/r3,
            x3: -y3/((k + l)*sin(alpha))^2*u4,
            y3: x3/((k + l)*sin(alpha))^2*u4,
            z: -m_l*g,
            z0: -m0*g,
        }
        // eq. (93), in the paper's order
        constraints {
            // P on its circle of radius r
            slew: 0.5*(x3^2 + y3^2 - ((k + l)*sin(alpha))^2),
            // rope L1 from A = beta1 P to the pulley
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 - beta1*x3)^2 + (y0 - beta1*y3)^2
                        + (z0 - beta1*(k + l)*cos(alpha))^2 - L1^2),
            // rope L2 from S = beta2 P to the pulley
            #[rope(N2 = L2)]
            rope2: 0.5*((x0 - beta2*x3)^2 + (y0 - beta2*y3)^2
                        + (z0 - beta2*(k + l)*cos(alpha))^2 - L2^2),
            // the part L0 of rope L3 from P to the pulley
            rope0: 0.5*((x0 - x3)^2 + (y0 - y3)^2 + (z0 - (k + l)*cos(alpha))^2 - L0^2),
            // the load rope L3 - L0 from the pulley to the load
            #[rope(N3 = L3 - L0)]
            hoist: 0.5*((x - x0)^2 + (y - y0)^2 + (z - z0)^2 - (L3 - L0)^2),
        }
    }
}
