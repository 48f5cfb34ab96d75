/// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
///
/// Declared with `crane_model!`: n = 7 coordinates, m = 3 constraints, a = 2 inputs, f = n - m = 4 degrees of freedom.
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
    pub fn g<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SVector<T, 3> {
        let alpha = T::from(self.alpha);
        let l = T::from(self.l);
        let L1 = q[0];
        let L2 = q[1];
        let L0 = q[2];
        let x0 = q[3];
        let z0 = q[4];
        let x = q[5];
        let z = q[6];
        let mut out = ::crane_runtime::nalgebra::SVector::<T, 3>::zeros();
        out[0] = ((x0 + l * alpha.sin()).powi(2) + (z0 + l * alpha.cos()).powi(2)
            - L1.powi(2)) * 0.5;
        out[1] = (x0.powi(2) + z0.powi(2) - L0.powi(2)) * 0.5;
        out[2] = ((x - x0).powi(2) + (z - z0).powi(2) - (L2 - L0).powi(2)) * 0.5;
        out
    }
    /// `G1 = dg/dp`, the robot block of the constraint Jacobian `G = [G1 G2]`
    /// (eq. 3).
    pub fn G1<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 3, 5> {
        let alpha = T::from(self.alpha);
        let l = T::from(self.l);
        let L1 = q[0];
        let L2 = q[1];
        let L0 = q[2];
        let x0 = q[3];
        let z0 = q[4];
        let x = q[5];
        let z = q[6];
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 3, 5>::zeros();
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
    pub fn G2<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 3, 2> {
        let x0 = q[3];
        let z0 = q[4];
        let x = q[5];
        let z = q[6];
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 3, 2>::zeros();
        out[(2, 0)] = x - x0;
        out[(2, 1)] = z - z0;
        out
    }
    /// Robot block `M1` of the constant mass matrix (eq. 11a), from the kinetic energy `T = 1/2 q'^T M q'` (eq. 28).
    /// `M` is block diagonal, `M = diag(M1, M2)`.
    pub fn M1<T: ::crane_runtime::Scalar>(
        &self,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 5, 5> {
        let J1 = T::from(self.J1);
        let J2 = T::from(self.J2);
        let r1 = T::from(self.r1);
        let r2 = T::from(self.r2);
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 5, 5>::zeros();
        out[(0, 0)] = J1 / r1.powi(2);
        out[(1, 1)] = J2 / r2.powi(2);
        out
    }
    /// Load block `M2` of the constant mass matrix (eq. 11a).
    /// `M` is block diagonal, `M = diag(M1, M2)`.
    pub fn M2<T: ::crane_runtime::Scalar>(
        &self,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 2, 2> {
        let m_l = T::from(self.m_l);
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 2, 2>::zeros();
        out[(0, 0)] = m_l;
        out[(1, 1)] = m_l;
        out
    }
    /// Applied forces on the robot coordinates without the inputs, `f1(q, q')`
    /// (eq. 11b).
    pub fn f1<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        v: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SVector<T, 5> {
        ::crane_runtime::nalgebra::SVector::<T, 5>::zeros()
    }
    /// Applied forces on the load coordinates, `f2(q, q')` (eq. 11b).
    pub fn f2<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        v: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SVector<T, 2> {
        let m_l = T::from(self.m_l);
        let g = T::from(self.g);
        let mut out = ::crane_runtime::nalgebra::SVector::<T, 2>::zeros();
        out[1] = -m_l * g;
        out
    }
    /// Input matrix `B1^T(q)`: generalized force on the robot coordinates per
    /// unit input (eq. 11c).
    /// The load rows of `B^T = [B1^T; 0]` are zero.
    pub fn B1T<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 5, 2> {
        let r1 = T::from(self.r1);
        let r2 = T::from(self.r2);
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 5, 2>::zeros();
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
impl ::crane_runtime::CraneModel<7, 3, 2> for NavyPlanar {
    const INFO: ::crane_runtime::ModelInfo = ::crane_runtime::ModelInfo {
        name: "NavyPlanar",
        description: "Planar US Navy crane with massless main pulley (paper, sect. 5.1).",
        coordinates: &["L1", "L2", "L0", "x0", "z0", "x", "z"],
        inputs: &["u1", "u2"],
        constraints: &["rope1", "rope0", "hoist"],
        ropes: &[
            ::crane_runtime::Rope {
                tension: "N1",
                constraint: 0,
            },
            ::crane_runtime::Rope {
                tension: "N2",
                constraint: 2,
            },
        ],
        parameters: &["m_l", "J1", "J2", "r1", "r2", "alpha", "l", "g"],
    };
    fn parameter_values(&self) -> ::std::vec::Vec<f64> {
        ::std::vec![
            self.m_l, self.J1, self.J2, self.r1, self.r2, self.alpha, self.l, self.g
        ]
    }
    fn set_parameter(
        &mut self,
        name: &str,
        value: f64,
    ) -> ::core::result::Result<(), ::crane_runtime::UnknownParameter> {
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
                return ::core::result::Result::Err(::crane_runtime::UnknownParameter {
                    name: ::std::string::String::from(name),
                    known: ::std::string::String::from(
                        "m_l, J1, J2, r1, r2, alpha, l, g",
                    ),
                });
            }
        }
        ::core::result::Result::Ok(())
    }
    fn constraints<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SVector<T, 3> {
        self.g(q)
    }
    fn constraint_jacobian<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 3, 7> {
        let alpha = T::from(self.alpha);
        let l = T::from(self.l);
        let L1 = q[0];
        let L2 = q[1];
        let L0 = q[2];
        let x0 = q[3];
        let z0 = q[4];
        let x = q[5];
        let z = q[6];
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 3, 7>::zeros();
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
    fn constraint_hessian<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        lambda: &::crane_runtime::nalgebra::SVector<T, 3>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 7, 7> {
        let t0 = lambda[0] + lambda[1] + lambda[2];
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
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
    fn mass_matrix<T: ::crane_runtime::Scalar>(
        &self,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 7, 7> {
        let m_l = T::from(self.m_l);
        let J1 = T::from(self.J1);
        let J2 = T::from(self.J2);
        let r1 = T::from(self.r1);
        let r2 = T::from(self.r2);
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
        out[(0, 0)] = J1 / r1.powi(2);
        out[(1, 1)] = J2 / r2.powi(2);
        out[(5, 5)] = m_l;
        out[(6, 6)] = m_l;
        out
    }
    fn forces<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        v: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SVector<T, 7> {
        let m_l = T::from(self.m_l);
        let g = T::from(self.g);
        let mut out = ::crane_runtime::nalgebra::SVector::<T, 7>::zeros();
        out[6] = -m_l * g;
        out
    }
    fn force_jacobians<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        v: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> (
        ::crane_runtime::nalgebra::SMatrix<T, 7, 7>,
        ::crane_runtime::nalgebra::SMatrix<T, 7, 7>,
    ) {
        let df_dq = ::crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
        let df_dv = ::crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros();
        (df_dq, df_dv)
    }
    fn input_matrix<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 7, 2> {
        let r1 = T::from(self.r1);
        let r2 = T::from(self.r2);
        let mut out = ::crane_runtime::nalgebra::SMatrix::<T, 7, 2>::zeros();
        out[(0, 0)] = r1.recip();
        out[(1, 1)] = r2.recip();
        out
    }
    fn input_jacobian<T: ::crane_runtime::Scalar>(
        &self,
        q: &::crane_runtime::nalgebra::SVector<T, 7>,
        u: &::crane_runtime::nalgebra::SVector<T, 2>,
    ) -> ::crane_runtime::nalgebra::SMatrix<T, 7, 7> {
        ::crane_runtime::nalgebra::SMatrix::<T, 7, 7>::zeros()
    }
    fn rope_lengths(
        &self,
        q: &::crane_runtime::nalgebra::SVector<f64, 7>,
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
