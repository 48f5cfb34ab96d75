//! The run summary (`summary.json`): feasibility and accuracy at a glance.

use crane_runtime::{Solution, State};
use serde::Serialize;

/// Extreme value of a column and when it occurs.
#[derive(Debug, Clone, Serialize)]
pub struct Extreme {
    pub name: String,
    pub value: f64,
    pub t: f64,
}

/// A rope's tension over the run.
#[derive(Debug, Clone, Serialize)]
pub struct RopeSummary {
    pub name: String,
    pub min_tension: f64,
    pub t_min: f64,
    /// First time the tension is below `-SLACK_TOLERANCE` times the peak
    /// tension (ropes only pull; a negative tension is infeasible).
    pub first_slack: Option<f64>,
}

/// Errors against the analytical reference.
#[derive(Debug, Clone, Serialize)]
pub struct ReferenceErrors {
    /// Relative error of u at t = 1.5 s, eq. (48): |u - u_ref| / |u_ref|.
    pub e_u_at_1_5s: Option<f64>,
    pub max_abs_error_u: Vec<Extreme>,
    pub max_abs_error_q: Vec<Extreme>,
    pub max_abs_error_lambda: Vec<Extreme>,
}

#[derive(Debug, Clone, Serialize)]
pub struct NewtonSummary {
    pub total_iterations: usize,
    pub mean_per_step: f64,
    pub max_per_step: usize,
    pub min_norm_steps: usize,
    /// Of a minimal run: the first steps taken in redundant coordinates at a
    /// degenerate start (a rope nearly slack).
    pub redundant_start_steps: usize,
}

/// A torque limit from the scenario's `[limits]` and when it is first exceeded.
#[derive(Debug, Clone, Serialize)]
pub struct LimitSummary {
    pub name: String,
    pub limit: f64,
    pub peak: f64,
    /// First time `|u| > limit`, if ever.
    pub first_violation: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub model: String,
    pub description: String,
    pub formulation: String,
    /// The time-discretisation scheme, e.g. `backward-euler` or `bdf4`.
    pub scheme: String,
    pub dt: f64,
    pub t0: f64,
    pub tf: f64,
    pub steps: usize,
    pub newton: NewtonSummary,
    pub wall_time_s: f64,
    pub peak_torque: Vec<Extreme>,
    pub ropes: Vec<RopeSummary>,
    pub torque_limits: Vec<LimitSummary>,
    pub reference: Option<ReferenceErrors>,
    /// `--replay`: the computed torques on the crane's forward dynamics.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replay: Option<ReplaySummary>,
    /// The internal dynamics along the run (`crane_runtime::internal`).
    pub internal_dynamics: InternalSummary,
    /// How smooth the path must be (the inputs depend on its derivatives
    /// up to `needed`) and is (`continuous`), where both are known.
    pub path_smoothness: Option<PathSmoothnessSummary>,
}

/// `path_smoothness` in summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct PathSmoothnessSummary {
    pub needed: usize,
    pub continuous: usize,
    pub sufficient: bool,
}

/// The internal dynamics at sampled states of a run.
#[derive(Debug, Clone, Serialize)]
pub struct InternalSummary {
    /// The count from the declaration's structure
    /// (`CraneModel::STRUCTURE`; none for a hand-written model).
    pub structural_dimension: Option<usize>,
    /// Largest dimension found (0: flat at every sampled state).
    pub dimension: usize,
    /// Largest real part of an eigenvalue, 1/s, and where (none when flat).
    pub max_real_part: Option<f64>,
    pub at: Option<f64>,
    /// No eigenvalue with a real part above round-off.
    pub stable: bool,
    /// States where the diagnosis could not tell (the first reason).
    pub unresolved: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unresolved_reason: Option<String>,
    /// Sampled states (up to `runaway_at`, past which states are not physical).
    pub samples: usize,
    /// First time an input exceeds 1e6 times the largest input at the start
    /// (at least 1): beyond any physical scale, the mark of unstable internal
    /// dynamics in the computed torques.
    pub runaway_at: Option<f64>,
}

impl InternalSummary {
    /// Nothing sampled yet.
    pub fn none() -> Self {
        Self::from(crane_runtime::internal::RunDiagnosis::none())
    }
}

