//! Function bodies: the reads of the parameters and coordinates a body
//! needs, a `let` for every subexpression used more than once (common
//! subexpressions, read off the hash-consed graph), and the writes of the
//! nonzero entries of the outputs.

use std::collections::HashMap;

use proc_macro2::{Ident, TokenStream};
use quote::{ToTokens, quote};

use super::printer::{Mode, Printer, minimal_coordinate, velocity_name};
use super::{index, internal, local};
use crate::expr::{Arena, Id, Node, Sym};
use crate::model::Model;

/// One output of a generated function.
#[derive(Clone)]
pub(super) struct Output {
    /// The local or parameter it is built in.
    pub(super) var: Ident,
    /// Where it is built.
    pub(super) target: Target,
    /// `(index, value)`: `var[index] = value`.
    pub(super) writes: Vec<(TokenStream, Id)>,
}

/// Where an [`Output`] is built.
#[derive(Clone)]
pub(super) enum Target {
    /// A new matrix from this expression of zeros: its entries that are not
    /// zero by structure written.
    New(TokenStream),
    /// A `&mut [f64]` parameter: every entry written.
    Slice,
    /// A `&mut [f64]` parameter whose entries that are zero by structure
    /// the caller keeps at zero (a buffer zeroed once): only the others
    /// written.
    ZeroedSlice,
}

