//! Dense linear solves for Newton's iteration matrix, in place and
//! allocation-free after construction.
//!
//! LU with partial pivoting; when the pivots say the matrix is singular to
//! working precision (the paper's degenerate starts, see docs/numerics.md) the
//! solver takes the minimum-norm least-squares step instead, the regularised
//! `min |J dz - r|^2 + eps^2 |dz|^2` by Householder QR. A matrix with a known
//! block lower triangular form ([`Triangular`]) is solved block by block,
//! each diagonal block factored on its own, or all of them with one LU of
//! the last where they nest (the dummy-derivative system's stages: a 26 x 26
//! LU becomes one of 10 x 10 on navy-planar).

use std::ops::Range;

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

/// The block lower triangular form of a square matrix: with its rows and
/// columns reordered (`rows[k]`, `cols[k]`: the original index of the
/// `k`-th), every entry above the square diagonal blocks is zero, so
/// `J x = b` is solved one block after another, each with the blocks
/// before it known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Triangular {
    rows: Vec<usize>,
    cols: Vec<usize>,
    blocks: Vec<Range<usize>>,
    /// Per block, where the matrix's entries are known to be zero outside a
    /// pattern ([`with_nonzeros`](Self::with_nonzeros)): the entries left
    /// of the block that are not, by the block's rows.
    left: Option<Vec<Left>>,
    /// Whether each entry (by columns) may be nonzero, where known.
    nonzero: Option<Vec<bool>>,
    /// What each row and column stands for ([`with_labels`](Self::with_labels)).
    labels: Option<(Vec<usize>, Vec<usize>)>,
}

/// The entries of a matrix left of one diagonal block (in the blocks
/// before it) that are not zero by structure, row by row of the block.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Left {
    /// Where each row's entries start in `entries` (one more than rows).
    starts: Vec<usize>,
    /// `(position of the column among the solved ones, index of the
    /// entry by columns)`, each row's in column order.
    entries: Vec<(usize, usize)>,
}

impl Triangular {
    /// The form that orders rows and columns by stage (each stable in
    /// index within its stage): `row_stage[i]`, `col_stage[j]` the stage of
    /// row `i` and column `j`, where a row depends only on the columns of
    /// its stage and of earlier (smaller) ones. `None` when the counts
    /// differ or a stage has not as many rows as columns.
    ///
    /// ```
    /// use crane_runtime::linsolve::Triangular;
    /// // rows 0, 2 in stage 0, row 1 in stage -1; columns likewise
    /// let form = Triangular::from_stages(&[0, -1, 0], &[-1, 0, 0]).unwrap();
    /// assert_eq!(form.block_sizes().collect::<Vec<_>>(), [1, 2]);
    /// assert!(Triangular::from_stages(&[0, 0], &[0, -1]).is_none());
    /// ```
    pub fn from_stages(row_stage: &[i32], col_stage: &[i32]) -> Option<Self> {
        if row_stage.len() != col_stage.len() {
            return None;
        }
        let mut stages: Vec<i32> = row_stage.to_vec();
        stages.sort_unstable();
        stages.dedup();
        let (mut rows, mut cols, mut blocks) = (Vec::new(), Vec::new(), Vec::new());
        for stage in stages {
            let start = rows.len();
            rows.extend((0..row_stage.len()).filter(|&i| row_stage[i] == stage));
            cols.extend((0..col_stage.len()).filter(|&j| col_stage[j] == stage));
            if rows.len() != cols.len() {
                return None;
            }
            blocks.push(start..rows.len());
        }
        (cols.len() == col_stage.len()).then_some(Self {
            rows,
            cols,
            blocks,
            left: None,
            nonzero: None,
            labels: None,
        })
    }

    /// The same form for matrices whose entries outside `nonzeros`
    /// (indices `j n + i` of entry `(i, j)`) are zero: the blocks before
    /// each one are then subtracted over those entries alone, in the same
    /// order, so with the same result.
    pub fn with_nonzeros(mut self, nonzeros: &[u32]) -> Self {
        let n = self.rows.len();
        let mut nonzero = vec![false; n * n];
        for &k in nonzeros {
            if let Some(flag) = nonzero.get_mut(k as usize) {
                *flag = true;
            }
        }
        self.nonzero = Some(nonzero);
        self.find_left();
        self
    }

    /// The entries left of each block not zero by structure, where the
    /// pattern is known (see [`with_nonzeros`](Self::with_nonzeros)).
    fn find_left(&mut self) {
        let Some(nonzero) = self.nonzero.as_ref() else {
            return;
        };
        let n = self.rows.len();
        let left = (self.blocks.iter())
            .map(|block| {
                let mut left = Left {
                    starts: vec![0],
                    entries: Vec::new(),
                };
                for &row in &self.rows[block.clone()] {
                    for (p, &col) in self.cols[..block.start].iter().enumerate() {
                        if nonzero[col * n + row] {
                            left.entries.push((p, col * n + row));
                        }
                    }
                    left.starts.push(left.entries.len());
                }
                left
            })
            .collect();
        self.left = Some(left);
    }

