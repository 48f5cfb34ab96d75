//! The studies of many runs from Python: `fastest` (the shortest feasible
//! duration), `sweep` (a grid of parameters and durations) and
//! `convergence` (the error of `u` as the step shrinks), as the command
//! line's `crane fastest`, `crane sweep` and `crane convergence` compute
//! them, into dicts of numpy arrays.

use std::time::Instant;

use crane_cli::scenario::{self, Overrides, ScenarioFile};
use crane_models::plan::{self, Column, Limits, Settings, ShapeSettings};
use crane_models::registry::Visit;
use crane_models::study::convergence::{DTS, reference_inputs, study_against};
use crane_models::{Case, Crane};
use crane_runtime::CraneModel;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyModule};

use super::{Columns, CraneError, Cranes, Mapping, Number, job, json_dict, numbers, value, visit_detached};

/// The scenario and the planner's settings from the keywords.
struct PlanInputs {
    file: ScenarioFile,
    min_tension: Vec<(String, f64)>,
    settings: Settings,
}

impl PlanInputs {
    #[allow(clippy::too_many_arguments)]
    fn new(
        scenario: Option<&Bound<'_, PyAny>>,
        parameters: Option<&Bound<'_, PyDict>>,
        limits: Option<&Bound<'_, PyDict>>,
        min_tension: Option<&Bound<'_, PyDict>>,
        scheme: Option<&str>,
        dt: Option<f64>,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        let (file, overrides) = job(None, None, scheme, None, scenario, parameters, limits)?;
        let settings =
            Settings::with(dt, overrides.scheme, tolerance).map_err(|e| CraneError::new_err(e.to_string()))?;
        Ok(Self {
            file,
            min_tension: numbers("min_tension", min_tension)?.into_iter().collect(),
            settings,
        })
    }

    /// The case of crane `C` and its limits: the scenario's `[limits]`
    /// with the `limits` keyword's (both by input name), the `min_tension`
    /// floors; every other rope taut.
    fn case_and_limits<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
        &self,
    ) -> Result<(Case<C, N, M, A>, Limits), String> {
        let (case, run) =
            scenario::build::<C, N, M, A>(Some(&self.file), &Overrides::default()).map_err(|e| e.to_string())?;
        let limits =
            Limits::by_name::<C::Model, N, M, A>(&run.limits, &[], &self.min_tension).map_err(|e| match e {
                plan::PlanError::TensionFloor(message) => format!("min_tension: {message}"),
                other => format!("limits: {other}"),
            })?;
        Ok((case, limits))
    }
}

/// `crane fastest` on one crane (`Some` shape settings: `--shape optimal`).
pub(super) struct FastestJob(PlanInputs, Option<ShapeSettings>);

/// The answer of a search: its report (JSON), its scenario (TOML) and the
/// run there.
pub(super) struct FastestData {
    report: String,
    scenario: String,
    run: Columns,
    widths: [usize; 4],
}

impl Visit for FastestJob {
    type Output = Result<FastestData, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, limits) = self.0.case_and_limits::<C, N, M, A>()?;
        let settings = self.0.settings;
        let clock = Instant::now();
        let best = plan::fastest(&case, &limits, &settings).map_err(|e| e.to_string())?;
        let info = <C::Model as CraneModel<N, M, A>>::INFO;
        let (report, path, solution) = match self.1 {
            None => (
                best.report::<C>(&settings, clock.elapsed().as_secs_f64()),
                best.path,
                best.solution,
            ),
            Some(shape) => {
                let shaped =
                    plan::fastest_shape(&case, &limits, &settings, &shape, &mut |_| {}).map_err(|e| e.to_string())?;
                let report = shaped.report::<C>(
                    &settings,
                    shape.control_points,
                    best.duration,
                    clock.elapsed().as_secs_f64(),
                );
                (report, shaped.path, shaped.solution)
            }
        };
        Ok(FastestData {
            report: serde_json::to_string(&report).map_err(|e| format!("report: {e}"))?,
            scenario: scenario::scenario_text::<C, N, M, A>(case.model(), &path, &limits, &[]),
            run: Columns::of(&solution)?,
            widths: [N, A, M, info.ropes.len()],
        })
    }
}

