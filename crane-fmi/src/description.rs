//! `modelDescription.xml` (FMI 2.0, co-simulation) from the variable table,
//! and the GUID that ties a description to its binary.

use std::any::TypeId;
use std::collections::HashMap;
use std::fmt::Write;
use std::sync::{LazyLock, Mutex, PoisonError};

use crane_models::Crane;
use crane_models::study::{Formulation, RunSpec};
use crane_runtime::Options;

use crate::start::Start;
use crate::variables::{Causality, TableError, variables};

/// The `modelIdentifier` of a crane: its name with every character that is
/// not ASCII alphanumeric replaced by `_` (`navy-planar` → `navy_planar`);
/// the binary in the FMU is `binaries/linux64/<identifier>.so`.
pub fn model_identifier(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// `text` with the five XML special characters escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

/// A start value as XML reads it back exactly (shortest round trip).
fn number(value: f64) -> String {
    format!("{value:?}")
}

/// 64-bit FNV-1a of `bytes` from `seed`.
fn fnv1a(bytes: &[u8], seed: u64) -> u64 {
    bytes
        .iter()
        .fold(seed, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

/// The GUID of a description body: two FNV-1a hashes of it, printed as a
/// UUID. It changes with any variable, start value or version of this
/// crate, so a binary refuses a description it was not built with.
fn guid(body: &str) -> String {
    let a = fnv1a(body.as_bytes(), 0xcbf2_9ce4_8422_2325);
    let b = fnv1a(body.as_bytes(), a ^ 0x9e37_79b9_7f4a_7c15);
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// The default experiment's start and stop times of crane `C` from
/// `start`: its move's start and the run's end, and for a run by stable
/// inversion the span of the bounded solution (from `t0 - T_pre` to `tf +
/// T_post`: the FMU plays it back from there).
pub fn default_experiment<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    start: &Start<A>,
) -> (f64, f64) {
    // found once per crane, packaged run and process: every instance's
    // start (and reset) asks, and for a run by stable inversion the answer
    // is a whole solve
    type Key = (TypeId, Option<String>);
    static FOUND: LazyLock<Mutex<HashMap<Key, (f64, f64)>>> = LazyLock::new(Default::default);
    let key = (TypeId::of::<C>(), start.resource.clone());
    let known = FOUND.lock().unwrap_or_else(PoisonError::into_inner).get(&key).copied();
    if let Some(span) = known {
        return span;
    }
    let span = find_default_experiment::<C, N, M, A>(&start.spec);
    FOUND.lock().unwrap_or_else(PoisonError::into_inner).insert(key, span);
    span
}

/// [`default_experiment`], found.
fn find_default_experiment<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    spec: &RunSpec<A>,
) -> (f64, f64) {
    let bounded = (spec.formulation == Formulation::StableInversion)
        .then(|| {
            let (case, settings) = spec.build::<C, N, M>().ok()?;
            let options = Options::new(settings.dt, case.tf()).ok()?;
            let start = case.run_start().ok()?;
            let states = case.simulate_stable_inversion(&start, &options).ok()?.solution.states;
            Some((states.first()?.t, states.last()?.t))
        })
        .flatten();
    bounded.unwrap_or((spec.path.t0, spec.tf))
}

/// `modelDescription.xml` of crane `C` starting from `start`, and its
/// GUID (which a packaged run's text enters too: a binary refuses a
/// description whose run it was not given).
pub fn model_description<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    start: &Start<A>,
) -> Result<(String, String), TableError> {
    let table = variables::<C, N, M, A>(start)?;
    let step = start.spec.dt;
    let (start_time, stop) = default_experiment::<C, N, M, A>(start);
    let mut vars = String::new();
    for v in &table {
        let (causality, variability, initial) = match v.causality {
            Causality::Parameter => ("parameter", "fixed", Some("exact")),
            Causality::Input => ("input", "continuous", None),
            // only a Real can be continuous
            Causality::Output if v.integer => ("output", "discrete", Some("calculated")),
            Causality::Output => ("output", "continuous", Some("calculated")),
        };
        let initial = initial.map(|i| format!(" initial=\"{i}\"")).unwrap_or_default();
        let kind = if v.integer { "Integer" } else { "Real" };
        let start = match (v.causality, v.integer) {
            (Causality::Output, _) => String::new(),
            (_, true) => format!(" start=\"{}\"", v.start as i64),
            (_, false) => format!(" start=\"{}\"", number(v.start)),
        };
        let _ = write!(
            vars,
            "    <ScalarVariable name=\"{}\" valueReference=\"{}\" description=\"{}\" \
                causality=\"{causality}\" variability=\"{variability}\"{initial}>\n      <{kind}{start}/>\n    </ScalarVariable>\n",
            escape(&v.name),
            v.value_reference,
            escape(&v.description),
        );
    }
    let outputs: String = table
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, _)| format!("      <Unknown index=\"{}\"/>\n", i + 1))
        .collect();
    let identifier = model_identifier(C::NAME);
    let body = format!(
        "  <CoSimulation modelIdentifier=\"{identifier}\" canHandleVariableCommunicationStepSize=\"true\" \
            canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"/>\n  <DefaultExperiment startTime=\"{}\" stopTime=\"{}\" stepSize=\"{}\"/>\n  <ModelVariables>\n{vars}  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n{outputs}    </Outputs>\n    <InitialUnknowns>\n{outputs}    </InitialUnknowns>\n  </ModelStructure>\n",
        number(start_time),
        number(stop),
        number(step),
    );
    let version = env!("CARGO_PKG_VERSION");
    let packaged = start.resource.as_deref().unwrap_or_default();
    let guid = guid(&format!("{version}\n{}\n{body}{packaged}", C::NAME));
    let xml = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription fmiVersion=\"2.0\" \
            modelName=\"{}\" guid=\"{guid}\" description=\"{}\" generationTool=\"crane-fmi {version}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">\n{body}</fmiModelDescription>\n",
        escape(C::NAME),
        escape(C::DESCRIPTION),
    );
    Ok((xml, guid))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crane_models::navy_planar;

    /// The description of navy-planar: every variable once, value
    /// references dense per type, the outputs listed by their 1-based
    /// index, start values that read back exactly, and a GUID that changes
    /// with the content.
    #[test]
    fn the_description_lists_every_variable_once() {
        type D = navy_planar::Description;
        let start = Start::default_for::<D, 7, 3>();
        let (xml, guid) = model_description::<D, 7, 3, 2>(&start).unwrap();
        let table = crate::variables::variables::<D, 7, 3, 2>(&start).unwrap();
        assert_eq!(xml.matches("<ScalarVariable ").count(), table.len());
        // the Reals first (the instance finds a Real by indexing the table)
        assert!(table.iter().skip_while(|v| !v.integer).all(|v| v.integer));
        for (i, v) in table.iter().enumerate() {
            assert_eq!(xml.matches(&format!("name=\"{}\"", v.name)).count(), 1, "{}", v.name);
            let same_type = table
                .iter()
                .filter(|w| w.integer == v.integer)
                .position(|w| w.name == v.name)
                .unwrap();
            assert_eq!(v.value_reference as usize, same_type, "{}", v.name);
            if v.causality == crate::variables::Causality::Output {
                assert!(xml.contains(&format!("<Unknown index=\"{}\"/>", i + 1)), "{}", v.name);
            }
        }
        // every start value reads back to the model's default exactly
        // (alpha, the boom angle, is not a short decimal)
        let values = crane_runtime::CraneModel::<7, 3, 2>::parameter_values(&navy_planar::NavyPlanar::default());
        for (k, v) in table
            .iter()
            .filter(|v| matches!(v.role, crate::variables::Role::Parameter(_)))
            .enumerate()
        {
            let tag = format!("name=\"{}\"", v.name);
            let after = &xml[xml.find(&tag).unwrap()..];
            let start: f64 = after
                .split("start=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert_eq!(start.to_bits(), values[k].to_bits(), "{}", v.name);
        }
        assert!(xml.contains(&format!("guid=\"{guid}\"")));
        let (_, other) = model_description::<navy_planar_pulley::Description, 8, 4, 3>(&Start::default_for::<
            navy_planar_pulley::Description,
            8,
            4,
        >())
        .unwrap();
        assert_ne!(guid, other);
        assert_eq!(model_identifier("navy-planar"), "navy_planar");
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }

    use crane_models::navy_planar_pulley;
}
