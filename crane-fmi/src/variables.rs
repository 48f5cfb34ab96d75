//! The FMU's variables for a crane: one table that the model description
//! and the instance's get/set share, so the two cannot disagree.
//!
//! Reals (value references `0..`) in this order: the model's parameters,
//! `dt`, the built-in move (`t0`, `duration`, `start_<x>`, `end_<x>` per
//! load coordinate, `tau0`), the external load target (`gamma_<x>`,
//! `gamma_<x>_d`, `gamma_<x>_dd`), then the outputs: the inputs `u1..`,
//! the coordinates, the multipliers `lambda1..` and the rope tensions, all
//! named as the model declares them. Integers: `scheme` and `path`.

use std::collections::HashSet;

use crane_models::{Crane, Profile};
use crane_runtime::CraneModel;

/// Default internal step, s (that of `crane run`).
pub const DEFAULT_DT: f64 = 0.01;

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
    /// Integer: the scheme's order (1 backward Euler, 2..5 BDF-k).
    Scheme,
    /// Integer: the path ([`PathKind`]).
    Path,
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

/// The path of an FMU instance (`path` variable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathKind {
    /// 0: rest-to-rest poly9 (eqs. 41-45).
    Poly9 = 0,
    /// 1: three-phase, ramps of `tau0`.
    ThreePhase = 1,
    /// 2: smooth three-phase, ramps of `tau0`.
    SmoothThreePhase = 2,
    /// 3: the external target `gamma_<x>`, `gamma_<x>_d`, `gamma_<x>_dd`.
    External = 3,
}

impl PathKind {
    /// The kind of an integer value, if it is one.
    pub fn from_value(value: i32) -> Option<Self> {
        [Self::Poly9, Self::ThreePhase, Self::SmoothThreePhase, Self::External]
            .into_iter()
            .find(|k| *k as i32 == value)
    }

    /// The kind of a built-in move's profile and its ramp duration, if any.
    pub fn of_profile(profile: Profile) -> (Self, Option<f64>) {
        match profile {
            Profile::Poly9 => (Self::Poly9, None),
            Profile::ThreePhase { tau0 } => (Self::ThreePhase, Some(tau0)),
            Profile::SmoothThreePhase { tau0 } => (Self::SmoothThreePhase, Some(tau0)),
        }
    }
}

/// Two variables share a name (a model parameter called `dt`, say).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("two FMU variables are called `{0}`; rename the model's parameter or coordinate")]
pub struct NameClash(pub String);

/// The variables of crane `C`, in model-description order: the Reals
/// first, with value references `0..` in table order, then the Integers.
pub fn variables<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() -> Result<Vec<Variable>, NameClash>
{
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let model = C::Model::default();
    let maneuver = C::maneuver();
    let spec = maneuver.path;
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
    let values = model.parameter_values();
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
        DEFAULT_DT,
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
            format!("load coordinate {x} at the start of the built-in move"),
            Role::Start(k),
        );
    }
    for (k, x) in load.iter().enumerate() {
        real(
            &mut table,
            format!("end_{x}"),
            Causality::Parameter,
            spec.end[k],
            format!("load coordinate {x} at the end of the built-in move"),
            Role::End(k),
        );
    }
    let (_, tau0) = PathKind::of_profile(spec.profile);
    let tau0 = tau0.unwrap_or((spec.t1 - spec.t0) / 4.0);
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
        start: 1.0,
        description: "order of the scheme: 1 backward Euler (the paper's), 2..5 BDF-k".into(),
        role: Role::Scheme,
    });
    table.push(Variable {
        name: "path".into(),
        integer: true,
        value_reference: 1,
        causality: Causality::Parameter,
        start: f64::from(PathKind::of_profile(spec.profile).0 as i32),
        description: "load path: 0 poly9, 1 three-phase, 2 smooth three-phase (the built-in move), 3 external target"
            .into(),
        role: Role::Path,
    });
    let mut seen = HashSet::new();
    for v in &table {
        if !seen.insert(v.name.as_str()) {
            return Err(NameClash(v.name.clone()));
        }
    }
    Ok(table)
}
