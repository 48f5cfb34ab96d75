//! Internal (zero) dynamics of the servo-constrained system: the motions
//! the prescribed load path leaves free, and whether they grow.
//!
//! Linearise `M q'' = f(q, q') + B^T(q) u - G^T(q) lambda`, `g(q) = 0`,
//! `x = gamma(t)` about a state of the solution, with the coefficients
//! frozen at that instant:
//! ```text
//! M dq'' = K dq + D dq' + B^T du - G^T dlambda,   G dq = 0,   dx = 0
//! K = df/dq + d(B^T u)/dq - d(G^T lambda)/dq,      D = df/dq'
//! ```
//! The inputs and multipliers drop out on the left null space of
//! `[B^T G^T]` (columns `Q`), and `dq = Z eta` with `Z` a basis of the null
//! space of `[G; S_x]` (the motions that keep the constraints and the load
//! on its path). What remains is
//! ```text
//! A2 eta'' + A1 eta' + A0 eta = 0,   A2 = Q^T M Z,  A1 = -Q^T D Z,  A0 = -Q^T K Z
//! ```
//! If `A2 = 0` the free coordinates are fixed algebraically by the path: the
//! crane is flat, no internal dynamics (the paper's planar cranes: the only
//! inertia in those directions is the load's, and `Z` does not move the
//! load). Otherwise, with `A2 = U S V^T` of rank `r`, the rows of `U^T` past
//! `r` hold no second derivatives; when they hold no first ones either they
//! fix the remaining coordinates algebraically, and the first `r` follow a
//! second-order ODE: internal dynamics of dimension `2r`, whose eigenvalues
//! are those of its companion matrix: the invariant zeros of the linearised
//! crane. A positive real part means the causal inverse
//! explodes along the path.
//!
//! The structure comes first where the model declares it
//! ([`CraneModel::STRUCTURE`], from `crane_model!`): Pryce's signature
//! method counts the states eqs. (22a-d) leave free, and where its system
//! Jacobian is regular at the state (reciprocal condition above 1e-8 after
//! scaling rows and columns) that count is the dimension. A flat crane is
//! then answered without the reduction above, which misses constraints
//! that act only through higher derivatives: `navy-3d-pulley`, whose pulley
//! mass sits in a free direction (`A2` of rank 1) yet which is flat, and
//! for which the reduction alone gave spurious pairs such as +-64.6 1/s.
//! Where the count is positive the reduction must find the same dimension,
//! or the state is reported as not resolved.
//!
//! The eigenvalues are frozen-time ones (the change of `Q`, `Z` along the
//! motion is left out): exact at rest, an indicator along a move.
//!
//! ```
//! # use crane_runtime::{CraneModel, State};
//! # fn demo<Mdl: CraneModel<4, 1, 2>>(model: &Mdl, start: &State<4, 1, 2>) {
//! let diagnosis = crane_runtime::internal::internal_dynamics(model, start).unwrap();
//! if diagnosis.dimension > 0 && !diagnosis.is_stable() {
//!     eprintln!("unstable internal dynamics: largest real part {:.3} 1/s", diagnosis.max_real_part);
//! }
//! # }
//! ```

use nalgebra::DMatrix;

use crate::model::{CraneModel, Structure};
use crate::solution::{Solution, State};

/// Relative size below which a singular value counts as zero (the inputs of
/// the decompositions are exact to round-off, ~1e-16 of their largest entry).
const RANK_TOLERANCE: f64 = 1e-9;

/// Smallest-to-largest singular value of the block that fixes the
/// coordinates without inertia, below which the reduction is refused.
const REDUCTION_TOLERANCE: f64 = 1e-6;

/// Reciprocal condition of Pryce's system Jacobian (rows and columns scaled
/// to largest entry 1) above which it counts as regular: the built-ins
/// measure 4e-3 to 4e-2 along their moves and exactly 0 where a rope
/// carries nothing (navy-planar at rest at its start) or a coupling is 0.
const REGULAR_TOLERANCE: f64 = 1e-8;

