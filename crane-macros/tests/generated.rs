//! The generated code compiles against `crane_runtime` and computes the
//! right thing: the planar crane of sect. 5.1 against the paper's matrices
//! (eqs. 29, 33-35), and every generated derivative of a deliberately
//! awkward model against central finite differences and dual numbers.
//! The minimal-coordinate map of sect. 5.1.2 (eqs. 36-40) is checked at
//! random points: `g(phi(mu)) = 0`, `G P = 0`, `P`, `P'` and `w` against
//! finite differences and dual numbers, and the paper's formulas.

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
        minimal [beta, gamma | theta, L] {           // mu1 | mu2 (eq. 39)
            let d = l*sin(gamma - beta)/sin(gamma);   // = L0, pulley to boom tip P
            L1 = l*sin(beta)/sin(gamma);  L2 = d + L;  L0 = d;     // eq. (37)
            x0 = -d*sin(alpha - beta);    z0 = -d*cos(alpha - beta);
            x  = x0 + L*sin(theta);       z  = z0 - L*cos(theta);  // eq. (38)
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
    assert_eq!(f, SVector::from([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -crane.m_l * crane.g]));
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
    assert_eq!(info.parameters, ["m_l", "J1", "J2", "r1", "r2", "alpha", "l", "g"]);
    assert_eq!(
        (NavyPlanar::N, NavyPlanar::M, NavyPlanar::A, NavyPlanar::F),
        (7, 3, 2, 4)
    );

    let mut crane = NavyPlanar::default();
    assert_eq!(
        crane.parameter_values(),
        vec![100.0, 0.1, 0.1, 0.1, 0.1, std::f64::consts::PI / 3.0, 10.0, 9.81]
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

fn assert_close<const R: usize, const C: usize>(what: &str, a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) {
    let scale = 1.0 + b.amax();
    assert!((a - b).amax() < 1e-7 * scale, "{what}:\ngenerated {a}\nnumerical {b}");
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
    assert_close("df/dq", &df_dq, &numerical_jacobian(&q, |q| model.forces(q, &v)));
    assert_close("df/dv", &df_dv, &numerical_jacobian(&v, |v| model.forces(&q, v)));
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

// --- the minimal-coordinate map of sect. 5.1.2 (eqs. 36-40)

use crane_runtime::MinimalMap;
use crane_runtime::num_dual::Dual2_64;

/// A small deterministic generator (xorshift64*), so that a failure
/// reproduces.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        lo + (hi - lo) * (bits as f64 / (1u64 << 53) as f64)
    }
}

/// `(mu, mu')` at 200 random points: `beta` in (0.2, 0.9), `gamma` in
/// (1.2, 2.2), `theta` in (-0.5, 0.5), `L` in (2, 10) m, velocities of order 1.
fn navy_samples() -> Vec<(SVector<f64, 4>, SVector<f64, 4>)> {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    (0..200)
        .map(|_| {
            let mu = SVector::from([
                rng.uniform(0.2, 0.9),
                rng.uniform(1.2, 2.2),
                rng.uniform(-0.5, 0.5),
                rng.uniform(2.0, 10.0),
            ]);
            let mu_dot = SVector::from([
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-2.0, 2.0),
            ]);
            (mu, mu_dot)
        })
        .collect()
}

/// `|a - b| <= tol (1 + |b|)` entrywise, with the largest violation in the
/// message.
#[track_caller]
fn assert_within<const R: usize, const C: usize>(what: &str, a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>, tol: f64) {
    let error = (a - b).amax() / (1.0 + b.amax());
    assert!(
        error <= tol,
        "{what}: relative error {error:.2e} > {tol:.0e}\ngenerated {a}\nexpected {b}"
    );
}

#[test]
fn navy_minimal_names_and_split() {
    assert_eq!(
        <NavyPlanar as MinimalMap<7, 3, 2, 4>>::MINIMAL_COORDINATES,
        ["beta", "gamma", "theta", "L"]
    );
    assert_eq!(NavyPlanar::MINIMAL_SPLIT, 2);
}

#[test]
fn navy_minimal_samples_give_a_real_crane() {
    // all rope lengths positive in the sampled range
    let crane = NavyPlanar::new();
    for (mu, _) in navy_samples() {
        let q = crane.phi(&mu);
        let mut ropes = [0.0; 2];
        crane.rope_lengths(&q, &mut ropes);
        let (l0, hoisted) = (q[2], q[1] - q[2]);
        assert!(ropes[0] > 0.0 && ropes[1] > 0.0 && l0 > 0.0, "mu = {mu}, q = {q}");
        assert!((hoisted - mu[3]).abs() < 1e-12, "L = L2 - L0");
    }
}

