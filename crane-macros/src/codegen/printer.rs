//! The expression printer: IR nodes → Rust expressions over the scalar `T`
//! (or `f64`), with numeric constants kept to the right and the fewest
//! parentheses, reading a node that has a `let` binding by its name.

use std::collections::HashMap;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{ToTokens, format_ident, quote};

use super::{bare, index, internal, local};
use crate::expr::{Arena, Id, Node, Sym};
use crate::model::Model;

/// The scalar a function computes in.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Mode {
    /// `T: ::crane_runtime::Scalar`.
    Generic,
    /// Plain `f64` (rope lengths).
    F64,
}

/// Precedence of a printed expression (Rust's, coarsened).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Prec {
    Sum,
    Product,
    Unary,
    Atom,
}

/// A printed expression.
pub(super) struct Printed {
    tokens: TokenStream,
    prec: Prec,
    /// A bare `f64` literal (needs `T::from` where a `T` is required).
    constant: bool,
}

impl Printed {
    fn new(tokens: TokenStream, prec: Prec) -> Self {
        Self {
            tokens,
            prec,
            constant: false,
        }
    }
}

/// An `f64` literal (`PI` by name); never negative.
pub(super) fn float_literal(value: f64) -> TokenStream {
    debug_assert!(value >= 0.0);
    if value == std::f64::consts::PI {
        return quote!(::core::f64::consts::PI);
    }
    if !value.is_finite() {
        return quote!(::core::f64::INFINITY);
    }
    // `{:?}` is the shortest representation that round-trips (`0.1`, `1e-10`)
    match format!("{value:?}").parse::<Literal>() {
        Ok(lit) => lit.into_token_stream(),
        Err(_) => Literal::f64_unsuffixed(value).into_token_stream(),
    }
}

