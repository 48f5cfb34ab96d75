//! A scenario file against a built-in crane: its default manoeuvre with the
//! file's keys and the command line's flags applied, as a [`RunSpec`]
//! (checked by [`RunSpec::build`], whose errors are named here by the keys
//! they come from), giving the run's [`Case`] and [`RunSettings`].

use crane_models::study::{RunSettings, RunSpec, SpecError};
use crane_models::{Case, Crane, PathSpec, ProfileKind};
use crane_runtime::CraneModel;
use nalgebra::SVector;

use super::{Overrides, ScenarioError, ScenarioFile};

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
    if let Some(tf) = tf_given.filter(|tf| !tf.is_finite()) {
        return Err(ScenarioError::NotFinite {
            key: "tf".into(),
            value: tf,
        });
    }
    if let Some(tf) = tf_given.filter(|tf| !(*tf > t0)) {
        return Err(ScenarioError::EndBeforeStart { tf, t0 });
    }
    let t1 = match (file.t1, file.duration) {
        (Some(_), Some(_)) => return Err(ScenarioError::EndTwice),
        (Some(t1), None) => t1,
        (None, Some(d)) => t0 + positive("duration", d)?,
        (None, None) => tf_given.unwrap_or(default.t1 - default.t0 + t0),
    };
    if !t1.is_finite() {
        let key = if file.t1.is_some() { "t1" } else { "duration" };
        return Err(ScenarioError::NotFinite {
            key: key.into(),
            value: t1,
        });
    }
    if !(t1 > t0) {
        return Err(ScenarioError::MotionEndsBeforeStart { t1, t0 });
    }
    let kind = file.trajectory.unwrap_or(default.profile.kind());
    if kind == ProfileKind::Poly9 && file.tau0.is_some() {
        return Err(ScenarioError::RampWithoutPhases);
    }
    let profile = kind
        .profile(file.tau0.or(default.profile.tau0()))
        .map_err(|_| ScenarioError::RampMissing)?;
    // the default's ramps on a shorter move than the default's
    if let Some(tau0) = profile
        .tau0()
        .filter(|&tau0| file.tau0.is_none() && !(tau0 <= 0.5 * (t1 - t0)))
    {
        return Err(ScenarioError::DefaultRampTooLong {
            tau0,
            duration: t1 - t0,
        });
    }
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

/// The run of `crane run MODEL` as data: crane `C`'s default manoeuvre with
/// the scenario's keys (or none) and the command-line overrides applied.
fn spec<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    file: Option<&ScenarioFile>,
    overrides: &Overrides,
) -> Result<RunSpec<A>, ScenarioError> {
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
    let default = RunSpec::default_for::<C, N, M>();
    let scheme = match (overrides.scheme, &file.scheme) {
        (Some(scheme), _) => scheme,
        (None, Some(name)) => name.parse().map_err(ScenarioError::Scheme)?,
        (None, None) => default.scheme,
    };
    check_flags(overrides, file.t0.unwrap_or(default.path.t0))?;
    let tf_given = overrides.tf.or(file.tf);
    let path = path_of(&default.path, file, tf_given, name, &info.coordinates[N - A..])?;
    Ok(RunSpec {
        parameters: file.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect(),
        path,
        p0: file.p0.clone().unwrap_or(default.p0),
        tf: tf_given.unwrap_or(path.t1),
        dt: overrides.dt.or(file.dt).unwrap_or(default.dt),
        scheme,
        formulation: overrides
            .formulation
            .or(file.formulation)
            .unwrap_or(default.formulation),
        limits: file.limits.iter().map(|(k, v)| (k.clone(), *v)).collect(),
        plant: file.plant.iter().map(|(k, v)| (k.clone(), *v)).collect(),
    })
}

/// A number as short as it reads back: `-4`, `-0.01`, `1e-300` (where
/// `{}` would print 300 zeros).
pub(super) fn short_number(value: f64) -> String {
    if value.is_finite() && value == value.trunc() && value.abs() < 1e15 {
        format!("{value}")
    } else {
        format!("{value:?}")
    }
}

/// The time flags are checked as flags (`--dt -0.01` is the flag's
/// mistake, not the scenario key `dt`'s): a step of at least the smallest
/// one, an end time that is a finite time after the start.
fn check_flags(overrides: &Overrides, t0: f64) -> Result<(), ScenarioError> {
    if let Some(dt) = overrides.dt
        && crane_runtime::Options::stepping(dt).is_err()
    {
        return Err(ScenarioError::Flag {
            flag: "--dt",
            value: short_number(dt),
            need: format!(
                "the time step must be at least {:e} s and finite",
                crane_runtime::options::MIN_DT
            ),
        });
    }
    if let Some(tf) = overrides.tf
        && !(tf.is_finite() && tf > t0)
    {
        return Err(ScenarioError::Flag {
            flag: "--tf",
            value: short_number(tf),
            need: format!("the end time must be finite and after the start time t0 = {t0} s"),
        });
    }
    Ok(())
}

/// Build the case and settings of `crane run MODEL` from a scenario (or none:
/// the default manoeuvre) and the command-line overrides; every error names
/// the scenario key it is about.
pub fn build<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    file: Option<&ScenarioFile>,
    overrides: &Overrides,
) -> Result<(Case<C, N, M, A>, RunSettings), ScenarioError> {
    let spec = spec::<C, N, M, A>(file, overrides)?;
    spec.build::<C, N, M>().map_err(|error| by_key::<C, N, M, A>(error))
}

/// A [`SpecError`] as the scenario error of the key it comes from.
fn by_key<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(error: SpecError) -> ScenarioError {
    let model = C::NAME.to_string();
    match error {
        SpecError::UnknownParameter { name, source } => ScenarioError::Parameter { key: name, source },
        SpecError::Parameters(crane_runtime::Error::NonFiniteParameter { name, value }) => ScenarioError::NotFinite {
            key: format!("parameters.{name}"),
            value,
        },
        SpecError::Parameters(crane_runtime::Error::NonPositiveParameter { name, value }) => {
            ScenarioError::NotPositiveParameter {
                key: name.to_string(),
                value,
            }
        }
        SpecError::Parameters(e) => ScenarioError::Physical(e),
        SpecError::Path(e) => ScenarioError::Path(e),
        SpecError::WrongStartLength { expected, names, found } => ScenarioError::WrongCount {
            key: "p0",
            expected,
            model,
            names,
            found,
        },
        SpecError::EndBeforeStart { tf, t0 } => ScenarioError::EndBeforeStart { tf, t0 },
        SpecError::Time(crane_runtime::Error::InvalidTimeStep { dt }) if dt > 0.0 && dt.is_finite() => {
            ScenarioError::StepTooSmall(dt)
        }
        SpecError::Time(crane_runtime::Error::InvalidTimeStep { dt }) => {
            ScenarioError::NotPositiveTime { key: "dt", value: dt }
        }
        SpecError::Time(e) => ScenarioError::Time(e),
        SpecError::UnknownInput { name, inputs } => ScenarioError::UnknownInput {
            key: name,
            model,
            inputs,
        },
        SpecError::LimitNotPositive { name, value } => ScenarioError::LimitNotPositive { key: name, value },
    }
}