impl Output {
    /// Whether entry `id` is written.
    pub(super) fn writes_entry(&self, arena: &Arena, id: Id) -> bool {
        matches!(self.target, Target::Slice) || !arena.is_zero(id)
    }
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

/// The values `outputs` write (their entries not zero by structure, where
/// those are not written).
pub(super) fn written_roots(arena: &Arena, outputs: &[Output]) -> Vec<Id> {
    outputs
        .iter()
        .flat_map(|o| {
            o.writes
                .iter()
                .filter(|(_, id)| o.writes_entry(arena, *id))
                .map(|&(_, id)| id)
        })
        .collect()
}

/// The statements of a function body that fills `outputs`.
pub(super) fn body(model: &Model, mode: Mode, outputs: &[Output]) -> TokenStream {
    let arena = &model.arena;
    let roots = written_roots(arena, outputs);
    let reachable = arena.reachable(roots.iter().copied());
    let bound_order = bound_order(arena, &roots, &reachable);

    let mut printer = Printer {
        model,
        arena,
        mode,
        bound: HashMap::new(),
    };
    let mut statements = reads(model, mode, &reachable);
    statements.extend(common_subexpressions(model, &mut printer, &bound_order));
    statements.extend(writes(&printer, outputs));
    statements
}

/// The nodes to bind to a `let`, children first: those that would be
/// printed twice or more if inlined.
fn bound_order(arena: &Arena, roots: &[Id], reachable: &[Id]) -> Vec<Id> {
    bound_order_past(arena, roots, reachable, &HashMap::new())
}

/// [`bound_order`] where the nodes of `bound` have their names already:
/// leaves, neither bound again nor looked into.
fn bound_order_past(arena: &Arena, roots: &[Id], reachable: &[Id], bound: &HashMap<Id, Ident>) -> Vec<Id> {
    // How often each node would be printed if inlined; bind those printed
    // twice or more. Parents have larger ids than their children.
    let mut uses: HashMap<Id, usize> = HashMap::new();
    for &r in roots {
        *uses.entry(r).or_default() += 1;
    }
    let mut bound_order = Vec::new();
    for &id in reachable.iter().rev() {
        if bound.contains_key(&id) {
            continue;
        }
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
    bound_order
}

/// `let name = ...;` for every parameter, coordinate, velocity, input and
/// minimal coordinate among `reachable`, in declaration order.
pub(super) fn reads(model: &Model, mode: Mode, reachable: &[Id]) -> TokenStream {
    let arena = &model.arena;
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
                let field = &model.params[i as usize].name;
                let name = local(field);
                match mode {
                    Mode::Generic => quote!(let #name = T::from(self.#field);),
                    Mode::F64 => quote!(let #name = self.#field;),
                }
            }
            Sym::Coord(i) => {
                let name = local(&model.coords[i as usize]);
                let i = index(i as usize);
                quote!(let #name = #q[#i];)
            }
            Sym::Vel(i) => {
                let name = velocity_name(&model.coords[i as usize]);
                let i = index(i as usize);
                quote!(let #name = #v[#i];)
            }
            Sym::Input(k) => {
                let name = local(&model.inputs[k as usize]);
                let k = index(k as usize);
                quote!(let #name = #u[#k];)
            }
            // multipliers are read by the constraint Hessian's printer, jets
            // by the dummy-derivative system's own reads
            Sym::Lambda(_) | Sym::Jet(..) => quote!(),
            Sym::Mu(k) => {
                let name = local(minimal_coordinate(model, k));
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
    statements
}

/// `let name = value;` for the nodes of `bound_order`, which the printer
/// then reads by name.
fn common_subexpressions(model: &Model, printer: &mut Printer<'_>, bound_order: &[Id]) -> TokenStream {
    common_subexpressions_from(model, printer, bound_order, &mut 0)
}

/// [`common_subexpressions`] whose temporaries are numbered on from
/// `temporaries` (the count of those an earlier block of the body named).
fn common_subexpressions_from(
    model: &Model,
    printer: &mut Printer<'_>,
    bound_order: &[Id],
    temporaries: &mut usize,
) -> TokenStream {
    let mut statements = TokenStream::new();

    // common subexpressions, children first; the user's name for the value
    // of a `let` (the first of equal ones), `tN` for the others
    let mut let_names: HashMap<Id, &Ident> = HashMap::new();
    for (name, id) in model.minimal.iter().flat_map(|m| &m.lets) {
        let_names.entry(*id).or_insert(name);
    }
    for &id in bound_order {
        let value = printer.print_node(id);
        let value = printer.value(value);
        let name = match let_names.get(&id) {
            Some(&name) => local(name),
            None => {
                *temporaries += 1;
                internal(&format!("t{}", *temporaries - 1))
            }
        };
        statements.extend(quote!(let #name = #value;));
        printer.bound.insert(id, name);
    }
    statements
}

/// The outputs: each new matrix from zeros, then its nonzero entries (all
/// entries of a [`Target::Slice`], the nonzero ones of a [`Target::ZeroedSlice`]).
fn writes(printer: &Printer<'_>, outputs: &[Output]) -> TokenStream {
    let arena = printer.arena;
    let mut statements = TokenStream::new();
    for output in outputs {
        let var = &output.var;
        let writes: Vec<&(TokenStream, Id)> = output
            .writes
            .iter()
            .filter(|(_, id)| output.writes_entry(arena, *id))
            .collect();
        if let Target::New(init) = &output.target {
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

/// A function body computed in blocks, between which some of the values it
/// reads change (the unknowns each block's solve updates): every block
/// binds its own common subexpressions and reuses those of earlier blocks
/// that [`forget`](Self::forget) has kept.
pub(super) struct Blocks<'a> {
    printer: Printer<'a>,
    /// Temporaries named so far (the next is `t{temporaries}`).
    temporaries: usize,
}

impl<'a> Blocks<'a> {
    /// A body of `model` in `mode`, nothing bound yet.
    pub(super) fn new(model: &'a Model, mode: Mode) -> Self {
        Self {
            printer: Printer {
                model,
                arena: &model.arena,
                mode,
                bound: HashMap::new(),
            },
            temporaries: 0,
        }
    }

    /// The `let`s, ahead of the first block, of the subexpressions of
    /// `roots` (every block's outputs) that `constant` says no block
    /// changes and that would be printed more than once: the common ones,
    /// and the largest constant parts of expressions that change (which
    /// every block computing them would compute anew).
    pub(super) fn prelude(&mut self, roots: &[Id], constant: impl Fn(Id) -> bool) -> TokenStream {
        let arena = self.printer.arena;
        let reachable = arena.reachable(roots.iter().copied());
        let mut bind = vec![false; arena.node_count()];
        for id in bound_order(arena, roots, &reachable) {
            bind[id.index()] = constant(id);
        }
        for &id in &reachable {
            if !constant(id) {
                for child in arena.node(id).children() {
                    bind[child.index()] |= constant(child) && bindable(arena, child);
                }
            }
        }
        let order: Vec<Id> = reachable.into_iter().filter(|id| bind[id.index()]).collect();
        let model = self.printer.model;
        common_subexpressions_from(model, &mut self.printer, &order, &mut self.temporaries)
    }

    /// The `let`s and writes of one block's `outputs`, reading the names
    /// bound by earlier blocks where they are kept.
    pub(super) fn block(&mut self, outputs: &[Output]) -> TokenStream {
        let arena = self.printer.arena;
        let roots = written_roots(arena, outputs);
        // the nodes the block prints, not looking into the bound ones
        let bound = &self.printer.bound;
        let reachable = arena.reachable_until(roots.iter().copied(), |id| bound.contains_key(&id));
        let order = bound_order_past(arena, &roots, &reachable, &self.printer.bound);
        let model = self.printer.model;
        let mut statements = common_subexpressions_from(model, &mut self.printer, &order, &mut self.temporaries);
        statements.extend(writes(&self.printer, outputs));
        statements
    }

    /// Forget the names of the bound nodes whose values `stale` says have
    /// changed: later blocks compute them anew.
    pub(super) fn forget(&mut self, stale: impl Fn(Id) -> bool) {
        self.printer.bound.retain(|&id, _| !stale(id));
    }
}

/// A vector output `out` of length `len`.
pub(super) fn vector_output(var: &str, len: usize, entries: &[Id]) -> Output {
    debug_assert_eq!(entries.len(), len);
    let len_lit = index(len);
    Output {
        var: internal(var),
        target: Target::New(quote!(__crane_runtime::nalgebra::SVector::<T, #len_lit>::zeros())),
        writes: entries
            .iter()
            .enumerate()
            .map(|(i, &id)| (index(i).into_token_stream(), id))
            .collect(),
    }
}

/// A matrix output from the rows `rows` and columns `cols` of `matrix`.
pub(super) fn matrix_output(
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
        target: Target::New(quote!(__crane_runtime::nalgebra::SMatrix::<T, #r, #c>::zeros())),
        writes,
    }
}

/// A function body that builds one output and returns it.
pub(super) fn single(model: &Model, output: Output) -> TokenStream {
    if output.writes.iter().all(|&(_, id)| model.arena.is_zero(id))
        && let Target::New(init) = output.target
    {
        return init;
    }
    let statements = body(model, Mode::Generic, std::slice::from_ref(&output));
    let var = output.var;
    quote!(#statements #var)
}
