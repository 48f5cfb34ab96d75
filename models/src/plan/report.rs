//! What planning reports, in one place for every front end: the answer of
//! [`fastest`](super::fastest) as a [`Report`] (the command line's
//! fastest.json, the dict Python's `fastest` returns), and a
//! [`sweep`](super::sweep) as named [`Column`]s (sweep.csv's columns, the
//! arrays of Python's `sweep`), with the one check of a sweep's grid
//! ([`check_grid`]).

use serde::Serialize;

use crane_runtime::CraneModel;

use super::{Binding, Fastest, IntervalCheck, MAX_SWEEP_POINTS, PlanError, Settings, Shaped, SweepPoint};
use crate::crane::{Crane, LowerBound};
use crate::study::Formulation;

/// A limit and how the answer meets it, as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LimitReport {
    /// `u2`, `N1`, ... as the model declares it.
    pub name: String,
    /// `"limit"` (a torque limit) or `"min-tension"` (a tension floor).
    pub kind: &'static str,
    /// The limit or the floor.
    pub limit: f64,
    /// The peak `|u|` or the minimum tension.
    pub value: f64,
    /// When it occurs, s.
    pub at: f64,
}

impl From<&Binding> for LimitReport {
    fn from(b: &Binding) -> Self {
        Self {
            name: b.name.clone(),
            kind: if b.tension { "min-tension" } else { "limit" },
            limit: b.limit,
            value: b.value,
            at: b.at,
        }
    }
}

/// The answer of [`fastest`](super::fastest) with how it was found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The crane.
    pub model: &'static str,
    /// The shortest feasible duration, s.
    pub duration: f64,
    /// The limit that binds.
    pub binding: LimitReport,
    /// Every limit at the answer.
    pub limits: Vec<LimitReport>,
    /// How the answer's path was shaped, and how close it is to the
    /// crane's lower bound.
    pub shape: ShapeReport,
    /// The final bracket `[infeasible, feasible]` of the time scaling's
    /// bisection, s (`None` for an optimised shape).
    pub bracket: Option<[f64; 2]>,
    /// Inverse runs of the search.
    pub evaluations: usize,
    /// The check that feasible durations form an interval (`None` for an
    /// optimised shape).
    pub interval: Option<IntervalCheck>,
    /// The formulation of every evaluation.
    pub formulation: &'static str,
    /// The scheme (a reduced run discretises nothing and ignores it).
    pub scheme: &'static str,
    /// The largest time step, s.
    pub dt: f64,
    /// The bisection's tolerance, s.
    pub tolerance: f64,
    /// Wall time of the search, s.
    pub wall_s: f64,
}

/// How the answer's path was shaped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapeReport {
    /// `"time-scaled"` (the case's own path shape, scaled in time) or
    /// `"optimal"` (the shape optimised, [`fastest_shape`](super::fastest_shape)).
    pub kind: &'static str,
    /// The profile of the answer's path (`poly9`, ..., `spline`).
    pub profile: &'static str,
    /// The time-scaled optimum of the case's own path, s (for an optimised
    /// shape, what it improves on).
    pub time_scaled: Option<f64>,
    /// The free control points per load coordinate of an optimised shape.
    pub control_points: Option<usize>,
    /// Iterations of the shape's optimisation.
    pub iterations: Option<usize>,
    /// The crane's lower bound on any move's duration, where it has one.
    pub lower_bound: Option<LowerBound>,
    /// How far above it the answer is, relative: `duration / bound - 1`.
    pub gap: Option<f64>,
}

impl ShapeReport {
    /// The report of a time-scaled answer of `duration` on `profile`.
    fn time_scaled(profile: &'static str, duration: f64, lower_bound: Option<LowerBound>) -> Self {
        Self {
            kind: "time-scaled",
            profile,
            time_scaled: None,
            control_points: None,
            iterations: None,
            gap: lower_bound.as_ref().map(|b| duration / b.duration - 1.0),
            lower_bound,
        }
    }
}

