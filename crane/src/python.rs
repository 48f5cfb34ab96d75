//! Python modules of cranes: the inverse dynamics of the cranes of a
//! registry from Python, a whole run at a time, into numpy arrays (feature
//! `python`; pyo3 with the stable ABI of CPython 3.9 and later, numpy).
//!
//! A crate of cranes becomes a Python module with one line,
//! [`export_module!`](crate::export_module), built into a wheel by maturin
//! (the crate a `cdylib`, `module-name` in its `pyproject.toml` the name
//! given here):
//!
//! ```ignore
//! crane::python::export_module!(registry = MyCranes, name = "my_cranes");
//! ```
//!
//! The module has what the package `crane` (the built-in cranes) has:
//!
//! ```python
//! import my_cranes
//! my_cranes.models()                         # the registry's cranes, a dict each
//! r = my_cranes.run("user-gantry", dt=0.01)  # as `my-cranes run` runs it
//! r.u.shape                                  # (steps + 1, inputs)
//! r.summary["peak_torque"]                   # the dict of summary.json
//! r.warnings                                 # what the audit found
//! s = my_cranes.stepper("user-gantry")       # one step at a time
//! my_cranes.fastest("user-gantry", limits={"u1": 100.0})   # as `my-cranes fastest`
//! my_cranes.sweep("user-gantry", {"m_l": [100.0, 200.0]})  # sweep.csv's columns
//! my_cranes.convergence("user-gantry")                     # convergence.csv's
//! ```
//!
//! A run is the command line's `run`: the same scenario keys (a TOML file
//! or a dict of the same keys), the same defaults, the same summary and
//! audit; it calls the library, not the command line. Failures raise
//! `CraneError` (a `ValueError`) with the tool's one-line message; runs
//! release the GIL.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crane_cli::scenario::{self, Overrides, ScenarioFile};
use crane_models::registry::{Entry, Registry, Visit};
use crane_models::study::audit::StepAudit;
use crane_models::study::replay::{FeedbackSpec, ReplayRequest};
use crane_models::study::{self, Formulation};
use crane_models::{Case, Crane};
use crane_runtime::cancel::Cancel;
use crane_runtime::redundant::Redundant;
use crane_runtime::stepper::{Advance, Stepper};
use crane_runtime::{CraneModel, Options, Solution, dummy_derivative, state_selection};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyBool, PyDict, PyFloat, PyInt, PyList, PyModule, PyString, PyTuple};

#[doc(hidden)]
pub use numpy;
#[doc(hidden)]
pub use pyo3;

pub use crate::export_module;

mod plan;

pyo3::create_exception!(
    crane,
    CraneError,
    PyValueError,
    "A run the tool could not make, or an argument it refuses: the tool's one-line message."
);

pyo3::create_exception!(
    crane,
    CraneWarning,
    pyo3::exceptions::PyUserWarning,
    "What the audit found in a run: its findings, one warning each (`Run.warnings` lists them too). \
     Filter them, or make them errors, with Python's `warnings` module."
);

/// Each of `findings` as a `CraneWarning` (`warnings.warn`), attributed to
/// the caller of the function that made the run.
fn warn_findings(py: Python<'_>, findings: &[String]) -> PyResult<()> {
    let category = py.get_type::<CraneWarning>();
    for finding in findings {
        let message = std::ffi::CString::new(finding.replace('\0', " "))
            .map_err(|e| CraneError::new_err(format!("warning: {e}")))?;
        PyErr::warn(py, &category, &message, 1)?;
    }
    Ok(())
}

/// A number argument (an int, a float, a numpy scalar), never a bool:
/// `dt=True` is refused, not taken as 1.
pub(crate) struct Number(pub(crate) f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Number {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if obj.is_instance_of::<PyBool>() {
            return Err(CraneError::new_err(format!("expected a number, not the bool {}", *obj)));
        }
        Ok(Number(obj.extract()?))
    }
}

/// A keyword argument that maps names to values: a dict, or any mapping
/// (a `MappingProxyType`, a pandas Series: anything with `keys()` and
/// item access), copied into a dict.
pub(crate) struct Mapping<'py>(Bound<'py, PyDict>);

impl<'a, 'py> FromPyObject<'a, 'py> for Mapping<'py> {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let obj = obj.to_owned();
        if let Ok(dict) = obj.cast::<PyDict>() {
            return Ok(Mapping(dict.clone()));
        }
        if obj.hasattr("keys")? {
            let dict = PyDict::new(obj.py());
            for key in obj.call_method0("keys")?.try_iter()? {
                let key = key?;
                dict.set_item(&key, obj.get_item(&key)?)?;
            }
            return Ok(Mapping(dict));
        }
        Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "expected a mapping of names to values (a dict, a MappingProxyType, a pandas Series), not a {}",
            obj.get_type().name()?
        )))
    }
}

impl<'py> std::ops::Deref for Mapping<'py> {
    type Target = Bound<'py, PyDict>;
    fn deref(&self) -> &Bound<'py, PyDict> {
        &self.0
    }
}

/// The memory the machine has available, bytes (`MemAvailable` of
/// /proc/meminfo; `None` where it cannot be read).
fn available_memory() -> Option<f64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// Refuse a run of `steps` whose results take `bytes` at their peak (the
/// run's states and their numpy copies) where that is more than the
/// machine has available: an error before the run, not an interpreter
/// killed or aborted by a failed allocation.
fn check_memory(steps: f64, bytes: f64) -> Result<(), String> {
    match available_memory() {
        Some(available) if bytes > available => Err(format!(
            "a run of {steps:.3e} steps needs about {:.1} GiB at its peak (its states and their numpy copies), \
             more than the {:.1} GiB this machine has available: take a longer dt or a shorter run",
            bytes / GIB,
            available / GIB
        )),
        _ => Ok(()),
    }
}

/// Bytes in a GiB.
const GIB: f64 = 1024.0 * 1024.0 * 1024.0;

/// The value of an optional [`Number`].
pub(crate) fn value(number: Option<Number>) -> Option<f64> {
    number.map(|n| n.0)
}

/// The states of a run as columns, row-major (one row per state).
struct Columns {
    rows: usize,
    t: Vec<f64>,
    q: Vec<f64>,
    v: Vec<f64>,
    u: Vec<f64>,
    lambda: Vec<f64>,
    tensions: Vec<f64>,
}

impl Columns {
    /// The bytes the columns of one state with `ropes` ropes take: `t`, `q`,
    /// `v`, `u`, `lambda` and the tensions.
    fn bytes_per_state<const N: usize, const M: usize, const A: usize>(ropes: usize) -> usize {
        (1 + 2 * N + A + M + ropes) * std::mem::size_of::<f64>()
    }

    /// The columns of `solution`, or where the memory for them cannot be
    /// had, why (an error for Python, not an abort of the interpreter).
    fn of<const N: usize, const M: usize, const A: usize>(solution: &Solution<N, M, A>) -> Result<Self, String> {
        let states = &solution.states;
        let ropes = solution.info.ropes.len();
        let bytes = states.len() * Self::bytes_per_state::<N, M, A>(ropes);
        let out_of_memory = |_| {
            format!(
                "out of memory: the run's {} states take {:.1} MB more as numpy arrays; take a longer dt or a \
                 shorter run",
                states.len(),
                bytes as f64 / 1e6
            )
        };
        let flat = |width: usize, value: &dyn Fn(usize, usize) -> f64| -> Result<Vec<f64>, String> {
            let mut column = Vec::new();
            column.try_reserve_exact(states.len() * width).map_err(out_of_memory)?;
            column.extend((0..states.len()).flat_map(|i| (0..width).map(move |k| value(i, k))));
            Ok(column)
        };
        Ok(Self {
            rows: states.len(),
            t: flat(1, &|i, _| states[i].t)?,
            q: flat(N, &|i, k| states[i].q[k])?,
            v: flat(N, &|i, k| states[i].v[k])?,
            u: flat(A, &|i, k| states[i].u[k])?,
            lambda: flat(M, &|i, k| states[i].lambda[k])?,
            tensions: flat(ropes, &|i, r| solution.tensions_at(i)[r])?,
        })
    }
}

