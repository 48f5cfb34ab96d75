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

mod minimal;

use std::collections::HashMap;

use proc_macro2::{Ident, TokenStream};

use crate::ctxt::Ctxt;
use crate::diff::Differentiator;
use crate::expr::{Arena, Id, Sym};
use crate::model::{Constraint, Model, Param, Rope, SelfTest};
use crate::parse::{BinOp, ConstraintDecl, Declaration, Expr, Function, ParamDecl, Section};

/// What a declared name is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Param,
    RobotCoord,
    LoadCoord,
    Input,
    Constraint,
    Tension,
}

impl Kind {
    fn describe(self) -> &'static str {
        match self {
            Kind::Param => "a parameter",
            Kind::RobotCoord => "a robot coordinate",
            Kind::LoadCoord => "a load coordinate",
            Kind::Input => "an input",
            Kind::Constraint => "a constraint",
            Kind::Tension => "a rope tension",
        }
    }
}

/// Names the DSL itself uses.
const RESERVED: &[(&str, &str)] = &[
    ("PI", "the constant pi"),
    ("dot", "dot(coordinate) is a velocity"),
    ("sin", "a function"),
    ("cos", "a function"),
    ("tan", "a function"),
    ("sqrt", "a function"),
    ("exp", "a function"),
    ("ln", "a function"),
    ("atan2", "a function"),
];

/// The symbol table: every declared name with its kind and index.
#[derive(Default)]
struct Names {
    map: HashMap<String, (Kind, usize)>,
    params: Vec<Ident>,
    coords: Vec<Ident>,
    inputs: Vec<Ident>,
}

impl Names {
    /// Declares `ident`; `false` if it was already declared.
    fn declare(&mut self, ident: &Ident, kind: Kind, index: usize, cx: &Ctxt) -> bool {
        let name = ident.to_string();
        if let Some((_, why)) = RESERVED.iter().find(|(r, _)| *r == name) {
            // reported, but declared anyway so that its uses do not add errors
            cx.error_at(
                ident.span(),
                format!("`{name}` is reserved ({why}) and cannot be declared"),
            );
        }
        if let Some((previous, _)) = self.map.get(&name) {
            cx.error_at(
                ident.span(),
                format!(
                    "duplicate name `{name}`: already declared as {}",
                    previous.describe()
                ),
            );
            return false;
        }
        self.map.insert(name, (kind, index));
        true
    }

    fn get(&self, ident: &Ident) -> Option<(Kind, usize)> {
        self.map.get(&ident.to_string()).copied()
    }
}

/// Where an expression stands, which decides what it may use.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Place {
    ParamDefault,
    Kinetic,
    Force,
    Constraint,
    RopeLength,
    Minimal,
}

impl Place {
    fn describe(self) -> &'static str {
        match self {
            Place::ParamDefault => "a parameter default",
            Place::Kinetic => "`kinetic`",
            Place::Force => "`forces`",
            Place::Constraint => "`constraints`",
            Place::RopeLength => "a rope length",
            Place::Minimal => "`minimal`",
        }
    }

    fn allows_velocities(self) -> bool {
        matches!(self, Place::Kinetic | Place::Force)
    }
}

fn join(idents: &[Ident]) -> String {
    idents
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Lowers expressions into the arena, reporting unknown or misplaced names.
struct Lowerer<'a> {
    arena: &'a mut Arena,
    names: &'a Names,
    cx: &'a Ctxt,
    /// What the statements of a `minimal` block have defined so far.
    minimal: Option<minimal::Scope>,
}

