//! The planar US Navy crane with massless main pulley (paper, sect. 5.1),
//! written entirely by hand.
//!
//! This is the independent check of what `crane_model!` generates for the
//! same crane, and the hand-written baseline for benchmarks. Every function
//! is transcribed from the paper: mass matrix (29), inputs and forces (34),
//! constraints (33) and their Jacobian (35); the constraint Hessian
//! `d(G^T lambda)/dq` is differentiated by hand below.
//!
//! Coordinates `q = [L1, L2, L0, x0, z0, x, z]` (eqs. 25-26), inputs
//! `u = [u1, u2]`, constraints `[rope1, rope0, hoist]` in the order of (33).
//! Equations of motion (docs/errata.md, "Conventions"):
//! `M q'' = f + B^T u - G^T lambda`, `G = dg/dq`.

use crane_runtime::{CraneModel, ModelInfo, Rope, Scalar, UnknownParameter};
use nalgebra::{SMatrix, SVector};

/// Parameter names, in the order of [`HandNavyPlanar::parameter_values`].
const PARAMETERS: [&str; 8] = ["m_l", "J1", "J2", "r1", "r2", "alpha", "l", "g"];

/// Hand-written planar US Navy crane with massless main pulley (paper, sect. 5.1).
///
/// Winch 2 sits at the boom tip `P` (the origin), winch 1 at
/// `A = (-l sin(alpha), -l cos(alpha))`; the pulley is at `B = (x0, z0)`, the
/// load at `C = (x, z)`.
#[allow(non_snake_case)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandNavyPlanar {
    /// Load mass `m_l`, in kg.
    pub m_l: f64,
    /// Moment of inertia of winch 1, in kg m^2.
    pub J1: f64,
    /// Moment of inertia of winch 2, in kg m^2.
    pub J2: f64,
    /// Radius of winch 1, in m.
    pub r1: f64,
    /// Radius of winch 2, in m.
    pub r2: f64,
    /// Angle of the boom with the vertical, in rad.
    pub alpha: f64,
    /// Distance `l = |PA|` between the two winches on the boom, in m.
    pub l: f64,
    /// Gravitational acceleration, in m/s^2.
    pub g: f64,
}

impl Default for HandNavyPlanar {
    /// The parameters of sect. 5.1.3 (and `g = 9.81`, docs/errata.md).
    fn default() -> Self {
        Self {
            m_l: 100.0,
            J1: 0.1,
            J2: 0.1,
            r1: 0.1,
            r2: 0.1,
            alpha: std::f64::consts::FRAC_PI_3,
            l: 10.0,
            g: 9.81,
        }
    }
}

impl CraneModel<7, 3, 2> for HandNavyPlanar {
    const INFO: ModelInfo = ModelInfo {
        name: "HandNavyPlanar",
        description: "Hand-written planar US Navy crane with massless main pulley (paper, sect. 5.1).",
        coordinates: &["L1", "L2", "L0", "x0", "z0", "x", "z"],
        inputs: &["u1", "u2"],
        constraints: &["rope1", "rope0", "hoist"],
        ropes: &[
            Rope {
                tension: "N1",
                constraint: 0,
            },
            Rope {
                tension: "N2",
                constraint: 2,
            },
        ],
        parameters: &PARAMETERS,
        // m_l, J1, J2, r1, r2 and l, as the built-in navy-planar declares them
        positive: &[0, 1, 2, 3, 4, 6],
    };