/// Largest real part counted as zero: round-off of an eigenvalue of a
/// companion matrix whose entries are `O(|A2^-1| |A0|)`.
const STABILITY_TOLERANCE: f64 = 1e-8;

/// The internal dynamics at one state.
#[derive(Debug, Clone, PartialEq)]
pub struct InternalDynamics {
    /// The time of the state.
    pub t: f64,
    /// Dimension of the internal dynamics, `2 rank(Q^T M Z)`; 0 for a flat
    /// crane.
    pub dimension: usize,
    /// Their eigenvalues `(re, im)` (frozen time); empty when `dimension` is 0.
    pub eigenvalues: Vec<(f64, f64)>,
    /// The largest real part (`-inf` when there are none), in 1/s.
    pub max_real_part: f64,
}

impl InternalDynamics {
    /// Whether no eigenvalue has a real part above round-off.
    pub fn is_stable(&self) -> bool {
        self.max_real_part <= STABILITY_TOLERANCE * self.eigenvalues.iter().map(|e| e.0.hypot(e.1)).fold(1.0, f64::max)
    }
}

/// Why the internal dynamics could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InternalDynamicsError {
    /// `[B^T G^T]` or `[G; S_x]` does not have full rank (dependent inputs
    /// and constraints, or constraints that fix the load): the projection is
    /// not square.
    #[error("the servo problem is not square at t = {t}: {left} free equations for {right} free coordinates")]
    NotSquare {
        /// Time of the state.
        t: f64,
        /// Dimension of the left null space of `[B^T G^T]`.
        left: usize,
        /// Dimension of the null space of `[G; S_x]`.
        right: usize,
    },
    /// `Q^T M Z` is neither zero nor regular and the rows without second
    /// derivatives hold first derivatives too (damping there), or do not fix
    /// the remaining coordinates: this diagnosis does not split that case.
    #[error("mixed structure at t = {t}: Q^T M Z has rank {rank} of {size}")]
    MixedRank {
        /// Time of the state.
        t: f64,
        /// Rank of `Q^T M Z`.
        rank: usize,
        /// Its size.
        size: usize,
    },
}

/// The columns of an orthonormal basis of the left null space of the
/// `n x k` matrix `w` (`k <= n`): the left singular vectors of `[w 0]`
/// (padded to square, so that the SVD returns all `n` of them) whose
/// singular values are below [`RANK_TOLERANCE`] of the largest. Accurate to
/// round-off (a Gram matrix `w w^T` would resolve only `sqrt(eps)`, and its
/// error, ~1e-8 of `|M|` in `Q^T M Z`, showed as a spurious eigenvalue of
/// 7e7 1/s on navy-3d-pulley).
fn left_null_basis(w: &DMatrix<f64>) -> DMatrix<f64> {
    let n = w.nrows();
    let mut padded = DMatrix::zeros(n, n);
    padded.columns_mut(0, w.ncols()).copy_from(w);
    let svd = padded.svd(true, false);
    let largest = svd.singular_values.amax();
    let columns: Vec<usize> = (0..n)
        .filter(|&i| svd.singular_values[i] <= RANK_TOLERANCE * largest.max(f64::MIN_POSITIVE))
        .collect();
    match svd.u {
        Some(u) => DMatrix::from_fn(n, columns.len(), |i, j| u[(i, columns[j])]),
        None => DMatrix::zeros(n, 0),
    }
}

