//! The generated code compiles against `crane_runtime` and computes the
//! right thing: the planar crane of sect. 5.1 against the paper's matrices
//! (eqs. 29, 33-35), and every generated derivative of a deliberately
//! awkward model against central finite differences and dual numbers.

use crane_macros::crane_model;
use crane_runtime::CraneModel;
use crane_runtime::nalgebra::{SMatrix, SVector};
use crane_runtime::num_dual::Dual64;

crane_model! {
    /// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
    pub struct NavyPlanar {
        params { m_l = 100.0, J1 = 0.1, J2 = 0.1, r1 = 0.1, r2 = 0.1,
                 alpha = PI / 3.0, l = 10.0, g = 9.81 }
        robot  [L1, L2, L0, x0, z0]      // p: the first n-a coordinates
        load   [x, z]                    // x: outputs, prescribed by gamma(t)
        inputs [u1, u2]
        kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }
        constraints {
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 + l*sin(alpha))^2 + (z0 + l*cos(alpha))^2 - L1^2),
            rope0: 0.5*(x0^2 + z0^2 - L0^2),
            #[rope(N2 = L2 - L0)]
            hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L2 - L0)^2),
        }
    }
}

crane_model! {
    /// Not a crane: every function, a coupled mass matrix, damping, a
    /// configuration-dependent input matrix, and names that collide with the
    /// generated code's locals (`q`, `v`, `u`, `out`, `t0`, `lambda`, `T`).
    pub(crate) struct Awkward {
        params {
            /// A mass.
            m = 2.0,
            c = 0.3, k = sqrt(2.0) * exp(-1), w = atan2(1, 2)^2, T = ln(3.0)
        }
        robot [q, v, out, t0]
        load [u, lambda]
        inputs [a, b]
        kinetic = 0.5*m*dot(q)^2 + c*dot(q)*dot(v) + 0.5*T*(dot(v) + dot(out))^2
                  + 0.5*m*(dot(u)^2 + dot(lambda)^2) + 0.25*dot(t0)^2;
        forces {
            q: a*cos(v) - c*dot(q)*sin(out) + b/(2 + q^2),
            v: b*sqrt(1 + out^2) - k*dot(v)^3,
            t0: a*exp(-t0) + w*atan2(u, 1 + v^2),
            lambda: -m*9.81 + c*tan(lambda/4)*dot(lambda),
        }
        constraints {
            #[rope(S = sqrt((u - q)^2 + (lambda - v)^2))]
            c1: 0.5*((u - q)^2 + (lambda - v)^2 - (out + 1)^2),
            c2: ln(2 + q^2) - v*sin(t0) + atan2(out, 2 + u^2),
            c3: (q + v)^2.5 - exp(out/3)*t0^-2 + u^(1/3) * lambda,
        }
    }
}

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// The paper's start of sect. 5.1: p0 of eq. (46) with the load at (0, -10).
fn navy_start() -> SVector<f64, 7> {
    SVector::from([5.0 * SQRT3, 10.0, 5.0, 0.0, -5.0, 0.0, -10.0])
}

#[test]
fn navy_constraints_vanish_at_the_start() {
    let crane = NavyPlanar::new();
    let g = crane.constraints(&navy_start());
    assert!(g.amax() < 1e-12, "g(q0) = {g}");
}

#[test]
fn navy_mass_matrix_is_eq_29() {
    let crane = NavyPlanar::new();
    let mass: SMatrix<f64, 7, 7> = crane.mass_matrix();
    let diagonal = [
        crane.J1 / crane.r1.powi(2),
        crane.J2 / crane.r2.powi(2),
        0.0,
        0.0,
        0.0,
        crane.m_l,
        crane.m_l,
    ];
    assert_eq!(mass, SMatrix::from_diagonal(&SVector::from(diagonal)));
    assert_eq!(mass.fixed_view::<5, 5>(0, 0), crane.M1::<f64>());
    assert_eq!(mass.fixed_view::<2, 2>(5, 5), crane.M2::<f64>());
}

#[test]
fn navy_jacobian_is_eq_35() {
    let crane = NavyPlanar::new();
    let q = SVector::<f64, 7>::from([8.1, 13.2, 4.9, 0.7, -4.6, 1.3, -11.8]);
    let [l1, l2, l0, x0, z0, x, z] = q.into();
    let (sa, ca) = crane.alpha.sin_cos();
    let l = crane.l;
    #[rustfmt::skip]
    let g1t = SMatrix::<f64, 5, 3>::from_row_slice(&[
        -l1,         0.0, 0.0,
        0.0,         0.0, l0 - l2,
        0.0,         -l0, l2 - l0,
        x0 + l * sa, x0,  x0 - x,
        z0 + l * ca, z0,  z0 - z,
    ]);
    #[rustfmt::skip]
    let g2t = SMatrix::<f64, 2, 3>::from_row_slice(&[
        0.0, 0.0, x - x0,
        0.0, 0.0, z - z0,
    ]);
    assert!((crane.G1(&q).transpose() - g1t).amax() < 1e-12);
    assert!((crane.G2(&q).transpose() - g2t).amax() < 1e-12);
    let g = crane.constraint_jacobian(&q);
    assert_eq!(g.fixed_view::<3, 5>(0, 0), crane.G1(&q));
    assert_eq!(g.fixed_view::<3, 2>(0, 5), crane.G2(&q));
}