/// Columns as numpy arrays, owned by Python.
struct Arrays<'py> {
    t: Bound<'py, PyArray1<f64>>,
    q: Bound<'py, PyArray2<f64>>,
    v: Bound<'py, PyArray2<f64>>,
    u: Bound<'py, PyArray2<f64>>,
    lambda: Bound<'py, PyArray2<f64>>,
    tensions: Bound<'py, PyArray2<f64>>,
}

impl Columns {
    /// The arrays, `[n, a, m, ropes]` the widths of `q` and `v`, `u`,
    /// `lambda` and `tensions`.
    fn into_arrays(self, py: Python<'_>, [n, a, m, r]: [usize; 4]) -> PyResult<Arrays<'_>> {
        let rows = self.rows;
        Ok(Arrays {
            t: PyArray1::from_vec(py, self.t),
            q: matrix(py, self.q, rows, n)?,
            v: matrix(py, self.v, rows, n)?,
            u: matrix(py, self.u, rows, a)?,
            lambda: matrix(py, self.lambda, rows, m)?,
            tensions: matrix(py, self.tensions, rows, r)?,
        })
    }
}

impl Columns {
    /// The arrays as a dict of `t`, `q`, `v`, `u`, `lambda_`, `tensions`.
    fn into_dict(self, py: Python<'_>, widths: [usize; 4]) -> PyResult<Bound<'_, PyDict>> {
        let arrays = self.into_arrays(py, widths)?;
        let dict = PyDict::new(py);
        dict.set_item("t", arrays.t)?;
        dict.set_item("q", arrays.q)?;
        dict.set_item("v", arrays.v)?;
        dict.set_item("u", arrays.u)?;
        dict.set_item("lambda_", arrays.lambda)?;
        dict.set_item("tensions", arrays.tensions)?;
        Ok(dict)
    }
}

/// A JSON object (a summary, a report) as a Python dict.
fn json_dict<'py>(py: Python<'py>, json: String, what: &str) -> PyResult<Bound<'py, PyDict>> {
    py.import("json")?
        .call_method1("loads", (json,))?
        .cast_into::<PyDict>()
        .map_err(|_| CraneError::new_err(format!("{what}: not a dict")))
}

/// A run's numbers, gathered without the GIL.
struct RunData {
    columns: Columns,
    /// The replay the summary describes (with feedback if asked for).
    replay: Option<Columns>,
    coordinates: Vec<String>,
    inputs: Vec<String>,
    ropes: Vec<String>,
    multipliers: usize,
    summary: crane_models::study::Summary,
    warnings: Vec<String>,
}

/// `crane run` on one crane, its numbers kept; with a replay if asked.
struct RunJob {
    file: ScenarioFile,
    overrides: Overrides,
    replay: Option<ReplayRequest>,
}

impl Visit for RunJob {
    type Output = Result<RunData, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) =
            scenario::build::<C, N, M, A>(Some(&self.file), &self.overrides).map_err(|e| e.to_string())?;
        if self.replay.is_none() && !settings.plant.is_empty() {
            let names: Vec<&str> = settings.plant.iter().map(|(name, _)| name.as_str()).collect();
            return Err(format!(
                "the plant's parameters ({}) apply only to a replay: add replay=True",
                names.join(", ")
            ));
        }
        // the scenario's [plant] first, then the keywords'
        let replay = self.replay.map(|request| ReplayRequest {
            plant: settings.plant.iter().cloned().chain(request.plant).collect(),
            ..request
        });
        // a replay's own checks before the run is made
        if let Some(request) = &replay {
            study::replay::plant(&case, request).map_err(|e| e.to_string())?;
            study::replay::check_step(settings.dt).map_err(|e| e.to_string())?;
        }
        // the peak: the run's states and their numpy copies, and a replay's
        // (its forward steps per step of the run)
        let steps = ((case.tf() - case.t0()) / settings.dt).max(0.0);
        let ropes = <C::Model as CraneModel<N, M, A>>::INFO.ropes.len();
        let per_state = Solution::<N, M, A>::bytes_per_state(ropes) + Columns::bytes_per_state::<N, M, A>(ropes);
        let runs = if replay.is_some() {
            1.0 + study::replay::forward_steps_per_step() as f64
        } else {
            1.0
        };
        check_memory(steps, runs * steps * per_state as f64)?;
        let mut outcome = study::run(&case, &settings, &mut |_, _| {}).map_err(|e| e.to_string())?;
        if let Some(request) = replay {
            outcome
                .replay(&case, &request)
                .map_err(|e| format!("the replay failed: {e}"))?;
        }
        let info = outcome.solution.info;
        Ok(RunData {
            columns: Columns::of(&outcome.solution)?,
            replay: outcome
                .replay
                .as_ref()
                .map(|replay| Columns::of(&replay.result().solution))
                .transpose()?,
            coordinates: info.coordinates.iter().map(|s| s.to_string()).collect(),
            inputs: info.inputs.iter().map(|s| s.to_string()).collect(),
            ropes: info.ropes.iter().map(|r| r.tension.to_string()).collect(),
            multipliers: M,
            summary: outcome.summary,
            warnings: outcome.findings.iter().map(|f| f.to_string()).collect(),
        })
    }
}

/// What `models()` says of a crane beyond its catalogue entry.
struct Traits {
    path_order: Option<usize>,
    formulation: &'static str,
    internal_dimension: Option<usize>,
}

struct TraitsOf;

impl Visit for TraitsOf {
    type Output = Traits;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Traits {
        let structure = <C::Model as CraneModel<N, M, A>>::STRUCTURE;
        Traits {
            path_order: structure.map(|s| s.path_order(A)),
            formulation: Formulation::default_for::<C, N, M, A>().name(),
            internal_dimension: Case::<C, N, M, A>::maneuver().ok().and_then(|case| {
                let start = case.start().ok()?;
                crane_runtime::internal::internal_dynamics(case.model(), &start)
                    .ok()
                    .map(|d| d.dimension)
            }),
        }
    }
}

/// What a module knows of its registry: the registry's functions, without
/// its type (a `#[pyfunction]` cannot be generic), kept in the module as
/// `_cranes`.
#[derive(Clone, Copy)]
struct Cranes {
    entries: fn() -> Vec<Entry>,
    traits: fn(&str) -> Option<Traits>,
    run: fn(&str, RunJob) -> Option<Result<RunData, String>>,
    stepper: fn(&str, StepperJob) -> Option<<StepperJob as Visit>::Output>,
    fastest: fn(&str, plan::FastestJob) -> Option<<plan::FastestJob as Visit>::Output>,
    sweep: fn(&str, plan::SweepJob) -> Option<<plan::SweepJob as Visit>::Output>,
    sweep_points: fn(&str, plan::SweepPointsJob) -> Option<<plan::SweepPointsJob as Visit>::Output>,
    convergence: fn(&str, plan::ConvergenceJob) -> Option<<plan::ConvergenceJob as Visit>::Output>,
}

