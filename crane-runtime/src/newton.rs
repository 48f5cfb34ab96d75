//! Newton's method with an exact iteration matrix for the square system of
//! one step of any problem on any scheme (eqs. 22a-d, 24b-e, the forward
//! dynamics), with a relative stopping test per block of unknowns (on the
//! update, or on the error it leaves estimated from the observed
//! contraction) and a minimum-norm step on a singular matrix.

use std::ops::Range;

use nalgebra::{DMatrix, DVector};

use crate::linsolve::{DenseSolver, SolveKind, Stages, Triangular};

/// A square nonlinear system `r(z) = 0`.
pub trait NonlinearSystem {
    /// Number of unknowns (and equations).
    fn dim(&self) -> usize;

    /// Write the residual `r(z)` and the iteration matrix `J = dr/dz`.
    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>);

    /// The residual `r` and iteration matrix `jac` of the last
    /// [`evaluate`](Self::evaluate), at `z`: the residual normalised row by
    /// row by the size of the terms that make it up (`max_i |r_i| /
    /// scale_i`), so that round-off shows as ~1e-16. Newton asks for it
    /// only where neither its update tests nor its quadratic stop end the
    /// solve.
    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64;

    /// Blocks of unknowns that each get their own relative stopping test
    /// (e.g. coordinates, scaled inputs, scaled multipliers).
    fn blocks(&self) -> &[Range<usize>];

    /// The sizes the relative stopping tests judge the unknowns `z` by:
    /// `z` itself (the default), or, for unknowns that are corrections to
    /// a base the system holds, what they correct (base plus correction,
    /// as of the last [`evaluate`](Self::evaluate)).
    fn magnitudes<'a>(&'a self, z: &'a DVector<f64>) -> &'a DVector<f64> {
        z
    }

    /// The block lower triangular form of the Jacobian, if it has one
    /// whatever `z` (then the linear solves take it block by block); `None`
    /// (the default): a dense Jacobian.
    fn triangular(&self) -> Option<Triangular> {
        None
    }

    /// One update of `z` taken stage by stage where the system evaluates its
    /// blocks itself: each block's residual at the blocks before it as
    /// updated, solved with the leading part of `stages`' one LU (a Newton
    /// step whose off-diagonal blocks are applied by evaluating the residual
    /// at the updated blocks, not by their derivatives: its error is
    /// quadratic in the update, as Newton's). `z` updated in place and the
    /// update in `dz` (`z_new = z_old - dz`); `Some(false)` where a block
    /// could not be solved (`z` then as the caller must restore it), `None`
    /// (the default) where the system cannot, and Newton evaluates and
    /// solves as usual.
    fn staged_update(&mut self, z: &mut DVector<f64>, dz: &mut DVector<f64>, stages: Stages<'_>) -> Option<bool> {
        let _ = (z, dz, stages);
        None
    }

    /// Whether successive solves are of nearby systems (one per time step
    /// of smooth data, each started close to its solution), so that Newton
    /// carries over what it learned ([`Newton::solve`]): the equilibration's
    /// scales ([`DenseSolver::solve_with_kept_scales`]) and the size of
    /// its quadratic term. `false` by default: each solve on its own.
    fn nearby_solves(&self) -> bool {
        false
    }
}

/// The residual normalised row by row, `max_i |r_i| / max(floor(i), sum_j
/// |J_ij z_j|)`: `sum_j |J_ij z_j|` is the residual a relative perturbation of
/// the unknowns causes, so round-off shows as ~1e-16 even in rows whose terms
/// nearly vanish; `floor(i)` adds other sizes of row `i` (its largest term).
/// A row with zero scale (every term vanishes at this iterate) is judged by
/// its absolute residual: it is converged only at exactly zero, and Newton
/// goes on (it used to report a non-finite iterate there).
pub fn normalised_residual(
    r: &DVector<f64>,
    jac: &DMatrix<f64>,
    z: &DVector<f64>,
    floor: impl Fn(usize) -> f64,
) -> f64 {
    // row sums in column order over chunks of rows (the matrix is stored by
    // columns): each row's sum adds its terms in the order j = 0, 1, ...
    const CHUNK: usize = 32;
    let (rows, entries) = (jac.nrows(), jac.as_slice());
    let mut normalised = 0.0f64;
    for first in (0..r.len()).step_by(CHUNK) {
        let len = CHUNK.min(r.len() - first);
        let mut sums = [0.0f64; CHUNK];
        for (j, &zj) in z.iter().enumerate() {
            let column = &entries[j * rows + first..j * rows + first + len];
            for (sum, &entry) in sums.iter_mut().zip(column) {
                *sum += (entry * zj).abs();
            }
        }
        for (k, &sum) in sums[..len].iter().enumerate() {
            let i = first + k;
            normalised = normalised.max(row_ratio(r[i], sum.max(floor(i))));
        }
    }
    normalised
}

