//! The checks of what the method assumes (paper, sect. 2): the required
//! sections and the counts, the kinetic energy as a quadratic form with a
//! constant mass matrix, forces linear in the inputs acting on the robot
//! coordinates, and constraints that depend on the coordinates. Each check
//! lowers what it checks.

use proc_macro2::Ident;

use super::resolve::{Kind, Lists, Lowerer, Names, Place, join};
use crate::ctxt::Ctxt;
use crate::diff::Differentiator;
use crate::expr::{Arena, Func, Id, Node, Sym};
use crate::model::{Constraint, Rope};
use crate::parse::{BinOp, ConstraintDecl, Declaration, Expr, Section};

/// Reports a missing section at the crane's name, with an example of it.
fn missing_section(decl: &Declaration, cx: &Ctxt, keyword: &str, example: &str) {
    cx.error_at(
        decl.name.span(),
        format!("missing section `{keyword}`: declare it, e.g. `{example}`"),
    );
}

/// Reports missing or empty sections.
pub(super) fn required_sections(decl: &Declaration, cx: &Ctxt) -> Lists {
    let s = &decl.sections;
    let missing = |keyword: &str, example: &str| missing_section(decl, cx, keyword, example);
    let list = |section: &Option<Section<Vec<Ident>>>, keyword: &str, example: &str| match section {
        None => {
            missing(keyword, example);
            Vec::new()
        }
        Some(sec) if sec.body.is_empty() => {
            cx.error_spanned_by(
                sec.range,
                format!("empty section `{keyword}`: declare at least one name"),
            );
            Vec::new()
        }
        Some(sec) => sec.body.clone(),
    };
    let lists = Lists {
        robot: list(&s.robot, "robot", "robot [L1, L2, x0, z0]"),
        load: list(&s.load, "load", "load [x, z]"),
        inputs: list(&s.inputs, "inputs", "inputs [u1, u2]"),
    };
    if s.kinetic.is_none() {
        missing("kinetic", "kinetic = 0.5*m*(dot(x)^2 + dot(z)^2);");
    }
    match &s.forces {
        None => missing("forces", "forces { L1: u1/r1, z: -m*g }"),
        Some(sec) if sec.body.is_empty() => {
            cx.error_spanned_by(
                sec.range,
                "empty section `forces`: every input must act on some coordinate",
            );
        }
        Some(_) => {}
    }
    lists
}

/// Reports a missing or empty `constraints` section; run after the kinetic
/// energy's checks, whose message for an angle formulation says which
/// constraint to write.
pub(super) fn required_constraints(decl: &Declaration, cx: &Ctxt) {
    match &decl.sections.constraints {
        None => missing_section(decl, cx, "constraints", "constraints { rope: 0.5*(x^2 + z^2 - L^2) }"),
        Some(sec) if sec.body.is_empty() => {
            cx.error_spanned_by(
                sec.range,
                "empty section `constraints`: declare at least one constraint",
            );
        }
        Some(_) => {}
    }
}

/// One input per load coordinate (eq. 1c), fewer constraints than
/// coordinates (`m < n`).
pub(super) fn check_counts(decl: &Declaration, names: &Names, cx: &Ctxt) {
    let s = &decl.sections;
    let (n, a, load) = (
        names.coords.len(),
        names.inputs.len(),
        s.load.as_ref().map_or(0, |l| l.body.len()),
    );
    if let Some(sec) = &s.inputs
        && a != load
    {
        cx.error_spanned_by(
            sec.range,
            format!(
                "number of inputs ({a}) must equal the number of load coordinates ({load}): \
                 each input drives one prescribed output (eq. 1c)"
            ),
        );
    }
    if let Some(sec) = &s.constraints
        && sec.body.len() >= n
    {
        cx.error_spanned_by(
            sec.range,
            format!(
                "number of constraints ({}) must be below the number of coordinates ({n}): \
                 the crane needs a degree of freedom (m < n)",
                sec.body.len()
            ),
        );
    }
}