impl Cranes {
    fn of<R: Registry + Default>() -> Self {
        Self {
            entries: || R::default().entries(),
            traits: |name| R::default().visit(name, TraitsOf),
            run: |name, job| R::default().visit(name, job),
            stepper: |name, job| R::default().visit(name, job),
            fastest: |name, job| R::default().visit(name, job),
            sweep: |name, job| R::default().visit(name, job),
            sweep_points: |name, job| R::default().visit(name, job),
            convergence: |name, job| R::default().visit(name, job),
        }
    }

    /// The registry of the module a function was called from.
    fn of_module(module: &Bound<'_, PyModule>) -> PyResult<Self> {
        let cranes = module.getattr("_cranes")?;
        let cranes = cranes
            .cast::<CranesObject>()
            .map_err(|_| CraneError::new_err("the module's `_cranes` is not its registry"))?;
        Ok(cranes.get().0)
    }
}

/// The registry of the module this library made (one per extension: a
/// user's module is a library of its own), for the classes' constructors,
/// which are not called from the module.
static MODULE_CRANES: std::sync::OnceLock<Cranes> = std::sync::OnceLock::new();

/// The registry's functions as a Python object.
#[pyclass(frozen, name = "_Cranes")]
struct CranesObject(Cranes);

/// The registry's cranes: a list of dicts with `name`, `description`, the
/// sizes `n` (coordinates), `m` (constraints), `a` (inputs), `reference`
/// (an analytical reference), `minimal` (a minimal-coordinate map),
/// `path_order` (the path derivative the inputs need), `formulation` (the
/// default) and `internal_dimension` (the internal dynamics' dimension at
/// the start of the default move, 0 for a flat crane).
#[pyfunction]
#[pyo3(pass_module)]
fn models<'py>(module: &Bound<'py, PyModule>) -> PyResult<Bound<'py, PyList>> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let list = PyList::empty(py);
    for entry in (cranes.entries)() {
        let dict = PyDict::new(py);
        dict.set_item("name", entry.name)?;
        dict.set_item("description", entry.description)?;
        dict.set_item("n", entry.n)?;
        dict.set_item("m", entry.m)?;
        dict.set_item("a", entry.a)?;
        dict.set_item("reference", entry.reference)?;
        dict.set_item("minimal", entry.minimal)?;
        if let Some(traits) = (cranes.traits)(entry.name) {
            dict.set_item("path_order", traits.path_order)?;
            dict.set_item("formulation", traits.formulation)?;
            dict.set_item("internal_dimension", traits.internal_dimension)?;
        }
        list.append(dict)?;
    }
    Ok(list)
}

/// How deep scenario values may nest (a scenario's own are at most a
/// table of lists of numbers, three levels): deeper is a mistake, refused
/// before it exhausts the stack.
const MAX_SCENARIO_DEPTH: usize = 32;

/// How many values a scenario may hold (its own hold a few dozen): more is
/// a mistake, refused before it exhausts the memory (a list that holds
/// itself twice, or the same list nested thirty times, is 1e9 values).
const MAX_SCENARIO_VALUES: usize = 1_000_000;

/// The walk through a scenario's values: the lists and dicts on the way
/// from the top (by identity, to refuse one that contains itself) and the
/// values seen so far.
#[derive(Default)]
struct ScenarioWalk {
    path: Vec<usize>,
    values: usize,
}

impl ScenarioWalk {
    /// Step into `container` (a list or dict) under `key`, refusing a cycle,
    /// too deep a nesting and too many values.
    fn enter(&mut self, container: &Bound<'_, PyAny>, key: &str) -> PyResult<()> {
        let id = container.as_ptr() as usize;
        if self.path.contains(&id) {
            return Err(CraneError::new_err(format!(
                "scenario: `{key}`: a list or dict that contains itself"
            )));
        }
        if self.path.len() >= MAX_SCENARIO_DEPTH {
            return Err(CraneError::new_err(format!(
                "scenario: `{key}`: values nest deeper than {MAX_SCENARIO_DEPTH} levels"
            )));
        }
        self.path.push(id);
        Ok(())
    }

    /// Count one value, refusing more than [`MAX_SCENARIO_VALUES`].
    fn count(&mut self, key: &str) -> PyResult<()> {
        self.values += 1;
        if self.values > MAX_SCENARIO_VALUES {
            return Err(CraneError::new_err(format!(
                "scenario: `{key}`: more than {MAX_SCENARIO_VALUES} values"
            )));
        }
        Ok(())
    }
}

/// A scenario value from Python: numbers, strings, booleans, lists and
/// dicts of them, and what `tolist()` makes of a numpy array or scalar.
fn toml_value(value: &Bound<'_, PyAny>, key: &str, walk: &mut ScenarioWalk) -> PyResult<toml::Value> {
    walk.count(key)?;
    if value.is_instance_of::<PyBool>() {
        Ok(toml::Value::Boolean(value.extract()?))
    } else if value.is_instance_of::<PyInt>() {
        Ok(toml::Value::Integer(value.extract().map_err(|_| {
            CraneError::new_err(format!("scenario: `{key}`: the integer does not fit in 64 bits"))
        })?))
    } else if value.is_instance_of::<PyFloat>() {
        Ok(toml::Value::Float(value.extract()?))
    } else if value.is_instance_of::<PyString>() {
        Ok(toml::Value::String(value.extract()?))
    } else if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        walk.enter(value, key)?;
        let items: PyResult<Vec<toml::Value>> = value.try_iter()?.map(|item| toml_value(&item?, key, walk)).collect();
        walk.path.pop();
        Ok(toml::Value::Array(items?))
    } else if let Ok(dict) = value.cast::<PyDict>() {
        walk.enter(value, key)?;
        let table = toml_table(dict, Some(key), walk);
        walk.path.pop();
        Ok(toml::Value::Table(table?))
    } else if value.hasattr("tolist")? {
        // a numpy array or scalar; where its `tolist` fails, that failure
        // is the cause (one that returns itself is a cycle)
        match value.call_method0("tolist") {
            Ok(list) => {
                walk.enter(value, key)?;
                let converted = toml_value(&list, key, walk);
                walk.path.pop();
                converted
            }
            Err(cause) => {
                let error = CraneError::new_err(format!(
                    "scenario: `{key}`: the {}'s tolist() failed",
                    value.get_type().name()?
                ));
                error.set_cause(value.py(), Some(cause));
                Err(error)
            }
        }
    } else {
        Err(CraneError::new_err(format!(
            "scenario: `{key}`: a {} is not a scenario value (numbers, strings, lists and dicts are)",
            value.get_type().name()?
        )))
    }
}

/// A dict of scenario keys as a TOML table (`parent` names the table in
/// messages).
fn toml_table(dict: &Bound<'_, PyDict>, parent: Option<&str>, walk: &mut ScenarioWalk) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in dict.iter() {
        let key: String = key
            .extract()
            .map_err(|_| CraneError::new_err("scenario: every key must be a string"))?;
        let path = parent.map_or_else(|| key.clone(), |p| format!("{p}.{key}"));
        table.insert(key, toml_value(&value, &path, walk)?);
    }
    Ok(table)
}