impl Lowerer<'_> {
    fn lower(&mut self, e: &Expr, place: Place) -> Option<Id> {
        let id = self.lower_inner(e, place)?;
        // constants are folded unless the result is not finite
        let operands_constant = match e {
            Expr::Binary { lhs, rhs, .. } => self.is_constant(lhs) && self.is_constant(rhs),
            Expr::Call { args, .. } => args.iter().all(|a| self.is_constant(a)),
            Expr::Neg { operand, .. } => self.is_constant(operand),
            _ => false,
        };
        if operands_constant && self.arena.as_const(id).is_none() {
            self.cx.error_spanned_by(
                e.range(),
                "this constant expression is not a finite number (a division by zero or a function outside its domain)",
            );
            return None;
        }
        Some(id)
    }

    /// Whether `e` is made of numbers and `PI` only.
    fn is_constant(&self, e: &Expr) -> bool {
        match e {
            Expr::Num { .. } => true,
            Expr::Name(ident) => ident == "PI",
            Expr::Dot { .. } => false,
            Expr::Neg { operand, .. } => self.is_constant(operand),
            Expr::Binary { lhs, rhs, .. } => self.is_constant(lhs) && self.is_constant(rhs),
            Expr::Call { args, .. } => args.iter().all(|a| self.is_constant(a)),
            Expr::Paren { inner, .. } => self.is_constant(inner),
        }
    }

    fn lower_inner(&mut self, e: &Expr, place: Place) -> Option<Id> {
        match e {
            Expr::Num { value, .. } => Some(self.arena.constant(*value)),
            Expr::Name(ident) => self.name(ident, place),
            Expr::Dot { coord, .. } => self.velocity(e, coord, place),
            Expr::Neg { operand, .. } => {
                let operand = self.lower(operand, place)?;
                Some(self.arena.neg(operand))
            }
            Expr::Binary { op, lhs, rhs, .. } => {
                // lower both sides before giving up, to report all errors
                let l = self.lower(lhs, place);
                let r = self.lower(rhs, place);
                let (l, r) = (l?, r?);
                Some(match op {
                    BinOp::Add => self.arena.add2(l, r),
                    BinOp::Sub => self.arena.sub(l, r),
                    BinOp::Mul => self.arena.mul2(l, r),
                    BinOp::Div => self.arena.div(l, r),
                    BinOp::Pow => match self.arena.as_const(r) {
                        Some(exponent) => self.arena.powf(l, exponent),
                        None => {
                            self.cx.error_spanned_by(
                                rhs.range(),
                                "exponent must be a constant number; for a variable exponent write exp(y * ln(x))",
                            );
                            return None;
                        }
                    },
                })
            }
            Expr::Call { func, args, .. } => {
                let lowered: Vec<Option<Id>> = args.iter().map(|a| self.lower(a, place)).collect();
                let args: Vec<Id> = lowered.into_iter().collect::<Option<_>>()?;
                Some(match func {
                    Function::Unary(f) => self.arena.func(*f, args[0]),
                    Function::Atan2 => self.arena.atan2(args[0], args[1]),
                })
            }
            Expr::Paren { inner, .. } => self.lower(inner, place),
        }
    }

    fn name(&mut self, ident: &Ident, place: Place) -> Option<Id> {
        if ident == "PI" {
            return Some(self.arena.constant(std::f64::consts::PI));
        }
        if place == Place::Minimal {
            return self.minimal_name(ident);
        }
        let span = ident.span();
        if place == Place::ParamDefault {
            let what = match self.names.get(ident) {
                Some((kind, _)) => format!("`{ident}` is {}", kind.describe()),
                None => format!("`{ident}` is unknown"),
            };
            self.cx.error_at(
                span,
                format!("parameter defaults must be constant (numbers, PI and functions of them); {what}"),
            );
            return None;
        }
        let Some((kind, index)) = self.names.get(ident) else {
            self.cx.error_at(
                span,
                format!("unknown symbol `{ident}`; {}", self.allowed(place)),
            );
            return None;
        };
        let sym = match kind {
            Kind::Param => Sym::Param(index as u16),
            Kind::RobotCoord | Kind::LoadCoord => Sym::Coord(index as u16),
            Kind::Input if place == Place::Force => Sym::Input(index as u16),
            Kind::Input => {
                self.cx.error_at(
                    span,
                    format!(
                        "input `{ident}` is not allowed in {}: inputs may appear only in `forces`",
                        place.describe()
                    ),
                );
                return None;
            }
            Kind::Constraint | Kind::Tension => {
                self.cx.error_at(
                    span,
                    format!(
                        "`{ident}` is {} and has no value in expressions; {}",
                        kind.describe(),
                        self.allowed(place)
                    ),
                );
                return None;
            }
        };
        Some(self.arena.sym(sym))
    }

    fn velocity(&mut self, e: &Expr, coord: &Ident, place: Place) -> Option<Id> {
        if place == Place::Minimal {
            self.cx.error_spanned_by(
                e.range(),
                format!(
                    "velocity `dot({coord})` is not allowed in `minimal`: the map q = phi(mu) depends on the \
                     minimal coordinates only, and its derivatives P and P' are generated (eqs. 8-9)"
                ),
            );
            return None;
        }
        match self.names.get(coord) {
            Some((Kind::RobotCoord | Kind::LoadCoord, index)) => {
                if place.allows_velocities() {
                    Some(self.arena.sym(Sym::Vel(index as u16)))
                } else {
                    self.cx.error_spanned_by(
                        e.range(),
                        format!(
                            "velocity `dot({coord})` is not allowed in {}: velocities may appear only in `kinetic` and `forces`",
                            place.describe()
                        ),
                    );
                    None
                }
            }
            Some((kind, _)) => {
                self.cx.error_at(
                    coord.span(),
                    format!(
                        "dot() takes a coordinate, but `{coord}` is {}",
                        kind.describe()
                    ),
                );
                None
            }
            None => {
                self.cx.error_at(
                    coord.span(),
                    format!(
                        "unknown coordinate `{coord}` in dot(); the coordinates are: {}",
                        join(&self.names.coords)
                    ),
                );
                None
            }
        }
    }

    /// "allowed in ...: ..." for the unknown-symbol message.
    fn allowed(&self, place: Place) -> String {
        if place == Place::Minimal {
            return self.allowed_in_minimal();
        }
        let mut kinds = Vec::new();
        if !self.names.params.is_empty() {
            kinds.push(format!("parameters ({})", join(&self.names.params)));
        }
        kinds.push(format!("coordinates ({})", join(&self.names.coords)));
        if place.allows_velocities() {
            kinds.push("velocities dot(coordinate)".to_owned());
        }
        if place == Place::Force {
            kinds.push(format!("inputs ({})", join(&self.names.inputs)));
        }
        kinds.push("PI".to_owned());
        format!("allowed in {}: {}", place.describe(), kinds.join(", "))
    }
}

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
    let kinetic = s
        .kinetic
        .as_ref()
        .and_then(|k| check_kinetic(&k.body, &mut lower));
    let forces = check_forces(decl, n_robot, &mut lower);
    let constraints = check_constraints(constraints, &mut lower);
    let minimal = s
        .minimal
        .as_ref()
        .and_then(|section| minimal::check(section, lists.load.len(), m, &mut lower));
    let (runtime, self_test_enabled, attrs) = crane_options(&decl.attrs, cx);
    let self_test = s.sample.as_ref().and_then(|section| {
        let mu: Option<Vec<Ident>> = s.minimal.as_ref().map(|m| m.body.mu1.iter().chain(&m.body.mu2).cloned().collect());
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
    })
}