#[test]
fn navy_map_satisfies_the_constraints() {
    // eq. (7): g(phi(mu)) = 0; g is half a difference of squared lengths,
    // so its round-off is eps |q|^2
    let crane = NavyPlanar::new();
    for (mu, _) in navy_samples() {
        let q = crane.phi(&mu);
        let g = crane.constraints(&q);
        assert!(g.amax() <= 1e-12 * q.amax().powi(2), "g(phi({mu})) = {g}");
        // and G(phi(mu)) P(mu) = 0, the columns of P span the null space of G
        let gp = crane.constraint_jacobian(&q) * crane.null_space(&mu);
        let scale = crane.constraint_jacobian(&q).amax() * crane.null_space(&mu).amax();
        assert!(gp.amax() <= 1e-12 * scale, "G P at {mu}: {gp}");
    }
}

#[test]
fn navy_null_space_is_the_jacobian_of_the_map() {
    // central differences: error h^2/6 |phi'''| + eps |phi| / h, about
    // 1e-10 + 4e-10 here (|phi| < 25, third derivatives of order 10; 8e-11
    // measured), so 1e-8 relative to 1 + |P| leaves a margin of 20
    const H: f64 = 1e-5;
    let crane = NavyPlanar::new();
    for (mu, _) in navy_samples() {
        let p = crane.null_space(&mu);
        let mut numerical = SMatrix::<f64, 7, 4>::zeros();
        for k in 0..4 {
            let mut e = SVector::<f64, 4>::zeros();
            e[k] = H;
            numerical.set_column(k, &((crane.phi(&(mu + e)) - crane.phi(&(mu - e))) / (2.0 * H)));
        }
        assert_within("P", &p, &numerical, 1e-8);

        // dual numbers: exact to round-off
        for k in 0..4 {
            let mu_d: SVector<Dual64, 4> = SVector::from_fn(|i, _| Dual64::new(mu[i], if i == k { 1.0 } else { 0.0 }));
            let column = crane.phi(&mu_d).map(|x| x.eps);
            assert_within("P (dual)", &column, &p.column(k).into(), 1e-13);
        }

        // the blocks with the paper's names
        let phi = crane.phi(&mu);
        assert_eq!(crane.phi_p(&mu), phi.fixed_rows::<5>(0));
        assert_eq!(crane.phi_x(&mu), phi.fixed_rows::<2>(5));
        assert_eq!(crane.D1_phi_x(&mu), p.fixed_view::<2, 2>(5, 0));
        assert_eq!(crane.D2_phi_x(&mu), p.fixed_view::<2, 2>(5, 2));
    }
}

#[test]
fn navy_null_space_rate_is_the_derivative_of_p_along_the_motion() {
    // eq. (9): P' = d/dt P(mu(t)) = directional derivative of P along mu';
    // central differences in that direction, same error budget as for P
    // with |mu'| <= 2
    const H: f64 = 1e-5;
    let crane = NavyPlanar::new();
    for (mu, mu_dot) in navy_samples() {
        let rate = crane.null_space_rate(&mu, &mu_dot);
        let numerical = (crane.null_space(&(mu + mu_dot * H)) - crane.null_space(&(mu - mu_dot * H))) / (2.0 * H);
        assert_within("P'", &rate, &numerical, 1e-8);

        // dual numbers through the generated P: exact to round-off
        let mu_d: SVector<Dual64, 4> = SVector::from_fn(|i, _| Dual64::new(mu[i], mu_dot[i]));
        let dual = crane.null_space(&mu_d).map(|x| x.eps);
        assert_within("P' (dual)", &rate, &dual, 1e-13);
    }
}

#[test]
fn navy_w_is_the_second_directional_derivative_of_phi_x() {
    // eq. (17): w = [P' mu']_x = d^2/dt^2 phi_x(mu + t mu') at t = 0.
    // The second difference (phi_x(mu + h mu') - 2 phi_x(mu) + phi_x(mu - h mu'))/h^2
    // has error h^2/12 |phi_x''''| |mu'|^4 + 4 eps |phi_x| / h^2: with h = 1e-4,
    // |phi_x| < 25 and fourth derivatives of order 10^2 along |mu'| <= 2, that
    // is about 1e-7 + 2e-6 (3e-7 measured); the tolerance is 1e-5 relative
    // to 1 + |w|.
    const H: f64 = 1e-4;
    let crane = NavyPlanar::new();
    for (mu, mu_dot) in navy_samples() {
        let w = crane.w(&mu, &mu_dot);
        let numerical =
            (crane.phi_x(&(mu + mu_dot * H)) - crane.phi_x(&mu) * 2.0 + crane.phi_x(&(mu - mu_dot * H))) / (H * H);
        assert_within("w", &w, &numerical, 1e-5);

        // the definition via P' (a different expression tree)
        let via_rate = (crane.null_space_rate(&mu, &mu_dot) * mu_dot)
            .fixed_rows::<2>(5)
            .into_owned();
        assert_within("w = [P' mu']_x", &w, &via_rate, 1e-13);

        // second-order dual numbers along mu': exact to round-off
        let mu_d: SVector<Dual2_64, 4> = SVector::from_fn(|i, _| Dual2_64::new(mu[i], mu_dot[i], 0.0));
        let dual = crane.phi_x(&mu_d).map(|x| x.v2);
        assert_within("w (Dual2)", &w, &dual, 1e-13);
    }
}

