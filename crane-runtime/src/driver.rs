//! The run loop, whatever the problem and scheme: it hands each accepted
//! step to an observer ([`run`]) or records the [`Solution`] ([`record`],
//! [`solve`]).

use crate::error::Error;
use crate::model::CraneModel;
use crate::options::{Options, step_count};
use crate::problem::Problem;
use crate::scheme::Method;
use crate::solution::{Solution, State};
use crate::stepper::{Advance, StepReport, Stepper};

/// Take `steps` steps, handing each accepted state with its report to
/// `observe(step, state, report)` (`step` from 1). Stops at the first
/// error, of the stepper or of the observer.
pub fn run<const N: usize, const M: usize, const A: usize>(
    stepper: &mut impl Advance<N, M, A>,
    steps: usize,
    mut observe: impl FnMut(usize, &State<N, M, A>, &StepReport) -> Result<(), Error>,
) -> Result<(), Error> {
    for step in 1..=steps {
        crate::cancel::check()?;
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
    solution.path_order_covered = stepper.path_order_covered();
    let mut lengths = vec![0.0; info.ropes.len()];
    solution.push(stepper.model(), &start, StepReport::default(), &mut lengths);
    for step in 1..=steps {
        crate::cancel::check()?;
        let report = stepper.step()?;
        solution.push(stepper.model(), stepper.state(), report, &mut lengths);
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
