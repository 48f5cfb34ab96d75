//! What can be wrong with a scenario, each variant naming the key.

use crane_models::ProfileKind;
use crane_runtime::UnknownParameter;
use crane_runtime::error::{Number, Seconds};
use crane_runtime::scheme::UnknownScheme;
use crane_runtime::trajectory::TrajectoryError;

use super::file::MAX_SCENARIO_BYTES;

/// Errors of a scenario, each naming the key (as written in the file).
/// Each variant is documented by its message.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    #[error("reading scenario {path}: {source}")]
    Read { path: String, source: std::io::Error },
    #[error("scenario {path}: {message}")]
    Parse { path: String, message: String },
    #[error("scenario: {message}")]
    Keys { message: String },
    #[error("scenario {path}: {what}; a scenario is a TOML file of at most {} KiB", MAX_SCENARIO_BYTES / 1024)]
    NotAScenario { path: String, what: String },
    #[error("{flag} {value}: {need}")]
    Flag {
        flag: &'static str,
        /// As written: as short as it reads back (`1e-300`, not 300 zeros).
        value: String,
        need: String,
    },
    #[error("scenario: `model` is \"{given}\" but the command runs {running}")]
    WrongModel { given: String, running: String },
    #[error("scenario: `{key}` must be a positive number of seconds, got {value:?}")]
    NotPositiveTime { key: &'static str, value: f64 },
    #[error("scenario: `dt` = {0:?} s is below the smallest time step, 1e-6 s")]
    StepTooSmall(f64),
    #[error("scenario: `{key}` must be finite, got {}", Number(*.value))]
    NotFinite { key: String, value: f64 },
    #[error("scenario: `t1` and `duration` both given; give one")]
    EndTwice,
    #[error("scenario: `tf` = {} s must be after the start time t0 = {} s", Seconds(*.tf), Seconds(*.t0))]
    EndBeforeStart { tf: f64, t0: f64 },
    #[error("scenario: `t1` = {} s must be after `t0` = {} s", Seconds(*.t1), Seconds(*.t0))]
    MotionEndsBeforeStart { t1: f64, t0: f64 },
    #[error("scenario: `{key}` needs {expected} numbers for {model} ({names}), got {found}")]
    WrongCount {
        key: &'static str,
        expected: usize,
        model: String,
        names: String,
        found: usize,
    },
    #[error("scenario: `{key}`: entry {index} ({name}) is not finite")]
    EntryNotFinite {
        key: &'static str,
        index: usize,
        name: String,
    },
    #[error("scenario: `tau0` applies only to trajectory = {}", ProfileKind::with_ramps())]
    RampWithoutPhases,
    #[error(
        "scenario: `tau0` (ramp duration, s) is required for trajectory = {}",
        ProfileKind::with_ramps()
    )]
    RampMissing,
    #[error(
        "the move lasts {} s, but its ramps last tau0 = {} s by default, more than half of it: give a longer move \
         (--tf, or `tf`, `t1`, `duration` in a scenario), or `tau0` <= {} s in a scenario",
        Seconds(*.duration),
        Seconds(*.tau0),
        Seconds(0.5 * *.duration)
    )]
    DefaultRampTooLong { tau0: f64, duration: f64 },
    #[error("scenario: the load path (keys `trajectory`, `tau0`, `start`, `end`, `t0`, `t1`): {0}")]
    Path(TrajectoryError),
    #[error("scenario: `{key}`: {reason}")]
    Spline { key: &'static str, reason: String },
    #[error("scenario: `parameters.{key}`: {source}")]
    Parameter { key: String, source: UnknownParameter },
    #[error("scenario: `parameters.{key}` = {} must be positive (the model declares it `positive`)", Number(*.value))]
    NotPositiveParameter { key: String, value: f64 },
    #[error("scenario: `parameters`: {0}")]
    Physical(crane_runtime::Error),
    #[error("scenario: `limits.{key}`: {model} has no input `{key}`; its inputs are {inputs}")]
    UnknownInput { key: String, model: String, inputs: String },
    #[error("scenario: `limits.{key}` must be a positive number, got {value}")]
    LimitNotPositive { key: String, value: f64 },
    #[error("scenario: `scheme`: {0}")]
    Scheme(UnknownScheme),
    #[error("scenario: `tf`: {0}")]
    Time(crane_runtime::Error),
}

#[cfg(test)]
impl ScenarioError {
    /// The key the error is about, as written in the file (`parameters.m_l`),
    /// if it is about one key (the property test checks that the message
    /// names it).
    pub fn key(&self) -> Option<String> {
        use ScenarioError::*;
        match self {
            Read { .. } | Parse { .. } | Keys { .. } | NotAScenario { .. } | Flag { .. } | EndTwice => None,
            WrongModel { .. } => Some("model".into()),
            NotPositiveTime { key, .. } | WrongCount { key, .. } | EntryNotFinite { key, .. } => Some(key.to_string()),
            StepTooSmall(_) => Some("dt".to_string()),
            NotFinite { key, .. } => Some(key.clone()),
            EndBeforeStart { .. } => Some("tf".into()),
            MotionEndsBeforeStart { .. } => Some("t1".into()),
            RampWithoutPhases | RampMissing | DefaultRampTooLong { .. } => Some("tau0".into()),
            Path(_) => Some("trajectory".into()),
            Spline { key, .. } => Some(key.to_string()),
            Parameter { key, .. } | NotPositiveParameter { key, .. } => Some(format!("parameters.{key}")),
            Physical(_) => Some("parameters".into()),
            UnknownInput { key, .. } | LimitNotPositive { key, .. } => Some(format!("limits.{key}")),
            Scheme(_) => Some("scheme".into()),
            Time(_) => Some("tf".into()),
        }
    }
}
