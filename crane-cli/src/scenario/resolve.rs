//! A scenario file against a built-in crane: its default manoeuvre with the
//! file's keys and the command line's flags applied, giving the run's
//! [`Case`] and [`Settings`].

use crane_models::{Case, Crane, Path, PathSpec, Profile};
use crane_runtime::CraneModel;
use nalgebra::SVector;

use super::{DEFAULT_DT, Kind, Overrides, ScenarioError, ScenarioFile, Settings};

fn positive(key: &'static str, value: f64) -> Result<f64, ScenarioError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ScenarioError::NotPositiveTime { key, value })
    }
}

fn vector<const K: usize>(
    key: &'static str,
    values: &[f64],
    model: &str,
    names: &[&str],
) -> Result<SVector<f64, K>, ScenarioError> {
    if values.len() != K {
        return Err(ScenarioError::WrongCount {
            key,
            expected: K,
            model: model.into(),
            names: names.join(", "),
            found: values.len(),
        });
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(ScenarioError::EntryNotFinite {
            key,
            index: i + 1,
            name: names[i].to_string(),
        });
    }
    Ok(SVector::from_column_slice(values))
}

/// The load path: the default's profile, times and points, with the file's
/// `trajectory`, `tau0`, `start`, `end`, `t0`, `t1` / `duration` applied;
/// without `t1` or `duration` the motion ends at `tf_given` if the command
/// gives one, else as long after `t0` as the default's.
fn path_of<const A: usize>(
    default: &PathSpec<A>,
    file: &ScenarioFile,
    tf_given: Option<f64>,
    name: &str,
    loads: &[&str],
) -> Result<PathSpec<A>, ScenarioError> {
    let t0 = file.t0.unwrap_or(default.t0);
    if !t0.is_finite() {
        return Err(ScenarioError::NotFinite {
            key: "t0".into(),
            value: t0,
        });
    }
    if let Some(tf) = tf_given.filter(|tf| !(tf.is_finite() && *tf > t0)) {
        return Err(ScenarioError::EndBeforeStart { tf, t0 });
    }
    let t1 = match (file.t1, file.duration) {
        (Some(_), Some(_)) => return Err(ScenarioError::EndTwice),
        (Some(t1), None) => t1,
        (None, Some(d)) => t0 + positive("duration", d)?,
        (None, None) => tf_given.unwrap_or(default.t1 - default.t0 + t0),
    };
    if !(t1.is_finite() && t1 > t0) {
        return Err(ScenarioError::MotionEndsBeforeStart { t1, t0 });
    }
    let default_tau0 = match default.profile {
        Profile::Poly9 => None,
        Profile::ThreePhase { tau0 } | Profile::SmoothThreePhase { tau0 } => Some(tau0),
    };
    let kind = file.trajectory.unwrap_or(match default.profile {
        Profile::Poly9 => Kind::Poly9,
        Profile::ThreePhase { .. } => Kind::ThreePhase,
        Profile::SmoothThreePhase { .. } => Kind::SmoothThreePhase,
    });
    let profile = match kind {
        Kind::Poly9 if file.tau0.is_some() => return Err(ScenarioError::RampWithoutPhases),
        Kind::Poly9 => Profile::Poly9,
        Kind::ThreePhase | Kind::SmoothThreePhase => {
            let tau0 = file.tau0.or(default_tau0).ok_or(ScenarioError::RampMissing)?;
            if kind == Kind::ThreePhase {
                Profile::ThreePhase { tau0 }
            } else {
                Profile::SmoothThreePhase { tau0 }
            }
        }
    };
    let start = match &file.start {
        Some(v) => vector::<A>("start", v, name, loads)?,
        None => default.start,
    };
    let end = match &file.end {
        Some(v) => vector::<A>("end", v, name, loads)?,
        None => default.end,
    };
    Ok(PathSpec {
        profile,
        t0,
        t1,
        start,
        end,
    })
}

/// Build the case and settings of `crane run MODEL` from a scenario (or none:
/// the default manoeuvre) and the command-line overrides.
pub fn build<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    file: Option<&ScenarioFile>,
    overrides: &Overrides,
) -> Result<(Case<C, N, M, A>, Settings), ScenarioError> {
    let empty = ScenarioFile::default();
    let file = file.unwrap_or(&empty);
    let name = C::NAME;
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    if let Some(model) = file.model.as_ref().filter(|m| *m != name) {
        return Err(ScenarioError::WrongModel {
            given: model.clone(),
            running: name.into(),
        });
    }
    let default = C::maneuver();
    let dt = positive("dt", overrides.dt.or(file.dt).unwrap_or(DEFAULT_DT))?;
    let formulation = overrides
        .formulation
        .or(file.formulation)
        .unwrap_or(crate::Formulation::Redundant);
    let scheme = match (overrides.scheme, &file.scheme) {
        (Some(scheme), _) => scheme,
        (None, Some(name)) => name.parse().map_err(ScenarioError::Scheme)?,
        (None, None) => Default::default(),
    };
    let tf_given = overrides.tf.or(file.tf);
    let spec = path_of(&default.path, file, tf_given, name, &info.coordinates[N - A..])?;
    let tf = tf_given.unwrap_or(spec.t1);
    if !(tf.is_finite() && tf > spec.t0) {
        return Err(ScenarioError::EndBeforeStart { tf, t0: spec.t0 });
    }
    let path = Path::new(spec).map_err(ScenarioError::Path)?;
    let mut model = C::Model::default();
    for (key, value) in &file.parameters {
        if !value.is_finite() {
            return Err(ScenarioError::NotFinite {
                key: format!("parameters.{key}"),
                value: *value,
            });
        }
        model
            .set_parameter(key, *value)
            .map_err(|source| ScenarioError::Parameter {
                key: key.clone(),
                source,
            })?;
    }
    // masses, inertias and lengths declared positive, and a positive
    // semi-definite mass matrix, with the file's values
    crane_runtime::driver::check_parameters(&model).map_err(|e| match e {
        crane_runtime::Error::NonPositiveParameter { name, value } => ScenarioError::NotPositiveParameter {
            key: name.to_string(),
            value,
        },
        other => ScenarioError::Physical(other),
    })?;
    let robot = &info.coordinates[..N - A];
    let p0 = match &file.p0 {
        Some(p0) if p0.len() != N - A => {
            return Err(ScenarioError::WrongCount {
                key: "p0",
                expected: N - A,
                model: name.into(),
                names: robot.join(", "),
                found: p0.len(),
            });
        }
        Some(p0) => p0.clone(),
        None => default.p0,
    };
    let mut limits = Vec::new();
    for (key, &limit) in &file.limits {
        let k = info
            .inputs
            .iter()
            .position(|n| n == key)
            .ok_or_else(|| ScenarioError::UnknownInput {
                key: key.clone(),
                model: name.into(),
                inputs: info.inputs.join(", "),
            })?;
        if !(limit.is_finite() && limit > 0.0) {
            return Err(ScenarioError::LimitNotPositive {
                key: key.clone(),
                value: limit,
            });
        }
        limits.push((k, limit));
    }
    let plant = file.plant.iter().map(|(k, v)| (k.clone(), *v)).collect();
    Ok((
        Case::from_parts(model, path, p0, tf),
        Settings {
            dt,
            formulation,
            scheme,
            limits,
            plant,
        },
    ))
}
