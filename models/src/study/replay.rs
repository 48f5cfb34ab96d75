//! The replay policy of a study: the computed torques on the crane's
//! forward dynamics ([`crane_runtime::replay`]) on the planned plant or on
//! one whose parameters differ, on `dt / 4` with BDF-2, beyond the move by
//! a settling window (by default twice the longest rope pendulum's period
//! at the end), open loop and, if asked, with a PD law on top.

use std::collections::BTreeMap;
use std::str::FromStr;

use crane_runtime::replay::{Feedback, Pendulum, Replay, ReplayOptions, replay, replay_with_feedback};
use crane_runtime::{CraneModel, Scheme, Solution, State};

use super::StudyError;
use super::summary::ReplaySummary;
use crate::case::Case;
use crate::crane::Crane;

/// The feedback law of a replay: `default` or `KP,KD`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FeedbackSpec {
    /// Gains from the model ([`Feedback::from_model`]).
    Default,
    /// The same stiffness and damping on every robot coordinate.
    Gains(f64, f64),
}

/// A feedback law that is neither `default` nor two numbers `KP,KD >= 0`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("expected `default` or KP,KD (two numbers >= 0), e.g. 5000,2000")]
pub struct BadFeedback;

impl FromStr for FeedbackSpec {
    type Err = BadFeedback;
    /// `default`, or `KP,KD` (spaces allowed around the numbers).
    ///
    /// ```
    /// use crane_models::study::replay::FeedbackSpec;
    /// assert_eq!("default".parse(), Ok(FeedbackSpec::Default));
    /// assert_eq!("5000, 2000".parse(), Ok(FeedbackSpec::Gains(5000.0, 2000.0)));
    /// assert!("5000".parse::<FeedbackSpec>().is_err());
    /// assert!("-1,2".parse::<FeedbackSpec>().is_err());
    /// ```
    fn from_str(text: &str) -> Result<Self, BadFeedback> {
        if text == "default" {
            return Ok(Self::Default);
        }
        let (kp, kd) = text.split_once(',').ok_or(BadFeedback)?;
        let (kp, kd): (f64, f64) = (
            kp.trim().parse().map_err(|_| BadFeedback)?,
            kd.trim().parse().map_err(|_| BadFeedback)?,
        );
        if kp.is_finite() && kd.is_finite() && kp >= 0.0 && kd >= 0.0 {
            Ok(Self::Gains(kp, kd))
        } else {
            Err(BadFeedback)
        }
    }
}

impl FeedbackSpec {
    /// The gains for `model` at `start`, and how to call them in a summary.
    pub fn gains<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        self,
        model: &Mdl,
        start: &State<N, M, A>,
    ) -> (Feedback<N>, String) {
        match self {
            Self::Default => (
                Feedback::from_model(model, start),
                "default (critically damped at 4 sqrt(g/L))".into(),
            ),
            Self::Gains(kp, kd) => {
                let robot = |k: f64| nalgebra::SVector::<f64, N>::from_fn(|i, _| if i < N - A { k } else { 0.0 });
                (
                    Feedback {
                        kp: robot(kp),
                        kd: robot(kd),
                    },
                    format!("kp = {kp}, kd = {kd}"),
                )
            }
        }
    }
}

/// The longest settling window a replay takes, s (eleven days: beyond any
/// crane's swing, and below where the replay's end time loses the step).
pub const MAX_SETTLE: f64 = 1e6;

/// The forward steps a replay takes per step of the run (its
/// [`ReplayOptions`]' `refine`).
pub fn forward_steps_per_step() -> usize {
    ReplayOptions::new(0.0, Scheme::Bdf2).refine.max(1)
}

/// Refuse a run's step `dt` whose replay would step the plant below the
/// runtime's smallest step (a replay takes [`ReplayOptions`]' `refine`
/// forward steps per step of the run): before the run is made, naming the
/// step the user gave.
pub fn check_step(dt: f64) -> Result<(), StudyError> {
    let refine = forward_steps_per_step();
    if dt / refine as f64 >= crane_runtime::options::MIN_DT {
        return Ok(());
    }
    Err(StudyError::ReplayStep { dt, refine })
}

/// Whether `settle` is a settling window a replay takes: positive and at
/// most [`MAX_SETTLE`].
pub fn valid_settle(settle: f64) -> bool {
    settle > 0.0 && settle <= MAX_SETTLE
}