    fn parameter_values(&self) -> Vec<f64> {
        vec![self.m_l, self.J1, self.J2, self.r1, self.r2, self.alpha, self.l, self.g]
    }

    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), UnknownParameter> {
        let slot = match name {
            "m_l" => &mut self.m_l,
            "J1" => &mut self.J1,
            "J2" => &mut self.J2,
            "r1" => &mut self.r1,
            "r2" => &mut self.r2,
            "alpha" => &mut self.alpha,
            "l" => &mut self.l,
            "g" => &mut self.g,
            _ => {
                return Err(UnknownParameter {
                    name: name.to_owned(),
                    known: PARAMETERS.join(", "),
                });
            }
        };
        *slot = value;
        Ok(())
    }

    /// Eq. (33), with the factors 1/2.
    fn constraints<T: Scalar>(&self, q: &SVector<T, 7>) -> SVector<T, 3> {
        let [l1, l2, l0, x0, z0, x, z] = coordinates(q);
        let (sa, ca) = self.alpha.sin_cos();
        // B - A and C - B.
        let (abx, abz) = (x0 + self.l * sa, z0 + self.l * ca);
        let (cbx, cbz) = (x - x0, z - z0);
        let len = l2 - l0;
        SVector::<T, 3>::new(
            (abx * abx + abz * abz - l1 * l1) * 0.5,
            (x0 * x0 + z0 * z0 - l0 * l0) * 0.5,
            (cbx * cbx + cbz * cbz - len * len) * 0.5,
        )
    }

    /// `G = [G1 G2]`, the transpose of eq. (35).
    fn constraint_jacobian<T: Scalar>(&self, q: &SVector<T, 7>) -> SMatrix<T, 3, 7> {
        let [l1, l2, l0, x0, z0, x, z] = coordinates(q);
        let (sa, ca) = self.alpha.sin_cos();
        let zero = T::zero();
        #[rustfmt::skip]
        let g = SMatrix::<T, 3, 7>::from_row_slice(&[
            // L1    L2       L0       x0                z0                x       z
            -l1,  zero,    zero,    x0 + self.l * sa, z0 + self.l * ca, zero,   zero,
            zero, zero,    -l0,     x0,               z0,               zero,   zero,
            zero, l0 - l2, l2 - l0, x0 - x,           z0 - z,           x - x0, z - z0,
        ]);
        g
    }

    /// `d(G^T lambda)/dq`. With `G^T lambda` written out row by row,
    /// ```text
    /// L1: -L1 l1             x0: (x0 + l sin a) l1 + x0 l2 + (x0 - x) l3
    /// L2: -(L2 - L0) l3      z0: (z0 + l cos a) l1 + z0 l2 + (z0 - z) l3
    /// L0: -L0 l2 + (L2 - L0) l3     x: (x - x0) l3,   z: (z - z0) l3
    /// ```
    /// (`l_k = lambda_k`), every row is linear in `q`; differentiating gives
    /// the constant-in-`q`, symmetric matrix below.
    fn constraint_hessian<T: Scalar>(&self, _q: &SVector<T, 7>, lambda: &SVector<T, 3>) -> SMatrix<T, 7, 7> {
        let (l1, l2, l3) = (lambda[0], lambda[1], lambda[2]);
        let s = l1 + l2 + l3;
        let zero = T::zero();
        #[rustfmt::skip]
        let h = SMatrix::<T, 7, 7>::from_row_slice(&[
            // L1    L2    L0         x0    z0    x     z
            -l1,  zero, zero,      zero, zero, zero, zero,
            zero, -l3,  l3,        zero, zero, zero, zero,
            zero, l3,   -l2 - l3,  zero, zero, zero, zero,
            zero, zero, zero,      s,    zero, -l3,  zero,
            zero, zero, zero,      zero, s,    zero, -l3,
            zero, zero, zero,      -l3,  zero, l3,   zero,
            zero, zero, zero,      zero, -l3,  zero, l3,
        ]);
        h
    }

    /// `M = diag(M1, M2)`, eq. (29): `diag(J1/r1^2, J2/r2^2, 0, 0, 0, m_l, m_l)`.
    fn mass_matrix<T: Scalar>(&self) -> SMatrix<T, 7, 7> {
        SMatrix::<T, 7, 7>::from_diagonal(&SVector::<T, 7>::from_column_slice(&[
            T::from(self.J1 / (self.r1 * self.r1)),
            T::from(self.J2 / (self.r2 * self.r2)),
            T::zero(),
            T::zero(),
            T::zero(),
            T::from(self.m_l),
            T::from(self.m_l),
        ]))
    }

    /// `f = [f1; f2] = [0, 0, 0, 0, 0, 0, -m_l g]`, eq. (34).
    fn forces<T: Scalar>(&self, _q: &SVector<T, 7>, _v: &SVector<T, 7>) -> SVector<T, 7> {
        let mut f = SVector::<T, 7>::zeros();
        f[6] = T::from(-self.m_l * self.g);
        f
    }

    /// Both zero: gravity is constant.
    fn force_jacobians<T: Scalar>(
        &self,
        _q: &SVector<T, 7>,
        _v: &SVector<T, 7>,
    ) -> (SMatrix<T, 7, 7>, SMatrix<T, 7, 7>) {
        (SMatrix::zeros(), SMatrix::zeros())
    }

    /// `B^T = [B1^T; 0]`, eq. (34) (5x2 `B1^T`, see docs/errata.md): `1/r1` in the row
    /// of `L1`, `1/r2` in the row of `L2`.
    fn input_matrix<T: Scalar>(&self, _q: &SVector<T, 7>) -> SMatrix<T, 7, 2> {
        let mut b = SMatrix::<T, 7, 2>::zeros();
        b[(0, 0)] = T::from(1.0 / self.r1);
        b[(1, 1)] = T::from(1.0 / self.r2);
        b
    }

    /// Zero: `B^T` does not depend on `q`.
    fn input_jacobian<T: Scalar>(&self, _q: &SVector<T, 7>, _u: &SVector<T, 2>) -> SMatrix<T, 7, 7> {
        SMatrix::zeros()
    }

    /// `[L1, L2 - L0]`: the lengths in the constraints `rope1` and `hoist`.
    fn rope_lengths(&self, q: &SVector<f64, 7>, out: &mut [f64]) {
        debug_assert_eq!(out.len(), 2, "HandNavyPlanar has two ropes");
        out[0] = q[0];
        out[1] = q[1] - q[2];
    }
}

