//! The servo problem in redundant coordinates, paper eqs. (22a-d), on any
//! scheme.
//!
//! With the servo constraints `x = gamma(t)` substituted, the unknowns of a
//! step are `p_{n+1}`, `u_{n+1}` and `lambda_{n+1}`; the scheme eliminates
//! `v_{n+1}` and `a_{n+1}` as affine functions of `p_{n+1}` (eq. 22a for
//! backward Euler; [`crate::scheme`] for BDF-k). The dynamic rows (22b, 22c)
//! are multiplied by `dt^2` and solved for `dt^2 u` and `dt^2 lambda`, which
//! keeps the iteration matrix's condition number independent of `dt` (about
//! 8e3 on `navy-planar` instead of 2.6e8 at dt = 0.01 and 2.6e12 at
//! dt = 0.001, measured at t = 1.5 s). In general form, valid for any
//! constant mass matrix,
//! ```text
//! r_dyn = dt^2 (M a - f(q, v)) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda) = 0   (22b, 22c)
//! r_g   = g(q) = 0                                                             (22d)
//! q = [p_{n+1}; gamma],  v = [(c/dt)(p_{n+1} - pbar); gamma'],
//! a = [(c/dt)(v_p - vbar); gamma'']
//! ```
//! (backward Euler: `c = 1`, `pbar = p_n`, `vbar = v_n`), which for
//! `M = diag(M1, M2)`, `B^T = [B1^T; 0]`, `f = [f1(p, p'); f2(x, x')]` is
//! exactly (22b) and (22c). In the iteration matrix the scheme's slopes
//! replace 1: `d(dt^2 a)/dp = c^2`, `d(dt^2 v)/dp = c dt`.