impl<const N: usize, const M: usize, const A: usize> Shaped<N, M, A> {
    /// The report of this answer for crane `C`, found with `settings` from
    /// the time-scaled optimum `time_scaled` (s) in `wall` seconds.
    pub fn report<C: Crane<N, M, A>>(
        &self,
        settings: &Settings,
        control_points: usize,
        time_scaled: f64,
        wall: f64,
    ) -> Report {
        let binding = self.at_answer.first().map(LimitReport::from).unwrap_or(LimitReport {
            name: String::new(),
            kind: "limit",
            limit: f64::NAN,
            value: f64::NAN,
            at: f64::NAN,
        });
        Report {
            model: C::NAME,
            duration: self.duration,
            binding,
            limits: self.at_answer.iter().map(LimitReport::from).collect(),
            shape: ShapeReport {
                kind: "optimal",
                profile: "spline",
                time_scaled: Some(time_scaled),
                control_points: Some(control_points),
                iterations: Some(self.iterations),
                gap: self.lower_bound.as_ref().map(|b| self.duration / b.duration - 1.0),
                lower_bound: self.lower_bound.clone(),
            },
            bracket: None,
            evaluations: self.runs,
            interval: None,
            formulation: Formulation::default_for::<C, N, M, A>().name(),
            scheme: settings.scheme.name(),
            dt: settings.dt,
            tolerance: settings.tolerance,
            wall_s: wall,
        }
    }
}

impl<const N: usize, const M: usize, const A: usize> Fastest<N, M, A> {
    /// The report of this answer for crane `C`, found with `settings` in
    /// `wall` seconds.
    pub fn report<C: Crane<N, M, A>>(&self, settings: &Settings, wall: f64) -> Report {
        Report {
            model: C::NAME,
            duration: self.duration,
            binding: LimitReport::from(&self.binding),
            limits: self.at_answer.iter().map(LimitReport::from).collect(),
            shape: ShapeReport::time_scaled(self.path.profile.kind().name(), self.duration, self.lower_bound.clone()),
            bracket: Some([self.bracket.0, self.bracket.1]),
            evaluations: self.evaluations,
            interval: Some(self.interval.clone()),
            formulation: Formulation::default_for::<C, N, M, A>().name(),
            scheme: settings.scheme.name(),
            dt: settings.dt,
            tolerance: settings.tolerance,
            wall_s: wall,
        }
    }
}

/// Check a set of points for crane `Mdl` before any run (as
/// [`sweep_points`](super::sweep_points) takes them: each the values of
/// `names` and a duration): every name a parameter of the crane, given
/// once; at least one point and at most [`MAX_SWEEP_POINTS`]; every point
/// with one value per name, every value finite, every duration finite and
/// positive. Returns the number of points.
///
/// ```
/// use crane_models::navy_planar::NavyPlanar;
/// use crane_models::plan::check_points;
/// let names = vec!["m_l".to_string()];
/// assert_eq!(check_points::<NavyPlanar, 7, 3, 2>(&names, &[(vec![80.0], 4.0), (vec![120.0], 3.0)]).unwrap(), 2);
/// assert!(check_points::<NavyPlanar, 7, 3, 2>(&names, &[(vec![f64::NAN], 4.0)]).is_err());
/// assert!(check_points::<NavyPlanar, 7, 3, 2>(&names, &[]).is_err());
/// ```
pub fn check_points<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    names: &[String],
    points: &[(Vec<f64>, f64)],
) -> Result<usize, PlanError> {
    let known = Mdl::INFO.parameters;
    for (i, name) in names.iter().enumerate() {
        if !known.contains(&name.as_str()) {
            return Err(PlanError::Grid(format!(
                "`{name}`: no such parameter; the parameters are {}",
                known.join(", ")
            )));
        }
        if names[..i].contains(name) {
            return Err(PlanError::Grid(format!("`{name}` is given twice")));
        }
    }
    if points.is_empty() {
        return Err(PlanError::Grid("no points".into()));
    }
    if points.len() > MAX_SWEEP_POINTS {
        return Err(PlanError::Grid(format!(
            "{} points, more than {MAX_SWEEP_POINTS} (split the set)",
            points.len()
        )));
    }
    for (i, (values, duration)) in points.iter().enumerate() {
        if values.len() != names.len() {
            return Err(PlanError::Grid(format!(
                "point {}: {} values for {} parameters",
                i + 1,
                values.len(),
                names.len()
            )));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(PlanError::Grid(format!(
                "point {}: `{}` = {} is not finite",
                i + 1,
                names[k],
                values[k]
            )));
        }
        if !(duration.is_finite() && *duration > 0.0) {
            return Err(PlanError::Grid(format!(
                "point {}: the duration {duration} s must be positive and finite",
                i + 1
            )));
        }
    }
    Ok(points.len())
}

