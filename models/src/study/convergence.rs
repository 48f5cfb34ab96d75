//! The convergence study of Figs. 7 and 16: the relative error of `u` at
//! t = 1.5 s (eq. 48) against the analytical reference (or, for a crane
//! without one, the exact inputs of its reduced formulation) for a range of
//! time steps, with the observed orders.

use crane_runtime::nalgebra::SVector;
use crane_runtime::{Options, Scheme};

use super::{Formulation, RunSettings, StudyError};
use crate::case::Case;
use crate::crane::Crane;

/// The time steps of the study, s.
pub const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

/// Time of the error measure (eq. 48), s.
pub const T_ERROR: f64 = 1.5;

/// An error at or below this is round-off (a few hundred ulps of `u`): no
/// order is observed against it. The dummy-derivative formulation of a flat
/// crane stays there at every step size (it discretises nothing).
pub const ROUND_OFF: f64 = 1e-13;

/// One time step of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The time step, s.
    pub dt: f64,
    /// `|u - u_ref| / |u_ref|` at [`T_ERROR`] (eq. 48).
    pub e_u: f64,
    /// The observed order against the row before, if there is one and
    /// neither error is at [`ROUND_OFF`].
    pub order: Option<f64>,
    /// What the [`audit`](super::audit()) of the run found: an error measured
    /// on states that are not a solution, or on a run beyond its
    /// formulation, is no evidence of an order; and an error that grew as
    /// the step shrank, beyond the run's round-off.
    pub findings: Vec<String>,
    /// The run's round-off floor ([`round_off_floor`] over the middle 60 %
    /// of the run), relative to `|u_ref|` like `e_u`.
    pub floor: f64,
}

impl Row {
    /// Whether the error is the run's round-off: at most twice its floor
    /// (noise measured at 0.55 to 0.61 of the floor where the error is
    /// noise), where a smaller step no longer helps.
    pub fn at_round_off(&self) -> bool {
        self.e_u <= ROUND_OFF || self.e_u <= 2.0 * self.floor
    }
}

/// The step-to-step noise of the inputs of `states` with `from <= t <= to`:
/// `max |Delta^6 u| / 32`, the sixth differences, which see almost nothing
/// of a smooth input (`u^(6) dt^6`) and about three standard deviations of
/// white noise. Eqs. (22) take the inputs from the scheme's second divided
/// differences of the coordinates, so the coordinates' round-off (1e-16 of
/// their size per step) reaches the inputs amplified like `(c/dt)^2`: the
/// error of a fine step is this noise, and grows as the step shrinks.
pub fn round_off_floor<const N: usize, const M: usize, const A: usize>(
    states: &[crane_runtime::State<N, M, A>],
    from: f64,
    to: f64,
) -> f64 {
    let mut floor = 0.0f64;
    for window in states.windows(7) {
        if window[3].t < from || window[3].t > to {
            continue;
        }
        let u = |k: usize| window[k].u;
        let sixth = (u(6) + u(0)) - (u(5) + u(1)) * 6.0 + (u(4) + u(2)) * 15.0 - u(3) * 20.0;
        floor = floor.max(sixth.amax() / 32.0);
    }
    floor
}

/// The observed order between errors `e0` at step `dt0` and `e1` at `dt1`:
/// `ln(e0/e1) / ln(dt0/dt1)`.
pub fn observed_order(dt0: f64, e0: f64, dt1: f64, e1: f64) -> f64 {
    (e0 / e1).ln() / (dt0 / dt1).ln()
}

/// What the errors of a study are measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reference {
    /// The crane's analytical reference ([`Crane::reference`]).
    Analytical,
    /// The inputs of the crane's reduced (dummy-derivative) formulation,
    /// exact at each step time (nothing is discretised): every flat crane
    /// declared with `crane_model!` has it, a user's included.
    Reduced,
}