/// The scenario: a path to a TOML file, a dict of the same keys, or none.
fn scenario_of(scenario: Option<&Bound<'_, PyAny>>) -> PyResult<ScenarioFile> {
    let Some(scenario) = scenario.filter(|s| !s.is_none()) else {
        return Ok(ScenarioFile::default());
    };
    // a mapping other than a dict (a MappingProxyType) as the dict it holds
    let copied = match scenario.cast::<PyDict>() {
        Err(_) if scenario.hasattr("keys")? => Some(scenario.extract::<Mapping<'_>>()?.0),
        _ => None,
    };
    let scenario = copied.as_ref().map_or(scenario, |dict| dict.as_any());
    if let Ok(dict) = scenario.cast::<PyDict>() {
        let text = toml::to_string(&{
            let mut walk = ScenarioWalk::default();
            walk.enter(dict, "the scenario")?;
            toml_table(dict, None, &mut walk)?
        })
        .map_err(|e| CraneError::new_err(format!("scenario: {e}")))?;
        return ScenarioFile::parse_keys(&text).map_err(|e| CraneError::new_err(e.to_string()));
    }
    let path: PathBuf = scenario
        .extract()
        .map_err(|_| CraneError::new_err("scenario: expected the path of a TOML file or a dict of scenario keys"))?;
    ScenarioFile::load(&path).map_err(|e| CraneError::new_err(e.to_string()))
}

/// Numbers by name from a dict (`parameters`, `limits`).
fn numbers(what: &str, dict: Option<&Bound<'_, PyDict>>) -> PyResult<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    for (key, value) in dict.into_iter().flat_map(|d| d.iter()) {
        let name: String = key
            .extract()
            .map_err(|_| CraneError::new_err(format!("{what}: every name must be a string")))?;
        let value = value
            .extract::<Number>()
            .map_err(|_| CraneError::new_err(format!("{what}: `{name}` must be a number")))?
            .0;
        out.insert(name, value);
    }
    Ok(out)
}

/// An array of `rows` rows of `width` numbers, owned by Python.
fn matrix<'py>(py: Python<'py>, values: Vec<f64>, rows: usize, width: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
    PyArray1::from_vec(py, values).reshape([rows, width])
}

/// One run: its states as numpy arrays (float64, one row per step), the
/// names of their columns, the summary (the dict `crane run` writes as
/// summary.json) and what the audit found.
#[pyclass(frozen, name = "Run", module = "crane")]
struct Run {
    /// Times, s: shape (steps + 1,).
    #[pyo3(get)]
    t: Py<PyArray1<f64>>,
    /// Coordinates: shape (steps + 1, n).
    #[pyo3(get)]
    q: Py<PyArray2<f64>>,
    /// Velocities: shape (steps + 1, n).
    #[pyo3(get)]
    v: Py<PyArray2<f64>>,
    /// Inputs: shape (steps + 1, a).
    #[pyo3(get)]
    u: Py<PyArray2<f64>>,
    /// Multipliers: shape (steps + 1, m).
    #[pyo3(get, name = "lambda_")]
    lambda: Py<PyArray2<f64>>,
    /// Rope tensions: shape (steps + 1, ropes).
    #[pyo3(get)]
    tensions: Py<PyArray2<f64>>,
    /// The coordinates' names, the columns of `q` and `v`.
    #[pyo3(get)]
    coordinates: Vec<String>,
    /// The inputs' names, the columns of `u`.
    #[pyo3(get)]
    inputs: Vec<String>,
    /// The ropes' tension names, the columns of `tensions`.
    #[pyo3(get)]
    ropes: Vec<String>,
    /// The summary, as summary.json has it.
    #[pyo3(get)]
    summary: Py<PyDict>,
    /// What the audit found (empty for a trustworthy run).
    #[pyo3(get)]
    warnings: Vec<String>,
    /// With `replay=True`: the forward run of the computed inputs (with the
    /// feedback if one was asked for), a dict of `t`, `q`, `v`, `u`,
    /// `lambda_`, `tensions` like the run's own; else None.
    #[pyo3(get)]
    replay: Option<Py<PyDict>>,
}

#[pymethods]
impl Run {
    /// A run from its parts, as a run has them (what unpickling calls): the
    /// arrays' rows one per time of `t`, their columns as the names say.
    #[new]
    #[pyo3(signature = (t, q, v, u, lambda_, tensions, coordinates, inputs, ropes, summary, warnings, replay=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        t: Py<PyArray1<f64>>,
        q: Py<PyArray2<f64>>,
        v: Py<PyArray2<f64>>,
        u: Py<PyArray2<f64>>,
        lambda_: Py<PyArray2<f64>>,
        tensions: Py<PyArray2<f64>>,
        coordinates: Vec<String>,
        inputs: Vec<String>,
        ropes: Vec<String>,
        summary: Py<PyDict>,
        warnings: Vec<String>,
        replay: Option<Py<PyDict>>,
    ) -> PyResult<Self> {
        let rows = t.bind(py).len()?;
        let shapes = [
            ("q", &q, Some(coordinates.len())),
            ("v", &v, Some(coordinates.len())),
            ("u", &u, Some(inputs.len())),
            ("lambda_", &lambda_, None),
            ("tensions", &tensions, Some(ropes.len())),
        ];
        for (name, array, width) in shapes {
            let shape = numpy::PyUntypedArrayMethods::shape(array.bind(py)).to_vec();
            if shape[0] != rows || width.is_some_and(|w| shape[1] != w) {
                return Err(CraneError::new_err(format!(
                    "Run: `{name}` has the shape {shape:?}, not {rows} rows of {} columns",
                    width.map_or_else(|| "any number of".to_string(), |w| w.to_string())
                )));
            }
        }
        Ok(Self {
            t,
            q,
            v,
            u,
            lambda: lambda_,
            tensions,
            coordinates,
            inputs,
            ropes,
            summary,
            warnings,
            replay,
        })
    }

    /// Pickling (and `copy.deepcopy`): the class and its parts.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let run = slf.get();
        let parts = (
            run.t.clone_ref(py),
            run.q.clone_ref(py),
            run.v.clone_ref(py),
            run.u.clone_ref(py),
            run.lambda.clone_ref(py),
            run.tensions.clone_ref(py),
            run.coordinates.clone(),
            run.inputs.clone(),
            run.ropes.clone(),
            run.summary.clone_ref(py),
            run.warnings.clone(),
            run.replay.as_ref().map(|r| r.clone_ref(py)),
        )
            .into_pyobject(py)?;
        Ok((slf.get_type().into_any(), parts))
    }

    /// Write the run as `crane run` writes results.csv: `t`, the
    /// coordinates, the inputs, `lambda1..` and the tensions, one row per
    /// step, the numbers in the shortest form that reads back exactly (the
    /// crane's derived outputs, which results.csv appends, are not here).
    /// `target` is a path (str or os.PathLike), written whole or not at all
    /// and never a symbolic link, folder, FIFO or device, which it refuses
    /// rather than replace; or a file object (`sys.stdout`, `io.StringIO`,
    /// an open file, or a FIFO opened by its caller), written through its
    /// `write`.
    fn to_csv(&self, py: Python<'_>, target: &Bound<'_, PyAny>) -> PyResult<()> {
        let text = self.csv_text(py)?;
        if let Ok(path) = target.extract::<PathBuf>() {
            write_whole(&path, &text)
        } else if target.hasattr("write")? {
            target.call_method1("write", (text,))?;
            Ok(())
        } else {
            Err(CraneError::new_err(format!(
                "to_csv: a {} is neither a path nor a file object with write()",
                target.get_type().name()?
            )))
        }
    }

    /// The run as a pandas DataFrame: the times `t` its index, the columns
    /// those of `to_csv` (the coordinates, the inputs, `lambda1..` and the
    /// tensions), their values the arrays' (copied). pandas is an optional
    /// dependency (`pip install crane[pandas]`): without it, ImportError.
    fn to_dataframe<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|cause| {
            let error = pyo3::exceptions::PyImportError::new_err(
                "Run.to_dataframe needs pandas: pip install pandas (or crane[pandas])",
            );
            error.set_cause(py, Some(cause));
            error
        })?;
        let columns = PyDict::new(py);
        let multipliers = self.lambda.bind(py).readonly().as_array().ncols();
        let lambdas: Vec<String> = (1..=multipliers).map(|i| format!("lambda{i}")).collect();
        for (array, names) in [
            (&self.q, &self.coordinates),
            (&self.u, &self.inputs),
            (&self.lambda, &lambdas),
            (&self.tensions, &self.ropes),
        ] {
            let array = array.bind(py).readonly();
            for (i, name) in names.iter().enumerate() {
                columns.set_item(
                    name,
                    PyArray1::from_owned_array(py, array.as_array().column(i).to_owned()),
                )?;
            }
        }
        let index = pandas.call_method(
            "Index",
            (self.t.bind(py).call_method0("copy")?,),
            Some(&[("name", "t")].into_py_dict(py)?),
        )?;
        pandas.call_method("DataFrame", (columns,), Some(&[("index", index)].into_py_dict(py)?))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let steps = self.t.bind(py).len().map_or(0, |n| n.saturating_sub(1));
        let model = (self.summary.bind(py).get_item("model").ok().flatten())
            .and_then(|m| m.extract::<String>().ok())
            .unwrap_or_default();
        format!(
            "<crane.Run of {model}: {steps} steps, inputs {}, {} warnings>",
            self.inputs.join(", "),
            self.warnings.len()
        )
    }
}