/// The entries of an `n x n` matrix that are not zero by structure, row
/// by row, each row's in column order (for [`normalised_residual_sparse`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowPattern {
    /// Where each row's entries start in `entries` (one more than rows).
    starts: Vec<usize>,
    /// `(column, index of the entry by columns, j n + i)`.
    entries: Vec<(usize, usize)>,
}

impl RowPattern {
    /// The pattern of the entries `(i, j)` of an `n x n` matrix given by
    /// their indices by columns, `j n + i`, in any order (those beyond the
    /// matrix are left out).
    ///
    /// ```
    /// use crane_runtime::newton::RowPattern;
    /// // [[a, 0], [b, c]]: entries 0 (0, 0), 1 (1, 0), 3 (1, 1)
    /// let pattern = RowPattern::new(2, &[3, 0, 1]);
    /// assert_eq!(pattern.row(1).collect::<Vec<_>>(), [0, 1]);
    /// assert_eq!(pattern.row(0).collect::<Vec<_>>(), [0]);
    /// ```
    pub fn new(n: usize, nonzeros: &[u32]) -> Self {
        let mut sorted: Vec<(usize, usize)> = (nonzeros.iter())
            .map(|&k| k as usize)
            .filter(|&k| k < n * n)
            .map(|k| (k % n, k / n))
            .collect();
        sorted.sort_unstable();
        sorted.dedup();
        let mut starts = Vec::with_capacity(n + 1);
        let mut entries = Vec::with_capacity(sorted.len());
        for row in 0..n {
            starts.push(entries.len());
            entries.extend(sorted.iter().filter(|&&(i, _)| i == row).map(|&(i, j)| (j, j * n + i)));
        }
        starts.push(entries.len());
        Self { starts, entries }
    }

    /// The columns of row `i`'s entries, in order.
    pub fn row(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        let span = self.starts.get(i).copied().unwrap_or(0)..self.starts.get(i + 1).copied().unwrap_or(0);
        self.entries[span].iter().map(|&(j, _)| j)
    }
}

/// [`normalised_residual`] of a Jacobian whose entries outside `pattern`
/// are zero, without the floor: each row's sum over its entries in the
/// pattern only, added in the same order (so the same number) in a
/// register, row after row.
pub fn normalised_residual_sparse(r: &DVector<f64>, jac: &DMatrix<f64>, z: &DVector<f64>, pattern: &RowPattern) -> f64 {
    let entries = jac.as_slice();
    let mut normalised = 0.0f64;
    for (&ri, span) in r.iter().zip(pattern.starts.windows(2)) {
        let mut sum = 0.0;
        for &(j, entry) in &pattern.entries[span[0]..span[1]] {
            sum += (entries[entry] * z[j]).abs();
        }
        normalised = normalised.max(row_ratio(ri, sum));
    }
    normalised
}

/// Whether every entry of `xs` is finite: a fold over all of them, without
/// the early exit that keeps the test from running on several at once.
fn all_finite(xs: &[f64]) -> bool {
    xs.iter().fold(true, |finite, x| finite & x.is_finite())
}

/// The largest magnitude in `xs` (0 for none), for finite `xs`.
fn largest(xs: &[f64]) -> f64 {
    xs.iter().fold(0.0, |largest, x| largest.max(x.abs()))
}

/// A row's residual `ri` in units of its `scale`, or as it is where the
/// scale is zero (or not a number).
fn row_ratio(ri: f64, scale: f64) -> f64 {
    if scale > 0.0 { ri.abs() / scale } else { ri.abs() }
}