/// Check a sweep's grid for crane `Mdl` before any run: every swept name
/// is a parameter of the crane and is swept once, every value and
/// duration is finite (durations positive), and the grid has at most
/// [`MAX_SWEEP_POINTS`] points. Returns the number of points (each a run).
///
/// ```
/// use crane_models::navy_planar::NavyPlanar;
/// use crane_models::plan::check_grid;
/// let masses = vec![("m_l".to_string(), vec![80.0, 100.0, 120.0])];
/// assert_eq!(check_grid::<NavyPlanar, 7, 3, 2>(&masses, &[3.0, 4.0]).unwrap(), 6);
/// assert!(check_grid::<NavyPlanar, 7, 3, 2>(&[("m_x".into(), vec![1.0])], &[]).is_err());
/// ```
pub fn check_grid<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    params: &[(String, Vec<f64>)],
    durations: &[f64],
) -> Result<usize, PlanError> {
    let names = Mdl::INFO.parameters;
    for (i, (name, values)) in params.iter().enumerate() {
        if !names.contains(&name.as_str()) {
            return Err(PlanError::Grid(format!(
                "`{name}`: no such parameter; the parameters are {}",
                names.join(", ")
            )));
        }
        if params[..i].iter().any(|(other, _)| other == name) {
            return Err(PlanError::Grid(format!(
                "parameter `{name}` is given twice: sweep each parameter once"
            )));
        }
        if values.is_empty() {
            return Err(PlanError::Grid(format!("parameter `{name}` has no values to sweep")));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(PlanError::Grid(format!(
                "parameter `{name}` = {v}: a swept value must be finite"
            )));
        }
    }
    if let Some(d) = durations.iter().find(|d| !(d.is_finite() && **d > 0.0)) {
        return Err(PlanError::Grid(format!(
            "duration {d}: a swept duration must be positive"
        )));
    }
    let points = params.iter().map(|(_, v)| v.len() as f64).product::<f64>() * durations.len().max(1) as f64;
    if points > MAX_SWEEP_POINTS as f64 {
        return Err(PlanError::Grid(format!(
            "the sweep has {points:.0} points, each a run; at most {MAX_SWEEP_POINTS} can be held"
        )));
    }
    Ok(points as usize)
}

/// One column of a sweep's table.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Numbers; `None` where a point's run failed.
    Numbers(Vec<Option<f64>>),
    /// Yes or no per point.
    Flags(Vec<bool>),
    /// Text per point (empty for none).
    Texts(Vec<String>),
}

/// The sweep of crane `Mdl` over the parameters named `params` as a table,
/// one row per point: the swept values, `duration`, `peak_<input>` (max
/// |u|), `min_<tension>` (the rope's smallest tension), `feasible`,
/// `error` (why the run failed) and `audit` (what the audit found, `; `
/// between findings).
pub fn sweep_columns<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    params: &[String],
    points: &[SweepPoint],
) -> Vec<(String, Column)> {
    let info = Mdl::INFO;
    let numbers = |f: &dyn Fn(&SweepPoint) -> Option<f64>| Column::Numbers(points.iter().map(f).collect());
    let mut out = Vec::new();
    for (i, name) in params.iter().enumerate() {
        out.push((name.clone(), numbers(&|p| p.values.get(i).copied())));
    }
    out.push(("duration".into(), numbers(&|p| Some(p.duration))));
    for (k, input) in info.inputs.iter().enumerate() {
        out.push((
            format!("peak_{input}"),
            numbers(&|p| p.evaluation.peak_u.get(k).map(|x| x.0)),
        ));
    }
    for (r, rope) in info.ropes.iter().enumerate() {
        out.push((
            format!("min_{}", rope.tension),
            numbers(&|p| p.evaluation.min_tension.get(r).map(|x| x.0)),
        ));
    }
    out.push((
        "feasible".into(),
        Column::Flags(points.iter().map(|p| p.feasible).collect()),
    ));
    out.push((
        "error".into(),
        Column::Texts(
            points
                .iter()
                .map(|p| p.evaluation.error.clone().unwrap_or_default())
                .collect(),
        ),
    ));
    out.push((
        "audit".into(),
        Column::Texts(points.iter().map(|p| p.evaluation.findings.join("; ")).collect()),
    ));
    out
}