#[test]
fn navy_forces_and_inputs_are_eq_34() {
    let crane = NavyPlanar::new();
    let q = navy_start();
    let v = SVector::<f64, 7>::from([0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.7]);
    let f = crane.forces(&q, &v);
    assert_eq!(
        f,
        SVector::from([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -crane.m_l * crane.g])
    );
    assert_eq!(f.fixed_rows::<5>(0), crane.f1(&q, &v));
    assert_eq!(f.fixed_rows::<2>(5), crane.f2(&q, &v));
    let bt = crane.input_matrix(&q);
    let mut expected = SMatrix::<f64, 7, 2>::zeros();
    expected[(0, 0)] = 1.0 / crane.r1;
    expected[(1, 1)] = 1.0 / crane.r2;
    assert_eq!(bt, expected);
    assert_eq!(bt.fixed_rows::<5>(0), crane.B1T(&q));
    let (df_dq, df_dv) = crane.force_jacobians(&q, &v);
    assert_eq!(
        (df_dq, df_dv),
        (SMatrix::<f64, 7, 7>::zeros(), SMatrix::<f64, 7, 7>::zeros())
    );
    assert_eq!(
        crane.input_jacobian(&q, &SVector::from([1.0, 2.0])),
        SMatrix::<f64, 7, 7>::zeros()
    );
}

#[test]
fn navy_info_parameters_and_ropes() {
    let info = NavyPlanar::INFO;
    assert_eq!(info.name, "NavyPlanar");
    assert_eq!(
        info.description,
        "Planar US Navy crane with massless main pulley (paper, sect. 5.1)."
    );
    assert_eq!(info.coordinates, ["L1", "L2", "L0", "x0", "z0", "x", "z"]);
    assert_eq!(info.inputs, ["u1", "u2"]);
    assert_eq!(info.constraints, ["rope1", "rope0", "hoist"]);
    assert_eq!(
        info.ropes,
        [
            crane_runtime::Rope {
                tension: "N1",
                constraint: 0
            },
            crane_runtime::Rope {
                tension: "N2",
                constraint: 2
            }
        ]
    );
    assert_eq!(
        info.parameters,
        ["m_l", "J1", "J2", "r1", "r2", "alpha", "l", "g"]
    );
    assert_eq!(
        (NavyPlanar::N, NavyPlanar::M, NavyPlanar::A, NavyPlanar::F),
        (7, 3, 2, 4)
    );

    let mut crane = NavyPlanar::default();
    assert_eq!(
        crane.parameter_values(),
        vec![
            100.0,
            0.1,
            0.1,
            0.1,
            0.1,
            std::f64::consts::PI / 3.0,
            10.0,
            9.81
        ]
    );
    crane.set_parameter("m_l", 250.0).unwrap();
    assert_eq!(crane.m_l, 250.0);
    let error = crane.set_parameter("mass", 1.0).unwrap_err();
    assert_eq!(
        error.to_string(),
        "unknown parameter `mass`; the model declares: m_l, J1, J2, r1, r2, alpha, l, g"
    );

    let mut lengths = [0.0; 2];
    crane.rope_lengths(&navy_start(), &mut lengths);
    assert_eq!(lengths, [5.0 * SQRT3, 5.0]);
}

// --- every derivative of `Awkward` against finite differences

const H: f64 = 1e-6;

fn awkward_point() -> (SVector<f64, 6>, SVector<f64, 6>) {
    let q = SVector::from([0.7, -0.4, 0.9, 1.3, 0.8, -0.6]);
    let v = SVector::from([0.3, -1.1, 0.5, 0.2, -0.7, 0.4]);
    (q, v)
}

/// Central differences of `f` at `x`, column `j` = d f / d x_j.
fn numerical_jacobian<const R: usize>(
    x: &SVector<f64, 6>,
    f: impl Fn(&SVector<f64, 6>) -> SVector<f64, R>,
) -> SMatrix<f64, R, 6> {
    let mut jac = SMatrix::<f64, R, 6>::zeros();
    for j in 0..6 {
        let mut plus = *x;
        let mut minus = *x;
        plus[j] += H;
        minus[j] -= H;
        jac.set_column(j, &((f(&plus) - f(&minus)) / (2.0 * H)));
    }
    jac
}

fn assert_close<const R: usize, const C: usize>(
    what: &str,
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
) {
    let scale = 1.0 + b.amax();
    assert!(
        (a - b).amax() < 1e-7 * scale,
        "{what}:\ngenerated {a}\nnumerical {b}"
    );
}