/// A (possibly negative) `f64` literal.
fn signed_literal(value: f64) -> TokenStream {
    let magnitude = float_literal(value.abs());
    if value < 0.0 { quote!(-#magnitude) } else { magnitude }
}

/// Prints expressions of one function body, given the `let` bindings.
pub(super) struct Printer<'a> {
    pub(super) model: &'a Model,
    pub(super) arena: &'a Arena,
    pub(super) mode: Mode,
    pub(super) bound: HashMap<Id, Ident>,
}

impl Printer<'_> {
    fn scalar(&self) -> TokenStream {
        match self.mode {
            Mode::Generic => quote!(T),
            Mode::F64 => quote!(f64),
        }
    }

    /// `id`, or its `let` name if it has one.
    pub(super) fn print(&self, id: Id) -> Printed {
        match self.bound.get(&id) {
            Some(name) => Printed::new(name.to_token_stream(), Prec::Atom),
            None => self.print_node(id),
        }
    }

    /// Parenthesizes `p` if it binds less tightly than `prec`.
    fn at_least(p: Printed, prec: Prec) -> TokenStream {
        let tokens = p.tokens;
        if p.prec < prec { quote!((#tokens)) } else { tokens }
    }

    /// `p` as the receiver of a method call.
    fn receiver(&self, p: Printed) -> TokenStream {
        if p.constant {
            let scalar = self.scalar();
            let tokens = p.tokens;
            quote!(#scalar::from(#tokens))
        } else {
            Self::at_least(p, Prec::Atom)
        }
    }

    /// `p` where a scalar value is required.
    pub(super) fn value(&self, p: Printed) -> TokenStream {
        if p.constant && self.mode == Mode::Generic {
            let tokens = p.tokens;
            quote!(T::from(#tokens))
        } else {
            p.tokens
        }
    }

    pub(super) fn print_node(&self, id: Id) -> Printed {
        match self.arena.node(id) {
            Node::Const(c) => {
                let c = c.get();
                let prec = if c < 0.0 { Prec::Unary } else { Prec::Atom };
                Printed {
                    tokens: signed_literal(c),
                    prec,
                    constant: true,
                }
            }
            Node::Sym(s) => Printed::new(self.symbol(*s), Prec::Atom),
            Node::Add(terms) => self.sum(terms),
            Node::Mul(factors) => {
                let (coefficient, rest) = self.split_coefficient(factors);
                self.product(coefficient, rest)
            }
            Node::Powi(base, n) => {
                let base = self.receiver(self.print(*base));
                let tokens = match *n {
                    -1 => quote!(#base.recip()),
                    n => {
                        let n = Literal::i32_unsuffixed(n);
                        quote!(#base.powi(#n))
                    }
                };
                Printed::new(tokens, Prec::Atom)
            }
            Node::Powf(base, r) => {
                let base = self.receiver(self.print(*base));
                let r = signed_literal(r.get());
                Printed::new(quote!(#base.powf(#r)), Prec::Atom)
            }
            Node::Func(f, arg) => {
                let arg = self.receiver(self.print(*arg));
                let f = format_ident!("{}", f.name());
                Printed::new(quote!(#arg.#f()), Prec::Atom)
            }
            Node::Atan2(y, x) => {
                let y = self.receiver(self.print(*y));
                let x = self.value(self.print(*x));
                Printed::new(quote!(#y.atan2(#x)), Prec::Atom)
            }
        }
    }

    fn symbol(&self, s: Sym) -> TokenStream {
        match s {
            Sym::Param(i) => local(&self.model.params[i as usize].name).to_token_stream(),
            Sym::Coord(i) => local(&self.model.coords[i as usize]).to_token_stream(),
            Sym::Vel(i) => velocity_name(&self.model.coords[i as usize]).to_token_stream(),
            Sym::Input(k) => local(&self.model.inputs[k as usize]).to_token_stream(),
            Sym::Lambda(k) => {
                let lambda = internal("lambda");
                let k = index(k as usize);
                quote!(#lambda[#k])
            }
            Sym::Mu(k) => local(minimal_coordinate(self.model, k)).to_token_stream(),
            Sym::MuDot(k) => velocity_name(minimal_coordinate(self.model, k)).to_token_stream(),
            Sym::Jet(j, k) => jet_name(self.model, j, k).to_token_stream(),
        }
    }

    fn split_coefficient<'f>(&self, factors: &'f [Id]) -> (f64, &'f [Id]) {
        match self.arena.as_const(factors[0]) {
            Some(c) => (c, &factors[1..]),
            None => (1.0, factors),
        }
    }

    /// If the (unbound) term is negative, its magnitude: `-2 x → 2 x`.
    fn negative_term(&self, term: Id) -> Option<Printed> {
        if self.bound.contains_key(&term) {
            return None;
        }
        match self.arena.node(term) {
            Node::Const(c) if c.get() < 0.0 => Some(Printed {
                tokens: float_literal(-c.get()),
                prec: Prec::Atom,
                constant: true,
            }),
            Node::Mul(factors) => {
                let (c, rest) = self.split_coefficient(factors);
                (c < 0.0).then(|| self.product(-c, rest))
            }
            _ => None,
        }
    }

    /// `a + b - c + 1.0`: a positive term first (constants last), negative
    /// terms as subtractions.
    fn sum(&self, terms: &[Id]) -> Printed {
        let (constants, mut order): (Vec<Id>, Vec<Id>) = terms.iter().partition(|&&t| self.arena.as_const(t).is_some());
        if let Some(first) = order.iter().position(|&t| self.negative_term(t).is_none()) {
            let t = order.remove(first);
            order.insert(0, t);
        }
        order.extend(constants);
        let mut tokens = TokenStream::new();
        for (i, &term) in order.iter().enumerate() {
            if i == 0 {
                tokens = Self::at_least(self.print(term), Prec::Sum);
            } else if let Some(magnitude) = self.negative_term(term) {
                let magnitude = Self::at_least(magnitude, Prec::Product);
                tokens.extend(quote!(- #magnitude));
            } else {
                let term = Self::at_least(self.print(term), Prec::Product);
                tokens.extend(quote!(+ #term));
            }
        }
        Printed::new(tokens, Prec::Sum)
    }

    /// `c * factors` as `-a * b * 2.0 / (d * e)`; `(d * e).recip()` if
    /// there is no numerator; a coefficient like `0.3333333333333333` as a
    /// division by `3.0`.
    fn product(&self, coefficient: f64, factors: &[Id]) -> Printed {
        let mut numerator: Vec<Printed> = Vec::new();
        let mut denominator: Vec<Printed> = Vec::new();
        for &f in factors {
            if !self.bound.contains_key(&f)
                && let Node::Powi(base, n) = *self.arena.node(f)
                && n < 0
            {
                denominator.push(self.power(base, -n));
            } else {
                numerator.push(self.print(f));
            }
        }
        let magnitude = coefficient.abs();
        let mut multiplier = None;
        if magnitude != 1.0 {
            match divisor(magnitude) {
                Some(d) => denominator.push(Printed {
                    tokens: float_literal(d),
                    prec: Prec::Atom,
                    constant: true,
                }),
                None => multiplier = Some(float_literal(magnitude)),
            }
        }
        let (mut tokens, mut prec) = if numerator.is_empty() {
            let d = self.joined(std::mem::take(&mut denominator));
            (quote!(#d.recip()), Prec::Atom)
        } else {
            let mut parts = numerator.into_iter();
            let mut tokens = TokenStream::new();
            let mut prec = Prec::Atom;
            if let Some(first) = parts.next() {
                prec = if first.prec < Prec::Unary {
                    Prec::Atom
                } else {
                    first.prec
                };
                tokens = Self::at_least(first, Prec::Unary);
            }
            for part in parts {
                let part = Self::at_least(part, Prec::Unary);
                tokens = quote!(#tokens * #part);
                prec = Prec::Product;
            }
            (tokens, prec)
        };
        if let Some(c) = multiplier {
            tokens = quote!(#tokens * #c);
            prec = Prec::Product;
        }
        if !denominator.is_empty() {
            let d = self.joined_unary(denominator);
            tokens = quote!(#tokens / #d);
            prec = Prec::Product;
        }
        if coefficient < 0.0 {
            tokens = quote!(-#tokens);
            prec = prec.min(Prec::Unary);
        }
        Printed::new(tokens, prec)
    }

    /// `base^n` for `n >= 1`.
    fn power(&self, base: Id, n: i32) -> Printed {
        if n == 1 {
            return self.print(base);
        }
        let base = self.receiver(self.print(base));
        let n = Literal::i32_unsuffixed(n);
        Printed::new(quote!(#base.powi(#n)), Prec::Atom)
    }

    /// `d1 * d2 * ...` as a receiver (parenthesized if a product).
    fn joined(&self, factors: Vec<Printed>) -> TokenStream {
        if factors.len() == 1 {
            let p = factors.into_iter().next().map(|p| self.receiver(p));
            return quote!(#p);
        }
        let mut parts = factors.into_iter().map(|p| Self::at_least(p, Prec::Unary));
        let first = parts.next();
        quote!((#first #(* #parts)*))
    }

    /// `d1 * d2 * ...` as the right operand of `/`.
    fn joined_unary(&self, factors: Vec<Printed>) -> TokenStream {
        if factors.len() == 1 {
            let p = factors.into_iter().next().map(|p| Self::at_least(p, Prec::Unary));
            return quote!(#p);
        }
        self.joined(factors)
    }
}

/// `Some(d)` if the coefficient `c` is better printed as a division by
/// `d = 1/c`: `c` has a long decimal expansion, `d` a short one, and the
/// two round-trip (`0.3333333333333333 → 3.0`).
fn divisor(c: f64) -> Option<f64> {
    let short = |v: f64| format!("{v:?}").len() <= 6;
    if short(c) {
        return None;
    }
    let d = 1.0 / c;
    (short(d) && 1.0 / d == c).then_some(d)
}

pub(super) fn velocity_name(coord: &Ident) -> Ident {
    internal(&format!("dot_{}", bare(coord)))
}

/// The local holding derivative `k` of unknown `j` of `[q, lambda, u]`:
/// `__q_L1_d2`, `__lambda_rope_d4`, `__u_u1_d0`. The kind of the unknown
/// comes first and the order last, so no two unknowns share a local
/// whatever they are named (a coordinate `lambda_rope` beside a constraint
/// `rope`: `__q_lambda_rope_d0` and `__lambda_rope_d0`), and no jet is
/// named like another internal local (`__q`, `__dot_x`, `__t3`, ...).
pub(super) fn jet_name(model: &Model, j: u16, k: u8) -> Ident {
    let (j, n, m) = (j as usize, model.n(), model.m());
    let (kind, name) = if j < n {
        ("q", bare(&model.coords[j]))
    } else if j < n + m {
        ("lambda", bare(&model.constraints[j - n].name))
    } else {
        ("u", bare(&model.inputs[j - n - m]))
    };
    internal(&format!("{kind}_{name}_d{k}"))
}

/// The declared name of derivative `k` of unknown `j` (`L1_d2`), for messages.
pub(super) fn jet_label(model: &Model, j: u16, k: u8) -> String {
    let (j, n, m) = (j as usize, model.n(), model.m());
    let base = if j < n {
        bare(&model.coords[j])
    } else if j < n + m {
        format!("lambda_{}", bare(&model.constraints[j - n].name))
    } else {
        bare(&model.inputs[j - n - m])
    };
    format!("{base}_d{k}")
}

/// The name of the minimal coordinate `mu_k`.
pub(super) fn minimal_coordinate(model: &Model, k: u16) -> &Ident {
    // `Sym::Mu` is only created for a model with a `minimal` block
    let minimal = model.minimal.as_ref();
    &minimal.map_or(&model.coords, |m| &m.mu)[k as usize]
}
