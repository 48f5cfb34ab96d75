//! Minimal coordinates of a redundant state (`phi(mu) = q`, `P mu' = q'`)
//! and the output Jacobian `D2 phi_x` of eq. (12): its condition check and
//! the servo solves with it.

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::error::Error;
use crate::init::CONSISTENCY_TOLERANCE;
use crate::linsolve::DenseSolver;
use crate::model::MinimalMap;
use crate::solution::State;

/// Condition estimate of `D2 phi_x` above which the split is refused: beyond
/// it the servo constraints no longer determine `mu2` to more than 4 digits.
pub const OUTPUT_JACOBIAN_CONDITION_LIMIT: f64 = 1e12;

/// Find minimal coordinates for a redundant start: `phi(mu0) = q0` by
/// Gauss-Newton from `mu_guess`, and `mu0'` from `P mu0' = q0'` (least squares).
pub fn minimal_start<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
) -> Result<(SVector<f64, F>, SVector<f64, F>), Error>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    let (mu, mu_dot, p) = minimal_coordinates(model, start, mu_guess)?;
    let tolerance = 1e-9 * start.v.amax().max(1.0);
    let residual = (p * mu_dot - start.v).amax();
    if residual > tolerance {
        return Err(Error::InconsistentStart {
            equation: "q0' = P mu0' (eq. 8)".into(),
            residual,
            tolerance,
        });
    }
    Ok((mu, mu_dot))
}

/// Minimal coordinates `mu`, their rates `mu'` and `P = D phi(mu)`.
pub(super) type MinimalCoordinates<const N: usize, const F: usize> =
    (SVector<f64, F>, SVector<f64, F>, SMatrix<f64, N, F>);

/// `mu` with `phi(mu) = q` by Gauss-Newton from `mu_guess`, the least-squares
/// `mu'` of `P mu' = q'` (the projection of `q'` onto the motions the map
/// allows) and `P`; allocation-free.
pub(super) fn minimal_coordinates<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
) -> Result<MinimalCoordinates<N, F>, Error>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    const MAX_ITERATIONS: usize = 50;
    let mut mu = *mu_guess;
    let scale = state.q.amax().max(1.0);
    // normal equations P^T P x = P^T rhs (P has full column rank for a
    // map that satisfies eq. 12; its condition is ~10 on the built-in maps)
    let least_squares = |p: &SMatrix<f64, N, F>, rhs: &SVector<f64, N>| {
        nalgebra::linalg::Cholesky::new(p.tr_mul(p)).map(|c| c.solve(&p.tr_mul(rhs)))
    };
    let mut last = f64::INFINITY;
    for iteration in 0..=MAX_ITERATIONS {
        let residual = state.q - model.phi(&mu);
        let p = model.null_space(&mu);
        let size = residual.amax();
        // phi(mu) = q to round-off; or, for a start that holds g(q) = 0 only
        // to the consistency checks' tolerance (no mu maps onto it
        // exactly), the closest mu: Gauss-Newton has stopped gaining (the
        // residual no longer halves) within that tolerance
        let closest = size >= 0.5 * last && size <= CONSISTENCY_TOLERANCE * scale;
        last = size;
        if size <= 1e-12 * scale || closest {
            let mu_dot = least_squares(&p, &state.v).ok_or(Error::NonFinite {
                quantity: "minimal start velocity",
                t: state.t,
            })?;
            return Ok((mu, mu_dot, p));
        }
        if iteration == MAX_ITERATIONS || !residual.amax().is_finite() {
            return Err(Error::MinimalStartNotFound {
                iterations: iteration,
                residual: residual.amax(),
            });
        }
        let step = least_squares(&p, &residual).ok_or(Error::MinimalStartNotFound {
            iterations: iteration,
            residual: residual.amax(),
        })?;
        mu += step;
    }
    Err(Error::MinimalStartNotFound {
        iterations: MAX_ITERATIONS,
        residual: f64::NAN,
    })
}

/// `D2 phi_x`, the load rows of `P` in the columns of `mu2` (eq. 12), with
/// the workspace of its solves.
#[derive(Debug, Clone)]
pub(super) struct OutputJacobian {
    solver: DenseSolver,
    matrix: DMatrix<f64>,
    rhs: DVector<f64>,
}

impl OutputJacobian {
    /// Workspace for `a` load coordinates.
    pub(super) fn new(a: usize) -> Self {
        Self {
            solver: DenseSolver::new(a),
            matrix: DMatrix::zeros(a, a),
            rhs: DVector::zeros(a),
        }
    }

    /// Take `D2 phi_x` from `P`.
    pub(super) fn set<const N: usize, const F: usize, const A: usize>(&mut self, p: &SMatrix<f64, N, F>) {
        let (off, split) = (N - A, F - A);
        for i in 0..A {
            for k in 0..A {
                self.matrix[(i, k)] = p[(off + i, split + k)];
            }
        }
    }

    /// Refuse an ill-conditioned `D2 phi_x` of `P` (eq. 12): 1-norm
    /// condition estimate `|D| |D^-1|` with the inverse from one LU.
    pub(super) fn check<const N: usize, const F: usize, const A: usize>(
        &mut self,
        p: &SMatrix<f64, N, F>,
        t: f64,
    ) -> Result<(), Error> {
        self.set::<N, F, A>(p);
        let norm1 = |m: &DMatrix<f64>| {
            m.column_iter()
                .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
                .fold(0.0, f64::max)
        };
        let d_norm = norm1(&self.matrix);
        let inverse_norm = self.solver.inverse_norm1(&self.matrix);
        let condition = d_norm * inverse_norm;
        if !(condition <= OUTPUT_JACOBIAN_CONDITION_LIMIT) {
            return Err(Error::SingularOutputJacobian { t, condition });
        }
        Ok(())
    }

    /// `x` with `D2 phi_x x = rhs(i)` (the matrix of the last [`set`](Self::set)).
    pub(super) fn solve<const A: usize>(
        &mut self,
        rhs: impl Fn(usize) -> f64,
        t: f64,
    ) -> Result<SVector<f64, A>, Error> {
        for i in 0..A {
            self.rhs[i] = rhs(i);
        }
        self.solver
            .solve(&self.matrix, &mut self.rhs)
            .map_err(|_| Error::SingularOutputJacobian {
                t,
                condition: f64::INFINITY,
            })?;
        Ok(SVector::from_fn(|k, _| self.rhs[k]))
    }
}
