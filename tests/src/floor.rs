//! The hand-written floor of a redundant step: backward Euler on eqs.
//! (22a-d) for a crane of the planar size (n = 7, m = 3, a = 2) written out
//! with static nalgebra types, the same unknowns `z = [p; dt^2 u; dt^2
//! lambda]`, the same predictor (after the first steps, the quadratic
//! through the last three steps' unknowns with the coordinates one degree
//! above the scheme's) and the same stopping rule (per block `|dz_B| <=
//! 1e-10 |z_B| + 1e-14`, or the error left estimated from the contraction
//! of successive updates below that), but none of the generic stepper's
//! machinery: no dynamic matrices, no residual normalisation, no
//! equilibration, no minimum-norm fallback (so it is only for regular runs).
//!
//! The benchmarks time `crane_runtime::simulate` against [`backward_euler`]
//! on the same model and path; `tests/tests/newton_cost.rs` checks that the
//! two compute the same inputs.

use crane_runtime::nalgebra::{SMatrix, SVector};
use crane_runtime::trajectory::Trajectory;
use crane_runtime::{CraneModel, State};

/// Unknowns of a step: 5 robot coordinates, 2 scaled inputs, 3 scaled multipliers.
const Z: usize = 10;

/// Why a hand-written run stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FloorError {
    /// The iteration matrix of the step at `t` was singular.
    Singular {
        /// Time of the step.
        t: f64,
    },
    /// Newton did not converge in 30 iterations at `t`.
    NotConverged {
        /// Time of the step.
        t: f64,
    },
}

