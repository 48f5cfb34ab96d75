//! A planar overhead crane with an elastic trolley drive: the motor (angle
//! `phi`, inertia `J_m`, torque `u1`) turns a belt pulley of radius `r_m`,
//! and the toothed belt, of stiffness `k`, pulls the trolley (mass `m_t`,
//! position `s`) with the force `k (r_m phi - s)`. The hoist winch on the
//! trolley (inertia `J_w`, radius `r_w`, torque `u2`) pays out the rope `L`
//! to the load `(x, z)`.
//!
//! Derivation (redundant coordinates `q = [phi, s, L | x, z]`):
//!
//! - `T = 1/2 J_m phi'^2 + 1/2 m_t s'^2 + 1/2 J_w/r_w^2 L'^2
//!   + 1/2 m_l (x'^2 + z'^2)`: a constant diagonal mass matrix.
//! - The belt stores `1/2 k (r_m phi - s)^2`: the generalized forces
//!   `-k r_m (r_m phi - s)` on `phi` and `k (r_m phi - s)` on `s`; the motor
//!   torque `u1` acts on `phi`, the winch torque as `u2/r_w` on `L`, gravity
//!   on the load.
//! - The rope: `1/2 ((x - s)^2 + z^2 - L^2) = 0`, multiplier times `L` the
//!   tension.
//!
//! `n = 5`, `m = 1`, `a = 2`, `f = 4 > a`. Flat with the load as output:
//! the trolley follows from `x, x''`, the belt's stretch from the trolley's
//! acceleration (`x''''`), the motor torque from the motor's acceleration
//! (`x^(6)`): `Structure::path_order` is 6. (A belt with damping would make
//! the motor's angle a state of internal dynamics instead.)
//!
//! Parameters of a light gantry with a toothed-belt axis: a 50 kg trolley,
//! a 200 kg load, a servo motor of 0.02 kg m^2 on a 50 mm pulley, a belt
//! of 2e5 N/m (the belt mode near 170 rad/s).

use crane_macros::crane_model;

crane_model! {
    /// Overhead crane with an elastic belt drive: motor, belt, trolley, hoist winch, load on one rope.
    pub struct ElasticDrive {
        params {
            /// Inertia of the motor and the belt pulley, kg m^2.
            J_m: positive = 0.02,
            /// Belt pulley radius, m.
            r_m: positive = 0.05,
            /// Belt stiffness, N/m.
            k: positive = 2.0e5,
            /// Trolley mass, kg.
            m_t: positive = 50.0,
            /// Inertia of the hoist winch, kg m^2.
            J_w: positive = 0.05,
            /// Hoist winch radius, m.
            r_w: positive = 0.1,
            /// Load mass, kg.
            m_l: positive = 200.0,
            /// Gravity, m/s^2.
            g: positive = 9.81,
        }
        robot  [phi, s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*J_m*dot(phi)^2 + 0.5*m_t*dot(s)^2 + 0.5*J_w/r_w^2*dot(L)^2
                + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { phi: u1 - k*r_m*(r_m*phi - s), s: k*(r_m*phi - s), L: u2/r_w, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        sample { phi = -100.0 .. 100.0, s = -5.0 .. 5.0, L = 1.0 .. 8.0, x = -5.0 .. 5.0, z = -8.0 .. -1.0 }
    }
}
