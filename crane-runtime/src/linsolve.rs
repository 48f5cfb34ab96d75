//! Dense linear solves for Newton's iteration matrix, in place and
//! allocation-free after construction.
//!
//! LU with partial pivoting; when the pivots say the matrix is singular to
//! working precision (the paper's degenerate starts, see docs/numerics.md) the
//! solver takes the minimum-norm least-squares step instead, the regularised
//! `min |J dz - r|^2 + eps^2 |dz|^2` by Householder QR.

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
    rhs: DVector<f64>,
    /// `[J; eps I]` and its right-hand side for the minimum-norm step.
    stacked: DMatrix<f64>,
    stacked_rhs: DVector<f64>,
    pivots: Vec<usize>,
    /// Row and column scale factors when equilibrating.
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
    equilibrate: bool,
    scaled: DMatrix<f64>,
    /// Smallest-to-largest pivot ratio of the last LU attempt.
    pivot_ratio: f64,
    /// Take the minimum-norm step whatever the pivots.
    hold: bool,
}

impl DenseSolver {
    /// Workspace for `n x n` systems.
    pub fn new(n: usize) -> Self {
        Self {
            lu: DMatrix::zeros(n, n),
            rhs: DVector::zeros(n),
            stacked: DMatrix::zeros(2 * n, n),
            stacked_rhs: DVector::zeros(2 * n),
            pivots: vec![0; n],
            row_scale: vec![1.0; n],
            col_scale: vec![1.0; n],
            equilibrate: false,
            scaled: DMatrix::zeros(0, 0),
            pivot_ratio: f64::NAN,
            hold: false,
        }
    }

    /// Workspace that first equilibrates each matrix: columns, then rows,
    /// scaled by powers of two to largest entry about 1 (exact in floating
    /// point), so that unknowns and equations of very different units do not
    /// spoil the pivoting or the singularity test (docs/numerics.md, minimal
    /// coordinates: condition 1e16 without it).
    pub fn equilibrated(n: usize) -> Self {
        Self {
            equilibrate: true,
            scaled: DMatrix::zeros(n, n),
            ..Self::new(n)
        }
    }

    /// Take the minimum-norm step whatever the pivots (`true`) or only on a
    /// matrix singular to working precision (`false`, the default).
    pub fn set_hold(&mut self, hold: bool) {
        self.hold = hold;
    }

    /// Whether [`set_hold`](Self::set_hold) is on.
    pub fn holds(&self) -> bool {
        self.hold
    }

    /// Solve `jac x = b` in place (`b` becomes `x`). `jac` is left unchanged.
    pub fn solve(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if self.equilibrate {
            self.find_scales(jac);
        }
        self.solve_scaled(jac, b)
    }

    /// [`solve`](Self::solve) with the scale factors of the last `solve`
    /// (any powers of two are exact; Newton's later iterations in one step
    /// have matrices of the same sizes as its first, and finding the factors
    /// costs a tenth of a minimal step).
    pub fn solve_with_last_scales(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        self.solve_scaled(jac, b)
    }

    /// `|jac^-1|_1`, the largest column sum of the inverse, from one LU of
    /// `jac` (not equilibrated); infinite when `jac` is singular to working
    /// precision.
    pub fn inverse_norm1(&mut self, jac: &DMatrix<f64>) -> f64 {
        self.lu.copy_from(jac);
        let ratio = lu_in_place(&mut self.lu, &mut self.pivots);
        if !(ratio.is_finite() && ratio >= SINGULAR_PIVOT_RATIO) {
            return f64::INFINITY;
        }
        let mut largest = 0.0f64;
        for k in 0..jac.nrows() {
            self.rhs.fill(0.0);
            self.rhs[k] = 1.0;
            lu_solve(&self.lu, &self.pivots, &mut self.rhs);
            largest = largest.max(self.rhs.iter().map(|x| x.abs()).sum::<f64>());
        }
        largest
    }

    /// The 2-norm condition number of `jac` after the scaling an
    /// [`equilibrated`](Self::equilibrated) solver applies before its LU
    /// (infinite if singular). A diagnostic: it allocates for an SVD.
    pub fn equilibrated_condition(&mut self, jac: &DMatrix<f64>) -> f64 {
        self.find_scales(jac);
        let mut scaled = jac.clone();
        self.write_scaled(jac, &mut scaled);
        let singular = scaled.singular_values();
        singular.max() / singular.min()
    }