/// The inputs `u` at every step of a backward-Euler run of `model` on `path`
/// from the consistent `start`, `steps` steps of `dt`, and the Newton
/// iterations it took in all.
pub fn backward_euler<Mdl: CraneModel<7, 3, 2>>(
    model: &Mdl,
    path: &impl Trajectory<2>,
    start: &State<7, 3, 2>,
    dt: f64,
    steps: usize,
) -> Result<(Vec<SVector<f64, 2>>, usize), FloorError> {
    let dt2 = dt * dt;
    let mass: SMatrix<f64, 7, 7> = model.mass_matrix();
    let mut p = start.q.fixed_rows::<5>(0).into_owned();
    let mut v = start.v.fixed_rows::<5>(0).into_owned();
    let mut z = SVector::<f64, Z>::zeros();
    z.fixed_rows_mut::<5>(0).copy_from(&p);
    z.fixed_rows_mut::<2>(5).copy_from(&(start.u * dt2));
    z.fixed_rows_mut::<3>(7).copy_from(&(start.lambda * dt2));
    // the last three steps' unknowns, newest first
    let mut past = [z; 3];
    let mut known = 1;
    let mut inputs = Vec::with_capacity(steps);
    let mut iterations = 0;
    for n in 0..steps {
        let t = start.t + (n + 1) as f64 * dt;
        let gamma = [0, 1, 2].map(|k| path.derivative(t, k));
        // the predictor: coordinates p_n + dt v_n on the first step, then
        // the linear extrapolation (the scheme's degree) and from the third
        // step on the quadratic, the inputs and multipliers the quadratic
        // through the last three steps (the last step's before that)
        if known >= 3 {
            z = past[0] * 3.0 - past[1] * 3.0 + past[2];
        } else if known == 2 {
            let extrapolated = past[0] * 2.0 - past[1];
            z.fixed_rows_mut::<5>(0).copy_from(&extrapolated.fixed_rows::<5>(0));
        } else {
            z.fixed_rows_mut::<5>(0).copy_from(&(p + v * dt));
        }
        let mut last_w = f64::INFINITY;
        let mut converged = false;
        for _ in 0..30 {
            iterations += 1;
            let (r, jac) = residual(model, &mass, &z, &p, &v, &gamma, dt);
            let dz = jac.lu().solve(&r).ok_or(FloorError::Singular { t })?;
            z -= dz;
            let w = [0..5, 5..7, 7..10]
                .into_iter()
                .map(|block| {
                    let step = dz.rows_range(block.clone()).amax();
                    let size = z.rows_range(block).amax();
                    step / (1e-10 * size + 1e-14)
                })
                .fold(0.0, f64::max);
            let contraction = w / last_w;
            let left = if last_w.is_finite() && contraction < 1.0 {
                contraction / (1.0 - contraction) * w
            } else {
                f64::INFINITY
            };
            last_w = w;
            if w <= 1.0 || left <= 1.0 {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(FloorError::NotConverged { t });
        }
        let p_new = z.fixed_rows::<5>(0).into_owned();
        v = (p_new - p) / dt; // eq. (22a)
        p = p_new;
        inputs.push(z.fixed_rows::<2>(5) / dt2);
        past = [z, past[0], past[1]];
        known = (known + 1).min(3);
    }
    Ok((inputs, iterations))
}

/// The residual of eqs. (22b-d) at `z` for backward Euler from `p_n, v_n`
/// with the load target `gamma`, and its iteration matrix.
fn residual<Mdl: CraneModel<7, 3, 2>>(
    model: &Mdl,
    mass: &SMatrix<f64, 7, 7>,
    z: &SVector<f64, Z>,
    p_n: &SVector<f64, 5>,
    v_n: &SVector<f64, 5>,
    gamma: &[SVector<f64, 2>; 3],
    dt: f64,
) -> (SVector<f64, Z>, SMatrix<f64, Z, Z>) {
    let dt2 = dt * dt;
    let p = z.fixed_rows::<5>(0);
    let u = z.fixed_rows::<2>(5).into_owned();
    let lambda = z.fixed_rows::<3>(7).into_owned();
    let vp = (p - p_n) / dt;
    // dt^2 a = p - p_n - dt v_n for the robot, dt^2 gamma'' for the load
    let ap_dt2 = p - p_n - v_n * dt;
    let mut q = SVector::<f64, 7>::zeros();
    let mut vel = SVector::<f64, 7>::zeros();
    let mut acc_dt2 = SVector::<f64, 7>::zeros();
    q.fixed_rows_mut::<5>(0).copy_from(&p);
    q.fixed_rows_mut::<2>(5).copy_from(&gamma[0]);
    vel.fixed_rows_mut::<5>(0).copy_from(&vp);
    vel.fixed_rows_mut::<2>(5).copy_from(&gamma[1]);
    acc_dt2.fixed_rows_mut::<5>(0).copy_from(&ap_dt2);
    acc_dt2.fixed_rows_mut::<2>(5).copy_from(&(gamma[2] * dt2));
    let f = model.forces(&q, &vel);
    let (df_dq, df_dv) = model.force_jacobians(&q, &vel);
    let bt = model.input_matrix(&q);
    let dbu_dq = model.input_jacobian(&q, &u);
    let g_jac = model.constraint_jacobian(&q);
    let dgl_dq = model.constraint_hessian(&q, &lambda);
    let dynamic = mass * acc_dt2 - f * dt2 - bt * u + g_jac.tr_mul(&lambda);
    let mut r = SVector::<f64, Z>::zeros();
    r.fixed_rows_mut::<7>(0).copy_from(&dynamic);
    r.fixed_rows_mut::<3>(7).copy_from(&model.constraints(&q));
    let mut jac = SMatrix::<f64, Z, Z>::zeros();
    for j in 0..5 {
        for i in 0..7 {
            jac[(i, j)] = mass[(i, j)] - dt2 * df_dq[(i, j)] - dt * df_dv[(i, j)] - dbu_dq[(i, j)] + dgl_dq[(i, j)];
        }
        for i in 0..3 {
            jac[(7 + i, j)] = g_jac[(i, j)];
        }
    }
    for k in 0..2 {
        for i in 0..7 {
            jac[(i, 5 + k)] = -bt[(i, k)];
        }
    }
    for l in 0..3 {
        for i in 0..7 {
            jac[(i, 7 + l)] = g_jac[(l, i)];
        }
    }
    (r, jac)
}