/// Pryce's system Jacobian of eqs. (22a-d) at a state (see [`Structure`]):
/// row `i`, column `j` is the derivative of equation `i` with respect to the
/// `(c_j - d_i)`-th derivative of unknown `j`, and its reciprocal condition
/// number after scaling every row and column to largest entry 1 (`0` if
/// the offsets do not fit the sizes).
fn system_jacobian_condition(
    structure: &Structure,
    mass: &DMatrix<f64>,
    damping: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
    jac_g: &DMatrix<f64>,
    inputs: &DMatrix<f64>,
) -> f64 {
    let (n, m, a) = (mass.nrows(), jac_g.nrows(), inputs.ncols());
    let size = n + m + a;
    let (c, d) = (structure.unknowns, structure.equations);
    if c.len() != size || d.len() != size {
        return 0.0;
    }
    let order = |i: usize, j: usize| i64::from(c[j]) - i64::from(d[i]);
    let mut jac = DMatrix::zeros(size, size);
    for i in 0..n {
        for j in 0..n {
            // M q'' - f - B^T u + G^T lambda = 0
            jac[(i, j)] = match order(i, j) {
                2 => mass[(i, j)],
                1 => -damping[(i, j)],
                0 => -stiffness[(i, j)],
                _ => 0.0,
            };
        }
        for k in 0..m {
            if order(i, n + k) == 0 {
                jac[(i, n + k)] = jac_g[(k, i)];
            }
        }
        for r in 0..a {
            if order(i, n + m + r) == 0 {
                jac[(i, n + m + r)] = -inputs[(i, r)];
            }
        }
    }
    for k in 0..m {
        for j in 0..n {
            if order(n + k, j) == 0 {
                jac[(n + k, j)] = jac_g[(k, j)];
            }
        }
    }
    for r in 0..a {
        if order(n + m + r, n - a + r) == 0 {
            jac[(n + m + r, n - a + r)] = 1.0;
        }
    }
    for mut row in jac.row_iter_mut() {
        let largest = row.amax();
        if largest > 0.0 {
            row /= largest;
        }
    }
    for mut column in jac.column_iter_mut() {
        let largest = column.amax();
        if largest > 0.0 {
            column /= largest;
        }
    }
    let singular = jac.svd(false, false).singular_values;
    singular.min() / singular.max().max(f64::MIN_POSITIVE)
}

