//! What the unit tests of the problems share: a hand-written planar gantry
//! whose forces depend on `q'` and whose input matrix depends on `q` (so
//! that every term of the iteration matrices counts), a reproducible random
//! sequence and the central-difference check of an iteration matrix.

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::model::{CraneModel, ModelInfo, Rope, Scalar, UnknownParameter};
use crate::newton::NonlinearSystem;
use crate::scheme::{History, Scheme};
use crate::solution::State;

/// A planar gantry written by hand: trolley `s`, rope `L`, load `(x, z)`.
pub(crate) struct Gantry;

impl CraneModel<4, 1, 2> for Gantry {
    const INFO: ModelInfo = ModelInfo {
        name: "Gantry",
        description: "",
        coordinates: &["s", "L", "x", "z"],
        inputs: &["u1", "u2"],
        constraints: &["rope"],
        ropes: &[Rope {
            tension: "N",
            constraint: 0,
        }],
        parameters: &[],
        positive: &[],
    };
    fn parameter_values(&self) -> Vec<f64> {
        Vec::new()
    }
    fn set_parameter(&mut self, name: &str, _: f64) -> Result<(), UnknownParameter> {
        Err(UnknownParameter {
            name: name.into(),
            known: String::new(),
        })
    }
    fn constraints<T: Scalar>(&self, q: &SVector<T, 4>) -> SVector<T, 1> {
        let d = q[2] - q[0];
        SVector::from([(d * d + q[3] * q[3] - q[1] * q[1]) * 0.5])
    }
    fn constraint_jacobian<T: Scalar>(&self, q: &SVector<T, 4>) -> SMatrix<T, 1, 4> {
        let d = q[2] - q[0];
        SMatrix::from_row_slice(&[-d, -q[1], d, q[3]])
    }
    fn constraint_hessian<T: Scalar>(&self, _: &SVector<T, 4>, lambda: &SVector<T, 1>) -> SMatrix<T, 4, 4> {
        let (l, z) = (lambda[0], T::from(0.0));
        SMatrix::from_row_slice(&[l, z, -l, z, z, -l, z, z, -l, z, l, z, z, z, z, l])
    }
    fn mass_matrix<T: Scalar>(&self) -> SMatrix<T, 4, 4> {
        SMatrix::from_diagonal(&SVector::from([
            T::from(50.0),
            T::from(5.0),
            T::from(200.0),
            T::from(200.0),
        ]))
    }
    fn forces<T: Scalar>(&self, _: &SVector<T, 4>, v: &SVector<T, 4>) -> SVector<T, 4> {
        // a little velocity-dependent friction on the trolley, so that df/dv counts
        SVector::from([-v[0] * 3.0, T::from(0.0), T::from(0.0), T::from(-200.0 * 9.81)])
    }
    fn force_jacobians<T: Scalar>(&self, _: &SVector<T, 4>, _: &SVector<T, 4>) -> (SMatrix<T, 4, 4>, SMatrix<T, 4, 4>) {
        let mut df_dv = SMatrix::zeros();
        df_dv[(0, 0)] = T::from(-3.0);
        (SMatrix::zeros(), df_dv)
    }
    fn input_matrix<T: Scalar>(&self, q: &SVector<T, 4>) -> SMatrix<T, 4, 2> {
        // the winch force grows with the rope length, so d(B^T u)/dq counts
        let mut b = SMatrix::zeros();
        b[(0, 0)] = T::from(1.0);
        b[(1, 1)] = q[1] * 0.1;
        b
    }
    fn input_jacobian<T: Scalar>(&self, _: &SVector<T, 4>, u: &SVector<T, 2>) -> SMatrix<T, 4, 4> {
        let mut j = SMatrix::zeros();
        j[(1, 1)] = u[1] * 0.1;
        j
    }
    fn rope_lengths(&self, q: &SVector<f64, 4>, out: &mut [f64]) {
        out[0] = q[1];
    }
}

/// Uniform numbers in [-1, 1) from a xorshift generator seeded with `seed`.
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// The largest difference between `system`'s iteration matrix at `z` and
/// central differences of its residual (steps `1e-6 (1 + |z_j|)`), and the
/// largest entry of the matrix.
pub(crate) fn central_difference_error(system: &mut impl NonlinearSystem, z: &DVector<f64>) -> (f64, f64) {
    let n = z.len();
    let (mut r, mut jac) = (DVector::zeros(n), DMatrix::zeros(n, n));
    system.evaluate(z, &mut r, &mut jac);
    let mut worst = 0.0f64;
    for j in 0..n {
        let h = 1e-6 * (1.0 + z[j].abs());
        let (mut plus, mut minus) = (z.clone(), z.clone());
        plus[j] += h;
        minus[j] -= h;
        let (mut rp, mut rm, mut scratch) = (DVector::zeros(n), DVector::zeros(n), DMatrix::zeros(n, n));
        system.evaluate(&plus, &mut rp, &mut scratch);
        system.evaluate(&minus, &mut rm, &mut scratch);
        for i in 0..n {
            worst = worst.max(((rp[i] - rm[i]) / (2.0 * h) - jac[(i, j)]).abs());
        }
    }
    (worst, jac.amax())
}

/// A random history of the gantry's coordinates for `scheme` (positions
/// 2 .. 4 m, rates in [-1, 1]) and the state at its newest entry.
pub(crate) fn random_history(scheme: Scheme, rnd: &mut impl FnMut() -> f64) -> (History<4>, State<4, 1, 2>) {
    let past: Vec<SVector<f64, 4>> = (0..5).map(|_| SVector::from_fn(|_, _| 3.0 + rnd())).collect();
    let rates: Vec<SVector<f64, 4>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
    let start = State {
        t: 0.0,
        q: past[0],
        v: rates[0],
        u: SVector::zeros(),
        lambda: SVector::zeros(),
    };
    (History::from_past(scheme, &past, &rates).expect("a past"), start)
}
