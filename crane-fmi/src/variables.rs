//! The FMU's variables for a crane: one table that the model description
//! and the instance's get/set share, so the two cannot disagree.
//!
//! Reals (value references `0..`) in this order: the model's parameters,
//! `dt`, the built-in move (`t0`, `duration`, `start_<x>`, `end_<x>` per
//! load coordinate, `tau0`; a spline move's shape is the packaged run's,
//! [`Start`]), the external load target (`gamma_<x>`,
//! `gamma_<x>_d`, `gamma_<x>_dd`), then the outputs: the inputs `u1..`,
//! the coordinates, the multipliers `lambda1..` and the rope tensions, all
//! named as the model declares them. Integers: `scheme` and `path`, and
//! the output `status`, the audit of the run so far ([`STATUS_HELP`]).

use std::collections::HashSet;

use crane_models::{Crane, Profile, ProfileKind};
use crane_runtime::CraneModel;

use crate::start::Start;

/// Default internal step, s (that of `crane run`).
pub use crane_models::study::DEFAULT_DT;

/// What a variable is to the instance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The model's parameter `k` (in `ModelInfo::parameters` order).
    Parameter(usize),
    /// The internal step `dt`.
    Dt,
    /// Start of the built-in move, s.
    T0,
    /// Duration of the built-in move, s.
    Duration,
    /// Start position of load coordinate `k`.
    Start(usize),
    /// End position of load coordinate `k`.
    End(usize),
    /// Ramp duration of the three-phase profiles, s.
    Tau0,
    /// External target: derivative `order` (0, 1, 2) of load coordinate `k`.
    Target(usize, usize),
    /// Output: input `u_k`.
    Input(usize),
    /// Output: coordinate `q_k`.
    Coordinate(usize),
    /// Output: multiplier `lambda_k`.
    Multiplier(usize),
    /// Output: tension of rope `k`.
    Tension(usize),
    /// Integer: the scheme's code ([`Scheme::code`](crane_runtime::Scheme::code)).
    Scheme,
    /// Integer: the path ([`path_of_code`]).
    Path,
    /// Integer output: the audit of the run so far ([`STATUS_HELP`]).
    Status,
}

/// What the `status` output means.
pub const STATUS_HELP: &str = "the audit of the run so far: 0 nothing found; 1 a warning (a rope would have to \
     push, unstable internal dynamics, many singular steps: a solution, but not a move to make), logged and returned \
     as fmi2Warning when found; 2 an error (states off their constraints, a rope of non-positive length, a runaway \
     input: not a solution), returned as fmi2Error";

/// The `status` values.
pub mod status {
    /// Nothing found.
    pub const OK: i32 = 0;
    /// A warning was found.
    pub const WARNING: i32 = 1;
    /// An error was found.
    pub const ERROR: i32 = 2;
}

/// `causality` in the model description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    /// Set before initialisation (`variability="fixed"`).
    Parameter,
    /// Set by the host before every step (`variability="continuous"`).
    Input,
    /// Computed (`variability="continuous"`, `initial="calculated"`).
    Output,
}

/// One scalar variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Its name.
    pub name: String,
    /// Real or Integer.
    pub integer: bool,
    /// Value reference (per type, from 0).
    pub value_reference: u32,
    /// Parameter, input or output.
    pub causality: Causality,
    /// Start value (parameters and inputs).
    pub start: f64,
    /// What it is, for people.
    pub description: String,
    /// What it is, for the instance.
    pub role: Role,
}

/// The `path` code of the external target (the built-in profiles have the
/// codes of [`ProfileKind::code`], 0 to 2).
pub const EXTERNAL_PATH: i32 = ProfileKind::ALL.len() as i32;

/// The `path` code of the spline move of the run the FMU starts from
/// ([`Start`]: the crane's default move or a packaged scenario's).
pub const SPLINE_PATH: i32 = EXTERNAL_PATH + 1;

/// What an instance's `path` code asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathChoice {
    /// A built-in straight move of this profile.
    Move(ProfileKind),
    /// The external target.
    External,
    /// The spline move the FMU starts from.
    Spline,
}

/// What a `path` code asks for, if it is a code at all.
pub fn path_of_code(code: i32) -> Option<PathChoice> {
    match code {
        EXTERNAL_PATH => Some(PathChoice::External),
        SPLINE_PATH => Some(PathChoice::Spline),
        code => ProfileKind::from_code(code).map(PathChoice::Move),
    }
}

/// The `path` codes in words: "0 poly9, 1 three-phase, 2 smooth-three-phase
/// (the built-in move from start_ to end_), 3 external target", and where
/// the FMU has a spline move, "or 4 the packaged spline move".
pub fn path_help(spline: bool) -> String {
    let profiles: Vec<String> = ProfileKind::ALL
        .iter()
        .zip(0..)
        .map(|(k, code)| format!("{code} {}", k.name()))
        .collect();
    let spline = if spline {
        format!(", {SPLINE_PATH} the spline move (its shape packaged, timed by t0 and duration)")
    } else {
        String::new()
    };
    format!(
        "{} (the built-in move from start_ to end_), {EXTERNAL_PATH} external target{spline}",
        profiles.join(", ")
    )
}

