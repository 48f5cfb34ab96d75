//! The planar US Navy crane with pulley mass (paper, sect. 5.2): the
//! generated model against finite differences and a transcription of
//! eqs. (53), (55)-(58); the paper's start (66) with docs/errata.md as a regular
//! equilibrium; convergence of u to the analytical solution of Appendix B
//! (Figs. 14-16, eq. 48), the long maneuver of Fig. 18, and rope tensions
//! (Fig. 17).

use crane_models::navy_planar_pulley::reference::reference_at;
use crane_models::navy_planar_pulley::{NavyPlanarPulley, PaperCase, paper_p0};
use crane_runtime::check::{SampleBox, check_derivatives};
use crane_runtime::{CraneModel, Error, Options, Rope, Scheme, Solution, init, simulate};
use crane_tests::kit::{self, Formulation};
use nalgebra::{SMatrix, SVector};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

/// Coordinates around the paper's maneuver: lengths 1..25 m, positions
/// -15..5 m (the pulley hangs below the boom, the load below the pulley).
fn sample_box() -> SampleBox<8> {
    SampleBox {
        q: [
            (1.0, 25.0),
            (1.0, 25.0),
            (1.0, 25.0),
            (1.0, 25.0),
            (-15.0, 5.0),
            (-15.0, 5.0),
            (-25.0, 0.0),
            (-25.0, 0.0),
        ],
        velocity: 2.0,
        multiplier: 500.0,
        input: 200.0,
    }
}

// ---------------------------------------------------------------------------
// The generated model

#[test]
fn generated_derivatives_match_central_differences() {
    let report = check_derivatives(&NavyPlanarPulley::default(), &sample_box(), 200, 17);
    println!("{report}");
    // central differences: O(h^2) truncation + O(eps/h) round-off, h ~ 1e-6 |q|,
    // give ~1e-9 normwise for correct derivatives; a wrong entry gives O(1)
    assert!(report.worst() < 1e-6, "{report}");
    assert_eq!(report.points, 200);
}

/// The paper's equations transcribed by hand: `g` (55), `G = [G1 G2]` from
/// `G1^T` (57) and `G2^T` (58), `M = diag(M1, M2)` (53), `f` and `B^T` (56
/// with docs/errata.md: one row per entry of `p`).
struct Paper(NavyPlanarPulley);

impl Paper {
    fn constraints(&self, q: &SVector<f64, 8>) -> SVector<f64, 4> {
        let p = &self.0;
        let [l1, l2, l3, l0, x0, x, z, z0] = [q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]];
        let (sa, ca) = p.alpha.sin_cos();
        let ls = p.l + p.s;
        SVector::<f64, 4>::new(
            0.5 * ((x0 + ls * sa).powi(2) + (z0 + ls * ca).powi(2) - l1 * l1),
            0.5 * ((x0 + p.s * sa).powi(2) + (z0 + p.s * ca).powi(2) - l0 * l0),
            0.5 * (x0 * x0 + z0 * z0 - l2 * l2),
            0.5 * ((x - x0).powi(2) + (z - z0).powi(2) - (l3 - l0).powi(2)),
        )
    }

    fn constraint_jacobian(&self, q: &SVector<f64, 8>) -> SMatrix<f64, 4, 8> {
        let p = &self.0;
        let [l1, l2, l3, l0, x0, x, z, z0] = [q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]];
        let (sa, ca) = p.alpha.sin_cos();
        let ls = p.l + p.s;
        // G1^T (57), rows L1, L2, L3, L0, x0; columns the four constraints
        #[rustfmt::skip]
        let g1t = SMatrix::<f64, 5, 4>::from_row_slice(&[
            -l1,            0.0,           0.0, 0.0,
            0.0,            0.0,           -l2, 0.0,
            0.0,            0.0,           0.0, l0 - l3,
            0.0,            -l0,           0.0, l3 - l0,
            x0 + ls * sa,   x0 + p.s * sa, x0,  x0 - x,
        ]);
        // G2^T (58), rows x, z, z0
        #[rustfmt::skip]
        let g2t = SMatrix::<f64, 3, 4>::from_row_slice(&[
            0.0,            0.0,           0.0, x - x0,
            0.0,            0.0,           0.0, z - z0,
            z0 + ls * ca,   z0 + p.s * ca, z0,  z0 - z,
        ]);
        let mut g = SMatrix::<f64, 4, 8>::zeros();
        g.columns_mut(0, 5).copy_from(&g1t.transpose());
        g.columns_mut(5, 3).copy_from(&g2t.transpose());
        g
    }

    fn mass_matrix(&self) -> SMatrix<f64, 8, 8> {
        let p = &self.0;
        SMatrix::from_diagonal(&SVector::<f64, 8>::from_column_slice(&[
            p.J1 / (p.r1 * p.r1),
            p.J2 / (p.r2 * p.r2),
            p.J3 / (p.r3 * p.r3),
            0.0,
            p.m0,
            p.m_l,
            p.m_l,
            p.m0,
        ]))
    }

    fn forces(&self) -> SVector<f64, 8> {
        let p = &self.0;
        SVector::<f64, 8>::from_column_slice(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -p.m_l * p.g, -p.m0 * p.g])
    }

    fn input_matrix(&self) -> SMatrix<f64, 8, 3> {
        let p = &self.0;
        let mut bt = SMatrix::<f64, 8, 3>::zeros();
        bt[(0, 0)] = 1.0 / p.r1;
        bt[(1, 1)] = 1.0 / p.r2;
        bt[(2, 2)] = 1.0 / p.r3;
        bt
    }
}