    /// The same form with what each row and column stands for: where each
    /// diagonal block's row labels and column labels are among the next
    /// block's, and its entries are the next block's at the same labels
    /// (Pryce's stages, labelled by equation and by unknown: every stage's
    /// block is a part of the system Jacobian, and the last stage's is all
    /// of it), one LU of the last block, its rows and columns ordered with
    /// the first block's labels first, then those the next one adds, and so
    /// on, and its pivots searched within each leading block, solves every
    /// block (checked at each solve, entry for entry; where a block differs,
    /// each block is factored on its own). Every block's rows and columns
    /// are put in that order, so that each is solved in place with the
    /// leading part of the factors. Labels of another length than the
    /// matrix's are ignored.
    ///
    /// ```
    /// use crane_runtime::linsolve::Triangular;
    /// // rows 0 and 1 are equation 0 at stages -1 and 0, row 2 equation 1
    /// // at stage 0; columns likewise of unknowns 0 and 1
    /// let form = Triangular::from_stages(&[-1, 0, 0], &[-1, 0, 0]).unwrap();
    /// let form = form.with_labels(&[0, 0, 1], &[0, 0, 1]);
    /// assert_eq!(form.block_sizes().collect::<Vec<_>>(), [1, 2]);
    /// ```
    pub fn with_labels(mut self, row_labels: &[usize], col_labels: &[usize]) -> Self {
        let n = self.rows.len();
        if row_labels.len() != n || col_labels.len() != n {
            return self;
        }
        // each block's rows and columns in the nested order, so that its
        // solve is the leading block's of the last one as they stand
        if let (Some(row_order), Some(col_order)) = (
            nested_order(&self.rows, &self.blocks, row_labels),
            nested_order(&self.cols, &self.blocks, col_labels),
        ) {
            for block in &self.blocks {
                for (indices, labels, order) in [
                    (&mut self.rows, row_labels, &row_order),
                    (&mut self.cols, col_labels, &col_order),
                ] {
                    indices[block.clone()].sort_by_key(|&i| order.iter().position(|&label| label == labels[i]));
                }
            }
            self.find_left();
        }
        self.labels = Some((row_labels.to_vec(), col_labels.to_vec()));
        self
    }

    /// The sizes of the diagonal blocks, in the order they are solved.
    pub fn block_sizes(&self) -> impl Iterator<Item = usize> + '_ {
        self.blocks.iter().map(|b| b.len())
    }

    /// The rows and the columns of diagonal block `k`, in the order solved.
    pub fn block(&self, k: usize) -> Option<(&[usize], &[usize])> {
        let block = self.blocks.get(k)?.clone();
        Some((&self.rows[block.clone()], &self.cols[block]))
    }

    /// Block `k`'s right-hand side into `rhs`: each of its rows of `b` less
    /// the blocks before it, whose solution is `known` (in the form's
    /// column order), with the matrix's `entries` by columns: the terms in
    /// column order, summed in a register (over the entries not zero by
    /// structure, where the form knows them: the same sum).
    fn reduce(&self, k: usize, entries: &[f64], b: &DVector<f64>, known: &[f64], rhs: &mut [f64]) {
        let n = self.rows.len();
        let block = &self.blocks[k];
        let rows = &self.rows[block.clone()];
        match self.left.as_ref().and_then(|left| left.get(k)) {
            Some(left) => {
                for ((value, &row), span) in rhs.iter_mut().zip(rows).zip(left.starts.windows(2)) {
                    let mut sum = b[row];
                    for &(p, entry) in &left.entries[span[0]..span[1]] {
                        sum -= entries[entry] * known[p];
                    }
                    *value = sum;
                }
            }
            None => {
                let cols = &self.cols[..block.start];
                for (value, &row) in rhs.iter_mut().zip(rows) {
                    let mut sum = b[row];
                    for (&col, &x) in cols.iter().zip(known) {
                        sum -= entries[col * n + row] * x;
                    }
                    *value = sum;
                }
            }
        }
    }

    /// The labels ([`with_labels`](Self::with_labels)) of the last diagonal
    /// block's rows and columns, in the order solved.
    pub fn last_labels(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        let (row_labels, col_labels) = self.labels.as_ref()?;
        let (rows, cols) = self.block(self.blocks.len().checked_sub(1)?)?;
        Some((
            rows.iter().map(|&i| row_labels[i]).collect(),
            cols.iter().map(|&j| col_labels[j]).collect(),
        ))
    }

    /// The largest entry of `jac` above the diagonal blocks, in magnitude
    /// (0 for a matrix of this form).
    pub fn largest_above(&self, jac: &DMatrix<f64>) -> f64 {
        let mut largest = 0.0f64;
        for block in &self.blocks {
            for &row in &self.rows[block.clone()] {
                for &col in &self.cols[block.end..] {
                    largest = largest.max(jac[(row, col)].abs());
                }
            }
        }
        largest
    }
}

/// The labels of `indices` in the nested order of `blocks` (the first
/// block's, then those each next block adds), if every block's labels are
/// distinct and hold all of the block's before it.
fn nested_order(indices: &[usize], blocks: &[Range<usize>], labels: &[usize]) -> Option<Vec<usize>> {
    let mut order: Vec<usize> = Vec::new();
    for block in blocks {
        let block_labels: Vec<usize> = indices[block.clone()].iter().map(|&i| labels[i]).collect();
        if !order.iter().all(|label| block_labels.contains(label)) {
            return None;
        }
        for label in block_labels {
            if !order.contains(&label) {
                order.push(label);
            }
        }
        // every label of the block once: as many as its size
        if order.len() != block.len() {
            return None;
        }
    }
    Some(order)
}

/// The one LU of a [`Triangular`] form whose blocks nest (see
/// [`Triangular::with_labels`]), lent to a system that evaluates its blocks
/// one after another itself, each at the solution of the blocks before it
/// ([`NonlinearSystem::staged_update`](crate::newton::NonlinearSystem::staged_update),
/// from [`DenseSolver::stages`]): [`factor`](Self::factor) the last
/// block's matrix, then [`solve`](Self::solve) each block in turn.
#[derive(Debug)]
pub struct Stages<'a> {
    form: &'a Triangular,
    solver: &'a mut DenseSolver,
    /// Whether the solver has found scales.
    scaled: &'a mut bool,
    /// Find the scales anew.
    rescale: bool,
    /// Keep the last factors.
    reuse: bool,
    /// Workspace of the matrix's size.
    x: &'a mut [f64],
}

