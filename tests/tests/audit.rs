//! The audit on results that converge step by step but are not the inverse
//! dynamics they claim: each is found, by name, and a regular run is not.

use crane_models::navy_planar::PaperCase;
use crane_models::study::{self, Finding, Formulation, RunSettings, Severity};
use crane_runtime::Options;

/// What the audit finds in a move up to `until`, from the case's checked start.
fn findings(case: &PaperCase, dt: f64, until: f64) -> Vec<Finding> {
    let settings = RunSettings {
        dt,
        ..RunSettings::default()
    };
    let start = case.start().unwrap();
    let options = Options::new(dt, until).unwrap();
    let solution = Formulation::Redundant
        .simulate(case, &start, &options, &mut |_, _| {})
        .unwrap();
    let summary = study::summarize_run(case, &settings, &solution, 0.0, study::DIAGNOSIS_SAMPLES);
    study::audit(&summary)
}

/// The paper's move slowed to 1000 s: rope N1 carries 3e-11 N at the start
/// and the massless pulley's place along the hoist rope is fixed only to
/// round-off; at dt = 0.001 s its jumps (13 to 80 mm from t = 0.284 s),
/// differentiated by the scheme, turn the winch torque u1 by 1.8e3 N m
/// from one step to the next, where the quasi-static torque is below 1e-8
/// N m. Every step converges; the audit names the spike. At dt = 0.01 s
/// the whole move's largest turn is 1.5 % of its peak (43 N m at the end)
/// and nothing is found.
#[test]
fn a_slow_move_whose_pulley_is_not_determined_is_found() {
    let slow = PaperCase::new(1000.0).unwrap();
    let found = findings(&slow, 0.001, 0.5);
    let spike = found
        .iter()
        .find_map(|f| match f {
            Finding::InputSpike { spike, .. } => Some(spike),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no spike found: {found:?}"));
    println!("{spike:?}");
    assert_eq!(spike.input, "u1");
    assert!((0.28..0.3).contains(&spike.t), "{spike:?}");
    assert!(spike.second_difference > 1e3, "{spike:?}");
    assert_eq!(findings(&slow, 0.01, 1000.0), vec![]);
}

/// Ramps of 0.01 s at dt = 0.01 s are one step long: found, with the step
/// that would resolve them; ramps of 1 s are not.
#[test]
fn a_ramp_shorter_than_four_steps_is_found() {
    use crane_models::{Path, PathSpec, Profile};
    let paper = PaperCase::new(4.0).unwrap();
    let with_ramps = |tau0: f64| {
        let spec = PathSpec {
            profile: Profile::ThreePhase { tau0 },
            ..*paper.path().spec()
        };
        PaperCase::from_parts(*paper.model(), Path::new(spec).unwrap(), paper.p0.clone(), 4.0)
    };
    let found = findings(&with_ramps(0.01), 0.01, 0.5);
    assert!(
        found.contains(&Finding::UnresolvedRamp { tau0: 0.01, dt: 0.01 }),
        "{found:?}"
    );
    let message = found
        .iter()
        .find(|f| matches!(f, Finding::UnresolvedRamp { .. }))
        .unwrap();
    assert!(message.to_string().contains("take dt <= 0.0025 s"), "{message}");
    assert_eq!(message.severity(), Severity::Warning);
    let smooth = findings(&with_ramps(1.0), 0.01, 0.5);
    assert!(
        !smooth.iter().any(|f| matches!(f, Finding::UnresolvedRamp { .. })),
        "{smooth:?}"
    );
}
