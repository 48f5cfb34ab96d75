//! Code generation: a checked [`Model`] and its [`Kernels`] → Rust items.
//!
//! Only printing happens here. Each generated function reads the parameters
//! and coordinates it needs into locals named as declared
//! (`let m_l = T::from(self.m_l);`, `let L1 = q[0];`), binds every
//! subexpression used more than once to a `let tN` (common-subexpression
//! elimination, read off the hash-consed graph), starts its outputs from
//! zeros and writes only the nonzero entries.
//!
//! The code is generic over `T: ::crane_runtime::Scalar`, which supports
//! `T op T` and `T op f64` but not `f64 op T`; the printer therefore keeps
//! numeric constants to the right (`x * 2.0`, `x - 1.0`, `r.recip()`).
//! Internal names (`q`, `v`, `lambda`, `mu`, `mu_dot`, `out`, `tN`, `dot_x`)
//! are `Span::mixed_site()` so they cannot collide with the user's names.
//! A common subexpression that is the value of a `let` of a `minimal` block
//! is bound under the user's name instead of a `tN`.

use std::collections::HashMap;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, format_ident, quote};

use crate::expr::{Arena, Id, Node, Sym};
use crate::model::{Kernels, Minimal, MinimalKernels, Model};
use crate::parse::{BinOp, Declaration, Expr, Function};

