//! A scenario file against a built-in crane: its default manoeuvre with the
//! file's keys and the command line's flags applied, as a [`RunSpec`]
//! (checked by [`RunSpec::build`], whose errors are named here by the keys
//! they come from), giving the run's [`Case`] and [`RunSettings`].

use crane_models::path::{Profile, SplineShape};
use crane_models::study::{RunSettings, RunSpec, SpecError};
use crane_models::{Case, Crane, PathSpec, ProfileKind};
use crane_runtime::{CraneModel, Trajectory};
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

/// The spline keys of a scenario file with their values' presence, in the
/// order messages name them.
fn spline_keys(file: &ScenarioFile) -> [(&'static str, bool); 5] {
    [
        ("waypoints", file.waypoints.is_some()),
        ("times", file.times.is_some()),
        ("knots", file.knots.is_some()),
        ("control", file.control.is_some()),
        ("degree", file.degree.is_some()),
    ]
}

/// The profile kind a file asks for: its `trajectory`, else a spline if it
/// gives a spline's points, else the default's.
fn kind_of(default: ProfileKind, file: &ScenarioFile) -> ProfileKind {
    let points = file.waypoints.is_some() || file.knots.is_some() || file.control.is_some();
    file.trajectory
        .unwrap_or(if points { ProfileKind::Spline } else { default })
}

/// The start of the motion a file asks for: the first waypoint's time of a
/// spline through waypoints, else `t0`, else the default's.
fn start_time(default_t0: f64, file: &ScenarioFile) -> f64 {
    match (&file.waypoints, &file.times) {
        (Some(_), Some(times)) if !times.is_empty() => times[0],
        _ => file.t0.unwrap_or(default_t0),
    }
}

/// The points of `key` (`waypoints`, `control`): each `A` finite numbers.
fn points<const A: usize>(
    key: &'static str,
    rows: &[Vec<f64>],
    model: &str,
    names: &[&str],
) -> Result<Vec<SVector<f64, A>>, ScenarioError> {
    let what = if key == "waypoints" {
        "waypoint"
    } else {
        "control point"
    };
    rows.iter()
        .enumerate()
        .map(|(i, row)| {
            if row.len() != A {
                return Err(ScenarioError::Spline {
                    key,
                    reason: format!(
                        "{what} {} needs {A} numbers for {model} ({}), got {}",
                        i + 1,
                        names.join(", "),
                        row.len()
                    ),
                });
            }
            match row.iter().position(|v| !v.is_finite()) {
                Some(k) => Err(ScenarioError::Spline {
                    key,
                    reason: format!("{what} {}: entry {} ({}) is not finite", i + 1, k + 1, names[k]),
                }),
                None => Ok(SVector::from_column_slice(row)),
            }
        })
        .collect()
}

/// What a crane of path order `order` needs of a spline, for messages.
fn needs(model: &str, order: usize) -> String {
    format!(
        "{model}'s inputs depend on the path's derivatives up to order {order}, so they are continuous only on a \
         path at rest to that order at both ends: degree {} or more through waypoints",
        2 * order + 1
    )
}

/// A spline move (`trajectory = "spline"`): through `waypoints` at `times`
/// (s), of degree `degree` (odd: at rest to order `(degree - 1) / 2` at both
/// ends; by default `2 p + 1` for the crane's path order `p`), or on
/// `knots` (normalised time, 0 to 1) and `control` points from `t0` to `t1`
/// (or `duration`; as for a straight move without them). Either way the
/// crane's inputs must come out continuous: a spline that is not continuous
/// to the path order at its ends and knots is refused.
fn spline_of<const A: usize>(
    times: (f64, f64),
    file: &ScenarioFile,
    name: &str,
    loads: &[&str],
    path_order: Option<usize>,
) -> Result<PathSpec<A>, ScenarioError> {
    if file.tau0.is_some() {
        return Err(ScenarioError::RampWithoutPhases);
    }
    let refuse = |key: &'static str, why: &str| {
        Err(ScenarioError::Spline {
            key,
            reason: why.to_string(),
        })
    };
    for (key, given) in [("start", file.start.is_some()), ("end", file.end.is_some())] {
        if given {
            return refuse(
                key,
                "a spline starts at its first point and ends at its last (`waypoints` or `control`)",
            );
        }
    }
    let shape = match (&file.waypoints, &file.control) {
        (Some(_), Some(_)) => {
            return refuse(
                "control",
                "a spline is given by `waypoints` (with `times`) or by `knots` and `control`, not both",
            );
        }
        (None, None) => {
            return refuse(
                "waypoints",
                "trajectory = \"spline\" needs `waypoints` with their `times` (s), or `knots` and `control` points",
            );
        }
        (Some(waypoints), None) => {
            for (key, given) in [
                ("t0", file.t0.is_some()),
                ("t1", file.t1.is_some()),
                ("duration", file.duration.is_some()),
                ("knots", file.knots.is_some()),
            ] {
                if given {
                    return refuse(key, "a spline through waypoints takes its times from `times`");
                }
            }
            let Some(times) = &file.times else {
                return refuse("times", "the waypoints' times (s) are required, one per waypoint");
            };
            let waypoints = points::<A>("waypoints", waypoints, name, loads)?;
            if times.len() != waypoints.len() || times.len() < 2 {
                return refuse(
                    "times",
                    &format!(
                        "a spline through waypoints needs at least two, each with its time; got {} waypoints and {} times",
                        waypoints.len(),
                        times.len()
                    ),
                );
            }
            if let Some(k) = times
                .windows(2)
                .position(|w| !(w[1] > w[0] && w[0].is_finite() && w[1].is_finite()))
            {
                return refuse(
                    "times",
                    &format!(
                        "the waypoints' times must be finite and increasing: {} then {}",
                        short_number(times[k]),
                        short_number(times[k + 1])
                    ),
                );
            }
            let degree = match (file.degree, path_order) {
                (Some(degree), _) => degree,
                (None, Some(order)) => 2 * order + 1,
                (None, None) => {
                    return refuse(
                        "degree",
                        "give the spline's degree: the model declares no structure to choose it from",
                    );
                }
            };
            if degree % 2 == 0 {
                return refuse(
                    "degree",
                    &format!(
                        "a spline through waypoints has an odd degree 2 r + 1 (at rest to order r at both ends), got {degree}"
                    ),
                );
            }
            let rest = degree / 2;
            if let Some(order) = path_order.filter(|&order| rest < order) {
                return refuse("degree", &format!("degree {degree} is too low: {}", needs(name, order)));
            }
            let (t0, t1) = (times[0], times[times.len() - 1]);
            let mut normalised: Vec<f64> = times.iter().map(|t| (t - t0) / (t1 - t0)).collect();
            let last = normalised.len() - 1;
            (normalised[0], normalised[last]) = (0.0, 1.0);
            SplineShape::through(&normalised, &waypoints, rest)
                .map_err(|e| ScenarioError::Spline {
                    key: "waypoints",
                    reason: e.to_string(),
                })
                .map(|shape| (shape, t0, t1))?
        }
        (None, Some(control)) => {
            if file.times.is_some() {
                return refuse(
                    "times",
                    "`times` go with `waypoints`; `knots` are in the move's normalised time",
                );
            }
            let Some(knots) = &file.knots else {
                return refuse(
                    "knots",
                    "the control points' knots (in the move's normalised time, 0 to 1) are required",
                );
            };
            let control = points::<A>("control", control, name, loads)?;
            let Some(degree) = knots.len().checked_sub(control.len() + 1).filter(|&d| d > 0) else {
                return refuse(
                    "knots",
                    &format!(
                        "a spline of n control points and degree p has n + p + 1 knots: {} knots for {} points",
                        knots.len(),
                        control.len()
                    ),
                );
            };
            if let Some(given) = file.degree.filter(|&given| given != degree) {
                return refuse(
                    "degree",
                    &format!(
                        "{} knots and {} control points make degree {degree}, not {given}",
                        knots.len(),
                        control.len()
                    ),
                );
            }
            let (t0, t1) = times;
            SplineShape::new(degree, knots.clone(), &control)
                .map_err(|e| ScenarioError::Spline {
                    key: "knots",
                    reason: e.to_string(),
                })
                .map(|shape| (shape, t0, t1))?
        }
    };
    let (shape, t0, t1) = shape;
    let (start, end) = shape.ends();
    let spec = PathSpec {
        start: SVector::from_column_slice(start),
        end: SVector::from_column_slice(end),
        profile: Profile::Spline(std::sync::Arc::new(shape)),
        t0,
        t1,
    };
    let path = crane_models::path::Path::new(spec.clone()).map_err(ScenarioError::Path)?;
    if let (Some(order), Some(continuity)) = (path_order, path.continuity())
        && continuity < order
    {
        let key = if file.waypoints.is_some() { "degree" } else { "control" };
        return refuse(
            key,
            &format!(
                "the spline is continuous (and at rest at its ends) only to order {continuity}: {}",
                needs(name, order)
            ),
        );
    }
    Ok(spec)
}

