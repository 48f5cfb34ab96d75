//! One FMU instance: the FMI 2.0 co-simulation state machine around the
//! stepper of the crane's default formulation, in safe Rust (the C entry points in
//! `ffi` only translate pointers and statuses).
//!
//! `exit_initialization_mode` builds the crane from the parameters, the
//! path, the consistent start and the stepper (all allocation happens
//! here); `do_step(t, h)` advances `h / dt` internal steps and writes the
//! outputs, without allocating.

use crane_models::study::audit::{Finding, Severity, StepAudit, unresolved_ramp};
use crane_models::study::{Formulation, RunSpec, SpecError};
use crane_models::{Case, Crane, Path, PathSpec, Profile};
use crane_runtime::options::steps_in;
use crane_runtime::problem::ServoTarget;
use crane_runtime::redundant::{Redundant, RedundantStepper};
use crane_runtime::stable_inversion::Playback;
use crane_runtime::{Advance, CraneModel, Options, Scheme, Stepper, state_selection};
use nalgebra::SVector;

use crate::description::default_experiment;
use crate::start::Start;
use crate::variables::{
    Causality, EXTERNAL_PATH, PathChoice, Role, SPLINE_PATH, TableError, Variable, path_help, path_of_code, status,
    variables,
};

/// What an instance can be asked to do, whatever its crane: the object the
/// C entry points hold.
pub trait Component {
    /// Set Real variables.
    fn set_real(&mut self, vr: &[u32], values: &[f64]) -> Result<(), String>;
    /// Get Real variables.
    fn get_real(&self, vr: &[u32], values: &mut [f64]) -> Result<(), String>;
    /// Set Integer variables.
    fn set_integer(&mut self, vr: &[u32], values: &[i32]) -> Result<(), String>;
    /// Get Integer variables.
    fn get_integer(&self, vr: &[u32], values: &mut [i32]) -> Result<(), String>;
    /// `fmi2SetupExperiment`: the start time.
    fn setup_experiment(&mut self, start_time: f64) -> Result<(), String>;
    /// `fmi2EnterInitializationMode`.
    fn enter_initialization_mode(&mut self) -> Result<(), String>;
    /// `fmi2ExitInitializationMode`: build the crane, its start and stepper.
    fn exit_initialization_mode(&mut self) -> Result<(), String>;
    /// `fmi2DoStep`: advance from `t` by `h`, a whole multiple of `dt`.
    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String>;
    /// `fmi2Terminate`.
    fn terminate(&mut self) -> Result<(), String>;
    /// `fmi2Reset`: back to the state after instantiation.
    fn reset(&mut self);
    /// What the audit found in the last call, if it is a warning (the call
    /// then returns `fmi2Warning` and logs it); taken once.
    fn take_warning(&mut self) -> Option<String>;
    /// Time of the last state.
    fn time(&self) -> f64;
    /// Whether the instance was terminated.
    fn terminated(&self) -> bool;
}

/// Where an instance is in the FMI 2.0 co-simulation state machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Instantiated,
    Initialization,
    Stepping,
    Terminated,
    /// After an error: only reset, get and free.
    Failed,
}

/// The quintic through `(gamma, gamma', gamma'')` at `ta` and at `tb`,
/// evaluated at `t`: the targets of the internal steps of an external step.
fn hermite<const A: usize>(ta: f64, a: &ServoTarget<A>, tb: f64, b: &ServoTarget<A>, t: f64) -> ServoTarget<A> {
    let h = tb - ta;
    let s = (t - ta) / h;
    let mut out = [SVector::zeros(); 3];
    for k in 0..A {
        let (c0, c1, c2) = (a[0][k], a[1][k] * h, 0.5 * a[2][k] * h * h);
        let p = b[0][k] - (c0 + c1 + c2);
        let v = b[1][k] * h - (c1 + 2.0 * c2);
        let acc = b[2][k] * h * h - 2.0 * c2;
        let c = [
            c0,
            c1,
            c2,
            10.0 * p - 4.0 * v + 0.5 * acc,
            -15.0 * p + 7.0 * v - acc,
            6.0 * p - 3.0 * v + 0.5 * acc,
        ];
        out[0][k] = c.iter().rev().fold(0.0, |acc, &ci| acc * s + ci);
        out[1][k] = (1..6).rev().fold(0.0, |acc, i| acc * s + i as f64 * c[i]) / h;
        out[2][k] = (2..6).rev().fold(0.0, |acc, i| acc * s + (i * (i - 1)) as f64 * c[i]) / (h * h);
    }
    out
}