/// Check the `sample` section: a constant range for every coordinate and, if
/// any minimal coordinate is named, for every minimal coordinate.
fn check_sample(
    section: &crate::parse::Section<Vec<crate::parse::SampleDecl>>,
    coords: &[Ident],
    mu: Option<&[Ident]>,
    lower: &mut Lowerer,
) -> Option<SelfTest> {
    let mut q_ranges: Vec<Option<(Expr, Expr)>> = vec![None; coords.len()];
    let mut mu_ranges: Vec<Option<(Expr, Expr)>> = vec![None; mu.map_or(0, <[Ident]>::len)];
    for item in &section.body {
        lower.lower(&item.low, Place::ParamDefault);
        lower.lower(&item.high, Place::ParamDefault);
        let slot = if let Some(i) = coords.iter().position(|c| *c == item.name) {
            &mut q_ranges[i]
        } else if let Some(k) = mu.and_then(|mu| mu.iter().position(|c| *c == item.name)) {
            &mut mu_ranges[k]
        } else {
            lower.cx.error_at(
                item.name.span(),
                format!(
                    "`{}` in `sample` is not a coordinate{}: give a range for each coordinate, e.g. `{} = 1.0 .. 10.0`",
                    item.name,
                    if mu.is_some() { " or minimal coordinate" } else { "" },
                    coords.first().map_or("x".to_string(), ToString::to_string),
                ),
            );
            continue;
        };
        if slot.is_some() {
            lower.cx.error_at(item.name.span(), format!("duplicate range for `{}` in `sample`", item.name));
        }
        *slot = Some((item.low.clone(), item.high.clone()));
    }
    let missing = |ranges: &[Option<(Expr, Expr)>], names: &[Ident]| -> Vec<String> {
        ranges.iter().zip(names).filter(|(r, _)| r.is_none()).map(|(_, n)| n.to_string()).collect()
    };
    let q_missing = missing(&q_ranges, coords);
    if !q_missing.is_empty() {
        lower.cx.error_at(
            section.keyword.span(),
            format!(
                "`sample` needs a range for every coordinate; missing: {} (write e.g. `{} = -10.0 .. 10.0`)",
                q_missing.join(", "),
                q_missing[0]
            ),
        );
        return None;
    }
    let mu_ranges = match mu {
        Some(mu) if mu_ranges.iter().any(Option::is_some) => {
            let mu_missing = missing(&mu_ranges, mu);
            if !mu_missing.is_empty() {
                lower.cx.error_at(
                    section.keyword.span(),
                    format!(
                        "`sample` names minimal coordinates but not all of them; missing: {}",
                        mu_missing.join(", ")
                    ),
                );
                return None;
            }
            Some(mu_ranges.into_iter().flatten().collect())
        }
        _ => None,
    };
    Some(SelfTest { q: q_ranges.into_iter().flatten().collect(), mu: mu_ranges })
}

