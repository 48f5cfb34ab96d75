//! `crane list`: the built-in cranes with their sizes, reference, minimal
//! map and internal dynamics at the start.

use crane_models::registry::{self, Visit};
use crane_models::{CATALOG, Case, Crane};

use crate::CliError;

/// The internal dynamics at the start of a crane's default manoeuvre:
/// `0 (flat)`, `2 stable`, `2 unstable`, or `?` where the diagnosis cannot
/// tell.
struct InternalAtStart;

impl Visit for InternalAtStart {
    type Output = String;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> String {
        let diagnosis = Case::<C, N, M, A>::maneuver().ok().and_then(|case| {
            let start = case.start().ok()?;
            crane_runtime::internal::internal_dynamics(case.model(), &start).ok()
        });
        match diagnosis {
            Some(d) if d.dimension == 0 => "0 (flat)".into(),
            Some(d) => format!("{} {}", d.dimension, if d.is_stable() { "stable" } else { "unstable" }),
            None => "?".into(),
        }
    }
}

/// Print the table.
pub fn list() -> Result<(), CliError> {
    let width = CATALOG.iter().map(|e| e.name.len()).max().unwrap_or(5);
    println!(
        "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:<10} description",
        "model", "n", "m", "a", "f", "reference", "minimal", "internal"
    );
    let yes = |b: bool| if b { "yes" } else { "no" };
    for e in CATALOG {
        let internal = registry::visit(e.name, InternalAtStart).unwrap_or_else(|| "?".into());
        println!(
            "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:<10} {}",
            e.name,
            e.n,
            e.m,
            e.a,
            e.dof(),
            yes(e.reference),
            yes(e.minimal),
            internal,
            e.description
        );
    }
    Ok(())
}