use std::ops::{Deref, Range};

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::double_double::DoubleDouble;
use crate::driver::solve;
use crate::error::Error;
use crate::init;
use crate::model::CraneModel;
use crate::newton::{NonlinearSystem, normalised_residual};
use crate::options::Options;
use crate::problem::{Accepted, Follow, Predictor, Problem, ServoTarget, Start, dynamic_rows};
use crate::scheme::{Method, Scheme, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::Stepper;
use crate::trajectory::Trajectory;

/// Eqs. (22a-d) of one step, as a [`Problem`] in the unknowns
/// `z = [dp; dt^2 du; dt^2 dlambda]`, for the crane behind the handle `H`
/// (`&Mdl`, `Box<Mdl>`, `Arc<Mdl>`) on the path `Tr`.
///
/// The unknowns are corrections, held in `f64`, to values held in
/// double-double: `dp` to the scheme's prediction of `p_{n+1}`, which the
/// step's formula gives ([`Predictor::Correction`]), `du` and `dlambda` to
/// the last step's `u` and `lambda`. The history, the offsets of eq. (22a),
/// the residual (22b-d) and the load's coordinates (the path's own
/// [`target_extended`](Trajectory::target_extended), where the drive is
/// the path's) are in that arithmetic too. The scheme's second differences
/// of `p` then carry no noise from rounding `p`, `u`, `lambda` or the
/// residual to `f64` (`~1e-16` of each, amplified like `1/dt^2` into `a`
/// and `u`: see [`crate::double_double`]). A formula without that part (a
/// test's) makes the unknowns the values themselves.
#[derive(Clone)]
pub struct Redundant<H, Tr, const N: usize, const M: usize, const A: usize> {
    model: H,
    trajectory: Tr,
    mass: SMatrix<f64, N, N>,
    /// `gamma, gamma', gamma''` at `t_{n+1}`.
    target: ServoTarget<A>,
    /// The scheme's affine maps `p -> v, a` for this step.
    formula: StepFormula<N>,
    /// What the unknowns `dp` correct: the prediction of `p` (zero where
    /// the unknowns are the coordinates), then the load's coordinates.
    base: SVector<DoubleDouble, N>,
    /// `base - ybar` and `vbar (c dt)` of eq. (22a).
    lead: SVector<DoubleDouble, N>,
    rate_term: SVector<DoubleDouble, N>,
    /// Whether the step's residual is evaluated in double-double: where the
    /// load target is known to that precision (the path's own), not where
    /// it arrives in `f64` (an external target, whose rounding the
    /// residual's precision would not remove).
    beyond_double: bool,
    /// `(c/dt)^2 dt^2`, the slope of `dt^2 a` in `p - ybar`.
    lead_slope: DoubleDouble,
    /// The load's `gamma'` and `dt^2 gamma''`.
    load_rate: SVector<DoubleDouble, A>,
    load_accel_dt2: SVector<DoubleDouble, A>,
    /// `dt^2 u` and `dt^2 lambda` of the last accepted step: what `dt^2 du`
    /// and `dt^2 dlambda` correct (where the unknowns are corrections).
    last_inputs: SVector<DoubleDouble, A>,
    last_multipliers: SVector<DoubleDouble, M>,
    /// `[p; dt^2 u; dt^2 lambda]` at the last evaluation (the sizes the
    /// stopping tests judge the unknowns by).
    absolute: DVector<f64>,
    /// The dynamic rows' floors of the residual test (their inertia or
    /// applied forces, the larger) at the last evaluation.
    floors: SVector<f64, N>,
    blocks: [Range<usize>; 3],
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    const P: usize = N - A;

    /// The servo problem of the crane behind `model` on `trajectory`.
    pub fn new(model: H, trajectory: Tr) -> Self {
        let mass = model.mass_matrix();
        Self {
            model,
            trajectory,
            mass,
            target: [SVector::zeros(); 3],
            formula: StepFormula::unprepared(),
            base: SVector::zeros(),
            lead: SVector::zeros(),
            rate_term: SVector::zeros(),
            beyond_double: false,
            lead_slope: DoubleDouble::from(f64::NAN),
            load_rate: SVector::zeros(),
            load_accel_dt2: SVector::zeros(),
            last_inputs: SVector::zeros(),
            last_multipliers: SVector::zeros(),
            absolute: DVector::zeros(N + M),
            floors: SVector::zeros(),
            blocks: [0..Self::P, Self::P..N, N..N + M],
        }
    }

    /// The load path.
    pub fn trajectory(&self) -> &Tr {
        &self.trajectory
    }

    /// `q`, `v`, `a` at the new time from the unknowns, in `f64`, and `q`
    /// and `v` in double-double (eq. 22a: `v = (c/dt) (p - ybar)`,
    /// `dt^2 a = c^2 (p - ybar) - c dt vbar`).
    fn kinematics(&self, z: &DVector<f64>) -> ([SVector<f64, N>; 3], [SVector<DoubleDouble, N>; 3]) {
        let (p, dt) = (Self::P, self.formula.dt);
        let mut q = SVector::<f64, N>::zeros();
        let mut v = SVector::<f64, N>::zeros();
        let mut a = SVector::<f64, N>::zeros();
        let mut q_extended = self.base;
        let mut v_extended = SVector::<DoubleDouble, N>::zeros();
        let mut a_dt2_extended = SVector::<DoubleDouble, N>::zeros();
        for i in 0..p {
            let lead = self.lead[i] + z[i];
            q_extended[i] = self.base[i] + z[i];
            v_extended[i] = lead * self.formula.rate;
            a_dt2_extended[i] = lead * self.lead_slope - self.rate_term[i];
            q[i] = q_extended[i].hi;
            v[i] = v_extended[i].hi;
            a[i] = a_dt2_extended[i].to_f64() / (dt * dt);
        }
        for k in 0..A {
            q[p + k] = self.target[0][k];
            v[p + k] = self.target[1][k];
            a[p + k] = self.target[2][k];
            v_extended[p + k] = self.load_rate[k];
            a_dt2_extended[p + k] = self.load_accel_dt2[k];
        }
        ([q, v, a], [q_extended, v_extended, a_dt2_extended])
    }

    /// `dt^2 u` and `dt^2 lambda` from the unknowns, in double-double: the
    /// last step's plus the corrections, or the unknowns themselves where
    /// the step's formula has no double-double part.
    fn scaled_forces(&self, z: &DVector<f64>) -> (SVector<DoubleDouble, A>, SVector<DoubleDouble, M>) {
        let p = Self::P;
        let (inputs, multipliers) = match self.formula.extended {
            Some(_) => (self.last_inputs, self.last_multipliers),
            None => (SVector::zeros(), SVector::zeros()),
        };
        (
            SVector::from_fn(|k, _| inputs[k] + z[p + k]),
            SVector::from_fn(|i, _| multipliers[i] + z[N + i]),
        )
    }

    /// The dynamic rows (22b, 22c) in double-double, rounded: `M (dt^2 a) -
    /// dt^2 f(q, v) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda)`.
    fn dynamic_residual(
        &self,
        [q, v, a_dt2]: &[SVector<DoubleDouble, N>; 3],
        inputs: &SVector<DoubleDouble, A>,
        multipliers: &SVector<DoubleDouble, M>,
    ) -> SVector<f64, N> {
        let model = &*self.model;
        let dt2 = self.formula.dt * self.formula.dt;
        let f = model.forces(q, v);
        let bt = model.input_matrix(q);
        let jac_g = model.constraint_jacobian(q);
        SVector::from_fn(|i, _| {
            let mut row = -(f[i] * dt2);
            for j in 0..N {
                if self.mass[(i, j)] != 0.0 {
                    row += a_dt2[j] * self.mass[(i, j)];
                }
            }
            // (B and G are sparse)
            for k in (0..A).filter(|&k| bt[(i, k)].hi != 0.0) {
                row -= bt[(i, k)] * inputs[k];
            }
            for l in (0..M).filter(|&l| jac_g[(l, i)].hi != 0.0) {
                row += jac_g[(l, i)] * multipliers[l];
            }
            row.to_f64()
        })
    }

    /// Keep `dt^2 u` and `dt^2 lambda` of `state` as the last step's.
    fn remember(&mut self, state: &State<N, M, A>, dt: f64) {
        let dt2 = dt * dt;
        self.last_inputs = state.u.map(|u| DoubleDouble::product(u, dt2));
        self.last_multipliers = state.lambda.map(|l| DoubleDouble::product(l, dt2));
    }
}

/// The load target `gamma, gamma', gamma''` of the step to `t`.
pub(crate) fn servo_target<const A: usize>(trajectory: &impl Trajectory<A>, t: f64) -> ServoTarget<A> {
    let mut target = [SVector::zeros(); 3];
    trajectory.derivatives_into(t, &mut target);
    target
}

/// The unknowns `[p; dt^2 u; dt^2 lambda]` of `state` at step `dt`, into `z`.
fn write_unknowns<const N: usize, const M: usize, const A: usize>(
    state: &State<N, M, A>,
    dt: f64,
    z: &mut DVector<f64>,
) {
    let (p, dt2) = (N - A, dt * dt);
    z.rows_mut(0, p).copy_from(&state.q.rows(0, p));
    z.rows_mut(p, A).copy_from(&(state.u * dt2));
    z.rows_mut(N, M).copy_from(&(state.lambda * dt2));
}

/// Refuse a NaN or infinite load target.
pub(crate) fn check_target<const A: usize>(
    target: &ServoTarget<A>,
    t: f64,
    load: &[&'static str],
) -> Result<(), Error> {
    if !target.iter().all(|x| x.iter().all(|v| v.is_finite())) {
        return Err(Error::NonFinite {
            quantity: "load target gamma(t)",
            t,
        });
    }
    check_path_position(&target[0], t, load)
}

/// Refuse a load position beyond 1e100 (`load`: the load coordinates'
/// names): the constraints' squares of lengths would overflow, and the
/// step would end as a non-finite Newton iterate.
pub(crate) fn check_path_position<const A: usize>(
    position: &SVector<f64, A>,
    t: f64,
    load: &[&'static str],
) -> Result<(), Error> {
    match position.iter().position(|x| x.abs() > 1e100) {
        Some(k) => Err(Error::PathOutOfRange {
            coordinate: load.get(k).copied().unwrap_or("load coordinate"),
            value: position[k],
            t,
        }),
        None => Ok(()),
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> NonlinearSystem for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    fn dim(&self) -> usize {
        N + M
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        let p = Self::P;
        let (kinematics, extended) = self.kinematics(z);
        let (inputs, multipliers) = self.scaled_forces(z);
        let u_scaled = inputs.map(|x| x.hi);
        let lambda_scaled = multipliers.map(|x| x.hi);
        self.absolute.rows_mut(0, p).copy_from(&kinematics[0].rows(0, p));
        self.absolute.rows_mut(p, A).copy_from(&u_scaled);
        self.absolute.rows_mut(N, M).copy_from(&lambda_scaled);
        // the residual beyond double precision, where the target is: its
        // rounding would be the coordinates' noise
        let constraints = if self.beyond_double {
            self.model.constraints(&extended[0]).map(DoubleDouble::to_f64)
        } else {
            self.model.constraints(&kinematics[0])
        };
        let model = &*self.model;
        // residual: dynamic rows (22b, 22c) scaled by dt^2, then (22d); the
        // iteration matrix column by column of z: p, then dt^2 u (-B^T over
        // 0), dt^2 lambda
        let rows = dynamic_rows(
            model,
            &self.mass,
            &self.formula,
            &kinematics,
            &u_scaled,
            &lambda_scaled,
            &constraints,
            p,
            r,
            jac,
        );
        for k in 0..A {
            for i in 0..N {
                jac[(i, p + k)] = -rows.input_matrix[(i, k)];
            }
        }
        if self.beyond_double {
            r.rows_mut(0, N)
                .copy_from(&self.dynamic_residual(&extended, &inputs, &multipliers));
        }
        // dynamic rows also by their largest term (the load row of x nearly
        // vanishes when the load hangs straight below the pulley)
        self.floors = SVector::from_fn(|i, _| rows.inertia[i].abs().max(rows.applied[i].abs()));
    }

    fn normalised_residual(&self, _z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        normalised_residual(r, jac, &self.absolute, |i| if i < N { self.floors[i] } else { 0.0 })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }

    /// The coordinates for their corrections.
    fn magnitudes<'a>(&'a self, _z: &'a DVector<f64>) -> &'a DVector<f64> {
        &self.absolute
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Problem<N, M, A, N> for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    type Model = H::Target;
    type Drive = ServoTarget<A>;

    /// A massless pulley on a nearly slack rope is placed by forces of
    /// round-off size, and the scheme differentiates its position twice.
    const HOLDS_NEARLY_SLACK: bool = true;

    fn model(&self) -> &H::Target {
        &self.model
    }

    /// The scheme's extrapolation for `p`, the last step's scaled `u` and `lambda`.
    /// 4: the minimal extension of eqs. (22, 24) reduces servo constraints of
    /// index 5, whose inputs need the path's 4th derivative.
    fn path_order_covered(&self) -> Option<usize> {
        Some(4)
    }

    fn predictor(&self) -> Predictor {
        Predictor::Correction { leading: Self::P }
    }

    fn drive(&self, t: f64) -> ServoTarget<A> {
        servo_target(&self.trajectory, t)
    }

    fn check_drive(&self, target: &ServoTarget<A>, t: f64) -> Result<(), Error> {
        check_target(target, t, &H::Target::INFO.coordinates[N - A..])
    }

    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<N>, Error> {
        write_unknowns(start, dt, z);
        // no change of u and lambda known before the first step
        z.rows_mut(N - A, A + M).fill(0.0);
        self.remember(start, dt);
        Ok(Start {
            y0: start.q,
            v0: start.v,
            at_rest: init::at_rest(&self.trajectory, start),
        })
    }

    fn prepare(&mut self, target: &ServoTarget<A>, formula: StepFormula<N>) {
        self.target = *target;
        self.formula = formula;
        let p = Self::P;
        // dt^2 a = (c/dt)^2 dt^2 (p - ybar) - (c/dt) dt^2 vbar with the
        // products of the rate and the step exact: their roundings (1e-16
        // relative, of terms of the size of v dt) would bias a by 1e-16 v/dt
        let rate_dt = DoubleDouble::product(formula.rate, formula.dt);
        self.lead_slope = rate_dt * rate_dt;
        let rate_slope = rate_dt * formula.dt;
        let (prediction, value_offset, rate_offset, load) = match formula.extended {
            Some(extended) => (
                extended.prediction,
                extended.value_offset,
                extended.rate_offset,
                extended.target_time.and_then(|t| self.trajectory.target_extended(t)),
            ),
            // the unknowns are the coordinates themselves
            None => (
                SVector::zeros(),
                formula.value_offset.map(DoubleDouble::from),
                formula.rate_offset.map(DoubleDouble::from),
                None,
            ),
        };
        self.beyond_double = load.is_some();
        let load = load.unwrap_or_else(|| target.map(|x| x.map(DoubleDouble::from)));
        for i in 0..p {
            self.base[i] = prediction[i];
            self.lead[i] = prediction[i] - value_offset[i];
            self.rate_term[i] = rate_offset[i] * rate_slope;
        }
        let dt2 = formula.dt * formula.dt;
        for k in 0..A {
            self.base[p + k] = load[0][k];
            self.load_rate[k] = load[1][k];
            self.load_accel_dt2[k] = load[2][k] * dt2;
        }
    }

    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, N>, Error> {
        let dt2 = self.formula.dt * self.formula.dt;
        let ([q, v, _], [q_extended, v_extended, _]) = self.kinematics(z);
        let (inputs, multipliers) = self.scaled_forces(z);
        (self.last_inputs, self.last_multipliers) = (inputs, multipliers);
        let u = SVector::from_fn(|k, _| inputs[k].hi / dt2);
        let lambda = SVector::from_fn(|i, _| multipliers[i].hi / dt2);
        Ok(Accepted {
            state: State { t, q, v, u, lambda },
            y: q,
            v,
            // (the load's rows, which the history never reads, without
            // their trailing parts: their leading ones are the drive's)
            trailing: Some([
                SVector::from_fn(|i, _| if i < Self::P { q_extended[i].lo } else { 0.0 }),
                SVector::from_fn(|i, _| if i < Self::P { v_extended[i].lo } else { 0.0 }),
            ]),
        })
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Follow<N, M, A, N> for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    /// Always: a consistent state is all its history needs.
    fn can_take_over(&self, _state: &State<N, M, A>) -> bool {
        true
    }

    /// `q` and `q'` of the state, and its unknowns `[p; dt^2 u; dt^2 lambda]`.
    fn follow(
        &mut self,
        state: &State<N, M, A>,
        _last: &SVector<f64, N>,
        formula: StepFormula<N>,
        z: &mut DVector<f64>,
    ) -> Result<(SVector<f64, N>, SVector<f64, N>), Error> {
        write_unknowns(state, formula.dt, z);
        // the corrections the stepper extrapolates: the change of u and
        // lambda over the step
        let (inputs, multipliers) = (self.last_inputs, self.last_multipliers);
        self.remember(state, formula.dt);
        for k in 0..A {
            z[N - A + k] = (self.last_inputs[k] - inputs[k]).to_f64();
        }
        for i in 0..M {
            z[N + i] = (self.last_multipliers[i] - multipliers[i]).to_f64();
        }
        Ok((state.q, state.v))
    }
}

/// Eqs. (22a-d) one step at a time: the [`Stepper`] of the [`Redundant`]
/// problem on the scheme `S`, made by
/// `Stepper::new(Redundant::new(&crane, &path), &start, &options)`; after
/// construction a step does not allocate.
pub type RedundantStepper<H, Tr, const N: usize, const M: usize, const A: usize, S = Scheme> =
    Stepper<Redundant<H, Tr, N, M, A>, S, N, M, A, N>;

/// Integrate eqs. (22a-d) from `start` to `options.tf()` with its scheme.
///
/// Storage for all steps is reserved up front; the step loop does not allocate.
/// The result is what the causal inverse computes: for a crane that is not
/// flat it can grow without bound, which
/// [`internal::diagnose`](crate::internal::diagnose) tells.
pub fn simulate<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
    S: Method,
{
    simulate_with_progress(model, trajectory, start, options, &mut |_, _| {})
}

/// [`simulate`], calling `progress(step, steps)` after every step.
pub fn simulate_with_progress<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
    S: Method,
{
    solve(Redundant::new(model, trajectory), start, options, progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{Gantry, central_difference_error, random_history, uniform};
    use crate::trajectory::{FromFn, Poly9};

    /// The same in double-double, where the unknowns are corrections and
    /// the residual is evaluated beyond double precision: the load target
    /// is the path's own at the step's time (a poly9 move of the gantry).
    #[test]
    fn the_extended_iteration_matrix_matches_central_differences() {
        let mut rnd = uniform(5);
        let path = Poly9::new(0.0, 4.0, SVector::from([0.0, -4.0]), SVector::from([3.0, -3.0])).unwrap();
        for scheme in Scheme::ALL {
            for dt in [0.1, 0.01, 0.001] {
                for _ in 0..10 {
                    let (history, start) = random_history(scheme, &mut rnd);
                    let mut problem = Redundant::new(&Gantry, &path);
                    problem.start(&start, dt, &mut DVector::zeros(5)).unwrap();
                    let t = 4.0 * rnd();
                    let target = servo_target(&path, t);
                    problem.prepare(&target, history.extended_formula(dt, 0, Some(DoubleDouble::from(t))));
                    assert!(problem.beyond_double, "the path's own target at t = {t}");
                    // corrections of the coordinates, dt^2 u and dt^2 lambda
                    let z = DVector::from_fn(5, |i, _| match i {
                        0 | 1 => 0.01 * rnd(),
                        2 | 3 => dt * dt * 100.0 * rnd(),
                        _ => dt * dt * 10.0 * rnd(),
                    });
                    let (worst, largest) = central_difference_error(&mut problem, &z);
                    assert!(
                        worst <= 1e-6 * largest,
                        "{scheme}, dt = {dt}: worst {worst:e} of {largest:e}"
                    );
                }
            }
        }
    }

    /// The redundant iteration matrix (eqs. 22b-d in `[p; dt^2 u; dt^2
    /// lambda]`) is the Jacobian of the residual: against central
    /// differences at random points, histories and load targets, for every
    /// scheme and three steps, entry by entry to 1e-6 of the largest entry
    /// (central differences of a smooth residual: ~1e-9). The gantry's
    /// friction and rope-length-dependent winch make every term count.
    #[test]
    fn iteration_matrix_matches_central_differences() {
        let mut rnd = uniform(3);
        let path = FromFn(|_t: f64, _k: usize| SVector::<f64, 2>::zeros());
        for scheme in Scheme::ALL {
            for dt in [0.1, 0.01, 0.001] {
                for _ in 0..10 {
                    let (history, start) = random_history(scheme, &mut rnd);
                    let mut problem = Redundant::new(&Gantry, &path);
                    problem.start(&start, dt, &mut DVector::zeros(5)).unwrap();
                    let target = [0.0, 1.0, 2.0].map(|scale| SVector::from_fn(|_, _| scale + rnd()));
                    problem.prepare(&target, history.formula(dt));
                    // p = [s, L] of the crane's size, dt^2 u, dt^2 lambda
                    let z = DVector::from_fn(5, |i, _| match i {
                        0 | 1 => 3.0 + rnd(),
                        2 | 3 => dt * dt * 1000.0 * rnd(),
                        _ => dt * dt * 100.0 * rnd(),
                    });
                    let (worst, largest) = central_difference_error(&mut problem, &z);
                    assert!(
                        worst <= 1e-6 * largest,
                        "{scheme}, dt = {dt}: worst {worst:e} of {largest:e}"
                    );
                }
            }
        }
    }
}
