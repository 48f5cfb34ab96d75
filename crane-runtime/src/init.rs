//! Consistent initial values (paper sect. 4.1 and docs/numerics.md).
//!
//! A start at `t0` must satisfy the constraints `g(p0, gamma(t0)) = 0`
//! (eq. 22d), the velocity constraints `G1 v0 + G2 gamma'(t0) = 0` (eq. 23)
//! and, for a load at rest, the static balance
//! `0 = f + B^T u - G^T lambda - M q''` with `q'' = [0; gamma''(t0)]` (eq. 1a).
//! [`check_start`] checks a user-given `p0` and finds `u0, lambda0`;
//! [`static_equilibrium`] solves for `(p0, u0, lambda0)` from a rough guess and
//! refuses to pick a point of a family of equilibria.

use nalgebra::{DMatrix, DVector, SVector};

use crate::error::Error;
use crate::model::CraneModel;
use crate::model::check_parameters;
use crate::newton::normalised_residual;
use crate::solution::State;
use crate::trajectory::Trajectory;

/// Relative tolerance of the consistency checks: equations hold to this
/// fraction of their natural scale (round-off in the generated functions is
/// ~1e-15 relative, a hand-typed start to 10 digits ~1e-10).
pub const CONSISTENCY_TOLERANCE: f64 = 1e-9;

/// Singular value ratio below which the equilibrated static balance is
/// called rank deficient. A regular crane balance has ratios around 1e-4..1e-2
/// after equilibration; the paper's degenerate starts give ~1e-17.
pub const RANK_TOLERANCE: f64 = 1e-10;

fn wrong_length(expected: usize, found: usize, what: &str) -> Error {
    Error::InconsistentStart {
        equation: format!("{what} needs {expected} entries, got {found}"),
        residual: f64::NAN,
        tolerance: 0.0,
    }
}

/// The crane's parameters checked ([`check_parameters`]) and `values` of
/// the length of the robot coordinates, `n - a` (returned).
fn checked_robot_coordinates<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    values: &[f64],
    what: &str,
) -> Result<usize, Error> {
    check_parameters(model)?;
    if values.len() != N - A {
        return Err(wrong_length(N - A, values.len(), what));
    }
    Ok(N - A)
}

/// Check a user-given start `p0` (and `v0`, zero if `None`) at `t0` against
/// eqs. (22d) and (23) and, when the load is at rest, the static balance;
/// return the consistent start with `u0, lambda0` from the balance (least
/// squares).
///
/// Errors name the violated equation, e.g. "constraint `hoist` (g = 0, eq. 22d)".
pub fn check_start<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: &Tr,
    t0: f64,
    p0: &[f64],
    v0: Option<&[f64]>,
) -> Result<State<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    let p = checked_robot_coordinates(model, p0, "the start p0")?;
    if let Some(v0) = v0
        && v0.len() != p
    {
        return Err(wrong_length(p, v0.len(), "the start velocity v0"));
    }
    let info = Mdl::INFO;
    let gamma = [0, 1, 2].map(|k| trajectory.derivative(t0, k));
    let mut q = SVector::<f64, N>::zeros();
    let mut v = SVector::<f64, N>::zeros();
    for i in 0..p {
        q[i] = p0[i];
        v[i] = v0.map_or(0.0, |v0| v0[i]);
    }
    for k in 0..A {
        q[p + k] = gamma[0][k];
        v[p + k] = gamma[1][k];
    }
    if !(q.iter().all(|x| x.is_finite()) && v.iter().all(|x| x.is_finite())) {
        return Err(Error::NonFinite {
            quantity: "start state",
            t: t0,
        });
    }

    // g = 0 (eq. 22d); g carries a factor 1/2 of squared lengths, which
    // overflow past 1e154 (and the tolerance with them)
    if let Some(i) = q.iter().position(|x| x.abs() > 1e100) {
        return Err(Error::StartOutOfRange {
            coordinate: info.coordinates[i],
            value: q[i],
        });
    }
    let scale = q.amax().max(1.0);
    constraints_hold(model, &q)?;

    // G q' = 0 (eq. 23)
    let jac_g = model.constraint_jacobian(&q);
    let gv = jac_g * v;
    worst_row(gv.as_slice(), CONSISTENCY_TOLERANCE * scale * v.amax().max(1.0), |i| {
        format!("velocity constraint of `{}` (eq. 23)", info.constraints[i])
    })?;

    // static balance: B^T u - G^T lambda = M q'' - f, least squares in (u, lambda)
    let mut accel = SVector::<f64, N>::zeros();
    for k in 0..A {
        accel[p + k] = gamma[2][k];
    }
    let rhs = model.mass_matrix() * accel - model.forces(&q, &v);
    let bt = model.input_matrix(&q);
    let mut balance = DMatrix::<f64>::zeros(N, A + M);
    balance.view_mut((0, 0), (N, A)).copy_from(&bt);
    balance.view_mut((0, A), (N, M)).copy_from(&(-jac_g.transpose()));
    let rhs_dyn = DVector::from_column_slice(rhs.as_slice());
    let solution = balance
        .clone()
        .svd(true, true)
        .solve(&rhs_dyn, 1e-14)
        .map_err(|_| Error::NonFinite {
            quantity: "static balance",
            t: t0,
        })?;
    let at_rest = v.iter().all(|x| *x == 0.0);
    if at_rest {
        let residual = &balance * &solution - &rhs_dyn;
        let force_scale = rhs.amax().max((&balance * &solution).amax()).max(1.0);
        worst_row(residual.as_slice(), CONSISTENCY_TOLERANCE * force_scale, |i| {
            format!("static balance of coordinate `{}` (eq. 1a)", info.coordinates[i])
        })?;
    }
    let start = State {
        t: t0,
        q,
        v,
        u: SVector::from_fn(|k, _| solution[k]),
        lambda: SVector::from_fn(|i, _| solution[A + i]),
    };
    check_rope_lengths(model, &start)?;
    Ok(start)
}