/// The shortest duration of the move's shape (the scenario's start, end
/// and profile, or the default move's, scaled in time) for which every
/// input stays within its limit (`limits`, |u| by input name, with the
/// scenario's `[limits]`) and every rope's tension at or above its floor
/// (`min_tension` by tension name; a rope without one must stay taut), as
/// `crane fastest` finds it: BDF-4 at `dt` <= 0.05 s, bisection to
/// `tolerance` = 1 ms by default. Returns the dict of fastest.json
/// (`duration`, `binding`, `limits`, `bracket`, `evaluations`, `interval`,
/// `formulation`, `scheme`, `dt`, `tolerance`, `wall_s`) with `run`, the
/// run at the answer (a dict of `t`, `q`, `v`, `u`, `lambda_`, `tensions`),
/// and `scenario`, the answer's scenario keys (fastest.toml as a dict:
/// `run(model, scenario=...)` runs it). `shape="optimal"` optimises the
/// path's shape with the duration, as `crane fastest --shape optimal` does
/// (`control_points` free control points per load coordinate, 20 by
/// default). Raises `CraneError` with the tool's message.
#[pyfunction]
#[pyo3(pass_module, signature = (
    model, *, limits=None, min_tension=None, scenario=None, parameters=None, scheme=None, dt=None, tolerance=None,
    shape="time-scaled", control_points=None
))]
#[allow(clippy::too_many_arguments)]
pub(super) fn fastest<'py>(
    module: &Bound<'py, PyModule>,
    model: &str,
    limits: Option<Mapping<'_>>,
    min_tension: Option<Mapping<'_>>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
    scheme: Option<&str>,
    dt: Option<Number>,
    tolerance: Option<Number>,
    shape: &str,
    control_points: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let (dt, tolerance) = (value(dt), value(tolerance));
    let shape = match (shape, control_points) {
        ("time-scaled", None) => None,
        ("time-scaled", Some(_)) => {
            return Err(CraneError::new_err("control_points: applies only to shape=\"optimal\""));
        }
        ("optimal", points) => Some(ShapeSettings {
            control_points: points.unwrap_or(ShapeSettings::default().control_points),
            ..ShapeSettings::default()
        }),
        (other, _) => {
            return Err(CraneError::new_err(format!(
                "shape `{other}`: expected \"time-scaled\" or \"optimal\""
            )));
        }
    };
    let inputs = PlanInputs::new(
        scenario,
        parameters.as_deref(),
        limits.as_deref(),
        min_tension.as_deref(),
        scheme,
        dt,
        tolerance,
    )?;
    let data = visit_detached(py, &cranes, cranes.fastest, model, FastestJob(inputs, shape))?;
    let dict = json_dict(py, data.report, "report")?;
    dict.set_item("run", data.run.into_dict(py, data.widths)?)?;
    let keys: toml::Table =
        toml::from_str(&data.scenario).map_err(|e| CraneError::new_err(format!("scenario: {e}")))?;
    let keys = serde_json::to_string(&keys).map_err(|e| CraneError::new_err(format!("scenario: {e}")))?;
    dict.set_item("scenario", json_dict(py, keys, "scenario")?)?;
    Ok(dict)
}

/// `crane sweep` on one crane.
pub(super) struct SweepJob {
    inputs: PlanInputs,
    grid: Vec<(String, Vec<f64>)>,
    durations: Vec<f64>,
}

impl Visit for SweepJob {
    type Output = Result<Vec<(String, Column)>, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, limits) = self.inputs.case_and_limits::<C, N, M, A>()?;
        let settings = self.inputs.settings;
        plan::check_grid::<C::Model, N, M, A>(&self.grid, &self.durations).map_err(|e| format!("grid: {e}"))?;
        plan::impulses(&case).map_err(|e| e.to_string())?;
        let points = plan::sweep(&case, &self.grid, &self.durations, &limits, &settings, &|| {});
        let names: Vec<String> = self.grid.iter().map(|(name, _)| name.clone()).collect();
        Ok(plan::sweep_columns::<C::Model, N, M, A>(&names, &points))
    }
}

