//! The scenario file's schema as written (TOML), and reading it: unknown
//! keys and wrong types are errors naming the key, its table, line and
//! column.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use super::ScenarioError;
use crane_models::ProfileKind;
use crane_models::study::Formulation;

/// The largest scenario file read, in bytes: the paper's scenarios are under
/// 1 KiB; a bound keeps a device such as `/dev/zero` or a huge file from
/// filling the memory.
pub const MAX_SCENARIO_BYTES: u64 = 1 << 20;

/// A scenario file as written.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Optional: the model the file is written for (checked).
    pub model: Option<String>,
    /// Time step, s.
    pub dt: Option<f64>,
    /// End of the run, s (default: the end of the motion).
    pub tf: Option<f64>,
    /// Formulation of the servo problem.
    pub formulation: Option<Formulation>,
    /// Time-discretisation scheme, by name (`bdf4`).
    pub scheme: Option<String>,
    /// Start of the robot coordinates (checked for consistency).
    pub p0: Option<Vec<f64>>,
    /// Profile of the load path.
    pub trajectory: Option<ProfileKind>,
    /// Ramp duration of `three-phase`, s.
    pub tau0: Option<f64>,
    /// A spline's waypoints, load coordinates each.
    pub waypoints: Option<Vec<Vec<f64>>>,
    /// The waypoints' times, s.
    pub times: Option<Vec<f64>>,
    /// A spline's degree.
    pub degree: Option<usize>,
    /// A spline's knots in the move's normalised time, from 0 to 1.
    pub knots: Option<Vec<f64>>,
    /// A spline's control points, load coordinates each.
    pub control: Option<Vec<Vec<f64>>>,
    /// Load coordinates at `t0`.
    pub start: Option<Vec<f64>>,
    /// Load coordinates at `t1`.
    pub end: Option<Vec<f64>>,
    /// Start of the motion (and of the run), s.
    pub t0: Option<f64>,
    /// End of the motion, s.
    pub t1: Option<f64>,
    /// `t1 - t0`, s (instead of `t1`).
    pub duration: Option<f64>,
    /// Parameter overrides by the model's names.
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
    /// Limits on `|u|` by input name.
    #[serde(default)]
    pub limits: BTreeMap<String, f64>,
    /// Parameters of the plant a `--replay` drives, where it differs from
    /// the model the torques are computed for.
    #[serde(default)]
    pub plant: BTreeMap<String, f64>,
}

impl ScenarioFile {
    /// Read and parse a scenario file (unknown keys and wrong types are errors naming the key).
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = read_bounded(path)?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parse the text of a scenario from `origin` (a file's path, or what
    /// it came from; errors name it and the key).
    pub fn parse(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        toml::from_str(text).map_err(|e| ScenarioError::Parse {
            path: origin.to_string(),
            message: describe(text, &e, true),
        })
    }

    /// Parse scenario keys given as data, not as a file (a Python dict
    /// written as TOML by the caller): errors name the key, and no line or
    /// column of a text the user never wrote.
    pub fn parse_keys(text: &str) -> Result<Self, ScenarioError> {
        toml::from_str(text).map_err(|e| ScenarioError::Keys {
            message: describe(text, &e, false),
        })
    }
}

/// The text of a scenario file: a regular file (not a device or a FIFO,
/// which could stream without end) of at most [`MAX_SCENARIO_BYTES`], read
/// no further than that bound.
fn read_bounded(path: &Path) -> Result<String, ScenarioError> {
    use std::io::Read;
    let read_error = |source| ScenarioError::Read {
        path: path.display().to_string(),
        source,
    };
    let not_a_scenario = |what: String| ScenarioError::NotAScenario {
        path: path.display().to_string(),
        what,
    };
    // the type first: opening a FIFO without a writer blocks for ever
    if !std::fs::metadata(path).map_err(read_error)?.is_file() {
        return Err(not_a_scenario("not a regular file".into()));
    }
    let file = std::fs::File::open(path).map_err(read_error)?;
    // and again on what was opened (the name may have been replaced since)
    let metadata = file.metadata().map_err(read_error)?;
    if !metadata.is_file() {
        return Err(not_a_scenario("not a regular file".into()));
    }
    let mut bytes = Vec::new();
    file.take(MAX_SCENARIO_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_SCENARIO_BYTES {
        return Err(not_a_scenario(format!("larger than {} KiB", MAX_SCENARIO_BYTES / 1024)));
    }
    String::from_utf8(bytes).map_err(|_| not_a_scenario("not UTF-8 text".into()))
}

/// One line for a TOML error: the key it is about (with its table), the
/// message and, where `located`, the position in `text`.
fn describe(text: &str, error: &toml::de::Error, located: bool) -> String {
    let message = error.message().trim_end().replace('\n', " ");
    let Some(span) = error.span() else {
        return message;
    };
    let before = &text[..span.start.min(text.len())];
    let line_no = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    let mut table = String::new();
    for line in before.lines() {
        let line = line.trim();
        if line.starts_with('[') && !line.contains('=') {
            table = line.trim_matches(|c| c == '[' || c == ']').trim().to_string();
        }
    }
    let line = text[before.rfind('\n').map_or(0, |i| i + 1)..]
        .lines()
        .next()
        .unwrap_or("");
    let key = line
        .split_once('=')
        .map(|(k, _)| k.trim().trim_matches('"').to_string())
        .filter(|k| !k.is_empty());
    let at = if located {
        format!(" (line {line_no}, column {column})")
    } else {
        String::new()
    };
    match key {
        Some(key) if table.is_empty() => format!("key `{key}`: {message}{at}"),
        Some(key) => format!("key `{table}.{key}`: {message}{at}"),
        None => format!("{message}{at}"),
    }
}