/// The frozen-time internal dynamics of `model` at `state` (see the module
/// docs).
pub fn internal_dynamics<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
) -> Result<InternalDynamics, InternalDynamicsError>
where
    Mdl: CraneModel<N, M, A>,
{
    let (q, v, u, lambda) = (&state.q, &state.v, &state.u, &state.lambda);
    let (df_dq, df_dv) = model.force_jacobians(q, v);
    let stiffness = df_dq + model.input_jacobian(q, u) - model.constraint_hessian(q, lambda);
    let dense = |m: &[f64], rows: usize, cols: usize| DMatrix::from_column_slice(rows, cols, m);
    let (mass, damping, stiffness) = (
        dense(model.mass_matrix::<f64>().as_slice(), N, N),
        dense(df_dv.as_slice(), N, N),
        dense(stiffness.as_slice(), N, N),
    );
    let jac_g = dense(model.constraint_jacobian(q).as_slice(), M, N);
    let inputs = dense(model.input_matrix(q).as_slice(), N, A);
    // Q: left null space of W = [B^T G^T]; Z: null space of C = [G; S_x]
    let mut w = DMatrix::zeros(N, A + M);
    w.columns_mut(0, A).copy_from(&inputs);
    w.columns_mut(A, M).copy_from(&jac_g.transpose());
    let mut c = DMatrix::zeros(M + A, N);
    c.rows_mut(0, M).copy_from(&jac_g);
    for k in 0..A {
        c[(M + k, N - A + k)] = 1.0;
    }
    let left = left_null_basis(&w);
    let right = left_null_basis(&c.transpose());
    let t = state.t;
    // where Pryce's system Jacobian is regular the structural count is the
    // dimension (a flat crane needs no further work)
    let structural = Mdl::STRUCTURE
        .filter(|s| system_jacobian_condition(s, &mass, &damping, &stiffness, &jac_g, &inputs) > REGULAR_TOLERANCE)
        .map(|s| s.dimension);
    if structural == Some(0) {
        return Ok(InternalDynamics {
            t,
            dimension: 0,
            eigenvalues: Vec::new(),
            max_real_part: f64::NEG_INFINITY,
        });
    }
    if left.ncols() != right.ncols() {
        return Err(InternalDynamicsError::NotSquare {
            t,
            left: left.ncols(),
            right: right.ncols(),
        });
    }
    let size = left.ncols();
    let a2 = left.transpose() * &mass * &right;
    let a1 = -(left.transpose() * &damping * &right);
    let a0 = -(left.transpose() * &stiffness * &right);
    let scale = mass.amax().max(f64::MIN_POSITIVE);
    let svd = a2.svd(true, true);
    let (Some(u_a2), Some(v_t)) = (svd.u, svd.v_t) else {
        return Err(InternalDynamicsError::MixedRank { t, rank: 0, size });
    };
    // nalgebra sorts singular values in decreasing order
    let rank = svd
        .singular_values
        .iter()
        .filter(|&&s| s > RANK_TOLERANCE * scale)
        .count();
    if rank == 0 && structural.is_none() {
        return Ok(InternalDynamics {
            t,
            dimension: 0,
            eigenvalues: Vec::new(),
            max_real_part: f64::NEG_INFINITY,
        });
    }
    // rows U^T, coordinates eta = V xi: the first `rank` rows read
    // S xi1'' + A1~ xi' + A0~ xi = 0, the others hold no second derivative;
    // without first derivatives there (no damping in those rows) they fix
    // xi2 = -A0~22^-1 A0~21 xi1 algebraically, and xi1 follows a
    // second-order system of size `rank`
    let v = v_t.transpose();
    let (a1t, a0t) = (u_a2.transpose() * &a1 * &v, u_a2.transpose() * &a0 * &v);
    let (r, rest) = (rank, size - rank);
    let coupling = if rest == 0 {
        DMatrix::zeros(0, r)
    } else {
        let first_order = a1t.rows(r, rest).amax();
        let a0_22 = a0t.view((r, r), (rest, rest)).into_owned();
        // those rows must fix the remaining coordinates well (a nearly
        // singular block leaves a direction free at first order, and the
        // reduction then returns round-off: navy-3d-pulley, singular values
        // 50 and 1e-10 along its move)
        let singular = a0_22.clone().svd(false, false).singular_values;
        let inverse = (singular.min() > REDUCTION_TOLERANCE * singular.max())
            .then(|| a0_22.try_inverse())
            .flatten();
        match inverse {
            Some(inverse) if first_order <= RANK_TOLERANCE * (a1t.amax() + a0t.amax()).max(f64::MIN_POSITIVE) => {
                inverse * a0t.view((r, 0), (rest, r))
            }
            _ => return Err(InternalDynamicsError::MixedRank { t, rank, size }),
        }
    };
    let reduce = |m: &DMatrix<f64>| {
        let mut reduced = m.view((0, 0), (r, r)).into_owned();
        if rest > 0 {
            reduced -= m.view((0, r), (r, rest)) * &coupling;
        }
        reduced
    };
    let (b1, b0) = (reduce(&a1t), reduce(&a0t));
    let inverse = DMatrix::from_diagonal(&svd.singular_values.rows(0, r).map(|s| 1.0 / s));
    // xi1'' = -S^-1 (B1 xi1' + B0 xi1), as a first-order system
    let mut companion = DMatrix::zeros(2 * r, 2 * r);
    companion.view_mut((0, r), (r, r)).fill_with_identity();
    companion.view_mut((r, 0), (r, r)).copy_from(&(-(&inverse * &b0)));
    companion.view_mut((r, r), (r, r)).copy_from(&(-(&inverse * &b1)));
    let eigenvalues: Vec<(f64, f64)> = companion.complex_eigenvalues().iter().map(|e| (e.re, e.im)).collect();
    let max_real_part = eigenvalues.iter().map(|e| e.0).fold(f64::NEG_INFINITY, f64::max);
    if structural.is_some_and(|d| d != 2 * r) {
        // the reduction above missed constraints hidden at higher derivatives
        return Err(InternalDynamicsError::MixedRank { t, rank, size });
    }
    Ok(InternalDynamics {
        t,
        dimension: 2 * r,
        eigenvalues,
        max_real_part,
    })
}

/// An input this many times the largest input at the start (at least 1) is
/// beyond any physical scale of the crane: the mark of unstable internal
/// dynamics in computed torques (the coupled crane: 3.4e9 times at 2.5 s).
pub const RUNAWAY_FACTOR: f64 = 1e6;

