//! The checks a user relies on when declaring a crane of their own:
//! the generated self-test always checks the minimal map (the macro requires
//! its sample ranges), and a crane with a negative mass or inertia is refused
//! before a run (a literal one at compile time, see the UI cases; one from a
//! parameter's value here, with the parameter named).

use crane_macros::crane_model;
use crane_models::navy_planar::PaperCase;
use crane_runtime::check::minimal_map_self_test;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{CraneModel, Error, Options, init, simulate};
use crane_tests::kit;
use nalgebra::vector;

crane_model! {
    /// Overhead crane: cart s, winch angle beta (rope length r beta), load (xd, zd), z down.
    pub struct Overhead {
        params { mt = 10.0, J = 0.1, r = 0.1, m = 100.0, g = 9.81 }
        robot  [s, beta]
        load   [xd, zd]
        inputs [uF, uM]
        kinetic = 0.5*mt*dot(s)^2 + 0.5*J*dot(beta)^2 + 0.5*m*(dot(xd)^2 + dot(zd)^2);
        forces { s: uF, beta: uM, zd: m*g }
        constraints {
            #[rope(N = r*beta)]
            rope: 0.5*((xd - s)^2 + zd^2 - (r*beta)^2),
        }
        minimal [c | a, b] {
            s = c;
            beta = sqrt((a - c)^2 + b^2)/r;
            xd = a;
            zd = b;
        }
        // the generated self-test of this crane runs in this file's tests
        sample { s = -5.0 .. 5.0, beta = 10.0 .. 100.0, xd = -5.0 .. 5.0, zd = 1.0 .. 10.0,
                 c = -5.0 .. 5.0, a = -5.0 .. 5.0, b = 1.0 .. 10.0 }
    }
}

crane_model! {
    /// The same crane with the winch angle of the map 1 % wrong: g(phi(mu)) != 0.
    #[crane(no_self_test)]
    pub struct WrongMap {
        params { mt = 10.0, J = 0.1, r = 0.1, m = 100.0, g = 9.81 }
        robot  [s, beta]
        load   [xd, zd]
        inputs [uF, uM]
        kinetic = 0.5*mt*dot(s)^2 + 0.5*J*dot(beta)^2 + 0.5*m*(dot(xd)^2 + dot(zd)^2);
        forces { s: uF, beta: uM, zd: m*g }
        constraints {
            rope: 0.5*((xd - s)^2 + zd^2 - (r*beta)^2),
        }
        minimal [c | a, b] {
            s = c;
            beta = 1.01*sqrt((a - c)^2 + b^2)/r;
            xd = a;
            zd = b;
        }
        sample { s = -5.0 .. 5.0, beta = 10.0 .. 100.0, xd = -5.0 .. 5.0, zd = 1.0 .. 10.0,
                 c = -5.0 .. 5.0, a = -5.0 .. 5.0, b = 1.0 .. 10.0 }
    }
}

/// What the generated minimal-map test runs (`minimal_map_self_test` on the
/// declared box) passes the correct map and fails the 1 % wrong one on
/// `g(phi(mu)) = 0` (measured 9.9e-5 of |q|^2, the threshold is 1e-12).
#[test]
fn the_self_test_of_a_wrong_minimal_map_fails() {
    let mu_box = [(-5.0, 5.0), (-5.0, 5.0), (1.0, 10.0)];
    let right = minimal_map_self_test(&Overhead::default(), &mu_box).expect("the correct map passes");
    println!("{right}");
    let wrong = minimal_map_self_test(&WrongMap::default(), &mu_box).expect_err("the wrong map fails");
    println!("{wrong}");
    let constraint_error = wrong.get("g(phi(mu)) = 0").unwrap().worst_relative_error;
    assert!(constraint_error > 1e-5, "{wrong}");
}

/// A negative mass from a parameter's value: refused before the start is
/// even computed, with the smallest eigenvalue, its direction and the
/// negative parameter named (an overhead crane with a trolley mass mt = -10).
#[test]
fn a_negative_mass_from_a_parameter_is_refused() {
    let mut crane = Overhead::default();
    crane.set_parameter("mt", -10.0).unwrap();
    let path = Poly9::new(0.0, 5.0, vector![0.0, 5.0], vector![3.0, 4.0]).unwrap();
    let error = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 50.0]).unwrap_err();
    let Error::IndefiniteMassMatrix {
        smallest_eigenvalue,
        coordinates,
        negative_parameters,
    } = &error
    else {
        panic!("{error:?}")
    };
    assert!((smallest_eigenvalue + 10.0).abs() < 1e-12, "{smallest_eigenvalue}");
    assert_eq!((coordinates.as_str(), negative_parameters.as_str()), ("s", "mt"));
    assert_eq!(
        error.to_string(),
        "the mass matrix is not positive semi-definite (smallest eigenvalue -1.0000e1, along s): a kinetic energy \
         cannot be negative; negative parameters: mt"
    );
}

