//! A planar gantry crane (trolley, hoist winch, load on one rope) as an
//! FMI 2.0 co-simulation FMU: declare it, describe its default move, export.

use crane::prelude::*;

crane_model! {
    /// Planar gantry crane: trolley, hoist winch, load on one rope.
    pub struct Gantry {
        params { m_t: positive = 50.0, m_l: positive = 200.0, J: positive = 0.05, r: positive = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

/// The crane and its default move: 4 m across and 2 m up in 5 s.
pub struct PlanarGantry;

impl Crane<4, 1, 2> for PlanarGantry {
    type Model = Gantry;
    const NAME: &'static str = "planar-gantry";
    const DESCRIPTION: &'static str = "planar gantry crane: trolley, hoist winch, one rope";

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec { profile: Profile::Poly9, t0: 0.0, t1: 5.0, start: SVector::from([0.0, -5.0]), end: SVector::from([4.0, -3.0]) },
            // the start guess [s, L]: at rest below the trolley
            p0: vec![0.0, 5.0],
        }
    }
}

crane::fmi::export_fmu!(PlanarGantry);