impl Run {
    /// The run as results.csv's text (without the crane's derived outputs).
    fn csv_text(&self, py: Python<'_>) -> PyResult<String> {
        let t = self.t.bind(py).readonly();
        let columns = [&self.q, &self.u, &self.lambda, &self.tensions].map(|a| a.bind(py).readonly());
        let mut header = vec!["t".to_string()];
        header.extend(self.coordinates.iter().cloned());
        header.extend(self.inputs.iter().cloned());
        let multipliers = columns[2].as_array().ncols();
        header.extend((1..=multipliers).map(|i| format!("lambda{i}")));
        header.extend(self.ropes.iter().cloned());
        let mut text = header.join(",");
        text.push('\n');
        let t = t.as_slice()?;
        for (i, time) in t.iter().enumerate() {
            text.push_str(&format!("{time}"));
            for column in &columns {
                let row = column.as_array();
                for value in row.row(i) {
                    text.push_str(&format!(",{value:e}"));
                }
            }
            text.push('\n');
        }
        Ok(text)
    }
}

/// `text` into the file at `path`, whole or not at all: through a partial
/// file beside it (made new, never through a link left there), renamed;
/// a path that is a symbolic link, a folder, a FIFO or a device is refused,
/// as `crane run` refuses it, not replaced.
fn write_whole(path: &std::path::Path, text: &str) -> PyResult<()> {
    use std::io::Write as _;
    if let Some(kind) = crane_models::files::not_a_regular_file(path) {
        return Err(CraneError::new_err(format!(
            "{}: it exists and is {kind}, which to_csv does not replace: remove it, choose another path, or \
             pass a file object opened on it",
            path.display()
        )));
    }
    let name = path
        .file_name()
        .ok_or_else(|| CraneError::new_err(format!("{} names no file", path.display())))?;
    let partial = path.with_file_name(format!(".{}.partial", name.to_string_lossy()));
    // (a partial file left by a crash, or a link planted in its place, goes)
    let _ = std::fs::remove_file(&partial);
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&partial)
        .and_then(|mut file| file.write_all(text.as_bytes()))
        .and_then(|()| std::fs::rename(&partial, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written.map_err(|e| CraneError::new_err(format!("writing {}: {e}", path.display())))
}

/// Run `model` as `crane run` does: its default manoeuvre, changed by the
/// `scenario` (a TOML file's path or a dict of the same keys), then by
/// `parameters` and `limits` (dicts by name) and the keywords `dt` (s),
/// `tf` (s), `scheme` (`backward-euler`, `bdf2` .. `bdf5`) and
/// `formulation` (`redundant`, `minimal`, `dummy-derivative`). With
/// `replay=True` the computed inputs also drive the forward dynamics, as
/// `crane run --replay` does: on a plant whose parameters `plant` (a dict
/// by name, after the scenario's `[plant]`) changes, with the feedback
/// `feedback` (`"default"` or `(kp, kd)`) and the settling window `settle`
/// (s); `Run.replay` then holds it, and the summary and warnings say how it
/// went. Returns a `crane.Run`, whose audit findings are also warned of
/// as `crane.CraneWarning`s; raises `crane.CraneError` with the tool's
/// message.
#[pyfunction]
#[pyo3(pass_module, signature = (
    model, *, dt=None, tf=None, scheme=None, formulation=None, scenario=None, parameters=None, limits=None,
    replay=false, plant=None, feedback=None, settle=None
))]
#[allow(clippy::too_many_arguments)]
fn run(
    module: &Bound<'_, PyModule>,
    model: &str,
    dt: Option<Number>,
    tf: Option<Number>,
    scheme: Option<&str>,
    formulation: Option<&str>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
    limits: Option<Mapping<'_>>,
    replay: bool,
    plant: Option<Mapping<'_>>,
    feedback: Option<&Bound<'_, PyAny>>,
    settle: Option<Number>,
) -> PyResult<Run> {
    let py = module.py();
    let cranes = Cranes::of_module(module)?;
    let (file, overrides) = job(
        value(dt),
        value(tf),
        scheme,
        formulation,
        scenario,
        parameters.as_deref(),
        limits.as_deref(),
    )?;
    let request = replay_request(replay, plant.as_deref(), feedback, value(settle))?;
    let job = RunJob {
        file,
        overrides,
        replay: request,
    };
    let data = visit_detached(py, &cranes, cranes.run, model, job)?;
    let widths = [
        data.coordinates.len(),
        data.inputs.len(),
        data.multipliers,
        data.ropes.len(),
    ];
    let summary = pythonize::pythonize(py, &data.summary)
        .map_err(|e| CraneError::new_err(format!("summary: {e}")))?
        .cast_into::<PyDict>()
        .map_err(|_| CraneError::new_err("summary: not a dict"))?;
    let replay = match data.replay {
        Some(replay) => Some(replay.into_dict(py, widths)?.unbind()),
        None => None,
    };
    let arrays = data.columns.into_arrays(py, widths)?;
    Ok(Run {
        t: arrays.t.unbind(),
        q: arrays.q.unbind(),
        v: arrays.v.unbind(),
        u: arrays.u.unbind(),
        lambda: arrays.lambda.unbind(),
        tensions: arrays.tensions.unbind(),
        coordinates: data.coordinates,
        inputs: data.inputs,
        ropes: data.ropes,
        summary: summary.unbind(),
        warnings: {
            warn_findings(py, &data.warnings)?;
            data.warnings
        },
        replay,
    })
}

