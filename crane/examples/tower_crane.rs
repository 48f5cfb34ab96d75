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
//! Run with `cargo run --release -p crane --example tower_crane`.

use crane::prelude::*;

crane_model! {
    /// Rotary tower crane: slewing jib, trolley on the jib, hoist winch, load on one rope.
    pub struct TowerCrane {
        params { J_jib = 2.0e5, R = 30.0, H = 20.0, m_t = 200.0, J_w = 1.0, r_w = 0.2,
                 m_l = 1000.0, g = 9.81 }
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
        sample { x1 = -30.0 .. 30.0, y1 = -30.0 .. 30.0, xt = -20.0 .. 20.0, yt = -20.0 .. 20.0,
                 L = 1.0 .. 20.0, x = -20.0 .. 20.0, y = -20.0 .. 20.0, z = 0.0 .. 15.0 }
    }
}

/// End time of the move, s.
pub const TF: f64 = 10.0;

/// The example's move: the load from `(10, 0, 5)` to `(6, 12, 10)` in 10 s,
/// rest to rest (Poly9, eqs. 41-45): the jib slews by atan2(12, 6) = 63.4 deg,
/// the trolley moves out from 10 m to 13.4 m, the load rises 5 m.
pub fn path() -> Poly9<3> {
    Poly9::new(
        0.0,
        TF,
        SVector::from([10.0, 0.0, 5.0]),
        SVector::from([6.0, 12.0, 10.0]),
    )
    .expect("a valid time span")
}

/// The start: at rest, the jib along `X`, the trolley at 10 m, the load
/// hanging straight below it on 15 m of rope.
pub const P0: [f64; 5] = [30.0, 0.0, 10.0, 0.0, 15.0];

#[allow(dead_code)]
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let crane = TowerCrane::default();
    let path = path();
    let start = init::check_start(&crane, &path, 0.0, &P0, None)?;
    let run = simulate(&crane, &path, &start, &Options::new(0.01, TF)?)?;
    println!("   t [s]  slew [deg]  slewing u1 [N m]  trolley u2 [N]  winch u3 [N m]  tension N [N]");
    for (i, state) in run.states.iter().enumerate().step_by(50) {
        let phi = state.q[1].atan2(state.q[0]).to_degrees();
        let [u1, u2, u3] = [state.u[0], state.u[1], state.u[2]];
        println!(
            "{:8.2} {phi:11.2} {u1:17.1} {u2:15.1} {u3:15.1} {:14.1}",
            state.t,
            run.tensions_at(i)[0]
        );
    }
    let lowest = run.tensions.iter().copied().fold(f64::INFINITY, f64::min);
    println!(
        "lowest rope tension: {lowest:.1} N (the rope pulls throughout: {})",
        lowest > 0.0
    );
    Ok(())
}
