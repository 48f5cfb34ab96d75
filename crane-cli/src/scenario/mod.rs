//! Scenario files (`crane run MODEL --scenario FILE.toml`): the load path,
//! times, parameters, start and torque limits of a run, applied over the
//! model's default manoeuvre. Three stages: `file` (the schema as
//! written, [`ScenarioFile`]), `error` (what can be wrong, naming the key,
//! [`ScenarioError`]), `resolve` (the file against a crane: a `RunSpec`,
//! then its `Case` and run settings, [`build`]).
//!
//! ```toml
//! dt = 0.01                 # time step, s
//! tf = 4.0                  # end of the run, s (default: end of the motion)
//! formulation = "redundant" # or "minimal"
//! scheme = "bdf4"           # backward-euler (default, also bdf1), bdf2 .. bdf5
//! p0 = [8.66, 10, 5, 0, -5] # start of the robot coordinates (default: the paper's)
//! trajectory = "poly9"      # or "three-phase", "smooth-three-phase" (then tau0 = ramp duration, s)
//! start = [0.0, -10.0]      # load coordinates at t0
//! end = [-3.0, -14.0]       # load coordinates at t1
//! t0 = 0.0                  # start of the motion and the run, s
//! t1 = 4.0                  # end of the motion, s (or duration = 4.0)
//!
//! [parameters]              # overrides, by the model's parameter names
//! m_l = 1200.0
//!
//! [limits]                  # optional |u| limits per input
//! u1 = 150.0
//! ```
//!
//! Every key is optional; what is missing comes from the paper's maneuver
//! (the built-in case), and command-line flags override the file.
//!
//! A spline path replaces `start`, `end`, `t0` and `t1` by its points:
//!
//! ```toml
//! trajectory = "spline"
//! times = [0.0, 2.0, 7.0, 9.0]                    # s, increasing
//! waypoints = [[0, 0, -5], [0, 0, -3], [6, 3, -3], [6, 3, -5]]
//! degree = 9                # optional, odd: by default 2 p + 1 for path order p
//! ```
//!
//! or `knots` (normalised time, 0 to 1) and `control` points, with `t0` and
//! `t1` / `duration` as for a straight move.

mod error;
mod file;
mod resolve;
mod write;

pub use error::ScenarioError;
pub use file::ScenarioFile;
pub use resolve::{build, checked_spec};
pub use write::scenario_text;

use crane_models::study::Formulation;
use crane_runtime::Scheme;

/// Command-line values that override the file.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    /// `--dt`, s.
    pub dt: Option<f64>,
    /// `--tf`, s.
    pub tf: Option<f64>,
    /// `--formulation`.
    pub formulation: Option<Formulation>,
    /// `--scheme`.
    pub scheme: Option<Scheme>,
}

#[cfg(test)]
mod tests {
    //! Arbitrary and mutated scenario files through parsing and resolution
    //! against a crane: each gives a case or a typed error that names its
    //! key, never a panic.
    use super::*;
    use crane_models::navy_planar::Description;
    use proptest::prelude::*;

    const KEYS: [&str; 22] = [
        "dt",
        "tf",
        "formulation",
        "scheme",
        "p0",
        "trajectory",
        "tau0",
        "start",
        "end",
        "t0",
        "t1",
        "duration",
        "model",
        "parameters.m_l",
        "parameters.mass",
        "limits.u1",
        "limits.u9",
        "waypoints",
        "times",
        "knots",
        "control",
        "degree",
    ];

    /// A TOML value of any kind: numbers (also negative, zero, huge, nan,
    /// inf), strings (some of them meaningful), booleans, arrays.
    fn value() -> impl Strategy<Value = String> {
        prop_oneof![
            (-1e3..1e3f64).prop_map(|v| format!("{v:?}")),
            prop_oneof![
                Just("0.0"),
                Just("-0.01"),
                Just("1e308"),
                Just("nan"),
                Just("inf"),
                Just("-inf"),
                Just("3")
            ]
            .prop_map(String::from),
            prop_oneof![
                Just("\"poly9\""),
                Just("\"three-phase\""),
                Just("\"smooth-three-phase\""),
                Just("\"minimal\""),
                Just("\"bdf4\""),
                Just("\"rk4\""),
                Just("\"navy-3d\""),
                Just("\"\""),
            ]
            .prop_map(String::from),
            any::<bool>().prop_map(|b| b.to_string()),
            prop::collection::vec(-20.0..20.0f64, 0..7).prop_map(|v| format!(
                "[{}]",
                v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
            )),
            // rows of points (waypoints, control points), some of them ragged
            prop::collection::vec(prop::collection::vec(-20.0..20.0f64, 1..4), 0..6).prop_map(|rows| format!(
                "[{}]",
                rows.iter()
                    .map(|v| format!(
                        "[{}]",
                        v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(", ")
                    ))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
            Just("\"spline\"".to_string()),
        ]
    }

    /// A scenario of up to 6 keys with arbitrary values, tables last.
    fn scenario() -> impl Strategy<Value = String> {
        prop::collection::vec((0..KEYS.len(), value()), 0..6).prop_map(|entries| {
            let (mut top, mut tables) = (String::new(), std::collections::BTreeMap::<&str, String>::new());
            for (k, v) in entries {
                match KEYS[k].split_once('.') {
                    Some((table, key)) => tables.entry(table).or_default().push_str(&format!("{key} = {v}\n")),
                    None => top.push_str(&format!("{} = {v}\n", KEYS[k])),
                }
            }
            for (table, body) in tables {
                top.push_str(&format!("[{table}]\n{body}"));
            }
            top
        })
    }

    fn check(text: &str) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.toml");
        std::fs::write(&path, text).unwrap();
        let error = match ScenarioFile::load(&path) {
            Err(e) => e,
            Ok(file) => match build::<Description, 7, 3, 2>(Some(&file), &Overrides::default()) {
                Ok((case, settings)) => {
                    assert!(settings.dt > 0.0 && case.tf() > case.t0(), "{text}");
                    // the start is checked, not assumed: Ok or a typed error
                    let _ = case.start();
                    return;
                }
                Err(e) => e,
            },
        };
        let message = error.to_string();
        match &error {
            ScenarioError::Parse { message: m, .. } => {
                assert!(m.contains("line") || m.contains('`'), "{text}: {message}")
            }
            ScenarioError::Read { .. } => panic!("{text}: {message}"),
            ScenarioError::EndTwice => assert!(message.contains("`t1`") && message.contains("`duration`")),
            other => {
                let key = other.key().unwrap_or_else(|| panic!("no key: {message}"));
                let last = key.rsplit('.').next().unwrap();
                assert!(message.contains(last), "{text}: {message} does not name `{key}`");
            }
        }
        assert_eq!(message.lines().count(), 1, "one line: {message}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn arbitrary_scenarios_resolve_or_name_the_key(text in scenario()) {
            check(&text);
        }

        /// A valid file with one byte changed anywhere.
        #[test]
        fn mutated_scenarios_resolve_or_name_the_key(position in 0usize..200, byte in 32u8..127) {
            let mut text = String::from("dt = 0.01\ntf = 4.0\nscheme = \"bdf2\"\ntrajectory = \
                \"poly9\"\nstart = [0.0, -10.0]\nend = [-3.0, -14.0]\n[parameters]\nm_l = 120.0\n[limits]\nu1 = 150.0\n").into_bytes();
            let i = position % text.len();
            text[i] = byte;
            check(&String::from_utf8(text).unwrap());
        }
    }
}
