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
        clippy::unreadable_literal,
        clippy::identity_op,
        clippy::erasing_op
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
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 3> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __L1 = __q[0];
            let __L2 = __q[1];
            let __L0 = __q[2];
            let __x0 = __q[3];
            let __z0 = __q[4];
            let __x = __q[5];
            let __z = __q[6];
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 3>::zeros();
            __out[0] = ((__x0 + __l * __alpha.sin()).powi(2)
                + (__z0 + __l * __alpha.cos()).powi(2) - __L1.powi(2)) * 0.5;
            __out[1] = (__x0.powi(2) + __z0.powi(2) - __L0.powi(2)) * 0.5;
            __out[2] = ((__x - __x0).powi(2) + (__z - __z0).powi(2)
                - (__L2 - __L0).powi(2)) * 0.5;
            __out
        }
        /// `G1 = dg/dp`, the robot block of the constraint Jacobian `G = [G1 G2]`
        /// (eq. 3).
        pub fn G1<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 5> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __L1 = __q[0];
            let __L2 = __q[1];
            let __L0 = __q[2];
            let __x0 = __q[3];
            let __z0 = __q[4];
            let __x = __q[5];
            let __z = __q[6];
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 3, 5>::zeros();
            __out[(0, 0)] = -__L1;
            __out[(0, 3)] = __x0 + __l * __alpha.sin();
            __out[(0, 4)] = __z0 + __l * __alpha.cos();
            __out[(1, 2)] = -__L0;
            __out[(1, 3)] = __x0;
            __out[(1, 4)] = __z0;
            __out[(2, 1)] = __L0 - __L2;
            __out[(2, 2)] = __L2 - __L0;
            __out[(2, 3)] = __x0 - __x;
            __out[(2, 4)] = __z0 - __z;
            __out
        }
        /// `G2 = dg/dx`, the load block of the constraint Jacobian `G = [G1 G2]`
        /// (eq. 3).
        pub fn G2<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 2> {
            let __x0 = __q[3];
            let __z0 = __q[4];
            let __x = __q[5];
            let __z = __q[6];
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 3, 2>::zeros();
            __out[(2, 0)] = __x - __x0;
            __out[(2, 1)] = __z - __z0;
            __out
        }
        /// Robot block `M1` of the constant mass matrix (eq. 11a), from the kinetic energy `T = 1/2 q'^T M q'` (eq. 28).
        /// `M` is block diagonal, `M = diag(M1, M2)`.
        pub fn M1<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 5, 5> {
            let __J1 = T::from(self.J1);
            let __J2 = T::from(self.J2);
            let __r1 = T::from(self.r1);
            let __r2 = T::from(self.r2);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 5, 5>::zeros();
            __out[(0, 0)] = __J1 / __r1.powi(2);
            __out[(1, 1)] = __J2 / __r2.powi(2);
            __out
        }
        /// Load block `M2` of the constant mass matrix (eq. 11a).
        /// `M` is block diagonal, `M = diag(M1, M2)`.
        pub fn M2<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let __m_l = T::from(self.m_l);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            __out[(0, 0)] = __m_l;
            __out[(1, 1)] = __m_l;
            __out
        }
        /// Applied forces on the robot coordinates without the inputs, `f1(q, q')`
        /// (eq. 11b).
        pub fn f1<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 5> {
            __crane_runtime::nalgebra::SVector::<T, 5>::zeros()
        }
        /// Applied forces on the load coordinates, `f2(q, q')` (eq. 11b).
        pub fn f2<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let __m_l = T::from(self.m_l);
            let __g = T::from(self.g);
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            __out[1] = -__m_l * __g;
            __out
        }
        /// Input matrix `B1^T(q)`: generalized force on the robot coordinates per
        /// unit input (eq. 11c).
        /// The load rows of `B^T = [B1^T; 0]` are zero.
        pub fn B1T<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 5, 2> {
            let __r1 = T::from(self.r1);
            let __r2 = T::from(self.r2);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 5, 2>::zeros();
            __out[(0, 0)] = __r1.recip();
            __out[(1, 1)] = __r2.recip();
            __out
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal,
        clippy::identity_op,
        clippy::erasing_op
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
            __name: &str,
            __value: f64,
        ) -> ::core::result::Result<(), __crane_runtime::UnknownParameter> {
            match __name {
                "m_l" => {
                    self.m_l = __value;
                    ::core::result::Result::Ok(())
                }
                "J1" => {
                    self.J1 = __value;
                    ::core::result::Result::Ok(())
                }
                "J2" => {
                    self.J2 = __value;
                    ::core::result::Result::Ok(())
                }
                "r1" => {
                    self.r1 = __value;
                    ::core::result::Result::Ok(())
                }
                "r2" => {
                    self.r2 = __value;
                    ::core::result::Result::Ok(())
                }
                "alpha" => {
                    self.alpha = __value;
                    ::core::result::Result::Ok(())
                }
                "l" => {
                    self.l = __value;
                    ::core::result::Result::Ok(())
                }
                "g" => {
                    self.g = __value;
                    ::core::result::Result::Ok(())
                }
                _ => {
                    ::core::result::Result::Err(__crane_runtime::UnknownParameter {
                        name: ::std::string::String::from(__name),
                        known: ::std::string::String::from(
                            "m_l, J1, J2, r1, r2, alpha, l, g",
                        ),
                    })
                }
            }
        }
        fn constraints<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 3> {
            self.g(__q)
        }
        fn constraint_jacobian<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 3, 7> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __L1 = __q[0];
            let __L2 = __q[1];
            let __L0 = __q[2];
            let __x0 = __q[3];
            let __z0 = __q[4];
            let __x = __q[5];
            let __z = __q[6];
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 3, 7>::zeros();
            __out[(0, 0)] = -__L1;
            __out[(0, 3)] = __x0 + __l * __alpha.sin();
            __out[(0, 4)] = __z0 + __l * __alpha.cos();
            __out[(1, 2)] = -__L0;
            __out[(1, 3)] = __x0;
            __out[(1, 4)] = __z0;
            __out[(2, 1)] = __L0 - __L2;
            __out[(2, 2)] = __L2 - __L0;
            __out[(2, 3)] = __x0 - __x;
            __out[(2, 4)] = __z0 - __z;
            __out[(2, 5)] = __x - __x0;
            __out[(2, 6)] = __z - __z0;
            __out
        }
        fn constraint_hessian<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __lambda: &__crane_runtime::nalgebra::SVector<T, 3>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            let __t0 = __lambda[0] + __lambda[1] + __lambda[2];
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            __out[(0, 0)] = -__lambda[0];
            __out[(1, 1)] = -__lambda[2];
            __out[(1, 2)] = __lambda[2];
            __out[(2, 1)] = __lambda[2];
            __out[(2, 2)] = -__lambda[2] - __lambda[1];
            __out[(3, 3)] = __t0;
            __out[(3, 5)] = -__lambda[2];
            __out[(4, 4)] = __t0;
            __out[(4, 6)] = -__lambda[2];
            __out[(5, 3)] = -__lambda[2];
            __out[(5, 5)] = __lambda[2];
            __out[(6, 4)] = -__lambda[2];
            __out[(6, 6)] = __lambda[2];
            __out
        }
        fn mass_matrix<T: __crane_runtime::Scalar>(
            &self,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            let __m_l = T::from(self.m_l);
            let __J1 = T::from(self.J1);
            let __J2 = T::from(self.J2);
            let __r1 = T::from(self.r1);
            let __r2 = T::from(self.r2);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            __out[(0, 0)] = __J1 / __r1.powi(2);
            __out[(1, 1)] = __J2 / __r2.powi(2);
            __out[(5, 5)] = __m_l;
            __out[(6, 6)] = __m_l;
            __out
        }
        fn forces<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SVector<T, 7> {
            let __m_l = T::from(self.m_l);
            let __g = T::from(self.g);
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            __out[6] = -__m_l * __g;
            __out
        }
        fn force_jacobians<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __v: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> (
            __crane_runtime::nalgebra::SMatrix<T, 7, 7>,
            __crane_runtime::nalgebra::SMatrix<T, 7, 7>,
        ) {
            let __df_dq = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            let __df_dv = __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
            (__df_dq, __df_dv)
        }
        fn input_matrix<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 2> {
            let __r1 = T::from(self.r1);
            let __r2 = T::from(self.r2);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 7, 2>::zeros();
            __out[(0, 0)] = __r1.recip();
            __out[(1, 1)] = __r2.recip();
            __out
        }
        fn input_jacobian<T: __crane_runtime::Scalar>(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<T, 7>,
            __u: &__crane_runtime::nalgebra::SVector<T, 2>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 7> {
            __crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros()
        }
        fn rope_lengths(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<f64, 7>,
            __out: &mut [f64],
        ) {
            ::core::assert_eq!(
                __out.len(), 2, "rope_lengths: `out` must have one entry per rope (2)"
            );
            let __L1 = __q[0];
            let __L2 = __q[1];
            let __L0 = __q[2];
            __out[0] = __L1;
            __out[1] = __L2 - __L0;
        }
        fn rope_tensions(
            &self,
            __q: &__crane_runtime::nalgebra::SVector<f64, 7>,
            __lambda: &__crane_runtime::nalgebra::SVector<f64, 3>,
            __out: &mut [f64],
        ) {
            ::core::assert_eq!(
                __out.len(), 2, "rope_tensions: `out` must have one entry per rope (2)"
            );
            let __L1 = __q[0];
            let __L2 = __q[1];
            let __L0 = __q[2];
            __out[0] = __L1 * __lambda[0];
            __out[1] = -__lambda[2] * (__L0 * 2.0 - __L2 * 2.0) * 0.5;
        }
        fn visit_dummy_derivatives<
            V: __crane_runtime::VisitDummyDerivatives<Self, 7, 3, 2>,
        >(
            __visitor: V,
        ) -> ::core::result::Result<V::Output, __crane_runtime::NoDummyDerivatives> {
            ::core::result::Result::Ok(__visitor.visit::<26>())
        }
        const HAS_MINIMAL_MAP: bool = true;
        fn visit_minimal_map<V: __crane_runtime::VisitMinimalMap<Self, 7, 3, 2>>(
            __visitor: V,
        ) -> ::core::option::Option<V::Output> {
            ::core::option::Option::Some(__visitor.visit::<4>())
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal,
        clippy::identity_op,
        clippy::erasing_op
    )]
    impl NavyPlanar {
        /// Number of minimal coordinates in `mu1`, `f - a`: `mu = [mu1; mu2]` with `mu1` = `beta`, `gamma` and `mu2` = `theta`, `L`, chosen so that `D2 phi_x` is regular (eq. 12).
        pub const MINIMAL_SPLIT: usize = 2;
        /// Robot part `phi_p(mu)` of the map `q = phi(mu)` (eq. 6): `L1`, `L2`, `L0`, `x0`, `z0` as functions of the minimal coordinates `mu` = `beta`, `gamma`, `theta`, `L`.
        pub fn phi_p<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 5> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __L = __mu[3];
            let __t0 = (__gamma - __beta).sin();
            let __t1 = __gamma.sin();
            let __d = __l * __t0 / __t1;
            let __t2 = __alpha - __beta;
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 5>::zeros();
            __out[0] = __l * __beta.sin() / __t1;
            __out[1] = __d + __L;
            __out[2] = __d;
            __out[3] = -__l * __t0 * __t2.sin() / __t1;
            __out[4] = -__l * __t0 * __t2.cos() / __t1;
            __out
        }
        /// Load part `phi_x(mu)` of the map `q = phi(mu)` (eq. 6): `x`, `z`; the servo constraints read `phi_x(mu) = gamma(t)` (eq. 10b).
        pub fn phi_x<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __t0 = (__gamma - __beta).sin();
            let __t1 = __gamma.sin();
            let __t2 = __alpha - __beta;
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            __out[0] = __L * __theta.sin() - __l * __t0 * __t2.sin() / __t1;
            __out[1] = -__l * __t0 * __t2.cos() / __t1 - __L * __theta.cos();
            __out
        }
        /// `D1 phi_x = d phi_x / d mu1` (eqs. 15-16): the load rows of `P = D phi` in
        /// the columns of `mu1`.
        pub fn D1_phi_x<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __t0 = __gamma - __beta;
            let __t1 = __t0.sin();
            let __t2 = __gamma.sin();
            let __t3 = __alpha - __beta;
            let __t4 = __t3.sin();
            let __t5 = __t3.cos();
            let __t6 = __gamma.cos();
            let __t7 = __t2.powi(-2);
            let __t8 = __t0.cos();
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            __out[(0, 0)] = __l * __t1 * __t5 / __t2 + __l * __t4 * __t8 / __t2;
            __out[(0, 1)] = __l * __t1 * __t4 * __t6 * __t7 - __l * __t4 * __t8 / __t2;
            __out[(1, 0)] = __l * __t5 * __t8 / __t2 - __l * __t1 * __t4 / __t2;
            __out[(1, 1)] = __l * __t1 * __t5 * __t6 * __t7 - __l * __t5 * __t8 / __t2;
            __out
        }
        /// `D2 phi_x = d phi_x / d mu2` (eqs. 12, 15-16): the load rows of `P = D phi`
        /// in the columns of `mu2`; must be regular.
        pub fn D2_phi_x<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 2, 2> {
            let __theta = __mu[2];
            let __L = __mu[3];
            let __t0 = __theta.sin();
            let __t1 = __theta.cos();
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
            __out[(0, 0)] = __L * __t1;
            __out[(0, 1)] = __t0;
            __out[(1, 0)] = __L * __t0;
            __out[(1, 1)] = -__t1;
            __out
        }
        /// `w = d/dt[D1 phi_x] mu1' + d/dt[D2 phi_x] mu2^` (eq. 17), with
        /// `mu_dot = [mu1'; mu2^]`: the load rows of `P'(mu, mu') mu'`, the second
        /// directional derivative of `phi_x` along `mu'`.
        pub fn w<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            __mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 2> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __dot_beta = __mu_dot[0];
            let __dot_gamma = __mu_dot[1];
            let __dot_theta = __mu_dot[2];
            let __dot_L = __mu_dot[3];
            let __t0 = __gamma - __beta;
            let __t1 = __t0.sin();
            let __t2 = __gamma.sin();
            let __t3 = __alpha - __beta;
            let __t4 = __t3.sin();
            let __t5 = __t3.cos();
            let __t6 = __theta.sin();
            let __t7 = __theta.cos();
            let __t8 = __gamma.cos();
            let __t9 = __t2.powi(-2);
            let __t10 = __t0.cos();
            let __t11 = __t2.powi(-3);
            let __t12 = __t8.powi(2);
            let __t13 = __dot_beta.powi(2);
            let __t14 = __dot_gamma.powi(2);
            let __t15 = __dot_theta.powi(2);
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 2>::zeros();
            __out[0] = (__l * __t1 * __t4 * 2.0 / __t2 - __l * __t5 * __t10 * 2.0 / __t2)
                * __t13
                + __dot_beta * __dot_gamma
                    * (__l * __t5 * __t10 / __t2 - __l * __t1 * __t4 / __t2
                        - __l * __t1 * __t5 * __t8 * __t9
                        - __l * __t4 * __t8 * __t9 * __t10) * 2.0
                + (__l * __t4 * __t8 * __t9 * __t10 * 2.0
                    - __l * __t1 * __t4 * __t11 * __t12 * 2.0) * __t14
                - __L * __t6 * __t15 + __t7 * __dot_theta * __dot_L * 2.0;
            __out[1] = (__l * __t1 * __t5 * 2.0 / __t2 + __l * __t4 * __t10 * 2.0 / __t2)
                * __t13
                + __dot_beta * __dot_gamma
                    * (__l * __t1 * __t4 * __t8 * __t9 - __l * __t1 * __t5 / __t2
                        - __l * __t4 * __t10 / __t2 - __l * __t5 * __t8 * __t9 * __t10)
                    * 2.0
                + (__l * __t5 * __t8 * __t9 * __t10 * 2.0
                    - __l * __t1 * __t5 * __t11 * __t12 * 2.0) * __t14
                + __L * __t7 * __t15 + __t6 * __dot_theta * __dot_L * 2.0;
            __out
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal,
        clippy::identity_op,
        clippy::erasing_op
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
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SVector<T, 7> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __t0 = (__gamma - __beta).sin();
            let __t1 = __gamma.sin();
            let __d = __l * __t0 / __t1;
            let __t2 = __alpha - __beta;
            let __t3 = -__l * __t0 * __t2.sin() / __t1;
            let __t4 = -__l * __t0 * __t2.cos() / __t1;
            let mut __out = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            __out[0] = __l * __beta.sin() / __t1;
            __out[1] = __d + __L;
            __out[2] = __d;
            __out[3] = __t3;
            __out[4] = __t4;
            __out[5] = __t3 + __L * __theta.sin();
            __out[6] = __t4 - __L * __theta.cos();
            __out
        }
        /// `P = D phi(mu)` (eq. 8).
        fn null_space<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 4> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __t0 = __gamma - __beta;
            let __t1 = __t0.sin();
            let __t2 = __gamma.sin();
            let __t3 = __alpha - __beta;
            let __t4 = __t3.sin();
            let __t5 = __t3.cos();
            let __t6 = __theta.sin();
            let __t7 = __theta.cos();
            let __t8 = __gamma.cos();
            let __t9 = __t2.powi(-2);
            let __t10 = __t0.cos();
            let __t11 = -__l * __t10 / __t2;
            let __t12 = __l * __t10 / __t2 - __l * __t1 * __t8 * __t9;
            let __t13 = __l * __t1 * __t5 / __t2 + __l * __t4 * __t10 / __t2;
            let __t14 = __l * __t1 * __t4 * __t8 * __t9 - __l * __t4 * __t10 / __t2;
            let __t15 = __l * __t5 * __t10 / __t2 - __l * __t1 * __t4 / __t2;
            let __t16 = __l * __t1 * __t5 * __t8 * __t9 - __l * __t5 * __t10 / __t2;
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 7, 4>::zeros();
            __out[(0, 0)] = __l * __beta.cos() / __t2;
            __out[(0, 1)] = -__l * __beta.sin() * __t8 * __t9;
            __out[(1, 0)] = __t11;
            __out[(1, 1)] = __t12;
            __out[(1, 3)] = T::from(1.0);
            __out[(2, 0)] = __t11;
            __out[(2, 1)] = __t12;
            __out[(3, 0)] = __t13;
            __out[(3, 1)] = __t14;
            __out[(4, 0)] = __t15;
            __out[(4, 1)] = __t16;
            __out[(5, 0)] = __t13;
            __out[(5, 1)] = __t14;
            __out[(5, 2)] = __L * __t7;
            __out[(5, 3)] = __t6;
            __out[(6, 0)] = __t15;
            __out[(6, 1)] = __t16;
            __out[(6, 2)] = __L * __t6;
            __out[(6, 3)] = -__t7;
            __out
        }
        /// `P' = sum_k dP/dmu_k mu_k'` (eq. 9).
        fn null_space_rate<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            __mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::nalgebra::SMatrix<T, 7, 4> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __dot_beta = __mu_dot[0];
            let __dot_gamma = __mu_dot[1];
            let __dot_theta = __mu_dot[2];
            let __dot_L = __mu_dot[3];
            let __t0 = __gamma - __beta;
            let __t1 = __t0.sin();
            let __t2 = __gamma.sin();
            let __t3 = __beta.sin();
            let __t4 = __alpha - __beta;
            let __t5 = __t4.sin();
            let __t6 = __t4.cos();
            let __t7 = __theta.sin();
            let __t8 = __theta.cos();
            let __t9 = __gamma.cos();
            let __t10 = __beta.cos();
            let __t11 = __t2.powi(-2);
            let __t12 = __t0.cos();
            let __t13 = __t2.powi(-3);
            let __t14 = __t9.powi(2);
            let __t15 = __l * __t1 / __t2 + __l * __t9 * __t11 * __t12;
            let __t16 = __dot_gamma * __t15 - __l * __t1 * __dot_beta / __t2;
            let __t17 = __dot_beta * __t15
                + __dot_gamma
                    * (__l * __t1 * __t13 * __t14 * 2.0
                        - __l * __t9 * __t11 * __t12 * 2.0);
            let __t18 = __l * __t6 * __t12 / __t2 - __l * __t1 * __t5 / __t2
                - __l * __t1 * __t6 * __t9 * __t11 - __l * __t5 * __t9 * __t11 * __t12;
            let __t19 = __dot_beta
                * (__l * __t1 * __t5 * 2.0 / __t2 - __l * __t6 * __t12 * 2.0 / __t2)
                + __dot_gamma * __t18;
            let __t20 = __dot_beta * __t18
                + __dot_gamma
                    * (__l * __t5 * __t9 * __t11 * __t12 * 2.0
                        - __l * __t1 * __t5 * __t13 * __t14 * 2.0);
            let __t21 = __l * __t1 * __t5 * __t9 * __t11 - __l * __t1 * __t6 / __t2
                - __l * __t5 * __t12 / __t2 - __l * __t6 * __t9 * __t11 * __t12;
            let __t22 = __dot_beta
                * (__l * __t1 * __t6 * 2.0 / __t2 + __l * __t5 * __t12 * 2.0 / __t2)
                + __dot_gamma * __t21;
            let __t23 = __dot_beta * __t21
                + __dot_gamma
                    * (__l * __t6 * __t9 * __t11 * __t12 * 2.0
                        - __l * __t1 * __t6 * __t13 * __t14 * 2.0);
            let mut __out = __crane_runtime::nalgebra::SMatrix::<T, 7, 4>::zeros();
            __out[(0, 0)] = -__l * __t3 * __dot_beta / __t2
                - __l * __t9 * __t10 * __t11 * __dot_gamma;
            __out[(0, 1)] = __dot_gamma
                * (__l * __t3 / __t2 + __l * __t3 * __t13 * __t14 * 2.0)
                - __l * __t9 * __t10 * __t11 * __dot_beta;
            __out[(1, 0)] = __t16;
            __out[(1, 1)] = __t17;
            __out[(2, 0)] = __t16;
            __out[(2, 1)] = __t17;
            __out[(3, 0)] = __t19;
            __out[(3, 1)] = __t20;
            __out[(4, 0)] = __t22;
            __out[(4, 1)] = __t23;
            __out[(5, 0)] = __t19;
            __out[(5, 1)] = __t20;
            __out[(5, 2)] = __t8 * __dot_L - __L * __t7 * __dot_theta;
            __out[(5, 3)] = __t8 * __dot_theta;
            __out[(6, 0)] = __t22;
            __out[(6, 1)] = __t23;
            __out[(6, 2)] = __L * __t8 * __dot_theta + __t7 * __dot_L;
            __out[(6, 3)] = __t7 * __dot_theta;
            __out
        }
        /// `phi`, `P`, `dP/dmu_k` and `d(P' mu')/dmu` in one pass, sharing
        /// their subexpressions: what the minimal Newton matrix needs.
        fn map_derivatives<T: __crane_runtime::Scalar>(
            &self,
            __mu: &__crane_runtime::nalgebra::SVector<T, 4>,
            __mu_dot: &__crane_runtime::nalgebra::SVector<T, 4>,
        ) -> __crane_runtime::MapDerivatives<T, 7, 4> {
            let __alpha = T::from(self.alpha);
            let __l = T::from(self.l);
            let __beta = __mu[0];
            let __gamma = __mu[1];
            let __theta = __mu[2];
            let __L = __mu[3];
            let __dot_beta = __mu_dot[0];
            let __dot_gamma = __mu_dot[1];
            let __dot_theta = __mu_dot[2];
            let __dot_L = __mu_dot[3];
            let __t0 = __gamma - __beta;
            let __t1 = __t0.sin();
            let __t2 = __gamma.sin();
            let __d = __l * __t1 / __t2;
            let __t3 = __beta.sin();
            let __t4 = __l * __t3 / __t2;
            let __t5 = -__l * __t1 / __t2;
            let __t6 = __alpha - __beta;
            let __t7 = __t6.sin();
            let __t8 = -__l * __t1 * __t7 / __t2;
            let __t9 = __t6.cos();
            let __t10 = -__l * __t1 * __t9 / __t2;
            let __t11 = __theta.sin();
            let __t12 = __L * __t11;
            let __t13 = __theta.cos();
            let __t14 = __L * __t13;
            let __t15 = __gamma.cos();
            let __t16 = __beta.cos();
            let __t17 = __l * __t16 / __t2;
            let __t18 = __t2.powi(-2);
            let __t19 = __t0.cos();
            let __t20 = -__l * __t19 / __t2;
            let __t21 = __l * __t19 / __t2 - __l * __t1 * __t15 * __t18;
            let __t22 = __l * __t1 * __t9 / __t2 + __l * __t7 * __t19 / __t2;
            let __t23 = -__l * __t7 * __t19 / __t2;
            let __t24 = __l * __t1 * __t7 * __t15 * __t18;
            let __t25 = __t23 + __t24;
            let __t26 = __l * __t9 * __t19 / __t2;
            let __t27 = __t8 + __t26;
            let __t28 = __l * __t1 * __t9 * __t15 * __t18 - __l * __t9 * __t19 / __t2;
            let __t29 = -__l * __t15 * __t16 * __t18;
            let __t30 = __t2.powi(-3);
            let __t31 = __t15.powi(2);
            let __t32 = __d + __l * __t15 * __t18 * __t19;
            let __t33 = __l * __t1 * __t30 * __t31 * 2.0
                - __l * __t15 * __t18 * __t19 * 2.0;
            let __t34 = -__l * __t9 * __t19 * 2.0 / __t2;
            let __t35 = __l * __t1 * __t7 * 2.0 / __t2 + __t34;
            let __t36 = __t8 + __t26 - __l * __t1 * __t9 * __t15 * __t18
                - __l * __t7 * __t15 * __t18 * __t19;
            let __t37 = -__l * __t1 * __t7 * __t30 * __t31 * 2.0;
            let __t38 = __l * __t7 * __t15 * __t18 * __t19 * 2.0;
            let __t39 = __t37 + __t38;
            let __t40 = __l * __t1 * __t9 * 2.0 / __t2;
            let __t41 = __l * __t7 * __t19 * 2.0 / __t2;
            let __t42 = __t40 + __t41;
            let __t43 = __t10 + __t23 + __t24 - __l * __t9 * __t15 * __t18 * __t19;
            let __t44 = __l * __t9 * __t15 * __t18 * __t19 * 2.0;
            let __t45 = __t44 - __l * __t1 * __t9 * __t30 * __t31 * 2.0;
            let __t46 = __dot_theta.powi(2);
            let __t47 = __l * __t3 * __t15 * __t18 * __dot_beta;
            let __t48 = __t2.powi(-4);
            let __t49 = __t15.powi(3);
            let __t50 = __t20 + __l * __t1 * __t15 * __t18;
            let __t51 = -__l * __t1 * __t15 * __t18 * 2.0;
            let __t52 = __t51 - __l * __t19 * __t30 * __t31 * 2.0;
            let __t53 = __dot_gamma * __t52;
            let __t54 = __dot_beta
                * (__l * __t19 * __dot_beta / __t2 + __dot_gamma * __t50)
                + __dot_gamma * (__dot_beta * __t50 + __t53);
            let __t55 = __dot_beta
                * (__t53 - __l * __t19 * __dot_beta / __t2
                    + __l * __t1 * __t15 * __t18 * __dot_beta)
                + __dot_gamma
                    * (__dot_beta * __t52
                        + __dot_gamma
                            * (__t51 - __l * __t1 * __t48 * __t49 * 6.0
                                + __l * __t19 * 2.0 / __t2
                                + __l * __t19 * __t30 * __t31 * 6.0));
            let __t56 = __t40 + __t41 + __t44 - __l * __t1 * __t7 * __t15 * __t18 * 2.0;
            let __t57 = __l * __t1 * __t7 * __t15 * __t18 * 2.0;
            let __t58 = __l * __t7 * __t19 * __t30 * __t31 * 2.0
                + __l * __t1 * __t9 * __t30 * __t31 * 2.0
                - __l * __t9 * __t15 * __t18 * __t19 * 2.0 + __t57;
            let __t59 = __dot_beta * __t56 + __dot_gamma * __t58;
            let __t60 = __dot_beta
                * (__dot_beta
                    * (-__l * __t7 * __t19 * 4.0 / __t2 - __l * __t1 * __t9 * 4.0 / __t2)
                    + __dot_gamma * __t56) + __dot_gamma * __t59;
            let __t61 = __dot_beta * __t59
                + __dot_gamma
                    * (__dot_beta * __t58
                        + __dot_gamma
                            * (__t57 - __l * __t7 * __t19 * 2.0 / __t2
                                + __l * __t1 * __t7 * __t48 * __t49 * 6.0
                                - __l * __t7 * __t19 * __t30 * __t31 * 6.0));
            let __t62 = __l * __t9 * __t19 * 2.0 / __t2 - __l * __t1 * __t7 * 2.0 / __t2
                - __l * __t1 * __t9 * __t15 * __t18 * 2.0
                - __l * __t7 * __t15 * __t18 * __t19 * 2.0;
            let __t63 = __l * __t1 * __t9 * __t15 * __t18 * 2.0;
            let __t64 = __t37 + __t38 + __l * __t9 * __t19 * __t30 * __t31 * 2.0 + __t63;
            let __t65 = __dot_beta * __t62 + __dot_gamma * __t64;
            let __t66 = __dot_beta
                * (__dot_beta
                    * (__l * __t1 * __t7 * 4.0 / __t2 - __l * __t9 * __t19 * 4.0 / __t2)
                    + __dot_gamma * __t62) + __dot_gamma * __t65;
            let __t67 = __dot_beta * __t65
                + __dot_gamma
                    * (__dot_beta * __t64
                        + __dot_gamma
                            * (__t34 + __t63 + __l * __t1 * __t9 * __t48 * __t49 * 6.0
                                - __l * __t9 * __t19 * __t30 * __t31 * 6.0));
            let mut __phi = __crane_runtime::nalgebra::SVector::<T, 7>::zeros();
            __phi[0] = __t4;
            __phi[1] = __d + __L;
            __phi[2] = __d;
            __phi[3] = __t8;
            __phi[4] = __t10;
            __phi[5] = __t8 + __t12;
            __phi[6] = __t10 - __L * __t13;
            let mut __null_space = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __null_space[(0, 0)] = __t17;
            __null_space[(0, 1)] = -__l * __t3 * __t15 * __t18;
            __null_space[(1, 0)] = __t20;
            __null_space[(1, 1)] = __t21;
            __null_space[(1, 3)] = T::from(1.0);
            __null_space[(2, 0)] = __t20;
            __null_space[(2, 1)] = __t21;
            __null_space[(3, 0)] = __t22;
            __null_space[(3, 1)] = __t25;
            __null_space[(4, 0)] = __t27;
            __null_space[(4, 1)] = __t28;
            __null_space[(5, 0)] = __t22;
            __null_space[(5, 1)] = __t25;
            __null_space[(5, 2)] = __t14;
            __null_space[(5, 3)] = __t11;
            __null_space[(6, 0)] = __t27;
            __null_space[(6, 1)] = __t28;
            __null_space[(6, 2)] = __t12;
            __null_space[(6, 3)] = -__t13;
            let mut __curvature_jacobian = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __curvature_jacobian[(0, 0)] = __dot_beta
                * (__l * __t3 * __t15 * __t18 * __dot_gamma
                    - __l * __t16 * __dot_beta / __t2)
                + __dot_gamma
                    * (__t47
                        + __dot_gamma * (__t17 + __l * __t16 * __t30 * __t31 * 2.0));
            __curvature_jacobian[(0, 1)] = __dot_beta
                * (__t47 + __l * __t16 * __dot_gamma / __t2
                    + __l * __t16 * __dot_gamma * __t30 * __t31 * 2.0)
                + __dot_gamma
                    * (__l * __t16 * __dot_beta / __t2
                        + __l * __t16 * __dot_beta * __t30 * __t31 * 2.0
                        + __dot_gamma
                            * (-__l * __t3 * __t48 * __t49 * 6.0
                                - __l * __t3 * __t15 * __t18 * 5.0));
            __curvature_jacobian[(1, 0)] = __t54;
            __curvature_jacobian[(1, 1)] = __t55;
            __curvature_jacobian[(2, 0)] = __t54;
            __curvature_jacobian[(2, 1)] = __t55;
            __curvature_jacobian[(3, 0)] = __t60;
            __curvature_jacobian[(3, 1)] = __t61;
            __curvature_jacobian[(4, 0)] = __t66;
            __curvature_jacobian[(4, 1)] = __t67;
            __curvature_jacobian[(5, 0)] = __t60;
            __curvature_jacobian[(5, 1)] = __t61;
            __curvature_jacobian[(5, 2)] = __dot_theta
                * (-__L * __t13 * __dot_theta - __t11 * __dot_L)
                - __t11 * __dot_theta * __dot_L;
            __curvature_jacobian[(5, 3)] = -__t11 * __t46;
            __curvature_jacobian[(6, 0)] = __t66;
            __curvature_jacobian[(6, 1)] = __t67;
            __curvature_jacobian[(6, 2)] = __t13 * __dot_theta * __dot_L
                + __dot_theta * (__t13 * __dot_L - __L * __t11 * __dot_theta);
            __curvature_jacobian[(6, 3)] = __t13 * __t46;
            let mut __d_null_space_0 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __d_null_space_0[(0, 0)] = -__l * __t3 / __t2;
            __d_null_space_0[(0, 1)] = __t29;
            __d_null_space_0[(1, 0)] = __t5;
            __d_null_space_0[(1, 1)] = __t32;
            __d_null_space_0[(2, 0)] = __t5;
            __d_null_space_0[(2, 1)] = __t32;
            __d_null_space_0[(3, 0)] = __t35;
            __d_null_space_0[(3, 1)] = __t36;
            __d_null_space_0[(4, 0)] = __t42;
            __d_null_space_0[(4, 1)] = __t43;
            __d_null_space_0[(5, 0)] = __t35;
            __d_null_space_0[(5, 1)] = __t36;
            __d_null_space_0[(6, 0)] = __t42;
            __d_null_space_0[(6, 1)] = __t43;
            let mut __d_null_space_1 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __d_null_space_1[(0, 0)] = __t29;
            __d_null_space_1[(0, 1)] = __t4 + __l * __t3 * __t30 * __t31 * 2.0;
            __d_null_space_1[(1, 0)] = __t32;
            __d_null_space_1[(1, 1)] = __t33;
            __d_null_space_1[(2, 0)] = __t32;
            __d_null_space_1[(2, 1)] = __t33;
            __d_null_space_1[(3, 0)] = __t36;
            __d_null_space_1[(3, 1)] = __t39;
            __d_null_space_1[(4, 0)] = __t43;
            __d_null_space_1[(4, 1)] = __t45;
            __d_null_space_1[(5, 0)] = __t36;
            __d_null_space_1[(5, 1)] = __t39;
            __d_null_space_1[(6, 0)] = __t43;
            __d_null_space_1[(6, 1)] = __t45;
            let mut __d_null_space_2 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __d_null_space_2[(5, 2)] = -__L * __t11;
            __d_null_space_2[(5, 3)] = __t13;
            __d_null_space_2[(6, 2)] = __t14;
            __d_null_space_2[(6, 3)] = __t11;
            let mut __d_null_space_3 = __crane_runtime::nalgebra::SMatrix::<
                T,
                7,
                4,
            >::zeros();
            __d_null_space_3[(5, 2)] = __t13;
            __d_null_space_3[(6, 2)] = __t11;
            __crane_runtime::MapDerivatives {
                phi: __phi,
                null_space: __null_space,
                null_space_derivatives: [
                    __d_null_space_0,
                    __d_null_space_1,
                    __d_null_space_2,
                    __d_null_space_3,
                ],
                curvature_jacobian: __curvature_jacobian,
            }
        }
    }
    #[allow(
        non_snake_case,
        unused_variables,
        clippy::too_many_lines,
        clippy::unreadable_literal,
        clippy::identity_op,
        clippy::erasing_op
    )]
    impl __crane_runtime::DummyDerivatives<7, 3, 2, 26> for NavyPlanar {
        const OFFSETS: &'static [u8] = &[2, 2, 2, 2, 2, 4, 4, 2, 2, 2, 0, 0];
        const PATH_ORDER: usize = 4;
        const JACOBIAN_NONZEROS: &'static [u32] = &[
            0, 17, 18, 19, 44, 45, 52, 71, 79, 80, 81, 82, 101, 102, 103, 107, 108, 128,
            129, 131, 134, 155, 157, 158, 159, 160, 176, 177, 178, 179, 180, 181, 185,
            186, 203, 204, 206, 207, 212, 230, 233, 239, 240, 241, 245, 246, 247, 251,
            252, 253, 254, 255, 256, 257, 258, 259, 266, 267, 272, 273, 278, 279, 281,
            282, 284, 285, 293, 299, 305, 308, 311, 320, 321, 322, 326, 327, 328, 329,
            330, 331, 332, 333, 334, 335, 336, 337, 347, 348, 353, 354, 356, 357, 359,
            360, 362, 363, 374, 380, 383, 386, 389, 390, 395, 396, 397, 398, 399, 400,
            422, 423, 425, 426, 449, 452, 470, 471, 472, 473, 474, 475, 476, 477, 478,
            497, 498, 500, 501, 503, 504, 524, 527, 530, 547, 548, 549, 550, 551, 552,
            553, 554, 555, 556, 557, 558, 559, 560, 561, 562, 575, 576, 578, 579, 581,
            582, 584, 585, 587, 588, 602, 605, 608, 611, 614, 624, 651,
        ];
        /// The residual of the dummy-derivative system and its Jacobian
        /// `d residual / d z` (by columns), the Jacobian's entries that
        /// are zero by structure left as they are.
        ///
        /// Unknowns `z` in order: `L1_d0`, `L1_d1`, `L1_d2`, `L2_d0`, `L2_d1`, `L2_d2`, `L0_d0`, `L0_d1`, `L0_d2`, `x0_d0`, `x0_d1`, `x0_d2`, `z0_d0`, `z0_d1`, `z0_d2`, `lambda_rope1_d0`, `lambda_rope1_d1`, `lambda_rope1_d2`, `lambda_rope0_d0`, `lambda_rope0_d1`, `lambda_rope0_d2`, `lambda_hoist_d0`, `lambda_hoist_d1`, `lambda_hoist_d2`, `u1_d0`, `u2_d0`; equations in order: dynamics of `L1`, dynamics of `L2`, dynamics of `L0`, dynamics of `L0` (derivative 1), dynamics of `L0` (derivative 2), dynamics of `x0`, dynamics of `x0` (derivative 1), dynamics of `x0` (derivative 2), dynamics of `z0`, dynamics of `z0` (derivative 1), dynamics of `z0` (derivative 2), dynamics of `x`, dynamics of `x` (derivative 1), dynamics of `x` (derivative 2), dynamics of `z`, dynamics of `z` (derivative 1), dynamics of `z` (derivative 2), constraint `rope1`, constraint `rope1` (derivative 1), constraint `rope1` (derivative 2), constraint `rope0`, constraint `rope0` (derivative 1), constraint `rope0` (derivative 2), constraint `hoist`, constraint `hoist` (derivative 1), constraint `hoist` (derivative 2).
        fn dummy_derivative_system_into(
            &self,
            __gamma: &[__crane_runtime::nalgebra::SVector<f64, 2>],
            __z: &[f64],
            __residual: &mut [f64],
            __jacobian: &mut [f64],
        ) {
            let __z = &__z[..26];
            let __residual = &mut __residual[..26];
            let __jacobian = &mut __jacobian[..676];
            let __q_L1_d0 = __z[0];
            let __q_L1_d1 = __z[1];
            let __q_L1_d2 = __z[2];
            let __q_L2_d0 = __z[3];
            let __q_L2_d1 = __z[4];
            let __q_L2_d2 = __z[5];
            let __q_L0_d0 = __z[6];
            let __q_L0_d1 = __z[7];
            let __q_L0_d2 = __z[8];
            let __q_x0_d0 = __z[9];
            let __q_x0_d1 = __z[10];
            let __q_x0_d2 = __z[11];
            let __q_z0_d0 = __z[12];
            let __q_z0_d1 = __z[13];
            let __q_z0_d2 = __z[14];
            let __q_x_d0 = __gamma[0][0];
            let __q_x_d1 = __gamma[1][0];
            let __q_x_d2 = __gamma[2][0];
            let __q_x_d3 = __gamma[3][0];
            let __q_x_d4 = __gamma[4][0];
            let __q_z_d0 = __gamma[0][1];
            let __q_z_d1 = __gamma[1][1];
            let __q_z_d2 = __gamma[2][1];
            let __q_z_d3 = __gamma[3][1];
            let __q_z_d4 = __gamma[4][1];
            let __lambda_rope1_d0 = __z[15];
            let __lambda_rope1_d1 = __z[16];
            let __lambda_rope1_d2 = __z[17];
            let __lambda_rope0_d0 = __z[18];
            let __lambda_rope0_d1 = __z[19];
            let __lambda_rope0_d2 = __z[20];
            let __lambda_hoist_d0 = __z[21];
            let __lambda_hoist_d1 = __z[22];
            let __lambda_hoist_d2 = __z[23];
            let __u_u1_d0 = __z[24];
            let __u_u2_d0 = __z[25];
            let __m_l = self.m_l;
            let __J1 = self.J1;
            let __J2 = self.J2;
            let __r1 = self.r1;
            let __r2 = self.r2;
            let __alpha = self.alpha;
            let __l = self.l;
            let __g = self.g;
            let __t0 = __r1.powi(-2);
            let __t1 = __r2.powi(-2);
            let __t2 = __q_L0_d0 - __q_L2_d0;
            let __t3 = __q_L2_d0 - __q_L0_d0;
            let __t4 = __l * __alpha.sin() + __q_x0_d0;
            let __t5 = __q_x0_d0 - __q_x_d0;
            let __t6 = __l * __alpha.cos() + __q_z0_d0;
            let __t7 = __q_z0_d0 - __q_z_d0;
            let __t8 = __q_x_d0 - __q_x0_d0;
            let __t9 = __q_z_d0 - __q_z0_d0;
            let __t10 = -__lambda_rope0_d0 - __lambda_hoist_d0;
            let __t11 = -__lambda_rope0_d1 - __lambda_hoist_d1;
            let __t12 = __q_L2_d1 - __q_L0_d1;
            let __t13 = __lambda_rope1_d0 + __lambda_rope0_d0 + __lambda_hoist_d0;
            let __t14 = __lambda_rope0_d1 + __lambda_hoist_d1 + __lambda_rope1_d1;
            let __t15 = __q_x0_d1 - __q_x_d1;
            let __t16 = __q_z0_d1 - __q_z_d1;
            let __t17 = __q_x_d1 - __q_x0_d1;
            let __t18 = __q_z_d1 - __q_z0_d1;
            let __t19 = __q_x0_d1.powi(2);
            let __t20 = __q_z0_d1.powi(2);
            let __t21 = __q_L0_d1 - __q_L2_d1;
            let __t22 = __lambda_hoist_d1 * 2.0;
            let __t23 = -__lambda_hoist_d1 * 2.0;
            let __t24 = -__q_L0_d1 * 2.0;
            let __t25 = __q_L2_d2 - __q_L0_d2;
            let __t26 = __t24 + __q_L2_d1 * 2.0;
            let __t27 = __lambda_rope0_d2 + __lambda_hoist_d2 + __lambda_rope1_d2;
            let __t28 = __t22 + __lambda_rope0_d1 * 2.0 + __lambda_rope1_d1 * 2.0;
            let __t29 = __q_x0_d1 * 2.0;
            let __t30 = __q_x0_d2 - __q_x_d2;
            let __t31 = __t29 - __q_x_d1 * 2.0;
            let __t32 = __q_z0_d1 * 2.0;
            let __t33 = __q_z0_d2 - __q_z_d2;
            let __t34 = __t32 - __q_z_d1 * 2.0;
            __residual[0] = __J1 * __t0 * __q_L1_d2 - __u_u1_d0 / __r1
                - __q_L1_d0 * __lambda_rope1_d0;
            __residual[1] = __J2 * __t1 * __q_L2_d2 - __u_u2_d0 / __r2
                + __lambda_hoist_d0 * __t2;
            __residual[2] = __lambda_hoist_d0 * __t3 - __q_L0_d0 * __lambda_rope0_d0;
            __residual[3] = __q_L2_d1 * __lambda_hoist_d0 + __q_L0_d1 * __t10
                - __q_L0_d0 * __lambda_rope0_d1 + __t3 * __lambda_hoist_d1;
            __residual[4] = __q_L2_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_L2_d2
                + __q_L0_d1 * __t11 + __t10 * __q_L0_d2 - __q_L0_d1 * __lambda_rope0_d1
                - __q_L0_d0 * __lambda_rope0_d2 + __lambda_hoist_d1 * __t12
                + __t3 * __lambda_hoist_d2;
            __residual[5] = __lambda_rope1_d0 * __t4 + __q_x0_d0 * __lambda_rope0_d0
                + __lambda_hoist_d0 * __t5;
            __residual[6] = __q_x0_d1 * __t13 - __q_x_d1 * __lambda_hoist_d0
                + __t4 * __lambda_rope1_d1 + __q_x0_d0 * __lambda_rope0_d1
                + __t5 * __lambda_hoist_d1;
            __residual[7] = __q_x0_d1 * __t14 + __t13 * __q_x0_d2
                - __q_x_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_x_d2
                + __q_x0_d1 * __lambda_rope1_d1 + __t4 * __lambda_rope1_d2
                + __q_x0_d1 * __lambda_rope0_d1 + __q_x0_d0 * __lambda_rope0_d2
                + __lambda_hoist_d1 * __t15 + __t5 * __lambda_hoist_d2;
            __residual[8] = __lambda_rope1_d0 * __t6 + __q_z0_d0 * __lambda_rope0_d0
                + __lambda_hoist_d0 * __t7;
            __residual[9] = __q_z0_d1 * __t13 - __q_z_d1 * __lambda_hoist_d0
                + __t6 * __lambda_rope1_d1 + __q_z0_d0 * __lambda_rope0_d1
                + __t7 * __lambda_hoist_d1;
            __residual[10] = __q_z0_d1 * __t14 + __t13 * __q_z0_d2
                - __q_z_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_z_d2
                + __q_z0_d1 * __lambda_rope1_d1 + __t6 * __lambda_rope1_d2
                + __q_z0_d1 * __lambda_rope0_d1 + __q_z0_d0 * __lambda_rope0_d2
                + __lambda_hoist_d1 * __t16 + __t7 * __lambda_hoist_d2;
            __residual[11] = __m_l * __q_x_d2 + __lambda_hoist_d0 * __t8;
            __residual[12] = __q_x_d1 * __lambda_hoist_d0 - __q_x0_d1 * __lambda_hoist_d0
                + __m_l * __q_x_d3 + __t8 * __lambda_hoist_d1;
            __residual[13] = __q_x_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_x_d2
                - __q_x0_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_x0_d2
                + __m_l * __q_x_d4 + __lambda_hoist_d1 * __t17
                + __t8 * __lambda_hoist_d2;
            __residual[14] = __m_l * __q_z_d2 + __m_l * __g + __lambda_hoist_d0 * __t9;
            __residual[15] = __q_z_d1 * __lambda_hoist_d0 - __q_z0_d1 * __lambda_hoist_d0
                + __m_l * __q_z_d3 + __t9 * __lambda_hoist_d1;
            __residual[16] = __q_z_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_z_d2
                - __q_z0_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_z0_d2
                + __m_l * __q_z_d4 + __lambda_hoist_d1 * __t18
                + __t9 * __lambda_hoist_d2;
            __residual[17] = (__t4.powi(2) + __t6.powi(2) - __q_L1_d0.powi(2)) * 0.5;
            __residual[18] = __q_x0_d1 * __t4 - __q_L1_d0 * __q_L1_d1 + __q_z0_d1 * __t6;
            __residual[19] = __t19 - __q_L1_d1.powi(2) - __q_L1_d0 * __q_L1_d2
                + __t4 * __q_x0_d2 + __t20 + __t6 * __q_z0_d2;
            __residual[20] = (__q_x0_d0.powi(2) + __q_z0_d0.powi(2) - __q_L0_d0.powi(2))
                * 0.5;
            __residual[21] = __q_x0_d0 * __q_x0_d1 - __q_L0_d0 * __q_L0_d1
                + __q_z0_d0 * __q_z0_d1;
            __residual[22] = __t19 + __t20 - __q_L0_d1.powi(2) - __q_L0_d0 * __q_L0_d2
                + __q_x0_d0 * __q_x0_d2 + __q_z0_d0 * __q_z0_d2;
            __residual[23] = (__t8.powi(2) + __t9.powi(2) - __t3.powi(2)) * 0.5;
            __residual[24] = __q_L2_d1 * __t2 + __q_L0_d1 * __t3 + __q_x0_d1 * __t5
                + __q_z0_d1 * __t7 + __q_x_d1 * __t8 + __q_z_d1 * __t9;
            __residual[25] = __q_L2_d1 * __t21 + __q_L2_d2 * __t2 + __q_L0_d1 * __t12
                + __t3 * __q_L0_d2 + __q_x0_d1 * __t15 + __t5 * __q_x0_d2
                + __q_z0_d1 * __t16 + __t7 * __q_z0_d2 + __q_x_d1 * __t17
                + __q_x_d2 * __t8 + __q_z_d1 * __t18 + __q_z_d2 * __t9;
            __jacobian[0 * 26 + 0] = -__lambda_rope1_d0;
            __jacobian[2 * 26 + 0] = __J1 * __t0;
            __jacobian[15 * 26 + 0] = -__q_L1_d0;
            __jacobian[24 * 26 + 0] = -__r1.recip();
            __jacobian[3 * 26 + 1] = -__lambda_hoist_d0;
            __jacobian[5 * 26 + 1] = __J2 * __t1;
            __jacobian[6 * 26 + 1] = __lambda_hoist_d0;
            __jacobian[21 * 26 + 1] = __t2;
            __jacobian[25 * 26 + 1] = -__r2.recip();
            __jacobian[3 * 26 + 2] = __lambda_hoist_d0;
            __jacobian[6 * 26 + 2] = __t10;
            __jacobian[18 * 26 + 2] = -__q_L0_d0;
            __jacobian[21 * 26 + 2] = __t3;
            __jacobian[3 * 26 + 3] = __lambda_hoist_d1;
            __jacobian[4 * 26 + 3] = __lambda_hoist_d0;
            __jacobian[6 * 26 + 3] = __t11;
            __jacobian[7 * 26 + 3] = __t10;
            __jacobian[18 * 26 + 3] = -__q_L0_d1;
            __jacobian[19 * 26 + 3] = -__q_L0_d0;
            __jacobian[21 * 26 + 3] = __t12;
            __jacobian[22 * 26 + 3] = __t3;
            __jacobian[3 * 26 + 4] = __lambda_hoist_d2;
            __jacobian[4 * 26 + 4] = __t22;
            __jacobian[5 * 26 + 4] = __lambda_hoist_d0;
            __jacobian[6 * 26 + 4] = -__lambda_rope0_d2 - __lambda_hoist_d2;
            __jacobian[7 * 26 + 4] = __t23 - __lambda_rope0_d1 * 2.0;
            __jacobian[8 * 26 + 4] = __t10;
            __jacobian[18 * 26 + 4] = -__q_L0_d2;
            __jacobian[19 * 26 + 4] = __t24;
            __jacobian[20 * 26 + 4] = -__q_L0_d0;
            __jacobian[21 * 26 + 4] = __t25;
            __jacobian[22 * 26 + 4] = __t26;
            __jacobian[23 * 26 + 4] = __t3;
            __jacobian[9 * 26 + 5] = __t13;
            __jacobian[15 * 26 + 5] = __t4;
            __jacobian[18 * 26 + 5] = __q_x0_d0;
            __jacobian[21 * 26 + 5] = __t5;
            __jacobian[9 * 26 + 6] = __t14;
            __jacobian[10 * 26 + 6] = __t13;
            __jacobian[15 * 26 + 6] = __q_x0_d1;
            __jacobian[16 * 26 + 6] = __t4;
            __jacobian[18 * 26 + 6] = __q_x0_d1;
            __jacobian[19 * 26 + 6] = __q_x0_d0;
            __jacobian[21 * 26 + 6] = __t15;
            __jacobian[22 * 26 + 6] = __t5;
            __jacobian[9 * 26 + 7] = __t27;
            __jacobian[10 * 26 + 7] = __t28;
            __jacobian[11 * 26 + 7] = __t13;
            __jacobian[15 * 26 + 7] = __q_x0_d2;
            __jacobian[16 * 26 + 7] = __t29;
            __jacobian[17 * 26 + 7] = __t4;
            __jacobian[18 * 26 + 7] = __q_x0_d2;
            __jacobian[19 * 26 + 7] = __t29;
            __jacobian[20 * 26 + 7] = __q_x0_d0;
            __jacobian[21 * 26 + 7] = __t30;
            __jacobian[22 * 26 + 7] = __t31;
            __jacobian[23 * 26 + 7] = __t5;
            __jacobian[12 * 26 + 8] = __t13;
            __jacobian[15 * 26 + 8] = __t6;
            __jacobian[18 * 26 + 8] = __q_z0_d0;
            __jacobian[21 * 26 + 8] = __t7;
            __jacobian[12 * 26 + 9] = __t14;
            __jacobian[13 * 26 + 9] = __t13;
            __jacobian[15 * 26 + 9] = __q_z0_d1;
            __jacobian[16 * 26 + 9] = __t6;
            __jacobian[18 * 26 + 9] = __q_z0_d1;
            __jacobian[19 * 26 + 9] = __q_z0_d0;
            __jacobian[21 * 26 + 9] = __t16;
            __jacobian[22 * 26 + 9] = __t7;
            __jacobian[12 * 26 + 10] = __t27;
            __jacobian[13 * 26 + 10] = __t28;
            __jacobian[14 * 26 + 10] = __t13;
            __jacobian[15 * 26 + 10] = __q_z0_d2;
            __jacobian[16 * 26 + 10] = __t32;
            __jacobian[17 * 26 + 10] = __t6;
            __jacobian[18 * 26 + 10] = __q_z0_d2;
            __jacobian[19 * 26 + 10] = __t32;
            __jacobian[20 * 26 + 10] = __q_z0_d0;
            __jacobian[21 * 26 + 10] = __t33;
            __jacobian[22 * 26 + 10] = __t34;
            __jacobian[23 * 26 + 10] = __t7;
            __jacobian[9 * 26 + 11] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 11] = __t8;
            __jacobian[9 * 26 + 12] = -__lambda_hoist_d1;
            __jacobian[10 * 26 + 12] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 12] = __t17;
            __jacobian[22 * 26 + 12] = __t8;
            __jacobian[9 * 26 + 13] = -__lambda_hoist_d2;
            __jacobian[10 * 26 + 13] = __t23;
            __jacobian[11 * 26 + 13] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 13] = __q_x_d2 - __q_x0_d2;
            __jacobian[22 * 26 + 13] = __q_x_d1 * 2.0 - __q_x0_d1 * 2.0;
            __jacobian[23 * 26 + 13] = __t8;
            __jacobian[12 * 26 + 14] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 14] = __t9;
            __jacobian[12 * 26 + 15] = -__lambda_hoist_d1;
            __jacobian[13 * 26 + 15] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 15] = __t18;
            __jacobian[22 * 26 + 15] = __t9;
            __jacobian[12 * 26 + 16] = -__lambda_hoist_d2;
            __jacobian[13 * 26 + 16] = __t23;
            __jacobian[14 * 26 + 16] = -__lambda_hoist_d0;
            __jacobian[21 * 26 + 16] = __q_z_d2 - __q_z0_d2;
            __jacobian[22 * 26 + 16] = __q_z_d1 * 2.0 - __q_z0_d1 * 2.0;
            __jacobian[23 * 26 + 16] = __t9;
            __jacobian[0 * 26 + 17] = -__q_L1_d0;
            __jacobian[9 * 26 + 17] = __t4;
            __jacobian[12 * 26 + 17] = __t6;
            __jacobian[0 * 26 + 18] = -__q_L1_d1;
            __jacobian[1 * 26 + 18] = -__q_L1_d0;
            __jacobian[9 * 26 + 18] = __q_x0_d1;
            __jacobian[10 * 26 + 18] = __t4;
            __jacobian[12 * 26 + 18] = __q_z0_d1;
            __jacobian[13 * 26 + 18] = __t6;
            __jacobian[0 * 26 + 19] = -__q_L1_d2;
            __jacobian[1 * 26 + 19] = -__q_L1_d1 * 2.0;
            __jacobian[2 * 26 + 19] = -__q_L1_d0;
            __jacobian[9 * 26 + 19] = __q_x0_d2;
            __jacobian[10 * 26 + 19] = __t29;
            __jacobian[11 * 26 + 19] = __t4;
            __jacobian[12 * 26 + 19] = __q_z0_d2;
            __jacobian[13 * 26 + 19] = __t32;
            __jacobian[14 * 26 + 19] = __t6;
            __jacobian[6 * 26 + 20] = -__q_L0_d0;
            __jacobian[9 * 26 + 20] = __q_x0_d0;
            __jacobian[12 * 26 + 20] = __q_z0_d0;
            __jacobian[6 * 26 + 21] = -__q_L0_d1;
            __jacobian[7 * 26 + 21] = -__q_L0_d0;
            __jacobian[9 * 26 + 21] = __q_x0_d1;
            __jacobian[10 * 26 + 21] = __q_x0_d0;
            __jacobian[12 * 26 + 21] = __q_z0_d1;
            __jacobian[13 * 26 + 21] = __q_z0_d0;
            __jacobian[6 * 26 + 22] = -__q_L0_d2;
            __jacobian[7 * 26 + 22] = __t24;
            __jacobian[8 * 26 + 22] = -__q_L0_d0;
            __jacobian[9 * 26 + 22] = __q_x0_d2;
            __jacobian[10 * 26 + 22] = __t29;
            __jacobian[11 * 26 + 22] = __q_x0_d0;
            __jacobian[12 * 26 + 22] = __q_z0_d2;
            __jacobian[13 * 26 + 22] = __t32;
            __jacobian[14 * 26 + 22] = __q_z0_d0;
            __jacobian[3 * 26 + 23] = __t2;
            __jacobian[6 * 26 + 23] = __t3;
            __jacobian[9 * 26 + 23] = __t5;
            __jacobian[12 * 26 + 23] = __t7;
            __jacobian[3 * 26 + 24] = __t21;
            __jacobian[4 * 26 + 24] = __t2;
            __jacobian[6 * 26 + 24] = __t12;
            __jacobian[7 * 26 + 24] = __t3;
            __jacobian[9 * 26 + 24] = __t15;
            __jacobian[10 * 26 + 24] = __t5;
            __jacobian[12 * 26 + 24] = __t16;
            __jacobian[13 * 26 + 24] = __t7;
            __jacobian[3 * 26 + 25] = __q_L0_d2 - __q_L2_d2;
            __jacobian[4 * 26 + 25] = __q_L0_d1 * 2.0 - __q_L2_d1 * 2.0;
            __jacobian[5 * 26 + 25] = __t2;
            __jacobian[6 * 26 + 25] = __t25;
            __jacobian[7 * 26 + 25] = __t26;
            __jacobian[8 * 26 + 25] = __t3;
            __jacobian[9 * 26 + 25] = __t30;
            __jacobian[10 * 26 + 25] = __t31;
            __jacobian[11 * 26 + 25] = __t5;
            __jacobian[12 * 26 + 25] = __t33;
            __jacobian[13 * 26 + 25] = __t34;
            __jacobian[14 * 26 + 25] = __t7;
        }
        const SYSTEM_ROWS: &'static [u16] = &[2, 3, 4, 5, 6, 7, 8, 9, 0, 1];
        const SYSTEM_COLUMNS: &'static [u16] = &[0, 1, 2, 3, 4, 7, 8, 9, 10, 11];
        /// The system stage by stage: the system Jacobian (rows
        /// `SYSTEM_ROWS`, columns `SYSTEM_COLUMNS`, by columns) and the
        /// lowest stage's residual at `z`, then each next stage's residual
        /// at the jets the solves of the stages before it left in `z`.
        fn dummy_derivative_stages_into(
            &self,
            __gamma: &[__crane_runtime::nalgebra::SVector<f64, 2>],
            __z: &mut [f64],
            __residual: &mut [f64],
            __system_jacobian: &mut [f64],
            __solve: &mut __crane_runtime::StageSolve<'_>,
        ) -> bool {
            let __z = &mut __z[..26];
            let __residual = &mut __residual[..26];
            let __system_jacobian = &mut __system_jacobian[..100];
            let __m_l = self.m_l;
            let __J1 = self.J1;
            let __J2 = self.J2;
            let __r1 = self.r1;
            let __r2 = self.r2;
            let __alpha = self.alpha;
            let __l = self.l;
            let __g = self.g;
            let __q_L1_d0 = __z[0];
            let __q_L1_d1 = __z[1];
            let __q_L1_d2 = __z[2];
            let __q_L2_d0 = __z[3];
            let __q_L2_d1 = __z[4];
            let __q_L2_d2 = __z[5];
            let __q_L0_d0 = __z[6];
            let __q_L0_d1 = __z[7];
            let __q_L0_d2 = __z[8];
            let __q_x0_d0 = __z[9];
            let __q_x0_d1 = __z[10];
            let __q_x0_d2 = __z[11];
            let __q_z0_d0 = __z[12];
            let __q_z0_d1 = __z[13];
            let __q_z0_d2 = __z[14];
            let __q_x_d0 = __gamma[0][0];
            let __q_x_d1 = __gamma[1][0];
            let __q_x_d2 = __gamma[2][0];
            let __q_x_d3 = __gamma[3][0];
            let __q_x_d4 = __gamma[4][0];
            let __q_z_d0 = __gamma[0][1];
            let __q_z_d1 = __gamma[1][1];
            let __q_z_d2 = __gamma[2][1];
            let __q_z_d3 = __gamma[3][1];
            let __q_z_d4 = __gamma[4][1];
            let __lambda_rope1_d0 = __z[15];
            let __lambda_rope1_d1 = __z[16];
            let __lambda_rope1_d2 = __z[17];
            let __lambda_rope0_d0 = __z[18];
            let __lambda_rope0_d1 = __z[19];
            let __lambda_rope0_d2 = __z[20];
            let __lambda_hoist_d0 = __z[21];
            let __lambda_hoist_d1 = __z[22];
            let __lambda_hoist_d2 = __z[23];
            let __u_u1_d0 = __z[24];
            let __u_u2_d0 = __z[25];
            let __t0 = __r1.powi(-2);
            let __t1 = __r2.powi(-2);
            let __t2 = __l * __alpha.sin();
            let __t3 = __l * __alpha.cos();
            let __t4 = __m_l * __q_x_d2;
            let __t5 = __m_l * __q_z_d2;
            let __t6 = __m_l * __g;
            let __t7 = __m_l * __q_x_d3;
            let __t8 = __m_l * __q_x_d4;
            let __t9 = __m_l * __q_z_d3;
            let __t10 = __m_l * __q_z_d4;
            let __t11 = __q_L2_d0 - __q_L0_d0;
            let __t12 = __t2 + __q_x0_d0;
            let __t13 = __q_x0_d0 - __q_x_d0;
            let __t14 = __t3 + __q_z0_d0;
            let __t15 = __q_z0_d0 - __q_z_d0;
            let __t16 = __q_x_d0 - __q_x0_d0;
            let __t17 = __q_z_d0 - __q_z0_d0;
            let __t18 = __lambda_rope1_d0 + __lambda_rope0_d0 + __lambda_hoist_d0;
            __system_jacobian[5] = -__q_L1_d0;
            __system_jacobian[8] = __J1 * __t0;
            __system_jacobian[10] = __lambda_hoist_d0;
            __system_jacobian[17] = __q_L0_d0 - __q_L2_d0;
            __system_jacobian[19] = __J2 * __t1;
            __system_jacobian[20] = -__lambda_rope0_d0 - __lambda_hoist_d0;
            __system_jacobian[26] = -__q_L0_d0;
            __system_jacobian[27] = __t11;
            __system_jacobian[31] = __t18;
            __system_jacobian[33] = -__lambda_hoist_d0;
            __system_jacobian[35] = __t12;
            __system_jacobian[36] = __q_x0_d0;
            __system_jacobian[37] = __t13;
            __system_jacobian[42] = __t18;
            __system_jacobian[44] = -__lambda_hoist_d0;
            __system_jacobian[45] = __t14;
            __system_jacobian[46] = __q_z0_d0;
            __system_jacobian[47] = __t15;
            __system_jacobian[51] = __t12;
            __system_jacobian[52] = __t14;
            __system_jacobian[60] = -__q_L0_d0;
            __system_jacobian[61] = __q_x0_d0;
            __system_jacobian[62] = __q_z0_d0;
            __system_jacobian[70] = __t11;
            __system_jacobian[71] = __t13;
            __system_jacobian[72] = __t15;
            __system_jacobian[73] = __t16;
            __system_jacobian[74] = __t17;
            __system_jacobian[88] = -__r1.recip();
            __system_jacobian[99] = -__r2.recip();
            __residual[2] = __lambda_hoist_d0 * __t11 - __q_L0_d0 * __lambda_rope0_d0;
            __residual[5] = __lambda_rope1_d0 * __t12 + __q_x0_d0 * __lambda_rope0_d0
                + __lambda_hoist_d0 * __t13;
            __residual[8] = __lambda_rope1_d0 * __t14 + __q_z0_d0 * __lambda_rope0_d0
                + __lambda_hoist_d0 * __t15;
            __residual[11] = __t4 + __lambda_hoist_d0 * __t16;
            __residual[14] = __t5 + __t6 + __lambda_hoist_d0 * __t17;
            __residual[17] = (__t12.powi(2) + __t14.powi(2) - __q_L1_d0.powi(2)) * 0.5;
            __residual[20] = (__q_x0_d0.powi(2) + __q_z0_d0.powi(2) - __q_L0_d0.powi(2))
                * 0.5;
            __residual[23] = (__t16.powi(2) + __t17.powi(2) - __t11.powi(2)) * 0.5;
            if !__solve(0, &*__system_jacobian, &mut *__z, &*__residual) {
                return false;
            }
            let __q_L1_d0 = __z[0];
            let __q_L2_d0 = __z[3];
            let __q_L0_d0 = __z[6];
            let __q_x0_d0 = __z[9];
            let __q_z0_d0 = __z[12];
            let __lambda_rope1_d0 = __z[15];
            let __lambda_rope0_d0 = __z[18];
            let __lambda_hoist_d0 = __z[21];
            let __t19 = __q_L2_d0 - __q_L0_d0;
            let __t20 = __t2 + __q_x0_d0;
            let __t21 = __q_x0_d0 - __q_x_d0;
            let __t22 = __t3 + __q_z0_d0;
            let __t23 = __q_z0_d0 - __q_z_d0;
            let __t24 = __q_x_d0 - __q_x0_d0;
            let __t25 = __q_z_d0 - __q_z0_d0;
            let __t26 = __lambda_rope1_d0 + __lambda_rope0_d0 + __lambda_hoist_d0;
            __residual[3] = __q_L2_d1 * __lambda_hoist_d0
                + __q_L0_d1 * (-__lambda_rope0_d0 - __lambda_hoist_d0)
                - __q_L0_d0 * __lambda_rope0_d1 + __t19 * __lambda_hoist_d1;
            __residual[6] = __q_x0_d1 * __t26 - __q_x_d1 * __lambda_hoist_d0
                + __t20 * __lambda_rope1_d1 + __q_x0_d0 * __lambda_rope0_d1
                + __t21 * __lambda_hoist_d1;
            __residual[9] = __q_z0_d1 * __t26 - __q_z_d1 * __lambda_hoist_d0
                + __t22 * __lambda_rope1_d1 + __q_z0_d0 * __lambda_rope0_d1
                + __t23 * __lambda_hoist_d1;
            __residual[12] = __q_x_d1 * __lambda_hoist_d0 - __q_x0_d1 * __lambda_hoist_d0
                + __t7 + __t24 * __lambda_hoist_d1;
            __residual[15] = __q_z_d1 * __lambda_hoist_d0 - __q_z0_d1 * __lambda_hoist_d0
                + __t9 + __t25 * __lambda_hoist_d1;
            __residual[18] = __q_x0_d1 * __t20 - __q_L1_d0 * __q_L1_d1
                + __q_z0_d1 * __t22;
            __residual[21] = __q_x0_d0 * __q_x0_d1 - __q_L0_d0 * __q_L0_d1
                + __q_z0_d0 * __q_z0_d1;
            __residual[24] = __q_L2_d1 * (__q_L0_d0 - __q_L2_d0) + __q_L0_d1 * __t19
                + __q_x0_d1 * __t21 + __q_z0_d1 * __t23 + __q_x_d1 * __t24
                + __q_z_d1 * __t25;
            if !__solve(1, &*__system_jacobian, &mut *__z, &*__residual) {
                return false;
            }
            let __q_L1_d1 = __z[1];
            let __q_L2_d1 = __z[4];
            let __q_L0_d1 = __z[7];
            let __q_x0_d1 = __z[10];
            let __q_z0_d1 = __z[13];
            let __lambda_rope1_d1 = __z[16];
            let __lambda_rope0_d1 = __z[19];
            let __lambda_hoist_d1 = __z[22];
            let __t27 = __q_L0_d0 - __q_L2_d0;
            let __t28 = __q_L2_d1 - __q_L0_d1;
            let __t29 = __lambda_rope0_d1 + __lambda_hoist_d1 + __lambda_rope1_d1;
            let __t30 = __q_x0_d1 - __q_x_d1;
            let __t31 = __q_z0_d1 - __q_z_d1;
            let __t32 = __q_x_d1 - __q_x0_d1;
            let __t33 = __q_z_d1 - __q_z0_d1;
            let __t34 = __q_x0_d1.powi(2);
            let __t35 = __q_z0_d1.powi(2);
            __residual[0] = __J1 * __t0 * __q_L1_d2 - __u_u1_d0 / __r1
                - __q_L1_d0 * __lambda_rope1_d0;
            __residual[1] = __J2 * __t1 * __q_L2_d2 - __u_u2_d0 / __r2
                + __lambda_hoist_d0 * __t27;
            __residual[4] = __q_L2_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_L2_d2
                + __q_L0_d1 * (-__lambda_rope0_d1 - __lambda_hoist_d1)
                + (-__lambda_rope0_d0 - __lambda_hoist_d0) * __q_L0_d2
                - __q_L0_d1 * __lambda_rope0_d1 - __q_L0_d0 * __lambda_rope0_d2
                + __lambda_hoist_d1 * __t28 + __t19 * __lambda_hoist_d2;
            __residual[7] = __q_x0_d1 * __t29 + __t26 * __q_x0_d2
                - __q_x_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_x_d2
                + __q_x0_d1 * __lambda_rope1_d1 + __t20 * __lambda_rope1_d2
                + __q_x0_d1 * __lambda_rope0_d1 + __q_x0_d0 * __lambda_rope0_d2
                + __lambda_hoist_d1 * __t30 + __t21 * __lambda_hoist_d2;
            __residual[10] = __q_z0_d1 * __t29 + __t26 * __q_z0_d2
                - __q_z_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_z_d2
                + __q_z0_d1 * __lambda_rope1_d1 + __t22 * __lambda_rope1_d2
                + __q_z0_d1 * __lambda_rope0_d1 + __q_z0_d0 * __lambda_rope0_d2
                + __lambda_hoist_d1 * __t31 + __t23 * __lambda_hoist_d2;
            __residual[13] = __q_x_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_x_d2
                - __q_x0_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_x0_d2 + __t8
                + __lambda_hoist_d1 * __t32 + __t24 * __lambda_hoist_d2;
            __residual[16] = __q_z_d1 * __lambda_hoist_d1 + __lambda_hoist_d0 * __q_z_d2
                - __q_z0_d1 * __lambda_hoist_d1 - __lambda_hoist_d0 * __q_z0_d2 + __t10
                + __lambda_hoist_d1 * __t33 + __t25 * __lambda_hoist_d2;
            __residual[19] = __t34 - __q_L1_d1.powi(2) - __q_L1_d0 * __q_L1_d2
                + __t20 * __q_x0_d2 + __t35 + __t22 * __q_z0_d2;
            __residual[22] = __t34 + __t35 - __q_L0_d1.powi(2) - __q_L0_d0 * __q_L0_d2
                + __q_x0_d0 * __q_x0_d2 + __q_z0_d0 * __q_z0_d2;
            __residual[25] = __q_L2_d1 * (__q_L0_d1 - __q_L2_d1) + __q_L2_d2 * __t27
                + __q_L0_d1 * __t28 + __t19 * __q_L0_d2 + __q_x0_d1 * __t30
                + __t21 * __q_x0_d2 + __q_z0_d1 * __t31 + __t23 * __q_z0_d2
                + __q_x_d1 * __t32 + __q_x_d2 * __t24 + __q_z_d1 * __t33
                + __q_z_d2 * __t25;
            if !__solve(2, &*__system_jacobian, &mut *__z, &*__residual) {
                return false;
            }
            true
        }
    }
};