/// Lowers and checks the generalized forces; the total force on each
/// coordinate (0 where none is declared).
pub(super) fn check_forces(decl: &Declaration, n_robot: usize, lower: &mut Lowerer<'_>) -> Vec<Id> {
    let (names, cx) = (lower.names, lower.cx);
    let zero = lower.arena.zero();
    let mut forces: Vec<Option<Id>> = vec![None; names.coords.len()];
    let mut declared = vec![false; names.coords.len()];
    let items = decl.sections.forces.as_ref().map_or(&[][..], |f| &f.body[..]);
    for item in items {
        let coord = &item.coord;
        let index = match names.get(coord) {
            Some((Kind::RobotCoord | Kind::LoadCoord, i)) => i,
            Some((kind, _)) => {
                cx.error_at(
                    coord.span(),
                    format!(
                        "`{coord}` is {}, not a coordinate: `forces` maps coordinates to generalized forces",
                        kind.describe()
                    ),
                );
                continue;
            }
            None => {
                cx.error_at(
                    coord.span(),
                    format!(
                        "unknown coordinate `{coord}` in `forces`; the coordinates are: {}",
                        join(&names.coords)
                    ),
                );
                continue;
            }
        };
        if std::mem::replace(&mut declared[index], true) {
            cx.error_at(
                coord.span(),
                format!("duplicate force on `{coord}`: write the sum as one expression"),
            );
            continue;
        }
        if let Some(id) = lower.lower(&item.force, Place::Force) {
            check_force(coord, &item.force, id, index >= n_robot, names, lower.arena, cx);
            forces[index] = Some(id);
        }
    }
    if !items.is_empty() {
        let mut used = vec![false; names.inputs.len()];
        for &id in forces.iter().flatten() {
            for sym in lower.arena.symbols(id) {
                if let Sym::Input(k) = sym {
                    used[k as usize] = true;
                }
            }
        }
        for (u, used) in names.inputs.iter().zip(used) {
            if !used {
                cx.error_at(
                    u.span(),
                    format!("input `{u}` appears in no force: B^T would have a zero column"),
                );
            }
        }
    }
    forces.into_iter().map(|f| f.unwrap_or(zero)).collect()
}

/// Lowers the constraints and their rope lengths.
pub(super) fn check_constraints(constraints: &[ConstraintDecl], lower: &mut Lowerer<'_>) -> Vec<Constraint> {
    let mut checked = Vec::new();
    for c in constraints {
        let g = lower.lower(&c.expr, Place::Constraint);
        let length = c.rope.as_ref().map(|r| lower.lower(&r.length, Place::RopeLength));
        let Some(g) = g else { continue };
        if lower.arena.find_symbol(g, |s| matches!(s, Sym::Coord(_))).is_none() {
            lower.cx.error_spanned_by(
                c.expr.range(),
                format!("constraint `{}` does not depend on any coordinate", c.name),
            );
        }
        let rope = match (&c.rope, length) {
            (Some(r), Some(Some(length))) => Some(Rope {
                tension: r.tension.clone(),
                length,
            }),
            _ => None,
        };
        checked.push(Constraint {
            name: c.name.clone(),
            g,
            rope,
        });
    }
    checked
}

/// The top-level additive terms of `e`: `a + b - c → [a, b, c]`.
fn additive_terms<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match e {
        Expr::Binary {
            op: BinOp::Add | BinOp::Sub,
            lhs,
            rhs,
            ..
        } => {
            additive_terms(lhs, out);
            additive_terms(rhs, out);
        }
        _ => out.push(e),
    }
}

/// Lowers the kinetic energy term by term and checks that each term is a
/// quadratic form in the velocities with constant coefficients (eq. 28).
pub(super) fn check_kinetic(e: &Expr, lower: &mut Lowerer<'_>) -> Option<Id> {
    let mut root = e;
    while let Expr::Paren { inner, .. } = root {
        root = inner;
    }
    let mut terms = Vec::new();
    additive_terms(root, &mut terms);
    let mut ok = true;
    for term in terms {
        match lower.lower(term, Place::Kinetic) {
            Some(id) => {
                if let Err(message) = quadratic_form(lower.arena, id, lower.names) {
                    lower.cx.error_spanned_by(term.range(), message);
                    ok = false;
                }
            }
            None => ok = false,
        }
    }
    // the whole energy, with signs, once every term is known to be fine
    if ok { lower.lower(root, Place::Kinetic) } else { None }
}

/// `Ok` if `t` is `1/2 v^T H v` with a constant `H`, else why not.
fn quadratic_form(arena: &mut Arena, t: Id, names: &Names) -> Result<(), String> {
    const NOT_QUADRATIC: &str = "not a quadratic form in the velocities";
    let vels: Vec<Sym> = arena
        .symbols(t)
        .into_iter()
        .filter(|s| matches!(s, Sym::Vel(_)))
        .collect();
    if vels.is_empty() {
        return Err(format!(
            "{NOT_QUADRATIC}: this term contains no velocity (a potential belongs in `forces`, as a generalized force)"
        ));
    }
    let mut d = Differentiator::new(arena);
    // third derivatives vanish: degree <= 2
    for (i, &vi) in vels.iter().enumerate() {
        let di = d.diff(t, vi);
        for (j, &vj) in vels.iter().enumerate().skip(i) {
            let dij = d.diff(di, vj);
            for &vk in &vels[j..] {
                let dijk = d.diff(dij, vk);
                if !d.arena().is_zero(dijk) {
                    return Err(format!(
                        "{NOT_QUADRATIC}: this term is cubic or of higher degree in the velocities (or not \
                            polynomial in them)"
                    ));
                }
            }
        }
    }
    // no part of degree 0 or 1: t(0) = 0 and dt/dv(0) = 0
    let zero = d.arena().zero();
    let at_rest = |arena: &mut Arena, e: Id| arena.substitute(e, &mut |s| matches!(s, Sym::Vel(_)).then_some(zero));
    if at_rest(d.arena(), t) != zero {
        return Err(format!("{NOT_QUADRATIC}: this term has a part without velocities"));
    }
    for &vi in &vels {
        let di = d.diff(t, vi);
        if at_rest(d.arena(), di) != zero {
            return Err(format!(
                "{NOT_QUADRATIC}: this term is linear in {}",
                describe_sym(vi, names)
            ));
        }
    }
    // constant coefficients
    for (i, &vi) in vels.iter().enumerate() {
        let di = d.diff(t, vi);
        for &vj in &vels[i..] {
            let dij = d.diff(di, vj);
            if let Some(coord) = d.arena().find_symbol(dij, |s| matches!(s, Sym::Coord(_))) {
                let mut message = format!(
                    "configuration-dependent mass matrix: the method needs a constant M, but the coefficient \
                        of this term depends on {}",
                    describe_sym(coord, names),
                );
                if is_angle(d.arena(), dij, coord) {
                    message += &format!("; {}", cartesian_rewrite(coord, names));
                }
                return Err(message);
            }
        }
    }
    Ok(())
}

