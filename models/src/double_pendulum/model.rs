//! A planar double-pendulum overhead crane: the trolley (mass `m_t`, force
//! `u1`) runs on a horizontal rail at height 0, the hoist winch on it
//! (inertia `J`, drum radius `r`, torque `u2`) pays out the hoist rope `L`
//! to the hook block (mass `m_h`) at `(xh, zh)`, and the load (mass `m_l`)
//! hangs at `(x, z)` on a sling of fixed length `l_s` below the hook. The
//! outputs are the load's two coordinates.
//!
//! Derivation (redundant coordinates `q = [s, L, xh, zh | x, z]`):
//!
//! - `T = 1/2 m_t s'^2 + 1/2 J/r^2 L'^2 + 1/2 m_h (xh'^2 + zh'^2)
//!   + 1/2 m_l (x'^2 + z'^2)`: the mass matrix is constant and diagonal.
//! - The hoist rope from the trolley `(s, 0)` to the hook and the sling
//!   from the hook to the load give two quadratic constraints
//!   `1/2 ((xh - s)^2 + zh^2 - L^2) = 0` and
//!   `1/2 ((x - xh)^2 + (z - zh)^2 - l_s^2) = 0`, whose multipliers times
//!   `L` and `l_s` are the tensions `N1` and `N2`.
//! - Generalized forces: `u1` on `s`, the winch torque as `u2/r` on `L`,
//!   gravity on the hook and the load.
//!
//! `n = 6`, `m = 2`, `a = 2`, `f = 4 > a`: underactuated, flat with the
//! load's position as flat output. The hook follows from the load's
//! acceleration (`x, x''`), the trolley and the rope from the hook's
//! (`x''''`), and the inputs from the trolley's and the rope's
//! (`x^(6)`): `Structure::path_order` is 6.
//!
//! Parameters of a 2 t workshop overhead crane: a 300 kg trolley, a 40 kg
//! hook block, a 1000 kg load on a 2 m sling, a hoist drum of radius
//! 0.1 m with 0.5 kg m^2 of motor and drum inertia.

use crane_macros::crane_model;

crane_model! {
    /// Double-pendulum overhead crane: trolley, hoist winch, hook block, load on a sling.
    pub struct DoublePendulum {
        params {
            /// Trolley mass, kg.
            m_t: positive = 300.0,
            /// Hook block mass, kg.
            m_h: positive = 40.0,
            /// Load mass, kg.
            m_l: positive = 1000.0,
            /// Inertia of the hoist drum and motor about the drum axis, kg m^2.
            J: positive = 0.5,
            /// Hoist drum radius, m.
            r: positive = 0.1,
            /// Sling length from the hook to the load, m.
            l_s: positive = 2.0,
            /// Gravity, m/s^2.
            g: positive = 9.81,
        }
        robot  [s, L, xh, zh]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2
                + 0.5*m_h*(dot(xh)^2 + dot(zh)^2) + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, zh: -m_h*g, z: -m_l*g }
        constraints {
            #[rope(N1 = L)]
            hoist: 0.5*((xh - s)^2 + zh^2 - L^2),
            #[rope(N2 = l_s)]
            sling: 0.5*((x - xh)^2 + (z - zh)^2 - l_s^2),
        }
        sample { s = -5.0 .. 5.0, L = 1.0 .. 6.0, xh = -5.0 .. 5.0, zh = -6.0 .. -1.0,
                 x = -5.0 .. 5.0, z = -8.0 .. -3.0 }
    }
}