#[test]
fn navy_d2_phi_x_is_eq_40() {
    let crane = NavyPlanar::new();
    for (mu, _) in navy_samples() {
        let [_, _, theta, l] = mu.into();
        let (s, c) = theta.sin_cos();
        #[rustfmt::skip]
        let eq40 = SMatrix::<f64, 2, 2>::from_row_slice(&[
            l * c, s,
            l * s, -c,
        ]);
        assert_within("D2 phi_x", &crane.D2_phi_x(&mu), &eq40, 1e-15);
        assert!(eq40.determinant() < 0.0, "regular: det = -L");
    }
}

#[test]
fn navy_map_is_eqs_37_and_38() {
    let crane = NavyPlanar::new();
    let (l, alpha) = (crane.l, crane.alpha);
    let mu = SVector::<f64, 4>::from([0.55, 1.7, 0.3, 6.5]);
    let [beta, gamma, theta, big_l] = mu.into();
    // as printed in the paper
    let d = l * (gamma - beta).sin() / gamma.sin();
    let eq37 = [
        l * beta.sin() / gamma.sin(),
        d + big_l,
        d,
        -d * (alpha - beta).sin(),
        -d * (alpha - beta).cos(),
    ];
    let eq38 = [
        -d * (alpha - beta).sin() + big_l * theta.sin(),
        -d * (alpha - beta).cos() - big_l * theta.cos(),
    ];
    assert_within("phi_p", &crane.phi_p(&mu), &SVector::from(eq37), 1e-15);
    assert_within("phi_x", &crane.phi_x(&mu), &SVector::from(eq38), 1e-15);

    // the paper's start (46): beta = alpha, gamma = pi/2, theta = 0, L = 5 m
    // put the pulley at (0, -5) and the load at (0, -10)
    let start = SVector::<f64, 4>::from([alpha, std::f64::consts::FRAC_PI_2, 0.0, 5.0]);
    assert_within("phi(mu0)", &crane.phi(&start), &navy_start(), 1e-15);
}

crane_model! {
    /// A trolley with a hoisted load, in minimal coordinates and `let`s whose
    /// names collide with the generated code's locals (`mu`, `mu_dot`,
    /// `dot_mu`, `out`, `t0`, `t1`).
    pub struct Trolley {
        params { m = 10.0, M = 50.0, J = 0.2, mu_dot = 9.81 }
        robot [s, Lr]
        load [x, z]
        inputs [u1, u2]
        kinetic = 0.5*M*dot(s)^2 + 0.5*J*dot(Lr)^2 + 0.5*m*(dot(x)^2 + dot(z)^2);
        forces { s: u1, Lr: u2, z: -m*mu_dot }
        constraints { rope: 0.5*((x - s)^2 + z^2 - Lr^2) }
        minimal [mu | t0, out] {
            let t1 = sin(t0);
            let dot_mu = cos(t0);
            s = mu;  Lr = out;
            x = s + Lr*t1;  z = -Lr*dot_mu;
        }
    }
}

#[test]
fn trolley_map_with_colliding_names() {
    const H: f64 = 1e-5;
    let trolley = Trolley::new();
    let mut rng = Rng(7);
    for _ in 0..100 {
        let mu = SVector::from([rng.uniform(-3.0, 3.0), rng.uniform(-1.0, 1.0), rng.uniform(1.0, 8.0)]);
        let mu_dot = SVector::from([rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]);
        let [trolley_position, angle, length] = mu.into();
        let q = trolley.phi(&mu);
        let expected = SVector::<f64, 4>::from([
            trolley_position,
            length,
            trolley_position + length * angle.sin(),
            -length * angle.cos(),
        ]);
        assert_within("phi", &q, &expected, 1e-15);
        assert!(trolley.constraints(&q).amax() < 1e-12);

        let p = trolley.null_space(&mu);
        let mut numerical = SMatrix::<f64, 4, 3>::zeros();
        for k in 0..3 {
            let mut e = SVector::<f64, 3>::zeros();
            e[k] = H;
            numerical.set_column(k, &((trolley.phi(&(mu + e)) - trolley.phi(&(mu - e))) / (2.0 * H)));
        }
        assert_within("P", &p, &numerical, 1e-8);

        let mu_d: SVector<Dual64, 3> = SVector::from_fn(|i, _| Dual64::new(mu[i], mu_dot[i]));
        let dual = trolley.null_space(&mu_d).map(|x| x.eps);
        assert_within("P'", &trolley.null_space_rate(&mu, &mu_dot), &dual, 1e-13);
        let mu_d: SVector<Dual2_64, 3> = SVector::from_fn(|i, _| Dual2_64::new(mu[i], mu_dot[i], 0.0));
        let w = trolley.phi_x(&mu_d).map(|x| x.v2);
        assert_within("w", &trolley.w(&mu, &mu_dot), &w, 1e-13);
    }
    assert_eq!(Trolley::MINIMAL_SPLIT, 1);
}

