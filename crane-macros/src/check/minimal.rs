//! Checks of a `minimal` block: the map `q = phi(mu)` to minimal
//! coordinates (paper sect. 3.2, eqs. 6-12).
//!
//! ```text
//! minimal [beta, gamma | theta, L] {          // mu = [mu1 | mu2]
//!     let d = l*sin(gamma - beta)/sin(gamma);  // an abbreviation
//!     L0 = d;  x0 = -d*sin(alpha - beta);  ... // one line per coordinate
//!     x = x0 + L*sin(theta);                   // may use x0, mapped above
//! }
//! ```
//!
//! The rules:
//! - `f = n - m` minimal coordinates, the last `a` (after `|`) are `mu2`,
//!   one per load coordinate, so that `D2 phi_x` is square (eq. 12);
//! - minimal coordinates and `let` names are new names: they may not reuse
//!   (shadow) a parameter, coordinate, input, constraint, tension, another
//!   minimal coordinate or `let`, or a reserved name;
//! - every redundant coordinate is mapped exactly once, and every minimal
//!   coordinate appears in the map (else `P` has a zero column);
//! - a right-hand side may use the parameters, the minimal coordinates,
//!   `PI`, and the `let` names and coordinates defined *above* it: the block
//!   reads top to bottom like Rust `let`s. A mapped coordinate stands for
//!   its mapping (it is substituted), so `x = x0 + L*sin(theta)` is
//!   `phi_x = phi_x0 + L sin(theta)`. Since only lines above can be used, a
//!   definition can never be circular.

use std::collections::HashMap;

use proc_macro2::Ident;

use super::resolve::{Kind, Lowerer, Names, Place, RESERVED, join, key};
use crate::expr::{Id, Sym};
use crate::model::Minimal;
use crate::parse::{MinimalDecl, MinimalStmt, Section};

/// What the statements of a `minimal` block define, as they are checked top
/// to bottom.
pub struct Scope {
    /// The minimal coordinates `mu = [mu1; mu2]`.
    mu: Vec<Ident>,
    /// Statement index of the (first, valid) definition of each `let`.
    let_at: HashMap<String, usize>,
    /// Values of the `let`s above the current statement (`None` if the value
    /// had errors, so that its uses add none).
    let_values: HashMap<String, Option<Id>>,
    /// The `let` names above the current statement, for messages.
    lets_above: Vec<Ident>,
    /// Statement index of the (first) mapping of each coordinate.
    coord_at: Vec<Option<usize>>,
    /// Mappings of the coordinates above the current statement (the inner
    /// `None` if the mapping had errors).
    coord_values: Vec<Option<Option<Id>>>,
    /// Index of the statement being checked.
    statement: usize,
}

