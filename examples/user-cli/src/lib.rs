//! Three cranes of a user's own with the whole tool: a planar gantry crane
//! (trolley, hoist winch, load on one rope), a workshop crane whose load
//! hangs on a sling below a hook block (a double pendulum, whose inputs
//! need the path's 6th derivative) and a gantry with a damped second
//! pendulum on its trolley (internal dynamics the load path leaves free),
//! each declared once, described once ([`PlanarGantry`], [`HookCrane`],
//! [`SwingCrane`]), listed in the registry [`MyCranes`] that the binary
//! `my-cranes` runs and the FMU functions of this `cdylib` export. Every
//! formulation their models support comes with the declaration: the hook
//! crane runs the exact reduced (dummy-derivative) formulation by default,
//! as a built-in crane of path order 6 does, and the swing crane the
//! reduced formulation with state selection (its free swing integrated by
//! the scheme, everything else exact), as every crane whose internal
//! dynamics are stable does.

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

crane_model! {
    /// Workshop crane: trolley, hoist winch, hook block, load on a sling.
    pub struct Hook {
        params { m_t: positive = 120.0, m_h: positive = 15.0, m_l: positive = 400.0, J: positive = 0.2,
                 r: positive = 0.08, l_s: positive = 1.5, g: positive = 9.81 }
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
    }
}

/// The workshop crane and its default move: 3 m across and 1 m up in 8 s
/// on a profile smooth to the 6th derivative (its inputs need the path's
/// 6th derivative).
pub struct HookCrane;

impl Crane<6, 2, 2> for HookCrane {
    type Model = Hook;
    const NAME: &'static str = "hook-crane";
    const DESCRIPTION: &'static str = "workshop crane: trolley, hoist winch, hook block, load on a sling";

    fn input_units() -> &'static [&'static str] {
        &["N", "N m"]
    }

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::SmoothThreePhase { tau0: 2.5 },
                t0: 0.0,
                t1: 8.0,
                start: SVector::from([0.0, -4.5]),
                end: SVector::from([3.0, -3.5]),
            },
            // the start guess [s, L, xh, zh]: hook and load at rest below the trolley
            p0: vec![0.0, 3.0, 0.0, -3.0],
        }
    }
}

crane_model! {
    /// Gantry crane with a second pendulum on its trolley, its swing damped.
    pub struct Swing {
        params { m_t: positive = 50.0, J: positive = 0.05, r: positive = 0.1, m_l: positive = 200.0,
                 m2: positive = 20.0, l2: positive = 2.0, b: positive = 40.0, g: positive = 9.81 }
        robot  [s, L, x2, z2]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m2*(dot(x2)^2 + dot(z2)^2)
                + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        // a damper of rate b between the trolley and the second pendulum's bob
        forces { s: u1 + b*(dot(x2) - dot(s)), L: u2/r, x2: -b*(dot(x2) - dot(s)), z2: -m2*g, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
            rod: 0.5*((x2 - s)^2 + z2^2 - l2^2),
        }
    }
}

/// The swing crane and its default move: 3 m across and 1 m up in 4 s (the
/// swing it starts dies out after it with the eigenvalues -1 +- 1.976i 1/s
/// of the swing at rest: `--tf 8` shows it).
pub struct SwingCrane;

impl Crane<6, 2, 2> for SwingCrane {
    type Model = Swing;
    const NAME: &'static str = "swing-crane";
    const DESCRIPTION: &'static str = "gantry crane with a damped second pendulum on its trolley";

    fn input_units() -> &'static [&'static str] {
        &["N", "N m"]
    }

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 4.0,
                start: SVector::from([0.0, -5.0]),
                end: SVector::from([3.0, -4.0]),
            },
            // the start guess [s, L, x2, z2]: everything at rest below the trolley
            p0: vec![0.0, 5.0, 0.0, -2.0],
        }
    }
}

crane::registry! {
    /// The cranes of `my-cranes` (add `crane::models::BuiltIn` as a pair,
    /// `(MyCranes, BuiltIn)`, in both places below to get the built-in
    /// ones too).
    pub struct MyCranes { PlanarGantry, HookCrane, SwingCrane }
}

crane::fmi::export_fmu!(registry = MyCranes);

// and a Python module of them (feature `python`): `maturin build` on this
// crate makes the wheel `my_cranes`, whose `run("hook-crane")` is
// `my-cranes run hook-crane` into numpy arrays
#[cfg(feature = "python")]
crane::python::export_module!(registry = MyCranes, name = "my_cranes");
