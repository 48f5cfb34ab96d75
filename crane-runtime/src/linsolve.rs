//! Dense linear solves for Newton's iteration matrix, in place and
//! allocation-free after construction.
//!
//! LU with partial pivoting; when the pivots say the matrix is singular to
//! working precision (the paper's degenerate starts, see docs/numerics.md) the
//! solver takes the minimum-norm least-squares step instead, computed from the
//! regularised normal equations `(J^T J + eps^2 I) dz = J^T r`.

use nalgebra::{DMatrix, DVector};

/// Smallest-to-largest LU pivot ratio below which the matrix is treated as
/// singular to working precision (docs/numerics.md: "about 1e-14").
pub const SINGULAR_PIVOT_RATIO: f64 = 1e-14;

/// Regularisation of the minimum-norm fallback relative to the largest
/// singular value squared: directions with singular values below
/// `1e-7 * sigma_max` are damped, the others are solved to relative accuracy
/// `(1e-7 sigma_max / sigma)^2`, which Newton's next iterate corrects.
const MIN_NORM_REGULARISATION: f64 = 1e-7;

/// How a linear system was solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolveKind {
    /// LU with partial pivoting.
    Lu,
    /// Minimum-norm least squares (the matrix was singular to working precision).
    MinNorm,
}

/// The matrix was singular and the minimum-norm fallback failed too (a
/// non-finite entry, or a zero matrix).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Singular {
    /// Smallest-to-largest pivot ratio of the LU attempt.
    pub pivot_ratio: f64,
}

/// Workspace for solving `J x = b` with `J` square of a fixed size.
#[derive(Debug, Clone)]
pub struct DenseSolver {
    lu: DMatrix<f64>,
    normal: DMatrix<f64>,
    rhs: DVector<f64>,
    pivots: Vec<usize>,
    /// Row and column scale factors when equilibrating.
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
    equilibrate: bool,
    scaled: DMatrix<f64>,
}

impl DenseSolver {
    /// Workspace for `n x n` systems.
    pub fn new(n: usize) -> Self {
        Self {
            lu: DMatrix::zeros(n, n),
            normal: DMatrix::zeros(n, n),
            rhs: DVector::zeros(n),
            pivots: vec![0; n],
            row_scale: vec![1.0; n],
            col_scale: vec![1.0; n],
            equilibrate: false,
            scaled: DMatrix::zeros(0, 0),
        }
    }

    /// Workspace that first equilibrates each matrix: columns, then rows,
    /// scaled by powers of two to largest entry about 1 (exact in floating
    /// point), so that unknowns and equations of very different units do not
    /// spoil the pivoting or the singularity test (docs/numerics.md, minimal
    /// coordinates: condition 1e16 without it).
    pub fn equilibrated(n: usize) -> Self {
        Self { equilibrate: true, scaled: DMatrix::zeros(n, n), ..Self::new(n) }
    }

    /// Solve `jac x = b` in place (`b` becomes `x`). `jac` is left unchanged.
    pub fn solve(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if !self.equilibrate {
            return self.solve_plain(jac, b);
        }
        let n = jac.nrows();
        let power_of_two = |m: f64| if m > 0.0 && m.is_finite() { 2f64.powi(-(m.log2().round() as i32)) } else { 1.0 };
        for j in 0..n {
            self.col_scale[j] = power_of_two(jac.column(j).amax());
        }
        for i in 0..n {
            let largest = (0..n).map(|j| (jac[(i, j)] * self.col_scale[j]).abs()).fold(0.0, f64::max);
            self.row_scale[i] = power_of_two(largest);
        }
        let mut scaled = std::mem::take(&mut self.scaled);
        for j in 0..n {
            for i in 0..n {
                scaled[(i, j)] = jac[(i, j)] * self.row_scale[i] * self.col_scale[j];
            }
        }
        for i in 0..n {
            b[i] *= self.row_scale[i];
        }
        let outcome = self.solve_plain(&scaled, b);
        self.scaled = scaled;
        for j in 0..n {
            b[j] *= self.col_scale[j];
        }
        outcome
    }

