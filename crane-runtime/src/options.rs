//! The settings of a run ([`Options`], each checked when it is set) and the
//! count of its steps ([`step_count`], [`steps_in`]): the one place that
//! says what a valid time step, end time and span are.

use crate::error::Error;
use crate::newton::NewtonOptions;
use crate::scheme::{Method, Scheme};

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
    /// finite and at least [`MIN_DT`], [`Error::InvalidEndTime`] unless `tf`
    /// is finite.
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

/// The smallest time step, s. The servo problems solve for `dt^2 u` and
/// `dt^2 lambda`; below a microsecond these approach Newton's absolute
/// tolerance (1e-14), which would then accept iterates that are not
/// converged (and near 1e-154 s `dt^2` underflows to 0).
pub const MIN_DT: f64 = 1e-6;

/// Refuse a time step that is not finite or below [`MIN_DT`].
fn check_step_size(dt: f64) -> Result<(), Error> {
    if dt.is_finite() && dt >= MIN_DT {
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
    let resolution = time_resolution(t0.abs().max(tf.abs()));
    if !(resolution <= TIME_RESOLUTION * dt) {
        return Err(Error::TimesUnresolved { t: tf, resolution, dt });
    }
    steps_in(tf - t0, dt)
}

/// The coarsest spacing of doubles at a run's times, as a fraction of its
/// step, that [`step_count`] takes: the step times `t0 + n dt` are each
/// rounded to that spacing, so that with 1e-6 the load path is sampled
/// within 1e-6 of a step of where the scheme assumes (`t0 = 1e14`, `dt =
/// 0.01` rounds every time to 0.0156 s: repeated times, and inputs of 1e44
/// N m).
pub const TIME_RESOLUTION: f64 = 1e-6;

/// The spacing of doubles at `t` (`t >= 0`): the distance to the next
/// larger double.
fn time_resolution(t: f64) -> f64 {
    f64::from_bits(t.to_bits() + 1) - t
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A run whose times double precision cannot tell apart at its step is
    /// refused: the paper's move shifted to t0 = 1e14 s (times spaced by
    /// 0.0156 s there, more than dt = 0.01 s), and to 1e9 s at dt = 0.001 s
    /// (1.2e-7 s, 1.2e-4 of the step); an FMU host's clock past 8192 s at
    /// dt = 0.001 s (1.8e-12 s, 1.8e-9 of the step) and a start at -1e5 s
    /// are taken.
    #[test]
    fn times_double_precision_cannot_tell_apart_are_refused() {
        for (t0, dt) in [(1e14, 0.01), (1e9, 0.001), (-1e14, 0.01)] {
            let refused = step_count(t0, t0 + 4.0, dt);
            assert!(
                matches!(refused, Err(Error::TimesUnresolved { .. })),
                "{t0}: {refused:?}"
            );
            assert!(refused.unwrap_err().to_string().contains("t0 = 0"));
        }
        assert_eq!(step_count(8192.0, 8196.0, 0.001).unwrap(), 4000);
        assert_eq!(step_count(-1e5, -1e5 + 4.0, 0.01).unwrap(), 400);
    }
}