/// Refuse a start with a rope of zero or negative length (the constraint
/// `1/2(d^2 - L^2)` holds for `-L` too: a mirror start).
fn check_rope_lengths<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    start: &State<N, M, A>,
) -> Result<(), Error> {
    let mut lengths = vec![0.0; Mdl::INFO.ropes.len()];
    model.rope_lengths(&start.q, &mut lengths);
    for (rope, &length) in Mdl::INFO.ropes.iter().zip(&lengths) {
        if !(length > 0.0) {
            return Err(Error::NonPositiveRopeLength {
                rope: rope.tension,
                length,
                t: start.t,
            });
        }
    }
    Ok(())
}

/// Error naming the row with the largest residual if it exceeds `tolerance`.
fn worst_row(residual: &[f64], tolerance: f64, name: impl Fn(usize) -> String) -> Result<(), Error> {
    let (index, value) = residual
        .iter()
        .enumerate()
        .map(|(i, r)| (i, r.abs()))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    if value > tolerance || value.is_nan() {
        return Err(Error::InconsistentStart {
            equation: name(index),
            residual: value,
            tolerance,
        });
    }
    Ok(())
}

/// Refuse coordinates `q` off the constraints `g(q) = 0` (eq. 22d) by more
/// than [`CONSISTENCY_TOLERANCE`] of their squared size (`g` carries a
/// factor 1/2 of squared lengths), naming the worst: the rule of a start.
pub(crate) fn constraints_hold<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    q: &SVector<f64, N>,
) -> Result<(), Error> {
    let scale = q.amax().max(1.0);
    let g = model.constraints(q);
    worst_row(g.as_slice(), CONSISTENCY_TOLERANCE * scale * scale, |i| {
        format!("constraint `{}` (g = 0, eq. 22d)", Mdl::INFO.constraints[i])
    })
}

/// Iterations of the static-equilibrium solve.
const STATIC_MAX_ITERATIONS: usize = 50;

