//! Scenario files (`crane run MODEL --scenario FILE.toml`): the load path,
//! times, parameters, start and torque limits of a run, applied over the
//! model's paper maneuver.
//!
//! ```toml
//! dt = 0.01                 # time step, s
//! tf = 4.0                  # end of the run, s (default: end of the motion)
//! formulation = "redundant" # or "minimal"
//! scheme = "bdf4"           # backward-euler (default, also bdf1), bdf2 .. bdf5
//! p0 = [8.66, 10, 5, 0, -5] # start of the robot coordinates (default: the paper's)
//! trajectory = "poly9"      # or "three-phase" (then tau0 = ramp duration, s)
//! start = [0.0, -10.0]      # load coordinates at t0
//! end = [-3.0, -14.0]       # load coordinates at t1
//! t0 = 0.0                  # start of the motion and the run, s
//! t1 = 4.0                  # end of the motion, s (or duration = 4.0)
//!
//! [parameters]              # overrides, by the model's parameter names
//! m_l = 1200.0
//!
//! [limits]                  # optional |u| limits per input
//! u1 = 150.0
//! ```
//!
//! Every key is optional; what is missing comes from the paper's maneuver
//! (the built-in case), and command-line flags override the file.

use std::collections::BTreeMap;
use std::path::Path;

use crane_models::{navy_3d, navy_3d_pulley, navy_planar, navy_planar_pulley};
use crane_runtime::trajectory::{Poly9, SmoothThreePhase, ThreePhase, TrajectoryError};
use crane_runtime::{CraneModel, Error, Options, Scheme, Solution, State, Trajectory, init};
use nalgebra::SVector;
use serde::Deserialize;

use crate::{CliError, Formulation};

/// Trajectory profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// Rest-to-rest 5-6-7-8-9 polynomial (eqs. 41-45).
    Poly9,
    /// Ramp, constant speed, ramp (eqs. 85-86).
    ThreePhase,
    /// The same with ramps continuous up to the 6th derivative (bounded
    /// slewing torque for the 3D crane with pulley mass, see ERRATA).
    SmoothThreePhase,
}

/// A scenario file as written.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Optional: the model the file is written for (checked).
    pub model: Option<String>,
    pub dt: Option<f64>,
    pub tf: Option<f64>,
    pub formulation: Option<Formulation>,
    /// Time-discretisation scheme, by name (`bdf4`).
    pub scheme: Option<String>,
    pub p0: Option<Vec<f64>>,
    /// Profile of the load path.
    pub trajectory: Option<Kind>,
    /// Ramp duration of `three-phase`, s.
    pub tau0: Option<f64>,
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
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
    #[serde(default)]
    pub limits: BTreeMap<String, f64>,
}

/// Errors of a scenario, each naming the key.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    #[error("reading scenario {path}: {source}")]
    Read {
        path: String,
        source: std::io::Error,
    },
    #[error("scenario {path}: {message}")]
    Parse { path: String, message: String },
    #[error("scenario: {0}")]
    Invalid(String),
}

impl ScenarioFile {
    /// Read and parse a scenario file (unknown keys and wrong types are errors naming the key).
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Read {
            path: path.display().to_string(),
            source,
        })?;
        toml::from_str(&text).map_err(|e| ScenarioError::Parse {
            path: path.display().to_string(),
            message: describe(&text, &e),
        })
    }
}

/// One line for a TOML error: the key it is about (with its table), the
/// message and the position.
fn describe(text: &str, error: &toml::de::Error) -> String {
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
            table = line
                .trim_matches(|c| c == '[' || c == ']')
                .trim()
                .to_string();
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
    let at = format!("line {line_no}, column {column}");
    match key {
        Some(key) if table.is_empty() => format!("key `{key}`: {message} ({at})"),
        Some(key) => format!("key `{table}.{key}`: {message} ({at})"),
        None => format!("{message} ({at})"),
    }
}

fn invalid(message: impl Into<String>) -> CliError {
    CliError::Scenario(ScenarioError::Invalid(message.into()))
}

/// The load path of a scenario: one of the runtime's profiles.
#[derive(Debug, Clone, PartialEq)]
pub enum ScenarioPath<const A: usize> {
    Poly9(Poly9<A>),
    ThreePhase(ThreePhase<A>),
    SmoothThreePhase(SmoothThreePhase<A>),
}

