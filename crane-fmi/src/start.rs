//! The run an FMU starts from: its crane's default move, parameters, step
//! and scheme, or those of a scenario it was packaged with
//! (`crane fmu MODEL --scenario FILE`). A packaged run travels in the
//! archive as [`RESOURCE`] under `resources/`, and the binary reads it
//! back at `fmi2Instantiate` from the location the host gives: the start
//! values in `modelDescription.xml` and the spline of a spline move
//! (which no scalar variable can hold) come from it.

use std::collections::BTreeMap;
use std::sync::Arc;

use crane_models::path::SplineShape;
use crane_models::study::{Formulation, RunSpec};
use crane_models::{Crane, PathSpec, Profile, ProfileKind};
use crane_runtime::{CraneModel, Scheme};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// The packaged run's file, in the archive's `resources/` folder.
pub const RESOURCE: &str = "start.toml";

/// The largest packaged run read, in bytes (a spline of a few thousand
/// control points).
pub const MAX_RESOURCE_BYTES: u64 = 1 << 20;

/// Why a run cannot be an FMU's start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StartError {
    /// The file is not a packaged run.
    #[error("resources/{RESOURCE} is not a packaged run: {0}")]
    Format(String),
    /// It was packaged for another crane.
    #[error("resources/{RESOURCE} was packaged for {found}, not {expected}")]
    WrongModel {
        /// The crane of this entry.
        expected: &'static str,
        /// The crane named in the file.
        found: String,
    },
    /// The run does not build for the crane.
    #[error("resources/{RESOURCE}: {0}")]
    Run(String),
}

/// The run an FMU starts from, and the text it travels as when it is not
/// the crane's default.
#[derive(Debug, Clone, PartialEq)]
pub struct Start<const A: usize> {
    /// Parameters, move, step, scheme, formulation, start guess and end.
    pub spec: RunSpec<A>,
    /// The text of [`RESOURCE`], for a packaged run.
    pub resource: Option<String>,
}

/// A run as [`RESOURCE`] holds it (names where the run has enums).
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct StartFile {
    model: String,
    dt: f64,
    tf: f64,
    scheme: String,
    formulation: String,
    p0: Vec<f64>,
    trajectory: String,
    t0: f64,
    t1: f64,
    start: Vec<f64>,
    end: Vec<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tau0: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    degree: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    knots: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    control: Option<Vec<Vec<f64>>>,
    parameters: BTreeMap<String, f64>,
}

impl<const A: usize> Start<A> {
    /// Crane `C`'s default run (what `crane run MODEL` does).
    pub fn default_for<C: Crane<N, M, A>, const N: usize, const M: usize>() -> Self {
        Self {
            spec: RunSpec::default_for::<C, N, M>(),
            resource: None,
        }
    }

    /// A packaged run of crane `C`, checked as `crane run` checks it (the
    /// parameters, the path, a whole number of steps to its end, the start
    /// `p0`); its limits and replay plant play no part in an FMU and are
    /// dropped.
    pub fn packaged<C: Crane<N, M, A>, const N: usize, const M: usize>(spec: &RunSpec<A>) -> Result<Self, StartError> {
        let mut spec = spec.clone();
        spec.limits.clear();
        spec.plant.clear();
        let (case, settings) = spec.build::<C, N, M>().map_err(|e| StartError::Run(e.to_string()))?;
        // as `crane run` checks the run: a whole number of steps to its end
        // (the default experiment's last step is one), and a start that
        // is the scenario's `p0` where it gives one
        crane_runtime::options::step_count(case.t0(), case.tf(), settings.dt)
            .map_err(|e| StartError::Run(e.to_string()))?;
        case.run_start().map_err(|e| {
            StartError::Run(format!(
                "no start: {e}; give a `p0` that meets every constraint with the load at the path's start, or \
                 leave `p0` out to start from the static equilibrium"
            ))
        })?;
        case.check_workspace().map_err(|e| StartError::Run(e.to_string()))?;
        let path = &spec.path;
        let shape = match &path.profile {
            Profile::Spline(shape) => Some(shape),
            _ => None,
        };
        let file = StartFile {
            model: C::NAME.to_string(),
            dt: spec.dt,
            tf: spec.tf,
            scheme: spec.scheme.name().to_string(),
            formulation: spec.formulation.name().to_string(),
            p0: spec.p0.clone(),
            trajectory: path.profile.kind().name().to_string(),
            t0: path.t0,
            t1: path.t1,
            start: path.start.iter().copied().collect(),
            end: path.end.iter().copied().collect(),
            tau0: path.profile.tau0(),
            degree: shape.map(|s| s.degree()),
            knots: shape.map(|s| s.knots().to_vec()),
            control: shape.map(|s| s.control().to_vec()),
            parameters: spec.parameters.iter().cloned().collect(),
        };
        let text = toml::to_string(&file).map_err(|e| StartError::Format(e.to_string()))?;
        // the text is what the binary reads: the run it gives is the one
        // packaged (numbers round-trip exactly)
        let read = Self::read::<C, N, M>(&text)?;
        Ok(Self {
            spec: read.spec,
            resource: Some(text),
        })
    }