/// Tolerances of [`Newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Relative tolerance on each block's update: `|dz_B| <= rtol |z_B| + atol`
    /// (infinity norms), or on the error the update leaves, estimated as
    /// `theta / (1 - theta) |dz_B|` from the contraction `theta` of
    /// successive updates.
    pub rtol: f64,
    /// Absolute floor of the update test, in the units of the scaled unknowns.
    pub atol: f64,
    /// A normalised residual (see [`NonlinearSystem::normalised_residual`]) at or below
    /// this is converged whatever the update: near a singular iteration matrix
    /// round-off in the update exceeds `rtol` although the equations hold to
    /// working precision (docs/numerics.md, dt = 0.001).
    pub residual_tol: f64,
    /// Iteration limit per solve.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    /// `rtol = 1e-10`, `atol = 1e-14`, `residual_tol = 1e-13` (a few
    /// hundred ulps), at most 30 iterations.
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-14,
            residual_tol: 1e-13,
            max_iterations: 30,
        }
    }
}

/// How a Newton solve ended, when it converged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Converged {
    /// Iterations taken (linear solves).
    pub iterations: usize,
    /// Of those, minimum-norm steps on a singular iteration matrix.
    pub min_norm_steps: usize,
}

/// Why a Newton solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NewtonFailure {
    /// Iteration limit reached.
    NotConverged {
        /// Iterations taken.
        iterations: usize,
        /// Residual infinity norm at the last evaluation.
        residual: f64,
    },
    /// Singular iteration matrix that even the minimum-norm step could not handle.
    Singular {
        /// Iterations taken, the failing one included.
        iterations: usize,
        /// Smallest-to-largest LU pivot ratio.
        pivot_ratio: f64,
    },
    /// The residual or the update became NaN or infinite.
    NonFinite {
        /// Iterations taken, the failing one included.
        iterations: usize,
    },
}

impl NewtonFailure {
    /// The iterations (linear solves and evaluations) the failed solve
    /// took: what a retry adds to its own count.
    pub fn iterations(&self) -> usize {
        match *self {
            NewtonFailure::NotConverged { iterations, .. }
            | NewtonFailure::Singular { iterations, .. }
            | NewtonFailure::NonFinite { iterations } => iterations,
        }
    }
}

/// How far above the residual tolerance a held solve may stop (see
/// [`Newton::set_hold`]): the residual left along a held direction, a force
/// of round-off size against a nearly slack rope (measured where navy-3d's
/// slack start was held at dt = 0.01 s: 7.5e-13, where the tolerance is
/// 1e-13).
pub const HELD_RESIDUAL: f64 = 1e3;

/// The largest update, relative to the unknowns, that the quadratic error
/// estimate of [nearby solves](NonlinearSystem::nearby_solves) judges:
/// about where the predictions of smooth jets land (updates of 1e-10 to
/// 3.5e-10 relative on navy-planar at dt = 0.01); larger ones, at the start
/// and where the path's derivatives jump, are confirmed by another
/// iteration.
pub const QUADRATIC_UPDATE: f64 = 1e-9;

/// The estimated relative error at which a solve of nearby systems ends
/// after an update (see [`Newton::solve`]): a dozen ulps (and at most the
/// tolerance, where that is smaller).
pub const QUADRATIC_ERROR: f64 = 3e-15;

/// The factor by which the quadratic term's estimate grows at each solve
/// that it ends where the tests on the update do not, so that it is
/// confirmed by a second iteration every few solves and follows a term
/// that grows by up to a tenth per solve (navy-planar at dt = 0.01: 1.18
/// iterations per step instead of 1.13, the double pendulum 1.09 instead
/// of 1.05).
pub const QUADRATIC_AGING: f64 = 1.1;

/// The largest update, relative to the unknowns, after which the next
/// staged update of the same solve keeps the factors of the last one (a
/// chord step): their matrix is off by about the updates since, and the
/// error the chord step leaves is about the quadratic term times its own
/// update times those (against its own update squared for Newton's), which
/// the quadratic stop takes into account.
pub const CHORD_UPDATE: f64 = 1e-6;