/// A sweep of `model` over `grid` (a dict of parameter name to the values
/// to take, e.g. `{"m_l": numpy.linspace(80, 120, 5)}`) and `durations`
/// (the move's own if none), every combination a run, as `crane sweep`
/// computes it (in parallel, BDF-4 at `dt` <= 0.05 s by default), each
/// point judged against `limits` and `min_tension` as `fastest` judges a
/// duration. Returns the columns of sweep.csv as a dict: one float64 array
/// per swept parameter, `duration`, `peak_<input>` and `min_<tension>`
/// (NaN where the run failed), `feasible` (a bool array), and the lists of
/// strings `error` (why a run failed) and `audit` (what the audit found).
#[pyfunction]
#[pyo3(pass_module, signature = (
    model, grid=None, *, durations=None, limits=None, min_tension=None, scenario=None, parameters=None, scheme=None,
    dt=None
))]
#[allow(clippy::too_many_arguments)]
pub(super) fn sweep<'py>(
    module: &Bound<'py, PyModule>,
    model: &str,
    grid: Option<Mapping<'_>>,
    durations: Option<Vec<f64>>,
    limits: Option<Mapping<'_>>,
    min_tension: Option<Mapping<'_>>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
    scheme: Option<&str>,
    dt: Option<Number>,
) -> PyResult<Bound<'py, PyDict>> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let inputs = PlanInputs::new(
        scenario,
        parameters.as_deref(),
        limits.as_deref(),
        min_tension.as_deref(),
        scheme,
        value(dt),
        None,
    )?;
    let mut swept = Vec::new();
    for (key, values) in grid.as_deref().into_iter().flat_map(|g| g.iter()) {
        let name: String = key
            .extract()
            .map_err(|_| CraneError::new_err("grid: every name must be a string"))?;
        let values: Vec<f64> = values
            .extract()
            .map_err(|_| CraneError::new_err(format!("grid: `{name}` must be a sequence of numbers")))?;
        swept.push((name, values));
    }
    let durations = durations.unwrap_or_default();
    if swept.is_empty() && durations.len() < 2 {
        return Err(CraneError::new_err(
            "nothing to sweep: give grid={name: values} or at least two durations",
        ));
    }
    let job = SweepJob {
        inputs,
        grid: swept,
        durations,
    };
    let columns = visit_detached(py, &cranes, cranes.sweep, model, job)?;
    columns_dict(py, columns)
}

/// `sweep_points` on one crane: the points' parameter values and
/// durations (the move's own where `None`).
pub(super) struct SweepPointsJob {
    inputs: PlanInputs,
    names: Vec<String>,
    values: Vec<Vec<f64>>,
    durations: Option<Vec<f64>>,
}

impl Visit for SweepPointsJob {
    type Output = Result<Vec<(String, Column)>, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, limits) = self.inputs.case_and_limits::<C, N, M, A>()?;
        let settings = self.inputs.settings;
        let spec = case.path().spec();
        let own = spec.t1 - spec.t0;
        let points: Vec<(Vec<f64>, f64)> = match self.durations {
            Some(durations) => self.values.into_iter().zip(durations).collect(),
            None => self.values.into_iter().map(|v| (v, own)).collect(),
        };
        plan::check_points::<C::Model, N, M, A>(&self.names, &points).map_err(|e| format!("points: {e}"))?;
        plan::impulses(&case).map_err(|e| e.to_string())?;
        let points = plan::sweep_points(&case, &self.names, points, &limits, &settings, &|| {});
        Ok(plan::sweep_columns::<C::Model, N, M, A>(&self.names, &points))
    }
}

/// A sequence of numbers from Python: a list or tuple, or what `tolist()`
/// makes of a numpy array or a pandas Series.
fn floats(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let list = if obj.hasattr("tolist")? {
        obj.call_method0("tolist")?
    } else {
        obj.clone()
    };
    list.extract()
        .map_err(|_| CraneError::new_err(format!("{what} must be a sequence of numbers")))
}