/// Solve the static equilibrium `0 = f + B^T u - G^T lambda - M q''`,
/// `0 = g(p, gamma(t0))` for `(p0, u0, lambda0)` from a rough guess of `p0`.
///
/// Gauss-Newton with minimum-norm steps on the row- and column-equilibrated
/// Jacobian and a backtracking line search. At the solution the Jacobian's
/// rank is checked: a rank-deficient balance (a slack rope leaves the pulley
/// free, as at the paper's start of sect. 5.1) is reported as
/// [`Error::NonUniqueEquilibrium`] naming the free coordinates, never
/// answered with an arbitrary member of the family.
pub fn static_equilibrium<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: &Tr,
    t0: f64,
    p_guess: &[f64],
) -> Result<State<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    let p = checked_robot_coordinates(model, p_guess, "the guess for p0")?;
    if !p_guess.iter().all(|x| x.is_finite()) {
        return Err(Error::NonFinite {
            quantity: "guess for p0",
            t: t0,
        });
    }
    let info = Mdl::INFO;
    let gamma = [0, 1, 2].map(|k| trajectory.derivative(t0, k));
    if !gamma.iter().all(|g| g.iter().all(|x| x.is_finite())) {
        return Err(Error::NonFinite {
            quantity: "load target gamma(t0)",
            t: t0,
        });
    }
    let dim = N + M; // unknowns p (N - A), u (A), lambda (M); equations N + M
    let mut z = DVector::<f64>::zeros(dim);
    z.rows_mut(0, p).copy_from(&DVector::from_column_slice(p_guess));

    let assemble = |z: &DVector<f64>| -> (DVector<f64>, DMatrix<f64>) {
        let mut q = SVector::<f64, N>::zeros();
        let mut accel = SVector::<f64, N>::zeros();
        for i in 0..p {
            q[i] = z[i];
        }
        for k in 0..A {
            q[p + k] = gamma[0][k];
            accel[p + k] = gamma[2][k];
        }
        let v = SVector::<f64, N>::zeros();
        let u = SVector::<f64, A>::from_fn(|k, _| z[p + k]);
        let lambda = SVector::<f64, M>::from_fn(|i, _| z[N + i]);
        let jac_g = model.constraint_jacobian(&q);
        let bt = model.input_matrix(&q);
        let balance = model.forces(&q, &v) + bt * u - jac_g.tr_mul(&lambda) - model.mass_matrix() * accel;
        let mut r = DVector::zeros(dim);
        r.rows_mut(0, N).copy_from(&balance);
        r.rows_mut(N, M).copy_from(&model.constraints(&q));
        let (df_dq, _) = model.force_jacobians(&q, &v);
        let d_balance = df_dq + model.input_jacobian(&q, &u) - model.constraint_hessian(&q, &lambda);
        let mut jac = DMatrix::zeros(dim, dim);
        jac.view_mut((0, 0), (N, p)).copy_from(&d_balance.columns(0, p));
        jac.view_mut((N, 0), (M, p)).copy_from(&jac_g.columns(0, p));
        jac.view_mut((0, p), (N, A)).copy_from(&bt);
        jac.view_mut((0, N), (N, M)).copy_from(&(-jac_g.transpose()));
        (r, jac)
    };

    // start u, lambda from the balance at the guess (zero would make the
    // Jacobian singular, docs/numerics.md)
    {
        let (r, jac) = assemble(&z);
        if !(r.iter().all(|x| x.is_finite()) && jac.iter().all(|x| x.is_finite())) {
            return Err(Error::NonFinite {
                quantity: "static balance at the guess",
                t: t0,
            });
        }
        if let Ok(ul) = jac.columns(p, A + M).into_owned().svd(true, true).solve(&(-&r), 1e-12) {
            z.rows_mut(p, A + M).copy_from(&ul);
        }
    }

    let mut iterations = 0;
    let (mut r, mut jac) = assemble(&z);
    let mut norm = r.norm();
    loop {
        if !(norm.is_finite() && jac.iter().all(|x| x.is_finite())) {
            return Err(Error::NonFinite {
                quantity: "static equilibrium iterate",
                t: t0,
            });
        }
        let (row_scale, col_scale) = equilibrate(&jac);
        let scaled = DMatrix::from_fn(dim, dim, |i, j| jac[(i, j)] * row_scale[i] * col_scale[j]);
        let svd = scaled.svd(true, true);
        let sigma_max = svd.singular_values.max();
        let rhs = DVector::from_fn(dim, |i, _| -r[i] * row_scale[i]);
        let step_scaled = svd.solve(&rhs, 1e-12 * sigma_max).map_err(|_| Error::NonFinite {
            quantity: "static equilibrium step",
            t: t0,
        })?;
        let step = DVector::from_fn(dim, |j, _| step_scaled[j] * col_scale[j]);
        // converged when each block's step (p, u, lambda) is below 1e-11 of the
        // block's size, or the residual is at round-off relative to |J| |z|
        // (a block can be exactly zero at the solution, e.g. a slewing torque
        // at rest, and then only the residual test can end the iteration)
        let converged_step = [0..p, p..N, N..dim].into_iter().all(|block| {
            let size = z.rows_range(block.clone()).amax();
            step.rows_range(block).amax() <= 1e-11 * size
        });
        let normalised = normalised_residual(&r, &jac, &z, |_| 0.0);
        if converged_step || normalised <= 1e-14 || norm == 0.0 {
            // the last step, below 1e-11 of each block, still halves the
            // digits left: taking it puts the start on g = 0 to round-off
            // (without it g(q0) was 5.7e-11 on a gantry from a far guess,
            // more than a minimal start's phi(mu0) = q0 allows)
            if converged_step && step.iter().all(|x| x.is_finite()) {
                z += &step;
            }
            let ratio = svd.singular_values.min() / sigma_max;
            if ratio < RANK_TOLERANCE {
                let free = free_direction(&svd, &col_scale, p, info.coordinates);
                return Err(Error::NonUniqueEquilibrium {
                    singular_value_ratio: ratio,
                    free,
                });
            }
            let start = State {
                t: t0,
                q: SVector::from_fn(|i, _| if i < p { z[i] } else { gamma[0][i - p] }),
                v: SVector::from_fn(|i, _| if i < p { 0.0 } else { gamma[1][i - p] }),
                u: SVector::from_fn(|k, _| z[p + k]),
                lambda: SVector::from_fn(|i, _| z[N + i]),
            };
            check_rope_lengths(model, &start)?;
            return Ok(start);
        }
        iterations += 1;
        if iterations > STATIC_MAX_ITERATIONS {
            return Err(Error::EquilibriumNotFound {
                iterations,
                residual: r.amax(),
            });
        }
        // backtracking on the residual norm, each equation in the units of
        // its row of the equilibrated Jacobian: unscaled, the force balance
        // (1e4 N) outweighs the constraints (m^2), and the second-order
        // force residual of a full step (the multipliers' change times the
        // coordinates') refused steps that solve the constraints; a sling
        // 0.1 m longer than p0 assumes then took 51 steps of 1/32 each
        let scaled_norm = |r: &DVector<f64>| {
            r.iter()
                .zip(&row_scale)
                .map(|(x, s)| (x * s).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let current = scaled_norm(&r);
        let mut alpha = 1.0;
        loop {
            let trial = &z + &step * alpha;
            let (r_trial, jac_trial) = assemble(&trial);
            let trial_norm = scaled_norm(&r_trial);
            if trial_norm.is_finite() && (trial_norm < current || alpha < 1e-3) {
                z = trial;
                norm = r_trial.norm();
                r = r_trial;
                jac = jac_trial;
                break;
            }
            if alpha < 1e-3 {
                // every step length tried gave a non-finite residual
                return Err(Error::NonFinite {
                    quantity: "static equilibrium step",
                    t: t0,
                });
            }
            alpha *= 0.5;
        }
    }
}

/// Row and column scale factors making every row and column of `jac` have
/// largest entry about 1 (columns first, then rows).
fn equilibrate(jac: &DMatrix<f64>) -> (Vec<f64>, Vec<f64>) {
    let inv = |m: f64| {
        if m > 0.0 && m.is_finite() { 1.0 / m } else { 1.0 }
    };
    let cols: Vec<f64> = jac.column_iter().map(|c| inv(c.amax())).collect();
    let rows: Vec<f64> = (0..jac.nrows())
        .map(|i| {
            inv((0..jac.ncols())
                .map(|j| (jac[(i, j)] * cols[j]).abs())
                .fold(0.0, f64::max))
        })
        .collect();
    (rows, cols)
}

/// Names of the coordinates (or, if none moves, the inputs/multipliers) that
/// the null direction of the balance moves.
fn free_direction(
    svd: &nalgebra::SVD<f64, nalgebra::Dyn, nalgebra::Dyn>,
    col_scale: &[f64],
    p: usize,
    coordinates: &[&str],
) -> String {
    let Some(v_t) = svd.v_t.as_ref() else {
        return "an unknown direction".into();
    };
    let smallest = svd.singular_values.imin();
    let direction: Vec<f64> = (0..col_scale.len())
        .map(|j| v_t[(smallest, j)] * col_scale[j])
        .collect();
    let largest = direction[..p].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest == 0.0 {
        return "the inputs and multipliers".into();
    }
    let names: Vec<&str> = (0..p)
        .filter(|&j| direction[j].abs() >= 1e-3 * largest)
        .map(|j| coordinates[j])
        .collect();
    names.join(", ")
}

/// Whether `start` is at rest on its path: `v0 = 0` and `gamma' = gamma'' = 0`
/// at `t0` (to round-off), as at the start of a rest-to-rest move.
pub fn at_rest<Tr, const N: usize, const M: usize, const A: usize>(trajectory: &Tr, start: &State<N, M, A>) -> bool
where
    Tr: Trajectory<A>,
{
    let scale = start.q.amax().max(1.0);
    let resting = |x: &SVector<f64, A>| x.amax() <= 1e-14 * scale;
    start.v.amax() <= 1e-14 * scale
        && resting(&trajectory.derivative(start.t, 1))
        && resting(&trajectory.derivative(start.t, 2))
}