impl From<crane_runtime::internal::RunDiagnosis> for InternalSummary {
    fn from(d: crane_runtime::internal::RunDiagnosis) -> Self {
        Self {
            structural_dimension: d.structural_dimension,
            dimension: d.dimension,
            max_real_part: d.max_real_part,
            at: d.at,
            stable: d.stable,
            unresolved: d.unresolved,
            unresolved_reason: d.unresolved_reason.map(|e| e.to_string()),
            samples: d.samples,
            runaway_at: d.runaway_at,
        }
    }
}

/// The internal dynamics at up to 101 evenly spaced states of `solution`.
pub fn internal_summary<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    solution: &Solution<N, M, A>,
) -> InternalSummary
where
    Mdl: crane_runtime::CraneModel<N, M, A>,
{
    crane_runtime::internal::diagnose(model, solution, 100).into()
}

/// The replay's results in summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct ReplaySummary {
    /// Largest |x(t) - gamma(t)| on [t0, tf], m.
    pub max_load_deviation: f64,
    /// |x(tf) - gamma(tf)|, m.
    pub deviation_at_tf: f64,
    /// Largest |x(t) - gamma(tf)| in the settling window, m.
    pub residual_sway: f64,
    /// Length of the settling window, s.
    pub settle_time: f64,
    /// Forward step, s, and scheme.
    pub dt: f64,
    pub scheme: String,
    /// The plant parameters that differ from the planner's.
    pub plant: std::collections::BTreeMap<String, f64>,
    /// The feedback law, if any (`null`: the computed torques alone); the
    /// numbers above are then those with feedback.
    pub feedback: Option<String>,
    /// The largest deviation of the open-loop replay (the same as
    /// `max_load_deviation` without feedback), m.
    pub open_loop_max_load_deviation: f64,
    /// Ropes that would have to push in the replay (tension below
    /// `-SLACK_TOLERANCE` of the peak): the first time, per rope.
    pub first_slack: std::collections::BTreeMap<String, f64>,
}

/// Tensions below `-SLACK_TOLERANCE * max |N|` count as slack; above it, a
/// negative value is round-off around a rope that carries no load (as at the
/// paper's start, where N1 = 0 exactly and evaluates to about -1e-13 N).
pub const SLACK_TOLERANCE: f64 = 1e-9;

fn column_extremes<const K: usize, const N: usize, const M: usize, const A: usize>(
    states: &[State<N, M, A>],
    names: &[&str],
    value: impl Fn(&State<N, M, A>, usize) -> f64,
) -> Vec<Extreme> {
    (0..K)
        .map(|k| {
            let (t, v) = states
                .iter()
                .map(|s| (s.t, value(s, k)))
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .unwrap_or((f64::NAN, f64::NAN));
            Extreme {
                name: names[k].to_string(),
                value: v,
                t,
            }
        })
        .collect()
}

/// Largest `|value|` per column over a stream of vectors, and when.
struct StreamingExtremes<const K: usize> {
    worst: [(f64, f64); K],
}

impl<const K: usize> StreamingExtremes<K> {
    fn new() -> Self {
        Self {
            worst: [(f64::NAN, f64::NAN); K],
        }
    }

    fn add(&mut self, t: f64, values: &nalgebra::SVector<f64, K>) {
        for (w, &v) in self.worst.iter_mut().zip(values.iter()) {
            if w.1.is_nan() || v.abs() > w.1.abs() {
                *w = (t, v);
            }
        }
    }

    fn into_extremes(self, names: &[&str]) -> Vec<Extreme> {
        self.worst
            .iter()
            .zip(names)
            .map(|(&(t, value), name)| Extreme {
                name: name.to_string(),
                value,
                t,
            })
            .collect()
    }
}

