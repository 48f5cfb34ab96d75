//! A crane that is not flat: the planar crane with a constant
//! coupling `c` between trolley and load in the kinetic energy. The load's
//! row reads `c s'' - lambda s = -lambda x - m x''` with
//! `lambda = -m (g + z'')/z`, so the trolley follows an unstable ODE with
//! growth rate `sqrt(lambda/c)` (9.9045 1/s hanging 5 m below at rest);
//! `c = 0` makes it flat again. Shared by the internal-dynamics tests of the
//! runtime and of `crane run`.

use crane_macros::crane_model;

crane_model! {
    /// A planar crane with a constant coupling c between trolley and load in
    /// the kinetic energy (not flat).
    #[crane(no_self_test)]
    pub struct Coupled {
        params { mt = 10.0, m = 100.0, c = 2.0, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*mt*dot(s)^2 + c*dot(s)*dot(x) + 0.5*dot(L)^2 + 0.5*m*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2, z: -m*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}