/// Every generated function equals the transcription of the paper at random
/// points, to round-off (1e-12 relative to the largest entry).
#[test]
fn generated_model_matches_the_paper_equations() {
    let generated = NavyPlanarPulley::default();
    // the declared defaults are the values of sect. 5.2.3 (and g = 9.81):
    // m_l, m0, J1, J2, J3, r1, r2, r3, alpha, l, s, g
    let pi = std::f64::consts::PI;
    assert_eq!(
        generated.parameter_values(),
        [100.0, 150.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, pi / 3.0, 10.0, 5.0, 9.81]
    );
    let paper = Paper(generated);
    let sample = sample_box();
    let mut rng = SmallRng::seed_from_u64(23);
    let close = |a: &[f64], b: &[f64], what: &str| {
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-12 * scale, "{what}: generated {a:?} vs paper {b:?}");
        }
    };
    close(
        generated.mass_matrix::<f64>().as_slice(),
        paper.mass_matrix().as_slice(),
        "M (eq. 53)",
    );
    for _ in 0..100 {
        let q = SVector::<f64, 8>::from_fn(|i, _| rng.random_range(sample.q[i].0..=sample.q[i].1));
        let v = SVector::<f64, 8>::from_fn(|_, _| rng.random_range(-2.0..=2.0));
        close(
            generated.constraints(&q).as_slice(),
            paper.constraints(&q).as_slice(),
            "g (eq. 55)",
        );
        close(
            generated.constraint_jacobian(&q).as_slice(),
            paper.constraint_jacobian(&q).as_slice(),
            "G (eqs. 57-58)",
        );
        close(
            generated.forces(&q, &v).as_slice(),
            paper.forces().as_slice(),
            "f (eq. 56)",
        );
        close(
            generated.input_matrix(&q).as_slice(),
            paper.input_matrix().as_slice(),
            "B^T (eq. 56)",
        );
        let mut lengths = [0.0; 3];
        generated.rope_lengths(&q, &mut lengths);
        close(&lengths, &[q[0], q[1], q[2] - q[3]], "rope lengths L1, L2, L3 - L0");
    }
    let info = NavyPlanarPulley::INFO;
    assert_eq!(info.coordinates, ["L1", "L2", "L3", "L0", "x0", "x", "z", "z0"]);
    assert_eq!(info.inputs, ["u1", "u2", "u3"]);
    assert_eq!(info.constraints, ["rope1", "rope0", "rope2", "hoist"]);
    assert_eq!(
        info.ropes,
        [
            Rope {
                tension: "N1",
                constraint: 0
            },
            Rope {
                tension: "N2",
                constraint: 2
            },
            Rope {
                tension: "N3",
                constraint: 3
            },
        ]
    );
    assert_eq!(
        (
            NavyPlanarPulley::N,
            NavyPlanarPulley::M,
            NavyPlanarPulley::A,
            NavyPlanarPulley::F
        ),
        (8, 4, 3, 4)
    );
}

// ---------------------------------------------------------------------------
// The paper's start

fn run(case: &PaperCase, dt: f64) -> Solution<8, 4, 3> {
    let start = case.start().expect("the paper's start is consistent");
    simulate(case.model(), case.path(), &start, &Options::new(dt, case.tf()).unwrap()).expect("the run converges")
}