/// Newton's method with preallocated workspace: `solve` does not allocate.
#[derive(Debug, Clone)]
pub struct Newton {
    options: NewtonOptions,
    solver: DenseSolver,
    residual: DVector<f64>,
    jac: DMatrix<f64>,
    /// The iterate and residual of the last evaluation, kept for the
    /// residual test once the update has replaced them.
    evaluated_at: DVector<f64>,
    evaluated: DVector<f64>,
    /// The quadratic term of the last solves, `w_2 / w_1^2` over two
    /// successive updates of an LU in tolerance units, the largest seen,
    /// halved at each new one (infinite before the first).
    quadratic: f64,
    /// Updates taken stage by stage ([`NonlinearSystem::staged_update`]).
    staged_updates: usize,
    /// Of those, updates with the factors of the update before
    /// ([`CHORD_UPDATE`]).
    chord_updates: usize,
}

impl Newton {
    /// Workspace for systems of dimension `n`.
    pub fn new(n: usize, options: NewtonOptions) -> Self {
        Self {
            options,
            solver: DenseSolver::new(n),
            residual: DVector::zeros(n),
            jac: DMatrix::zeros(n, n),
            evaluated_at: DVector::zeros(n),
            evaluated: DVector::zeros(n),
            quadratic: f64::INFINITY,
            staged_updates: 0,
            chord_updates: 0,
        }
    }

    /// Workspace for systems of dimension `n` whose matrices are equilibrated
    /// before each solve (see [`DenseSolver::equilibrated`]).
    pub fn equilibrated(n: usize, options: NewtonOptions) -> Self {
        Self {
            solver: DenseSolver::equilibrated(n),
            ..Self::new(n, options)
        }
    }

    /// Take minimum-norm steps whatever the pivots (see
    /// [`DenseSolver::set_hold`]): the solve holds the directions the
    /// iteration matrix barely determines, and ends once the residual stops
    /// falling at most [`HELD_RESIDUAL`] times the residual tolerance.
    pub fn set_hold(&mut self, hold: bool) {
        self.solver.set_hold(hold);
    }

    /// Solve the linear systems of every iteration as ones of the block
    /// lower triangular `form` ([`DenseSolver::set_triangular`]).
    pub fn set_triangular(&mut self, form: Triangular) {
        self.solver.set_triangular(form);
    }

    /// The linear solver's form, if any.
    pub fn triangular(&self) -> Option<&Triangular> {
        self.solver.triangular()
    }

    /// Iterations whose update the system took stage by stage
    /// ([`NonlinearSystem::staged_update`]) so far.
    pub fn staged_updates(&self) -> usize {
        self.staged_updates
    }

    /// Of the [`staged_updates`](Self::staged_updates), those that kept the
    /// factors of the update before ([`CHORD_UPDATE`]).
    pub fn chord_updates(&self) -> usize {
        self.chord_updates
    }

    /// Find the equilibration's scale factors anew at the next solve
    /// ([`DenseSolver::forget_scales`]).
    pub fn forget_scales(&mut self) {
        self.solver.forget_scales();
    }

    /// The pivot ratio of the last LU of an iteration matrix
    /// ([`DenseSolver::pivot_ratio`]).
    pub fn pivot_ratio(&self) -> f64 {
        self.solver.pivot_ratio()
    }

    /// LU factorisations of the iteration matrices so far
    /// ([`DenseSolver::factorisations`]).
    pub fn factorisations(&self) -> usize {
        self.solver.factorisations()
    }

    /// The tolerances in use.
    pub fn options(&self) -> &NewtonOptions {
        &self.options
    }

