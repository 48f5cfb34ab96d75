//! The planar US Navy crane with nonzero pulley mass, in redundant
//! coordinates (paper, sect. 5.2.1, eqs. 49-58).
//!
//! `n = 8` coordinates `q = [L1, L2, L3, L0, x0 | x, z, z0]` (eqs. 49-50),
//! `m = 4` rope constraints (eq. 55), `a = 3` winch torques. The pulley's
//! height `z0` is the third flat output (eq. 50), so the pulley mass `m0`
//! appears in both `M1` (row `x0`) and `M2` (row `z0`) of eq. (53); `M1` is
//! singular because `L0` carries no inertia. `crane_model!` derives
//! `G = [G1 G2]` (eqs. 57-58), `M` (eq. 53), `f` and `B^T` (eq. 56: one row
//! of `B1^T` and `f1` per entry of `p`, `f2 = [0, -m_l g, -m0 g]`).
//!
//! Geometry (eq. 55): the winch of rope 2 at `S` (the origin), the winch of
//! rope 3 at `P = -s (sin(alpha), cos(alpha))` and that of rope 1 at
//! `A = -(l + s) (sin(alpha), cos(alpha))`, all on the boom, which makes the
//! angle `alpha` with the vertical. Ropes 1 and 2 end at the main pulley
//! `B = (x0, z0)`; rope 3 runs from `P` over the pulley to the load
//! `C = (x, z)`, split into `L0 = |PB|` and `L3 - L0 = |BC|`.
//!
//! The `minimal` block is the map to the minimal coordinates of sect. 5.2.2,
//! `mu = [beta | gamma, theta, L]` (eqs. 59, 63), from the law of sines in
//! the triangle PAB (`|PA| = l`): `phi_p` is eq. (60) as corrected in docs/errata.md
//! (its printed rows 2 and 3 are garbled; with `p` of eq. (49) they are
//! `L2 = sqrt(x0^2 + z0^2)` and `L3 = L0 + L`), `phi_x` is eq. (61), the
//! pulley position `(x0, z0)` eq. (62).
//! The angles, in this model's frame (z up, boom from `S` through `P` to `A`
//! along `-(sin(alpha), cos(alpha))`):
//! - `beta` is the angle at `P` from `PA` to `PB`:
//!   `B - P = -L0 (sin(alpha - beta), cos(alpha - beta))` (eq. 62);
//! - `theta` is the load rope's angle with the vertical:
//!   `C - B = L (sin(theta), -cos(theta))` (eq. 61);
//! - `gamma` is the angle at `B` from the load rope's upward extension to
//!   rope 1: `A - B = L1 (-sin(gamma + theta), cos(gamma + theta))`, so the
//!   angle at `B` in PAB is `gamma + theta + alpha - beta` and the one at
//!   `A` is `pi - (gamma + theta + alpha)`;
//! - `L = L3 - L0 = |BC|`, the length of the load rope.
//!
//! `D2 phi_x` (eq. 12) has determinant
//! `-L l sin(beta) cos(alpha - beta) / sin^2(gamma + theta + alpha - beta)`:
//! regular for a load rope of positive length unless `PB` is along the boom
//! (`beta = 0`) or horizontal (`cos(alpha - beta) = 0`); at the paper's start
//! (eqs. 66-67, docs/errata.md) `mu = [pi/3 | pi/3, 0, 5]`.

use crane_macros::crane_model;

crane_model! {
    /// Planar US Navy crane with pulley mass (paper, sect. 5.2).
    ///
    /// Three winches (radii `r1..r3`, inertias `J1..J3`, torques `u1..u3`)
    /// on a fixed boom: rope `L1` from `A` and rope `L2` from `S` hold the
    /// main pulley `(x0, z0)` of mass `m0`; rope `L3` runs from `P` over the
    /// pulley to the load `(x, z)` of mass `m_l`. Redundant coordinates
    /// eqs. (49)-(50), kinetic energy (51), constraints (55), forces (56).
    pub struct NavyPlanarPulley {
        params {
            /// Load mass `m_l`, in kg (sect. 5.2.3).
            m_l: positive = 100.0,
            /// Mass `m0` of the main pulley, in kg (sect. 5.2.3).
            m0: positive = 150.0,
            /// Moment of inertia of winch 1 (rope `L1`, at `A`), in kg m^2.
            J1: positive = 0.1,
            /// Moment of inertia of winch 2 (rope `L2`, at `S`), in kg m^2.
            J2: positive = 0.1,
            /// Moment of inertia of winch 3 (rope `L3`, at `P`), in kg m^2.
            J3: positive = 0.1,
            /// Radius of winch 1, in m.
            r1: positive = 0.1,
            /// Radius of winch 2, in m.
            r2: positive = 0.1,
            /// Radius of winch 3, in m.
            r3: positive = 0.1,
            /// Angle of the boom with the vertical, in rad.
            alpha = PI / 3.0,
            /// Distance `l = |PA|` between winches 3 and 1 on the boom, in m.
            l: positive = 10.0,
            /// Distance `s = |SP|` between winches 2 and 3 on the boom, in m.
            s: positive = 5.0,
            /// Gravitational acceleration, in m/s^2.
            g: positive = 9.81,
        }
        robot  [L1, L2, L3, L0, x0]      // p (eq. 49)
        load   [x, z, z0]                // x: flat outputs (eq. 50)
        inputs [u1, u2, u3]
        kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*J3/r3^2*dot(L3)^2
                + 0.5*m0*(dot(x0)^2 + dot(z0)^2) + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { L1: u1/r1, L2: u2/r2, L3: u3/r3, z: -m_l*g, z0: -m0*g }
        constraints {
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 + (l + s)*sin(alpha))^2 + (z0 + (l + s)*cos(alpha))^2 - L1^2),
            rope0: 0.5*((x0 + s*sin(alpha))^2 + (z0 + s*cos(alpha))^2 - L0^2),
            #[rope(N2 = L2)]
            rope2: 0.5*(x0^2 + z0^2 - L2^2),
            #[rope(N3 = L3 - L0)]
            hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L3 - L0)^2),
        }
        minimal [beta | gamma, theta, L] {                 // mu1 | mu2 (eqs. 59, 63)
            let psi = gamma + theta + alpha;               // psi - beta: angle at B in PAB
            let d = l*sin(psi)/sin(psi - beta);            // = L0 = |PB|, law of sines
            x0 = -s*sin(alpha) - d*sin(alpha - beta);      // eq. (62)
            z0 = -s*cos(alpha) - d*cos(alpha - beta);
            L1 = l*sin(beta)/sin(psi - beta);              // eq. (60) with docs/errata.md
            L2 = sqrt(x0^2 + z0^2);
            L3 = d + L;
            L0 = d;
            x  = x0 + L*sin(theta);                        // eq. (61)
            z  = z0 - L*cos(theta);
        }
    }
}