/// The replay `run` asks for: none without `replay=True` (then `plant`,
/// `feedback` and `settle` are refused), else its plant, feedback and
/// settling window.
fn replay_request(
    replay: bool,
    plant: Option<&Bound<'_, PyDict>>,
    feedback: Option<&Bound<'_, PyAny>>,
    settle: Option<f64>,
) -> PyResult<Option<ReplayRequest>> {
    let feedback = feedback.filter(|f| !f.is_none());
    if !replay {
        if plant.is_some() || feedback.is_some() || settle.is_some() {
            return Err(CraneError::new_err(
                "`plant`, `feedback` and `settle` apply only to a replay: add replay=True",
            ));
        }
        return Ok(None);
    }
    let feedback = match feedback {
        None => None,
        Some(value) => {
            let text = if let Ok(text) = value.extract::<String>() {
                text
            } else if let Ok((kp, kd)) = value.extract::<(f64, f64)>() {
                format!("{kp},{kd}")
            } else {
                return Err(CraneError::new_err("feedback: expected \"default\" or a pair (kp, kd)"));
            };
            Some(
                text.parse::<FeedbackSpec>()
                    .map_err(|e| CraneError::new_err(format!("feedback `{text}`: {e}")))?,
            )
        }
    };
    if let Some(settle) = settle
        && !crane_models::study::replay::valid_settle(settle)
    {
        return Err(CraneError::new_err(format!(
            "settle = {settle}: the settling window must be a positive number of seconds, at most {}",
            crane_models::study::replay::MAX_SETTLE
        )));
    }
    Ok(Some(ReplayRequest {
        plant: numbers("plant", plant)?.into_iter().collect(),
        settle,
        feedback,
    }))
}

/// The scenario and the flags of a run or a stepper from the keywords.
#[allow(clippy::too_many_arguments)]
fn job(
    dt: Option<f64>,
    tf: Option<f64>,
    scheme: Option<&str>,
    formulation: Option<&str>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<&Bound<'_, PyDict>>,
    limits: Option<&Bound<'_, PyDict>>,
) -> PyResult<(ScenarioFile, Overrides)> {
    let mut file = scenario_of(scenario)?;
    file.parameters.extend(numbers("parameters", parameters)?);
    file.limits.extend(numbers("limits", limits)?);
    let overrides = Overrides {
        dt,
        tf,
        formulation: formulation
            .map(str::parse)
            .transpose()
            .map_err(|e: study::UnknownFormulation| CraneError::new_err(e.to_string()))?,
        scheme: scheme
            .map(str::parse)
            .transpose()
            .map_err(|e: crane_runtime::scheme::UnknownScheme| CraneError::new_err(e.to_string()))?,
    };
    Ok((file, overrides))
}

/// How often a thread waiting for a job looks for a Ctrl-C.
const SIGNAL_POLL: std::time::Duration = std::time::Duration::from_millis(20);

/// `job` on the crane `model` by `visit`, one of the registry's functions
/// in [`Cranes`], with the GIL released; a model the registry does not have,
/// or the job's failure, as `CraneError`. The job runs on a thread of its
/// own while this one looks for signals every [`SIGNAL_POLL`]: a Ctrl-C
/// cancels the job at its next step or sweep point ([`Cancel`]) and is
/// raised as KeyboardInterrupt, nothing of the job returned.
fn visit_detached<J: Send, O: Send>(
    py: Python<'_>,
    cranes: &Cranes,
    visit: fn(&str, J) -> Option<Result<O, String>>,
    model: &str,
    job: J,
) -> PyResult<O> {
    let cancel = Cancel::default();
    let mut interrupted = None;
    let waiting = std::thread::current();
    let joined = py.detach(|| {
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| {
                let done = cancel.scope(|| visit(model, job));
                waiting.unpark();
                done
            });
            while !worker.is_finished() {
                std::thread::park_timeout(SIGNAL_POLL);
                if interrupted.is_none()
                    && let Err(signal) = Python::attach(|py| py.check_signals())
                {
                    interrupted = Some(signal);
                    cancel.set();
                }
            }
            worker.join()
        })
    });
    let done = joined.unwrap_or_else(|panic| std::panic::resume_unwind(panic));
    if let Some(signal) = interrupted {
        return Err(signal);
    }
    // a Ctrl-C as the job ended: KeyboardInterrupt now, before its result
    // is made into Python objects
    py.check_signals()?;
    done.ok_or_else(|| unknown_model(cranes, model))?
        .map_err(CraneError::new_err)
}

/// The error for a model the registry does not have.
fn unknown_model(cranes: &Cranes, model: &str) -> PyErr {
    let names: Vec<&str> = (cranes.entries)().iter().map(|e| e.name).collect();
    CraneError::new_err(format!("unknown model `{model}`; expected one of {}", names.join(", ")))
}

/// One state of a crane, its tensions with it, whatever its sizes.
struct StateData {
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    u: Vec<f64>,
    lambda: Vec<f64>,
    tensions: Vec<f64>,
}

/// A stepper of any crane behind one interface (a Python class cannot be
/// generic over the crane's sizes).
trait AnyStepper: Send {
    /// One step, and what the step audit found in it, if anything.
    fn step(&mut self) -> Result<Option<String>, String>;
    /// What the audit found at the start (once: then empty).
    fn take_start_findings(&mut self) -> Vec<String>;
    /// The state after the last step.
    fn state(&self) -> StateData;
    /// The time step.
    fn dt(&self) -> f64;
}

/// A crane's stepper (eqs. 22 or the reduced system) behind [`AnyStepper`],
/// with the step audit the FMU runs ([`StepAudit`]).
struct Erased<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> {
    advance: Box<dyn Advance<N, M, A, Model = Mdl> + Send>,
    audit: StepAudit,
    start_findings: Vec<String>,
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> Erased<Mdl, N, M, A> {
    /// The stepper of the crane called `name`, audited from its start.
    fn new(name: &'static str, advance: Box<dyn Advance<N, M, A, Model = Mdl> + Send>) -> Self {
        let (audit, findings) = StepAudit::start(name, advance.model(), advance.state(), advance.path_order_covered());
        Self {
            advance,
            audit,
            start_findings: findings.iter().map(ToString::to_string).collect(),
        }
    }
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> AnyStepper for Erased<Mdl, N, M, A> {
    fn step(&mut self) -> Result<Option<String>, String> {
        let report = self.advance.step().map_err(|e| e.to_string())?;
        let found = self
            .audit
            .step(self.advance.model(), self.advance.state(), report.left_free());
        Ok(found.map(|finding| finding.to_string()))
    }

    fn take_start_findings(&mut self) -> Vec<String> {
        std::mem::take(&mut self.start_findings)
    }

    fn state(&self) -> StateData {
        let state = self.advance.state();
        let mut tensions = vec![0.0; Mdl::INFO.ropes.len()];
        self.advance
            .model()
            .rope_tensions(&state.q, &state.lambda, &mut tensions);
        StateData {
            t: state.t,
            q: state.q.iter().copied().collect(),
            v: state.v.iter().copied().collect(),
            u: state.u.iter().copied().collect(),
            lambda: state.lambda.iter().copied().collect(),
            tensions,
        }
    }

    fn dt(&self) -> f64 {
        self.advance.dt()
    }
}

/// The stepper of one crane, from the start `crane run` takes.
struct StepperJob {
    file: ScenarioFile,
    overrides: Overrides,
}

impl Visit for StepperJob {
    type Output = Result<Box<dyn AnyStepper>, String>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) =
            scenario::build::<C, N, M, A>(Some(&self.file), &self.overrides).map_err(|e| e.to_string())?;
        let start = case.run_start().map_err(|e| e.to_string())?;
        let options = Options::new(settings.dt, case.tf())
            .map_err(|e| e.to_string())?
            .with_scheme(settings.scheme);
        let advance: Box<dyn Advance<N, M, A, Model = C::Model> + Send> = match settings.formulation {
            Formulation::DummyDerivative => {
                dummy_derivative::boxed_stepper(Box::new(case.model), case.path, &start, &options)
                    .map_err(|e| study::StudyError::of_crane(C::NAME, e).to_string())?
            }
            Formulation::StateSelection => {
                state_selection::boxed_stepper(Box::new(case.model), case.path, &start, &options)
                    .map_err(|e| study::StudyError::of_crane(C::NAME, e).to_string())?
            }
            Formulation::Redundant => Box::new(
                Stepper::new(Redundant::new(Box::new(case.model), case.path), &start, &options)
                    .map_err(|e| e.to_string())?,
            ),
            Formulation::Minimal => {
                return Err(
                    "a stepper runs the redundant, the dummy-derivative and the state-selection formulation; the \
                     minimal one runs whole: run(..., formulation=\"minimal\")"
                        .to_string(),
                );
            }
            Formulation::StableInversion => {
                return Err(
                    "a stepper cannot know the path ahead, which stable inversion needs (it acts before the load \
                     moves): it runs whole, run(..., formulation=\"stable-inversion\"); a stepper of eqs. (22a-d) \
                     is formulation=\"redundant\""
                        .to_string(),
                );
            }
        };
        Ok(Box::new(Erased::new(C::NAME, advance)))
    }
}