impl Reference {
    /// What it is, in a few words.
    pub fn describe(self) -> &'static str {
        match self {
            Reference::Analytical => "the analytical reference",
            Reference::Reduced => "the exact inputs of the dummy-derivative formulation",
        }
    }
}

/// The inputs at [`T_ERROR`] to measure the error against: the crane's
/// analytical reference if it has one there, else the exact inputs of its
/// reduced formulation (a run to [`T_ERROR`] at dt = 0.01 s: its inputs do
/// not depend on the step); an error for a crane with neither (internal
/// dynamics and no analytical reference).
pub fn reference_inputs<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
) -> Result<(SVector<f64, A>, Reference), StudyError> {
    check_span(case)?;
    if let Some(state) = case.reference(T_ERROR) {
        return Ok((state.u, Reference::Analytical));
    }
    let start = case.run_start()?;
    let options = Options::new(0.01, T_ERROR)?;
    let reduced = case
        .simulate_dummy_derivative(&start, &options, &mut |_, _| {})
        .map_err(|error| match error {
            crane_runtime::Error::NoDummyDerivatives { reason, .. } => StudyError::Convergence(format!(
                "{} has no analytical reference at t = {T_ERROR} s and no exact reduced formulation to measure the \
                 error against: {reason}",
                C::NAME
            )),
            error => StudyError::Runtime(error),
        })?;
    let state = reduced
        .states
        .last()
        .filter(|s| (s.t - T_ERROR).abs() < 1e-9)
        .ok_or_else(|| StudyError::Convergence(format!("the reduced run ends before t = {T_ERROR} s")))?;
    Ok((state.u, Reference::Reduced))
}

/// The error is measured inside the run.
fn check_span<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
) -> Result<(), StudyError> {
    if case.t0() < T_ERROR && T_ERROR <= case.tf() {
        Ok(())
    } else {
        Err(StudyError::Convergence(format!(
            "the error is measured at t = {T_ERROR} s, outside the run [{}, {}] s",
            case.t0(),
            case.tf()
        )))
    }
}

/// The study on `case` for the steps `dts` (each run stops at 1.5 s: the
/// state there does not depend on later steps) against
/// [`reference_inputs`], handing each row to `observe` as soon as it is
/// known.
///
/// ```
/// use crane_models::navy_planar::PaperCase;
/// use crane_models::study::{Formulation, convergence};
/// use crane_runtime::Scheme;
///
/// let case = PaperCase::new(4.0).unwrap();
/// let rows = convergence::study(&case, Formulation::Redundant, Scheme::Bdf2, &[0.01, 0.005], |_| {}).unwrap();
/// assert!((rows[1].order.unwrap() - 2.0).abs() < 0.1);
/// ```
pub fn study<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dts: &[f64],
    observe: impl FnMut(&Row),
) -> Result<Vec<Row>, StudyError> {
    let (reference, _) = reference_inputs(case)?;
    study_against(case, &reference, formulation, scheme, dts, observe)
}