/// Checks the block and lowers the map; `None` if anything was reported.
/// `a` is the number of load coordinates, `m` of constraints.
pub(super) fn check(section: &Section<MinimalDecl>, a: usize, m: usize, lower: &mut Lowerer<'_>) -> Option<Minimal> {
    let (names, cx) = (lower.names, lower.cx);
    let decl = &section.body;
    let n = names.coords.len();
    let errors_before = cx.error_count();

    // --- the split [mu1 | mu2] (eq. 12) and the count f = n - m
    let mu: Vec<Ident> = decl.mu1.iter().chain(&decl.mu2).cloned().collect();
    if decl.mu2.len() != a {
        cx.error_at(
            decl.split,
            format!(
                "mu2 (after `|`) has {} {}, but there {} {a} load {} ({}): mu2 needs one entry per load \
                 coordinate, so that D2 phi_x is square (eq. 12)",
                decl.mu2.len(),
                plural(decl.mu2.len(), "entry", "entries"),
                if a == 1 { "is" } else { "are" },
                plural(a, "coordinate", "coordinates"),
                join(&names.coords[n - a..]),
            ),
        );
    }
    if m < n && mu.len() != n - m {
        cx.error_at(
            decl.split,
            format!(
                "`minimal` declares {} minimal {} ({}), but the crane has f = n - m = {n} - {m} = {} degrees \
                 of freedom",
                mu.len(),
                plural(mu.len(), "coordinate", "coordinates"),
                join(&mu),
                n - m
            ),
        );
    }

    // --- names: minimal coordinates and `let`s are new names
    let mut scope = Scope {
        mu: Vec::new(),
        let_at: HashMap::new(),
        let_values: HashMap::new(),
        lets_above: Vec::new(),
        coord_at: vec![None; n],
        coord_values: vec![None; n],
        statement: 0,
    };
    for ident in &mu {
        let taken = if scope.mu.contains(ident) {
            Some("a minimal coordinate".to_owned())
        } else {
            taken_by(lower, ident)
        };
        if let Some(what) = taken {
            cx.error_at(
                ident.span(),
                format!(
                    "duplicate name `{ident}`: already declared as {what}; minimal coordinates need names of \
                     their own"
                ),
            );
        }
        // declared even if duplicate, so that its uses add no errors
        if !scope.mu.contains(ident) {
            scope.mu.push(ident.clone());
        }
    }
    for (i, stmt) in decl.body.iter().enumerate() {
        match stmt {
            MinimalStmt::Let { name, .. } => {
                let taken = if scope.mu.contains(name) {
                    Some("a minimal coordinate".to_owned())
                } else if scope.let_at.contains_key(&name.to_string()) {
                    Some("a `let` above".to_owned())
                } else {
                    taken_by(lower, name)
                };
                match taken {
                    Some(what) => cx.error_at(
                        name.span(),
                        format!(
                            "`let {name}` would shadow `{name}`, which is {what}: choose another name for the \
                             abbreviation"
                        ),
                    ),
                    None => {
                        scope.let_at.insert(name.to_string(), i);
                    }
                }
            }
            MinimalStmt::Assign { coord, .. } => match names.get(coord) {
                Some((Kind::RobotCoord | Kind::LoadCoord, k)) => {
                    if scope.coord_at[k].is_some() {
                        cx.error_at(
                            coord.span(),
                            format!(
                                "coordinate `{coord}` is mapped twice: the map gives each coordinate one \
                                 expression"
                            ),
                        );
                    } else {
                        scope.coord_at[k] = Some(i);
                    }
                }
                Some((kind, _)) => cx.error_at(
                    coord.span(),
                    format!(
                        "`{coord}` is {}, not a coordinate: {}",
                        kind.describe(),
                        left_hand_sides(names)
                    ),
                ),
                None if scope.mu.contains(coord) => cx.error_at(
                    coord.span(),
                    format!(
                        "`{coord}` is a minimal coordinate, not a redundant one: {}",
                        left_hand_sides(names)
                    ),
                ),
                None if scope.let_at.contains_key(&coord.to_string()) => cx.error_at(
                    coord.span(),
                    format!(
                        "`{coord}` is a `let` abbreviation, not a coordinate: {}",
                        left_hand_sides(names)
                    ),
                ),
                None => cx.error_at(
                    coord.span(),
                    format!(
                        "unknown coordinate `{coord}` in `minimal`; the coordinates are: {}",
                        join(&names.coords)
                    ),
                ),
            },
        }
    }

    // --- the right-hand sides, top to bottom
    lower.minimal = Some(scope);
    let mut lets = Vec::new();
    let mut source = Vec::new();
    for (i, stmt) in decl.body.iter().enumerate() {
        lower.minimal.as_mut()?.statement = i;
        let (name, value) = match stmt {
            MinimalStmt::Let { name, value } => {
                source.push(format!("let {name} = {value}"));
                (name, value)
            }
            MinimalStmt::Assign { coord, value } => {
                source.push(format!("{coord} = {value}"));
                (coord, value)
            }
        };
        let id = lower.lower(value, Place::Minimal);
        let scope = lower.minimal.as_mut()?;
        if scope.let_at.get(&name.to_string()) == Some(&i) {
            scope.let_values.insert(name.to_string(), id);
            scope.lets_above.push(name.clone());
            if let Some(id) = id {
                lets.push((name.clone(), id));
            }
        } else if let Some(k) = scope.coord_at.iter().position(|&at| at == Some(i)) {
            scope.coord_values[k] = Some(id);
        }
    }
    let scope = lower.minimal.take()?;

    // --- every coordinate mapped, every minimal coordinate used
    for (k, at) in scope.coord_at.iter().enumerate() {
        if at.is_none() {
            let coord = &names.coords[k];
            cx.error_at(
                section.keyword.span(),
                format!(
                    "coordinate `{coord}` has no mapping in `minimal`: every redundant coordinate needs one, \
                     `{coord} = <expression in the minimal coordinates>;`"
                ),
            );
        }
    }
    let phi: Option<Vec<Id>> = scope.coord_values.iter().map(|v| v.flatten()).collect();
    let phi = phi?;
    if cx.error_count() > errors_before {
        return None;
    }
    let mut used = vec![false; mu.len()];
    for &id in &phi {
        for sym in lower.arena.symbols(id) {
            if let Sym::Mu(k) = sym {
                used[k as usize] = true;
            }
        }
    }
    for (ident, used) in mu.iter().zip(used) {
        if !used {
            cx.error_at(
                ident.span(),
                format!(
                    "minimal coordinate `{ident}` appears in no mapping: P = D phi (eq. 8) would have a zero \
                     column"
                ),
            );
        }
    }
    Some(Minimal {
        mu,
        n_mu1: decl.mu1.len(),
        phi,
        lets,
        source,
    })
}

