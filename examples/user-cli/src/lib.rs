//! A planar gantry crane (trolley, hoist winch, load on one rope) with the
//! whole tool: declared once, described once ([`PlanarGantry`]), listed in
//! the registry [`MyCranes`] that the binary `my-cranes` runs and the FMU
//! functions of this `cdylib` export.

use crane::prelude::*;

crane_model! {
    /// Planar gantry crane: trolley, hoist winch, load on one rope.
    pub struct Gantry {
        params { m_t: positive = 50.0, m_l: positive = 200.0, J: positive = 0.05, r: positive = 0.1,
                 g: positive = 9.81 }
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

// Names of this crate's own that the model's parameters `J`, `g` and its
// coordinate `L` share: the generated code is out of their reach.

/// The catalogue drum's inertia in kg m^2 (the model's `J` is a parameter
/// of its own).
pub const J: f64 = 0.05;

/// Standard gravity in m/s^2.
pub fn g() -> f64 {
    9.80665
}

/// A marker type of this crate, named like the rope length `L`.
#[derive(Debug)]
pub struct L;

/// The crane and its default move: 4 m across and 2 m up in 5 s.
pub struct PlanarGantry;

impl Crane<4, 1, 2> for PlanarGantry {
    type Model = Gantry;
    const NAME: &'static str = "planar-gantry";
    const DESCRIPTION: &'static str = "planar gantry crane: trolley, hoist winch, one rope";

    // the trolley force and the winch torque
    fn input_units() -> &'static [&'static str] {
        &["N", "N m"]
    }

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 5.0,
                start: SVector::from([0.0, -5.0]),
                end: SVector::from([4.0, -3.0]),
            },
            // the start guess [s, L]: at rest below the trolley
            p0: vec![0.0, 5.0],
        }
    }
}

crane::registry! {
    /// The cranes of `my-cranes` (add `crane::models::BuiltIn` as a pair,
    /// `(MyCranes, BuiltIn)`, in both places below to get the built-in
    /// ones too).
    pub struct MyCranes { PlanarGantry }
}

crane::fmi::export_fmu!(registry = MyCranes);
