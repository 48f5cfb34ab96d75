//! A rope's tension is a force, whichever way its constraint is written:
//! the planar gantry (200 kg load, g = 9.81: 1962 N hanging at rest) with
//! its rope as `1/2 (|d|^2 - L^2)`, `|d|^2 - L^2`, `|d| - L` and `L^2 -
//! |d|^2` reports 1962 N at rest and the same tensions along a move, where
//! each form has its own multiplier (the tension used to be `lambda L`:
//! 981 N for the second form, 7848 N for the third at L = 4 m). A rope
//! whose length is an expression of the coordinates (`N = L - L0`, a drum
//! whose coordinate counts from an offset; `N = 2*L`, a rope reeved over a
//! sheave on the load, two falls) has the tension `-lambda dg/dl` along
//! that length `l`.

use crane_macros::crane_model;
use crane_runtime::nalgebra::SVector;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{CraneModel, Options, Solution, init, simulate};

macro_rules! gantry {
    ($name:ident, $rope:expr) => {
        crane_model! {
            /// Planar gantry crane.
            pub struct $name {
                params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
                robot  [s, L]
                load   [x, z]
                inputs [u1, u2]
                kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
                forces { s: u1, L: u2/r, z: -m_l*g }
                constraints { #[rope(N = L)] rope: $rope }
            }
        }
    };
}

/// The gantry with the rope attribute's length `$length` and the
/// constraint `$rope`, and a drum offset `L0`.
macro_rules! gantry_rope {
    ($name:ident, $length:expr, $rope:expr) => {
        crane_model! {
            /// Planar gantry crane.
            pub struct $name {
                params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81, L0 = 1.5 }
                robot  [s, L]
                load   [x, z]
                inputs [u1, u2]
                kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
                forces { s: u1, L: u2/r, z: -m_l*g }
                constraints { #[rope(N = $length)] rope: $rope }
            }
        }
    };
}

gantry!(Half, 0.5 * ((x - s) ^ 2 + z ^ 2 - L ^ 2));
gantry_rope!(Offset, L - L0, 0.5 * ((x - s) ^ 2 + z ^ 2 - (L - L0) ^ 2));
gantry_rope!(TwoFalls, 2 * L, 0.5 * ((x - s) ^ 2 + z ^ 2 - L ^ 2));
gantry!(Squares, (x - s) ^ 2 + z ^ 2 - L ^ 2);
gantry!(Distance, sqrt((x - s) ^ 2 + z ^ 2) - L);
gantry!(Reversed, L ^ 2 - (x - s) ^ 2 - z ^ 2);

fn run<Mdl: CraneModel<4, 1, 2>>(crane: &Mdl) -> Solution<4, 1, 2> {
    run_from(crane, 4.0)
}

/// The move from the drum coordinate `L = l0` at the start.
fn run_from<Mdl: CraneModel<4, 1, 2>>(crane: &Mdl, l0: f64) -> Solution<4, 1, 2> {
    let path = Poly9::new(0.0, 5.0, SVector::from([0.0, -4.0]), SVector::from([4.0, -3.0])).unwrap();
    let start = init::static_equilibrium(crane, &path, 0.0, &[0.0, l0]).unwrap();
    simulate(crane, &path, &start, &Options::new(0.01, 5.0).unwrap()).unwrap()
}

#[test]
fn a_rope_pulls_the_same_whichever_way_its_constraint_is_written() {
    let runs = [
        run(&Half::default()),
        run(&Squares::default()),
        run(&Distance::default()),
        run(&Reversed::default()),
    ];
    // at rest the rope carries the load's weight m_l g; the balance is
    // solved to round-off (1e-12 of it)
    for (form, run) in ["1/2 (|d|^2 - L^2)", "|d|^2 - L^2", "|d| - L", "L^2 - |d|^2"]
        .iter()
        .zip(&runs)
    {
        let at_rest = run.tensions_at(0)[0];
        println!("{form}: N(0) = {at_rest} N, lambda(0) = {}", run.states[0].lambda[0]);
        assert!((at_rest - 200.0 * 9.81).abs() < 1e-12 * 1962.0, "{form}: {at_rest}");
    }
    // along the move: the same inputs (the forms differ in their
    // multipliers only) and the same tensions, to Newton's tolerance
    // (relative 1e-10 on the unknowns)
    let (peak_u, peak_n) = (
        runs[0].states.iter().map(|s| s.u.amax()).fold(0.0, f64::max),
        (0..runs[0].states.len())
            .map(|i| runs[0].tensions_at(i)[0].abs())
            .fold(0.0, f64::max),
    );
    for other in &runs[1..] {
        for (i, (a, b)) in runs[0].states.iter().zip(&other.states).enumerate() {
            assert!((a.u - b.u).amax() < 1e-8 * peak_u, "t = {}: {} vs {}", a.t, a.u, b.u);
            let (na, nb) = (runs[0].tensions_at(i)[0], other.tensions_at(i)[0]);
            assert!((na - nb).abs() < 1e-8 * peak_n, "t = {}: N = {na} vs {nb}", a.t);
        }
    }
}

/// A rope's length given as an expression: with the drum counting from an
/// offset (`N = L - L0`) the rope still carries the load's weight at rest,
/// m_l g, and the tensions of the plain form along the move; reeved over a
/// sheave on the load (`N = 2*L`: the rope is twice the fall, each of the
/// two falls carries half the load) the tension is m_l g / 2 at rest and
/// half the plain form's along the move. (Without the division by the
/// length's gradient `dl/dL` the second would report m_l g.)
#[test]
fn a_rope_whose_length_is_an_expression_pulls_along_that_length() {
    let plain = run(&Half::default());
    let offset = run_from(&Offset::default(), 4.0 + 1.5);
    let two_falls = run(&TwoFalls::default());
    let weight = 200.0 * 9.81;
    for (form, run, expected) in [("L - L0", &offset, weight), ("2 L", &two_falls, 0.5 * weight)] {
        let at_rest = run.tensions_at(0)[0];
        println!("N = {form}: N(0) = {at_rest} N");
        assert!((at_rest - expected).abs() < 1e-12 * weight, "{form}: {at_rest}");
    }
    let peak = (0..plain.states.len())
        .map(|i| plain.tensions_at(i)[0].abs())
        .fold(0.0, f64::max);
    for i in 0..plain.states.len() {
        let n = plain.tensions_at(i)[0];
        // Newton's tolerance: relative 1e-10 on the unknowns
        assert!(
            (offset.tensions_at(i)[0] - n).abs() < 1e-8 * peak,
            "t = {}",
            plain.states[i].t
        );
        assert!(
            (two_falls.tensions_at(i)[0] - 0.5 * n).abs() < 1e-8 * peak,
            "t = {}",
            plain.states[i].t
        );
    }
}
