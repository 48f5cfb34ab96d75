//! The generated `navy-planar` model against the paper's equations and finite
//! differences (sect. 5.1.1, eqs. 29, 33-35).

use crane_models::navy_planar::NavyPlanar;
use crane_runtime::CraneModel;
use crane_runtime::check::{SampleBox, check_derivatives};
use crane_tests::handwritten::HandNavyPlanar;
use nalgebra::SVector;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// Coordinates around the paper's maneuver: lengths 1..20 m, positions -15..15 m.
fn sample_box() -> SampleBox<7> {
    SampleBox {
        q: [
            (1.0, 20.0),
            (1.0, 20.0),
            (1.0, 20.0),
            (-15.0, 15.0),
            (-15.0, 0.0),
            (-15.0, 15.0),
            (-20.0, 0.0),
        ],
        velocity: 2.0,
        multiplier: 500.0,
        input: 200.0,
    }
}

#[test]
fn generated_derivatives_match_central_differences() {
    let report = check_derivatives(&NavyPlanar::default(), &sample_box(), 200, 7);
    println!("{report}");
    // central differences: O(h^2) truncation + O(eps/h) round-off, h ~ 1e-6 |q|,
    // give ~1e-9 normwise for correct derivatives; a wrong entry gives O(1)
    assert!(report.worst() < 1e-6, "{report}");
    assert_eq!(report.points, 200);
}

/// Every generated function equals the hand transcription of eqs. (29),
/// (33), (34), (35) at random points, to round-off (1e-12 relative: both sides
/// evaluate the same few products in a different order).
#[test]
fn generated_model_matches_the_paper_equations() {
    let generated = NavyPlanar::default();
    let paper = HandNavyPlanar::default();
    let sample = sample_box();
    let mut rng = SmallRng::seed_from_u64(11);
    let close = |a: &[f64], b: &[f64], what: &str| {
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-12 * scale, "{what}: generated {a:?} vs paper {b:?}");
        }
    };
    for _ in 0..100 {
        let q = SVector::<f64, 7>::from_fn(|i, _| rng.random_range(sample.q[i].0..=sample.q[i].1));
        let v = SVector::<f64, 7>::from_fn(|_, _| rng.random_range(-2.0..=2.0));
        let lambda = SVector::<f64, 3>::from_fn(|_, _| rng.random_range(-500.0..=500.0));
        let u = SVector::<f64, 2>::from_fn(|_, _| rng.random_range(-200.0..=200.0));
        close(
            generated.constraints(&q).as_slice(),
            paper.constraints(&q).as_slice(),
            "g (eq. 33)",
        );
        close(
            generated.constraint_jacobian(&q).as_slice(),
            paper.constraint_jacobian(&q).as_slice(),
            "G = [G1 G2] (eq. 35)",
        );
        close(
            generated.constraint_hessian(&q, &lambda).as_slice(),
            paper.constraint_hessian(&q, &lambda).as_slice(),
            "d(G^T lambda)/dq",
        );
        close(
            generated.mass_matrix::<f64>().as_slice(),
            paper.mass_matrix::<f64>().as_slice(),
            "M = diag(M1, M2) (eq. 29)",
        );
        close(
            generated.forces(&q, &v).as_slice(),
            paper.forces(&q, &v).as_slice(),
            "f (eq. 34)",
        );
        close(
            generated.input_matrix(&q).as_slice(),
            paper.input_matrix(&q).as_slice(),
            "B^T (eq. 34)",
        );
        close(
            generated.input_jacobian(&q, &u).as_slice(),
            paper.input_jacobian(&q, &u).as_slice(),
            "d(B^T u)/dq",
        );
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        generated.rope_lengths(&q, &mut a);
        paper.rope_lengths(&q, &mut b);
        close(&a, &b, "rope lengths");
    }
    assert_eq!(NavyPlanar::INFO.coordinates, HandNavyPlanar::INFO.coordinates);
    assert_eq!(NavyPlanar::INFO.ropes, HandNavyPlanar::INFO.ropes);
}

/// The paper's printed blocks at the start (46)-(47): G1^T and G2^T of (35)
/// with L1 = 5 sqrt 3, L2 = 10, L0 = 5, x0 = 0, z0 = -5, x = 0, z = -10.
#[test]
fn constraint_jacobian_at_the_paper_start() {
    let s3 = 3f64.sqrt();
    let q = SVector::<f64, 7>::from_column_slice(&[5.0 * s3, 10.0, 5.0, 0.0, -5.0, 0.0, -10.0]);
    let (l, alpha) = (10.0, std::f64::consts::FRAC_PI_3);
    let g = NavyPlanar::default().constraint_jacobian(&q);
    // rows of G = columns of G^T in (35)
    let expected = [
        [-5.0 * s3, 0.0, 0.0, l * alpha.sin(), -5.0 + l * alpha.cos(), 0.0, 0.0],
        [0.0, 0.0, -5.0, 0.0, -5.0, 0.0, 0.0],
        [0.0, -5.0, 5.0, 0.0, 5.0, 0.0, -5.0],
    ];
    for (i, row) in expected.iter().enumerate() {
        for (j, value) in row.iter().enumerate() {
            assert!(
                (g[(i, j)] - value).abs() < 1e-12,
                "G[{i},{j}] = {} vs {value}",
                g[(i, j)]
            );
        }
    }
}

/// The macro reads the force structure off the declaration: the paper's
/// crane has gravity and winch torques only (eq. 34), constant in q and free
/// of q', so the minimal Newton matrix may skip those products.
#[test]
fn force_structure_is_read_off_the_declaration() {
    // checked when the test compiles: the flags are constants of the generated code
    const { assert!(!<NavyPlanar as CraneModel<7, 3, 2>>::FORCES_DEPEND_ON_VELOCITY) };
    const { assert!(!<NavyPlanar as CraneModel<7, 3, 2>>::FORCES_DEPEND_ON_POSITION) };
    // a hand-written model keeps the conservative defaults
    const { assert!(<HandNavyPlanar as CraneModel<7, 3, 2>>::FORCES_DEPEND_ON_VELOCITY) };
}
