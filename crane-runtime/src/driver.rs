//! What a run means, whatever the problem and scheme: its settings
//! ([`Options`], validated once), the checks before it starts
//! ([`check_parameters`], [`step_count`]) and the run loop that hands each
//! accepted step to an observer ([`run`]) or records the [`Solution`]
//! ([`record`]).

use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::NewtonOptions;
use crate::problem::Problem;
use crate::scheme::{Method, Scheme};
use crate::solution::{Solution, State};
use crate::stepper::{Advance, Stepper};

/// Settings of a run: the time step, the end time, the scheme (a
/// [`Method`]: the built-in [`Scheme`]s by default) and Newton's
/// tolerances, each checked when it is set.
///
/// ```
/// use crane_runtime::{Error, Options, Scheme};
/// let options = Options::new(0.01, 4.0)?.with_scheme(Scheme::Bdf4);
/// assert_eq!((options.dt(), options.tf(), *options.scheme()), (0.01, 4.0, Scheme::Bdf4));
/// assert!(matches!(Options::new(-0.01, 4.0), Err(Error::InvalidTimeStep { .. })));
/// assert!(matches!(Options::new(0.01, f64::NAN), Err(Error::InvalidEndTime { .. })));
/// # Ok::<(), Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options<S: Method = Scheme> {
    dt: f64,
    tf: f64,
    scheme: S,
    newton: NewtonOptions,
}

impl Options<Scheme> {
    /// A run with step `dt` to `tf`, backward Euler (the paper's scheme) and
    /// default Newton tolerances; [`Error::InvalidTimeStep`] unless `dt` is
    /// finite and positive, [`Error::InvalidEndTime`] unless `tf` is finite.
    pub fn new(dt: f64, tf: f64) -> Result<Self, Error> {
        if !tf.is_finite() {
            return Err(Error::InvalidEndTime { tf });
        }
        Ok(Self {
            tf,
            ..Self::stepping(dt)?
        })
    }

    /// Settings for a stepper that runs without an end (a controller, an
    /// FMU): step `dt`, backward Euler, default Newton tolerances.
    pub fn stepping(dt: f64) -> Result<Self, Error> {
        check_step_size(dt)?;
        Ok(Self {
            dt,
            tf: f64::INFINITY,
            scheme: Scheme::default(),
            newton: NewtonOptions::default(),
        })
    }
}

impl<S: Method> Options<S> {
    /// The same settings with another scheme.
    pub fn with_scheme<T: Method>(self, scheme: T) -> Options<T> {
        Options {
            dt: self.dt,
            tf: self.tf,
            scheme,
            newton: self.newton,
        }
    }

    /// The same settings with other Newton tolerances: each tolerance
    /// finite and not negative, at least one iteration.
    pub fn with_newton(self, newton: NewtonOptions) -> Result<Self, Error> {
        let tolerance = |x: f64| x.is_finite() && x >= 0.0;
        if !(tolerance(newton.rtol) && tolerance(newton.atol) && tolerance(newton.residual_tol)) {
            return Err(Error::InvalidNewtonOptions(
                "rtol, atol and residual_tol must be finite and not negative",
            ));
        }
        if newton.max_iterations == 0 {
            return Err(Error::InvalidNewtonOptions("max_iterations must be at least 1"));
        }
        Ok(Self { newton, ..self })
    }

    /// The same settings with another end time (finite).
    pub fn with_end(self, tf: f64) -> Result<Self, Error> {
        if !tf.is_finite() {
            return Err(Error::InvalidEndTime { tf });
        }
        Ok(Self { tf, ..self })
    }

    /// Time step `dt`.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// End time `tf` (infinite for [`Options::stepping`]); the run starts
    /// at the start state's time.
    pub fn tf(&self) -> f64 {
        self.tf
    }

    /// The scheme.
    pub fn scheme(&self) -> &S {
        &self.scheme
    }

    /// Newton's tolerances.
    pub fn newton(&self) -> &NewtonOptions {
        &self.newton
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
        if let (Some(&name), Some(&value)) = (Mdl::INFO.parameters.get(k), values.get(k))
            && !(value > 0.0)
        {
            return Err(Error::NonPositiveParameter { name, value });
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

/// Refuse a time step that is not a finite positive number.
fn check_step_size(dt: f64) -> Result<(), Error> {
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
    steps_in(tf - t0, dt)
}

/// Number of steps of size `dt` in `span` (`> 0`), refusing a span that is
/// not a whole number of steps (to 1e-9 relative) and step counts that
/// cannot be indexed: the one rule for a run's length and an FMU's
/// communication step.
pub fn steps_in(span: f64, dt: f64) -> Result<usize, Error> {
    check_step_size(dt)?;
    let steps = (span / dt).round();
    if !((steps * dt - span).abs() <= 1e-9 * span && steps >= 1.0) {
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
    stepper: &mut impl Advance<N, M, A>,
    steps: usize,
    mut observe: impl FnMut(usize, &State<N, M, A>, &StepReport) -> Result<(), Error>,
) -> Result<(), Error> {
    for step in 1..=steps {
        let report = stepper.step()?;
        observe(step, stepper.state(), &report)?;
    }
    Ok(())
}

/// Run `stepper` from its state to `tf` and record the solution, calling
/// `progress(step, steps)` after every step. Storage for all steps is
/// reserved up front (a run too long to hold is an error before the first
/// step); the loop does not allocate.
pub fn record<Adv, const N: usize, const M: usize, const A: usize>(
    stepper: &mut Adv,
    tf: f64,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Adv: Advance<N, M, A>,
{
    let start = *stepper.state();
    let steps = step_count(start.t, tf, stepper.dt())?;
    let info = <Adv::Model as CraneModel<N, M, A>>::INFO;
    let mut solution = Solution::with_capacity(info, stepper.dt(), stepper.scheme_name(), steps + 1)?;
    let mut lengths = vec![0.0; info.ropes.len()];
    solution.push(stepper.model(), &start, 0, 0, &mut lengths);
    for step in 1..=steps {
        let report = stepper.step()?;
        solution.push(
            stepper.model(),
            stepper.state(),
            report.iterations,
            report.min_norm_steps,
            &mut lengths,
        );
        progress(step, steps);
    }
    Ok(solution)
}

/// Run `problem` from `start` to `options.tf()` on the [`Stepper`] and
/// record the solution (see [`record`]).
pub fn solve<P, S, const N: usize, const M: usize, const A: usize, const K: usize>(
    problem: P,
    start: &State<N, M, A>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    P: Problem<N, M, A, K>,
    S: Method,
{
    record(&mut Stepper::new(problem, start, options)?, options.tf(), progress)
}
