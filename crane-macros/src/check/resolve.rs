//! Name resolution and lowering: the symbol table of the declared names,
//! and the [`Lowerer`] that turns the expressions of the syntax tree into
//! the IR, reporting unknown names and names used where they have no place
//! (an input outside `forces`, a velocity outside `kinetic` and `forces`).

use std::collections::HashMap;

use proc_macro2::Ident;
use syn::ext::IdentExt;

use super::minimal;
use crate::ctxt::Ctxt;
use crate::expr::{Arena, Id, Sym};
use crate::parse::{BinOp, ConstraintDecl, Expr, Function, ParamDecl};

/// What a declared name is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Kind {
    Param,
    RobotCoord,
    LoadCoord,
    Input,
    Constraint,
    Tension,
}

impl Kind {
    pub(super) fn describe(self) -> &'static str {
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
pub(super) const RESERVED: &[(&str, &str)] = &[
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
pub(super) struct Names {
    map: HashMap<String, (Kind, usize)>,
    pub(super) params: Vec<Ident>,
    pub(super) coords: Vec<Ident>,
    pub(super) inputs: Vec<Ident>,
}

impl Names {
    /// Declares `ident`; `false` if it was already declared.
    fn declare(&mut self, ident: &Ident, kind: Kind, index: usize, cx: &Ctxt) -> bool {
        let name = key(ident);
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
                format!("duplicate name `{name}`: already declared as {}", previous.describe()),
            );
            return false;
        }
        self.map.insert(name, (kind, index));
        true
    }

    pub(super) fn get(&self, ident: &Ident) -> Option<(Kind, usize)> {
        self.map.get(&key(ident)).copied()
    }
}

/// The name an identifier declares: a raw identifier's without its `r#`
/// (`r#x` and `x` are one name in Rust, and would be one local of the
/// generated code).
pub(super) fn key(ident: &Ident) -> String {
    ident.unraw().to_string()
}

/// Where an expression stands, which decides what it may use.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Place {
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

pub(super) fn join(idents: &[Ident]) -> String {
    idents.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
}

/// Lowers expressions into the arena, reporting unknown or misplaced names.
pub(super) struct Lowerer<'a> {
    pub(super) arena: &'a mut Arena,
    pub(super) names: &'a Names,
    pub(super) cx: &'a Ctxt,
    /// What the statements of a `minimal` block have defined so far.
    pub(super) minimal: Option<minimal::Scope>,
}

impl Lowerer<'_> {
    pub(super) fn lower(&mut self, e: &Expr, place: Place) -> Option<Id> {
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
                // each parameter is set on its own (`Crane::set_parameter`,
                // `--param`), so a default cannot follow another's value
                Some((Kind::Param, _)) => format!(
                    "`{ident}` is a parameter, set on its own at run time, so a default cannot follow it: write \
                     the number, or use `{ident}` where the derived value is needed (in `kinetic`, `forces` or \
                     `constraints`)"
                ),
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
            let hint = self
                .closest(ident, place)
                .map(|name| format!("did you mean `{name}`? "))
                .unwrap_or_default();
            self.cx
                .error_at(span, format!("unknown symbol `{ident}`; {hint}{}", self.allowed(place)));
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
                            "velocity `dot({coord})` is not allowed in {}: velocities may appear only in \
                                `kinetic` and `forces`",
                            place.describe()
                        ),
                    );
                    None
                }
            }
            Some((kind, _)) => {
                self.cx.error_at(
                    coord.span(),
                    format!("dot() takes a coordinate, but `{coord}` is {}", kind.describe()),
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

    /// The name allowed at `place` closest to the unknown `ident` (a
    /// misspelling: at most a third of its letters off, at least one, for a
    /// name of three letters or more; only case for a shorter one, a change
    /// of case counting half), if any.
    fn closest(&self, ident: &Ident, place: Place) -> Option<String> {
        let unknown = key(ident);
        let mut names: Vec<String> = self.names.params.iter().chain(&self.names.coords).map(key).collect();
        if place == Place::Force {
            names.extend(self.names.inputs.iter().map(key));
        }
        names.push("PI".to_owned());
        // a name of one or two letters only differs in case (`pi` for `PI`):
        // any other one-letter change would suggest a different symbol
        let letters = unknown.chars().count();
        let limit = if letters >= 3 {
            (letters / 3).max(1) as f64
        } else {
            0.5 * letters as f64
        };
        names
            .into_iter()
            .map(|name| (edit_distance(&unknown, &name), name))
            .filter(|(distance, _)| *distance <= limit)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, name)| name)
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

/// The names of the list sections (empty where missing or empty).
pub(super) struct Lists {
    pub(super) robot: Vec<Ident>,
    pub(super) load: Vec<Ident>,
    pub(super) inputs: Vec<Ident>,
}

/// The symbol table; `None` if names are missing or ambiguous, since every
/// expression would then only add follow-on errors.
pub(super) fn declare_names(
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

/// Levenshtein distance between `a` and `b`, a change of case counting half.
fn edit_distance(a: &str, b: &str) -> f64 {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut previous: Vec<f64> = (0..=b.len()).map(|j| j as f64).collect();
    for (i, &ca) in a.iter().enumerate() {
        let mut current = vec![(i + 1) as f64; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let change = if ca == cb {
                0.0
            } else if ca.eq_ignore_ascii_case(&cb) {
                0.5
            } else {
                1.0
            };
            current[j + 1] = (previous[j] + change).min(previous[j + 1] + 1.0).min(current[j] + 1.0);
        }
        previous = current;
    }
    previous[b.len()]
}
