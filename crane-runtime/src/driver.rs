//! The driver shared by every problem and scheme: run settings, the
//! [`Stepper`] interface, the step count of a run, and the run loop that
//! hands each accepted step to an observer (a [`Solution`] being recorded,
//! a progress bar, a file being streamed).

use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::{NewtonFailure, NewtonOptions};
use crate::scheme::Scheme;
use crate::solution::{Solution, State};
use crate::trajectory::Trajectory;

/// Settings of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Time step `dt`.
    pub dt: f64,
    /// End time `tf`; the run starts at the start state's time.
    pub tf: f64,
    /// Time-discretisation scheme (default backward Euler, the paper's).
    pub scheme: Scheme,
    /// Newton tolerances.
    pub newton: NewtonOptions,
}

impl Options {
    /// `dt` and `tf` with backward Euler and default Newton tolerances.
    pub fn new(dt: f64, tf: f64) -> Self {
        Self {
            dt,
            tf,
            scheme: Scheme::default(),
            newton: NewtonOptions::default(),
        }
    }

    /// The same settings with another scheme.
    pub fn with_scheme(self, scheme: Scheme) -> Self {
        Self { scheme, ..self }
    }
}

/// What one step reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Of those, minimum-norm steps on a singular iteration matrix.
    pub min_norm_steps: usize,
}

/// The load target of one step: `gamma, gamma', gamma''` at the new time.
pub type ServoTarget<const A: usize> = [nalgebra::SVector<f64, A>; 3];

/// A one-step-at-a-time integrator of a crane problem (any scheme, any
/// formulation).
pub trait Stepper<const N: usize, const M: usize, const A: usize> {
    /// Advance one step along the trajectory.
    fn step(&mut self) -> Result<StepReport, Error>;
    /// The state after the last step (the start before the first).
    fn state(&self) -> &State<N, M, A>;
}

/// The load target `gamma, gamma', gamma''` of the step to `t`.
pub(crate) fn servo_target<const A: usize>(trajectory: &impl Trajectory<A>, t: f64) -> ServoTarget<A> {
    [0, 1, 2].map(|k| trajectory.derivative(t, k))
}

/// Refuse a NaN or infinite load target.
pub(crate) fn check_target<const A: usize>(target: &ServoTarget<A>, t: f64) -> Result<(), Error> {
    if target.iter().all(|x| x.iter().all(|v| v.is_finite())) {
        Ok(())
    } else {
        Err(Error::NonFinite {
            quantity: "load target gamma(t)",
            t,
        })
    }
}

/// Refuse a step to `t` that is not `t_n + dt` (to 1e-9 of the step).
pub(crate) fn check_step_time(t: f64, t_prev: f64, dt: f64) -> Result<(), Error> {
    if (t - (t_prev + dt)).abs() <= 1e-9 * dt {
        Ok(())
    } else {
        Err(Error::WrongStepTime {
            t,
            expected: t_prev + dt,
        })
    }
}

/// The runtime error for a failed Newton solve of the step to `t`.
pub(crate) fn step_error(failure: NewtonFailure, t: f64) -> Error {
    match failure {
        NewtonFailure::NotConverged { iterations, residual } => Error::NewtonNotConverged {
            t,
            iterations,
            residual,
        },
        NewtonFailure::Singular { pivot_ratio } => Error::SingularIterationMatrix { t, pivot_ratio },
        NewtonFailure::NonFinite => Error::NonFinite {
            quantity: "Newton iterate",
            t,
        },
    }
}