/// The internal dynamics along a computed run ([`diagnose`]).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct RunDiagnosis {
    /// The count from the declaration ([`CraneModel::STRUCTURE`]).
    pub structural_dimension: Option<usize>,
    /// Largest dimension found at the sampled states (0: flat at all); the
    /// structural count where no sampled state was resolved.
    pub dimension: usize,
    /// Largest real part of an eigenvalue, 1/s, and the time of its state
    /// (`None` when flat).
    pub max_real_part: Option<f64>,
    /// The time of `max_real_part`.
    pub at: Option<f64>,
    /// No eigenvalue at any sampled state with a real part above round-off
    /// (`Some(true)`), one above it (`Some(false)`), or not known: the
    /// structure counts internal dynamics and no sampled state was resolved
    /// (`None`; a damped free mode, whose rows the frozen-time reduction
    /// does not split).
    pub stable: Option<bool>,
    /// Sampled states where the diagnosis could not tell, and the first
    /// reason.
    pub unresolved: usize,
    /// Why the first unresolved state was not resolved.
    #[cfg_attr(
        feature = "serde",
        serde(skip_serializing_if = "Option::is_none", serialize_with = "serialize_reason")
    )]
    pub unresolved_reason: Option<InternalDynamicsError>,
    /// States sampled (evenly spaced, up to `runaway_at`: past a runaway
    /// input the states are not physical and not diagnosed).
    pub samples: usize,
    /// First time an input exceeds [`RUNAWAY_FACTOR`] times its size at the
    /// start.
    pub runaway_at: Option<f64>,
    /// The highest derivative of the load path the crane's inputs need
    /// ([`Structure::path_order`]) and the highest the formulation that
    /// computed the run covers, where both are known.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub path_order: Option<PathOrder>,
}

/// The load path's derivative a crane's inputs need and the one the
/// formulation of a run covers: beyond it the run's errors grow as dt
/// shrinks (the index of the discretised system exceeds what the scheme
/// tolerates), whatever Newton reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PathOrder {
    /// What the crane needs ([`Structure::path_order`]).
    pub needed: usize,
    /// What the formulation covers ([`Problem::path_order_covered`](crate::problem::Problem::path_order_covered)).
    pub covered: usize,
}

impl PathOrder {
    /// Whether the formulation covers the crane.
    pub fn is_covered(&self) -> bool {
        self.needed <= self.covered
    }
}

/// The reason as its message.
#[cfg(feature = "serde")]
fn serialize_reason<S: serde::Serializer>(reason: &Option<InternalDynamicsError>, s: S) -> Result<S::Ok, S::Error> {
    match reason {
        Some(reason) => s.collect_str(reason),
        None => s.serialize_none(),
    }
}

impl RunDiagnosis {
    /// Nothing diagnosed: flat, stable, no samples.
    pub fn none() -> Self {
        Self {
            structural_dimension: None,
            dimension: 0,
            max_real_part: None,
            at: None,
            stable: Some(true),
            unresolved: 0,
            unresolved_reason: None,
            samples: 0,
            runaway_at: None,
            path_order: None,
        }
    }

    /// Whether the run's torques can be used as a feedforward: internal
    /// dynamics not found unstable, no runaway input, and a formulation
    /// that covers the crane's path order.
    pub fn is_usable(&self) -> bool {
        self.stable != Some(false) && self.runaway_at.is_none() && self.path_order.is_none_or(|p| p.is_covered())
    }
}

