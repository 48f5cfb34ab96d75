//! A 3D gantry (bridge) crane: the bridge travels along `X` (force `u1`),
//! the trolley travels on the bridge along `Y` (force `u2`), the hoist winch
//! on the trolley (inertia `J`, radius `r`, torque `u3`) pays out the rope
//! `L`, and the load `(x, y, z)` hangs on that one rope. The outputs are the
//! load's three coordinates.
//!
//! Derivation (rotationless, redundant coordinates `q = [X, Y, L | x, y, z]`):
//!
//! - The bridge (mass `m_b`) moves with velocity `(X', 0, 0)`; the trolley
//!   (mass `m_t`) rides on it with velocity `(X', Y', 0)`; the winch drum turns
//!   with angular velocity `L'/r`; the load moves with `(x', y', z')`. So
//!   `T = 1/2 (m_b + m_t) X'^2 + 1/2 m_t Y'^2 + 1/2 J/r^2 L'^2
//!      + 1/2 m_l (x'^2 + y'^2 + z'^2)`,
//!   a quadratic form with constant coefficients: the mass matrix is
//!   `diag(m_b + m_t, m_t, J/r^2, m_l, m_l, m_l)`, constant and regular.
//! - The trolley's rope exit is at `(X, Y, 0)`; the rope (length `L`) to the
//!   load gives one quadratic constraint
//!   `g = 1/2 ((x - X)^2 + (y - Y)^2 + z^2 - L^2) = 0`, its multiplier times `L`
//!   the rope tension.
//! - Generalized forces: `u1` on `X`, `u2` on `Y`, the winch torque `u3` on
//!   `L` as `u3/r` (virtual work `u3 dL/r`), gravity `-m_l g` on `z`.
//!
//! `n = 6`, `m = 1` constraint, `a = 3` inputs, `f = n - m = 5 > a`:
//! underactuated (the load swings).
//!

use crane_macros::crane_model;

crane_model! {
    /// 3D gantry crane: bridge (X), trolley (Y), hoist winch (L), load on one rope.
    pub struct Gantry3d {
        params { m_b: positive = 400.0, m_t: positive = 100.0, m_l: positive = 500.0, J: positive = 0.05, r: positive = 0.1, g: positive = 9.81 }
        robot  [X, Y, L]
        load   [x, y, z]
        inputs [u1, u2, u3]
        kinetic = 0.5*(m_b + m_t)*dot(X)^2 + 0.5*m_t*dot(Y)^2 + 0.5*J/r^2*dot(L)^2
                + 0.5*m_l*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        forces { X: u1, Y: u2, L: u3/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - X)^2 + (y - Y)^2 + z^2 - L^2),
        }
        // minimal coordinates: the bridge and trolley positions and the load
        // itself (x = mu2: D2 phi_x is the identity, eq. 12 holds everywhere)
        minimal [bx, by | cx, cy, cz] {
            X = bx;  Y = by;
            L = sqrt((cx - bx)^2 + (cy - by)^2 + cz^2);
            x = cx;  y = cy;  z = cz;
        }
        sample { X = -10.0 .. 10.0, Y = -10.0 .. 10.0, L = 1.0 .. 10.0,
                 x = -10.0 .. 10.0, y = -10.0 .. 10.0, z = -10.0 .. -1.0,
                 bx = -10.0 .. 10.0, by = -10.0 .. 10.0,
                 cx = -10.0 .. 10.0, cy = -10.0 .. 10.0, cz = -10.0 .. -1.0 }
    }
}