/// Refuse parameters a crane cannot have before a run starts: NaN or
/// infinite values, values that make the mass matrix indefinite (a kinetic
/// energy is positive semi-definite; a negative mass or inertia would flip
/// the sign of the inputs it moves and still "converge"), and non-positive
/// values of parameters the model declares `positive`.
pub fn check_parameters<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
) -> Result<(), Error> {
    let values = model.parameter_values();
    for (name, &value) in Mdl::INFO.parameters.iter().zip(&values) {
        if !value.is_finite() {
            return Err(Error::NonFiniteParameter { name, value });
        }
    }
    for &k in Mdl::INFO.positive {
        if let (Some(&name), Some(&value)) = (Mdl::INFO.parameters.get(k), values.get(k)) {
            if !(value > 0.0) {
                return Err(Error::NonPositiveParameter { name, value });
            }
        }
    }
    let mass = model.mass_matrix::<f64>();
    let scale = mass.amax();
    if scale > 0.0 {
        let eigen = nalgebra::DMatrix::from_column_slice(N, N, mass.as_slice()).symmetric_eigen();
        let (index, smallest) = eigen.eigenvalues.argmin();
        if smallest < -1e-12 * scale {
            let direction = eigen.eigenvectors.column(index);
            let largest = direction.amax();
            let coordinates: Vec<&str> = (0..N)
                .filter(|&i| direction[i].abs() > 0.1 * largest)
                .map(|i| Mdl::INFO.coordinates[i])
                .collect();
            let negative: Vec<&str> = Mdl::INFO
                .parameters
                .iter()
                .zip(&values)
                .filter(|(_, v)| **v < 0.0)
                .map(|(n, _)| *n)
                .collect();
            return Err(Error::IndefiniteMassMatrix {
                smallest_eigenvalue: smallest,
                coordinates: coordinates.join(", "),
                negative_parameters: if negative.is_empty() {
                    "none".into()
                } else {
                    negative.join(", ")
                },
            });
        }
    }
    Ok(())
}

/// Refuse a time step that is not a finite positive number (every stepper
/// and [`step_count`] starts with this).
pub(crate) fn check_step_size(dt: f64) -> Result<(), Error> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidTimeStep { dt })
    }
}

/// Number of steps of size `dt` from `t0` to `tf`, refusing spans that are
/// not a whole number of steps (to 1e-9 relative) and step counts that
/// cannot be indexed.
pub fn step_count(t0: f64, tf: f64, dt: f64) -> Result<usize, Error> {
    check_step_size(dt)?;
    if !(tf.is_finite() && t0.is_finite() && tf > t0) {
        return Err(Error::InvalidTimeSpan { t0, tf });
    }
    let span = tf - t0;
    let steps = (span / dt).round();
    if (steps * dt - span).abs() > 1e-9 * span || steps < 1.0 {
        return Err(Error::StepsDoNotFit { span, dt });
    }
    // beyond 2^53 steps the times t0 + i dt no longer differ step by step
    if steps >= 2f64.powi(53) {
        return Err(Error::TooManySteps {
            steps,
            bytes: f64::INFINITY,
        });
    }
    Ok(steps as usize)
}

/// Take `steps` steps, handing each accepted state with its report to
/// `observe(step, state, report)` (`step` from 1). Stops at the first
/// error, of the stepper or of the observer.
pub fn run<const N: usize, const M: usize, const A: usize>(
    stepper: &mut impl Stepper<N, M, A>,
    steps: usize,
    mut observe: impl FnMut(usize, &State<N, M, A>, &StepReport) -> Result<(), Error>,
) -> Result<(), Error> {
    for step in 1..=steps {
        let report = stepper.step()?;
        observe(step, stepper.state(), &report)?;
    }
    Ok(())
}

/// Take `steps` steps and record the solution. Storage for all steps is
/// reserved up front (a run too long to hold is an error before the first
/// step); the loop does not allocate.
pub fn record<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    start: &State<N, M, A>,
    stepper: &mut impl Stepper<N, M, A>,
    steps: usize,
    options: &Options,
    progress: &mut impl FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
{
    let mut solution = Solution::with_capacity(Mdl::INFO, options.dt, options.scheme, steps + 1)?;
    let mut lengths = vec![0.0; Mdl::INFO.ropes.len()];
    solution.push(model, start, 0, 0, &mut lengths);
    run(stepper, steps, |step, state, report| {
        solution.push(model, state, report.iterations, report.min_norm_steps, &mut lengths);
        progress(step, steps);
        Ok(())
    })?;
    Ok(solution)
}