/// A parameter declared `positive` (the built-in models declare masses,
/// inertias, radii and lengths so) given a negative value through
/// `set_parameter`: the run is refused naming the parameter.
#[test]
fn a_non_positive_declared_parameter_is_refused() {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let mut crane = *case.model();
    crane.set_parameter("m_l", -100.0).unwrap();
    let error = simulate(&crane, case.path(), &start, &Options::new(0.01, 4.0).unwrap()).unwrap_err();
    assert_eq!(
        error,
        Error::NonPositiveParameter {
            name: "m_l",
            value: -100.0
        }
    );
    assert_eq!(
        error.to_string(),
        "parameter `m_l` = -100 must be positive (it is declared `positive`)"
    );
    crane.set_parameter("m_l", 0.0).unwrap();
    assert!(matches!(
        case_start(&crane),
        Err(Error::NonPositiveParameter { name: "m_l", .. })
    ));
    // the boom angle is not declared positive: a negative alpha is a geometry
    assert!(
        <crane_models::navy_planar::NavyPlanar as CraneModel<7, 3, 2>>::INFO
            .positive
            .iter()
            .all(|&k| k != 5)
    );
}

fn case_start(crane: &crane_models::navy_planar::NavyPlanar) -> Result<(), Error> {
    let case = PaperCase::new(4.0).unwrap();
    init::check_start(crane, case.path(), 0.0, &case.p0, None).map(|_| ())
}

/// A static solve that lands on the mirror solution of a rope constraint
/// (the gantry from the guess L = -5: the load "hangs" on a negative rope)
/// is refused naming the rope, not returned as a start.
#[test]
fn a_start_with_a_negative_rope_length_is_refused() {
    let case = crane_models::gantry_3d::DefaultCase::maneuver().unwrap();
    let error = init::static_equilibrium(case.model(), case.path(), 0.0, &[3.0, 3.0, -5.0]).unwrap_err();
    assert_eq!(
        error,
        Error::NonPositiveRopeLength {
            rope: "N",
            length: -5.0,
            t: 0.0
        }
    );
    assert!(
        error
            .to_string()
            .starts_with("the state at rest at t = 0 s gives rope `N` the length -5")
    );
    assert!(init::static_equilibrium(case.model(), case.path(), 0.0, &[3.0, 3.0, 5.0]).is_ok());
}

/// The overhead crane in minimal coordinates, with the load coordinates as
/// minimal coordinates themselves (`xd = a`, `zd = b`): it failed at its
/// first step with a non-finite Newton iterate (the servo rows had no scale:
/// every term `J_ij z_j` vanished with the load at x = 0 at rest, and the
/// normalised residual was infinite). Now both formulations run, and their
/// inputs approach each other at the scheme's order: max |u_red - u_min|
/// over the move falls by 2^k from dt = 0.02 to 0.01 (band: 25 %).
#[test]
fn the_overhead_crane_runs_in_both_formulations() {
    use crane_runtime::{Scheme, minimal::simulate_minimal};
    let crane = Overhead::default();
    let path = Poly9::new(0.0, 5.0, vector![0.0, 5.0], vector![3.0, 4.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.1, 48.0]).unwrap();
    let guess = nalgebra::SVector::<f64, 3>::from([0.0, 0.0, 5.0]);
    for scheme in [Scheme::BackwardEuler, Scheme::Bdf2] {
        let differences: Vec<f64> = [0.02, 0.01]
            .iter()
            .map(|&dt| {
                let options = Options::new(dt, 5.0).unwrap().with_scheme(scheme);
                let redundant = simulate(&crane, &path, &start, &options).unwrap();
                let minimal = simulate_minimal(&crane, &path, &start, &guess, &options).unwrap();
                kit::redundant_minimal_difference(&redundant, &minimal).0
            })
            .collect();
        let ratio = differences[0] / differences[1];
        println!(
            "overhead crane {scheme}: max |u_red - u_min| = {:.3e} / {:.3e}, ratio {ratio:.2}",
            differences[0], differences[1]
        );
        kit::assert_ratio_of_order("overhead crane", scheme, ratio);
    }
}

/// `check_minimal_map` reports where in the box `D2 phi_x` comes closest to
/// singular: the identity for a map with the load as minimal coordinates,
/// and for navy-planar's angles `[beta, gamma | theta, L]` the block
/// `d(x, z)/d(theta, L)`, a rotation scaled by `L` in its first column, so
/// its smallest singular value is `min(L, 1)` over the box (L in [2, 10]: 1).
#[test]
fn the_minimal_map_check_reports_the_conditioning_of_d2_phi_x() {
    use crane_runtime::check::check_minimal_map;
    let report = check_minimal_map(
        &Overhead::default(),
        &[(-5.0, 5.0), (-5.0, 5.0), (1.0, 10.0)],
        1.0,
        50,
        1,
    );
    let d2 = report.output_jacobian.clone().expect("a minimal map reports D2 phi_x");
    assert_eq!(
        (d2.smallest_singular_value, d2.largest_condition),
        (1.0, 1.0),
        "{report}"
    );
    assert_eq!(d2.at.len(), 3);
    let navy = crane_models::navy_planar::NavyPlanar::default();
    let report = check_minimal_map(&navy, &[(0.2, 0.9), (1.2, 2.2), (-0.5, 0.5), (2.0, 10.0)], 1.0, 200, 2);
    println!("{report}");
    let d2 = report.output_jacobian.expect("reported");
    assert!((d2.smallest_singular_value - 1.0).abs() < 1e-12, "{d2:?}");
    assert!(
        d2.largest_condition > 2.0 && d2.largest_condition <= 10.0 + 1e-9,
        "{d2:?}"
    );
}
