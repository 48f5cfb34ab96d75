//! Cranes with stable internal dynamics, as a user declares them: a belt
//! drive with a damper beside its spring ([`DampedDrive`], a first-order
//! free state) and a damped second pendulum on the trolley ([`DampedSwing`],
//! a second-order one).

crane_macros::crane_model! {
    /// Overhead crane whose belt drive has a damper beside its spring: the
    /// motor angle follows a first-order ODE the path leaves free.
    pub struct DampedDrive {
        params {
            J_m: positive = 0.02,
            r_m: positive = 0.05,
            k: positive = 2.0e5,
            d: positive = 4.0e5,
            m_t: positive = 50.0,
            J_w: positive = 0.05,
            r_w: positive = 0.1,
            m_l: positive = 200.0,
            g: positive = 9.81,
        }
        robot  [phi, s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*J_m*dot(phi)^2 + 0.5*m_t*dot(s)^2 + 0.5*J_w/r_w^2*dot(L)^2
                + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces {
            phi: u1 - r_m*(k*(r_m*phi - s) + d*(r_m*dot(phi) - dot(s))),
            s: k*(r_m*phi - s) + d*(r_m*dot(phi) - dot(s)),
            L: u2/r_w,
            z: -m_l*g,
        }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        sample { phi = -100.0 .. 100.0, s = -5.0 .. 5.0, L = 1.0 .. 8.0, x = -5.0 .. 5.0, z = -8.0 .. -1.0 }
    }
}

crane_macros::crane_model! {
    /// Overhead crane with a second pendulum on its trolley (a bob of mass
    /// `m2` on a rod of length `l2`, its swing damped by a damper of rate
    /// `b` between bob and trolley): the path leaves the swing free, a
    /// damped oscillation with eigenvalues `-b/(2 m2) +- i sqrt(g/l2 -
    /// (b/(2 m2))^2)` at rest.
    pub struct DampedSwing {
        params {
            m_t: positive = 50.0,
            J: positive = 0.05,
            r: positive = 0.1,
            m_l: positive = 200.0,
            m2: positive = 20.0,
            l2: positive = 2.0,
            b: positive = 40.0,
            g: positive = 9.81,
        }
        robot  [s, L, x2, z2]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m2*(dot(x2)^2 + dot(z2)^2)
                + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces {
            s: u1 + b*(dot(x2) - dot(s)),
            L: u2/r,
            x2: -b*(dot(x2) - dot(s)),
            z2: -m2*g,
            z: -m_l*g,
        }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
            rod: 0.5*((x2 - s)^2 + z2^2 - l2^2),
        }
        sample { s = -5.0 .. 5.0, L = 1.0 .. 8.0, x2 = -5.0 .. 5.0, z2 = -2.0 .. -1.0, x = -5.0 .. 5.0, z = -8.0 .. -1.0 }
    }
}