/// Eq. (66) with docs/errata.md is the flatness solution at t0; `u` and `lambda` of
/// the static balance agree with Appendix B.
#[test]
fn paper_start_is_consistent_and_matches_appendix_b() {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let reference = case.reference(0.0).unwrap();
    for i in 0..8 {
        assert!(
            (start.q[i] - reference.q[i]).abs() < 1e-10,
            "q[{i}]: {} vs {}",
            start.q[i],
            reference.q[i]
        );
    }
    // The balance is a regular 8x7 least-squares problem with entries up to
    // ~15 m and solution entries up to ~200 N/m, 100 N m: the SVD solve is
    // accurate to ~1e-13 relative, so 1e-9 absolute (1e-12 relative to the
    // weights m_l g ~ 1e3 N) leaves ample room and would catch any wrong row.
    println!(
        "start: u = {:?}, lambda = {:?}; |du| = {:.1e}, |dlambda| = {:.1e}",
        start.u.as_slice(),
        start.lambda.as_slice(),
        (start.u - reference.u).amax(),
        (start.lambda - reference.lambda).amax()
    );
    assert!((start.u - reference.u).amax() < 1e-9, "{} vs {}", start.u, reference.u);
    assert!(
        (start.lambda - reference.lambda).amax() < 1e-9,
        "{} vs {}",
        start.lambda,
        reference.lambda
    );
    // all ropes taut: u_i = -N_i r_i with N = (490.5, 98.1 sqrt 175, 981) N
    let expected_u = [-49.05, -9.81 * 175f64.sqrt(), -98.1];
    for (i, e) in expected_u.iter().enumerate() {
        assert!((start.u[i] - e).abs() < 1e-9, "u{} = {}", i + 1, start.u[i]);
    }
}

/// The printed (66), `[10, 15, 13.23, 10, -5/2 sqrt 3]`, has L2 and L3
/// swapped (docs/errata.md): the consistency check refuses it and names rope 2.
#[test]
fn printed_p0_is_refused() {
    let case = PaperCase::new(4.0).unwrap();
    let printed = [10.0, 15.0, 13.23, 10.0, -2.5 * 3f64.sqrt()];
    let error = init::check_start(case.model(), case.path(), 0.0, &printed, None).unwrap_err();
    match &error {
        Error::InconsistentStart { equation, residual, .. } => {
            assert!(equation.contains("rope2"), "{error}");
            // g_rope2 = 1/2 (x0^2 + z0^2 - 15^2) = 1/2 (175 - 225)
            assert!((residual - 25.0).abs() < 1e-12, "{error}");
        }
        other => panic!("expected an inconsistent start, got {other}"),
    }
}

/// The start is a regular equilibrium (docs/errata.md, "Degenerate starts"): the
/// static solve recovers it from a perturbed guess, and the reference.
#[test]
fn static_solve_recovers_the_paper_start() {
    let case = PaperCase::new(4.0).unwrap();
    let reference = case.reference(0.0).unwrap();
    let p0 = paper_p0();
    let guess = [p0[0] + 0.5, p0[1] - 0.4, p0[2] + 0.6, p0[3] - 0.3, p0[4] + 0.4];
    let state = init::static_equilibrium(case.model(), case.path(), 0.0, &guess).unwrap();
    println!(
        "static solve: |q - q_ref| = {:.1e}, |u - u_ref| = {:.1e}, |lambda - lambda_ref| = {:.1e}",
        (state.q - reference.q).amax(),
        (state.u - reference.u).amax(),
        (state.lambda - reference.lambda).amax()
    );
    for (i, e) in p0.iter().enumerate() {
        assert!((state.q[i] - e).abs() < 1e-9, "p[{i}] = {} vs {e}", state.q[i]);
    }
    // Newton to round-off (1e-11 relative update test) against exact formulas
    assert!((state.q - reference.q).amax() < 1e-9, "{} vs {}", state.q, reference.q);
    assert!((state.u - reference.u).amax() < 1e-7, "{} vs {}", state.u, reference.u);
    assert!((state.lambda - reference.lambda).amax() < 1e-7);
    // and at the end of the maneuver (load 1 m below the pulley)
    let end = case.reference(4.0).unwrap();
    let guess: Vec<f64> = (0..5).map(|i| end.q[i] + [0.3, -0.3, 0.2, 0.2, -0.2][i]).collect();
    let state = init::static_equilibrium(case.model(), case.path(), 4.0, &guess).unwrap();
    assert!((state.q - end.q).amax() < 1e-9, "{} vs {}", state.q, end.q);
    assert!((state.u - end.u).amax() < 1e-7, "{} vs {}", state.u, end.u);
}

// ---------------------------------------------------------------------------
// Convergence (Figs. 14-16, 18)

