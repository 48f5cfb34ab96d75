//! `crane run --replay`: the computed torques on the crane's forward
//! dynamics (`crane_runtime::replay`), on the planned plant or on one whose
//! parameters differ (`--plant`, `[plant]`): replay.csv, replay.svg and the
//! summary's "replay" entry.

use std::collections::BTreeMap;

use crane_models::{Case, Crane};
use crane_runtime::replay::{Feedback, Pendulum, ReplayOptions, load_deviation, replay, replay_with_feedback};
use crane_runtime::{CraneModel, Scheme, Solution};

use crate::report::ReplaySummary;
use crate::{CliError, plot};

/// `--feedback default` or `--feedback KP,KD`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FeedbackSpec {
    /// Gains from the model (`Feedback::from_model`).
    Default,
    /// The same stiffness and damping on every robot coordinate.
    Gains(f64, f64),
}

impl FeedbackSpec {
    /// Parse the flag's value.
    pub fn parse(text: &str) -> Result<Self, CliError> {
        if text == "default" {
            return Ok(Self::Default);
        }
        let bad = || CliError::Feedback(text.to_string());
        let (kp, kd) = text.split_once(',').ok_or_else(bad)?;
        let (kp, kd): (f64, f64) = (
            kp.trim().parse().map_err(|_| bad())?,
            kd.trim().parse().map_err(|_| bad())?,
        );
        if kp.is_finite() && kd.is_finite() && kp >= 0.0 && kd >= 0.0 {
            Ok(Self::Gains(kp, kd))
        } else {
            Err(bad())
        }
    }

    fn gains<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        self,
        model: &Mdl,
        start: &crane_runtime::State<N, M, A>,
    ) -> (Feedback<N>, String) {
        match self {
            Self::Default => (
                Feedback::from_model(model, start),
                "default (critically damped at 4 sqrt(g/L))".into(),
            ),
            Self::Gains(kp, kd) => {
                let robot = |k: f64| nalgebra::SVector::<f64, N>::from_fn(|i, _| if i < N - A { k } else { 0.0 });
                (
                    Feedback {
                        kp: robot(kp),
                        kd: robot(kd),
                    },
                    format!("kp = {kp}, kd = {kd}"),
                )
            }
        }
    }
}

/// Replay `inverse` on the case's crane with the `plant` overrides (and
/// `feedback` on top, after an open-loop replay); the summary and the files
/// `replay.csv`, `replay.svg`.
pub fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    inverse: &Solution<N, M, A>,
    plant: &[(String, f64)],
    settle: Option<f64>,
    feedback: Option<FeedbackSpec>,
) -> Result<(ReplaySummary, Vec<(String, String)>), CliError> {
    let mut model = case.model().clone();
    let mut changed = BTreeMap::new();
    for (name, value) in plant {
        if !value.is_finite() {
            return Err(CliError::PlantParameter {
                name: name.clone(),
                message: format!("{value} is not finite"),
            });
        }
        model
            .set_parameter(name, *value)
            .map_err(|e| CliError::PlantParameter {
                name: name.clone(),
                message: e.to_string(),
            })?;
        changed.insert(name.clone(), *value);
    }
    let end = inverse.states.last().expect("a run has its start");
    // default: twice the longest rope pendulum's period at the end
    let settle = settle.unwrap_or_else(|| 2.0 * Pendulum::longest(&model, end).period());
    let options = ReplayOptions::new(settle, Scheme::Bdf2);
    let open = replay(&model, case.path(), inverse, &options)?;
    let gains = feedback.map(|f| f.gains(&model, &inverse.states[0]));
    let closed = match &gains {
        Some((g, _)) => Some(replay_with_feedback(&model, case.path(), inverse, &options, Some(g))?),
        None => None,
    };
    let result = closed.as_ref().unwrap_or(&open);
    let info = inverse.info;
    let tf = end.t;
    let deviation = |s: &crane_runtime::State<N, M, A>| load_deviation(case.path(), tf, s);
    let mut writer = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["t".to_string()];
    header.extend(info.coordinates.iter().map(|s| s.to_string()));
    header.extend((1..=M).map(|i| format!("lambda{i}")));
    header.extend(info.ropes.iter().map(|r| r.tension.to_string()));
    header.push("load_deviation".into());
    let failed = |e: csv::Error| CliError::Output {
        what: "replay.csv".into(),
        message: e.to_string(),
    };
    writer.write_record(&header).map_err(failed)?;
    let mut row = Vec::new();
    for (i, s) in result.solution.states.iter().enumerate() {
        row.clear();
        row.push(format!("{}", s.t));
        row.extend(s.q.iter().chain(s.lambda.iter()).map(|v| format!("{v:e}")));
        row.extend(result.solution.tensions_at(i).iter().map(|v| format!("{v:e}")));
        row.push(format!("{:e}", deviation(s)));
        writer.write_record(&row).map_err(failed)?;
    }
    let csv = writer.into_inner().map_err(|e| CliError::Output {
        what: "replay.csv".into(),
        message: e.to_string(),
    })?;
    let curve = |r: &crane_runtime::replay::Replay<N, M, A>| -> Vec<(f64, f64)> {
        r.solution.states.iter().map(|s| (s.t, deviation(s))).collect()
    };
    let plant_label = if changed.is_empty() {
        "the planned plant".to_string()
    } else {
        changed
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let title = format!(
        "{} - replay on {plant_label}: load deviation (torques held after {tf} s)",
        info.name
    );
    let svg = match &closed {
        None => plot::curves_over_time(&title, "|x - gamma| [m]", &[("open loop", curve(&open))])?,
        Some(c) => plot::curves_over_time(
            &title,
            "|x - gamma| [m]",
            &[("open loop", curve(&open)), ("with feedback", curve(c))],
        )?,
    };
    let peak = result.solution.tensions.iter().fold(0.0f64, |m, n| m.max(n.abs()));
    let mut first_slack = BTreeMap::new();
    for (i, s) in result.solution.states.iter().enumerate() {
        for (rope, &n) in info.ropes.iter().zip(result.solution.tensions_at(i)) {
            if n < -crate::report::SLACK_TOLERANCE * peak {
                first_slack.entry(rope.tension.to_string()).or_insert(s.t);
            }
        }
    }
    let summary = ReplaySummary {
        max_load_deviation: result.max_load_deviation,
        deviation_at_tf: result.deviation_at_tf,
        residual_sway: result.residual_sway,
        settle_time: settle,
        dt: result.solution.dt,
        scheme: result.solution.scheme.to_string(),
        plant: changed,
        feedback: gains.map(|(_, label)| label),
        open_loop_max_load_deviation: open.max_load_deviation,
        first_slack,
    };
    Ok((
        summary,
        vec![
            ("replay.csv".into(), String::from_utf8_lossy(&csv).into_owned()),
            ("replay.svg".into(), svg),
        ],
    ))
}