impl Stages<'_> {
    /// Factor the last block's matrix, whose entries by columns are
    /// `matrix` (its rows and columns in the order of
    /// [`Triangular::last_labels`]): `false` where it is singular to
    /// working precision (with the scales kept and with new ones).
    pub fn factor(&mut self, matrix: &[f64]) -> bool {
        if self.reuse {
            return true;
        }
        let kept = !self.rescale && *self.scaled;
        *self.scaled = true;
        let factored = self.solver.factor_entries(matrix, !kept) || (kept && self.solver.factor_entries(matrix, true));
        if factored {
            self.solver.find_permutation();
        }
        factored
    }

    /// Block `k`'s update with the leading part of the factors: its rows of
    /// `b` (the residual of the block's rows, at the blocks before it as
    /// solved) solved for `x`, which is subtracted from `z` and written
    /// into `dz` at the block's columns. `false` for no block `k`.
    pub fn solve(&mut self, k: usize, b: &[f64], z: &mut [f64], dz: &mut [f64]) -> bool {
        let Some(block) = self.form.blocks.get(k) else {
            return false;
        };
        let (rows, cols) = (&self.form.rows[block.clone()], &self.form.cols[block.clone()]);
        let x = &mut self.x[..block.len()];
        // the right-hand side with its rows exchanged and scaled as the
        // factors' in one pass, the solution scaled by the columns as it
        // is written
        let solver = &*self.solver;
        for ((x, &row), &scale) in x.iter_mut().zip(&solver.permutation).zip(&solver.permuted_row_scale) {
            *x = b[rows[row]] * scale;
        }
        lu_substitute(&solver.lu, &solver.inverse_diagonal, x);
        for ((&x, &col), &scale) in x.iter().zip(cols).zip(&solver.col_scale) {
            let x = x * scale;
            z[col] -= x;
            dz[col] = x;
        }
        true
    }
}

/// A solver per diagonal block of a [`Triangular`] form, and its workspace.
#[derive(Debug, Clone)]
struct BlockSolver {
    form: Triangular,
    solvers: Vec<DenseSolver>,
    matrices: Vec<DMatrix<f64>>,
    rhs: Vec<DVector<f64>>,
    /// The solution in the form's column order.
    x: DVector<f64>,
    /// Whether each block's solver has found scales of its own.
    scaled: Vec<bool>,
    /// One LU for every block, where the form's labels nest.
    nested: Option<Box<Nested>>,
}

/// One LU of the last diagonal block of a [`Triangular`] form that solves
/// every block (see [`Triangular::with_labels`]): each block's rows and
/// columns are the leading ones of the last block's, in the same order.
#[derive(Debug, Clone)]
struct Nested {
    /// The last block's rows and columns (of the matrix).
    rows: Vec<usize>,
    cols: Vec<usize>,
    /// Entries (by columns) that must be equal for the nesting to hold:
    /// each earlier block's against the last block's at the same labels,
    /// where either may be nonzero.
    equal: Vec<(usize, usize)>,
    solver: DenseSolver,
    matrix: DMatrix<f64>,
    /// Whether the solver has found scales.
    scaled: bool,
}

impl Nested {
    /// The nesting of `form`'s labelled blocks, if each block's labels are
    /// the leading ones of the last block's, in the same order (as
    /// [`Triangular::with_labels`] orders them where they nest).
    fn new(form: &Triangular, equilibrate: bool) -> Option<Self> {
        let (row_labels, col_labels) = form.labels.as_ref()?;
        let last = form.blocks.last()?.clone();
        if form.blocks.len() < 2 {
            return None;
        }
        let n = form.rows.len();
        let (rows, cols) = (form.rows[last.clone()].to_vec(), form.cols[last.clone()].to_vec());
        let leading = |indices: &[usize], last: &[usize], labels: &[usize]| {
            indices.len() <= last.len() && indices.iter().zip(last).all(|(&i, &l)| labels[i] == labels[l])
        };
        let may_be_nonzero = |entry: usize| form.nonzero.as_ref().is_none_or(|nonzero| nonzero[entry]);
        let mut equal = Vec::new();
        for block in &form.blocks[..form.blocks.len() - 1] {
            let (block_rows, block_cols) = (&form.rows[block.clone()], &form.cols[block.clone()]);
            if !leading(block_rows, &rows, row_labels) || !leading(block_cols, &cols, col_labels) {
                return None;
            }
            for (&col, &last_col) in block_cols.iter().zip(&cols) {
                for (&row, &last_row) in block_rows.iter().zip(&rows) {
                    let (entry, in_last) = (col * n + row, last_col * n + last_row);
                    if may_be_nonzero(entry) || may_be_nonzero(in_last) {
                        equal.push((entry, in_last));
                    }
                }
            }
        }
        let size = last.len();
        let mut solver = DenseSolver::sized(size, equilibrate);
        // column c's pivot is searched up to the end of the first block
        // that holds it
        solver.pivot_ends = (0..size)
            .map(|c| {
                (form.blocks.iter())
                    .map(|block| block.len())
                    .find(|&end| end > c)
                    .unwrap_or(size)
            })
            .collect();
        Some(Self {
            rows,
            cols,
            equal,
            solver,
            matrix: DMatrix::zeros(size, size),
            scaled: false,
        })
    }
}

impl BlockSolver {
    fn new(form: Triangular, equilibrate: bool) -> Self {
        let sizes: Vec<usize> = form.block_sizes().collect();
        Self {
            solvers: sizes.iter().map(|&n| DenseSolver::sized(n, equilibrate)).collect(),
            matrices: sizes.iter().map(|&n| DMatrix::zeros(n, n)).collect(),
            rhs: sizes.iter().map(|&n| DVector::zeros(n)).collect(),
            x: DVector::zeros(form.rows.len()),
            scaled: vec![false; sizes.len()],
            nested: Nested::new(&form, equilibrate).map(Box::new),
            form,
        }
    }