#[test]
fn awkward_constraint_jacobian_and_hessian() {
    let model = Awkward::new();
    let (q, _) = awkward_point();
    let g = model.constraint_jacobian(&q);
    assert_close("G", &g, &numerical_jacobian(&q, |q| model.constraints(q)));
    assert_eq!(g.fixed_view::<3, 4>(0, 0), model.G1(&q));
    assert_eq!(g.fixed_view::<3, 2>(0, 4), model.G2(&q));

    let lambda = SVector::<f64, 3>::from([0.8, -1.7, 0.45]);
    let hessian = model.constraint_hessian(&q, &lambda);
    let numerical = numerical_jacobian(&q, |q| model.constraint_jacobian(q).transpose() * lambda);
    assert_close("d(G^T lambda)/dq", &hessian, &numerical);
    assert_eq!(hessian, hessian.transpose());
}

#[test]
fn awkward_jacobian_matches_dual_numbers() {
    let model = Awkward::new();
    let (q, _) = awkward_point();
    let g = model.constraint_jacobian(&q);
    for j in 0..6 {
        let qd: SVector<Dual64, 6> = SVector::from_fn(|i, _| {
            if i == j {
                Dual64::from_re(q[i]).derivative()
            } else {
                Dual64::from_re(q[i])
            }
        });
        let gd = model.constraints(&qd);
        for k in 0..3 {
            assert!(
                (gd[k].eps - g[(k, j)]).abs() < 1e-12 * (1.0 + g[(k, j)].abs()),
                "G[{k},{j}]"
            );
            assert!((gd[k].re - model.constraints(&q)[k]).abs() < 1e-14);
        }
    }
}

#[test]
fn awkward_mass_matrix_is_the_hessian_of_the_kinetic_energy() {
    let model = Awkward::new();
    let (m, c, t) = (model.m, model.c, model.T);
    #[rustfmt::skip]
    let expected = SMatrix::<f64, 6, 6>::from_row_slice(&[
        m,   c,   0.0, 0.0, 0.0, 0.0,
        c,   t,   t,   0.0, 0.0, 0.0,
        0.0, t,   t,   0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.5, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, m,   0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, m,
    ]);
    assert_close("M", &model.mass_matrix(), &expected);
}

#[test]
fn awkward_forces_inputs_and_their_jacobians() {
    let model = Awkward::new();
    let (q, v) = awkward_point();
    let u = SVector::<f64, 2>::from([1.5, -0.8]);
    let (df_dq, df_dv) = model.force_jacobians(&q, &v);
    assert_close(
        "df/dq",
        &df_dq,
        &numerical_jacobian(&q, |q| model.forces(q, &v)),
    );
    assert_close(
        "df/dv",
        &df_dv,
        &numerical_jacobian(&v, |v| model.forces(&q, v)),
    );
    let bt_u = |q: &SVector<f64, 6>| model.input_matrix(q) * u;
    assert_close(
        "d(B^T u)/dq",
        &model.input_jacobian(&q, &u),
        &numerical_jacobian(&q, bt_u),
    );

    // the declared forces, by hand
    let [x_q, x_v, x_out, x_t0, x_u, x_lambda] = q.into();
    let [d_q, d_v, _, _, _, d_lambda] = v.into();
    let (c, k, w, m) = (model.c, model.k, model.w, model.m);
    let total = |a: f64, b: f64| {
        SVector::<f64, 6>::from([
            a * x_v.cos() - c * d_q * x_out.sin() + b / (2.0 + x_q * x_q),
            b * (1.0 + x_out * x_out).sqrt() - k * d_v.powi(3),
            0.0,
            a * (-x_t0).exp() + w * x_u.atan2(1.0 + x_v * x_v),
            0.0,
            -m * 9.81 + c * (x_lambda / 4.0).tan() * d_lambda,
        ])
    };
    let f = model.forces(&q, &v);
    assert_close("f", &f, &total(0.0, 0.0));
    let bt = model.input_matrix(&q);
    assert_close("B^T u", &(f + bt * u), &total(u[0], u[1]));
    assert_eq!(bt.fixed_rows::<4>(0), model.B1T(&q));
    assert_eq!(f.fixed_rows::<4>(0), model.f1(&q, &v));
    assert_eq!(f.fixed_rows::<2>(4), model.f2(&q, &v));
}

#[test]
fn awkward_defaults_and_rope() {
    let model = Awkward::default();
    assert_eq!(model.k, 2f64.sqrt() * (-1f64).exp());
    assert_eq!(model.w, 1f64.atan2(2.0).powf(2.0));
    assert_eq!(model.T, 3f64.ln());
    let (q, _) = awkward_point();
    let mut length = [0.0];
    model.rope_lengths(&q, &mut length);
    assert!((length[0] - ((q[4] - q[0]).powi(2) + (q[5] - q[1]).powi(2)).sqrt()).abs() < 1e-15);
    assert_eq!(
        Awkward::INFO.ropes,
        [crane_runtime::Rope {
            tension: "S",
            constraint: 0
        }]
    );
    assert_eq!(
        Awkward::INFO.description,
        "Not a crane: every function, a coupled mass matrix, damping, a"
    );
}