/// Why a crane has no table of FMU variables.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TableError {
    /// Two variables share a name (a model parameter called `dt`, say).
    #[error("two FMU variables are called `{0}`; rename the model's parameter or coordinate")]
    NameClash(String),
}

/// The variables of crane `C` starting from `start`, in model-description
/// order: the Reals first, with value references `0..` in table order,
/// then the Integers.
pub fn variables<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    start: &Start<A>,
) -> Result<Vec<Variable>, TableError> {
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let spec = &start.spec.path;
    let spline = matches!(spec.profile, Profile::Spline(_));
    let path_code = spec.profile.kind().code().unwrap_or(SPLINE_PATH);
    let load = &info.coordinates[N - A..];
    let mut table = Vec::new();
    let real = |table: &mut Vec<Variable>, name: String, causality, start, description: String, role| {
        let value_reference = table.iter().filter(|v: &&Variable| !v.integer).count() as u32;
        table.push(Variable {
            name,
            integer: false,
            value_reference,
            causality,
            start,
            description,
            role,
        });
    };
    let values = start.parameter_values::<C, N, M>();
    for (k, name) in info.parameters.iter().enumerate() {
        real(
            &mut table,
            name.to_string(),
            Causality::Parameter,
            values[k],
            format!("model parameter {name}"),
            Role::Parameter(k),
        );
    }
    real(
        &mut table,
        "dt".into(),
        Causality::Parameter,
        start.spec.dt,
        "internal time step, s; a communication step is a whole multiple of it".into(),
        Role::Dt,
    );
    real(
        &mut table,
        "t0".into(),
        Causality::Parameter,
        spec.t0,
        "start of the built-in move, s".into(),
        Role::T0,
    );
    real(
        &mut table,
        "duration".into(),
        Causality::Parameter,
        spec.t1 - spec.t0,
        "duration of the built-in move, s".into(),
        Role::Duration,
    );
    for (k, x) in load.iter().enumerate() {
        real(
            &mut table,
            format!("start_{x}"),
            Causality::Parameter,
            spec.start[k],
            format!("load coordinate {x} at the start of the built-in straight move"),
            Role::Start(k),
        );
    }
    for (k, x) in load.iter().enumerate() {
        real(
            &mut table,
            format!("end_{x}"),
            Causality::Parameter,
            spec.end[k],
            format!("load coordinate {x} at the end of the built-in straight move"),
            Role::End(k),
        );
    }
    let tau0 = spec.profile.tau0().unwrap_or((spec.t1 - spec.t0) / 4.0);
    real(
        &mut table,
        "tau0".into(),
        Causality::Parameter,
        tau0,
        "ramp duration of the three-phase paths, s".into(),
        Role::Tau0,
    );
    for (k, x) in load.iter().enumerate() {
        for (order, suffix, what) in [(0, "", "position"), (1, "_d", "velocity"), (2, "_dd", "acceleration")] {
            real(
                &mut table,
                format!("gamma_{x}{suffix}"),
                Causality::Input,
                if order == 0 { spec.start[k] } else { 0.0 },
                format!("external load target ({what} of {x}) at the end of the next communication step (path = 3)"),
                Role::Target(k, order),
            );
        }
    }
    for (k, u) in info.inputs.iter().enumerate() {
        real(
            &mut table,
            u.to_string(),
            Causality::Output,
            0.0,
            format!("input {u}"),
            Role::Input(k),
        );
    }
    for (k, q) in info.coordinates.iter().enumerate() {
        real(
            &mut table,
            q.to_string(),
            Causality::Output,
            0.0,
            format!("coordinate {q}"),
            Role::Coordinate(k),
        );
    }
    for (k, g) in info.constraints.iter().enumerate() {
        real(
            &mut table,
            format!("lambda{}", k + 1),
            Causality::Output,
            0.0,
            format!("multiplier of constraint {g}"),
            Role::Multiplier(k),
        );
    }
    for (k, rope) in info.ropes.iter().enumerate() {
        real(
            &mut table,
            rope.tension.to_string(),
            Causality::Output,
            0.0,
            format!("tension of rope {}, N", rope.tension),
            Role::Tension(k),
        );
    }
    table.push(Variable {
        name: "scheme".into(),
        integer: true,
        value_reference: 0,
        causality: Causality::Parameter,
        start: f64::from(start.spec.scheme.code()),
        description: format!("the scheme: {}", crane_runtime::Scheme::code_help()),
        role: Role::Scheme,
    });
    table.push(Variable {
        name: "path".into(),
        integer: true,
        value_reference: 1,
        causality: Causality::Parameter,
        start: f64::from(path_code),
        description: format!("load path: {}", path_help(spline)),
        role: Role::Path,
    });
    table.push(Variable {
        name: "status".into(),
        integer: true,
        value_reference: 2,
        causality: Causality::Output,
        start: f64::from(status::OK),
        description: STATUS_HELP.into(),
        role: Role::Status,
    });
    let mut seen = HashSet::new();
    for v in &table {
        if !seen.insert(v.name.as_str()) {
            return Err(TableError::NameClash(v.name.clone()));
        }
    }
    Ok(table)
}