    /// [`solve`](Self::solve) with one LU of the last block, if the form's
    /// blocks nest and their entries do: `false` (and `b` untouched)
    /// otherwise, or where the last block is singular to working precision.
    fn solve_nested(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>, rescale: bool) -> bool {
        let Some(mut nested) = self.nested.take() else {
            return false;
        };
        let solved = self.solve_with(&mut nested, jac, b, rescale);
        self.nested = Some(nested);
        solved
    }

    /// [`solve_nested`](Self::solve_nested) with the nesting at hand.
    fn solve_with(&mut self, nested: &mut Nested, jac: &DMatrix<f64>, b: &mut DVector<f64>, rescale: bool) -> bool {
        let entries = jac.as_slice(); // by columns
        if !nested.equal.iter().all(|&(a, b)| entries[a] == entries[b]) {
            return false;
        }
        gather(jac, &nested.rows, &nested.cols, &mut nested.matrix);
        // kept scales that leave the block singular are found anew
        let kept = !rescale && nested.scaled;
        nested.scaled = true;
        let factored =
            nested.solver.factor(&nested.matrix, !kept) || (kept && nested.solver.factor(&nested.matrix, true));
        if !factored {
            return false;
        }
        // each block's right-hand side and solution in place in `x`
        for (k, block) in self.form.blocks.iter().enumerate() {
            let (known, unknown) = self.x.as_mut_slice().split_at_mut(block.start);
            let x = &mut unknown[..block.len()];
            self.form.reduce(k, entries, b, known, x);
            nested.solver.solve_leading(x);
        }
        self.scatter(b);
        true
    }

    /// Solve `jac x = b` block by block (`b` becomes `x`), with one LU of
    /// the last block where the blocks nest ([`solve_nested`](Self::solve_nested)),
    /// else one per block, each block's scales found anew (`rescale`) or
    /// kept from the last solve; `false` (and `b` untouched) when a
    /// diagonal block is singular to working precision.
    fn solve(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>, rescale: bool) -> bool {
        if self.solve_nested(jac, b, rescale) {
            return true;
        }
        let entries = jac.as_slice(); // by columns
        for k in 0..self.form.blocks.len() {
            let block = self.form.blocks[k].clone();
            self.form.reduce(
                k,
                entries,
                b,
                &self.x.as_slice()[..block.start],
                self.rhs[k].as_mut_slice(),
            );
            let matrix = &mut self.matrices[k];
            gather(
                jac,
                &self.form.rows[block.clone()],
                &self.form.cols[block.clone()],
                matrix,
            );
            // a solver finds its scales at its first solve
            let rescale = rescale || !self.scaled[k];
            self.scaled[k] = true;
            if !self.solvers[k].solve_lu(matrix, &mut self.rhs[k], rescale) {
                return false;
            }
            self.x.rows_mut(block.start, block.len()).copy_from(&self.rhs[k]);
        }
        self.scatter(b);
        true
    }

    /// The solution, in the form's column order, into `b`.
    fn scatter(&self, b: &mut DVector<f64>) {
        for (&col, &x) in self.form.cols.iter().zip(self.x.iter()) {
            b[col] = x;
        }
    }
}