#[test]
fn u_converges_with_order_one_tf4() {
    let errors = kit::assert_order(
        &PaperCase::new(4.0).unwrap(),
        Formulation::Redundant,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
    assert!(errors[0] < 0.1 && errors[5] < 1e-3, "{errors:?}");
}

#[test]
fn u_converges_with_order_one_tf15() {
    kit::assert_order(
        &PaperCase::new(15.0).unwrap(),
        Formulation::Redundant,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
}

/// docs/errata.md, "Where the discretisation error sits": the servo constraints (with
/// the exact gamma'') and the load rows fix `q` and `lambda2`, `lambda4`
/// algebraically at each step, so backward Euler reproduces them to
/// round-off. `lambda1`, `lambda3` come from the pulley's rows (124e, f),
/// whose `m0 x0''` is a second difference: they converge with order 1, like u.
#[test]
fn coordinates_and_multipliers_follow_the_reference() {
    let case = PaperCase::new(4.0).unwrap();
    let worst = |dt: f64| {
        let solution = run(&case, dt);
        let (mut q_err, mut exact_err, mut pulley_err) = (0.0f64, 0.0f64, 0.0f64);
        for state in &solution.states {
            let reference = case.reference(state.t).unwrap();
            let d = state.lambda - reference.lambda;
            let scale = reference.lambda.amax();
            q_err = q_err.max((state.q - reference.q).amax());
            exact_err = exact_err.max(d[1].abs().max(d[3].abs()) / scale);
            pulley_err = pulley_err.max(d[0].abs().max(d[2].abs()) / scale);
        }
        println!(
            "dt = {dt}: max |q - q_ref| = {q_err:.2e} m, lambda2, lambda4 rel. {exact_err:.2e}, \
             lambda1, lambda3 rel. {pulley_err:.2e}"
        );
        (q_err, exact_err, pulley_err)
    };
    let (q1, e1, _) = worst(0.1); // Fig. 14
    let (q2, e2, p2) = worst(0.01); // Fig. 16 (right)
    let (q3, e3, p3) = worst(0.001);
    for (q, e) in [(q1, e1), (q2, e2), (q3, e3)] {
        assert!(q < 1e-8, "{q}");
        assert!(e < 1e-8, "{e}");
    }
    // order 1 over the whole path (measured ratio 9.9; between dt = 0.1 and
    // 0.01 it is only 6.7, not yet asymptotic)
    let ratio = p2 / p3;
    assert!(
        (9.0..11.0).contains(&ratio),
        "lambda1, lambda3 errors {p2:e} -> {p3:e}: ratio {ratio}, expected 10"
    );
    // relative to the largest multiplier at the time (lambda4, 200..1000 N/m):
    // measured 8.0e-2 (dt = 0.1), 1.2e-2 (0.01), 1.3e-3 (0.001)
    assert!(p2 < 0.02, "{p2}");
}

// ---------------------------------------------------------------------------
// Rope tensions (Fig. 17)

/// All three ropes stay taut along both maneuvers, and the tensions of the
/// run approach Appendix B's (`N3` exactly, `N1`, `N2` to O(dt)).
#[test]
fn ropes_stay_taut_along_the_maneuver() {
    for tf in [4.0, 15.0] {
        let case = PaperCase::new(tf).unwrap();
        let params = *case.model();
        let solution = run(&case, 0.01);
        let (mut min, mut peak, mut worst) = ([f64::INFINITY; 3], [0.0f64; 3], [0.0f64; 3]);
        for (i, state) in solution.states.iter().enumerate() {
            let reference = reference_at(&params, case.path(), state.t);
            for (k, (rope, &n)) in solution.info.ropes.iter().zip(solution.tensions_at(i)).enumerate() {
                assert!(n > 0.0, "rope {} slack at t = {}: {n}", rope.tension, state.t);
                assert!(
                    reference.tensions[k] > 0.0,
                    "reference {} at t = {}",
                    rope.tension,
                    state.t
                );
                min[k] = min[k].min(n);
                peak[k] = peak[k].max(reference.tensions[k]);
                worst[k] = worst[k].max((n - reference.tensions[k]).abs());
            }
        }
        let relative: Vec<f64> = (0..3).map(|k| worst[k] / peak[k]).collect();
        println!(
            "tf = {tf}, dt = 0.01: min N = {min:.1?} N, peak N_ref = {peak:.1?} N; \
             max |N - N_ref| / peak N_ref = {:.1e}, {:.1e}, {:.1e}",
            relative[0], relative[1], relative[2]
        );
        // N3 = lambda4 (L3 - L0) is fixed algebraically (see above), N1 and N2
        // carry the O(dt) error of lambda1, lambda3 (measured 4.8e-2 and
        // 8.1e-3 at tf = 4 s, 1.6e-4 and 2.9e-5 at tf = 15 s)
        assert!(relative[2] < 1e-13, "N3 is exact: {relative:?}");
        // the O(dt) errors as measured, 25 % above: backward Euler's error
        // constant is reproducible to far better than that
        let bound = if tf < 10.0 { [6e-2, 1e-2] } else { [2e-4, 4e-5] };
        assert!(relative[0] < bound[0] && relative[1] < bound[1], "{relative:?}");
    }
}