/// The summary of a run; `references(t)` is the analytical reference at `t`
/// where the model has one.
pub fn summarize<const N: usize, const M: usize, const A: usize>(
    model: &str,
    formulation: &str,
    solution: &Solution<N, M, A>,
    references: Option<&dyn Fn(f64) -> Option<State<N, M, A>>>,
    limits: &[(usize, f64)],
    wall_time_s: f64,
) -> Summary {
    let info = solution.info;
    let states = &solution.states;
    let peak_torque = column_extremes::<A, N, M, A>(states, info.inputs, |s, k| s.u[k]);
    let ropes = info
        .ropes
        .iter()
        .enumerate()
        .map(|(r, rope)| {
            let series = || {
                states
                    .iter()
                    .enumerate()
                    .map(|(i, s)| (s.t, solution.tensions_at(i)[r]))
            };
            let peak = series().fold(0.0f64, |m, (_, n)| m.max(n.abs()));
            let (t_min, min_tension) = series()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((f64::NAN, f64::NAN));
            let first_slack = series().find(|(_, n)| *n < -SLACK_TOLERANCE * peak).map(|(t, _)| t);
            RopeSummary {
                name: rope.tension.to_string(),
                min_tension,
                t_min,
                first_slack,
            }
        })
        .collect();
    let torque_limits = limits
        .iter()
        .map(|&(k, limit)| LimitSummary {
            name: info.inputs[k].to_string(),
            limit,
            peak: states.iter().fold(0.0f64, |m, s| m.max(s.u[k].abs())),
            first_violation: states.iter().find(|s| s.u[k].abs() > limit).map(|s| s.t),
        })
        .collect();
    let reference = references.map(|reference_at| {
        let lambda_names: Vec<String> = (1..=M).map(|i| format!("lambda{i}")).collect();
        let lambda_refs: Vec<&str> = lambda_names.iter().map(String::as_str).collect();
        // one pass over the states, the reference evaluated at each: no copy
        // of the run (a run of 2e6 steps would otherwise hold 2 x 320 MB)
        let mut u = StreamingExtremes::<A>::new();
        let mut q = StreamingExtremes::<N>::new();
        let mut lambda = StreamingExtremes::<M>::new();
        let mut e_u_at_1_5s = None;
        for s in states {
            let Some(r) = reference_at(s.t) else { continue };
            u.add(s.t, &(s.u - r.u));
            q.add(s.t, &(s.q - r.q));
            lambda.add(s.t, &(s.lambda - r.lambda));
            if e_u_at_1_5s.is_none() && (s.t - 1.5).abs() < 0.5 * solution.dt {
                e_u_at_1_5s = Some((s.u - r.u).norm() / r.u.norm());
            }
        }
        ReferenceErrors {
            e_u_at_1_5s,
            max_abs_error_u: u.into_extremes(info.inputs),
            max_abs_error_q: q.into_extremes(info.coordinates),
            max_abs_error_lambda: lambda.into_extremes(&lambda_refs),
        }
    });
    let newton = NewtonSummary {
        total_iterations: solution.newton_iterations.iter().sum(),
        mean_per_step: solution.mean_newton_iterations(),
        max_per_step: solution.newton_iterations.iter().copied().max().unwrap_or(0),
        min_norm_steps: solution.min_norm_steps,
        redundant_start_steps: solution.redundant_start_steps,
    };
    Summary {
        model: model.to_string(),
        description: info.description.to_string(),
        formulation: formulation.to_string(),
        scheme: solution.scheme.to_string(),
        dt: solution.dt,
        t0: states.first().map_or(f64::NAN, |s| s.t),
        tf: states.last().map_or(f64::NAN, |s| s.t),
        steps: solution.steps(),
        newton,
        wall_time_s,
        peak_torque,
        ropes,
        torque_limits,
        reference,
        replay: None,
        internal_dynamics: InternalSummary::none(),
        path_smoothness: None,
    }
}

/// A few lines for the terminal.
pub fn highlights(summary: &Summary) -> Vec<String> {
    let mut lines = Vec::new();
    for p in &summary.peak_torque {
        lines.push(format!(
            "peak |{}| = {:.3} N m at t = {:.3} s",
            p.name,
            p.value.abs(),
            p.t
        ));
    }
    for r in &summary.ropes {
        match r.first_slack {
            Some(t) => lines.push(format!(
                "WARNING: rope {} goes slack at t = {t:.3} s (min tension {:.3e} N)",
                r.name, r.min_tension
            )),
            None => lines.push(format!(
                "rope {} stays taut: min tension {:.3} N at t = {:.3} s",
                r.name, r.min_tension, r.t_min
            )),
        }
    }
    for l in &summary.torque_limits {
        match l.first_violation {
            Some(t) => lines.push(format!(
                "WARNING: |{}| exceeds its limit {} N m first at t = {t:.3} s (peak {:.3} N m)",
                l.name, l.limit, l.peak
            )),
            None => lines.push(format!(
                "|{}| stays within its limit {} N m (peak {:.3} N m)",
                l.name, l.limit, l.peak
            )),
        }
    }
    if let Some(reference) = &summary.reference {
        if let Some(e) = reference.e_u_at_1_5s {
            lines.push(format!(
                "relative error of u at t = 1.5 s against the analytical reference (eq. 48): {e:.3e}"
            ));
        }
    }
    let internal = &summary.internal_dynamics;
    lines.push(match (internal.dimension, internal.stable) {
        (0, _) if internal.unresolved == 0 => {
            "internal dynamics: none (flat), the torques are the unique ones".to_string()
        }
        (0, _) => format!(
            "internal dynamics: not resolved at {} of {} sampled states",
            internal.unresolved, internal.samples
        ),
        (k, true) => format!("internal dynamics: dimension {k}, stable"),
        (k, false) => {
            format!("WARNING: internal dynamics: dimension {k}, UNSTABLE: the torques are not a usable feedforward")
        }
    });
    lines
}