/// The scalar a function computes in.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mode {
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
struct Printed {
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

fn internal(name: &str) -> Ident {
    Ident::new(name, Span::mixed_site())
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// An `f64` literal (`PI` by name); never negative.
fn float_literal(value: f64) -> TokenStream {
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
    if value < 0.0 {
        quote!(-#magnitude)
    } else {
        magnitude
    }
}

/// One output of a generated function.
struct Output {
    /// The local it is built in.
    var: Ident,
    /// `Some(zeros)`: a new matrix; `None`: a `&mut [f64]` parameter, all
    /// entries written.
    init: Option<TokenStream>,
    /// `(index, value)`: `var[index] = value`.
    writes: Vec<(TokenStream, Id)>,
}

/// Prints expressions of one function body, given the `let` bindings.
struct Printer<'a> {
    model: &'a Model,
    arena: &'a Arena,
    mode: Mode,
    bound: HashMap<Id, Ident>,
}

impl Printer<'_> {
    fn scalar(&self) -> TokenStream {
        match self.mode {
            Mode::Generic => quote!(T),
            Mode::F64 => quote!(f64),
        }
    }

    /// `id`, or its `let` name if it has one.
    fn print(&self, id: Id) -> Printed {
        match self.bound.get(&id) {
            Some(name) => Printed::new(name.to_token_stream(), Prec::Atom),
            None => self.print_node(id),
        }
    }

    /// Parenthesizes `p` if it binds less tightly than `prec`.
    fn at_least(p: Printed, prec: Prec) -> TokenStream {
        let tokens = p.tokens;
        if p.prec < prec {
            quote!((#tokens))
        } else {
            tokens
        }
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
    fn value(&self, p: Printed) -> TokenStream {
        if p.constant && self.mode == Mode::Generic {
            let tokens = p.tokens;
            quote!(T::from(#tokens))
        } else {
            p.tokens
        }
    }

    fn print_node(&self, id: Id) -> Printed {
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
            Sym::Param(i) => self.model.params[i as usize].name.to_token_stream(),
            Sym::Coord(i) => self.model.coords[i as usize].to_token_stream(),
            Sym::Vel(i) => velocity_name(&self.model.coords[i as usize]).to_token_stream(),
            Sym::Input(k) => self.model.inputs[k as usize].to_token_stream(),
            Sym::Lambda(k) => {
                let lambda = internal("lambda");
                let k = index(k as usize);
                quote!(#lambda[#k])
            }
            Sym::Mu(k) => minimal_coordinate(self.model, k).to_token_stream(),
            Sym::MuDot(k) => velocity_name(minimal_coordinate(self.model, k)).to_token_stream(),
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
        let (constants, mut order): (Vec<Id>, Vec<Id>) = terms
            .iter()
            .partition(|&&t| self.arena.as_const(t).is_some());
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
            let p = factors
                .into_iter()
                .next()
                .map(|p| Self::at_least(p, Prec::Unary));
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

fn velocity_name(coord: &Ident) -> Ident {
    Ident::new(&format!("dot_{coord}"), Span::mixed_site())
}

/// The name of the minimal coordinate `mu_k`.
fn minimal_coordinate(model: &Model, k: u16) -> &Ident {
    // `Sym::Mu` is only created for a model with a `minimal` block
    let minimal = model.minimal.as_ref();
    &minimal.map_or(&model.coords, |m| &m.mu)[k as usize]
}

/// Nodes worth a `let`: not leaves, not a bare reciprocal (printed as a
/// division) or negation.
fn bindable(arena: &Arena, id: Id) -> bool {
    match arena.node(id) {
        Node::Const(_) | Node::Sym(_) | Node::Powi(_, -1) => false,
        Node::Mul(factors) => !(factors.len() == 2 && arena.as_const(factors[0]) == Some(-1.0)),
        _ => true,
    }
}

/// The statements of a function body that fills `outputs`.
fn body(model: &Model, mode: Mode, outputs: &[Output]) -> TokenStream {
    let arena = &model.arena;
    let roots: Vec<Id> = outputs
        .iter()
        .flat_map(|o| {
            o.writes
                .iter()
                .filter(|(_, id)| o.init.is_none() || !arena.is_zero(*id))
                .map(|&(_, id)| id)
        })
        .collect();

    // How often each node would be printed if inlined; bind those printed
    // twice or more. Parents have larger ids than their children.
    let reachable = arena.reachable(roots.iter().copied());
    let mut uses: HashMap<Id, usize> = HashMap::new();
    for &r in &roots {
        *uses.entry(r).or_default() += 1;
    }
    let mut bound_order = Vec::new();
    for &id in reachable.iter().rev() {
        let u = uses.get(&id).copied().unwrap_or(0);
        let is_bound = u >= 2 && bindable(arena, id);
        if is_bound {
            bound_order.push(id);
        }
        let contribution = if is_bound { 1 } else { u };
        for child in arena.node(id).children() {
            *uses.entry(child).or_default() += contribution;
        }
    }
    bound_order.reverse();

    let mut printer = Printer {
        model,
        arena,
        mode,
        bound: HashMap::new(),
    };
    let mut statements = TokenStream::new();

    // reads of parameters and coordinates, in declaration order
    let mut syms: Vec<Sym> = reachable
        .iter()
        .filter_map(|&id| match arena.node(id) {
            Node::Sym(s) => Some(*s),
            _ => None,
        })
        .collect();
    syms.sort();
    let q = internal("q");
    let v = internal("v");
    let u = internal("u");
    let mu = internal("mu");
    let mu_dot = internal("mu_dot");
    for s in syms {
        statements.extend(match s {
            Sym::Param(i) => {
                let name = &model.params[i as usize].name;
                match mode {
                    Mode::Generic => quote!(let #name = T::from(self.#name);),
                    Mode::F64 => quote!(let #name = self.#name;),
                }
            }
            Sym::Coord(i) => {
                let name = &model.coords[i as usize];
                let i = index(i as usize);
                quote!(let #name = #q[#i];)
            }
            Sym::Vel(i) => {
                let name = velocity_name(&model.coords[i as usize]);
                let i = index(i as usize);
                quote!(let #name = #v[#i];)
            }
            Sym::Input(k) => {
                let name = &model.inputs[k as usize];
                let k = index(k as usize);
                quote!(let #name = #u[#k];)
            }
            Sym::Lambda(_) => quote!(),
            Sym::Mu(k) => {
                let name = minimal_coordinate(model, k);
                let k = index(k as usize);
                quote!(let #name = #mu[#k];)
            }
            Sym::MuDot(k) => {
                let name = velocity_name(minimal_coordinate(model, k));
                let k = index(k as usize);
                quote!(let #name = #mu_dot[#k];)
            }
        });
    }

    // common subexpressions, children first; the user's name for the value
    // of a `let` (the first of equal ones), `tN` for the others
    let mut let_names: HashMap<Id, &Ident> = HashMap::new();
    for (name, id) in model.minimal.iter().flat_map(|m| &m.lets) {
        let_names.entry(*id).or_insert(name);
    }
    let mut temporaries = 0;
    for &id in &bound_order {
        let value = printer.print_node(id);
        let value = printer.value(value);
        let name = match let_names.get(&id) {
            Some(&name) => name.clone(),
            None => {
                temporaries += 1;
                internal(&format!("t{}", temporaries - 1))
            }
        };
        statements.extend(quote!(let #name = #value;));
        printer.bound.insert(id, name);
    }

    for output in outputs {
        let var = &output.var;
        let writes: Vec<&(TokenStream, Id)> = output
            .writes
            .iter()
            .filter(|(_, id)| output.init.is_none() || !arena.is_zero(*id))
            .collect();
        if let Some(init) = &output.init {
            if writes.is_empty() {
                statements.extend(quote!(let #var = #init;));
            } else {
                statements.extend(quote!(let mut #var = #init;));
            }
        }
        for (idx, id) in writes {
            let value = printer.value(printer.print(*id));
            statements.extend(quote!(#var[#idx] = #value;));
        }
    }
    statements
}

/// A vector output `out` of length `len`.
fn vector_output(var: &str, len: usize, entries: &[Id]) -> Output {
    debug_assert_eq!(entries.len(), len);
    let len_lit = index(len);
    Output {
        var: internal(var),
        init: Some(quote!(__crane_runtime::nalgebra::SVector::<T, #len_lit>::zeros())),
        writes: entries
            .iter()
            .enumerate()
            .map(|(i, &id)| (index(i).into_token_stream(), id))
            .collect(),
    }
}

/// A matrix output from the rows `rows` and columns `cols` of `matrix`.
fn matrix_output(
    var: &str,
    matrix: &[Vec<Id>],
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
) -> Output {
    let (r, c) = (index(rows.len()), index(cols.len()));
    let mut writes = Vec::new();
    for (i, row) in rows.clone().enumerate() {
        for (j, col) in cols.clone().enumerate() {
            let (i, j) = (index(i), index(j));
            writes.push((quote!((#i, #j)), matrix[row][col]));
        }
    }
    Output {
        var: internal(var),
        init: Some(quote!(__crane_runtime::nalgebra::SMatrix::<T, #r, #c>::zeros())),
        writes,
    }
}

/// A function body that builds one output and returns it.
fn single(model: &Model, output: Output) -> TokenStream {
    if output.writes.iter().all(|&(_, id)| model.arena.is_zero(id))
        && let Some(init) = output.init
    {
        return init;
    }
    let statements = body(model, Mode::Generic, std::slice::from_ref(&output));
    let var = output.var;
    quote!(#statements #var)
}

/// The default value of a parameter as `f64` code.
fn default_tokens(e: &Expr) -> TokenStream {
    match e {
        Expr::Num { value, .. } => float_literal(*value),
        Expr::Name(_) => quote!(::core::f64::consts::PI),
        Expr::Dot { .. } => quote!(::core::f64::NAN),
        Expr::Neg { operand, .. } => {
            let operand = default_tokens(operand);
            quote!(-(#operand))
        }
        Expr::Binary { op, lhs, rhs } => {
            let l = default_tokens(lhs);
            let r = default_tokens(rhs);
            match op {
                BinOp::Add => quote!((#l + #r)),
                BinOp::Sub => quote!((#l - #r)),
                BinOp::Mul => quote!((#l * #r)),
                BinOp::Div => quote!((#l / #r)),
                BinOp::Pow => quote!(f64::powf(#l, #r)),
            }
        }
        Expr::Call { func, args, .. } => {
            let args: Vec<TokenStream> = args.iter().map(default_tokens).collect();
            match func {
                Function::Unary(f) => {
                    let f = format_ident!("{}", f.name());
                    quote!(f64::#f(#(#args),*))
                }
                Function::Atan2 => quote!(f64::atan2(#(#args),*)),
            }
        }
        Expr::Paren { inner, .. } => default_tokens(inner),
    }
}

/// Removes the outermost parentheses that `default_tokens` adds.
fn default_value(e: &Expr) -> TokenStream {
    let tokens = default_tokens(e);
    let mut iter = tokens.clone().into_iter();
    match (iter.next(), iter.next()) {
        (Some(proc_macro2::TokenTree::Group(g)), None)
            if g.delimiter() == proc_macro2::Delimiter::Parenthesis =>
        {
            g.stream()
        }
        _ => tokens,
    }
}

fn doc(text: impl AsRef<str>) -> TokenStream {
    let text = format!(" {}", text.as_ref());
    quote!(#[doc = #text])
}

fn names_list(idents: &[Ident]) -> String {
    idents
        .iter()
        .map(|i| format!("`{i}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn str_list(idents: impl IntoIterator<Item = String>) -> TokenStream {
    let items: Vec<String> = idents.into_iter().collect();
    quote!(&[#(#items),*])
}

/// Whether every entry of the given block is the literal 0.
fn block_is_zero(
    arena: &Arena,
    m: &[Vec<Id>],
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
) -> bool {
    rows.into_iter()
        .all(|i| cols.clone().all(|j| arena.is_zero(m[i][j])))
}

/// The complete expansion for a checked model.
pub fn generate(model: &Model, k: &Kernels) -> TokenStream {
    let runtime = &model.runtime;
    let self_test = self_test(model);
    let name = &model.name;
    let vis = &model.vis;
    let attrs = &model.attrs;
    let (n, m, a) = (model.n(), model.m(), model.a());
    let nr = model.n_robot;
    let (n_lit, m_lit, a_lit, nr_lit, f_lit) =
        (index(n), index(m), index(a), index(nr), index(n - m));
    let arena = &model.arena;

    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let q = internal("q");
    let v = internal("v");
    let u = internal("u");
    let lambda = internal("lambda");
    let out = internal("out");

    // --- the struct
    let fields = model.params.iter().map(|p| {
        let pname = &p.name;
        let docs = &p.docs;
        let generated = doc(format!("Parameter `{pname}`, default `{}`.", p.default));
        let separator = if docs.is_empty() { quote!() } else { doc("") };
        quote!(#(#docs)* #separator #generated pub #pname: f64,)
    });
    let defaults = model.params.iter().map(|p| {
        let pname = &p.name;
        let value = default_value(&p.default);
        quote!(#pname: #value,)
    });
    let summary = doc(format!(
        "Declared with `crane_model!`: n = {n} coordinates, m = {m} constraints, a = {a} inputs, f = n - m = {} degrees of freedom.",
        n - m
    ));
    let summary_separator = if attrs.iter().any(|a| a.path().is_ident("doc")) {
        doc("")
    } else {
        quote!()
    };

    // --- inherent items
    let robot = &model.coords[..nr];
    let load = &model.coords[nr..];
    let doc_n = doc(format!(
        "Number of redundant coordinates `n` in `q = [p; x]` (eq. 2): robot coordinates {}, load coordinates {}.",
        names_list(robot),
        names_list(load)
    ));
    let constraint_names: Vec<Ident> = model.constraints.iter().map(|c| c.name.clone()).collect();
    let doc_m = doc(format!(
        "Number of holonomic constraints `m` (eq. 1b): {}.",
        names_list(&constraint_names)
    ));
    let doc_a = doc(format!(
        "Number of inputs `a` (eq. 1a), equal to the number of load coordinates prescribed by `x = gamma(t)` (eq. 1c): {}.",
        names_list(&model.inputs)
    ));

    let g_body = single(model, vector_output("out", m, &k.g));
    let g1_body = single(model, matrix_output("out", &k.jacobian, 0..m, 0..nr));
    let g2_body = single(model, matrix_output("out", &k.jacobian, 0..m, nr..n));
    let m1_body = single(model, matrix_output("out", &k.mass, 0..nr, 0..nr));
    let m2_body = single(model, matrix_output("out", &k.mass, nr..n, nr..n));
    let f1_body = single(model, vector_output("out", nr, &k.f[..nr]));
    let f2_body = single(model, vector_output("out", a, &k.f[nr..]));
    let b1t_body = single(model, matrix_output("out", &k.bt, 0..nr, 0..a));

    let coupling = if block_is_zero(arena, &k.mass, 0..nr, nr..n) {
        " `M` is block diagonal, `M = diag(M1, M2)`."
    } else {
        " `M` also couples robot and load velocities; `mass_matrix` gives all of it."
    };
    let load_inputs_doc = " The load rows of `B^T = [B1^T; 0]` are zero.";

    // --- trait items
    let info_coords = str_list(model.coords.iter().map(ToString::to_string));
    let info_inputs = str_list(model.inputs.iter().map(ToString::to_string));
    let info_constraints = str_list(constraint_names.iter().map(ToString::to_string));
    let info_params = str_list(model.params.iter().map(|p| p.name.to_string()));
    let ropes = model.ropes().map(|(index_k, r)| {
        let tension = r.tension.to_string();
        let index_k = index(index_k);
        quote!(__crane_runtime::Rope { tension: #tension, constraint: #index_k })
    });
    let description = &model.description;
    let name_str = name.to_string();

    let param_names: Vec<&Ident> = model.params.iter().map(|p| &p.name).collect();
    let param_strs: Vec<String> = param_names.iter().map(ToString::to_string).collect();
    let known = param_strs.join(", ");
    let parameter_values = if param_names.is_empty() {
        quote!(::std::vec::Vec::new())
    } else {
        quote!(::std::vec![#(self.#param_names),*])
    };

    let jacobian_body = single(model, matrix_output("out", &k.jacobian, 0..m, 0..n));
    let hessian_body = single(model, matrix_output("out", &k.hessian, 0..n, 0..n));
    let mass_body = single(model, matrix_output("out", &k.mass, 0..n, 0..n));
    let forces_body = single(model, vector_output("out", n, &k.f));
    let force_jacobians_body = {
        let outputs = [
            matrix_output("df_dq", &k.df_dq, 0..n, 0..n),
            matrix_output("df_dv", &k.df_dv, 0..n, 0..n),
        ];
        let statements = body(model, Mode::Generic, &outputs);
        let (a_var, b_var) = (&outputs[0].var, &outputs[1].var);
        quote!(#statements (#a_var, #b_var))
    };
    let input_matrix_body = single(model, matrix_output("out", &k.bt, 0..n, 0..a));
    let input_jacobian_body = single(model, matrix_output("out", &k.dbtu_dq, 0..n, 0..n));
    let n_ropes = k.rope_lengths.len();
    let rope_lengths_body = {
        let output = Output {
            var: out.clone(),
            init: None,
            writes: k
                .rope_lengths
                .iter()
                .enumerate()
                .map(|(i, &id)| (index(i).into_token_stream(), id))
                .collect(),
        };
        let statements = body(model, Mode::F64, std::slice::from_ref(&output));
        let n_ropes_lit = index(n_ropes);
        let message = format!("rope_lengths: `out` must have one entry per rope ({n_ropes})");
        quote!(::core::assert_eq!(#out.len(), #n_ropes_lit, #message); #statements)
    };

    let lints = quote!(#[allow(non_snake_case, unused_variables, clippy::too_many_lines, clippy::unreadable_literal)]);
    let minimal_items = match (&model.minimal, &k.minimal) {
        (Some(minimal), Some(kernels)) => generate_minimal(model, minimal, kernels, &lints),
        _ => TokenStream::new(),
    };

    quote! {
        #(#attrs)*
        #summary_separator
        #summary
        #[derive(::core::fmt::Debug, ::core::clone::Clone, ::core::marker::Copy, ::core::cmp::PartialEq)]
        #[allow(non_snake_case)]
        #vis struct #name {
            #(#fields)*
        }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                Self { #(#defaults)* }
            }
        }

        // the model functions, naming the runtime crate through one alias
        const _: () = {
        use #runtime as __crane_runtime;

        #lints
        impl #name {
            #doc_n
            pub const N: usize = #n_lit;
            #doc_m
            pub const M: usize = #m_lit;
            #doc_a
            pub const A: usize = #a_lit;
            /// Degrees of freedom `f = n - m`.
            pub const F: usize = #f_lit;

            /// The crane with the declared default parameters.
            pub fn new() -> Self {
                <Self as ::core::default::Default>::default()
            }

            /// Constraint functions `g(q)` (eq. 1b).
            pub fn g<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sv<T, #m_lit> {
                #g_body
            }

            /// `G1 = dg/dp`, the robot block of the constraint Jacobian `G = [G1 G2]`
            /// (eq. 3).
            pub fn G1<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sm<T, #m_lit, #nr_lit> {
                #g1_body
            }

            /// `G2 = dg/dx`, the load block of the constraint Jacobian `G = [G1 G2]`
            /// (eq. 3).
            pub fn G2<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sm<T, #m_lit, #a_lit> {
                #g2_body
            }

            /// Robot block `M1` of the constant mass matrix (eq. 11a), from the kinetic energy `T = 1/2 q'^T M q'` (eq. 28).
            #[doc = #coupling]
            pub fn M1<T: #scalar>(&self) -> #sm<T, #nr_lit, #nr_lit> {
                #m1_body
            }

            /// Load block `M2` of the constant mass matrix (eq. 11a).
            #[doc = #coupling]
            pub fn M2<T: #scalar>(&self) -> #sm<T, #a_lit, #a_lit> {
                #m2_body
            }

            /// Applied forces on the robot coordinates without the inputs, `f1(q, q')`
            /// (eq. 11b).
            pub fn f1<T: #scalar>(&self, #q: &#sv<T, #n_lit>, #v: &#sv<T, #n_lit>) -> #sv<T, #nr_lit> {
                #f1_body
            }

            /// Applied forces on the load coordinates, `f2(q, q')` (eq. 11b).
            pub fn f2<T: #scalar>(&self, #q: &#sv<T, #n_lit>, #v: &#sv<T, #n_lit>) -> #sv<T, #a_lit> {
                #f2_body
            }

            /// Input matrix `B1^T(q)`: generalized force on the robot coordinates per
            /// unit input (eq. 11c).
            #[doc = #load_inputs_doc]
            pub fn B1T<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sm<T, #nr_lit, #a_lit> {
                #b1t_body
            }
        }

        #lints
        impl __crane_runtime::CraneModel<#n_lit, #m_lit, #a_lit> for #name {
            const INFO: __crane_runtime::ModelInfo = __crane_runtime::ModelInfo {
                name: #name_str,
                description: #description,
                coordinates: #info_coords,
                inputs: #info_inputs,
                constraints: #info_constraints,
                ropes: &[#(#ropes),*],
                parameters: #info_params,
            };

            fn parameter_values(&self) -> ::std::vec::Vec<f64> {
                #parameter_values
            }

            fn set_parameter(
                &mut self,
                name: &str,
                value: f64,
            ) -> ::core::result::Result<(), __crane_runtime::UnknownParameter> {
                match name {
                    #(#param_strs => self.#param_names = value,)*
                    _ => {
                        return ::core::result::Result::Err(__crane_runtime::UnknownParameter {
                            name: ::std::string::String::from(name),
                            known: ::std::string::String::from(#known),
                        });
                    }
                }
                ::core::result::Result::Ok(())
            }

            fn constraints<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sv<T, #m_lit> {
                self.g(#q)
            }

            fn constraint_jacobian<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sm<T, #m_lit, #n_lit> {
                #jacobian_body
            }

            fn constraint_hessian<T: #scalar>(
                &self,
                #q: &#sv<T, #n_lit>,
                #lambda: &#sv<T, #m_lit>,
            ) -> #sm<T, #n_lit, #n_lit> {
                #hessian_body
            }

            fn mass_matrix<T: #scalar>(&self) -> #sm<T, #n_lit, #n_lit> {
                #mass_body
            }

            fn forces<T: #scalar>(&self, #q: &#sv<T, #n_lit>, #v: &#sv<T, #n_lit>) -> #sv<T, #n_lit> {
                #forces_body
            }

            fn force_jacobians<T: #scalar>(
                &self,
                #q: &#sv<T, #n_lit>,
                #v: &#sv<T, #n_lit>,
            ) -> (#sm<T, #n_lit, #n_lit>, #sm<T, #n_lit, #n_lit>) {
                #force_jacobians_body
            }

            fn input_matrix<T: #scalar>(&self, #q: &#sv<T, #n_lit>) -> #sm<T, #n_lit, #a_lit> {
                #input_matrix_body
            }

            fn input_jacobian<T: #scalar>(
                &self,
                #q: &#sv<T, #n_lit>,
                #u: &#sv<T, #a_lit>,
            ) -> #sm<T, #n_lit, #n_lit> {
                #input_jacobian_body
            }

            fn rope_lengths(&self, #q: &#sv<f64, #n_lit>, #out: &mut [f64]) {
                #rope_lengths_body
            }
        }

        #minimal_items
        };

        #self_test
    }
}

/// The self-test the macro emits for a model with a `sample` section: under
/// `cfg(test)`, the user's `cargo test` compares every generated derivative
/// with central differences (`check_derivatives`, and `check_minimal_map`
/// for a minimal map) at 100 random points of the declared box. Correct
/// derivatives show ~1e-9, a wrong one O(1); the threshold is 1e-6.
fn self_test(model: &Model) -> TokenStream {
    let Some(sample) = &model.self_test else { return TokenStream::new() };
    let runtime = &model.runtime;
    let name = &model.name;
    let module = format_ident!("__crane_self_test_{}", name.to_string().to_lowercase());
    let ranges = |ranges: &[(crate::parse::Expr, crate::parse::Expr)]| {
        let items = ranges.iter().map(|(low, high)| {
            let (low, high) = (default_value(low), default_value(high));
            quote!((#low, #high))
        });
        quote!([#(#items),*])
    };
    let q_box = ranges(&sample.q);
    let minimal_test = sample.mu.as_ref().map(|mu| {
        let mu_box = ranges(mu);
        quote! {
            /// `g(phi(mu)) = 0`, `G P = 0`, `P` and `P'` against central differences.
            #[test]
            fn minimal_map_checks() {
                let report = #runtime::check::check_minimal_map(&super::#name::default(), &#mu_box, 1.0, 100, 0x5eed);
                assert!(report.get("g(phi(mu)) = 0").map_or(f64::INFINITY, |e| e.worst_relative_error) < 1e-12
                    && report.worst() < 1e-6, "the minimal map of {} fails its check:\n{}", stringify!(#name), report);
            }
        }
    });
    quote! {
        /// Generated by `crane_model!` from the `sample` section (turn off with
        /// `#[crane(no_self_test)]`).
        #[cfg(test)]
        #[allow(non_snake_case)]
        mod #module {
            /// Generated derivatives against central differences.
            #[test]
            fn generated_derivatives_match_central_differences() {
                let sample = #runtime::check::SampleBox::new(#q_box);
                let report = #runtime::check::check_derivatives(&super::#name::default(), &sample, 100, 0x5eed);
                assert!(report.worst() < 1e-6, "generated derivatives of {} disagree with central differences:\n{}", stringify!(#name), report);
            }
            #minimal_test
        }
    }
}

/// The items of a `minimal` block: inherent methods with the paper's names
/// and sizes, and the `MinimalMap` implementation.
fn generate_minimal(
    model: &Model,
    minimal: &Minimal,
    k: &MinimalKernels,
    lints: &TokenStream,
) -> TokenStream {
    let name = &model.name;
    let (n, m, a, f) = (model.n(), model.m(), model.a(), minimal.mu.len());
    let nr = model.n_robot;
    let f1 = minimal.n_mu1;
    let (n_lit, m_lit, a_lit, nr_lit, f_lit, f1_lit) =
        (index(n), index(m), index(a), index(nr), index(f), index(f1));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let mu = internal("mu");
    let mu_dot = internal("mu_dot");

    let (mu1, mu2) = minimal.mu.split_at(f1);
    let doc_split = doc(format!(
        "Number of minimal coordinates in `mu1`, `f - a`: `mu = [mu1; mu2]` with `mu1` = {} and `mu2` = {}, \
         chosen so that `D2 phi_x` is regular (eq. 12).",
        names_list(mu1),
        names_list(mu2)
    ));
    let robot = &model.coords[..nr];
    let load = &model.coords[nr..];
    let doc_phi_p = doc(format!(
        "Robot part `phi_p(mu)` of the map `q = phi(mu)` (eq. 6): {} as functions of the minimal coordinates \
         `mu` = {}.",
        names_list(robot),
        names_list(&minimal.mu)
    ));
    let doc_phi_x = doc(format!(
        "Load part `phi_x(mu)` of the map `q = phi(mu)` (eq. 6): {}; the servo constraints read \
         `phi_x(mu) = gamma(t)` (eq. 10b).",
        names_list(load)
    ));
    let declared: Vec<TokenStream> = minimal.source.iter().map(doc).collect();

    let phi_body = single(model, vector_output("out", n, &k.phi));
    let phi_p_body = single(model, vector_output("out", nr, &k.phi[..nr]));
    let phi_x_body = single(model, vector_output("out", a, &k.phi[nr..]));
    let p_body = single(model, matrix_output("out", &k.p, 0..n, 0..f));
    let p_rate_body = single(model, matrix_output("out", &k.p_rate, 0..n, 0..f));
    let d1_body = single(model, matrix_output("out", &k.p, nr..n, 0..f1));
    let d2_body = single(model, matrix_output("out", &k.p, nr..n, f1..f));
    let w_body = single(model, vector_output("out", a, &k.w));
    let mu_names = str_list(minimal.mu.iter().map(ToString::to_string));

    quote! {
        #lints
        impl #name {
            #doc_split
            pub const MINIMAL_SPLIT: usize = #f1_lit;

            #doc_phi_p
            pub fn phi_p<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sv<T, #nr_lit> {
                #phi_p_body
            }

            #doc_phi_x
            pub fn phi_x<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sv<T, #a_lit> {
                #phi_x_body
            }

            /// `D1 phi_x = d phi_x / d mu1` (eqs. 15-16): the load rows of `P = D phi` in
            /// the columns of `mu1`.
            pub fn D1_phi_x<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sm<T, #a_lit, #f1_lit> {
                #d1_body
            }

            /// `D2 phi_x = d phi_x / d mu2` (eqs. 12, 15-16): the load rows of `P = D phi`
            /// in the columns of `mu2`; must be regular.
            pub fn D2_phi_x<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sm<T, #a_lit, #a_lit> {
                #d2_body
            }

            /// `w = d/dt[D1 phi_x] mu1' + d/dt[D2 phi_x] mu2^` (eq. 17), with
            /// `mu_dot = [mu1'; mu2^]`: the load rows of `P'(mu, mu') mu'`, the second
            /// directional derivative of `phi_x` along `mu'`.
            pub fn w<T: #scalar>(
                &self,
                #mu: &#sv<T, #f_lit>,
                #mu_dot: &#sv<T, #f_lit>,
            ) -> #sv<T, #a_lit> {
                #w_body
            }
        }

        #lints
        impl __crane_runtime::MinimalMap<#n_lit, #m_lit, #a_lit, #f_lit> for #name {
            const MINIMAL_COORDINATES: &'static [&'static str] = #mu_names;

            /// The map `q = phi(mu)` (eq. 6), as declared:
            ///
            /// ```text
            #(#declared)*
            /// ```
            fn phi<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sv<T, #n_lit> {
                #phi_body
            }

            /// `P = D phi(mu)` (eq. 8).
            fn null_space<T: #scalar>(&self, #mu: &#sv<T, #f_lit>) -> #sm<T, #n_lit, #f_lit> {
                #p_body
            }

            /// `P' = sum_k dP/dmu_k mu_k'` (eq. 9).
            fn null_space_rate<T: #scalar>(
                &self,
                #mu: &#sv<T, #f_lit>,
                #mu_dot: &#sv<T, #f_lit>,
            ) -> #sm<T, #n_lit, #f_lit> {
                #p_rate_body
            }
        }
    }
}

/// What is emitted after errors (besides the `compile_error!`s): the struct
/// with its defaults, so that uses of the name elsewhere do not add
/// follow-on errors.
pub fn stub(decl: &Declaration) -> TokenStream {
    let name = &decl.name;
    let vis = &decl.vis;
    let docs = decl.attrs.iter().filter(|a| a.path().is_ident("doc"));
    quote! {
        #(#docs)*
        #[derive(::core::fmt::Debug, ::core::clone::Clone, ::core::marker::Copy, ::core::cmp::PartialEq, ::core::default::Default)]
        #vis struct #name;

        impl #name {
            /// Placeholder: the declaration has errors.
            pub fn new() -> Self {
                Self
            }
        }
    }
}