    fn solve_plain(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        self.lu.copy_from(jac);
        let pivot_ratio = lu_in_place(&mut self.lu, &mut self.pivots);
        if pivot_ratio.is_finite() && pivot_ratio >= SINGULAR_PIVOT_RATIO {
            lu_solve(&self.lu, &self.pivots, b);
            return Ok(SolveKind::Lu);
        }
        // Minimum-norm least squares via (J^T J + eps^2 I) x = J^T b.
        self.normal.gemm_tr(1.0, jac, jac, 0.0);
        let largest = (0..self.normal.nrows()).map(|i| self.normal[(i, i)]).fold(0.0, f64::max);
        if !(largest.is_finite() && largest > 0.0) {
            return Err(Singular { pivot_ratio });
        }
        let eps2 = largest * MIN_NORM_REGULARISATION * MIN_NORM_REGULARISATION;
        for i in 0..self.normal.nrows() {
            self.normal[(i, i)] += eps2;
        }
        self.rhs.gemv_tr(1.0, jac, b, 0.0);
        self.lu.copy_from(&self.normal);
        let ratio = lu_in_place(&mut self.lu, &mut self.pivots);
        if !(ratio.is_finite() && ratio > 0.0) {
            return Err(Singular { pivot_ratio });
        }
        lu_solve(&self.lu, &self.pivots, &mut self.rhs);
        b.copy_from(&self.rhs);
        if b.iter().all(|v| v.is_finite()) {
            Ok(SolveKind::MinNorm)
        } else {
            Err(Singular { pivot_ratio })
        }
    }
}

/// LU factorisation with partial pivoting, in place (Doolittle, unit lower
/// triangle stored below the diagonal). Returns the smallest-to-largest
/// absolute pivot ratio (0 when a pivot is exactly zero; NaN for non-finite input).
fn lu_in_place(a: &mut DMatrix<f64>, pivots: &mut [usize]) -> f64 {
    let n = a.nrows();
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0f64);
    for k in 0..n {
        // pivot search in column k
        let column = a.column(k);
        let mut p = k;
        let mut best = column[k].abs();
        for i in (k + 1)..n {
            let v = column[i].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best.is_nan() {
            return f64::NAN;
        }
        pivots[k] = p;
        smallest = smallest.min(best);
        largest = largest.max(best);
        if best == 0.0 {
            return 0.0;
        }
        if p != k {
            a.swap_rows(k, p);
        }
        let inv = 1.0 / a[(k, k)];
        for i in (k + 1)..n {
            a[(i, k)] *= inv;
        }
        for j in (k + 1)..n {
            let akj = a[(k, j)];
            if akj != 0.0 {
                for i in (k + 1)..n {
                    let lik = a[(i, k)];
                    a[(i, j)] -= lik * akj;
                }
            }
        }
    }
    if largest > 0.0 { smallest / largest } else { 0.0 }
}

/// Forward and back substitution with the factors of [`lu_in_place`].
fn lu_solve(lu: &DMatrix<f64>, pivots: &[usize], b: &mut DVector<f64>) {
    let n = lu.nrows();
    for k in 0..n {
        b.swap_rows(k, pivots[k]);
    }
    for j in 0..n {
        let bj = b[j];
        if bj != 0.0 {
            for i in (j + 1)..n {
                b[i] -= lu[(i, j)] * bj;
            }
        }
    }
    for j in (0..n).rev() {
        b[j] /= lu[(j, j)];
        let bj = b[j];
        for i in 0..j {
            b[i] -= lu[(i, j)] * bj;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_a_regular_system() {
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 4.0, -1.0, 3.0]);
        let x = DVector::from_row_slice(&[1.0, -2.0, 0.5]);
        let mut b = &a * &x;
        let kind = DenseSolver::new(3).solve(&a, &mut b).unwrap();
        assert_eq!(kind, SolveKind::Lu);
        // a well-conditioned 3x3 system: error of order eps * cond
        assert!((b - x).amax() < 1e-14);
    }

    #[test]
    fn singular_system_gets_the_minimum_norm_solution() {
        // rank 2: third column = first + second
        let a = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0]);
        let mut b = DVector::from_row_slice(&[1.0, 1.0, 2.0]);
        let kind = DenseSolver::new(3).solve(&a, &mut b).unwrap();
        assert_eq!(kind, SolveKind::MinNorm);
        // pseudo-inverse solution, orthogonal to the null vector (1, 1, -1):
        // x = (1/3, 1/3, 2/3); regularisation error ~ (1e-7)^2 relative
        let expected = DVector::from_row_slice(&[1.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0]);
        assert!((b - expected).amax() < 1e-10);
    }

    #[test]
    fn zero_matrix_is_an_error() {
        let a = DMatrix::zeros(2, 2);
        let mut b = DVector::from_row_slice(&[1.0, 1.0]);
        assert!(DenseSolver::new(2).solve(&a, &mut b).is_err());
    }
}