/// The names of the list sections (empty where missing or empty).
struct Lists {
    robot: Vec<Ident>,
    load: Vec<Ident>,
    inputs: Vec<Ident>,
}

/// Reports missing or empty sections.
fn required_sections(decl: &Declaration, cx: &Ctxt) -> Lists {
    let s = &decl.sections;
    let name_span = decl.name.span();
    let missing = |keyword: &str, example: &str| {
        cx.error_at(
            name_span,
            format!("missing section `{keyword}`: declare it, e.g. `{example}`"),
        );
    };
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
    match &s.constraints {
        None => missing("constraints", "constraints { rope: 0.5*(x^2 + z^2 - L^2) }"),
        Some(sec) if sec.body.is_empty() => {
            cx.error_spanned_by(
                sec.range,
                "empty section `constraints`: declare at least one constraint",
            );
        }
        Some(_) => {}
    }
    lists
}

/// The symbol table; `None` if names are missing or ambiguous, since every
/// expression would then only add follow-on errors.
fn declare_names(
    params: &[ParamDecl],
    lists: &Lists,
    constraints: &[ConstraintDecl],
    cx: &Ctxt,
) -> Option<Names> {
    let mut names = Names::default();
    let mut unique = true;
    for (i, p) in params.iter().enumerate() {
        unique &= names.declare(&p.name, Kind::Param, i, cx);
    }
    for (i, c) in lists.robot.iter().enumerate() {
        unique &= names.declare(c, Kind::RobotCoord, i, cx);
    }
    for (i, c) in lists.load.iter().enumerate() {
        unique &= names.declare(c, Kind::LoadCoord, lists.robot.len() + i, cx);
    }
    for (i, u) in lists.inputs.iter().enumerate() {
        unique &= names.declare(u, Kind::Input, i, cx);
    }
    for (k, c) in constraints.iter().enumerate() {
        unique &= names.declare(&c.name, Kind::Constraint, k, cx);
    }
    for (k, c) in constraints.iter().enumerate() {
        if let Some(rope) = &c.rope {
            unique &= names.declare(&rope.tension, Kind::Tension, k, cx);
        }
    }
    names.params = params.iter().map(|p| p.name.clone()).collect();
    names.coords = lists.robot.iter().chain(&lists.load).cloned().collect();
    names.inputs = lists.inputs.clone();
    let complete = !lists.robot.is_empty() && !lists.load.is_empty() && !lists.inputs.is_empty();
    (complete && unique).then_some(names)
}