/// `q` unpacked as `[L1, L2, L0, x0, z0, x, z]`.
#[inline]
fn coordinates<T: Scalar>(q: &SVector<T, 7>) -> [T; 7] {
    [q[0], q[1], q[2], q[3], q[4], q[5], q[6]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual64;

    /// Deterministic pseudo-random points around the crane's working range
    /// (a small LCG: the tests crate has no `rand`).
    fn sample_points(count: usize) -> Vec<SVector<f64, 7>> {
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..count)
            .map(|_| {
                // L1, L2, L0 in [2, 20], x0, x in [-10, 5], z0, z in [-20, 0].
                SVector::<f64, 7>::from_fn(|i, _| match i {
                    0..=2 => 2.0 + 18.0 * next(),
                    3 | 5 => -10.0 + 15.0 * next(),
                    _ => -20.0 * next(),
                })
            })
            .collect()
    }

    /// `G` against central differences of `g`. Every `g_k` is quadratic in
    /// `q`, so the central difference has no truncation error (its error
    /// term `h^2/6 g'''` vanishes); what is left is round-off, at most about
    /// `eps * |g terms| / h` with terms of size `|q|^2 <= 400`:
    /// `2.2e-16 * 400 / 1e-4 ~ 1e-9`. Tolerance 1e-8.
    #[test]
    fn jacobian_matches_central_differences() {
        let model = HandNavyPlanar::default();
        let h = 1e-4;
        for q in sample_points(100) {
            let g = model.constraint_jacobian(&q);
            for j in 0..7 {
                let mut qp = q;
                let mut qm = q;
                qp[j] += h;
                qm[j] -= h;
                let fd = (model.constraints(&qp) - model.constraints(&qm)) / (2.0 * h);
                for i in 0..3 {
                    assert!(
                        (g[(i, j)] - fd[i]).abs() < 1e-8,
                        "G[{i},{j}] = {} but central difference {} at q = {q:?}",
                        g[(i, j)],
                        fd[i]
                    );
                }
            }
        }
    }

    /// `G` against forward-mode dual numbers pushed through `g`: exact up to
    /// round-off, so 1e-12 relative.
    #[test]
    fn jacobian_matches_dual_numbers() {
        let model = HandNavyPlanar::default();
        for q in sample_points(100) {
            let g = model.constraint_jacobian(&q);
            for j in 0..7 {
                let qd = SVector::<Dual64, 7>::from_fn(|i, _| {
                    let d = Dual64::from_re(q[i]);
                    if i == j { d.derivative() } else { d }
                });
                let gd = model.constraints(&qd);
                for i in 0..3 {
                    let scale = 1.0 + g[(i, j)].abs();
                    assert!((g[(i, j)] - gd[i].eps).abs() < 1e-12 * scale);
                }
            }
        }
        // The generic path agrees with the f64 path.
        let q = sample_points(1)[0];
        let qd = q.map(Dual64::from_re);
        assert_eq!(
            model.constraint_jacobian(&qd).map(|v| v.re),
            model.constraint_jacobian(&q)
        );
    }

    /// The Hessian against central differences of `G^T lambda`, which is
    /// linear in `q`: again no truncation error, only round-off
    /// `eps * |G^T lambda| / h ~ 2.2e-16 * 20 * 300 / 1e-4 ~ 1e-8`. Tolerance 1e-7.
    #[test]
    fn hessian_matches_central_differences() {
        let model = HandNavyPlanar::default();
        let h = 1e-4;
        let points = sample_points(60);
        for (k, q) in points.iter().enumerate() {
            // Multipliers of both signs and of the sizes met in practice.
            let lambda = SVector::<f64, 3>::new(
                100.0 * (k as f64 * 0.7).sin(),
                100.0 * (k as f64 * 1.3).cos(),
                50.0 + k as f64,
            );
            let hess = model.constraint_hessian(q, &lambda);
            assert_eq!(hess, hess.transpose(), "a Hessian of a scalar is symmetric");
            let force = |q: &SVector<f64, 7>| model.constraint_jacobian(q).transpose() * lambda;
            for j in 0..7 {
                let mut qp = *q;
                let mut qm = *q;
                qp[j] += h;
                qm[j] -= h;
                let fd = (force(&qp) - force(&qm)) / (2.0 * h);
                for i in 0..7 {
                    assert!(
                        (hess[(i, j)] - fd[i]).abs() < 1e-7,
                        "H[{i},{j}] = {} but central difference {}",
                        hess[(i, j)],
                        fd[i]
                    );
                }
            }
        }
    }

    #[test]
    fn constant_matrices_and_metadata() {
        let model = HandNavyPlanar::default();
        let q = sample_points(1)[0];
        let m: SMatrix<f64, 7, 7> = model.mass_matrix();
        let expected = [10.0, 10.0, 0.0, 0.0, 0.0, 100.0, 100.0];
        assert!(m.diagonal().iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12));
        assert_eq!(m, SMatrix::from_diagonal(&m.diagonal()));
        let f = model.forces(&q, &SVector::zeros());
        assert_eq!(f.as_slice(), &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -981.0]);
        let b = model.input_matrix(&q);
        assert_eq!(b[(0, 0)], 10.0);
        assert_eq!(b[(1, 1)], 10.0);
        assert_eq!(b.iter().filter(|v| **v != 0.0).count(), 2);
        let mut lengths = [0.0; 2];
        model.rope_lengths(&q, &mut lengths);
        assert_eq!(lengths, [q[0], q[1] - q[2]]);
        assert_eq!(HandNavyPlanar::INFO.coordinates.len(), 7);
        assert_eq!(HandNavyPlanar::INFO.parameters, &PARAMETERS);
    }

    #[test]
    fn parameters_by_name() {
        let mut model = HandNavyPlanar::default();
        assert_eq!(
            model.parameter_values(),
            vec![100.0, 0.1, 0.1, 0.1, 0.1, std::f64::consts::FRAC_PI_3, 10.0, 9.81]
        );
        model.set_parameter("l", 12.0).unwrap();
        model.set_parameter("J2", 0.2).unwrap();
        assert_eq!(model.l, 12.0);
        assert_eq!(model.J2, 0.2);
        let err = model.set_parameter("m0", 1.0).unwrap_err();
        assert_eq!(err.name, "m0");
        assert!(err.known.contains("alpha"));
    }

    /// The printed start (46)-(47) satisfies `g = 0` (to round-off).
    #[test]
    fn paper_start_is_consistent() {
        let model = HandNavyPlanar::default();
        let q = SVector::<f64, 7>::from_column_slice(&[5.0 * 3f64.sqrt(), 10.0, 5.0, 0.0, -5.0, 0.0, -10.0]);
        assert!(model.constraints(&q).amax() < 1e-13);
    }
}
