//! Checks of the physics a declaration states, on the differentiated model:
//! errors where the method cannot work (a kinetic energy that is not
//! positive semi-definite, a rope whose constraint does not involve its
//! length, constraints that depend on each other) and lints (warnings,
//! [`Lint`]) where a declaration is legal but almost surely not meant (a
//! weight on a coordinate without inertia).
//!
//! Numerical checks evaluate the IR at the parameters' defaults and at a
//! few pseudo-random configurations: the constraint functions are analytic
//! where they are defined, so a rank they lose at every such point they
//! lose everywhere.

use proc_macro2::Span;

use crate::expr::{Id, Sym};
use crate::model::{Kernels, Model};
use crate::parse::Declaration;

/// A kinetic energy must be positive semi-definite: a diagonal entry of the
/// mass matrix `M_ii = d^2 T / dq_i'^2` that is a negative constant (a
/// literal negative coefficient of `dot(q_i)^2`) is an error at the
/// `kinetic` keyword. Entries that depend on parameters are checked by the
/// runtime, with the parameters' values, before a run.
pub fn negative_inertia(decl: &Declaration, model: &Model, kernels: &Kernels) -> Option<syn::Error> {
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
pub fn ropes_depend_on_their_lengths(decl: &Declaration, model: &Model, kernels: &Kernels) -> Option<syn::Error> {
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

/// How many configurations the numerical checks try, and how many of them
/// must be inside the constraints' domain (no `sqrt` of a negative number)
/// for a check to conclude anything.
const TRIALS: usize = 16;
const NEEDED: usize = 4;

/// Relative size below which a constraint's gradient counts as a
/// combination of the gradients before it: independent rows at a generic
/// point leave residuals of order one, dependent ones round-off (~1e-15).
const DEPENDENT: f64 = 1e-8;

/// The constraints must be independent (`G = dg/dq` of full rank `m`, eq.
/// 3): a constraint whose gradient is a linear combination of the earlier
/// ones' at every configuration tried (a duplicated rope, a sum of two
/// constraints) is an error naming it and the constraints it depends on.
/// Without this the run stops at its first step with a Jacobian whose
/// multipliers are not unique.
pub fn dependent_constraints(model: &Model, kernels: &Kernels) -> Option<syn::Error> {
    let m = model.m();
    // per constraint: at every point tried it was dependent, and on which
    let mut dependent = vec![true; m];
    let mut on = vec![vec![false; m]; m];
    let mut points = 0;
    for env in configurations(model) {
        let rows: Vec<Vec<f64>> = (kernels.jacobian.iter())
            .map(|row| row.iter().map(|&e| model.arena.eval(e, &env)).collect())
            .collect();
        if rows.iter().flatten().any(|v| !v.is_finite()) {
            continue;
        }
        points += 1;
        for (k, (is_dependent, on)) in dependent.iter_mut().zip(&mut on).enumerate() {
            match combination(&rows[..k], &rows[k]) {
                Some(coefficients) => {
                    for (j, c) in coefficients.iter().enumerate() {
                        on[j] |= c.abs() > DEPENDENT;
                    }
                }
                None => *is_dependent = false,
            }
        }
        if points == NEEDED {
            break;
        }
    }
    if points < NEEDED {
        return None;
    }
    let k = dependent.iter().position(|&d| d)?;
    let name = &model.constraints[k].name;
    let others: Vec<String> = (0..k)
        .filter(|&j| on[k][j])
        .map(|j| format!("`{}`", model.constraints[j].name))
        .collect();
    let message = if others.is_empty() {
        format!(
            "constraint `{name}` does not depend on the coordinates (its gradient vanishes): a constraint \
             must restrict the motion, `G = dg/dq` needs full rank (eq. 3)"
        )
    } else {
        format!(
            "constraint `{name}` depends on {}: its gradient is a combination of theirs at every configuration \
             tried, so `G = dg/dq` has rank < m (eq. 3) and the constraint forces are not unique; remove it or \
             state an independent constraint",
            others.join(", ")
        )
    };
    Some(syn::Error::new(name.span(), message))
}

/// [`TRIALS`] pseudo-random configurations (the same ones at every
/// compilation), each as the values of the symbols: coordinates in
/// `+-[0.3, 1.7]` (away from zero, where lengths and angles of real cranes
/// are, and of either sign), parameters at their defaults.
fn configurations(model: &Model) -> impl Iterator<Item = impl Fn(Sym) -> f64> {
    let n = model.n();
    let params: Vec<f64> = model
        .params
        .iter()
        .map(|p| model.arena.eval(p.value, &|_| f64::NAN))
        .collect();
    let mut rng = 0x2545_f491_4f6c_dd1d_u64;
    (0..TRIALS).map(move |_| {
        let q: Vec<f64> = (0..n)
            .map(|_| {
                let (a, b) = (next_uniform(&mut rng), next_uniform(&mut rng));
                let magnitude = 0.3 + 1.4 * a;
                if b < 0.25 { -magnitude } else { magnitude }
            })
            .collect();
        let params = params.clone();
        move |s: Sym| match s {
            Sym::Coord(i) => q[i as usize],
            Sym::Param(i) => params[i as usize],
            _ => f64::NAN,
        }
    })
}

/// A rope's length must be its length: the constraint loosens (or
/// tightens) as the length grows, the same way at every configuration where
/// the length is positive, since it relates the length to the distance
/// between the rope's ends. A length along which the constraint changes
/// either way (a trolley's position `s` in `0.5*((x - s)^2 + z^2 - L^2)`
/// marked `#[rope(N = s)]`) gives `-lambda dg/ds`, a horizontal force, as
/// the rope's tension: an error at the rope's tension name.
pub fn ropes_pull_along_their_lengths(decl: &Declaration, model: &Model, kernels: &Kernels) -> Option<syn::Error> {
    let constraints = &decl.sections.constraints.as_ref()?.body;
    let declared = constraints.iter().filter_map(|c| c.rope.as_ref().map(|r| (c, r)));
    for (((constraint, rope), (_, lowered)), &along) in declared.zip(model.ropes()).zip(&kernels.rope_along) {
        // the signs of dg/dL where L > 0
        let (mut loosens, mut tightens) = (false, false);
        for env in configurations(model) {
            let (length, rate) = (model.arena.eval(lowered.length, &env), model.arena.eval(along, &env));
            if length > 0.0 && rate.is_finite() {
                loosens |= rate < 0.0;
                tightens |= rate > 0.0;
            }
        }
        if loosens && tightens {
            let length = &rope.length;
            return Some(syn::Error::new(
                rope.tension.span(),
                format!(
                    "`{length}` is not the length of rope `{}`: constraint `{}` grows with it at some \
                     configurations and shrinks at others, so `-lambda dg/d{length}` is no rope's pull; a rope's \
                     length is what its winch pays out (or a sling's length), and its constraint relates it to \
                     the distance between the rope's ends, e.g. `0.5*((x - s)^2 + z^2 - L^2)` with \
                     `#[rope(N = L)]`",
                    rope.tension, constraint.name
                ),
            ));
        }
    }
    None
}

/// The coefficients `c` with `row = sum_j c_j rows[j]` when `row` is such a
/// combination (relative residual below [`DEPENDENT`]), else `None`. Least
/// squares by modified Gram-Schmidt on the rows, tracking each orthogonal
/// row as a combination of the original ones.
fn combination(rows: &[Vec<f64>], row: &[f64]) -> Option<Vec<f64>> {
    let scale = row.iter().map(|v| v * v).sum::<f64>().sqrt();
    if scale == 0.0 {
        return Some(vec![0.0; rows.len()]);
    }
    // basis[b] = (orthonormal vector, its expression in the rows)
    let mut basis: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for (j, r) in rows.iter().enumerate() {
        let mut v = r.clone();
        let mut expr = vec![0.0; rows.len()];
        expr[j] = 1.0;
        for (e, ex) in &basis {
            let d: f64 = v.iter().zip(e).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(e).for_each(|(a, b)| *a -= d * b);
            expr.iter_mut().zip(ex).for_each(|(a, b)| *a -= d * b);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let row_norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > DEPENDENT * row_norm {
            v.iter_mut().for_each(|a| *a /= norm);
            expr.iter_mut().for_each(|a| *a /= norm);
            basis.push((v, expr));
        }
    }
    let mut residual = row.to_vec();
    let mut coefficients = vec![0.0; rows.len()];
    for (e, ex) in &basis {
        let d: f64 = residual.iter().zip(e).map(|(a, b)| a * b).sum();
        residual.iter_mut().zip(e).for_each(|(a, b)| *a -= d * b);
        coefficients.iter_mut().zip(ex).for_each(|(a, b)| *a += d * b);
    }
    let left = residual.iter().map(|v| v * v).sum::<f64>().sqrt();
    (left <= DEPENDENT * scale).then_some(coefficients)
}

/// A uniform number in `[0, 1)` from a xorshift generator: the points are
/// the same on every build.
fn next_uniform(state: &mut u64) -> f64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

/// A warning about a legal declaration that is almost surely not meant:
/// emitted as the use of a deprecated constant named [`Lint::name`] with
/// the span of the culprit, so the compiler prints [`Lint::message`] there
/// (and `#![deny(warnings)]` turns it into an error).
pub struct Lint {
    /// Where the compiler points.
    pub span: Span,
    /// A snake-case name that says what is wrong.
    pub name: String,
    /// What is wrong and what to write instead.
    pub message: String,
}

/// The lints of a checked model: a coordinate that carries a weight (a
/// force that depends on neither the coordinates, the velocities nor the
/// inputs, like `z: -m_l*g`) but has no inertia in the kinetic energy.
/// Nothing accelerates it, so the constraint force holds the weight alone:
/// the run gives the rope a constant tension and inputs without the
/// load's inertia. Massless pulleys without weight, and springs on massless
/// elements, are not flagged.
pub fn physics_lints(decl: &Declaration, model: &Model, kernels: &Kernels) -> Vec<Lint> {
    let Some(forces) = decl.sections.forces.as_ref() else {
        return Vec::new();
    };
    let mut lints = Vec::new();
    for (i, coord) in model.coords.iter().enumerate() {
        let f: Id = kernels.f[i];
        let weight = !model.arena.is_zero(f)
            && model
                .arena
                .find_symbol(f, |s| matches!(s, Sym::Coord(_) | Sym::Vel(_) | Sym::Input(_)))
                .is_none();
        let massless = kernels.mass[i].iter().all(|&e| model.arena.is_zero(e));
        if !(weight && massless) {
            continue;
        }
        let span = forces
            .body
            .iter()
            .find(|force| force.coord == *coord)
            .map_or(model.name.span(), |force| force.coord.span());
        lints.push(Lint {
            span,
            name: format!("{}_has_a_force_but_no_inertia", super::resolve::key(coord)),
            message: format!(
                "`{coord}` carries a constant force but has no inertia: the kinetic energy has no `dot({coord})` \
                 term, so nothing accelerates it and the constraint force holds the force alone (a constant \
                 rope tension, inputs without the load's inertia); add its mass, e.g. `0.5*m*dot({coord})^2`"
            ),
        });
    }
    lints
}
