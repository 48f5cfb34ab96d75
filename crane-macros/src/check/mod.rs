//! Semantic checks: names, counts, and the structure the method needs.
//!
//! Resolves every name of a [`Declaration`], lowers the expressions into the
//! IR and checks what the paper assumes (sect. 2):
//! - the kinetic energy is a quadratic form in the velocities with constant
//!   coefficients, `T = 1/2 q'^T M q'` (eq. 28), checked term by term;
//! - the generalized forces are linear in the inputs, `f + B^T(q) u`, and
//!   the inputs act on the robot coordinates only (eq. 11c);
//! - one input per load coordinate (eq. 1c) and fewer constraints than
//!   coordinates (`m < n`);
//! - a `minimal` block maps every coordinate once, with `f = n - m` minimal
//!   coordinates of which the last `a` are `mu2` (eqs. 6, 12); see
//!   [`minimal`].
//!
//! Every problem is reported to the [`Ctxt`] with a span on the culprit.
//!
//! The stages: [`resolve`] (the symbol table and the lowering into the IR),
//! [`rules`] (the sections, counts, kinetic energy, forces and
//! constraints), [`minimal`], [`sample`] (the self-test's box) and
//! [`attributes`] (the `#[crane(...)]` options and the description); this
//! module runs them in order.

mod attributes;
mod minimal;
mod physics;
mod resolve;
mod rules;
mod sample;

use proc_macro2::Ident;

use crate::ctxt::Ctxt;
use crate::expr::Arena;
use crate::model::{Model, Param};
use crate::parse::Declaration;
pub(crate) use attributes::crane_options;
use attributes::first_doc_line;
pub use physics::{
    Lint, dependent_constraints, negative_inertia, physics_lints, ropes_depend_on_their_lengths,
    ropes_pull_along_their_lengths,
};
use resolve::{Lowerer, Place, declare_names};
use rules::{check_constraints, check_counts, check_forces, check_kinetic, required_constraints, required_sections};
use sample::check_sample;

/// Checks `decl` and builds the [`Model`]; `None` if anything was reported.
pub fn check(decl: &Declaration, cx: &Ctxt) -> Option<Model> {
    let s = &decl.sections;
    let lists = required_sections(decl, cx);
    let no_params = Vec::new();
    let params = s.params.as_ref().map_or(&no_params, |p| &p.body);
    let constraints = s.constraints.as_ref().map_or(&[][..], |c| &c.body[..]);
    let m = constraints.len();
    let names = declare_names(params, &lists, constraints, cx)?;
    let (n_robot, inputs) = (lists.robot.len(), lists.inputs);
    check_counts(decl, &names, cx);

    let mut arena = Arena::new();
    let mut lower = Lowerer {
        arena: &mut arena,
        names: &names,
        cx,
        minimal: None,
    };
    // `None` only after an error was reported
    let defaults: Option<Vec<crate::expr::Id>> = params
        .iter()
        .map(|p| lower.lower(&p.default, Place::ParamDefault))
        .collect();
    let kinetic = s.kinetic.as_ref().and_then(|k| check_kinetic(&k.body, &mut lower));
    required_constraints(decl, cx);
    let forces = check_forces(decl, n_robot, &mut lower);
    let constraints = check_constraints(constraints, &mut lower);
    let minimal = s
        .minimal
        .as_ref()
        .and_then(|section| minimal::check(section, lists.load.len(), m, &mut lower));
    let attributes::CraneOptions {
        runtime,
        self_test: self_test_enabled,
        dummy_derivatives,
        rest: attrs,
    } = crane_options(&decl.attrs, cx);
    let self_test = s.sample.as_ref().and_then(|section| {
        let mu: Option<Vec<Ident>> = s
            .minimal
            .as_ref()
            .map(|m| m.body.mu1.iter().chain(&m.body.mu2).cloned().collect());
        check_sample(section, &names.coords, mu.as_deref(), &mut lower)
    });
    if cx.has_errors() {
        return None;
    }

    let params = params
        .iter()
        .zip(defaults?)
        .map(|(p, value)| Param {
            name: p.name.clone(),
            default: p.default.clone(),
            value,
            positive: p.positive,
            docs: p.docs.clone(),
        })
        .collect();
    Some(Model {
        arena,
        runtime,
        attrs,
        vis: decl.vis.clone(),
        name: decl.name.clone(),
        description: first_doc_line(&decl.attrs),
        params,
        coords: names.coords,
        n_robot,
        inputs,
        constraints,
        kinetic: kinetic?,
        forces,
        minimal,
        self_test: self_test.filter(|_| self_test_enabled),
        dummy_derivatives,
    })
}