/// A crane one step at a time, for a control loop: `step()` advances one
/// step and returns the state, `step_to(t)` advances to the step at `t`;
/// `state` is the state after the last step (the start before the first).
/// A state is a dict of `t` and numpy arrays `q`, `v`, `u`, `lambda_`,
/// `tensions`. The steps are those of `run` with the same keywords, bit for
/// bit.
///
/// It may be used from any thread, one call at a time (`step_to` releases
/// the interpreter while it steps: other threads run, and a call on the same
/// stepper meanwhile raises).
#[pyclass(name = "Stepper", module = "crane")]
struct PyStepper {
    /// Behind a lock, so that the stepper may move between threads.
    inner: std::sync::Mutex<Box<dyn AnyStepper>>,
    /// What the step audit found so far (also warned of as
    /// `CraneWarning`s as found).
    #[pyo3(get)]
    warnings: Vec<String>,
}

impl PyStepper {
    /// What the audit found in a step, if anything: warned of, and kept.
    fn found(&mut self, py: Python<'_>, finding: Option<String>) -> PyResult<()> {
        if let Some(finding) = finding {
            warn_findings(py, std::slice::from_ref(&finding))?;
            self.warnings.push(finding);
        }
        Ok(())
    }

    /// The stepper (a call that panicked inside it left it as it was).
    fn stepper(&self) -> std::sync::MutexGuard<'_, Box<dyn AnyStepper>> {
        self.inner.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn state_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let state = self.stepper().state();
        let dict = PyDict::new(py);
        dict.set_item("t", state.t)?;
        dict.set_item("q", PyArray1::from_vec(py, state.q))?;
        dict.set_item("v", PyArray1::from_vec(py, state.v))?;
        dict.set_item("u", PyArray1::from_vec(py, state.u))?;
        dict.set_item("lambda_", PyArray1::from_vec(py, state.lambda))?;
        dict.set_item("tensions", PyArray1::from_vec(py, state.tensions))?;
        Ok(dict)
    }
}

/// The most steps one `Stepper.step_to` takes (about a quarter of an hour
/// at a microsecond a step): `step_to(1e9)` at dt = 0.01 s ran without end,
/// holding the interpreter.
const MAX_STEP_TO: usize = 1_000_000_000;

/// Steps between two checks for Ctrl-C in `Stepper.step_to`, taken without
/// the interpreter (a check and the release cost about as much as a step).
const SIGNAL_STEPS: usize = 1024;

#[pymethods]
impl PyStepper {
    /// Pickling (and copying): refused with the reason.
    fn __reduce__(&self) -> PyResult<()> {
        Err(pyo3::exceptions::PyTypeError::new_err(
            "a Stepper does not pickle: it holds a run under way (its scheme's history of past steps and Newton's \
             state), not data; pickle the states it returned, or make a new Stepper with the same keywords and \
             step it to the same time",
        ))
    }

    /// `Stepper(model, dt=..., ...)`: the same as `stepper(model, ...)`, with
    /// the cranes of the module the class belongs to.
    #[new]
    #[pyo3(signature = (model, *, dt=None, scheme=None, formulation=None, scenario=None, parameters=None))]
    fn new(
        py: Python<'_>,
        model: &str,
        dt: Option<Number>,
        scheme: Option<&str>,
        formulation: Option<&str>,
        scenario: Option<&Bound<'_, PyAny>>,
        parameters: Option<Mapping<'_>>,
    ) -> PyResult<Self> {
        let cranes = MODULE_CRANES
            .get()
            .copied()
            .ok_or_else(|| CraneError::new_err("the module of Stepper has no registry: import it first"))?;
        PyStepper::made(py, &cranes, model, dt, scheme, formulation, scenario, parameters)
    }

    /// One step; returns the new state. Raises `CraneError` if the step
    /// fails (the stepper is then left at the last good state).
    fn step<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let found = self.stepper().step().map_err(CraneError::new_err)?;
        self.found(py, found)?;
        self.state_dict(py)
    }

    /// Advance to the step at time `t` (a step time `t0 + k dt` not before
    /// the current one, at most [`MAX_STEP_TO`] steps on); returns the state
    /// there. Ctrl-C stops it between steps (`KeyboardInterrupt`, the
    /// stepper at the last step taken).
    fn step_to<'py>(&mut self, py: Python<'py>, t: f64) -> PyResult<Bound<'py, PyDict>> {
        // (the lock of the one field, so that the warnings may grow meanwhile)
        let mut stepper = self.inner.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let (now, dt) = (stepper.state().t, stepper.dt());
        let steps = ((t - now) / dt).round();
        if !(steps >= 0.0 && (t - now - steps * dt).abs() <= 1e-9 * dt * steps.max(1.0)) {
            return Err(CraneError::new_err(format!(
                "t = {t} s is not a step time at or after t = {now} s (the steps are {dt} s apart)"
            )));
        }
        if steps > MAX_STEP_TO as f64 {
            return Err(CraneError::new_err(format!(
                "t = {t} s is {steps:.3e} steps of {dt} s on: step_to takes at most {MAX_STEP_TO:e} steps per call"
            )));
        }
        // chunks of steps without the interpreter, so that other threads
        // run meanwhile; Ctrl-C checked between them (another thread's call
        // on this stepper meanwhile finds it borrowed and raises)
        let inner: &mut dyn AnyStepper = &mut **stepper;
        let mut left = steps as usize;
        let mut found = Vec::new();
        while left > 0 {
            let chunk = left.min(SIGNAL_STEPS);
            let stepped = py.detach(|| {
                for _ in 0..chunk {
                    found.extend(inner.step()?);
                }
                Ok::<(), String>(())
            });
            // what the audit found is warned of even where a step failed
            for finding in found.drain(..) {
                warn_findings(py, std::slice::from_ref(&finding))?;
                self.warnings.push(finding);
            }
            stepped.map_err(CraneError::new_err)?;
            left -= chunk;
            py.check_signals()?;
        }
        drop(stepper);
        self.state_dict(py)
    }

    /// The state after the last step (the start before the first).
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.state_dict(py)
    }

    /// The time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.stepper().dt()
    }
}