    /// Solve `r(z) = 0` starting from `z`, which holds the solution on success.
    ///
    /// For [nearby solves](NonlinearSystem::nearby_solves), an update of at
    /// most [`QUADRATIC_UPDATE`] relative ends the solve where the error it
    /// leaves, estimated from the quadratic term learned in earlier solves,
    /// is at most [`QUADRATIC_ERROR`] relative: round-off, which another
    /// evaluation and solve would only confirm. Each solve so ended ages the
    /// estimate by [`QUADRATIC_AGING`].
    ///
    /// The residual test ([`NonlinearSystem::normalised_residual`]) is asked
    /// only where the updates leave the solve open: most steps of nearby
    /// solves end without it.
    pub fn solve<S: NonlinearSystem + ?Sized>(
        &mut self,
        system: &mut S,
        z: &mut DVector<f64>,
    ) -> Result<Converged, NewtonFailure> {
        let mut min_norm_steps = 0;
        let nearby = system.nearby_solves();
        // the previous update in tolerance units (none before the first)
        let mut last_w = f64::INFINITY;
        let mut last_residual = f64::INFINITY;
        // whether the last update was an LU's, and small
        let (mut last_lu, mut last_small) = (false, false);
        // whether the last update was staged, and below CHORD_UPDATE; and
        // whether it was taken with factors of its own iterate
        let (mut last_chordable, mut last_fresh) = (false, false);
        // the updates since the factors in use were taken (tolerance units)
        let mut drift = 0.0;
        for iteration in 1..=self.options.max_iterations {
            self.evaluated_at.copy_from(z);
            // the update stage by stage, where the system takes it (z and
            // dz then written, the residual not evaluated at one iterate)
            let rescale = !nearby && iteration == 1;
            let staged = match self.solver.stages(rescale, last_chordable) {
                Some(stages) => system.staged_update(z, &mut self.residual, stages),
                None => None,
            };
            let evaluated = staged != Some(true);
            let kind = if evaluated {
                if staged == Some(false) {
                    z.copy_from(&self.evaluated_at);
                }
                self.evaluate_and_solve(system, z, iteration, nearby)?
            } else {
                self.staged_updates += 1;
                self.chord_updates += usize::from(last_chordable);
                if !all_finite(self.residual.as_slice()) {
                    // the iterate as it was, as an evaluated update leaves it
                    z.copy_from(&self.evaluated_at);
                    return Err(NewtonFailure::NonFinite { iterations: iteration });
                }
                SolveKind::Lu
            };
            // a chord update's matrix is off by the updates since its
            // factors were taken
            let chord = !evaluated && last_chordable;
            let drift_now = if chord { drift } else { 0.0 };
            if kind == SolveKind::MinNorm {
                min_norm_steps += 1;
            }
            let dz = &self.residual;
            // the update in units of the tolerance, the largest over blocks:
            // `w <= 1` is `|dz_B| <= rtol |z_B| + atol` for every block
            let w = system
                .blocks()
                .iter()
                .map(|block| {
                    let step = largest(&dz.as_slice()[block.clone()]);
                    let size = largest(&system.magnitudes(z).as_slice()[block.clone()]);
                    step / (self.options.rtol * size + self.options.atol)
                })
                .fold(0.0, f64::max);
            // after the first iteration, the error left by this update is
            // estimated from the observed contraction theta = w_k / w_(k-1):
            // |z_k - z*| <= theta / (1 - theta) |dz_k| (Hairer and Wanner,
            // Solving ODEs II, IV.8), so a converged step is recognised
            // without another evaluation and solve
            let contraction = w / last_w;
            // (not after a minimum-norm step: on a singular matrix the
            // updates do not contract along the free direction, and their
            // ratio says nothing about the error left there)
            let left = if kind == SolveKind::Lu && last_w.is_finite() && contraction < 1.0 {
                contraction / (1.0 - contraction) * w
            } else {
                f64::INFINITY
            };
            // Newton's error after an update w is about kappa w^2 (in
            // tolerance units; kappa w^2 rtol relative), kappa learned from
            // two successive LU updates the size of those it judges (the
            // second mostly round-off, so the estimate errs large), the
            // first with factors of its own iterate (the second measures
            // the error it left, whatever its own factors); a chord update
            // with factors taken a drift d away leaves about kappa w (w + d)
            let small = w * self.options.rtol <= QUADRATIC_UPDATE;
            if nearby && kind == SolveKind::Lu && last_lu && last_fresh && last_small && last_w > 0.0 {
                // a second update of exactly zero (a residual at zero by
                // round-off) says the first left round-off, not that there
                // is no quadratic term: four ulps at least
                let observed = w.max(4.0 * f64::EPSILON / self.options.rtol) / (last_w * last_w);
                self.quadratic = if self.quadratic.is_finite() {
                    observed.max(0.5 * self.quadratic)
                } else {
                    observed
                };
            }
            // (at most one tolerance unit, where the tolerance is below
            // the round-off the bound speaks of)
            let quadratic_converged = nearby
                && kind == SolveKind::Lu
                && small
                && self.quadratic * w * (w + drift_now) <= (QUADRATIC_ERROR / self.options.rtol).min(1.0);
            last_lu = kind == SolveKind::Lu;
            last_small = small;
            last_chordable = !evaluated && w * self.options.rtol <= CHORD_UPDATE;
            last_fresh = !chord;
            drift = drift_now + w;
            last_w = w;
            let update_converged = w <= 1.0 || left <= 1.0;
            // a solve the estimate ends without the update tests ages it: a
            // term that grows by less than that per solve stays below it,
            // and a faster one meets a confirming iteration within a few
            // solves
            if quadratic_converged && !update_converged {
                self.quadratic *= QUADRATIC_AGING;
            }
            // the residual, where the updates leave the solve open (a held
            // solve's steps are minimum-norm ones, which the quadratic stop
            // never ends: its residual is compared at every iteration that
            // does not end on the update)
            // (a staged update's residual is evaluated here, after its first
            // iteration: before, the next update is the cheaper test)
            let residual_converged = if !(update_converged || quadratic_converged) && (evaluated || iteration > 1) {
                if !evaluated {
                    system.evaluate(&self.evaluated_at, &mut self.evaluated, &mut self.jac);
                }
                let normalised = system.normalised_residual(&self.evaluated_at, &self.evaluated, &self.jac);
                if !normalised.is_finite() {
                    return Err(NewtonFailure::NonFinite { iterations: iteration });
                }
                // a held step is done once the residual no longer halves:
                // what is left lies along the held direction, whose solve
                // would move it (by the slow creep of the damped steps)
                // where round-off puts it
                let held_converged = self.solver.holds()
                    && normalised <= HELD_RESIDUAL * self.options.residual_tol
                    && normalised > 0.5 * last_residual;
                last_residual = normalised;
                // a residual at round-off level (normalised) ends the solve,
                // but only after the step it gives is applied: the row
                // normalisation is dominated by the largest columns, so an
                // unknown with a small column (a light coordinate of the
                // minimal formulation) can still be off by far more than
                // round-off when the residual test holds (measured: 5e-8 m
                // in q on navy-planar-pulley, BDF-5 at dt = 0.005)
                normalised <= self.options.residual_tol || held_converged
            } else {
                false
            };
            if update_converged || quadratic_converged || residual_converged {
                return Ok(Converged {
                    iterations: iteration,
                    min_norm_steps,
                });
            }
        }
        system.evaluate(z, &mut self.residual, &mut self.jac);
        Err(NewtonFailure::NotConverged {
            iterations: self.options.max_iterations,
            residual: self.residual.amax(),
        })
    }