    /// Column scales, then row scales of the column-scaled matrix: powers of
    /// two that bring the largest entry of each near 1.
    fn find_scales(&mut self, jac: &DMatrix<f64>) {
        let n = jac.nrows();
        let entries = jac.as_slice(); // column-major
        for (scale, column) in self.col_scale.iter_mut().zip(entries.chunks_exact(n)) {
            *scale = power_of_two(column.iter().fold(0.0, |m, x| m.max(x.abs())));
        }
        self.row_scale.fill(0.0);
        for (column, scale) in entries.chunks_exact(n).zip(&self.col_scale) {
            for (largest, x) in self.row_scale.iter_mut().zip(column) {
                *largest = largest.max((x * scale).abs());
            }
        }
        for largest in &mut self.row_scale {
            *largest = power_of_two(*largest);
        }
    }

    /// `diag(row) jac diag(col)` into `target`.
    fn write_scaled(&self, jac: &DMatrix<f64>, target: &mut DMatrix<f64>) {
        let n = jac.nrows();
        for ((target, column), &scale) in target
            .as_mut_slice()
            .chunks_exact_mut(n)
            .zip(jac.as_slice().chunks_exact(n))
            .zip(&self.col_scale)
        {
            for ((t, x), row) in target.iter_mut().zip(column).zip(&self.row_scale) {
                *t = x * row * scale;
            }
        }
    }

    fn solve_scaled(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if !self.equilibrate {
            self.lu.copy_from(jac);
            return self.factor_and_solve(jac, b);
        }
        let mut lu = std::mem::take(&mut self.lu);
        self.write_scaled(jac, &mut lu);
        self.lu = lu;
        for (x, row) in b.iter_mut().zip(&self.row_scale) {
            *x *= row;
        }
        let outcome = match self.factor_and_solve_in_lu(b) {
            Some(kind) => Ok(kind),
            None => {
                // singular to working precision: the minimum-norm step of the
                // scaled system
                let mut scaled = std::mem::take(&mut self.scaled);
                self.write_scaled(jac, &mut scaled);
                let outcome = self.min_norm(&scaled, b);
                self.scaled = scaled;
                outcome
            }
        };
        for (x, col) in b.iter_mut().zip(&self.col_scale) {
            *x *= col;
        }
        outcome
    }

    /// Factor `self.lu` (a copy of `jac`) and solve; the minimum-norm step
    /// of `jac` when it is singular to working precision.
    fn factor_and_solve(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        match self.factor_and_solve_in_lu(b) {
            Some(kind) => Ok(kind),
            None => self.min_norm(jac, b),
        }
    }

    /// LU of `self.lu` in place and the solve, or `None` (with the pivot
    /// ratio kept) when the pivots say singular.
    fn factor_and_solve_in_lu(&mut self, b: &mut DVector<f64>) -> Option<SolveKind> {
        self.pivot_ratio = lu_in_place(&mut self.lu, &mut self.pivots);
        if !self.hold && self.pivot_ratio.is_finite() && self.pivot_ratio >= SINGULAR_PIVOT_RATIO {
            lu_solve(&self.lu, &self.pivots, b);
            return Some(SolveKind::Lu);
        }
        None
    }

    /// Minimum-norm least squares: `min |J x - b|^2 + eps^2 |x|^2`, by
    /// Householder QR of the stacked `[J; eps I]` (the normal equations
    /// `(J^T J + eps^2 I) x = J^T b` have the condition squared, and their
    /// round-off, 1e-2 of the step in the damped directions, kept Newton
    /// from converging on navy-3d's slack start).
    fn min_norm(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        let pivot_ratio = self.pivot_ratio;
        let n = jac.nrows();
        let largest = jac.column_iter().map(|column| column.norm()).fold(0.0, f64::max);
        if !(largest.is_finite() && largest > 0.0) {
            return Err(Singular { pivot_ratio });
        }
        let eps = largest * MIN_NORM_REGULARISATION;
        let stacked = &mut self.stacked;
        stacked.fill(0.0);
        stacked.view_mut((0, 0), (n, n)).copy_from(jac);
        for i in 0..n {
            stacked[(n + i, i)] = eps;
        }
        let rhs = &mut self.stacked_rhs;
        rhs.fill(0.0);
        rhs.rows_mut(0, n).copy_from(b);
        householder_solve(stacked, rhs);
        b.copy_from(&rhs.rows(0, n));
        if b.iter().all(|v| v.is_finite()) {
            Ok(SolveKind::MinNorm)
        } else {
            Err(Singular { pivot_ratio })
        }
    }
}