    /// The packaged run of crane `C` in `text` (the contents of
    /// [`RESOURCE`]), checked.
    pub fn read<C: Crane<N, M, A>, const N: usize, const M: usize>(text: &str) -> Result<Self, StartError> {
        let file: StartFile = toml::from_str(text).map_err(|e| StartError::Format(e.message().to_string()))?;
        if file.model != C::NAME {
            return Err(StartError::WrongModel {
                expected: C::NAME,
                found: file.model,
            });
        }
        let format = |what: String| StartError::Format(what);
        let point = |key: &str, values: &[f64]| -> Result<SVector<f64, A>, StartError> {
            if values.len() != A {
                return Err(format(format!("`{key}` has {} numbers, not {A}", values.len())));
            }
            Ok(SVector::from_column_slice(values))
        };
        let kind: ProfileKind = file.trajectory.parse().map_err(|e| format(format!("{e}")))?;
        let profile = match kind {
            ProfileKind::Spline => {
                let (Some(degree), Some(knots), Some(control)) = (file.degree, file.knots, file.control) else {
                    return Err(format("a spline move needs `degree`, `knots` and `control`".into()));
                };
                let control = control
                    .iter()
                    .map(|p| point("control", p))
                    .collect::<Result<Vec<_>, _>>()?;
                let shape = SplineShape::new(degree, knots, &control).map_err(|e| format(e.to_string()))?;
                Profile::Spline(Arc::new(shape))
            }
            kind => kind.profile(file.tau0).map_err(|e| format(e.to_string()))?,
        };
        let spec = RunSpec {
            parameters: file.parameters.into_iter().collect(),
            path: PathSpec {
                profile,
                t0: file.t0,
                t1: file.t1,
                start: point("start", &file.start)?,
                end: point("end", &file.end)?,
            },
            p0: file.p0,
            tf: file.tf,
            dt: file.dt,
            scheme: file.scheme.parse::<Scheme>().map_err(|e| format(e.to_string()))?,
            formulation: file
                .formulation
                .parse::<Formulation>()
                .map_err(|e| format(e.to_string()))?,
            limits: Vec::new(),
            plant: Vec::new(),
        };
        spec.build::<C, N, M>().map_err(|e| StartError::Run(e.to_string()))?;
        Ok(Self {
            spec,
            resource: Some(text.to_string()),
        })
    }

    /// Every parameter's start value, in the model's order: its default,
    /// or the packaged run's.
    pub fn parameter_values<C: Crane<N, M, A>, const N: usize, const M: usize>(&self) -> Vec<f64> {
        let info = <C::Model as CraneModel<N, M, A>>::INFO;
        let mut values = C::Model::default().parameter_values();
        for (name, value) in &self.spec.parameters {
            if let Some(k) = info.parameters.iter().position(|p| p == name) {
                values[k] = *value;
            }
        }
        values
    }
}