/// [`study`] against the inputs `reference` at [`T_ERROR`].
pub fn study_against<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    reference: &SVector<f64, A>,
    formulation: Formulation,
    scheme: Scheme,
    dts: &[f64],
    mut observe: impl FnMut(&Row),
) -> Result<Vec<Row>, StudyError> {
    check_span(case)?;
    let start = case.run_start()?;
    let mut rows: Vec<Row> = Vec::new();
    for &dt in dts {
        let options = Options::new(dt, T_ERROR)?.with_scheme(scheme);
        let solution = formulation
            .simulate(case, &start, &options, &mut |_, _| {})
            .map_err(|error| match error {
                // the span is the study's, not one the user set
                StudyError::Runtime(crane_runtime::Error::StepsDoNotFit { .. }) => StudyError::Convergence(format!(
                    "dt = {dt} s: each run of the study stops at t = {T_ERROR} s, where it measures e_u (eq. 48), \
                     and the run from t = {} s is not a whole number of steps of {dt} s; choose steps that divide it",
                    case.t0()
                )),
                other => other,
            })?;
        let state = solution
            .states
            .iter()
            .find(|s| (s.t - T_ERROR).abs() < 0.5 * dt)
            .ok_or_else(|| StudyError::Convergence(format!("dt = {dt} s: no step at t = {T_ERROR} s")))?;
        let e_u = (state.u - reference).norm() / reference.norm();
        let order = rows
            .last()
            .filter(|last| last.e_u > ROUND_OFF && e_u > ROUND_OFF)
            .map(|last| observed_order(last.dt, last.e_u, dt, e_u));
        let settings = RunSettings {
            dt,
            formulation,
            scheme,
            ..RunSettings::default()
        };
        let summary = super::summarize_run(case, &settings, &solution, 0.0, crate::plan::DIAGNOSIS_SAMPLES);
        let t0 = case.t0();
        let floor =
            round_off_floor(&solution.states, t0 + 0.2 * (T_ERROR - t0), t0 + 0.8 * (T_ERROR - t0)) / reference.norm();
        let mut row = Row {
            dt,
            e_u,
            order,
            findings: super::audit(&summary).iter().map(|f| f.to_string()).collect(),
            floor,
        };
        if let Some(last) = rows.last().filter(|last| e_u > last.e_u && !row.at_round_off()) {
            row.findings.push(format!(
                "the error grew from {:.3e} at dt = {} s to {e_u:.3e} as the step shrank, beyond the run's round-off \
                 ({floor:.1e}): not the scheme's convergence",
                last.e_u, last.dt
            ));
        }
        observe(&row);
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crane_runtime::State;
    use crane_runtime::nalgebra::SVector;

    /// States at `t = 0, dt, ...` with the one input `u(t, i)`.
    fn states(n: usize, dt: f64, u: impl Fn(f64, usize) -> f64) -> Vec<State<1, 0, 1>> {
        (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                State {
                    t,
                    q: SVector::zeros(),
                    v: SVector::zeros(),
                    u: SVector::from([u(t, i)]),
                    lambda: SVector::zeros(),
                }
            })
            .collect()
    }

    /// The floor on synthetic inputs. A polynomial of degree 5 has sixth
    /// differences of zero: its floor is the rounding of the differences,
    /// below 1e-12 of its size. White noise of standard deviation sigma
    /// has sixth differences of standard deviation sigma sqrt(C(12, 6)) =
    /// 30.4 sigma (the sum of the squared binomial coefficients of order
    /// 6), so the floor, their largest over ~400 windows divided by 32, is
    /// about 0.95 sigma times the largest of ~400 standard normal
    /// magnitudes (about 3): within [1, 6] sigma.
    #[test]
    fn the_round_off_floor_sees_noise_and_not_a_smooth_input() {
        let poly =
            |t: f64, _: usize| 3.0 + 2.0 * t - 5.0 * t.powi(2) + 0.7 * t.powi(3) - 0.2 * t.powi(4) + 0.01 * t.powi(5);
        let smooth = states(400, 0.01, poly);
        let largest = smooth.iter().map(|s| s.u[0].abs()).fold(0.0, f64::max);
        let floor = round_off_floor(&smooth, 0.0, 4.0);
        assert!(floor < 1e-12 * largest, "{floor:e} of {largest}");
        // seeded white noise, Box-Muller on a xorshift generator
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let noise: Vec<f64> = (0..400)
            .map(|_| {
                let (a, b) = (uniform().max(f64::MIN_POSITIVE), uniform());
                (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
            })
            .collect();
        let sigma = 1e-6;
        let noisy = states(400, 0.01, |t, i| poly(t, i) + sigma * noise[i]);
        let floor = round_off_floor(&noisy, 0.0, 4.0);
        println!("floor {floor:e} for sigma {sigma:e}");
        assert!((1.0 * sigma..=6.0 * sigma).contains(&floor), "{floor:e}");
    }
}