/// A stepper of `model` from the start `run` takes, with the same keywords
/// (`dt`, `scheme`, `formulation`, `scenario`, `parameters`): a
/// `Stepper`. Raises `CraneError` with the tool's message.
#[pyfunction]
#[pyo3(pass_module, signature = (model, *, dt=None, scheme=None, formulation=None, scenario=None, parameters=None))]
fn stepper(
    module: &Bound<'_, PyModule>,
    model: &str,
    dt: Option<Number>,
    scheme: Option<&str>,
    formulation: Option<&str>,
    scenario: Option<&Bound<'_, PyAny>>,
    parameters: Option<Mapping<'_>>,
) -> PyResult<PyStepper> {
    let cranes = Cranes::of_module(module)?;
    PyStepper::made(
        module.py(),
        &cranes,
        model,
        dt,
        scheme,
        formulation,
        scenario,
        parameters,
    )
}

impl PyStepper {
    /// A stepper of `model` of the registry `cranes` (see [`stepper`]).
    #[allow(clippy::too_many_arguments)]
    fn made(
        py: Python<'_>,
        cranes: &Cranes,
        model: &str,
        dt: Option<Number>,
        scheme: Option<&str>,
        formulation: Option<&str>,
        scenario: Option<&Bound<'_, PyAny>>,
        parameters: Option<Mapping<'_>>,
    ) -> PyResult<PyStepper> {
        let (file, overrides) = job(
            value(dt),
            None,
            scheme,
            formulation,
            scenario,
            parameters.as_deref(),
            None,
        )?;
        let mut inner = (cranes.stepper)(model, StepperJob { file, overrides })
            .ok_or_else(|| unknown_model(cranes, model))?
            .map_err(CraneError::new_err)?;
        let warnings = inner.take_start_findings();
        warn_findings(py, &warnings)?;
        Ok(PyStepper {
            inner: std::sync::Mutex::new(inner),
            warnings,
        })
    }
}

/// The Python source of `PACKAGE.distributed`: sweeps on a Dask cluster.
const DISTRIBUTED: &str = include_str!("python/distributed.py");

/// Add `package.distributed` (sweeps on a Dask cluster, in Python: it
/// imports dask only when used) as an attribute of `module` and of the
/// package, and to `sys.modules`, so that `from crane import distributed`
/// and `import crane.distributed` find it, and the workers of a cluster
/// unpickle its task function by name.
fn add_distributed(module: &Bound<'_, PyModule>, package: &str) -> PyResult<()> {
    let py = module.py();
    let name = format!("{package}.distributed");
    let code = std::ffi::CString::new(DISTRIBUTED).map_err(|e| CraneError::new_err(e.to_string()))?;
    let file =
        std::ffi::CString::new(format!("{package}/distributed.py")).map_err(|e| CraneError::new_err(e.to_string()))?;
    let module_name = std::ffi::CString::new(name.clone()).map_err(|e| CraneError::new_err(e.to_string()))?;
    let distributed = PyModule::from_code(py, &code, &file, &module_name)?;
    distributed.setattr("_PACKAGE", package)?;
    // the grid's order is `sweep`'s own, from the one place that knows it
    distributed.setattr("_grid_points", wrap_pyfunction!(plan::grid_points, module)?)?;
    module.add("distributed", &distributed)?;
    let modules = py.import("sys")?.getattr("modules")?;
    modules.set_item(&name, &distributed)?;
    if let Ok(parent) = modules.get_item(package)
        && !parent.is(module)
    {
        parent.setattr("distributed", &distributed)?;
    }
    Ok(())
}

/// Fill `module` with the cranes of registry `R`: `models()`, `run(...)`,
/// `stepper(...)`, `fastest(...)`, `sweep(...)`, `convergence(...)`, the
/// classes `Run` and `Stepper` and the exception `CraneError`. What
/// [`export_module!`](crate::export_module) calls.
pub fn add_to_module<R: Registry + Default>(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    // numpy's C API now, on import: fetched first at a run's end, a Ctrl-C
    // pending then made its import fail inside the numpy crate, a panic
    PyArray1::<f64>::zeros(py, 0, false);
    module.add("CraneError", py.get_type::<CraneError>())?;
    module.add("CraneWarning", py.get_type::<CraneWarning>())?;
    module.add_class::<Run>()?;
    module.add("_cranes", CranesObject(Cranes::of::<R>()))?;
    // (set once: an import of the module again brings the same registry)
    let _ = MODULE_CRANES.set(Cranes::of::<R>());
    module.add_function(wrap_pyfunction!(models, module)?)?;
    module.add_function(wrap_pyfunction!(run, module)?)?;
    module.add_class::<PyStepper>()?;
    module.add_function(wrap_pyfunction!(stepper, module)?)?;
    module.add_function(wrap_pyfunction!(plan::fastest, module)?)?;
    module.add_function(wrap_pyfunction!(plan::sweep, module)?)?;
    module.add_function(wrap_pyfunction!(plan::sweep_points, module)?)?;
    module.add_function(wrap_pyfunction!(plan::convergence, module)?)?;
    // the classes under the package's own name (`my_cranes.Run` for a
    // user's module, which pickling then finds there, not in `crane`): the
    // package of the module (`crane` of `crane.crane`)
    let name: String = module.name()?.extract()?;
    let package = name.split_once('.').map_or(name.as_str(), |(package, _)| package);
    for class in ["CraneError", "CraneWarning", "Run", "Stepper"] {
        module.getattr(class)?.setattr("__module__", &package)?;
    }
    add_distributed(module, package)?;
    // the version of the library the module was built with (in `__all__`
    // too: a wheel's package re-exports the module by `import *`)
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add(
        "__all__",
        [
            "__version__",
            "CraneError",
            "CraneWarning",
            "Run",
            "Stepper",
            "models",
            "run",
            "stepper",
            "fastest",
            "sweep",
            "sweep_points",
            "convergence",
        ],
    )?;
    Ok(())
}

/// Make this crate a Python module of the cranes of a registry:
/// `export_module!(registry = MyCranes, name = "my_cranes")` defines the
/// module's entry point (`PyInit_my_cranes`), which fills it with
/// [`add_to_module`]. The crate must be a `cdylib` that depends on this
/// facade under the name `crane` with its feature `python`; maturin builds
/// the wheel (`module-name = "my_cranes"` in `pyproject.toml`).
#[macro_export]
macro_rules! export_module {
    (registry = $registry:ty, name = $name:literal $(,)?) => {
        /// Inverse dynamics of underactuated cranes: `models()` lists the
        /// cranes, `run(model, ...)` runs one and returns a `Run` of numpy
        /// arrays, its summary and what the audit found; failures raise
        /// `CraneError`.
        #[$crate::python::pyo3::pymodule]
        #[pyo3(crate = "crane::python::pyo3", name = $name)]
        fn __crane_python_module(
            module: &$crate::python::pyo3::Bound<'_, $crate::python::pyo3::types::PyModule>,
        ) -> $crate::python::pyo3::PyResult<()> {
            $crate::python::add_to_module::<$registry>(module)
        }
    };
}
