//! No declared name can change a number: a planar gantry whose names mimic
//! the generated code's own (a rope length `lambda_rope` beside the
//! constraint `rope`, whose multiplier the reduced system's layout calls
//! `lambda_rope`; a trolley `s_d1`, named like a jet; `x_d1`, `q_x_d0`,
//! `u_u1_d0`, `dot_s_d1`, `t0`, `gamma`, `q`, `lambda` for coordinates,
//! inputs and parameters) gives bit for bit the numbers of its plainly
//! named twin in every generated function, the dummy-derivative system
//! included.
#![allow(non_snake_case)]

use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, DummyDerivatives, MinimalMap};

crane_macros::crane_model! {
    /// Planar gantry crane, plainly named.
    pub struct Plain {
        params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
        minimal [y | l, th] { s = y;  L = l;  x = y + l*sin(th);  z = -l*cos(th); }
    }
}

crane_macros::crane_model! {
    /// The same gantry named like the generated code: the trolley `s_d1`,
    /// the rope length `lambda_rope` (the multiplier of `rope` is
    /// `lambda_rope` in the reduced system's layout), the load `[x_d1,
    /// q_x_d0]`, the inputs `[u_u1_d0, z]`, the parameters `dot_s_d1`, `t0`,
    /// `gamma`, `q`, `lambda`, the minimal coordinates `[q_s_d1_d0 |
    /// lambda_rope_d0, dot_x]`.
    pub struct Mimic {
        params { q = 50.0, dot_s_d1 = 200.0, lambda = 0.05, t0 = 0.1, gamma = 9.81 }
        robot  [s_d1, lambda_rope]
        load   [x_d1, q_x_d0]
        inputs [u_u1_d0, z]
        kinetic = 0.5*q*dot(s_d1)^2 + 0.5*lambda/t0^2*dot(lambda_rope)^2
                + 0.5*dot_s_d1*(dot(x_d1)^2 + dot(q_x_d0)^2);
        forces { s_d1: u_u1_d0, lambda_rope: z/t0, q_x_d0: -dot_s_d1*gamma }
        constraints {
            #[rope(N = lambda_rope)]
            rope: 0.5*((x_d1 - s_d1)^2 + q_x_d0^2 - lambda_rope^2)
        }
        minimal [q_s_d1_d0 | lambda_rope_d0, dot_x] {
            s_d1 = q_s_d1_d0;  lambda_rope = lambda_rope_d0;
            x_d1 = q_s_d1_d0 + lambda_rope_d0*sin(dot_x);  q_x_d0 = -lambda_rope_d0*cos(dot_x);
        }
    }
}

#[test]
fn names_like_the_generated_ones_give_the_same_numbers() {
    let (a, b) = (Plain::new(), Mimic::new());
    assert_eq!(a.parameter_values(), b.parameter_values());
    let q = SVector::<f64, 4>::from([0.3, 5.2, 1.1, -4.9]);
    let v = SVector::<f64, 4>::from([0.1, -0.2, 0.3, 0.4]);
    let lambda = SVector::<f64, 1>::from([-39.0]);
    let u = SVector::<f64, 2>::from([40.0, -3.0]);
    assert_eq!(a.constraints(&q), b.constraints(&q));
    assert_eq!(a.constraint_jacobian(&q), b.constraint_jacobian(&q));
    assert_eq!(a.constraint_hessian(&q, &lambda), b.constraint_hessian(&q, &lambda));
    assert_eq!(a.mass_matrix::<f64>(), b.mass_matrix::<f64>());
    assert_eq!(a.forces(&q, &v), b.forces(&q, &v));
    assert_eq!(a.force_jacobians(&q, &v), b.force_jacobians(&q, &v));
    assert_eq!(a.input_matrix(&q), b.input_matrix(&q));
    assert_eq!(a.input_jacobian(&q, &u), b.input_jacobian(&q, &u));
    let (mut ropes_a, mut ropes_b) = ([0.0; 1], [0.0; 1]);
    a.rope_lengths(&q, &mut ropes_a);
    b.rope_lengths(&q, &mut ropes_b);
    assert_eq!(ropes_a, ropes_b);
    let mu = SVector::<f64, 3>::from([0.4, 5.1, 0.2]);
    let mu_dot = SVector::<f64, 3>::from([0.01, -0.02, 0.3]);
    assert_eq!(a.phi(&mu), b.phi(&mu));
    assert_eq!(a.null_space(&mu), b.null_space(&mu));
    assert_eq!(a.null_space_rate(&mu, &mu_dot), b.null_space_rate(&mu, &mu_dot));
    assert_eq!(a.map_derivatives(&mu, &mu_dot), b.map_derivatives(&mu, &mu_dot));
}

/// The reduced system reads its unknowns by position: the jets of every
/// robot coordinate, multiplier and input, with values unlike each other
/// so that two jets sharing a local would show.
#[test]
fn the_reduced_systems_agree_with_names_like_their_jets() {
    let (a, b) = (Plain::new(), Mimic::new());
    assert_eq!(
        <Plain as DummyDerivatives<4, 1, 2, 11>>::OFFSETS,
        <Mimic as DummyDerivatives<4, 1, 2, 11>>::OFFSETS
    );
    let gamma: Vec<SVector<f64, 2>> = (0..=4)
        .map(|k| SVector::from([1.1 - 0.3 * k as f64, -4.9 + 0.7 * k as f64]))
        .collect();
    let z = SVector::<f64, 11>::from_fn(|i, _| 0.5 + 1.37 * i as f64 - 0.11 * (i * i) as f64);
    let (residual_a, jacobian_a) = a.dummy_derivative_system(&gamma, &z);
    let (residual_b, jacobian_b) = b.dummy_derivative_system(&gamma, &z);
    assert_eq!(residual_a, residual_b);
    assert_eq!(jacobian_a, jacobian_b);
}