/// What makes a run infeasible: slack ropes, violated torque limits and
/// unstable internal dynamics (for `--strict`).
pub fn infeasibilities(summary: &Summary) -> Vec<String> {
    let mut out: Vec<String> = summary
        .ropes
        .iter()
        .filter_map(|r| {
            r.first_slack
                .map(|t| format!("rope {} goes slack at t = {t:.3} s", r.name))
        })
        .collect();
    out.extend(summary.torque_limits.iter().filter_map(|l| {
        l.first_violation
            .map(|t| format!("|{}| exceeds its limit {} N m at t = {t:.3} s", l.name, l.limit))
    }));
    let internal = &summary.internal_dynamics;
    if !internal.stable {
        out.push(format!(
            "unstable internal dynamics (largest real part {:.4} 1/s at t = {} s)",
            internal.max_real_part.unwrap_or(f64::NAN),
            crane_runtime::error::Seconds(internal.at.unwrap_or(f64::NAN))
        ));
    }
    if let Some(t) = internal.runaway_at {
        out.push(format!(
            "an input exceeds {:e} times its size at the start from t = {} s",
            crane_runtime::internal::RUNAWAY_FACTOR,
            crane_runtime::error::Seconds(t)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crane_models::coupled_trolley::CoupledTrolley as Coupled;
    use crane_runtime::nalgebra::vector;
    use crane_runtime::trajectory::Poly9;
    use crane_runtime::{Options, init, simulate};

    fn run(c: f64) -> Solution<4, 1, 2> {
        let crane = Coupled {
            c,
            ..Coupled::default()
        };
        let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
        let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
        simulate(&crane, &path, &start, &Options::new(0.01, 5.0).unwrap()).unwrap()
    }

    /// The coupled crane: the run "succeeds", the summary says
    /// why its torques are not a result: unstable internal dynamics of
    /// dimension 2 from the start (sqrt(lambda/c) = 9.9045 1/s there, larger
    /// where the load rises and accelerates), and an input beyond 1e6 times
    /// its size at the start before t = 2.5 s (3.4e12 N there).
    #[test]
    fn an_unstable_crane_is_reported_as_such() {
        let crane = Coupled::default();
        let summary = internal_summary(&crane, &run(2.0));
        assert_eq!(summary.structural_dimension, Some(2), "{summary:?}");
        assert_eq!(summary.dimension, 2, "{summary:?}");
        assert!(!summary.stable, "{summary:?}");
        assert!(summary.max_real_part.unwrap() >= 9.9, "{summary:?}");
        assert!(summary.runaway_at.is_some_and(|t| t < 2.5), "{summary:?}");
        // diagnosed up to the runaway (1.8 s of 5 s: 37 of the 101 samples)
        assert!(summary.samples >= 30 && summary.unresolved == 0, "{summary:?}");
    }

    /// Without the coupling: flat, nothing to report.
    #[test]
    fn a_flat_crane_is_reported_flat() {
        let crane = Coupled {
            c: 0.0,
            ..Coupled::default()
        };
        let summary = internal_summary(&crane, &run(0.0));
        // structurally 2 (c is a parameter), numerically 0 at c = 0
        assert_eq!(summary.structural_dimension, Some(2), "{summary:?}");
        assert_eq!(summary.dimension, 0, "{summary:?}");
        assert!(summary.stable && summary.runaway_at.is_none(), "{summary:?}");
    }
}