/// The load path: the default's profile, times and points, with the file's
/// `trajectory`, `tau0`, `start`, `end`, `t0`, `t1` / `duration` applied;
/// without `t1` or `duration` the motion ends at `tf_given` if the command
/// gives one, else as long after `t0` as the default's. A spline's keys
/// make a spline move ([`spline_of`]).
fn path_of<const A: usize>(
    default: &PathSpec<A>,
    file: &ScenarioFile,
    tf_given: Option<f64>,
    name: &str,
    loads: &[&str],
    path_order: Option<usize>,
) -> Result<PathSpec<A>, ScenarioError> {
    let kind = kind_of(default.profile.kind(), file);
    if kind == ProfileKind::Spline && file.waypoints.is_some() {
        return spline_of((0.0, 0.0), file, name, loads, path_order);
    }
    if kind != ProfileKind::Spline
        && let Some((key, _)) = spline_keys(file).into_iter().find(|(_, given)| *given)
    {
        return Err(ScenarioError::Spline {
            key,
            reason: format!("applies only to trajectory = \"spline\", not \"{kind}\""),
        });
    }
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
    if kind == ProfileKind::Spline {
        return spline_of((t0, t1), file, name, loads, path_order);
    }
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
    check_flags(overrides, start_time(default.path.t0, file))?;
    let tf_given = overrides.tf.or(file.tf);
    let path_order = <C::Model as CraneModel<N, M, A>>::STRUCTURE.map(|s| s.path_order(A));
    let path = path_of(
        &default.path,
        file,
        tf_given,
        name,
        &info.coordinates[N - A..],
        path_order,
    )?;
    Ok(RunSpec {
        parameters: file.parameters.iter().map(|(k, v)| (k.clone(), *v)).collect(),
        tf: tf_given.unwrap_or(path.t1),
        path,
        p0: file.p0.clone().unwrap_or(default.p0),
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

/// The run of a scenario (or none: the default manoeuvre) with the
/// command-line overrides, checked as [`build`] checks it.
pub fn checked_spec<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    file: Option<&ScenarioFile>,
    overrides: &Overrides,
) -> Result<RunSpec<A>, ScenarioError> {
    let spec = spec::<C, N, M, A>(file, overrides)?;
    spec.build::<C, N, M>().map_err(|error| by_key::<C, N, M, A>(error))?;
    Ok(spec)
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
