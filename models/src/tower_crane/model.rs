//! A rotary tower crane: the jib slews about the tower's vertical axis
//! (torque `u1`), the trolley travels along the jib (force `u2`), the hoist
//! winch (inertia `J_w`, radius `r_w`, torque `u3`) pays out the rope `L`, and
//! the load `(x, y, z)` hangs on that one rope from the trolley. The outputs
//! are the load's three coordinates.
//!
//! Derivation (rotationless, redundant coordinates, as the paper's 3D crane,
//! sect. 6.1): `q = [x1, y1, xt, yt, L | x, y, z]`.
//!
//! - Slewing without an angle: the jib tip `(x1, y1)` at the jib's height `H`
//!   lies on the circle `x1^2 + y1^2 = R^2` (`R` the jib length). With the
//!   slewing angle `phi`, `x1 = R cos phi`, `y1 = R sin phi`, so
//!   `x1'^2 + y1'^2 = R^2 phi'^2` and the jib's kinetic energy
//!   `1/2 J_jib phi'^2 = 1/2 J_jib/R^2 (x1'^2 + y1'^2)`: constant coefficient.
//! - The trolley (mass `m_t`) at `(xt, yt, H)` has kinetic energy
//!   `1/2 m_t (xt'^2 + yt'^2)` (its share of the slewing inertia included);
//!   it stays on the jib line through the axis and the tip:
//!   `xt y1 - yt x1 = 0` (the cross product, quadratic).
//! - The winch drum turns with `L'/r_w`: `1/2 J_w/r_w^2 L'^2` (winch on the
//!   trolley, or reeving that keeps `L` independent of the trolley travel).
//!   The load: `1/2 m_l (x'^2 + y'^2 + z'^2)`. The mass matrix is
//!   `diag(J_jib/R^2, J_jib/R^2, m_t, m_t, J_w/r_w^2, m_l, m_l, m_l)`: constant.
//! - The rope from the trolley to the load: `1/2 (|r - r_t|^2 - L^2) = 0`.
//! - Forces: the slewing torque `u1` does the virtual work `u1 dphi` with
//!   `dphi = (x1 dy1 - y1 dx1)/R^2`, hence `-y1/R^2 u1` on `x1` and
//!   `x1/R^2 u1` on `y1` (paper eq. 79). The trolley drive pushes along the
//!   jib, unit vector `(x1, y1)/R`: `x1/R u2` on `xt`, `y1/R u2` on `yt`; its
//!   reaction on the jib is radial, parallel to the gradient of the circle
//!   constraint, so it only shifts that constraint's multiplier and is left
//!   out. The winch torque: `u3/r_w` on `L`; gravity `-m_l g` on `z`.
//!
//! `n = 8`, `m = 3` constraints, `a = 3` inputs, `f = n - m = 5 > a`:
//! underactuated (the load swings).
//!

use crane_macros::crane_model;

crane_model! {
    /// Rotary tower crane: slewing jib, trolley on the jib, hoist winch, load on one rope.
    pub struct TowerCrane {
        params { J_jib: positive = 2.0e5, R: positive = 30.0, H: positive = 20.0, m_t: positive = 200.0, J_w: positive = 1.0, r_w: positive = 0.2,
                 m_l: positive = 1000.0, g: positive = 9.81 }
        robot  [x1, y1, xt, yt, L]
        load   [x, y, z]
        inputs [u1, u2, u3]
        kinetic = 0.5*J_jib/R^2*(dot(x1)^2 + dot(y1)^2) + 0.5*m_t*(dot(xt)^2 + dot(yt)^2)
                + 0.5*J_w/r_w^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(y)^2 + dot(z)^2);
        forces { x1: -y1/R^2*u1, y1: x1/R^2*u1, xt: x1/R*u2, yt: y1/R*u2, L: u3/r_w, z: -m_l*g }
        constraints {
            slew: 0.5*(x1^2 + y1^2 - R^2),
            jib: xt*y1 - yt*x1,
            #[rope(N = L)]
            rope: 0.5*((x - xt)^2 + (y - yt)^2 + (z - H)^2 - L^2),
        }
        // minimal coordinates: the slewing angle, the trolley's distance from
        // the axis and the load itself (x = mu2: D2 phi_x is the identity)
        minimal [phi, rho | cx, cy, cz] {
            x1 = R*cos(phi);   y1 = R*sin(phi);
            xt = rho*cos(phi); yt = rho*sin(phi);
            L = sqrt((cx - xt)^2 + (cy - yt)^2 + (cz - H)^2);
            x = cx;  y = cy;  z = cz;
        }
        sample { x1 = -30.0 .. 30.0, y1 = -30.0 .. 30.0, xt = -20.0 .. 20.0, yt = -20.0 .. 20.0,
                 L = 1.0 .. 20.0, x = -20.0 .. 20.0, y = -20.0 .. 20.0, z = 0.0 .. 15.0,
                 phi = -3.0 .. 3.0, rho = 1.0 .. 25.0, cx = -20.0 .. 20.0, cy = -20.0 .. 20.0, cz = 0.0 .. 15.0 }
    }
}