/// The points of `grid` and `durations` in `sweep`'s order
/// ([`plan::grid_points`]: row-major, the last parameter fastest, the
/// duration fastest of all), for `distributed.sweep`: the names, one list
/// of values per name, and the durations (`None`: the move's own).
#[pyfunction]
#[pyo3(signature = (grid, durations=None))]
pub(super) fn grid_points(
    grid: Mapping<'_>,
    durations: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Vec<String>, Vec<Vec<f64>>, Option<Vec<f64>>)> {
    let mut swept = Vec::new();
    for (key, values) in grid.iter() {
        let name: String = key
            .extract()
            .map_err(|_| CraneError::new_err("grid: every name must be a string"))?;
        let values = floats(&values, &format!("grid: `{name}`"))?;
        swept.push((name, values));
    }
    let given = durations.map(|d| floats(d, "durations")).transpose()?;
    // no durations: each point's is the move's own, which the sweep knows
    let points = match &given {
        Some(d) if d.is_empty() => Vec::new(),
        Some(d) => plan::grid_points(f64::NAN, &swept, d),
        None => plan::grid_points(f64::NAN, &swept, &[]),
    };
    let columns = (0..swept.len())
        .map(|k| points.iter().map(|(values, _)| values[k]).collect())
        .collect();
    let durations = given.map(|_| points.iter().map(|&(_, d)| d).collect());
    Ok((swept.into_iter().map(|(name, _)| name).collect(), columns, durations))
}

/// The columns of a sweep as a dict of numpy arrays (and lists of strings).
fn columns_dict<'py>(py: Python<'py>, columns: Vec<(String, Column)>) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for (name, column) in columns {
        match column {
            Column::Numbers(values) => {
                let values = values.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect();
                dict.set_item(name, PyArray1::from_vec(py, values))?
            }
            Column::Flags(values) => dict.set_item(name, PyArray1::from_vec(py, values))?,
            Column::Texts(values) => dict.set_item(name, values)?,
        }
    }
    Ok(dict)
}

/// A sweep of `model` over any set of points: `points` maps each swept
/// parameter to its values, one per point (a dict of equal-length arrays,
/// or a pandas DataFrame), `durations` gives each point's duration (the
/// move's own if none). Returns the columns `sweep` returns, in the order
/// of the points; `sweep` is this over its grid. Every point is checked
/// before any run: an unknown name, a NaN, ragged arrays, no points or
/// more than a million are a `CraneError`.
#[pyfunction]
#[pyo3(pass_module, signature = (
    model, points, *, durations=None, limits=None, min_tension=None, scenario=None, parameters=None, scheme=None,
    dt=None
))]
#[allow(clippy::too_many_arguments)]
pub(super) fn sweep_points<'py>(
    module: &Bound<'py, PyModule>,
    model: &str,
    points: Mapping<'_>,
    durations: Option<&Bound<'_, PyAny>>,
    limits: Option<Mapping<'_>>,
    min_tension: Option<Mapping<'_>>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
    scheme: Option<&str>,
    dt: Option<Number>,
) -> PyResult<Bound<'py, PyDict>> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let inputs = PlanInputs::new(
        scenario,
        parameters.as_deref(),
        limits.as_deref(),
        min_tension.as_deref(),
        scheme,
        value(dt),
        None,
    )?;
    let mut names = Vec::new();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    for (key, values) in points.iter() {
        let name: String = key
            .extract()
            .map_err(|_| CraneError::new_err("points: every name must be a string"))?;
        columns.push(floats(&values, &format!("points: `{name}`"))?);
        names.push(name);
    }
    let count = match (columns.first(), durations) {
        (Some(first), _) => first.len(),
        (None, Some(d)) => floats(d, "durations")?.len(),
        (None, None) => 0,
    };
    if let Some(k) = columns.iter().position(|c| c.len() != count) {
        return Err(CraneError::new_err(format!(
            "points: ragged: `{}` has {} values, `{}` {count}",
            names[k],
            columns[k].len(),
            names[0]
        )));
    }
    let durations = durations.map(|d| floats(d, "durations")).transpose()?;
    if let Some(d) = durations.as_ref().filter(|d| d.len() != count) {
        return Err(CraneError::new_err(format!(
            "durations: {} for {count} points",
            d.len()
        )));
    }
    let values = (0..count).map(|i| columns.iter().map(|c| c[i]).collect()).collect();
    let job = SweepPointsJob {
        inputs,
        names,
        values,
        durations,
    };
    let columns = visit_detached(py, &cranes, cranes.sweep_points, model, job)?;
    columns_dict(py, columns)
}