impl<const A: usize> Trajectory<A> for ScenarioPath<A> {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        match self {
            ScenarioPath::Poly9(p) => p.derivative(t, k),
            ScenarioPath::ThreePhase(p) => p.derivative(t, k),
            ScenarioPath::SmoothThreePhase(p) => p.derivative(t, k),
        }
    }
}

/// The paper's maneuver of a model: what a scenario starts from.
pub struct PaperDefaults<const A: usize> {
    pub kind: Kind,
    pub tau0: Option<f64>,
    pub t0: f64,
    /// End of the motion (and of the run) without `--tf`.
    pub t1: f64,
    pub start: SVector<f64, A>,
    pub end: SVector<f64, A>,
    pub p0: Vec<f64>,
}

/// A built-in model as the command runs it: its default model, the paper's
/// maneuver, and its analytical reference and minimal coordinates on any path.
pub trait Crane<const N: usize, const M: usize, const A: usize> {
    type Model: CraneModel<N, M, A> + Clone;
    fn model() -> Self::Model;
    fn defaults() -> PaperDefaults<A>;
    /// The paper's path ending at `t1` (used as is when the scenario changes only times).
    fn paper_path(t1: f64) -> Result<ScenarioPath<A>, TrajectoryError>;
    fn reference(model: &Self::Model, path: &ScenarioPath<A>, t: f64) -> Option<State<N, M, A>>;
    fn simulate_minimal(
        model: &Self::Model,
        path: &ScenarioPath<A>,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>>;
    /// Names of derived outputs (see `crane_models::Case::derived_outputs`).
    fn derived_outputs() -> &'static [&'static str] {
        &[]
    }
    /// The derived outputs of a state.
    fn derived(state: &State<N, M, A>) -> Vec<f64> {
        let _ = state;
        Vec::new()
    }
}

fn finite_state<const N: usize, const M: usize, const A: usize>(
    t: f64,
    q: SVector<f64, N>,
    v: SVector<f64, N>,
    u: SVector<f64, A>,
    lambda: SVector<f64, M>,
) -> Option<State<N, M, A>> {
    let finite = |s: &[f64]| s.iter().all(|x| x.is_finite());
    (finite(q.as_slice())
        && finite(v.as_slice())
        && finite(u.as_slice())
        && finite(lambda.as_slice()))
    .then_some(State { t, q, v, u, lambda })
}

/// The planar crane (sect. 5.1).
pub struct Planar;
/// The planar crane with pulley mass (sect. 5.2).
pub struct PlanarPulley;
/// The 3D crane (sect. 6.1).
pub struct Crane3d;

fn poly9_defaults<const A: usize>(path: &Poly9<A>, p0: Vec<f64>) -> PaperDefaults<A> {
    PaperDefaults {
        kind: Kind::Poly9,
        tau0: None,
        t0: path.t0(),
        t1: path.tf(),
        start: path.derivative(path.t0(), 0),
        end: path.derivative(path.tf(), 0),
        p0,
    }
}