/// What `ident` already names, as "a parameter" or "reserved (a function)";
/// `None` if it is free.
fn taken_by(lower: &Lowerer<'_>, ident: &Ident) -> Option<String> {
    let name = key(ident);
    if let Some((_, why)) = RESERVED.iter().find(|(r, _)| *r == name) {
        return Some(format!("reserved ({why})"));
    }
    lower.names.get(ident).map(|(kind, _)| kind.describe().to_owned())
}

/// The explanation of what may stand left of `=`.
fn left_hand_sides(names: &Names) -> String {
    format!(
        "the left-hand sides of `minimal` are the redundant coordinates ({}); write `let name = ...;` for an \
         abbreviation",
        join(&names.coords)
    )
}

fn plural<'s>(count: usize, one: &'s str, many: &'s str) -> &'s str {
    if count == 1 { one } else { many }
}

impl Lowerer<'_> {
    /// Resolves a name on a right-hand side of a `minimal` block.
    pub(super) fn minimal_name(&mut self, ident: &Ident) -> Option<Id> {
        let scope = self.minimal.as_ref()?;
        let name = ident.to_string();
        let span = ident.span();
        if let Some(&value) = scope.let_values.get(&name) {
            return value;
        }
        if let Some(&at) = scope.let_at.get(&name) {
            let message = if at == scope.statement {
                format!(
                    "`let {ident} = ...` uses `{ident}` itself: an abbreviation cannot be defined in terms of itself"
                )
            } else {
                format!(
                    "`{ident}` is used above its `let`: the block reads top to bottom, so move `let {ident} = ...;` \
                     above this line"
                )
            };
            self.cx.error_at(span, message);
            return None;
        }
        if let Some(k) = scope.mu.iter().position(|m| m == ident) {
            return Some(self.arena.sym(Sym::Mu(k as u16)));
        }
        match self.names.get(ident) {
            Some((Kind::Param, i)) => Some(self.arena.sym(Sym::Param(i as u16))),
            Some((Kind::RobotCoord | Kind::LoadCoord, k)) => {
                if let Some(value) = scope.coord_values[k] {
                    return value;
                }
                let message = if scope.coord_at[k] == Some(scope.statement) {
                    format!("`{ident} = ...` uses `{ident}` itself: a coordinate cannot be defined in terms of itself")
                } else if scope.coord_at[k].is_some() {
                    format!(
                        "coordinate `{ident}` is used above its mapping: the block reads top to bottom, so move \
                         `{ident} = ...;` above this line (this also rules out circular definitions)"
                    )
                } else {
                    format!("coordinate `{ident}` has no mapping to stand for; map it above this line")
                };
                self.cx.error_at(span, message);
                None
            }
            Some((Kind::Input, _)) => {
                self.cx.error_at(
                    span,
                    format!("input `{ident}` is not allowed in `minimal`: inputs may appear only in `forces`"),
                );
                None
            }
            Some((kind, _)) => {
                self.cx.error_at(
                    span,
                    format!(
                        "`{ident}` is {} and has no value in expressions; {}",
                        kind.describe(),
                        self.allowed_in_minimal()
                    ),
                );
                None
            }
            None => {
                self.cx
                    .error_at(span, format!("unknown symbol `{ident}`; {}", self.allowed_in_minimal()));
                None
            }
        }
    }

    /// "allowed in `minimal`: ..." for the unknown-symbol message, with the
    /// `let`s and coordinates defined above the current statement.
    pub(super) fn allowed_in_minimal(&self) -> String {
        let mut kinds = Vec::new();
        if !self.names.params.is_empty() {
            kinds.push(format!("parameters ({})", join(&self.names.params)));
        }
        let Some(scope) = &self.minimal else {
            return String::new();
        };
        kinds.push(format!("minimal coordinates ({})", join(&scope.mu)));
        let or_none = |s: String| {
            if s.is_empty() { "none yet".to_owned() } else { s }
        };
        kinds.push(format!("`let` names above ({})", or_none(join(&scope.lets_above))));
        let mapped: Vec<Ident> = scope
            .coord_values
            .iter()
            .zip(&self.names.coords)
            .filter(|(v, _)| v.is_some())
            .map(|(_, c)| c.clone())
            .collect();
        kinds.push(format!("coordinates mapped above ({})", or_none(join(&mapped))));
        kinds.push("PI".to_owned());
        format!("allowed in `minimal`: {}", kinds.join(", "))
    }
}
