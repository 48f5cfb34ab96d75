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
use resolve::{Lowerer, Place, declare_names};
use rules::{check_constraints, check_counts, check_forces, check_kinetic, required_sections};
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
    for p in params {
        lower.lower(&p.default, Place::ParamDefault);
    }
    let kinetic = s.kinetic.as_ref().and_then(|k| check_kinetic(&k.body, &mut lower));
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
        .map(|p| Param {
            name: p.name.clone(),
            default: p.default.clone(),
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

/// A kinetic energy must be positive semi-definite: a diagonal entry of the
/// mass matrix `M_ii = d^2 T / dq_i'^2` that is a negative constant (a
/// literal negative coefficient of `dot(q_i)^2`) is an error at the
/// `kinetic` keyword. Entries that depend on parameters are checked by the
/// runtime, with the parameters' values, before a run.
pub fn negative_inertia(
    decl: &crate::parse::Declaration,
    model: &crate::model::Model,
    kernels: &crate::model::Kernels,
) -> Option<syn::Error> {
    let kinetic = decl.sections.kinetic.as_ref()?;
    let (i, value) = (0..model.coords.len()).find_map(|i| {
        model
            .arena
            .as_const(kernels.mass[i][i])
            .filter(|v| *v < 0.0)
            .map(|v| (i, v))
    })?;
    let coord = &model.coords[i];
    Some(syn::Error::new(
        kinetic.keyword.span(),
        format!(
            "the kinetic energy gives `{coord}` the negative inertia {value} (the coefficient of `dot({coord})^2` is \
             {}): a kinetic energy must be positive semi-definite",
            value / 2.0
        ),
    ))
}

/// A rope's constraint must depend on the rope's length: its tension is
/// the constraint's generalized force along that length (`N = -lambda
/// dg/dL`), which is zero for a constraint that does not change with `L`
/// (a rail `h - 1.0` marked as a rope once reported a tension of -2602 N).
/// The error points at the rope's tension name.
pub fn ropes_depend_on_their_lengths(
    decl: &crate::parse::Declaration,
    model: &crate::model::Model,
    kernels: &crate::model::Kernels,
) -> Option<syn::Error> {
    let constraints = &decl.sections.constraints.as_ref()?.body;
    // the declared ropes, the model's and the kernels' are in constraint order
    let declared = constraints.iter().filter_map(|c| c.rope.as_ref().map(|r| (c, r)));
    for (((constraint, rope), (_, lowered)), &along) in declared.zip(model.ropes()).zip(&kernels.rope_along) {
        if !model.arena.is_zero(along) {
            continue;
        }
        let length = &rope.length;
        let message = if crate::model::length_variables(&model.arena, lowered.length).is_empty() {
            format!(
                "the length `{length}` of rope `{}` is a number: a rope's length is a coordinate (a winch's \
                 rope), a parameter (a sling) or an expression of them, so that its tension, the constraint's \
                 force along the length, is defined",
                rope.tension
            )
        } else {
            format!(
                "constraint `{}` does not depend on the length `{length}` of rope `{}`, so it exerts no force \
                 along the rope: a rope's constraint relates its length to the distance between its ends, e.g. \
                 `0.5*((x - s)^2 + z^2 - L^2)`; for a constraint that is no rope, remove `#[rope(...)]`",
                constraint.name, rope.tension
            )
        };
        return Some(syn::Error::new(rope.tension.span(), message));
    }
    None
}