impl Crane<7, 3, 2> for Planar {
    type Model = navy_planar::NavyPlanar;
    fn model() -> Self::Model {
        Self::Model::default()
    }
    fn defaults() -> PaperDefaults<2> {
        poly9_defaults(
            &navy_planar::paper_path(4.0).expect("paper path"),
            navy_planar::paper_p0().to_vec(),
        )
    }
    fn paper_path(t1: f64) -> Result<ScenarioPath<2>, TrajectoryError> {
        navy_planar::paper_path(t1).map(ScenarioPath::Poly9)
    }
    fn reference(model: &Self::Model, path: &ScenarioPath<2>, t: f64) -> Option<State<7, 3, 2>> {
        use navy_planar::reference::{PlanarParams, reference_at};
        let r = reference_at(
            &PlanarParams::from_values(&model.parameter_values())?,
            path,
            t,
        );
        finite_state(t, r.q, r.v, r.u, r.lambda)
    }
    fn simulate_minimal(
        model: &Self::Model,
        path: &ScenarioPath<2>,
        start: &State<7, 3, 2>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<7, 3, 2>, Error>> {
        let guess = navy_planar::minimal_guess(model, start);
        Some(crane_runtime::minimal::simulate_minimal_with_progress(
            model, path, start, &guess, options, progress,
        ))
    }
}

impl Crane<8, 4, 3> for PlanarPulley {
    type Model = navy_planar_pulley::NavyPlanarPulley;
    fn model() -> Self::Model {
        Self::Model::default()
    }
    fn defaults() -> PaperDefaults<3> {
        poly9_defaults(
            &navy_planar_pulley::paper_path(4.0).expect("paper path"),
            navy_planar_pulley::paper_p0().to_vec(),
        )
    }
    fn paper_path(t1: f64) -> Result<ScenarioPath<3>, TrajectoryError> {
        navy_planar_pulley::paper_path(t1).map(ScenarioPath::Poly9)
    }
    fn reference(model: &Self::Model, path: &ScenarioPath<3>, t: f64) -> Option<State<8, 4, 3>> {
        use navy_planar_pulley::reference::{PulleyParams, reference_at};
        let r = reference_at(
            &PulleyParams::from_values(&model.parameter_values())?,
            path,
            t,
        );
        finite_state(t, r.q, r.v, r.u, r.lambda)
    }
    fn simulate_minimal(
        model: &Self::Model,
        path: &ScenarioPath<3>,
        start: &State<8, 4, 3>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<8, 4, 3>, Error>> {
        let guess = navy_planar_pulley::minimal_guess(model, start);
        Some(crane_runtime::minimal::simulate_minimal_with_progress(
            model, path, start, &guess, options, progress,
        ))
    }
}

impl Crane<11, 4, 3> for Crane3d {
    fn derived_outputs() -> &'static [&'static str] {
        &["phi"]
    }
    fn derived(state: &State<11, 4, 3>) -> Vec<f64> {
        vec![navy_3d::slewing_angle(state)]
    }
    type Model = navy_3d::Navy3d;
    fn model() -> Self::Model {
        Self::Model::default()
    }
    fn defaults() -> PaperDefaults<3> {
        let path = navy_3d::paper_path(navy_3d::TF).expect("paper path");
        PaperDefaults {
            kind: Kind::ThreePhase,
            tau0: Some(navy_3d::TAU0),
            t0: 0.0,
            t1: navy_3d::TF,
            start: path.derivative(0.0, 0),
            end: path.derivative(navy_3d::TF, 0),
            p0: navy_3d::paper_p0().to_vec(),
        }
    }
    fn paper_path(t1: f64) -> Result<ScenarioPath<3>, TrajectoryError> {
        navy_3d::paper_path(t1).map(ScenarioPath::ThreePhase)
    }
    fn reference(model: &Self::Model, path: &ScenarioPath<3>, t: f64) -> Option<State<11, 4, 3>> {
        use navy_3d::reference::{Params3d, reference_at};
        let r = reference_at(&Params3d::from_values(&model.parameter_values())?, path, t)?;
        finite_state(t, r.q, r.v, r.u, r.lambda)
    }
    fn simulate_minimal(
        _: &Self::Model,
        _: &ScenarioPath<3>,
        _: &State<11, 4, 3>,
        _: &Options,
        _: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<11, 4, 3>, Error>> {
        None
    }
}

/// The 3D crane with pulley mass (sect. 6.2), on the paper's three-phase path.
pub struct Crane3dPulley;

impl Crane<12, 5, 4> for Crane3dPulley {
    fn derived_outputs() -> &'static [&'static str] {
        &["phi"]
    }
    fn derived(state: &State<12, 5, 4>) -> Vec<f64> {
        vec![navy_3d_pulley::slewing_angle(state)]
    }
    type Model = navy_3d_pulley::Navy3dPulley;
    fn model() -> Self::Model {
        Self::Model::default()
    }
    fn defaults() -> PaperDefaults<4> {
        let path = navy_3d_pulley::paper_path(navy_3d_pulley::TF).expect("paper path");
        PaperDefaults {
            kind: Kind::ThreePhase,
            tau0: Some(navy_3d_pulley::TAU0),
            t0: 0.0,
            t1: navy_3d_pulley::TF,
            start: path.derivative(0.0, 0),
            end: path.derivative(navy_3d_pulley::TF, 0),
            p0: navy_3d_pulley::paper_p0().to_vec(),
        }
    }
    fn paper_path(t1: f64) -> Result<ScenarioPath<4>, TrajectoryError> {
        navy_3d_pulley::paper_path(t1).map(ScenarioPath::ThreePhase)
    }
    fn reference(_: &Self::Model, _: &ScenarioPath<4>, _: f64) -> Option<State<12, 5, 4>> {
        None
    }
    fn simulate_minimal(
        _: &Self::Model,
        _: &ScenarioPath<4>,
        _: &State<12, 5, 4>,
        _: &Options,
        _: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<12, 5, 4>, Error>> {
        None
    }
}

/// A model on a scenario's path from a scenario's start: a [`crane_models::Case`].
pub struct ScenarioCase<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    pub model: C::Model,
    pub path: ScenarioPath<A>,
    pub p0: Vec<f64>,
    pub t0: f64,
    pub tf: f64,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> crane_models::Case<N, M, A>
    for ScenarioCase<C, N, M, A>
{
    type Model = C::Model;
    type Path = ScenarioPath<A>;

    fn model(&self) -> &C::Model {
        &self.model
    }
    fn path(&self) -> &ScenarioPath<A> {
        &self.path
    }
    fn t0(&self) -> f64 {
        self.t0
    }
    fn tf(&self) -> f64 {
        self.tf
    }
    fn start(&self) -> Result<State<N, M, A>, Error> {
        init::check_start(&self.model, &self.path, self.t0, &self.p0, None)
    }
    fn reference(&self, t: f64) -> Option<State<N, M, A>> {
        C::reference(&self.model, &self.path, t)
    }
    fn derived_outputs(&self) -> &'static [&'static str] {
        C::derived_outputs()
    }
    fn derived(&self, state: &State<N, M, A>) -> Vec<f64> {
        C::derived(state)
    }
    fn simulate_minimal_with_progress(
        &self,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        C::simulate_minimal(&self.model, &self.path, start, options, progress)
    }
}

/// Command-line values that override the file.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    pub dt: Option<f64>,
    pub tf: Option<f64>,
    pub formulation: Option<Formulation>,
    pub scheme: Option<Scheme>,
}

