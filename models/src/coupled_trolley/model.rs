//! A planar trolley crane with a constant coupling `c` between trolley and
//! load in the kinetic energy: the trolley `s` (mass `mt`, force `u1`), the
//! hoist rope `L` (unit inertia, force `u2`) and the load `(x, z)` (mass `m`)
//! on that rope, hanging from the trolley. The outputs are the load's
//! coordinates.
//!
//! Derivation (redundant coordinates `q = [s, L | x, z]`):
//!
//! - `T = 1/2 mt s'^2 + c s' x' + 1/2 L'^2 + 1/2 m (x'^2 + z'^2)`: the term
//!   `c s' x'` couples the trolley and the load (a stand-in for any elastic
//!   or inertial coupling the paper's cranes do not have); the mass matrix
//!   is constant and positive definite for `c^2 < mt m`.
//! - One rope from the trolley `(s, 0)` to the load:
//!   `g = 1/2 ((x - s)^2 + z^2 - L^2) = 0`, tension `N = lambda L`.
//! - Forces: `u1` on `s`, `u2` on `L`, gravity `-m g` on `z`.
//!
//! Why it is not flat: the load's row `x` reads
//! `c s'' + m x'' = -lambda (x - s)`, with `x` given by the path and
//! `lambda = -m (g + z'')/z` from the row `z`. So `c s'' - lambda s =
//! -lambda x - m x''`: the trolley follows a second-order ODE driven by the
//! path, with eigenvalues `+-sqrt(lambda/c)`: real (about 9.9 1/s for the
//! load hanging 5 m below at rest) for a hanging load, so the causal inverse
//! grows like `exp(9.9 t)`. With `c = 0` the row fixes `s` algebraically
//! and the crane is flat again.
//!
//! `n = 4`, `m = 1`, `a = 2`, `f = 3 > a`: underactuated.

use crane_macros::crane_model;

crane_model! {
    /// A planar trolley crane with a constant trolley-load coupling c in the
    /// kinetic energy (not flat: unstable internal dynamics).
    pub struct CoupledTrolley {
        params { mt: positive = 10.0, m: positive = 100.0, c = 2.0, g: positive = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*mt*dot(s)^2 + c*dot(s)*dot(x) + 0.5*dot(L)^2 + 0.5*m*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2, z: -m*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        sample { s = -5.0 .. 5.0, L = 1.0 .. 10.0, x = -5.0 .. 5.0, z = -10.0 .. -1.0 }
    }
}
