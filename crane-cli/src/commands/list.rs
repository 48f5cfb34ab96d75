//! `crane list`: the cranes of the tool's registry with their sizes, reference, minimal
//! map, the path derivative their inputs need, their default formulation
//! (and why it is), and their internal dynamics at the start.

use crane_models::registry::{Registry, Visit};
use crane_models::study::Formulation;
use crane_models::{Case, Crane};
use crane_runtime::CraneModel;

use crate::{CliError, Tool};

/// What the table says of one crane beyond its catalogue entry.
struct Row {
    /// The path derivative the inputs need (`?` if not known).
    path_order: String,
    /// The default formulation.
    formulation: &'static str,
    /// `0 (flat)`, `2 stable`, `2 unstable`, or `?` where the diagnosis
    /// cannot tell.
    internal: String,
}

/// The [`Row`] of a crane, its internal dynamics at the start of its
/// default manoeuvre.
struct RowOf;

impl Visit for RowOf {
    type Output = Row;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Row {
        let diagnosis = Case::<C, N, M, A>::maneuver().ok().and_then(|case| {
            // the start a run takes (a rough default p0 resolved to the
            // static equilibrium), so that list and run agree
            let start = case.run_start().ok()?;
            crane_runtime::internal::internal_dynamics(case.model(), &start).ok()
        });
        let internal = match diagnosis {
            Some(d) if d.dimension == 0 => "0 (flat)".into(),
            Some(d) => format!("{} {}", d.dimension, if d.is_stable() { "stable" } else { "unstable" }),
            None => "?".into(),
        };
        let path_order =
            <C::Model as CraneModel<N, M, A>>::STRUCTURE.map_or_else(|| "?".into(), |s| s.path_order(A).to_string());
        Row {
            path_order,
            formulation: Formulation::default_for::<C, N, M, A>().name(),
            internal,
        }
    }
}

/// Print the table.
pub fn list<R: Registry>(tool: &Tool<R>) -> Result<(), CliError> {
    let entries = tool.registry().entries();
    let width = entries.iter().map(|e| e.name.len()).max().unwrap_or(5);
    say!(
        "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:>5}  {:<16} {:<10} description",
        "model",
        "n",
        "m",
        "a",
        "f",
        "reference",
        "minimal",
        "order",
        "formulation",
        "internal"
    )?;
    let yes = |b: bool| if b { "yes" } else { "no" };
    for e in &entries {
        let Some(row) = tool.registry().visit(e.name, RowOf) else {
            continue;
        };
        say!(
            "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:>5}  {:<16} {:<10} {}",
            e.name,
            e.n,
            e.m,
            e.a,
            e.dof(),
            yes(e.reference),
            yes(e.minimal),
            row.path_order,
            row.formulation,
            row.internal,
            e.description
        )?;
    }
    // why the defaults are what they are, on standard error: the table on
    // standard output stays one line per crane for scripts that read it
    eprintln!(
        "note: the formulation column is the default: {} for a crane without internal dynamics (its exact \
         inputs at each step time, solved stage by stage for less per step than eqs. (22a-d) with backward \
         Euler), {} for one whose internal dynamics are stable (the free states by the scheme, the rest \
         exact), {} for one whose internal dynamics are unstable (the bounded inputs, with pre- and \
         post-actuation), {} (eqs. 22a-d) for the others; --formulation runs another",
        Formulation::DummyDerivative,
        Formulation::StateSelection,
        Formulation::StableInversion,
        Formulation::Redundant
    );
    Ok(())
}