/// Whether `coord` enters `e` through a `sin`, `cos` or `tan`: an angle.
fn is_angle(arena: &Arena, e: Id, coord: Sym) -> bool {
    arena.reachable([e]).into_iter().any(|n| match arena.node(n) {
        Node::Func(Func::Sin | Func::Cos | Func::Tan, a) => arena.symbols(*a).contains(&coord),
        _ => false,
    })
}

/// How to write a kinetic energy whose mass matrix depends on the angle
/// `coord` (a pendulum's, typically) with a constant one: the load's position as
/// coordinates, its rope a constraint (sect. 2, eq. 28).
fn cartesian_rewrite(coord: Sym, names: &Names) -> String {
    let Sym::Coord(i) = coord else {
        return String::new();
    };
    let angle = &names.coords[i as usize];
    let trolley = names
        .coords
        .iter()
        .find(|c| *c != angle)
        .map_or("s".to_string(), |c| c.to_string());
    format!(
        "write it with the load's position instead of `{angle}`: the load's coordinates `x`, `z` (z up) in \
         `load`, the rope length `L` in `robot` (or a parameter), the kinetic energy \
         `0.5*m_l*(dot(x)^2 + dot(z)^2)` plus the robot's terms, gravity as the force `z: -m_l*g`, and the \
         rope as a constraint, `#[rope(N = L)] rope: 0.5*((x - {trolley})^2 + z^2 - L^2)`; `{angle}` then \
         follows from the positions (sin({angle}) = (x - {trolley})/L)"
    )
}

fn describe_sym(sym: Sym, names: &Names) -> String {
    match sym {
        Sym::Coord(i) => format!("the coordinate `{}`", names.coords[i as usize]),
        Sym::Vel(i) => format!("the velocity `dot({})`", names.coords[i as usize]),
        Sym::Input(k) => format!("the input `{}`", names.inputs[k as usize]),
        Sym::Param(i) => format!("the parameter `{}`", names.params[i as usize]),
        Sym::Lambda(k) => format!("lambda_{}", k + 1),
        Sym::Mu(k) => format!("the minimal coordinate number {}", k + 1),
        Sym::MuDot(k) => format!("the velocity of minimal coordinate number {}", k + 1),
        Sym::Jet(j, k) => format!("derivative {k} of unknown number {}", j + 1),
    }
}

/// Checks that a generalized force is `f(q, q') + B^T(q) u` (eq. 11c).
fn check_force(coord: &Ident, e: &Expr, force: Id, is_load: bool, names: &Names, arena: &mut Arena, cx: &Ctxt) {
    let inputs: Vec<Sym> = arena
        .symbols(force)
        .into_iter()
        .filter(|s| matches!(s, Sym::Input(_)))
        .collect();
    if inputs.is_empty() {
        return;
    }
    if is_load {
        cx.error_spanned_by(
            e.range(),
            format!(
                "{} acts on the load coordinate `{coord}`: inputs may act only on robot coordinates (B^T = \
                    [B1^T; 0], eq. 11c)",
                describe_sym(inputs[0], names)
            ),
        );
        return;
    }
    let mut d = Differentiator::new(arena);
    for (i, &ui) in inputs.iter().enumerate() {
        let di = d.diff(force, ui);
        for &uj in &inputs[i..] {
            let dij = d.diff(di, uj);
            if !d.arena().is_zero(dij) {
                cx.error_spanned_by(
                    e.range(),
                    format!("force on `{coord}` is not linear in the inputs: B^T must not depend on u (eq. 11c)"),
                );
                return;
            }
        }
        if let Some(v) = d.arena().find_symbol(di, |s| matches!(s, Sym::Vel(_))) {
            cx.error_spanned_by(
                e.range(),
                format!(
                    "force on `{coord}`: the coefficient of {} depends on {}; B^T may depend only on the \
                        coordinates (eq. 11c)",
                    describe_sym(ui, names),
                    describe_sym(v, names)
                ),
            );
            return;
        }
    }
}