/// `crane convergence` on one crane.
pub(super) struct ConvergenceJob {
    file: ScenarioFile,
    overrides: Overrides,
    dts: Vec<f64>,
}

/// The rows of a convergence study and what it measured against.
pub(super) struct ConvergenceData {
    dt: Vec<f64>,
    e_u: Vec<f64>,
    order: Vec<f64>,
    audit: Vec<String>,
    reference: &'static str,
    formulation: &'static str,
    scheme: &'static str,
}

impl Visit for ConvergenceJob {
    type Output = Result<ConvergenceData, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) =
            scenario::build::<C, N, M, A>(Some(&self.file), &self.overrides).map_err(|e| e.to_string())?;
        let (reference, against) = reference_inputs(&case).map_err(|e| e.to_string())?;
        let rows = study_against(
            &case,
            &reference,
            settings.formulation,
            settings.scheme,
            &self.dts,
            |_| {},
        )
        .map_err(|e| e.to_string())?;
        Ok(ConvergenceData {
            dt: rows.iter().map(|r| r.dt).collect(),
            e_u: rows.iter().map(|r| r.e_u).collect(),
            order: rows.iter().map(|r| r.order.unwrap_or(f64::NAN)).collect(),
            audit: rows.iter().map(|r| r.findings.join("; ")).collect(),
            reference: against.describe(),
            formulation: settings.formulation.name(),
            scheme: settings.scheme.name(),
        })
    }
}

/// The convergence study of `crane convergence`: the relative error of `u`
/// at t = 1.5 s (eq. 48) against the crane's analytical reference, or the
/// exact inputs of its reduced formulation, for each step in `dts`
/// (0.1 ... 0.001 s by default), with the observed order between
/// neighbouring steps. Returns a dict of float64 arrays `dt`, `e_u` and
/// `order` (NaN for the first row and where an error is at round-off), the
/// list `audit` (what the audit found of each row's run, empty if
/// nothing), and the strings `reference`, `formulation`, `scheme`.
#[pyfunction]
#[pyo3(pass_module, signature = (model, *, dts=None, scheme=None, formulation=None, scenario=None, parameters=None))]
pub(super) fn convergence<'py>(
    module: &Bound<'py, PyModule>,
    model: &str,
    dts: Option<Vec<f64>>,
    scheme: Option<&str>,
    formulation: Option<&str>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
) -> PyResult<Bound<'py, PyDict>> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let (file, overrides) = job(None, None, scheme, formulation, scenario, parameters.as_deref(), None)?;
    let dts = dts.unwrap_or_else(|| DTS.to_vec());
    if dts.is_empty() {
        return Err(CraneError::new_err("dts: give at least one time step"));
    }
    let job = ConvergenceJob { file, overrides, dts };
    let data = visit_detached(py, &cranes, cranes.convergence, model, job)?;
    let dict = PyDict::new(py);
    dict.set_item("dt", PyArray1::from_vec(py, data.dt))?;
    dict.set_item("e_u", PyArray1::from_vec(py, data.e_u))?;
    dict.set_item("order", PyArray1::from_vec(py, data.order))?;
    dict.set_item("audit", data.audit)?;
    dict.set_item("reference", data.reference)?;
    dict.set_item("formulation", data.formulation)?;
    dict.set_item("scheme", data.scheme)?;
    Ok(dict)
}