/// The stepper of a run, which owns its model: eqs. (22a-d), which also
/// follow an external target, or on a built-in move the crane's default
/// formulation (dummy derivatives, state selection, or the bounded solution
/// by stable inversion played back).
enum Stepping<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> {
    Redundant(Box<RedundantStepper<Box<Mdl>, Path<A>, N, M, A>>),
    Reduced(Box<dyn Advance<N, M, A, Model = Mdl>>),
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> Stepping<Mdl, N, M, A> {
    fn advance(&self) -> &dyn Advance<N, M, A, Model = Mdl> {
        match self {
            Stepping::Redundant(stepper) => stepper.as_ref(),
            Stepping::Reduced(stepper) => stepper.as_ref(),
        }
    }
}

/// A running crane.
struct Run<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> {
    stepper: Stepping<Mdl, N, M, A>,
    /// The external target at the last state, if the path is external.
    external: Option<ServoTarget<A>>,
    /// Rope tensions (one per rope).
    tensions: Vec<f64>,
    /// The audit of the states as they come.
    audit: StepAudit,
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> Run<Mdl, N, M, A> {
    /// The run, and what the audit finds at its start.
    fn new(
        name: &'static str,
        stepper: Stepping<Mdl, N, M, A>,
        external: Option<ServoTarget<A>>,
    ) -> (Self, Vec<Finding>) {
        let advance = stepper.advance();
        let (audit, findings) = StepAudit::start(name, advance.model(), advance.state(), advance.path_order_covered());
        let run = Self {
            stepper,
            external,
            tensions: vec![0.0; Mdl::INFO.ropes.len()],
            audit,
        };
        (run, findings)
    }
}

/// An FMU instance of crane `C`.
pub struct Instance<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    /// The run it starts from (the spline of a spline move is its).
    start: Start<A>,
    table: Vec<Variable>,
    defaults: (Vec<f64>, [i32; 3]),
    reals: Vec<f64>,
    /// `scheme`, `path`, `status`.
    integers: [i32; 3],
    /// A warning of the audit not yet returned ([`Component::take_warning`]).
    warning: Option<String>,
    /// Value references of the external target, `[k][order]` (found once:
    /// `do_step` reads them on every step).
    targets: Vec<[usize; 3]>,
    mode: Mode,
    start_time: f64,
    run: Option<Run<C::Model, N, M, A>>,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> Instance<C, N, M, A> {
    /// A new instance of the crane's default run, every variable at its
    /// start value.
    pub fn new() -> Result<Self, TableError> {
        Self::starting_from(Start::default_for::<C, N, M>())
    }

    /// A new instance of the run `start` (a packaged scenario's), every
    /// variable at its start value.
    pub fn starting_from(start: Start<A>) -> Result<Self, TableError> {
        let table = variables::<C, N, M, A>(&start)?;
        let reals: Vec<f64> = table.iter().filter(|v| !v.integer).map(|v| v.start).collect();
        let mut integers = [0; 3];
        for v in table.iter().filter(|v| v.integer) {
            integers[v.value_reference as usize] = v.start as i32;
        }
        let mut targets = vec![[0; 3]; A];
        for v in &table {
            if let Role::Target(k, order) = v.role {
                targets[k][order] = v.value_reference as usize;
            }
        }
        Ok(Self {
            targets,
            defaults: (reals.clone(), integers),
            table,
            reals,
            integers,
            mode: Mode::Instantiated,
            start_time: default_experiment::<C, N, M, A>(&start).0,
            run: None,
            warning: None,
            start,
        })
    }

    /// The Real variable with value reference `vr`.
    /// The table lists the Reals first, in value-reference order, so the
    /// lookup is an index (`fmi2SetReal` of the external target runs every
    /// step).
    fn real_variable(&self, vr: u32) -> Result<&Variable, String> {
        self.table
            .get(vr as usize)
            .filter(|v| !v.integer && v.value_reference == vr)
            .ok_or_else(|| format!("no Real variable has value reference {vr}"))
    }

    /// The Real variable playing `role`, its value.
    fn value(&self, role: Role) -> f64 {
        self.table
            .iter()
            .find(|v| v.role == role)
            .map_or(f64::NAN, |v| self.reals[v.value_reference as usize])
    }

    /// The external target in the inputs.
    fn target(&self) -> ServoTarget<A> {
        std::array::from_fn(|order| SVector::from_fn(|k, _| self.reals[self.targets[k][order]]))
    }

    /// Whether a variable of `causality` may be set now.
    fn settable(&self, causality: Causality, name: &str) -> Result<(), String> {
        match (causality, self.mode) {
            (_, Mode::Failed | Mode::Terminated) => Err(format!(
                "`{name}` cannot be set after an error or fmi2Terminate (fmi2Reset first)"
            )),
            (Causality::Output, _) => Err(format!("`{name}` is an output and cannot be set")),
            (Causality::Parameter, Mode::Stepping) => Err(format!(
                "parameter `{name}` can only be set before fmi2ExitInitializationMode"
            )),
            _ => Ok(()),
        }
    }

    /// The run the variables describe, checked: the crane's parameters, the
    /// built-in move, the spline move timed anew or (path = external) a
    /// path at rest at the external target, the start run's start guess and
    /// formulation, `dt` and the scheme.
    fn spec(&self) -> Result<(RunSpec<A>, Option<ServoTarget<A>>), String> {
        let info = <C::Model as CraneModel<N, M, A>>::INFO;
        let mut spec = self.start.spec.clone();
        // how long the start run goes on after its move (a stable
        // inversion's post-actuation is found within it)
        let tail = (spec.tf - spec.path.t1).max(0.0);
        spec.parameters = info
            .parameters
            .iter()
            .enumerate()
            .map(|(k, name)| (name.to_string(), self.value(Role::Parameter(k))))
            .collect();
        spec.dt = self.value(Role::Dt);
        let code = self.integers[0];
        spec.scheme =
            Scheme::from_code(code).ok_or_else(|| format!("scheme = {code}: expected {}", Scheme::code_help()))?;
        let position = |role: fn(usize) -> Role| SVector::<f64, A>::from_fn(|k, _| self.value(role(k)));
        let t0 = self.value(Role::T0);
        let external = match path_of_code(self.integers[1]) {
            None => {
                return Err(format!(
                    "path = {}: expected {}",
                    self.integers[1],
                    path_help(self.spline().is_some())
                ));
            }
            Some(PathChoice::External) => {
                let target = self.target();
                if target[1].amax() != 0.0 || target[2].amax() != 0.0 {
                    return Err(format!(
                        "path = {EXTERNAL_PATH} (external): the run starts at rest; set gamma_<x>_d and gamma_<x>_dd \
                         to 0 before fmi2ExitInitializationMode"
                    ));
                }
                // at rest at the target from the start time on: a move from
                // the target to itself (the move's own t0 plays no part)
                let t0 = self.start_time;
                spec.path = PathSpec {
                    profile: Profile::Poly9,
                    t0,
                    t1: t0 + 1.0,
                    start: target[0],
                    end: target[0],
                };
                Some(target)
            }
            Some(PathChoice::Move(kind)) => {
                let profile = kind.profile(Some(self.value(Role::Tau0))).map_err(|e| e.to_string())?;
                let t1 = t0 + self.value(Role::Duration);
                spec.path = PathSpec {
                    profile,
                    t0,
                    t1,
                    start: position(Role::Start),
                    end: position(Role::End),
                };
                None
            }
            Some(PathChoice::Spline) => {
                let Some(profile) = self.spline() else {
                    return Err(format!(
                        "path = {SPLINE_PATH} (the spline move): this FMU has none; package one with `crane fmu \
                         MODEL --scenario FILE` from a scenario with trajectory = \"spline\""
                    ));
                };
                spec.path.profile = profile;
                spec.path.t0 = t0;
                spec.path.t1 = t0 + self.value(Role::Duration);
                None
            }
        };
        spec.tf = spec.path.t1 + if external.is_some() { 0.0 } else { tail };
        Ok((spec, external))
    }

    /// The spline move of the start run, if it has one.
    fn spline(&self) -> Option<Profile> {
        matches!(self.start.spec.path.profile, Profile::Spline(_)).then(|| self.start.spec.path.profile.clone())
    }

    /// The crane, path, start and stepper from the variables: the start of
    /// `crane run` where it holds (the default move), else the static
    /// equilibrium from the same guess; and what the audit finds at the start.
    fn build(&self) -> Result<(Run<C::Model, N, M, A>, Vec<Finding>), String> {
        let (spec, external) = self.spec()?;
        let (case, settings) = spec.build::<C, N, M>().map_err(|e| match e {
            SpecError::Path(e) if external.is_some() => format!("the external target: {e}"),
            SpecError::Path(e) => format!("the built-in move: {e}"),
            SpecError::Time(e) => format!("`dt`: {e}"),
            SpecError::EndBeforeStart { tf, t0 } => {
                format!("the built-in move: `duration` = {} s must be positive", tf - t0)
            }
            other => other.to_string(),
        })?;
        if settings.formulation == Formulation::StableInversion && external.is_none() {
            let dt = settings.dt;
            let (run, mut findings) = Run::new(C::NAME, Stepping::Reduced(self.bounded(case, dt)?), None);
            // bounded whatever the internal dynamics: not warned of them,
            // as `crane run`'s audit does not warn a run by stable inversion
            findings.retain(|f| !matches!(f, Finding::UnstableInternalDynamics { .. }));
            findings.extend(unresolved_ramp(spec.path.profile.tau0(), dt));
            return Ok((run, findings));
        }
        let options = Options::stepping(settings.dt)
            .map_err(|e| format!("`dt`: {e}"))?
            .with_scheme(settings.scheme);
        let start = case
            .consistent_start(self.start_time)
            .map_err(|e| format!("no consistent start at t = {}: {e}", self.start_time))?;
        // an external target gives the path's derivatives up to gamma'' only:
        // the reduced system, which needs them up to the crane's path order,
        // is replaced by eqs. (22a-d) where those reduce it (path order 4 at
        // most: the scheme's discretisation in place of the higher ones)
        let order = <C::Model as CraneModel<N, M, A>>::STRUCTURE.map_or(0, |s| s.path_order(A));
        let reduced = matches!(
            settings.formulation,
            Formulation::DummyDerivative | Formulation::StateSelection
        ) && !(external.is_some() && order <= 4);
        let stepper =
            if reduced {
                if external.is_some() {
                    return Err(format!(
                        "path = {EXTERNAL_PATH} (external) gives gamma, gamma' and gamma'' only, but the inputs of {} \
                     need the path's derivatives up to order {order}: use a built-in move",
                        C::NAME
                    ));
                }
                let stepper = state_selection::boxed_stepper(Box::new(case.model), case.path, &start, &options)
                    .map_err(|error| match error {
                        crane_runtime::Error::NoDummyDerivatives { reason, .. } => {
                            format!("{} has no dummy-derivative formulation: {reason}", C::NAME)
                        }
                        error => error.to_string(),
                    })?;
                Stepping::Reduced(stepper)
            } else {
                Stepping::Redundant(Box::new(
                    Stepper::new(Redundant::new(Box::new(case.model), case.path), &start, &options)
                        .map_err(|e| e.to_string())?,
                ))
            };
        let (run, mut findings) = Run::new(C::NAME, stepper, external);
        // a built-in move's ramps the step cannot resolve (an external
        // target has no ramps known in advance)
        let ramp = spec.path.profile.tau0().filter(|_| run.external.is_none());
        findings.extend(unresolved_ramp(ramp, settings.dt));
        Ok((run, findings))
    }

    /// The bounded solution of `case` (a built-in move) by stable inversion
    /// on steps of `dt`, played back from the start time: the solution acts
    /// from `t0 - T_pre`, and a start time after that, or not a whole number
    /// of steps before it, is refused with the time to start at.
    fn bounded(&self, case: Case<C, N, M, A>, dt: f64) -> Result<Box<dyn Advance<N, M, A, Model = C::Model>>, String> {
        let options = Options::new(dt, case.tf()).map_err(|e| format!("`dt`: {e}"))?;
        let start = case
            .run_start()
            .map_err(|e| format!("no consistent start at t = {}: {e}", case.t0()))?;
        let inversion = case
            .simulate_stable_inversion(&start, &options)
            .map_err(|e| e.to_string())?;
        let first = inversion.solution.states.first().map_or(case.t0(), |s| s.t);
        let lead = (first - self.start_time) / dt;
        if lead < -1e-9 || (lead - lead.round()).abs() > 1e-6 {
            return Err(format!(
                "the bounded inputs of {} by stable inversion act from t = {first} s, {} s before the move \
                 (pre-actuation): set the start time to {first} s (t0 - T_pre: the default experiment's for the \
                 default t0), or earlier by whole steps of dt = {dt} s; it is {} s",
                C::NAME,
                inversion.t_pre,
                self.start_time
            ));
        }
        let playback = Playback::new(Box::new(case.model), inversion.solution, lead.round() as usize)
            .map_err(|e| e.to_string())?;
        Ok(Box::new(playback))
    }

    /// Copy the last state into the outputs.
    fn write_outputs(&mut self) {
        let Some(run) = self.run.as_mut() else { return };
        let stepper = run.stepper.advance();
        let state = *stepper.state();
        stepper
            .model()
            .rope_tensions(&state.q, &state.lambda, &mut run.tensions);
        for v in &self.table {
            let value = match v.role {
                Role::Input(k) => state.u[k],
                Role::Coordinate(k) => state.q[k],
                Role::Multiplier(k) => state.lambda[k],
                Role::Tension(k) => run.tensions[k],
                _ => continue,
            };
            self.reals[v.value_reference as usize] = value;
        }
    }

    /// `do_step` once the checks passed.
    fn advance(&mut self, t: f64, h: f64) -> Result<(), String> {
        let external = self.run.as_ref().is_some_and(|r| r.external.is_some());
        let target_b = if external { self.target() } else { [SVector::zeros(); 3] };
        let run = self
            .run
            .as_mut()
            .ok_or("fmi2DoStep before fmi2ExitInitializationMode")?;
        if !(t.is_finite() && h.is_finite()) {
            return Err(format!(
                "fmi2DoStep at t = {t} with h = {h}: the communication point and step must be finite"
            ));
        }
        if !(h > 0.0) {
            return Err(format!("communication step h = {h} s must be positive"));
        }
        let now = run.stepper.advance().state().t;
        let scale = 1.0f64.max(now.abs()).max(h.abs());
        if !((t - now).abs() <= 1e-9 * scale) {
            return Err(format!("fmi2DoStep at t = {t}, but the instance is at t = {now}"));
        }
        let dt = run.stepper.advance().dt();
        let k = match steps_in(h, dt) {
            Ok(k) => k,
            Err(_) => {
                return Err(format!(
                    "communication step h = {h} s is not a whole multiple of dt = {dt} s"
                ));
            }
        };
        let tb = t + h;
        for i in 1..=k {
            let result = match (&mut run.stepper, &run.external) {
                (Stepping::Redundant(stepper), Some(target_a)) => {
                    let ti = stepper.next_time();
                    let target = if i == k {
                        target_b
                    } else {
                        hermite(t, target_a, tb, &target_b, ti)
                    };
                    stepper.step_to(ti, &target)
                }
                (Stepping::Redundant(stepper), None) => stepper.step(),
                (Stepping::Reduced(stepper), _) => stepper.step(),
            };
            let report = result.map_err(|e| e.to_string())?;
            let stepper = run.stepper.advance();
            if let Some(finding) = run.audit.step(stepper.model(), stepper.state(), report.left_free()) {
                if finding.severity() == Severity::Error {
                    return Err(finding.to_string());
                }
                self.integers[2] = self.integers[2].max(status::WARNING);
                self.warning = Some(match self.warning.take() {
                    Some(earlier) => format!("{earlier}; {finding}"),
                    None => finding.to_string(),
                });
            }
        }
        if run.external.is_some() {
            run.external = Some(target_b);
        }
        self.write_outputs();
        Ok(())
    }
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> Component for Instance<C, N, M, A> {
    fn set_real(&mut self, vr: &[u32], values: &[f64]) -> Result<(), String> {
        for (&r, &value) in vr.iter().zip(values) {
            let v = self.real_variable(r)?;
            self.settable(v.causality, &v.name)?;
            if !value.is_finite() {
                return Err(format!("`{}` = {value}: not a finite number", v.name));
            }
            self.reals[r as usize] = value;
        }
        Ok(())
    }

    fn get_real(&self, vr: &[u32], values: &mut [f64]) -> Result<(), String> {
        for (&r, value) in vr.iter().zip(values.iter_mut()) {
            *value = *self
                .reals
                .get(r as usize)
                .ok_or_else(|| format!("no Real variable has value reference {r}"))?;
        }
        Ok(())
    }

    fn set_integer(&mut self, vr: &[u32], values: &[i32]) -> Result<(), String> {
        for (&r, &value) in vr.iter().zip(values) {
            let v = self
                .table
                .iter()
                .find(|v| v.integer && v.value_reference == r)
                .ok_or_else(|| format!("no Integer variable has value reference {r}"))?;
            self.settable(v.causality, &v.name)?;
            self.integers[r as usize] = value;
        }
        Ok(())
    }

    fn get_integer(&self, vr: &[u32], values: &mut [i32]) -> Result<(), String> {
        for (&r, value) in vr.iter().zip(values.iter_mut()) {
            *value = *self
                .integers
                .get(r as usize)
                .ok_or_else(|| format!("no Integer variable has value reference {r}"))?;
        }
        Ok(())
    }

    fn setup_experiment(&mut self, start_time: f64) -> Result<(), String> {
        if self.mode != Mode::Instantiated {
            return Err("fmi2SetupExperiment must come right after fmi2Instantiate (or fmi2Reset)".into());
        }
        if !start_time.is_finite() {
            return Err(format!("start time {start_time} is not finite"));
        }
        self.start_time = start_time;
        Ok(())
    }

    fn enter_initialization_mode(&mut self) -> Result<(), String> {
        if self.mode != Mode::Instantiated {
            return Err("fmi2EnterInitializationMode twice, or after initialisation".into());
        }
        self.mode = Mode::Initialization;
        Ok(())
    }

    fn exit_initialization_mode(&mut self) -> Result<(), String> {
        if self.mode != Mode::Initialization {
            return Err("fmi2ExitInitializationMode without fmi2EnterInitializationMode".into());
        }
        match self.build() {
            Ok((run, findings)) => {
                self.run = Some(run);
                self.mode = Mode::Stepping;
                self.write_outputs();
                if !findings.is_empty() {
                    self.integers[2] = status::WARNING;
                    let findings: Vec<String> = findings.iter().map(|f| f.to_string()).collect();
                    self.warning = Some(findings.join("; "));
                }
                Ok(())
            }
            Err(e) => {
                self.mode = Mode::Failed;
                self.integers[2] = status::ERROR;
                Err(e)
            }
        }
    }

    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        if self.mode != Mode::Stepping {
            return Err(
                "fmi2DoStep is only possible after fmi2ExitInitializationMode and before an error or fmi2Terminate"
                    .into(),
            );
        }
        let result = self.advance(t, h);
        if result.is_err() {
            self.mode = Mode::Failed;
            self.integers[2] = status::ERROR;
        }
        result
    }

    fn terminate(&mut self) -> Result<(), String> {
        self.mode = Mode::Terminated;
        Ok(())
    }

    fn reset(&mut self) {
        self.run = None;
        self.reals.copy_from_slice(&self.defaults.0);
        self.integers = self.defaults.1;
        self.warning = None;
        self.mode = Mode::Instantiated;
        self.start_time = default_experiment::<C, N, M, A>(&self.start).0;
    }

    fn time(&self) -> f64 {
        self.run
            .as_ref()
            .map_or(self.start_time, |r| r.stepper.advance().state().t)
    }

    fn terminated(&self) -> bool {
        self.mode == Mode::Terminated
    }

    fn take_warning(&mut self) -> Option<String> {
        self.warning.take()
    }
}
