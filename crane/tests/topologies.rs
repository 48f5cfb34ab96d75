//! The facade's examples `examples/gantry_3d.rs` and `examples/tower_crane.rs`
//! declare, through `crane::prelude`, the same cranes as the built-in models
//! `gantry-3d` and `tower-crane` of crane-models (which the tests in
//! crane-tests check in full). Here: the two declarations generate the same
//! model (every generated function at random points, to round-off), the
//! examples' `sample` self-tests run (these files are compiled with
//! `cfg(test)`), and each example's move runs from its start.

use crane::prelude::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

#[path = "../examples/gantry_3d.rs"]
mod gantry;
#[path = "../examples/tower_crane.rs"]
mod tower;

/// `a` and `b` evaluate alike at 200 random states (entries within 1e-12 of
/// the largest, round-off of identical expressions compiled twice).
fn assert_same_model<X, Y, const N: usize, const M: usize, const A: usize>(a: &X, b: &Y, seed: u64)
where
    X: CraneModel<N, M, A>,
    Y: CraneModel<N, M, A>,
{
    assert_eq!(X::INFO.coordinates, Y::INFO.coordinates);
    assert_eq!(X::INFO.parameters, Y::INFO.parameters);
    assert_eq!(a.parameter_values(), b.parameter_values());
    let mut rng = SmallRng::seed_from_u64(seed);
    let close = |x: &[f64], y: &[f64], what: &str| {
        let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (p, q) in x.iter().zip(y) {
            assert!((p - q).abs() <= 1e-12 * scale, "{what}: {x:?} vs {y:?}");
        }
    };
    for _ in 0..200 {
        let q = SVector::<f64, N>::from_fn(|_, _| rng.random_range(-10.0..10.0));
        let v = SVector::<f64, N>::from_fn(|_, _| rng.random_range(-2.0..2.0));
        close(a.constraints(&q).as_slice(), b.constraints(&q).as_slice(), "g");
        close(
            a.constraint_jacobian(&q).as_slice(),
            b.constraint_jacobian(&q).as_slice(),
            "G",
        );
        close(
            a.mass_matrix::<f64>().as_slice(),
            b.mass_matrix::<f64>().as_slice(),
            "M",
        );
        close(a.forces(&q, &v).as_slice(), b.forces(&q, &v).as_slice(), "f");
        close(a.input_matrix(&q).as_slice(), b.input_matrix(&q).as_slice(), "B^T");
    }
}

#[test]
fn the_gantry_example_is_the_built_in_gantry() {
    assert_same_model(
        &gantry::Gantry3d::default(),
        &crane_models::gantry_3d::Gantry3d::default(),
        7,
    );
    let crane = gantry::Gantry3d::default();
    let start = init::check_start(&crane, &gantry::path(), 0.0, &gantry::P0, None).unwrap();
    let run = simulate(&crane, gantry::path(), &start, &Options::new(0.02, gantry::TF).unwrap()).unwrap();
    assert!(run.tensions.iter().all(|&n| n > 0.0));
}

#[test]
fn the_tower_crane_example_is_the_built_in_tower_crane() {
    assert_same_model(
        &tower::TowerCrane::default(),
        &crane_models::tower_crane::TowerCrane::default(),
        11,
    );
    let crane = tower::TowerCrane::default();
    let start = init::check_start(&crane, &tower::path(), 0.0, &tower::P0, None).unwrap();
    let run = simulate(&crane, tower::path(), &start, &Options::new(0.02, tower::TF).unwrap()).unwrap();
    assert!(run.tensions.iter().all(|&n| n > 0.0));
}