// --- the values of `Awkward` against hand-written formulas at random points

/// `g`, `f`, `B^T`, `M` and the rope length of `Awkward`, written out by hand
/// from its declaration: `q = [q, v, out, t0 | u, lambda]`, the forces
/// section split into the input-free part `f` and the input matrix `B^T`
/// (`a` and `b` multiply `cos(v)`, `1/(2 + q^2)`, `sqrt(1 + out^2)`,
/// `exp(-t0)`), and `M` the Hessian of the kinetic energy in the velocities.
#[test]
fn awkward_values_match_hand_written_formulas_at_random_points() {
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};
    let crane = Awkward::default();
    let (m, c, k, w, t) = (
        2.0,
        0.3,
        2f64.sqrt() * (-1f64).exp(),
        1f64.atan2(2.0).powi(2),
        3f64.ln(),
    );
    assert_eq!(crane.parameter_values(), vec![m, c, k, w, t]);
    let mut rng = SmallRng::seed_from_u64(99);
    for _ in 0..500 {
        // inside the functions' domains: q + v > 0 ((q + v)^2.5), u > 0 (u^(1/3)), t0 != 0
        let qq: f64 = rng.random_range(0.1..2.0);
        let vv: f64 = rng.random_range(-0.05..2.0);
        let [out, t0, u, lam] = [
            rng.random_range(-2.0..2.0),
            rng.random_range(0.3..2.0),
            rng.random_range(0.1..3.0),
            rng.random_range(-2.0..2.0),
        ];
        let z = SVector::from([qq, vv, out, t0, u, lam]);
        let dz = SVector::from_fn(|_, _| rng.random_range(-2.0..2.0));
        let (dq, dv, dlam) = (dz[0], dz[1], dz[5]);
        let close = |a: f64, b: f64, what: &str| {
            assert!((a - b).abs() <= 1e-13 * b.abs().max(1.0), "{what}: {a} vs {b} at {z}")
        };
        let g = crane.constraints(&z);
        close(
            g[0],
            0.5 * ((u - qq).powi(2) + (lam - vv).powi(2) - (out + 1.0).powi(2)),
            "c1",
        );
        close(
            g[1],
            (2.0 + qq * qq).ln() - vv * t0.sin() + out.atan2(2.0 + u * u),
            "c2",
        );
        close(
            g[2],
            (qq + vv).powf(2.5) - (out / 3.0).exp() * t0.powi(-2) + u.cbrt() * lam,
            "c3",
        );
        let f = crane.forces(&z, &dz);
        let expected_f = [
            -c * dq * out.sin(),
            -k * dv.powi(3),
            0.0,
            w * u.atan2(1.0 + vv * vv),
            0.0,
            -m * 9.81 + c * (lam / 4.0).tan() * dlam,
        ];
        for (i, e) in expected_f.iter().enumerate() {
            close(f[i], *e, &format!("f[{i}]"));
        }
        let bt = crane.input_matrix(&z);
        let mut expected_bt = [[0.0; 2]; 6];
        expected_bt[0] = [vv.cos(), 1.0 / (2.0 + qq * qq)];
        expected_bt[1] = [0.0, (1.0 + out * out).sqrt()];
        expected_bt[3] = [(-t0).exp(), 0.0];
        for i in 0..6 {
            for j in 0..2 {
                close(bt[(i, j)], expected_bt[i][j], &format!("B^T[{i}][{j}]"));
            }
        }
        let mut lengths = [0.0];
        crane.rope_lengths(&z, &mut lengths);
        close(lengths[0], ((u - qq).powi(2) + (lam - vv).powi(2)).sqrt(), "rope S");
    }
    let mass: SMatrix<f64, 6, 6> = crane.mass_matrix();
    let mut expected = SMatrix::<f64, 6, 6>::zeros();
    expected[(0, 0)] = m;
    expected[(0, 1)] = c;
    expected[(1, 0)] = c;
    expected[(1, 1)] = t;
    expected[(1, 2)] = t;
    expected[(2, 1)] = t;
    expected[(2, 2)] = t;
    expected[(3, 3)] = 0.5;
    expected[(4, 4)] = m;
    expected[(5, 5)] = m;
    assert!((mass - expected).amax() < 1e-15, "{mass} vs {expected}");
}