    /// The classic iteration's update: the residual and Jacobian evaluated
    /// at `z` (kept for the residual test) and `J dz = r` solved in the
    /// residual buffer, `z -= dz`.
    fn evaluate_and_solve<S: NonlinearSystem + ?Sized>(
        &mut self,
        system: &mut S,
        z: &mut DVector<f64>,
        iteration: usize,
        nearby: bool,
    ) -> Result<SolveKind, NewtonFailure> {
        system.evaluate(z, &mut self.residual, &mut self.jac);
        if !all_finite(self.residual.as_slice()) {
            return Err(NewtonFailure::NonFinite { iterations: iteration });
        }
        self.evaluated.copy_from(&self.residual);
        // dz = J^{-1} r, computed in place in the residual buffer; z -= dz
        // an equilibrated solver finds its scale factors on the first
        // iteration and keeps them for the later ones of this solve (or
        // for good, where the system says they serve)
        let solved = if nearby {
            self.solver.solve_with_kept_scales(&self.jac, &mut self.residual)
        } else if iteration == 1 {
            self.solver.solve(&self.jac, &mut self.residual)
        } else {
            self.solver.solve_with_last_scales(&self.jac, &mut self.residual)
        };
        let kind = solved.map_err(|singular| NewtonFailure::Singular {
            iterations: iteration,
            pivot_ratio: singular.pivot_ratio,
        })?;
        if !all_finite(self.residual.as_slice()) {
            return Err(NewtonFailure::NonFinite { iterations: iteration });
        }
        *z -= &self.residual;
        Ok(kind)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `z^2 - 2 = 0` from `z = 1`, whose evaluation turns NaN from the
    /// `nan_from`-th on: a failed solve reports how far it got.
    struct Square {
        evaluations: usize,
        nan_from: usize,
        block: Range<usize>,
    }

    impl NonlinearSystem for Square {
        fn dim(&self) -> usize {
            1
        }
        fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
            self.evaluations += 1;
            if self.evaluations >= self.nan_from {
                r[0] = f64::NAN;
                return;
            }
            r[0] = z[0] * z[0] - 2.0;
            jac[(0, 0)] = 2.0 * z[0];
        }
        fn normalised_residual(&self, _z: &DVector<f64>, r: &DVector<f64>, _jac: &DMatrix<f64>) -> f64 {
            (r[0] / 2.0).abs()
        }
        fn blocks(&self) -> &[Range<usize>] {
            std::slice::from_ref(&self.block)
        }
    }