/// The internal dynamics of a run of `model`: [`internal_dynamics`] at up
/// to `samples + 1` evenly spaced states of `solution` (before its first
/// runaway input), with the largest real part and where it occurs; with
/// `samples = 0` at none (the runaway and the path order only).
///
/// `simulate` returns whatever the causal inverse computes; this is the
/// check that tells a usable result from an exploding one.
///
/// ```
/// # use crane_runtime::{CraneModel, Solution};
/// # fn demo<Mdl: CraneModel<4, 1, 2>>(model: &Mdl, run: &Solution<4, 1, 2>) {
/// let diagnosis = crane_runtime::internal::diagnose(model, run, 100);
/// if !diagnosis.is_usable() {
///     eprintln!("not a feedforward: unstable internal dynamics ({:?} 1/s at t = {:?} s), runaway from {:?} s",
///         diagnosis.max_real_part, diagnosis.at, diagnosis.runaway_at);
/// }
/// # }
/// ```
pub fn diagnose<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    solution: &Solution<N, M, A>,
    samples: usize,
) -> RunDiagnosis
where
    Mdl: CraneModel<N, M, A>,
{
    let states = &solution.states;
    let stride = (states.len() / samples.max(1)).max(1);
    let mut diagnosis = RunDiagnosis {
        structural_dimension: Mdl::STRUCTURE.map(|s| s.dimension),
        path_order: Mdl::STRUCTURE
            .zip(solution.path_order_covered)
            .map(|(s, covered)| PathOrder {
                needed: s.path_order(A),
                covered,
            }),
        ..RunDiagnosis::none()
    };
    let scale = states.first().map_or(1.0, |s| s.u.amax().max(1.0));
    diagnosis.runaway_at = states
        .iter()
        .find(|s| !(s.u.amax() <= RUNAWAY_FACTOR * scale))
        .map(|s| s.t);
    let runaway_at = diagnosis.runaway_at;
    let physical = |t: f64| runaway_at.is_none_or(|runaway| t < runaway);
    let sampled = if samples == 0 { 0 } else { states.len() };
    let mut resolved = 0;
    for state in states[..sampled].iter().step_by(stride).take_while(|s| physical(s.t)) {
        diagnosis.samples += 1;
        match internal_dynamics(model, state) {
            Ok(d) => {
                diagnosis.dimension = diagnosis.dimension.max(d.dimension);
                if d.dimension > 0 && diagnosis.max_real_part.is_none_or(|r| d.max_real_part > r) {
                    diagnosis.max_real_part = Some(d.max_real_part);
                    diagnosis.at = Some(state.t);
                }
                diagnosis.stable = Some(diagnosis.stable != Some(false) && d.is_stable());
                resolved += 1;
            }
            Err(e) => {
                diagnosis.unresolved += 1;
                diagnosis.unresolved_reason.get_or_insert(e);
            }
        }
    }
    // nothing resolved where the structure counts free states: not "flat
    // and stable", but the structure's count and stability unknown
    let structural = diagnosis.structural_dimension.unwrap_or(0);
    if diagnosis.samples > 0 && resolved == 0 && structural > 0 {
        diagnosis.dimension = structural;
        diagnosis.stable = None;
    }
    diagnosis
}

/// How smooth a load path must be for a crane, and how smooth it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PathSmoothness {
    /// The highest derivative of the path the inputs depend on
    /// ([`Structure::path_order`]).
    pub needed: usize,
    /// The highest derivative of the path that is continuous
    /// ([`Trajectory::continuity`](crate::trajectory::Trajectory::continuity)).
    pub continuous: usize,
}

impl PathSmoothness {
    /// Whether the path is smooth enough: otherwise the exact inputs jump
    /// (or carry impulses) where the path's derivative `continuous + 1`
    /// jumps, and the computed ones grow there as the step shrinks.
    pub fn is_sufficient(&self) -> bool {
        self.continuous >= self.needed
    }
}

/// The smoothness `trajectory` has and `model` needs, where both are known
/// (the model's [`CraneModel::STRUCTURE`], the path's
/// [`Trajectory::continuity`](crate::trajectory::Trajectory::continuity)).
///
/// `navy-3d-pulley` on the paper's three-phase profile: needed 6,
/// continuous 4, so its slewing torque has impulses at the ramp corners
/// (1790 N m at dt = 0.0005 s, 446 N m at 0.002 s).
pub fn path_smoothness<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    trajectory: &Tr,
) -> Option<PathSmoothness>
where
    Mdl: CraneModel<N, M, A>,
    Tr: crate::trajectory::Trajectory<A>,
{
    Some(PathSmoothness {
        needed: Mdl::STRUCTURE?.path_order(A),
        continuous: trajectory.continuity()?,
    })
}