/// One input per load coordinate (eq. 1c), fewer constraints than
/// coordinates (`m < n`).
fn check_counts(decl: &Declaration, names: &Names, cx: &Ctxt) {
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
fn check_forces(decl: &Declaration, n_robot: usize, lower: &mut Lowerer<'_>) -> Vec<Id> {
    let (names, cx) = (lower.names, lower.cx);
    let zero = lower.arena.zero();
    let mut forces: Vec<Option<Id>> = vec![None; names.coords.len()];
    let mut declared = vec![false; names.coords.len()];
    let items = decl
        .sections
        .forces
        .as_ref()
        .map_or(&[][..], |f| &f.body[..]);
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
            check_force(
                coord,
                &item.force,
                id,
                index >= n_robot,
                names,
                lower.arena,
                cx,
            );
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
fn check_constraints(constraints: &[ConstraintDecl], lower: &mut Lowerer<'_>) -> Vec<Constraint> {
    let mut checked = Vec::new();
    for c in constraints {
        let g = lower.lower(&c.expr, Place::Constraint);
        let length = c
            .rope
            .as_ref()
            .map(|r| lower.lower(&r.length, Place::RopeLength));
        let Some(g) = g else { continue };
        if lower
            .arena
            .find_symbol(g, |s| matches!(s, Sym::Coord(_)))
            .is_none()
        {
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
fn check_kinetic(e: &Expr, lower: &mut Lowerer<'_>) -> Option<Id> {
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
    if ok {
        lower.lower(root, Place::Kinetic)
    } else {
        None
    }
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
                        "{NOT_QUADRATIC}: this term is cubic or of higher degree in the velocities (or not polynomial in them)"
                    ));
                }
            }
        }
    }
    // no part of degree 0 or 1: t(0) = 0 and dt/dv(0) = 0
    let zero = d.arena().zero();
    let at_rest = |arena: &mut Arena, e: Id| {
        arena.substitute(e, &mut |s| matches!(s, Sym::Vel(_)).then_some(zero))
    };
    if at_rest(d.arena(), t) != zero {
        return Err(format!(
            "{NOT_QUADRATIC}: this term has a part without velocities"
        ));
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
                return Err(format!(
                    "configuration-dependent mass matrix: the method needs a constant M, but the coefficient of this term depends on {}",
                    describe_sym(coord, names)
                ));
            }
        }
    }
    Ok(())
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
    }
}

/// Checks that a generalized force is `f(q, q') + B^T(q) u` (eq. 11c).
fn check_force(
    coord: &Ident,
    e: &Expr,
    force: Id,
    is_load: bool,
    names: &Names,
    arena: &mut Arena,
    cx: &Ctxt,
) {
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
                "{} acts on the load coordinate `{coord}`: inputs may act only on robot coordinates (B^T = [B1^T; 0], eq. 11c)",
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
                    "force on `{coord}`: the coefficient of {} depends on {}; B^T may depend only on the coordinates (eq. 11c)",
                    describe_sym(ui, names),
                    describe_sym(v, names)
                ),
            );
            return;
        }
    }
}

/// The `#[crane(...)]` options on the struct: `runtime = path` names the
/// runtime crate the generated code uses (default `::crane_runtime`; a facade
/// crate passes its own re-export so that its users need not depend on
/// `crane-runtime`), and `no_self_test` turns off the generated self-test.
/// Returns the runtime path, whether the self-test is on, and the other
/// attributes, which pass through to the struct.
fn crane_options(attrs: &[syn::Attribute], cx: &Ctxt) -> (TokenStream, bool, Vec<syn::Attribute>) {
    let mut runtime = quote::quote!(::crane_runtime);
    let mut self_test = true;
    let mut rest = Vec::new();
    for attr in attrs {
        if !attr.path().is_ident("crane") {
            rest.push(attr.clone());
            continue;
        }
        let parsed = attr.parse_args_with(|input: syn::parse::ParseStream| {
            let key: Ident = input.parse()?;
            if key == "no_self_test" {
                return Ok((key, None));
            }
            if key != "runtime" {
                return Err(syn::Error::new(
                    key.span(),
                    "unknown `crane` option: expected `runtime = path::to::crane_runtime` or `no_self_test`",
                ));
            }
            input.parse::<syn::Token![=]>()?;
            Ok((key, Some(input.parse::<TokenStream>()?)))
        });
        match parsed {
            Ok((_, None)) => self_test = false,
            Ok((_, Some(path))) if !path.is_empty() => runtime = path,
            Ok(_) => cx.error_spanned_by(attr, "`#[crane(runtime = ...)]` needs a path"),
            Err(error) => cx.syn_error(error),
        }
    }
    (runtime, self_test, rest)
}

/// The first line of the first doc comment, trimmed.
fn first_doc_line(attrs: &[syn::Attribute]) -> String {
    for attr in attrs {
        if let syn::Meta::NameValue(nv) = &attr.meta
            && nv.path.is_ident("doc")
            && let syn::Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Str(s),
                ..
            }) = &nv.value
        {
            let value = s.value();
            if let Some(line) = value.lines().map(str::trim).find(|l| !l.is_empty()) {
                return line.to_owned();
            }
        }
    }
    String::new()
}