    #[test]
    fn a_failed_solve_counts_its_iterations() {
        let mut newton = Newton::new(1, NewtonOptions::default());
        let mut system = Square {
            evaluations: 0,
            nan_from: 3,
            block: 0..1,
        };
        let failure = newton
            .solve(&mut system, &mut DVector::from_element(1, 1.0))
            .unwrap_err();
        assert_eq!(failure, NewtonFailure::NonFinite { iterations: 3 });
        assert_eq!(failure.iterations(), 3);
        // without the NaN it converges to sqrt(2) in a few iterations
        let mut system = Square {
            evaluations: 0,
            nan_from: usize::MAX,
            block: 0..1,
        };
        let mut z = DVector::from_element(1, 1.0);
        let converged = newton.solve(&mut system, &mut z).unwrap();
        assert!((z[0] - 2f64.sqrt()).abs() < 1e-14);
        assert!((4..=6).contains(&converged.iterations), "{converged:?}");
    }

    /// `z^2 = c` for a `c` that moves by 1e-9 relative between solves,
    /// each started from the last root (an update of 5e-10 relative, above
    /// the update test's 1e-10).
    struct Root {
        c: f64,
        nearby: bool,
        block: Range<usize>,
    }

    impl NonlinearSystem for Root {
        fn dim(&self) -> usize {
            1
        }
        fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
            r[0] = z[0] * z[0] - self.c;
            jac[(0, 0)] = 2.0 * z[0];
        }
        fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, _jac: &DMatrix<f64>) -> f64 {
            r[0].abs() / (2.0 * z[0] * z[0]).abs()
        }
        fn blocks(&self) -> &[Range<usize>] {
            std::slice::from_ref(&self.block)
        }
        fn nearby_solves(&self) -> bool {
            self.nearby
        }
    }

    /// Two stages: `z0^2 - 2 = 0`, then its time derivative with a
    /// source, `2 z0 z1 - 1 = 0`, whose block `2 z0` is the first's (one
    /// LU of it serves both). `staged`: the update stage by stage, through
    /// [`Stages`], each stage's residual at the stages before it as
    /// updated; or a staged update that fails after scribbling over `z`.
    struct TwoStages {
        staged: Option<bool>,
        block: Range<usize>,
    }

    impl NonlinearSystem for TwoStages {
        fn dim(&self) -> usize {
            2
        }
        fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
            r[0] = z[0] * z[0] - 2.0;
            r[1] = 2.0 * z[0] * z[1] - 1.0;
            jac[(0, 0)] = 2.0 * z[0];
            jac[(1, 0)] = 2.0 * z[1];
            jac[(1, 1)] = 2.0 * z[0];
        }
        fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, _jac: &DMatrix<f64>) -> f64 {
            (r[0].abs() / (2.0 * z[0] * z[0])).max(r[1].abs() / (2.0 * z[0] * z[1]).abs())
        }
        fn blocks(&self) -> &[Range<usize>] {
            std::slice::from_ref(&self.block)
        }
        fn triangular(&self) -> Option<Triangular> {
            Triangular::from_stages(&[-1, 0], &[-1, 0]).map(|form| form.with_labels(&[0, 0], &[0, 0]))
        }
        fn staged_update(
            &mut self,
            z: &mut DVector<f64>,
            dz: &mut DVector<f64>,
            mut stages: Stages<'_>,
        ) -> Option<bool> {
            match self.staged? {
                false => {
                    z.fill(f64::NAN);
                    Some(false)
                }
                true => {
                    let (z, dz) = (z.as_mut_slice(), dz.as_mut_slice());
                    let jacobian = [2.0 * z[0]];
                    let first = [z[0] * z[0] - 2.0, 0.0];
                    if !(stages.factor(&jacobian) && stages.solve(0, &first, z, dz)) {
                        return Some(false);
                    }
                    let second = [0.0, 2.0 * z[0] * z[1] - 1.0];
                    Some(stages.solve(1, &second, z, dz))
                }
            }
        }
    }

    /// A staged update is Newton's to round-off, each taking one LU of the
    /// shared block per iteration; one that fails leaves `z` as it was and
    /// the iteration is taken whole.
    #[test]
    fn staged_updates_converge_as_whole_ones_and_a_failed_one_is_taken_whole() {
        let solve = |staged: Option<bool>| {
            let mut system = TwoStages { staged, block: 0..2 };
            let mut newton = Newton::equilibrated(2, NewtonOptions::default());
            if let Some(form) = system.triangular() {
                newton.set_triangular(form);
            }
            let mut z = DVector::from_row_slice(&[1.5, 0.3]);
            let converged = newton.solve(&mut system, &mut z).unwrap();
            let lus = newton.factorisations() + newton.chord_updates();
            (z, converged.iterations, newton.staged_updates(), lus)
        };
        let exact = [2f64.sqrt(), 1.0 / (2.0 * 2f64.sqrt())];
        for staged in [None, Some(true), Some(false)] {
            let (z, iterations, staged_updates, factorisations) = solve(staged);
            for (zi, ei) in z.iter().zip(exact) {
                assert!((zi - ei).abs() <= 4.0 * f64::EPSILON * ei, "{staged:?}: {z}");
            }
            let expected = if staged == Some(true) { iterations } else { 0 };
            assert_eq!(staged_updates, expected, "{staged:?}");
            // one LU per iteration, of the shared block, but for chord
            // updates (a failed staged update factors nothing: it fails
            // before)
            assert_eq!(factorisations, iterations, "{staged:?}");
        }
    }

    #[test]
    fn nearby_solves_end_where_the_quadratic_term_puts_the_error_at_round_off() {
        let iterations = |nearby: bool| {
            let mut newton = Newton::equilibrated(1, NewtonOptions::default());
            let mut system = Root {
                c: 2.0,
                nearby,
                block: 0..1,
            };
            let mut z = DVector::from_element(1, 2f64.sqrt());
            let mut counts = Vec::new();
            for _ in 0..100 {
                system.c *= 1.0 + 1e-9;
                counts.push(newton.solve(&mut system, &mut z).unwrap().iterations);
                // the root to a few ulps either way
                assert!((z[0] - system.c.sqrt()).abs() <= 4.0 * f64::EPSILON * z[0], "{}", z[0]);
            }
            counts
        };
        // each update of 5e-10 relative needs a second to confirm it
        assert!(iterations(false).iter().all(|&n| n == 2));
        // the first solve learns the quadratic term (w2 / w1^2, the second
        // update at round-off), the later ones end after one update but for
        // a confirming second iteration once the estimate has aged (every
        // eight or nine solves: 1.1^8 = 2.1, the halving at each new
        // observation undone)
        let counts = iterations(true);
        assert_eq!(counts[0], 2);
        let confirmed = counts[1..].iter().filter(|&&n| n == 2).count();
        assert!(counts.iter().all(|&n| n <= 2), "{counts:?}");
        assert!((5..=20).contains(&confirmed), "{counts:?}");
    }
}
