/// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
///
/// Declared with `crane_model!`: n = 7 coordinates, m = 3 constraints, a = 2 inputs, f = n - m = 4 degrees of freedom.
///
/// Internal dynamics (structural, eqs. 22a-d): none, the load path fixes every state (flat). The inputs depend on the load path's derivatives up to order 4: a path continuous only to a lower order gives them jumps or impulses.
#[derive(
    ::core::fmt::Debug,
    ::core::clone::Clone,
    ::core::marker::Copy,
    ::core::cmp::PartialEq
)]
#[allow(non_snake_case)]
pub struct NavyPlanar {
    /// Parameter `m_l`, default `100.0`.
    pub m_l: f64,
    /// Parameter `J1`, default `0.1`.
    pub J1: f64,
    /// Parameter `J2`, default `0.1`.
    pub J2: f64,
    /// Parameter `r1`, default `0.1`.
    pub r1: f64,
    /// Parameter `r2`, default `0.1`.
    pub r2: f64,
    /// Parameter `alpha`, default `PI / 3.0`.
    pub alpha: f64,
    /// Parameter `l`, default `10.0`.
    pub l: f64,
    /// Parameter `g`, default `9.81`.
    pub g: f64,
}
impl ::core::default::Default for NavyPlanar {
    fn default() -> Self {
        Self {
            m_l: 100.0,
            J1: 0.1,
            J2: 0.1,
            r1: 0.1,
            r2: 0.1,
            alpha: ::core::f64::consts::PI / 3.0,
            l: 10.0,
            g: 9.81,
        }
    }
}
const _: () = {
    use ::crane_runtime as __crane_runtime;
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal
    )]
    impl NavyPlanar {
        /// Number of redundant coordinates `n` in `q = [p; x]` (eq. 2): robot coordinates `L1`, `L2`, `L0`, `x0`, `z0`, load coordinates `x`, `z`.
        pub const N: usize = 7;
        /// Number of holonomic constraints `m` (eq. 1b): `rope1`, `rope0`, `hoist`.
        pub const M: usize = 3;
        /// Number of inputs `a` (eq. 1a), equal to the number of load coordinates prescribed by `x = gamma(t)` (eq. 1c): `u1`, `u2`.
        pub const A: usize = 2;
        /// Degrees of freedom `f = n - m`.
        pub const F: usize = 4;
        /// The crane with the declared default parameters.
        pub fn new() -> Self {
            <Self as ::core::default::Default>::default()
        }
        /// Constraint functions `g(q)` (eq. 1b).
        pub fn g<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 3> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let L1 = q[0];
            let L2 = q[1];
            let L0 = q[2];
            let x0 = q[3];
            let z0 = q[4];
            let x = q[5];
            let z = q[6];
            let mut out = __crane_runtime::nalgebra::SVector::<T, 3>::zeros();
            out[0] = ((x0 + l * alpha.sin()).powi(2) + (z0 + l * alpha.cos()).powi(2)
                - L1.powi(2)) * 0.5;
            out[1] = (x0.powi(2) + z0.powi(2) - L0.powi(2)) * 0.5;
            out[2] = ((x - x0).powi(2) + (z - z0).powi(2) - (L2 - L0).powi(2)) * 0.5;
            out
        }
        /// `G1 = dg/dp`, the robot block of the constraint Jacobian `G = [G1 G2]`
        /// (eq. 3).
        pub fn G1<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 5> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let L1 = q[0];
            let L2 = q[1];
            let L0 = q[2];
            let x0 = q[3];
            let z0 = q[4];
            let x = q[5];
            let z = q[6];
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 3, 5>::zeros();
            out[(0, 0)] = -L1;
            out[(0, 3)] = x0 + l * alpha.sin();
            out[(0, 4)] = z0 + l * alpha.cos();
            out[(1, 2)] = -L0;
            out[(1, 3)] = x0;
            out[(1, 4)] = z0;
            out[(2, 1)] = L0 - L2;
            out[(2, 2)] = L2 - L0;
            out[(2, 3)] = x0 - x;
            out[(2, 4)] = z0 - z;
            out
        }
        /// `G2 = dg/dx`, the load block of the constraint Jacobian `G = [G1 G2]`
        /// (eq. 3).
        pub fn G2<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 2> {
            let x0 = q[3];
            let z0 = q[4];
            let x = q[5];
            let z = q[6];
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 3, 2>::zeros();
            out[(2, 0)] = x - x0;
            out[(2, 1)] = z - z0;
            out
        }
        /// Robot block `M1` of the constant mass matrix (eq. 11a), from the kinetic energy `T = 1/2 q'^T M q'` (eq. 28).
        /// `M` is block diagonal, `M = diag(M1, M2)`.
        pub fn M1<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 5, 5> {
            let J1 = T::from(self.J1);
            let J2 = T::from(self.J2);
            let r1 = T::from(self.r1);
            let r2 = T::from(self.r2);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 5, 5>::zeros();
            out[(0, 0)] = J1 / r1.powi(2);
            out[(1, 1)] = J2 / r2.powi(2);
            out
        }
        /// Load block `M2` of the constant mass matrix (eq. 11a).
        /// `M` is block diagonal, `M = diag(M1, M2)`.
        pub fn M2<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let m_l = T::from(self.m_l);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            out[(0, 0)] = m_l;
            out[(1, 1)] = m_l;
            out
        }
        /// Applied forces on the robot coordinates without the inputs, `f1(q, q')`
        /// (eq. 11b).
        pub fn f1<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 5> {
            __crane_runtime::nalgebra::SVector::<T, 5>::zeros()
        }
        /// Applied forces on the load coordinates, `f2(q, q')` (eq. 11b).
        pub fn f2<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let m_l = T::from(self.m_l);
            let g = T::from(self.g);
            let mut out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            out[1] = -m_l * g;
            out
        }
        /// Input matrix `B1^T(q)`: generalized force on the robot coordinates per
        /// unit input (eq. 11c).
        /// The load rows of `B^T = [B1^T; 0]` are zero.
        pub fn B1T<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 5, 2> {
            let r1 = T::from(self.r1);
            let r2 = T::from(self.r2);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 5, 2>::zeros();
            out[(0, 0)] = r1.recip();
            out[(1, 1)] = r2.recip();
            out
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal
    )]
    impl __crane_runtime::CraneModel<7, 3, 2> for NavyPlanar {
        const INFO: __crane_runtime::ModelInfo = __crane_runtime::ModelInfo {
            name: "NavyPlanar",
            description: "Planar US Navy crane with massless main pulley (paper, sect. 5.1).",
            coordinates: &["L1", "L2", "L0", "x0", "z0", "x", "z"],
            inputs: &["u1", "u2"],
            constraints: &["rope1", "rope0", "hoist"],
            ropes: &[
                __crane_runtime::Rope {
                    tension: "N1",
                    constraint: 0,
                },
                __crane_runtime::Rope {
                    tension: "N2",
                    constraint: 2,
                },
            ],
            parameters: &["m_l", "J1", "J2", "r1", "r2", "alpha", "l", "g"],
            positive: &[],
        };
        const FORCES_DEPEND_ON_VELOCITY: bool = false;
        const FORCES_DEPEND_ON_POSITION: bool = false;
        const STRUCTURE: ::core::option::Option<__crane_runtime::Structure> = ::core::option::Option::Some(__crane_runtime::Structure {
            dimension: 0,
            unknowns: &[2, 2, 2, 2, 2, 4, 4, 2, 2, 2, 0, 0],
            equations: &[0, 0, 2, 2, 2, 2, 2, 2, 2, 2, 4, 4],
        });
        fn parameter_values(&self) -> ::std::vec::Vec<f64> {
            ::std::vec![
                self.m_l, self.J1, self.J2, self.r1, self.r2, self.alpha, self.l, self.g
            ]
        }
        fn set_parameter(
            &mut self,
            name: &str,
            value: f64,
        ) -> ::core::result::Result<(), __crane_runtime::UnknownParameter> {
            match name {
                "m_l" => self.m_l = value,
                "J1" => self.J1 = value,
                "J2" => self.J2 = value,
                "r1" => self.r1 = value,
                "r2" => self.r2 = value,
                "alpha" => self.alpha = value,
                "l" => self.l = value,
                "g" => self.g = value,
                _ => {
                    return ::core::result::Result::Err(__crane_runtime::UnknownParameter {
                        name: ::std::string::String::from(name),
                        known: ::std::string::String::from(
                            "m_l, J1, J2, r1, r2, alpha, l, g",
                        ),
                    });
                }
            }
            ::core::result::Result::Ok(())
        }
        fn constraints<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 3> {
            self.g(q)
        }
        fn constraint_jacobian<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 7> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let L1 = q[0];
            let L2 = q[1];
            let L0 = q[2];
            let x0 = q[3];
            let z0 = q[4];
            let x = q[5];
            let z = q[6];
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 3, 7>::zeros();
            out[(0, 0)] = -L1;
            out[(0, 3)] = x0 + l * alpha.sin();
            out[(0, 4)] = z0 + l * alpha.cos();
            out[(1, 2)] = -L0;
            out[(1, 3)] = x0;
            out[(1, 4)] = z0;
            out[(2, 1)] = L0 - L2;
            out[(2, 2)] = L2 - L0;
            out[(2, 3)] = x0 - x;
            out[(2, 4)] = z0 - z;
            out[(2, 5)] = x - x0;
            out[(2, 6)] = z - z0;
            out
        }
        fn constraint_hessian<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            lambda: &__crane_runtime::nalgebra::SVector<T, 3>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            let t0 = lambda[0] + lambda[1] + lambda[2];
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            out[(0, 0)] = -lambda[0];
            out[(1, 1)] = -lambda[2];
            out[(1, 2)] = lambda[2];
            out[(2, 1)] = lambda[2];
            out[(2, 2)] = -lambda[2] - lambda[1];
            out[(3, 3)] = t0;
            out[(3, 5)] = -lambda[2];
            out[(4, 4)] = t0;
            out[(4, 6)] = -lambda[2];
            out[(5, 3)] = -lambda[2];
            out[(5, 5)] = lambda[2];
            out[(6, 4)] = -lambda[2];
            out[(6, 6)] = lambda[2];
            out
        }
        fn mass_matrix<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            let m_l = T::from(self.m_l);
            let J1 = T::from(self.J1);
            let J2 = T::from(self.J2);
            let r1 = T::from(self.r1);
            let r2 = T::from(self.r2);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            out[(0, 0)] = J1 / r1.powi(2);
            out[(1, 1)] = J2 / r2.powi(2);
            out[(5, 5)] = m_l;
            out[(6, 6)] = m_l;
            out
        }
        fn forces<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 7> {
            let m_l = T::from(self.m_l);
            let g = T::from(self.g);
            let mut out = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            out[6] = -m_l * g;
            out
        }
        fn force_jacobians<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> (
            __crane_runtime::nalgebra::SMatrix<T, 7, 7>,
            __crane_runtime::nalgebra::SMatrix<T, 7, 7>,
        ) {
            let df_dq = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            let df_dv = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            (df_dq, df_dv)
        }
        fn input_matrix<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 2> {
            let r1 = T::from(self.r1);
            let r2 = T::from(self.r2);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 7, 2>::zeros();
            out[(0, 0)] = r1.recip();
            out[(1, 1)] = r2.recip();
            out
        }
        fn input_jacobian<T: __crane_runtime::Scalar>(
            &self,
            q: &__crane_runtime::nalgebra::SVector<T, 7>,
            u: &__crane_runtime::nalgebra::SVector<T, 2>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros()
        }
        fn rope_lengths(
            &self,
            q: &__crane_runtime::nalgebra::SVector<f64, 7>,
            out: &mut [f64],
        ) {
            ::core::assert_eq!(
                out.len(), 2, "rope_lengths: `out` must have one entry per rope (2)"
            );
            let L1 = q[0];
            let L2 = q[1];
            let L0 = q[2];
            out[0] = L1;
            out[1] = L2 - L0;
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal
    )]
    impl NavyPlanar {
        /// Number of minimal coordinates in `mu1`, `f - a`: `mu = [mu1; mu2]` with `mu1` = `beta`, `gamma` and `mu2` = `theta`, `L`, chosen so that `D2 phi_x` is regular (eq. 12).
        pub const MINIMAL_SPLIT: usize = 2;
        /// Robot part `phi_p(mu)` of the map `q = phi(mu)` (eq. 6): `L1`, `L2`, `L0`, `x0`, `z0` as functions of the minimal coordinates `mu` = `beta`, `gamma`, `theta`, `L`.
        pub fn phi_p<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 5> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let L = mu[3];
            let t0 = (gamma - beta).sin();
            let t1 = gamma.sin();
            let d = l * t0 / t1;
            let t2 = alpha - beta;
            let mut out = __crane_runtime::nalgebra::SVector::<T, 5>::zeros();
            out[0] = l * beta.sin() / t1;
            out[1] = d + L;
            out[2] = d;
            out[3] = -l * t0 * t2.sin() / t1;
            out[4] = -l * t0 * t2.cos() / t1;
            out
        }
        /// Load part `phi_x(mu)` of the map `q = phi(mu)` (eq. 6): `x`, `z`; the servo constraints read `phi_x(mu) = gamma(t)` (eq. 10b).
        pub fn phi_x<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let t0 = (gamma - beta).sin();
            let t1 = gamma.sin();
            let t2 = alpha - beta;
            let mut out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            out[0] = L * theta.sin() - l * t0 * t2.sin() / t1;
            out[1] = -l * t0 * t2.cos() / t1 - L * theta.cos();
            out
        }
        /// `D1 phi_x = d phi_x / d mu1` (eqs. 15-16): the load rows of `P = D phi` in
        /// the columns of `mu1`.
        pub fn D1_phi_x<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let t0 = gamma - beta;
            let t1 = t0.sin();
            let t2 = gamma.sin();
            let t3 = alpha - beta;
            let t4 = t3.sin();
            let t5 = t3.cos();
            let t6 = gamma.cos();
            let t7 = t2.powi(-2);
            let t8 = t0.cos();
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            out[(0, 0)] = l * t1 * t5 / t2 + l * t4 * t8 / t2;
            out[(0, 1)] = l * t1 * t4 * t6 * t7 - l * t4 * t8 / t2;
            out[(1, 0)] = l * t5 * t8 / t2 - l * t1 * t4 / t2;
            out[(1, 1)] = l * t1 * t5 * t6 * t7 - l * t5 * t8 / t2;
            out
        }
        /// `D2 phi_x = d phi_x / d mu2` (eqs. 12, 15-16): the load rows of `P = D phi`
        /// in the columns of `mu2`; must be regular.
        pub fn D2_phi_x<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let theta = mu[2];
            let L = mu[3];
            let t0 = theta.sin();
            let t1 = theta.cos();
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            out[(0, 0)] = L * t1;
            out[(0, 1)] = t0;
            out[(1, 0)] = L * t0;
            out[(1, 1)] = -t1;
            out
        }
        /// `w = d/dt[D1 phi_x] mu1' + d/dt[D2 phi_x] mu2^` (eq. 17), with
        /// `mu_dot = [mu1'; mu2^]`: the load rows of `P'(mu, mu') mu'`, the second
        /// directional derivative of `phi_x` along `mu'`.
        pub fn w<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let dot_beta = mu_dot[0];
            let dot_gamma = mu_dot[1];
            let dot_theta = mu_dot[2];
            let dot_L = mu_dot[3];
            let t0 = gamma - beta;
            let t1 = t0.sin();
            let t2 = gamma.sin();
            let t3 = alpha - beta;
            let t4 = t3.sin();
            let t5 = t3.cos();
            let t6 = theta.sin();
            let t7 = theta.cos();
            let t8 = gamma.cos();
            let t9 = t2.powi(-2);
            let t10 = t0.cos();
            let t11 = t2.powi(-3);
            let t12 = t8.powi(2);
            let t13 = dot_beta.powi(2);
            let t14 = dot_gamma.powi(2);
            let t15 = dot_theta.powi(2);
            let mut out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            out[0] = (l * t1 * t4 * 2.0 / t2 - l * t5 * t10 * 2.0 / t2) * t13
                + dot_beta * dot_gamma
                    * (l * t5 * t10 / t2 - l * t1 * t4 / t2 - l * t1 * t5 * t8 * t9
                        - l * t4 * t8 * t9 * t10) * 2.0
                + (l * t4 * t8 * t9 * t10 * 2.0 - l * t1 * t4 * t11 * t12 * 2.0) * t14
                - L * t6 * t15 + t7 * dot_theta * dot_L * 2.0;
            out[1] = (l * t1 * t5 * 2.0 / t2 + l * t4 * t10 * 2.0 / t2) * t13
                + dot_beta * dot_gamma
                    * (l * t1 * t4 * t8 * t9 - l * t1 * t5 / t2 - l * t4 * t10 / t2
                        - l * t5 * t8 * t9 * t10) * 2.0
                + (l * t5 * t8 * t9 * t10 * 2.0 - l * t1 * t5 * t11 * t12 * 2.0) * t14
                + L * t7 * t15 + t6 * dot_theta * dot_L * 2.0;
            out
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal
    )]
    impl __crane_runtime::MinimalMap<7, 3, 2, 4> for NavyPlanar {
        const MINIMAL_COORDINATES: &'static [&'static str] = &[
            "beta",
            "gamma",
            "theta",
            "L",
        ];
        /// The map `q = phi(mu)` (eq. 6), as declared:
        ///
        /// ```text
        /// let d = l * sin(gamma - beta) / sin(gamma)
        /// L1 = l * sin(beta) / sin(gamma)
        /// L2 = d + L
        /// L0 = d
        /// x0 = -d * sin(alpha - beta)
        /// z0 = -d * cos(alpha - beta)
        /// x = x0 + L * sin(theta)
        /// z = z0 - L * cos(theta)
        /// ```
        fn phi<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 7> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let t0 = (gamma - beta).sin();
            let t1 = gamma.sin();
            let d = l * t0 / t1;
            let t2 = alpha - beta;
            let t3 = -l * t0 * t2.sin() / t1;
            let t4 = -l * t0 * t2.cos() / t1;
            let mut out = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            out[0] = l * beta.sin() / t1;
            out[1] = d + L;
            out[2] = d;
            out[3] = t3;
            out[4] = t4;
            out[5] = t3 + L * theta.sin();
            out[6] = t4 - L * theta.cos();
            out
        }
        /// `P = D phi(mu)` (eq. 8).
        fn null_space<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 4> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let t0 = gamma - beta;
            let t1 = t0.sin();
            let t2 = gamma.sin();
            let t3 = alpha - beta;
            let t4 = t3.sin();
            let t5 = t3.cos();
            let t6 = theta.sin();
            let t7 = theta.cos();
            let t8 = gamma.cos();
            let t9 = t2.powi(-2);
            let t10 = t0.cos();
            let t11 = -l * t10 / t2;
            let t12 = l * t10 / t2 - l * t1 * t8 * t9;
            let t13 = l * t1 * t5 / t2 + l * t4 * t10 / t2;
            let t14 = l * t1 * t4 * t8 * t9 - l * t4 * t10 / t2;
            let t15 = l * t5 * t10 / t2 - l * t1 * t4 / t2;
            let t16 = l * t1 * t5 * t8 * t9 - l * t5 * t10 / t2;
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 7, 4>::zeros();
            out[(0, 0)] = l * beta.cos() / t2;
            out[(0, 1)] = -l * beta.sin() * t8 * t9;
            out[(1, 0)] = t11;
            out[(1, 1)] = t12;
            out[(1, 3)] = T::from(1.0);
            out[(2, 0)] = t11;
            out[(2, 1)] = t12;
            out[(3, 0)] = t13;
            out[(3, 1)] = t14;
            out[(4, 0)] = t15;
            out[(4, 1)] = t16;
            out[(5, 0)] = t13;
            out[(5, 1)] = t14;
            out[(5, 2)] = L * t7;
            out[(5, 3)] = t6;
            out[(6, 0)] = t15;
            out[(6, 1)] = t16;
            out[(6, 2)] = L * t6;
            out[(6, 3)] = -t7;
            out
        }
        /// `P' = sum_k dP/dmu_k mu_k'` (eq. 9).
        fn null_space_rate<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 4> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let dot_beta = mu_dot[0];
            let dot_gamma = mu_dot[1];
            let dot_theta = mu_dot[2];
            let dot_L = mu_dot[3];
            let t0 = gamma - beta;
            let t1 = t0.sin();
            let t2 = gamma.sin();
            let t3 = beta.sin();
            let t4 = alpha - beta;
            let t5 = t4.sin();
            let t6 = t4.cos();
            let t7 = theta.sin();
            let t8 = theta.cos();
            let t9 = gamma.cos();
            let t10 = beta.cos();
            let t11 = t2.powi(-2);
            let t12 = t0.cos();
            let t13 = t2.powi(-3);
            let t14 = t9.powi(2);
            let t15 = l * t1 / t2 + l * t9 * t11 * t12;
            let t16 = dot_gamma * t15 - l * t1 * dot_beta / t2;
            let t17 = dot_beta * t15
                + dot_gamma * (l * t1 * t13 * t14 * 2.0 - l * t9 * t11 * t12 * 2.0);
            let t18 = l * t6 * t12 / t2 - l * t1 * t5 / t2 - l * t1 * t6 * t9 * t11
                - l * t5 * t9 * t11 * t12;
            let t19 = dot_beta * (l * t1 * t5 * 2.0 / t2 - l * t6 * t12 * 2.0 / t2)
                + dot_gamma * t18;
            let t20 = dot_beta * t18
                + dot_gamma
                    * (l * t5 * t9 * t11 * t12 * 2.0 - l * t1 * t5 * t13 * t14 * 2.0);
            let t21 = l * t1 * t5 * t9 * t11 - l * t1 * t6 / t2 - l * t5 * t12 / t2
                - l * t6 * t9 * t11 * t12;
            let t22 = dot_beta * (l * t1 * t6 * 2.0 / t2 + l * t5 * t12 * 2.0 / t2)
                + dot_gamma * t21;
            let t23 = dot_beta * t21
                + dot_gamma
                    * (l * t6 * t9 * t11 * t12 * 2.0 - l * t1 * t6 * t13 * t14 * 2.0);
            let mut out = __crane_runtime::nalgebra::SMatrix::<T, 7, 4>::zeros();
            out[(0, 0)] = -l * t3 * dot_beta / t2 - l * t9 * t10 * t11 * dot_gamma;
            out[(0, 1)] = dot_gamma * (l * t3 / t2 + l * t3 * t13 * t14 * 2.0)
                - l * t9 * t10 * t11 * dot_beta;
            out[(1, 0)] = t16;
            out[(1, 1)] = t17;
            out[(2, 0)] = t16;
            out[(2, 1)] = t17;
            out[(3, 0)] = t19;
            out[(3, 1)] = t20;
            out[(4, 0)] = t22;
            out[(4, 1)] = t23;
            out[(5, 0)] = t19;
            out[(5, 1)] = t20;
            out[(5, 2)] = t8 * dot_L - L * t7 * dot_theta;
            out[(5, 3)] = t8 * dot_theta;
            out[(6, 0)] = t22;
            out[(6, 1)] = t23;
            out[(6, 2)] = L * t8 * dot_theta + t7 * dot_L;
            out[(6, 3)] = t7 * dot_theta;
            out
        }
        /// `phi`, `P`, `dP/dmu_k` and `d(P' mu')/dmu` in one pass, sharing
        /// their subexpressions: what the minimal Newton matrix needs.
        fn map_derivatives<T: __crane_runtime::Scalar>(
            &self,
            mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::MapDerivatives<T, 7, 4> {
            let alpha = T::from(self.alpha);
            let l = T::from(self.l);
            let beta = mu[0];
            let gamma = mu[1];
            let theta = mu[2];
            let L = mu[3];
            let dot_beta = mu_dot[0];
            let dot_gamma = mu_dot[1];
            let dot_theta = mu_dot[2];
            let dot_L = mu_dot[3];
            let t0 = gamma - beta;
            let t1 = t0.sin();
            let t2 = gamma.sin();
            let d = l * t1 / t2;
            let t3 = beta.sin();
            let t4 = l * t3 / t2;
            let t5 = -l * t1 / t2;
            let t6 = alpha - beta;
            let t7 = t6.sin();
            let t8 = -l * t1 * t7 / t2;
            let t9 = t6.cos();
            let t10 = -l * t1 * t9 / t2;
            let t11 = theta.sin();
            let t12 = L * t11;
            let t13 = theta.cos();
            let t14 = L * t13;
            let t15 = gamma.cos();
            let t16 = beta.cos();
            let t17 = l * t16 / t2;
            let t18 = t2.powi(-2);
            let t19 = t0.cos();
            let t20 = -l * t19 / t2;
            let t21 = l * t19 / t2 - l * t1 * t15 * t18;
            let t22 = l * t1 * t9 / t2 + l * t7 * t19 / t2;
            let t23 = -l * t7 * t19 / t2;
            let t24 = l * t1 * t7 * t15 * t18;
            let t25 = t23 + t24;
            let t26 = l * t9 * t19 / t2;
            let t27 = t8 + t26;
            let t28 = l * t1 * t9 * t15 * t18 - l * t9 * t19 / t2;
            let t29 = -l * t15 * t16 * t18;
            let t30 = t2.powi(-3);
            let t31 = t15.powi(2);
            let t32 = d + l * t15 * t18 * t19;
            let t33 = l * t1 * t30 * t31 * 2.0 - l * t15 * t18 * t19 * 2.0;
            let t34 = -l * t9 * t19 * 2.0 / t2;
            let t35 = l * t1 * t7 * 2.0 / t2 + t34;
            let t36 = t8 + t26 - l * t1 * t9 * t15 * t18 - l * t7 * t15 * t18 * t19;
            let t37 = -l * t1 * t7 * t30 * t31 * 2.0;
            let t38 = l * t7 * t15 * t18 * t19 * 2.0;
            let t39 = t37 + t38;
            let t40 = l * t1 * t9 * 2.0 / t2;
            let t41 = l * t7 * t19 * 2.0 / t2;
            let t42 = t40 + t41;
            let t43 = t10 + t23 + t24 - l * t9 * t15 * t18 * t19;
            let t44 = l * t9 * t15 * t18 * t19 * 2.0;
            let t45 = t44 - l * t1 * t9 * t30 * t31 * 2.0;
            let t46 = dot_theta.powi(2);
            let t47 = l * t3 * t15 * t18 * dot_beta;
            let t48 = t2.powi(-4);
            let t49 = t15.powi(3);
            let t50 = t20 + l * t1 * t15 * t18;
            let t51 = -l * t1 * t15 * t18 * 2.0;
            let t52 = t51 - l * t19 * t30 * t31 * 2.0;
            let t53 = dot_gamma * t52;
            let t54 = dot_beta * (l * t19 * dot_beta / t2 + dot_gamma * t50)
                + dot_gamma * (dot_beta * t50 + t53);
            let t55 = dot_beta
                * (t53 - l * t19 * dot_beta / t2 + l * t1 * t15 * t18 * dot_beta)
                + dot_gamma
                    * (dot_beta * t52
                        + dot_gamma
                            * (t51 - l * t1 * t48 * t49 * 6.0 + l * t19 * 2.0 / t2
                                + l * t19 * t30 * t31 * 6.0));
            let t56 = t40 + t41 + t44 - l * t1 * t7 * t15 * t18 * 2.0;
            let t57 = l * t1 * t7 * t15 * t18 * 2.0;
            let t58 = l * t7 * t19 * t30 * t31 * 2.0 + l * t1 * t9 * t30 * t31 * 2.0
                - l * t9 * t15 * t18 * t19 * 2.0 + t57;
            let t59 = dot_beta * t56 + dot_gamma * t58;
            let t60 = dot_beta
                * (dot_beta * (-l * t7 * t19 * 4.0 / t2 - l * t1 * t9 * 4.0 / t2)
                    + dot_gamma * t56) + dot_gamma * t59;
            let t61 = dot_beta * t59
                + dot_gamma
                    * (dot_beta * t58
                        + dot_gamma
                            * (t57 - l * t7 * t19 * 2.0 / t2
                                + l * t1 * t7 * t48 * t49 * 6.0
                                - l * t7 * t19 * t30 * t31 * 6.0));
            let t62 = l * t9 * t19 * 2.0 / t2 - l * t1 * t7 * 2.0 / t2
                - l * t1 * t9 * t15 * t18 * 2.0 - l * t7 * t15 * t18 * t19 * 2.0;
            let t63 = l * t1 * t9 * t15 * t18 * 2.0;
            let t64 = t37 + t38 + l * t9 * t19 * t30 * t31 * 2.0 + t63;
            let t65 = dot_beta * t62 + dot_gamma * t64;
            let t66 = dot_beta
                * (dot_beta * (l * t1 * t7 * 4.0 / t2 - l * t9 * t19 * 4.0 / t2)
                    + dot_gamma * t62) + dot_gamma * t65;
            let t67 = dot_beta * t65
                + dot_gamma
                    * (dot_beta * t64
                        + dot_gamma
                            * (t34 + t63 + l * t1 * t9 * t48 * t49 * 6.0
                                - l * t9 * t19 * t30 * t31 * 6.0));
            let mut phi = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            phi[0] = t4;
            phi[1] = d + L;
            phi[2] = d;
            phi[3] = t8;
            phi[4] = t10;
            phi[5] = t8 + t12;
            phi[6] = t10 - L * t13;
            let mut null_space = __crane_runtime::nalgebra::SMatrix::<T, 7, 4>::zeros();
            null_space[(0, 0)] = t17;
            null_space[(0, 1)] = -l * t3 * t15 * t18;
            null_space[(1, 0)] = t20;
            null_space[(1, 1)] = t21;
            null_space[(1, 3)] = T::from(1.0);
            null_space[(2, 0)] = t20;
            null_space[(2, 1)] = t21;
            null_space[(3, 0)] = t22;
            null_space[(3, 1)] = t25;
            null_space[(4, 0)] = t27;
            null_space[(4, 1)] = t28;
            null_space[(5, 0)] = t22;
            null_space[(5, 1)] = t25;
            null_space[(5, 2)] = t14;
            null_space[(5, 3)] = t11;
            null_space[(6, 0)] = t27;
            null_space[(6, 1)] = t28;
            null_space[(6, 2)] = t12;
            null_space[(6, 3)] = -t13;
            let mut curvature_jacobian = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            curvature_jacobian[(0, 0)] = dot_beta
                * (l * t3 * t15 * t18 * dot_gamma - l * t16 * dot_beta / t2)
                + dot_gamma * (t47 + dot_gamma * (t17 + l * t16 * t30 * t31 * 2.0));
            curvature_jacobian[(0, 1)] = dot_beta
                * (t47 + l * t16 * dot_gamma / t2
                    + l * t16 * dot_gamma * t30 * t31 * 2.0)
                + dot_gamma
                    * (l * t16 * dot_beta / t2 + l * t16 * dot_beta * t30 * t31 * 2.0
                        + dot_gamma
                            * (-l * t3 * t48 * t49 * 6.0 - l * t3 * t15 * t18 * 5.0));
            curvature_jacobian[(1, 0)] = t54;
            curvature_jacobian[(1, 1)] = t55;
            curvature_jacobian[(2, 0)] = t54;
            curvature_jacobian[(2, 1)] = t55;
            curvature_jacobian[(3, 0)] = t60;
            curvature_jacobian[(3, 1)] = t61;
            curvature_jacobian[(4, 0)] = t66;
            curvature_jacobian[(4, 1)] = t67;
            curvature_jacobian[(5, 0)] = t60;
            curvature_jacobian[(5, 1)] = t61;
            curvature_jacobian[(5, 2)] = dot_theta * (-L * t13 * dot_theta - t11 * dot_L)
                - t11 * dot_theta * dot_L;
            curvature_jacobian[(5, 3)] = -t11 * t46;
            curvature_jacobian[(6, 0)] = t66;
            curvature_jacobian[(6, 1)] = t67;
            curvature_jacobian[(6, 2)] = t13 * dot_theta * dot_L
                + dot_theta * (t13 * dot_L - L * t11 * dot_theta);
            curvature_jacobian[(6, 3)] = t13 * t46;
            let mut d_null_space_0 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            d_null_space_0[(0, 0)] = -l * t3 / t2;
            d_null_space_0[(0, 1)] = t29;
            d_null_space_0[(1, 0)] = t5;
            d_null_space_0[(1, 1)] = t32;
            d_null_space_0[(2, 0)] = t5;
            d_null_space_0[(2, 1)] = t32;
            d_null_space_0[(3, 0)] = t35;
            d_null_space_0[(3, 1)] = t36;
            d_null_space_0[(4, 0)] = t42;
            d_null_space_0[(4, 1)] = t43;
            d_null_space_0[(5, 0)] = t35;
            d_null_space_0[(5, 1)] = t36;
            d_null_space_0[(6, 0)] = t42;
            d_null_space_0[(6, 1)] = t43;
            let mut d_null_space_1 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            d_null_space_1[(0, 0)] = t29;
            d_null_space_1[(0, 1)] = t4 + l * t3 * t30 * t31 * 2.0;
            d_null_space_1[(1, 0)] = t32;
            d_null_space_1[(1, 1)] = t33;
            d_null_space_1[(2, 0)] = t32;
            d_null_space_1[(2, 1)] = t33;
            d_null_space_1[(3, 0)] = t36;
            d_null_space_1[(3, 1)] = t39;
            d_null_space_1[(4, 0)] = t43;
            d_null_space_1[(4, 1)] = t45;
            d_null_space_1[(5, 0)] = t36;
            d_null_space_1[(5, 1)] = t39;
            d_null_space_1[(6, 0)] = t43;
            d_null_space_1[(6, 1)] = t45;
            let mut d_null_space_2 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            d_null_space_2[(5, 2)] = -L * t11;
            d_null_space_2[(5, 3)] = t13;
            d_null_space_2[(6, 2)] = t14;
            d_null_space_2[(6, 3)] = t11;
            let mut d_null_space_3 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            d_null_space_3[(5, 2)] = t13;
            d_null_space_3[(6, 2)] = t11;
            __crane_runtime::MapDerivatives {
                phi: phi,
                null_space: null_space,
                null_space_derivatives: [
                    d_null_space_0,
                    d_null_space_1,
                    d_null_space_2,
                    d_null_space_3,
                ],
                curvature_jacobian: curvature_jacobian,
            }
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal
    )]
    impl __crane_runtime::DummyDerivatives<7, 3, 2, 26> for NavyPlanar {
        const OFFSETS: &'static [u8] = &[2, 2, 2, 2, 2, 4, 4, 2, 2, 2, 0, 0];
        const PATH_ORDER: usize = 4;
        /// The residual of the dummy-derivative system and its Jacobian
        /// `d residual / d z`.
        ///
        /// Unknowns `z` in order: `L1_d0`, `L1_d1`, `L1_d2`, `L2_d0`, `L2_d1`, `L2_d2`, `L0_d0`, `L0_d1`, `L0_d2`, `x0_d0`, `x0_d1`, `x0_d2`, `z0_d0`, `z0_d1`, `z0_d2`, `lambda_rope1_d0`, `lambda_rope1_d1`, `lambda_rope1_d2`, `lambda_rope0_d0`, `lambda_rope0_d1`, `lambda_rope0_d2`, `lambda_hoist_d0`, `lambda_hoist_d1`, `lambda_hoist_d2`, `u1_d0`, `u2_d0`; equations in order: dynamics of `L1`, dynamics of `L2`, dynamics of `L0`, dynamics of `L0` (derivative 1), dynamics of `L0` (derivative 2), dynamics of `x0`, dynamics of `x0` (derivative 1), dynamics of `x0` (derivative 2), dynamics of `z0`, dynamics of `z0` (derivative 1), dynamics of `z0` (derivative 2), dynamics of `x`, dynamics of `x` (derivative 1), dynamics of `x` (derivative 2), dynamics of `z`, dynamics of `z` (derivative 1), dynamics of `z` (derivative 2), constraint `rope1`, constraint `rope1` (derivative 1), constraint `rope1` (derivative 2), constraint `rope0`, constraint `rope0` (derivative 1), constraint `rope0` (derivative 2), constraint `hoist`, constraint `hoist` (derivative 1), constraint `hoist` (derivative 2).
        fn dummy_derivative_system(
            &self,
            gamma: &[__crane_runtime::nalgebra::SVector<f64, 2>],
            z: &__crane_runtime::nalgebra::SVector<f64, 26>,
        ) -> (
            __crane_runtime::nalgebra::SVector<f64, 26>,
            __crane_runtime::nalgebra::SMatrix<f64, 26, 26>,
        ) {
            let L1_d0 = z[0];
            let L1_d1 = z[1];
            let L1_d2 = z[2];
            let L2_d0 = z[3];
            let L2_d1 = z[4];
            let L2_d2 = z[5];
            let L0_d0 = z[6];
            let L0_d1 = z[7];
            let L0_d2 = z[8];
            let x0_d0 = z[9];
            let x0_d1 = z[10];
            let x0_d2 = z[11];
            let z0_d0 = z[12];
            let z0_d1 = z[13];
            let z0_d2 = z[14];
            let x_d0 = gamma[0][0];
            let x_d1 = gamma[1][0];
            let x_d2 = gamma[2][0];
            let x_d3 = gamma[3][0];
            let x_d4 = gamma[4][0];
            let z_d0 = gamma[0][1];
            let z_d1 = gamma[1][1];
            let z_d2 = gamma[2][1];
            let z_d3 = gamma[3][1];
            let z_d4 = gamma[4][1];
            let lambda_rope1_d0 = z[15];
            let lambda_rope1_d1 = z[16];
            let lambda_rope1_d2 = z[17];
            let lambda_rope0_d0 = z[18];
            let lambda_rope0_d1 = z[19];
            let lambda_rope0_d2 = z[20];
            let lambda_hoist_d0 = z[21];
            let lambda_hoist_d1 = z[22];
            let lambda_hoist_d2 = z[23];
            let u1_d0 = z[24];
            let u2_d0 = z[25];
            let m_l = self.m_l;
            let J1 = self.J1;
            let J2 = self.J2;
            let r1 = self.r1;
            let r2 = self.r2;
            let alpha = self.alpha;
            let l = self.l;
            let g = self.g;
            let t0 = r1.powi(-2);
            let t1 = r2.powi(-2);
            let t2 = L0_d0 - L2_d0;
            let t3 = L2_d0 - L0_d0;
            let t4 = l * alpha.sin() + x0_d0;
            let t5 = x0_d0 - x_d0;
            let t6 = l * alpha.cos() + z0_d0;
            let t7 = z0_d0 - z_d0;
            let t8 = x_d0 - x0_d0;
            let t9 = z_d0 - z0_d0;
            let t10 = -lambda_rope0_d0 - lambda_hoist_d0;
            let t11 = -lambda_rope0_d1 - lambda_hoist_d1;
            let t12 = L2_d1 - L0_d1;
            let t13 = lambda_rope1_d0 + lambda_rope0_d0 + lambda_hoist_d0;
            let t14 = lambda_rope0_d1 + lambda_hoist_d1 + lambda_rope1_d1;
            let t15 = x0_d1 - x_d1;
            let t16 = z0_d1 - z_d1;
            let t17 = x_d1 - x0_d1;
            let t18 = z_d1 - z0_d1;
            let t19 = x0_d1.powi(2);
            let t20 = z0_d1.powi(2);
            let t21 = L0_d1 - L2_d1;
            let t22 = lambda_hoist_d1 * 2.0;
            let t23 = -lambda_hoist_d1 * 2.0;
            let t24 = -L0_d1 * 2.0;
            let t25 = L2_d2 - L0_d2;
            let t26 = t24 + L2_d1 * 2.0;
            let t27 = lambda_rope0_d2 + lambda_hoist_d2 + lambda_rope1_d2;
            let t28 = t22 + lambda_rope0_d1 * 2.0 + lambda_rope1_d1 * 2.0;
            let t29 = x0_d1 * 2.0;
            let t30 = x0_d2 - x_d2;
            let t31 = t29 - x_d1 * 2.0;
            let t32 = z0_d1 * 2.0;
            let t33 = z0_d2 - z_d2;
            let t34 = t32 - z_d1 * 2.0;
            let mut residual = __crane_runtime::nalgebra::SVector::<f64, 26>::zeros();
            residual[0] = J1 * t0 * L1_d2 - u1_d0 / r1 - L1_d0 * lambda_rope1_d0;
            residual[1] = J2 * t1 * L2_d2 - u2_d0 / r2 + lambda_hoist_d0 * t2;
            residual[2] = lambda_hoist_d0 * t3 - L0_d0 * lambda_rope0_d0;
            residual[3] = L2_d1 * lambda_hoist_d0 + L0_d1 * t10 - L0_d0 * lambda_rope0_d1
                + t3 * lambda_hoist_d1;
            residual[4] = L2_d1 * lambda_hoist_d1 + lambda_hoist_d0 * L2_d2 + L0_d1 * t11
                + t10 * L0_d2 - L0_d1 * lambda_rope0_d1 - L0_d0 * lambda_rope0_d2
                + lambda_hoist_d1 * t12 + t3 * lambda_hoist_d2;
            residual[5] = lambda_rope1_d0 * t4 + x0_d0 * lambda_rope0_d0
                + lambda_hoist_d0 * t5;
            residual[6] = x0_d1 * t13 - x_d1 * lambda_hoist_d0 + t4 * lambda_rope1_d1
                + x0_d0 * lambda_rope0_d1 + t5 * lambda_hoist_d1;
            residual[7] = x0_d1 * t14 + t13 * x0_d2 - x_d1 * lambda_hoist_d1
                - lambda_hoist_d0 * x_d2 + x0_d1 * lambda_rope1_d1 + t4 * lambda_rope1_d2
                + x0_d1 * lambda_rope0_d1 + x0_d0 * lambda_rope0_d2
                + lambda_hoist_d1 * t15 + t5 * lambda_hoist_d2;
            residual[8] = lambda_rope1_d0 * t6 + z0_d0 * lambda_rope0_d0
                + lambda_hoist_d0 * t7;
            residual[9] = z0_d1 * t13 - z_d1 * lambda_hoist_d0 + t6 * lambda_rope1_d1
                + z0_d0 * lambda_rope0_d1 + t7 * lambda_hoist_d1;
            residual[10] = z0_d1 * t14 + t13 * z0_d2 - z_d1 * lambda_hoist_d1
                - lambda_hoist_d0 * z_d2 + z0_d1 * lambda_rope1_d1 + t6 * lambda_rope1_d2
                + z0_d1 * lambda_rope0_d1 + z0_d0 * lambda_rope0_d2
                + lambda_hoist_d1 * t16 + t7 * lambda_hoist_d2;
            residual[11] = m_l * x_d2 + lambda_hoist_d0 * t8;
            residual[12] = x_d1 * lambda_hoist_d0 - x0_d1 * lambda_hoist_d0 + m_l * x_d3
                + t8 * lambda_hoist_d1;
            residual[13] = x_d1 * lambda_hoist_d1 + lambda_hoist_d0 * x_d2
                - x0_d1 * lambda_hoist_d1 - lambda_hoist_d0 * x0_d2 + m_l * x_d4
                + lambda_hoist_d1 * t17 + t8 * lambda_hoist_d2;
            residual[14] = m_l * z_d2 + m_l * g + lambda_hoist_d0 * t9;
            residual[15] = z_d1 * lambda_hoist_d0 - z0_d1 * lambda_hoist_d0 + m_l * z_d3
                + t9 * lambda_hoist_d1;
            residual[16] = z_d1 * lambda_hoist_d1 + lambda_hoist_d0 * z_d2
                - z0_d1 * lambda_hoist_d1 - lambda_hoist_d0 * z0_d2 + m_l * z_d4
                + lambda_hoist_d1 * t18 + t9 * lambda_hoist_d2;
            residual[17] = (t4.powi(2) + t6.powi(2) - L1_d0.powi(2)) * 0.5;
            residual[18] = x0_d1 * t4 - L1_d0 * L1_d1 + z0_d1 * t6;
            residual[19] = t19 - L1_d1.powi(2) - L1_d0 * L1_d2 + t4 * x0_d2 + t20
                + t6 * z0_d2;
            residual[20] = (x0_d0.powi(2) + z0_d0.powi(2) - L0_d0.powi(2)) * 0.5;
            residual[21] = x0_d0 * x0_d1 - L0_d0 * L0_d1 + z0_d0 * z0_d1;
            residual[22] = t19 + t20 - L0_d1.powi(2) - L0_d0 * L0_d2 + x0_d0 * x0_d2
                + z0_d0 * z0_d2;
            residual[23] = (t8.powi(2) + t9.powi(2) - t3.powi(2)) * 0.5;
            residual[24] = L2_d1 * t2 + L0_d1 * t3 + x0_d1 * t5 + z0_d1 * t7 + x_d1 * t8
                + z_d1 * t9;
            residual[25] = L2_d1 * t21 + L2_d2 * t2 + L0_d1 * t12 + t3 * L0_d2
                + x0_d1 * t15 + t5 * x0_d2 + z0_d1 * t16 + t7 * z0_d2 + x_d1 * t17
                + x_d2 * t8 + z_d1 * t18 + z_d2 * t9;
            let mut jacobian = __crane_runtime::nalgebra::SMatrix::<
                f64,
                26,
                26,
            >::zeros();
            jacobian[(0, 0)] = -lambda_rope1_d0;
            jacobian[(0, 2)] = J1 * t0;
            jacobian[(0, 15)] = -L1_d0;
            jacobian[(0, 24)] = -r1.recip();
            jacobian[(1, 3)] = -lambda_hoist_d0;
            jacobian[(1, 5)] = J2 * t1;
            jacobian[(1, 6)] = lambda_hoist_d0;
            jacobian[(1, 21)] = t2;
            jacobian[(1, 25)] = -r2.recip();
            jacobian[(2, 3)] = lambda_hoist_d0;
            jacobian[(2, 6)] = t10;
            jacobian[(2, 18)] = -L0_d0;
            jacobian[(2, 21)] = t3;
            jacobian[(3, 3)] = lambda_hoist_d1;
            jacobian[(3, 4)] = lambda_hoist_d0;
            jacobian[(3, 6)] = t11;
            jacobian[(3, 7)] = t10;
            jacobian[(3, 18)] = -L0_d1;
            jacobian[(3, 19)] = -L0_d0;
            jacobian[(3, 21)] = t12;
            jacobian[(3, 22)] = t3;
            jacobian[(4, 3)] = lambda_hoist_d2;
            jacobian[(4, 4)] = t22;
            jacobian[(4, 5)] = lambda_hoist_d0;
            jacobian[(4, 6)] = -lambda_rope0_d2 - lambda_hoist_d2;
            jacobian[(4, 7)] = t23 - lambda_rope0_d1 * 2.0;
            jacobian[(4, 8)] = t10;
            jacobian[(4, 18)] = -L0_d2;
            jacobian[(4, 19)] = t24;
            jacobian[(4, 20)] = -L0_d0;
            jacobian[(4, 21)] = t25;
            jacobian[(4, 22)] = t26;
            jacobian[(4, 23)] = t3;
            jacobian[(5, 9)] = t13;
            jacobian[(5, 15)] = t4;
            jacobian[(5, 18)] = x0_d0;
            jacobian[(5, 21)] = t5;
            jacobian[(6, 9)] = t14;
            jacobian[(6, 10)] = t13;
            jacobian[(6, 15)] = x0_d1;
            jacobian[(6, 16)] = t4;
            jacobian[(6, 18)] = x0_d1;
            jacobian[(6, 19)] = x0_d0;
            jacobian[(6, 21)] = t15;
            jacobian[(6, 22)] = t5;
            jacobian[(7, 9)] = t27;
            jacobian[(7, 10)] = t28;
            jacobian[(7, 11)] = t13;
            jacobian[(7, 15)] = x0_d2;
            jacobian[(7, 16)] = t29;
            jacobian[(7, 17)] = t4;
            jacobian[(7, 18)] = x0_d2;
            jacobian[(7, 19)] = t29;
            jacobian[(7, 20)] = x0_d0;
            jacobian[(7, 21)] = t30;
            jacobian[(7, 22)] = t31;
            jacobian[(7, 23)] = t5;
            jacobian[(8, 12)] = t13;
            jacobian[(8, 15)] = t6;
            jacobian[(8, 18)] = z0_d0;
            jacobian[(8, 21)] = t7;
            jacobian[(9, 12)] = t14;
            jacobian[(9, 13)] = t13;
            jacobian[(9, 15)] = z0_d1;
            jacobian[(9, 16)] = t6;
            jacobian[(9, 18)] = z0_d1;
            jacobian[(9, 19)] = z0_d0;
            jacobian[(9, 21)] = t16;
            jacobian[(9, 22)] = t7;
            jacobian[(10, 12)] = t27;
            jacobian[(10, 13)] = t28;
            jacobian[(10, 14)] = t13;
            jacobian[(10, 15)] = z0_d2;
            jacobian[(10, 16)] = t32;
            jacobian[(10, 17)] = t6;
            jacobian[(10, 18)] = z0_d2;
            jacobian[(10, 19)] = t32;
            jacobian[(10, 20)] = z0_d0;
            jacobian[(10, 21)] = t33;
            jacobian[(10, 22)] = t34;
            jacobian[(10, 23)] = t7;
            jacobian[(11, 9)] = -lambda_hoist_d0;
            jacobian[(11, 21)] = t8;
            jacobian[(12, 9)] = -lambda_hoist_d1;
            jacobian[(12, 10)] = -lambda_hoist_d0;
            jacobian[(12, 21)] = t17;
            jacobian[(12, 22)] = t8;
            jacobian[(13, 9)] = -lambda_hoist_d2;
            jacobian[(13, 10)] = t23;
            jacobian[(13, 11)] = -lambda_hoist_d0;
            jacobian[(13, 21)] = x_d2 - x0_d2;
            jacobian[(13, 22)] = x_d1 * 2.0 - x0_d1 * 2.0;
            jacobian[(13, 23)] = t8;
            jacobian[(14, 12)] = -lambda_hoist_d0;
            jacobian[(14, 21)] = t9;
            jacobian[(15, 12)] = -lambda_hoist_d1;
            jacobian[(15, 13)] = -lambda_hoist_d0;
            jacobian[(15, 21)] = t18;
            jacobian[(15, 22)] = t9;
            jacobian[(16, 12)] = -lambda_hoist_d2;
            jacobian[(16, 13)] = t23;
            jacobian[(16, 14)] = -lambda_hoist_d0;
            jacobian[(16, 21)] = z_d2 - z0_d2;
            jacobian[(16, 22)] = z_d1 * 2.0 - z0_d1 * 2.0;
            jacobian[(16, 23)] = t9;
            jacobian[(17, 0)] = -L1_d0;
            jacobian[(17, 9)] = t4;
            jacobian[(17, 12)] = t6;
            jacobian[(18, 0)] = -L1_d1;
            jacobian[(18, 1)] = -L1_d0;
            jacobian[(18, 9)] = x0_d1;
            jacobian[(18, 10)] = t4;
            jacobian[(18, 12)] = z0_d1;
            jacobian[(18, 13)] = t6;
            jacobian[(19, 0)] = -L1_d2;
            jacobian[(19, 1)] = -L1_d1 * 2.0;
            jacobian[(19, 2)] = -L1_d0;
            jacobian[(19, 9)] = x0_d2;
            jacobian[(19, 10)] = t29;
            jacobian[(19, 11)] = t4;
            jacobian[(19, 12)] = z0_d2;
            jacobian[(19, 13)] = t32;
            jacobian[(19, 14)] = t6;
            jacobian[(20, 6)] = -L0_d0;
            jacobian[(20, 9)] = x0_d0;
            jacobian[(20, 12)] = z0_d0;
            jacobian[(21, 6)] = -L0_d1;
            jacobian[(21, 7)] = -L0_d0;
            jacobian[(21, 9)] = x0_d1;
            jacobian[(21, 10)] = x0_d0;
            jacobian[(21, 12)] = z0_d1;
            jacobian[(21, 13)] = z0_d0;
            jacobian[(22, 6)] = -L0_d2;
            jacobian[(22, 7)] = t24;
            jacobian[(22, 8)] = -L0_d0;
            jacobian[(22, 9)] = x0_d2;
            jacobian[(22, 10)] = t29;
            jacobian[(22, 11)] = x0_d0;
            jacobian[(22, 12)] = z0_d2;
            jacobian[(22, 13)] = t32;
            jacobian[(22, 14)] = z0_d0;
            jacobian[(23, 3)] = t2;
            jacobian[(23, 6)] = t3;
            jacobian[(23, 9)] = t5;
            jacobian[(23, 12)] = t7;
            jacobian[(24, 3)] = t21;
            jacobian[(24, 4)] = t2;
            jacobian[(24, 6)] = t12;
            jacobian[(24, 7)] = t3;
            jacobian[(24, 9)] = t15;
            jacobian[(24, 10)] = t5;
            jacobian[(24, 12)] = t16;
            jacobian[(24, 13)] = t7;
            jacobian[(25, 3)] = L0_d2 - L2_d2;
            jacobian[(25, 4)] = L0_d1 * 2.0 - L2_d1 * 2.0;
            jacobian[(25, 5)] = t2;
            jacobian[(25, 6)] = t25;
            jacobian[(25, 7)] = t26;
            jacobian[(25, 8)] = t3;
            jacobian[(25, 9)] = t30;
            jacobian[(25, 10)] = t31;
            jacobian[(25, 11)] = t5;
            jacobian[(25, 12)] = t33;
            jacobian[(25, 13)] = t34;
            jacobian[(25, 14)] = t7;
            (residual, jacobian)
        }
    }
};