/// What to replay on.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReplayRequest {
    /// Plant parameters that differ from the planner's, `(name, value)`, in
    /// order (a later one wins).
    pub plant: Vec<(String, f64)>,
    /// The settling window, s (default: twice the longest rope pendulum's
    /// period `2 pi sqrt(L/g)` at the end).
    pub settle: Option<f64>,
    /// A feedback law on top of the computed torques (the replay then also
    /// runs open loop).
    pub feedback: Option<FeedbackSpec>,
}

/// What a replay found: the summary entry and the runs behind it.
#[derive(Debug, Clone)]
pub struct ReplayOutcome<const N: usize, const M: usize, const A: usize> {
    /// `summary.json`'s `replay`.
    pub summary: ReplaySummary,
    /// The replay of the computed torques alone.
    pub open_loop: Replay<N, M, A>,
    /// With the feedback law, if one was asked for.
    pub closed_loop: Option<Replay<N, M, A>>,
    /// The end of the inverse run, s: the torques are held after it.
    pub end: f64,
}

impl<const N: usize, const M: usize, const A: usize> ReplayOutcome<N, M, A> {
    /// The replay the summary describes: with feedback if there is one.
    pub fn result(&self) -> &Replay<N, M, A> {
        self.closed_loop.as_ref().unwrap_or(&self.open_loop)
    }
}

/// The plant of `request`: the case's crane with the request's parameters,
/// each known, finite and in its range
/// ([`check_parameters`](crane_runtime::model::check_parameters)), and
/// those that changed. A request is checked so before any run.
pub fn plant<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    request: &ReplayRequest,
) -> Result<(C::Model, BTreeMap<String, f64>), StudyError> {
    let mut model = case.model().clone();
    let mut changed = BTreeMap::new();
    for (name, value) in &request.plant {
        let refused = |message: String| StudyError::PlantParameter {
            name: name.clone(),
            message,
        };
        if !value.is_finite() {
            return Err(refused(format!("{value} is not finite")));
        }
        model.set_parameter(name, *value).map_err(|e| refused(e.to_string()))?;
        changed.insert(name.clone(), *value);
    }
    crane_runtime::model::check_parameters(&model).map_err(|e| StudyError::PlantParameter {
        name: changed.keys().cloned().collect::<Vec<_>>().join(", "),
        message: e.to_string(),
    })?;
    Ok((model, changed))
}

/// Replay `inverse` (a run of `case`) on the case's crane with the
/// request's plant parameters, settling window and feedback law.
pub fn replay_run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    inverse: &Solution<N, M, A>,
    request: &ReplayRequest,
) -> Result<ReplayOutcome<N, M, A>, StudyError> {
    let (model, changed) = plant(case, request)?;
    let (Some(start), Some(end)) = (inverse.states.first(), inverse.states.last()) else {
        return Err(StudyError::Runtime(crane_runtime::Error::InvalidTimeSpan {
            t0: f64::NAN,
            tf: f64::NAN,
        }));
    };
    let settle = request
        .settle
        .unwrap_or_else(|| 2.0 * Pendulum::longest(&model, end).period());
    let options = ReplayOptions::new(settle, Scheme::Bdf2);
    let open_loop = replay(&model, case.path(), inverse, &options)?;
    let gains = request.feedback.map(|f| f.gains(&model, start));
    let closed_loop = match &gains {
        Some((g, _)) => Some(replay_with_feedback(&model, case.path(), inverse, &options, Some(g))?),
        None => None,
    };
    let result = closed_loop.as_ref().unwrap_or(&open_loop);
    let info = inverse.info;
    let solution = &result.solution;
    let first_slack = (info.ropes.iter().enumerate())
        .filter_map(|(r, rope)| {
            crane_runtime::replay::first_slack(solution, r).map(|i| (rope.tension.to_string(), solution.states[i].t))
        })
        .collect();
    let spec = case.path().spec();
    let travel = (spec.end - spec.start).norm();
    let summary = ReplaySummary {
        max_load_deviation: result.max_load_deviation,
        deviation_at_tf: result.deviation_at_tf,
        residual_sway: result.residual_sway,
        settle_time: settle,
        dt: solution.dt,
        scheme: solution.scheme.to_string(),
        plant: changed,
        feedback: gains.map(|(_, label)| label),
        open_loop_max_load_deviation: open_loop.max_load_deviation,
        first_slack,
        travel,
    };
    Ok(ReplayOutcome {
        summary,
        open_loop,
        closed_loop,
        end: end.t,
    })
}