/// Everything a run needs besides the case.
pub struct Settings {
    pub dt: f64,
    pub formulation: Formulation,
    pub scheme: Scheme,
    /// `(input index, limit)` pairs.
    pub limits: Vec<(usize, f64)>,
}

/// Default time step when neither the file nor the command line gives one.
pub const DEFAULT_DT: f64 = 0.01;

fn vector<const K: usize>(
    key: &str,
    values: &[f64],
    model: &str,
    names: &[&str],
) -> Result<SVector<f64, K>, CliError> {
    if values.len() != K {
        return Err(invalid(format!(
            "`{key}` needs {K} numbers for {model} ({}), got {}",
            names.join(", "),
            values.len()
        )));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(invalid(format!(
            "`{key}`: entry {} ({}) is not finite",
            i + 1,
            names[i]
        )));
    }
    Ok(SVector::from_column_slice(values))
}

fn positive(key: &str, value: f64) -> Result<f64, CliError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(format!(
            "`{key}` must be a positive number of seconds, got {value}"
        )))
    }
}

/// Build the case and settings of `crane run MODEL` from a scenario (or none:
/// the paper's maneuver) and the command-line overrides.
pub fn build<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    name: &str,
    file: Option<&ScenarioFile>,
    overrides: &Overrides,
) -> Result<(ScenarioCase<C, N, M, A>, Settings), CliError> {
    let empty = ScenarioFile::default();
    let file = file.unwrap_or(&empty);
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    if let Some(model) = file.model.as_ref().filter(|m| *m != name) {
        return Err(invalid(format!(
            "`model` is \"{model}\" but the command runs {name}"
        )));
    }
    let defaults = C::defaults();
    let spec = file;
    let dt = positive("dt", overrides.dt.or(file.dt).unwrap_or(DEFAULT_DT))?;
    let formulation = overrides
        .formulation
        .or(file.formulation)
        .unwrap_or(Formulation::Redundant);
    let scheme = match (overrides.scheme, &file.scheme) {
        (Some(scheme), _) => scheme,
        (None, Some(name)) => name.parse().map_err(|e| invalid(format!("`scheme`: {e}")))?,
        (None, None) => Scheme::default(),
    };
    let t0 = spec.t0.unwrap_or(defaults.t0);
    if !t0.is_finite() {
        return Err(invalid(format!("`t0` must be finite, got {t0}")));
    }
    let tf_given = overrides.tf.or(file.tf);
    if spec.t1.is_some() && spec.duration.is_some() {
        return Err(invalid("`t1` and `duration` both given; give one"));
    }
    // end of the motion: t1, t0 + duration, else the run's tf, else the paper's
    let t1 = match (spec.t1, spec.duration) {
        (Some(t1), _) => t1,
        (None, Some(d)) => t0 + positive("duration", d)?,
        (None, None) => tf_given.unwrap_or(defaults.t1 - defaults.t0 + t0),
    };
    let tf = tf_given.unwrap_or(t1);
    if !(tf.is_finite() && tf > t0) {
        return Err(invalid(format!(
            "`tf` = {tf} s must be after the start time t0 = {t0} s"
        )));
    }
    if !(t1.is_finite() && t1 > t0) {
        return Err(invalid(format!(
            "`t1` = {t1} s must be after `t0` = {t0} s"
        )));
    }
    let loads = &info.coordinates[N - A..];
    let robot = &info.coordinates[..N - A];
    let kind = spec.trajectory.unwrap_or(defaults.kind);
    let only_times = spec.trajectory.is_none()
        && spec.tau0.is_none()
        && spec.start.is_none()
        && spec.end.is_none()
        && t0 == defaults.t0;
    let path = if only_times {
        C::paper_path(t1)
    } else {
        let start = match &spec.start {
            Some(v) => vector::<A>("start", v, name, loads)?,
            None => defaults.start,
        };
        let end = match &spec.end {
            Some(v) => vector::<A>("end", v, name, loads)?,
            None => defaults.end,
        };
        match kind {
            Kind::Poly9 => {
                if spec.tau0.is_some() {
                    return Err(invalid(
                        "`tau0` applies only to trajectory = \"three-phase\"",
                    ));
                }
                Poly9::new(t0, t1, start, end).map(ScenarioPath::Poly9)
            }
            Kind::ThreePhase | Kind::SmoothThreePhase => {
                let tau0 = spec.tau0.or(defaults.tau0).ok_or_else(|| {
                    invalid(
                        "`tau0` (ramp duration, s) is required for trajectory = \"three-phase\" and \"smooth-three-phase\"",
                    )
                })?;
                if kind == Kind::ThreePhase {
                    ThreePhase::new(t0, t1 - t0, tau0, start, end).map(ScenarioPath::ThreePhase)
                } else {
                    SmoothThreePhase::new(t0, t1 - t0, tau0, start, end).map(ScenarioPath::SmoothThreePhase)
                }
            }
        }
    }
    .map_err(|e| invalid(format!("load path: {e}")))?;
    let mut model = C::model();
    for (key, value) in &file.parameters {
        if !value.is_finite() {
            return Err(invalid(format!(
                "`parameters.{key}` must be finite, got {value}"
            )));
        }
        model
            .set_parameter(key, *value)
            .map_err(|e| invalid(format!("`parameters.{key}`: {e}")))?;
    }
    let p0 = match &file.p0 {
        Some(p0) => {
            if p0.len() != N - A {
                return Err(invalid(format!(
                    "`p0` needs {} numbers for {name} ({}), got {}",
                    N - A,
                    robot.join(", "),
                    p0.len()
                )));
            }
            p0.clone()
        }
        None => defaults.p0,
    };
    let mut limits = Vec::new();
    for (key, &limit) in &file.limits {
        let k = info.inputs.iter().position(|n| n == key).ok_or_else(|| {
            invalid(format!(
                "`limits.{key}`: {name} has no input `{key}`; its inputs are {}",
                info.inputs.join(", ")
            ))
        })?;
        if !(limit.is_finite() && limit > 0.0) {
            return Err(invalid(format!(
                "`limits.{key}` must be a positive number, got {limit}"
            )));
        }
        limits.push((k, limit));
    }
    let case = ScenarioCase {
        model,
        path,
        p0,
        t0,
        tf,
    };
    Ok((
        case,
        Settings {
            dt,
            formulation,
            scheme,
            limits,
        },
    ))
}
