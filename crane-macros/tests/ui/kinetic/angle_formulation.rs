// Mistake: the textbook angle formulation of a gantry crane (trolley `s`,
// pendulum angle `theta`): its mass matrix depends on the angle. The message
// shows the rewrite in the load's position, before the constraint it asks
// for is found missing.
use crane_macros::crane_model;

crane_model! {
    /// Gantry crane with a pendulum of fixed length.
    pub struct Pendulum {
        params { m_t = 10.0, m = 100.0, l = 5.0, g = 9.81 }
        robot  [s]
        load   [theta]
        inputs [u]
        kinetic = 0.5*(m_t + m)*dot(s)^2 + m*l*cos(theta)*dot(s)*dot(theta) + 0.5*m*l^2*dot(theta)^2;
        forces { s: u, theta: -m*g*l*sin(theta) }
        constraints { }
    }
}

fn main() {}