/// The submatrix of `jac` at `rows` and `cols` into `target` (square, of
/// their length).
fn gather(jac: &DMatrix<f64>, rows: &[usize], cols: &[usize], target: &mut DMatrix<f64>) {
    let (n, entries) = (jac.nrows(), jac.as_slice()); // by columns
    for (target, &col) in target.as_mut_slice().chunks_exact_mut(rows.len()).zip(cols) {
        let column = &entries[col * n..(col + 1) * n];
        for (t, &row) in target.iter_mut().zip(rows) {
            *t = column[row];
        }
    }
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
    /// The reciprocals of the diagonal of `U` (the back substitution
    /// multiplies by them: a division's latency on every unknown of the
    /// chain was a tenth of a reduced step).
    inverse_diagonal: Vec<f64>,
    /// Where each column's pivot search ends (see [`lu_in_place`]; empty:
    /// at the last row).
    pivot_ends: Vec<usize>,
    /// The row exchanges of the last factors as one permutation (row `i`
    /// of the factors is row `permutation[i]` of the matrix) and the row
    /// scales in that order ([`find_permutation`](Self::find_permutation)).
    permutation: Vec<usize>,
    permuted_row_scale: Vec<f64>,
    /// Row and column scale factors when equilibrating.
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
    equilibrate: bool,
    /// Whether the factors in `lu` are those of the equilibrated matrix
    /// (always when equilibrating; otherwise only where the plain matrix
    /// was singular to working precision and the equilibrated one not).
    scaled_factors: bool,
    scaled: DMatrix<f64>,
    /// Smallest-to-largest pivot ratio of the last LU attempt.
    pivot_ratio: f64,
    /// Take the minimum-norm step whatever the pivots.
    hold: bool,
    /// The blocks of a block lower triangular matrix, if it is one.
    blocks: Option<Box<BlockSolver>>,
    /// Whether the scales are the last `solve`'s (not when its blocks
    /// solved it).
    scales_found: bool,
    /// LU factorisations by `solve` so far, its blocks' included.
    factorisations: usize,
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
            inverse_diagonal: vec![0.0; n],
            pivot_ends: Vec::new(),
            permutation: (0..n).collect(),
            permuted_row_scale: vec![1.0; n],
            row_scale: vec![1.0; n],
            col_scale: vec![1.0; n],
            equilibrate: false,
            scaled_factors: false,
            scaled: DMatrix::zeros(0, 0),
            pivot_ratio: f64::NAN,
            hold: false,
            blocks: None,
            scales_found: false,
            factorisations: 0,
        }
    }

    /// Solve every matrix as one of the block lower triangular `form` (of
    /// this solver's size), block by block; a matrix one of whose diagonal
    /// blocks is singular to working precision is solved whole as before,
    /// and so is every matrix while [`set_hold`](Self::set_hold) is on.
    pub fn set_triangular(&mut self, form: Triangular) {
        self.blocks = Some(Box::new(BlockSolver::new(form, self.equilibrate)));
    }

    /// Find the scale factors anew at the next solve (for a matrix that
    /// changed its form, not only its entries).
    pub fn forget_scales(&mut self) {
        self.scales_found = false;
    }

    /// The smallest-to-largest pivot ratio of the last LU of a matrix
    /// solved whole (equilibrated where the solver equilibrates): how close
    /// to singular it was; NaN before the first.
    pub fn pivot_ratio(&self) -> f64 {
        self.pivot_ratio
    }

    /// LU factorisations the solves so far took: one per matrix solved
    /// whole, one per matrix whose blocks nest, one per diagonal block of
    /// another solved by blocks (a deterministic cost, for tests).
    pub fn factorisations(&self) -> usize {
        self.factorisations
            + self.blocks.as_ref().map_or(0, |b| {
                let nested = b.nested.as_ref().map_or(0, |n| n.solver.factorisations);
                nested + b.solvers.iter().map(|s| s.factorisations).sum::<usize>()
            })
    }

    /// The one LU of the form [`set_triangular`](Self::set_triangular) set,
    /// for a system that evaluates its blocks itself, if the form's blocks
    /// nest and the solver does not hold; its scales found anew
    /// (`rescale`) or kept.
    pub fn stages(&mut self, rescale: bool, reuse: bool) -> Option<Stages<'_>> {
        if self.hold {
            return None;
        }
        let BlockSolver { form, x, nested, .. } = self.blocks.as_deref_mut()?;
        let nested = nested.as_deref_mut()?;
        Some(Stages {
            form,
            solver: &mut nested.solver,
            scaled: &mut nested.scaled,
            rescale,
            reuse,
            x: x.as_mut_slice(),
        })
    }

    /// The form [`set_triangular`](Self::set_triangular) set, if any.
    pub fn triangular(&self) -> Option<&Triangular> {
        self.blocks.as_ref().map(|b| &b.form)
    }

    /// Workspace that first equilibrates each matrix: columns, then rows,
    /// scaled by powers of two to largest entry about 1 (exact in floating
    /// point), so that unknowns and equations of very different units do not
    /// spoil the pivoting or the singularity test (docs/numerics.md, minimal
    /// coordinates: condition 1e16 without it).
    pub fn equilibrated(n: usize) -> Self {
        Self {
            equilibrate: true,
            scaled_factors: true,
            scaled: DMatrix::zeros(n, n),
            ..Self::new(n)
        }
    }

    /// Take the minimum-norm step whatever the pivots (`true`) or only on a
    /// matrix singular to working precision (`false`, the default).
    pub fn set_hold(&mut self, hold: bool) {
        self.hold = hold;
    }

    /// [`equilibrated`](Self::equilibrated) or [`new`](Self::new).
    fn sized(n: usize, equilibrate: bool) -> Self {
        if equilibrate {
            Self::equilibrated(n)
        } else {
            Self::new(n)
        }
    }

    /// Whether [`set_hold`](Self::set_hold) is on.
    pub fn holds(&self) -> bool {
        self.hold
    }

    /// Solve `jac x = b` in place (`b` becomes `x`). `jac` is left unchanged.
    pub fn solve(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if self.solve_blocks(jac, b, true) {
            self.scales_found = false;
            return Ok(SolveKind::Lu);
        }
        if self.equilibrate {
            self.find_scales(jac.as_slice());
            self.scales_found = true;
        }
        self.solve_scaled(jac, b)
    }

    /// [`solve`](Self::solve) with the scale factors of earlier solves
    /// where they serve (an LU with them finds `jac` regular; any powers of
    /// two are exact): for a sequence of matrices of the same sizes, such as
    /// Newton's over the time steps of smooth jets. Where they do not (or
    /// there are none yet), as [`solve`](Self::solve).
    pub fn solve_with_kept_scales(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if self.solve_blocks(jac, b, false) {
            return Ok(SolveKind::Lu);
        }
        let kept = self.blocks.is_none() && self.equilibrate && self.scales_found && !self.hold;
        if kept && self.solve_lu(jac, b, false) {
            return Ok(SolveKind::Lu);
        }
        self.solve(jac, b)
    }

    /// [`solve`](Self::solve) with the scale factors of the last `solve`
    /// (any powers of two are exact; Newton's later iterations in one step
    /// have matrices of the same sizes as its first, and finding the factors
    /// costs a tenth of a minimal step).
    pub fn solve_with_last_scales(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if self.solve_blocks(jac, b, false) {
            return Ok(SolveKind::Lu);
        }
        if self.equilibrate && !self.scales_found {
            // the last solve was by blocks: the whole matrix has no scales yet
            self.find_scales(jac.as_slice());
            self.scales_found = true;
        }
        self.solve_scaled(jac, b)
    }

    /// The block-by-block solve of a [`Triangular`] matrix, if the solver
    /// has a form, does not hold, and no diagonal block is singular.
    fn solve_blocks(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>, rescale: bool) -> bool {
        match self.blocks.as_mut() {
            Some(blocks) if !self.hold => blocks.solve(jac, b, rescale),
            _ => false,
        }
    }

    /// Solve with the factors (and scales) of the last successful
    /// [`solve_lu`](Self::solve_lu): `b` scaled by the rows, substituted,
    /// scaled by the columns (when equilibrating).
    fn solve_factored(&self, b: &mut DVector<f64>) {
        self.solve_leading(b.as_mut_slice());
    }

    /// `b` times the row scales.
    fn scale_rows(&self, b: &mut [f64]) {
        for (x, row) in b.iter_mut().zip(&self.row_scale) {
            *x *= row;
        }
    }

    /// LU alone (no minimum-norm step): `false` when `jac` is singular to
    /// working precision (then `b` is left as it was); the scales found
    /// anew (`rescale`) or kept.
    fn solve_lu(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>, rescale: bool) -> bool {
        if !self.factor(jac, rescale) {
            return false;
        }
        self.solve_factored(b);
        true
    }

    /// The LU factors of `jac` (equilibrated with scales found anew,
    /// `rescale`, or kept): `false` when it is singular to working precision.
    fn factor(&mut self, jac: &DMatrix<f64>, rescale: bool) -> bool {
        self.factor_entries(jac.as_slice(), rescale)
    }

    /// [`factor`](Self::factor) of the matrix of this solver's size whose
    /// entries, by columns, are `entries`.
    fn factor_entries(&mut self, entries: &[f64], rescale: bool) -> bool {
        if self.equilibrate {
            return self.factor_equilibrated(entries, rescale);
        }
        self.unscale();
        self.lu.as_mut_slice().copy_from_slice(entries);
        let regular = self.factor_in_lu();
        if regular || self.hold {
            return regular;
        }
        // singular to working precision as it stands, perhaps only because
        // its rows and columns are in very different units (winches of 1e6
        // kg m^2 beside ropes): the pivot ratio is not invariant under
        // scaling, so the equilibrated matrix decides
        if self.factor_equilibrated(entries, true) {
            return true;
        }
        self.unscale();
        false
    }

    /// The LU factors of the equilibrated matrix whose entries, by columns,
    /// are `entries` (its scales found anew, `rescale`, or kept).
    fn factor_equilibrated(&mut self, entries: &[f64], rescale: bool) -> bool {
        if rescale {
            self.find_scales(entries);
        }
        let mut lu = std::mem::take(&mut self.lu);
        self.write_scaled(entries, &mut lu);
        self.lu = lu;
        self.scaled_factors = true;
        self.factor_in_lu()
    }

    /// Unit scales again for a solver that does not equilibrate, after an
    /// equilibrated retry of its last matrix.
    fn unscale(&mut self) {
        if self.scaled_factors {
            self.row_scale.fill(1.0);
            self.col_scale.fill(1.0);
            self.scaled_factors = false;
        }
    }

    /// The row exchanges of the last factors as one permutation, and the
    /// row scales (1 where not equilibrating) in its order: what the leading
    /// rows of every nested block need (the exchanges of a block's columns
    /// stay within its rows, those of later columns below them).
    fn find_permutation(&mut self) {
        for (i, p) in self.permutation.iter_mut().enumerate() {
            *p = i;
        }
        for (k, &p) in self.pivots.iter().enumerate() {
            self.permutation.swap(k, p);
        }
        for (scale, &row) in self.permuted_row_scale.iter_mut().zip(&self.permutation) {
            *scale = if self.scaled_factors { self.row_scale[row] } else { 1.0 };
        }
    }

    /// Solve the leading `x.len()` rows and columns of the last factored
    /// matrix (all of them, or a nested leading block of its pivot ends)
    /// with its factors and scales.
    fn solve_leading(&self, x: &mut [f64]) {
        if self.scaled_factors {
            self.scale_rows(x);
        }
        lu_solve(&self.lu, &self.pivots, &self.inverse_diagonal, x);
        if self.scaled_factors {
            for (x, col) in x.iter_mut().zip(&self.col_scale) {
                *x *= col;
            }
        }
    }

    /// `|jac^-1|_1`, the largest column sum of the inverse, from one LU of
    /// `jac` (not equilibrated); infinite when `jac` is singular to working
    /// precision.
    pub fn inverse_norm1(&mut self, jac: &DMatrix<f64>) -> f64 {
        self.lu.copy_from(jac);
        let ratio = lu_in_place(&mut self.lu, &mut self.pivots, &mut self.inverse_diagonal, &[]);
        if !(ratio.is_finite() && ratio >= SINGULAR_PIVOT_RATIO) {
            return f64::INFINITY;
        }
        let mut largest = 0.0f64;
        for k in 0..jac.nrows() {
            self.rhs.fill(0.0);
            self.rhs[k] = 1.0;
            lu_solve(&self.lu, &self.pivots, &self.inverse_diagonal, self.rhs.as_mut_slice());
            largest = largest.max(self.rhs.iter().map(|x| x.abs()).sum::<f64>());
        }
        largest
    }

    /// The 2-norm condition number of `jac` after the scaling an
    /// [`equilibrated`](Self::equilibrated) solver applies before its LU
    /// (infinite if singular). A diagnostic: it allocates for an SVD.
    pub fn equilibrated_condition(&mut self, jac: &DMatrix<f64>) -> f64 {
        self.find_scales(jac.as_slice());
        let mut scaled = jac.clone();
        self.write_scaled(jac.as_slice(), &mut scaled);
        let singular = scaled.singular_values();
        singular.max() / singular.min()
    }

    /// Column scales, then row scales of the column-scaled matrix: powers of
    /// two that bring the largest entry of each near 1.
    fn find_scales(&mut self, entries: &[f64]) {
        let n = self.col_scale.len(); // entries column-major
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
    fn write_scaled(&self, entries: &[f64], target: &mut DMatrix<f64>) {
        let n = self.col_scale.len();
        for ((target, column), &scale) in target
            .as_mut_slice()
            .chunks_exact_mut(n)
            .zip(entries.chunks_exact(n))
            .zip(&self.col_scale)
        {
            for ((t, x), row) in target.iter_mut().zip(column).zip(&self.row_scale) {
                *t = x * row * scale;
            }
        }
    }

    /// LU (with the scales of the last [`find_scales`](Self::find_scales)
    /// when equilibrating) and the solve; the minimum-norm step (of the
    /// scaled system when equilibrating) when the matrix is singular to
    /// working precision.
    fn solve_scaled(&mut self, jac: &DMatrix<f64>, b: &mut DVector<f64>) -> Result<SolveKind, Singular> {
        if self.solve_lu(jac, b, false) {
            return Ok(SolveKind::Lu);
        }
        if !self.equilibrate {
            return self.min_norm(jac, b);
        }
        self.scale_rows(b.as_mut_slice());
        let mut scaled = std::mem::take(&mut self.scaled);
        self.write_scaled(jac.as_slice(), &mut scaled);
        let outcome = self.min_norm(&scaled, b);
        self.scaled = scaled;
        for (x, col) in b.iter_mut().zip(&self.col_scale) {
            *x *= col;
        }
        outcome
    }

    /// LU of `self.lu` in place: `false` (with the pivot ratio kept) when
    /// the pivots say singular, or the solver holds.
    fn factor_in_lu(&mut self) -> bool {
        self.pivot_ratio = lu_in_place(
            &mut self.lu,
            &mut self.pivots,
            &mut self.inverse_diagonal,
            &self.pivot_ends,
        );
        self.factorisations += 1;
        !self.hold && self.pivot_ratio.is_finite() && self.pivot_ratio >= SINGULAR_PIVOT_RATIO
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
/// triangle stored below the diagonal), with the reciprocals of `U`'s
/// diagonal into `inverse_diagonal` and `U`'s rows above the diagonal
/// stored divided by their diagonal entry (so that the back substitution's
/// chain is one multiply and subtract per unknown). The pivot of column `k` is searched in
/// rows `k .. ends[k]` (all below the diagonal where `ends` is empty): with
/// the ends of nested leading blocks, the factors' leading part is each
/// block's LU (the rows below a leading block may then have multipliers
/// above one; the blocks are equilibrated, and Newton corrects what their
/// growth costs). Returns the smallest-to-largest absolute pivot ratio (0 when
/// a pivot is exactly zero; NaN for non-finite input).
fn lu_in_place(a: &mut DMatrix<f64>, pivots: &mut [usize], inverse_diagonal: &mut [f64], ends: &[usize]) -> f64 {
    let n = a.nrows();
    let data = a.as_mut_slice();
    // the small sizes each with their own code, whose loops know their
    // lengths (a tenth of a reduced step faster on navy-planar's 10 x 10)
    macro_rules! sized {
        ($($size:literal)*) => {
            match n {
                $($size => lu_sized::<$size>(data, n, pivots, inverse_diagonal, ends),)*
                _ => lu_sized::<0>(data, n, pivots, inverse_diagonal, ends),
            }
        };
    }
    sized!(2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24)
}

/// [`lu_in_place`] of the `n x n` matrix whose entries by columns are
/// `data`: `n` is `S` where `S` is not 0, a constant of the compiled code.
fn lu_sized<const S: usize>(
    data: &mut [f64],
    n: usize,
    pivots: &mut [usize],
    inverse_diagonal: &mut [f64],
    ends: &[usize],
) -> f64 {
    let n = if S == 0 { n } else { S };
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0f64);
    for k in 0..n {
        // pivot search in column k
        let end = ends.get(k).copied().unwrap_or(n);
        let column = &data[k * n..(k + 1) * n];
        let mut p = k;
        let mut best = column[k].abs();
        for (i, v) in column[..end].iter().enumerate().skip(k + 1) {
            let v = v.abs();
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
            for column in data.chunks_exact_mut(n) {
                column.swap(k, p);
            }
        }
        // the matrix by columns: column j is data[j n .. (j + 1) n]
        let inv = 1.0 / data[k * n + k];
        inverse_diagonal[k] = inv;
        for x in &mut data[k * n + k + 1..(k + 1) * n] {
            *x *= inv;
        }
        let (left, right) = data.split_at_mut((k + 1) * n);
        let multipliers = &left[k * n + k + 1..];
        for column in right.chunks_exact_mut(n) {
            let akj = column[k];
            if akj != 0.0 {
                for (x, &lik) in column[k + 1..].iter_mut().zip(multipliers) {
                    *x -= lik * akj;
                }
                column[k] = akj * inv;
            }
        }
    }
    if largest > 0.0 { smallest / largest } else { 0.0 }
}

/// Forward and back substitution with the factors of [`lu_in_place`], row
/// by row: each unknown is its row's right-hand side less a sum over the
/// unknowns already found, added in a register, the one found last added
/// last (column by column, the update of the unknowns still to come was
/// stored and read back at once for every unknown, a store-to-load stall on
/// the substitution's chain).
///
/// `x` is the right-hand side of the leading `x.len()` rows and columns
/// (of all of them, or of a nested leading block, see [`lu_in_place`]).
fn lu_solve(lu: &DMatrix<f64>, pivots: &[usize], inverse_diagonal: &[f64], x: &mut [f64]) {
    for (k, &p) in pivots.iter().enumerate().take(x.len()) {
        x.swap(k, p);
    }
    lu_substitute(lu, inverse_diagonal, x);
}

/// [`lu_solve`] of a right-hand side whose rows are exchanged already.
fn lu_substitute(lu: &DMatrix<f64>, inverse_diagonal: &[f64], x: &mut [f64]) {
    let (n, m) = (lu.nrows(), x.len());
    let data = lu.as_slice();
    // L y = P b, L unit lower triangular: entry (i, k) at data[k n + i]
    for i in 1..m {
        let mut sum = x[i];
        for (k, &y) in x[..i].iter().enumerate() {
            sum -= data[k * n + i] * y;
        }
        x[i] = sum;
    }
    // U x = y, each row's terms from the last column on: the term of the
    // unknown just found comes last, and the chain of the substitution is
    // one multiply and subtract per unknown (U's rows are stored divided by
    // their diagonal, the right-hand side is multiplied by its reciprocal)
    for i in (0..m).rev() {
        let mut sum = x[i] * inverse_diagonal[i];
        for k in (i + 1..m).rev() {
            sum -= data[k * n + i] * x[k];
        }
        x[i] = sum;
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

    /// A regular matrix in very different units, `D B D` with `B` of
    /// condition 3 and `D = diag(1e6, 1, 1e-6)` (pivot ratio 8e-25 as it
    /// stands), is solved by LU of its equilibrated form, not taken for
    /// singular, whether or not the solver equilibrates; its factors serve
    /// the next solve with their scales, and a well-scaled matrix after it
    /// is solved unscaled.
    #[test]
    fn a_regular_matrix_in_mixed_units_is_not_singular() {
        let a = DMatrix::from_row_slice(3, 3, &[2e12, 1e6, 0.0, 1e6, 3.0, 1e-6, 0.0, 1e-6, 2e-12]);
        let x = DVector::from_row_slice(&[1e-6, 2.0, -1e6]);
        for mut solver in [DenseSolver::new(3), DenseSolver::equilibrated(3)] {
            let mut b = &a * &x;
            assert_eq!(solver.solve(&a, &mut b).unwrap(), SolveKind::Lu);
            // the equilibrated matrix is B up to powers of two: relative
            // error of a few eps cond(B) per unknown
            for i in 0..3 {
                assert!((b[i] - x[i]).abs() <= 1e-14 * x[i].abs(), "{b} vs {x}");
            }
            // the kept factors solve another right-hand side with their scales
            let mut b = &a * &x;
            solver.solve_factored(&mut b);
            for i in 0..3 {
                assert!((b[i] - x[i]).abs() <= 1e-14 * x[i].abs(), "{b} vs {x}");
            }
            let well = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 4.0, -1.0, 3.0]);
            let y = DVector::from_row_slice(&[1.0, -2.0, 0.5]);
            let mut b = &well * &y;
            assert_eq!(solver.solve(&well, &mut b).unwrap(), SolveKind::Lu);
            assert!((b - &y).amax() < 1e-14);
        }
        // truly singular stays singular: rank 2 in any units
        let singular = DMatrix::from_row_slice(3, 3, &[1e12, 3e5, 0.0, 2e5, 1e-6, 0.0, 0.0, 0.0, 0.0]);
        let mut b = DVector::from_row_slice(&[1.0, 1.0, 0.0]);
        assert_eq!(
            DenseSolver::new(3).solve(&singular, &mut b).unwrap(),
            SolveKind::MinNorm
        );
    }

    /// The sizes compiled on their own and the others (1, beyond 24) are
    /// solved alike, with row exchanges: a matrix whose pivots come from
    /// below the diagonal.
    #[test]
    fn every_size_is_solved_with_its_pivots() {
        for n in [1, 2, 5, 24, 25, 31] {
            // a small diagonal, the row below each one large: every column
            // exchanges rows
            let a = DMatrix::from_fn(n, n, |i, j| match i as i64 - j as i64 {
                0 => 1e-3,
                1 => 4.0 + j as f64,
                _ => 1.0 / (1.0 + (i + 2 * j) as f64),
            });
            let x = DVector::from_fn(n, |i, _| 1.0 - 0.1 * i as f64);
            let mut b = &a * &x;
            let mut solver = DenseSolver::new(n);
            assert_eq!(solver.solve(&a, &mut b).unwrap(), SolveKind::Lu, "n = {n}");
            // the error is of the order of eps cond: the condition is
            // 2.4e3 at most here, eps cond 5.3e-13
            assert!((b - &x).amax() < 1e-12, "n = {n}");
        }
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

    /// Two stages, equation 0 and unknown 0 in both: the first stage's
    /// block is the entry of the second's at those labels, and one LU of
    /// the second solves both; where the entries differ, each block is
    /// factored on its own. Either way the solution is the dense solve's.
    #[test]
    fn nested_stage_blocks_share_one_lu() {
        let form = Triangular::from_stages(&[-1, 0, 0], &[-1, 0, 0])
            .unwrap()
            .with_labels(&[0, 0, 1], &[0, 0, 1]);
        let x = DVector::from_row_slice(&[1.0, -2.0, 0.5]);
        for (entry, lus) in [(2.0, 1), (2.5, 2)] {
            let a = DMatrix::from_row_slice(3, 3, &[2.0, 0.0, 0.0, 5.0, entry, 1.0, 3.0, 4.0, 7.0]);
            let mut solver = DenseSolver::equilibrated(3);
            solver.set_triangular(form.clone());
            let mut b = &a * &x;
            assert_eq!(solver.solve(&a, &mut b).unwrap(), SolveKind::Lu);
            // well-conditioned 3x3: a few ulps
            assert!((b - &x).amax() < 1e-14);
            assert_eq!(solver.factorisations(), lus, "entry {entry}");
        }
    }

    #[test]
    fn labels_order_each_block_as_the_last_one_leads() {
        // row 1 is equation 0 at stage -1; rows 2 and 0 equations 0 and 1
        // at stage 0 (in that order once labelled); columns likewise
        let form = Triangular::from_stages(&[0, -1, 0], &[0, -1, 0])
            .unwrap()
            .with_labels(&[1, 0, 0], &[1, 0, 0]);
        assert_eq!(form.block(1), Some((&[2, 0][..], &[2, 0][..])));
        // the stage -1 block (entry (1, 1)) is the stage 0 block's (2, 2)
        let a = DMatrix::from_row_slice(3, 3, &[7.0, 3.0, 4.0, 0.0, 2.0, 0.0, 1.0, 5.0, 2.0]);
        let x = DVector::from_row_slice(&[0.5, 1.0, -2.0]);
        let mut solver = DenseSolver::equilibrated(3);
        solver.set_triangular(form);
        let mut b = &a * &x;
        assert_eq!(solver.solve(&a, &mut b).unwrap(), SolveKind::Lu);
        assert!((b - &x).amax() < 1e-14);
        assert_eq!(solver.factorisations(), 1);
    }

    #[test]
    fn zero_matrix_is_an_error() {
        let a = DMatrix::zeros(2, 2);
        let mut b = DVector::from_row_slice(&[1.0, 1.0]);
        assert!(DenseSolver::new(2).solve(&a, &mut b).is_err());
    }
}