/// Solve the least-squares problem `min |a x - b|` for `a` of full column
/// rank (`2n x n`) in place: Householder reflections make `a` upper
/// triangular and are applied to `b`; `x` is left in `b`'s first `n` rows.
fn householder_solve(a: &mut DMatrix<f64>, b: &mut DVector<f64>) {
    let (rows, n) = a.shape();
    for k in 0..n {
        let norm = a.view((k, k), (rows - k, 1)).norm();
        if norm == 0.0 {
            continue;
        }
        // v = a_k + sign(a_kk) |a_k| e_k, stored over column k
        let alpha = if a[(k, k)] >= 0.0 { -norm } else { norm };
        a[(k, k)] -= alpha;
        let vv = a.view((k, k), (rows - k, 1)).norm_squared();
        for j in (k + 1)..n {
            let dot: f64 = (k..rows).map(|i| a[(i, k)] * a[(i, j)]).sum();
            let factor = 2.0 * dot / vv;
            for i in k..rows {
                let v = a[(i, k)];
                a[(i, j)] -= factor * v;
            }
        }
        let dot: f64 = (k..rows).map(|i| a[(i, k)] * b[i]).sum();
        let factor = 2.0 * dot / vv;
        for i in k..rows {
            b[i] -= factor * a[(i, k)];
        }
        a[(k, k)] = alpha;
    }
    for j in (0..n).rev() {
        b[j] /= a[(j, j)];
        let bj = b[j];
        for i in 0..j {
            b[i] -= a[(i, j)] * bj;
        }
    }
}

/// `2^-k` with `2^k` the power of two nearest to `m` (`log2 m` rounded), or
/// 1 for zero, subnormal and non-finite `m`; from the bits of `m` (a
/// `log2`, `round` and `powi` per entry cost a fifth of a minimal step).
fn power_of_two(m: f64) -> f64 {
    const MANTISSA: u64 = (1 << 52) - 1;
    // mantissa bits of sqrt(2): at or above them, log2 m rounds up
    const SQRT_2_MANTISSA: u64 = 0x6A09E667F3BCD;
    if !(m.is_finite() && m >= f64::MIN_POSITIVE) {
        return 1.0;
    }
    let bits = m.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32 - 1023 + i32::from(bits & MANTISSA >= SQRT_2_MANTISSA);
    // 2^-exponent, with -exponent in -1022 ..= 1023 here (m normal); for
    // m near f64::MAX, 2^-1024 is subnormal: fall back
    if -exponent < -1022 {
        2f64.powi(-exponent)
    } else {
        f64::from_bits(((1023 - exponent) as u64) << 52)
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

    /// The scale factors from the bits are `2^-round(log2 m)` over the whole
    /// normal range (away from the rounding boundary `m = 2^k sqrt(2)`, where
    /// `log2` itself may round either way).
    #[test]
    fn power_of_two_is_the_nearest_power() {
        let mut seed = 3u64;
        for _ in 0..100_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let m = f64::from_bits((seed >> 2) % f64::MAX.to_bits()).max(f64::MIN_POSITIVE);
            let exact = -m.log2().round() as i32;
            if (m.log2().fract().abs() - 0.5).abs() < 1e-9 {
                continue;
            }
            let expected = if exact < -1022 {
                2f64.powi(exact)
            } else {
                f64::from_bits(((1023 + exact) as u64) << 52)
            };
            assert_eq!(power_of_two(m), expected, "m = {m:e}");
        }
        assert_eq!(power_of_two(1.0), 1.0);
        assert_eq!(power_of_two(1.5), 0.5);
        assert_eq!(power_of_two(1.4), 1.0);
        assert_eq!(power_of_two(1e-3), 1024.0);
        assert_eq!(power_of_two(0.0), 1.0);
        assert_eq!(power_of_two(f64::NAN), 1.0);
        assert_eq!(power_of_two(f64::INFINITY), 1.0);
        assert_eq!(power_of_two(1e-310), 1.0);
    }

    #[test]
    fn inverse_norm_is_the_largest_column_sum_of_the_inverse() {
        // inverse of [[2, 1], [1, 1]] is [[1, -1], [-1, 2]]: column sums 2 and 3
        let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 1.0]);
        assert!((DenseSolver::new(2).inverse_norm1(&a) - 3.0).abs() < 1e-15);
        let singular = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert_eq!(DenseSolver::new(2).inverse_norm1(&singular), f64::INFINITY);
    }

    #[test]
    fn zero_matrix_is_an_error() {
        let a = DMatrix::zeros(2, 2);
        let mut b = DVector::from_row_slice(&[1.0, 1.0]);
        assert!(DenseSolver::new(2).solve(&a, &mut b).is_err());
    }
}
