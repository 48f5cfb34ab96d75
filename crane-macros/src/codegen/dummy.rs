//! The `DummyDerivatives` implementation of a flat crane: the
//! dummy-derivative system of `dummy.rs` (its residual and Jacobian in one
//! function body) and its layout.

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};

use super::body::{Blocks, Output, Target, body, reads};
use super::printer::{Mode, jet_label, jet_name};
use super::{index, internal};
use crate::dummy::DummyKernels;
use crate::expr::{Id, Node, Sym};
use crate::model::Model;

/// `impl DummyDerivatives<N, M, A, J> for Name { ... }`.
pub(super) fn dummy_derivatives_impl(model: &Model, k: &DummyKernels, lints: &TokenStream) -> TokenStream {
    let name = &model.name;
    let (n, m, a) = (model.n(), model.m(), model.a());
    let size = k.unknowns.len();
    let (n_lit, m_lit, a_lit, j_lit, jj_lit) = (index(n), index(m), index(a), index(size), index(size * size));
    let offsets = k.offsets.iter().map(|&c| index(c.into()));
    let path_order = index(k.path_order.into());
    // (the runtime's default is a flat crane's 0)
    let dimension = (k.dimension > 0).then(|| {
        let d = index(k.dimension);
        quote!(const DIMENSION: usize = #d;)
    });
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let (gamma, z) = (internal("gamma"), internal("z"));

    let residual = Output {
        var: internal("residual"),
        target: Target::Slice,
        writes: k
            .residual
            .iter()
            .enumerate()
            .map(|(i, &id)| (index(i).into_token_stream(), id))
            .collect(),
    };
    // the Jacobian by columns, as nalgebra stores a matrix: entry (i, j)
    // at j J + i, written so
    let mut writes = Vec::new();
    for (i, row) in k.jacobian.iter().enumerate() {
        for (j, &id) in row.iter().enumerate() {
            let (i, j) = (index(i), index(j));
            writes.push((quote!(#j * #j_lit + #i), id));
        }
    }
    let jacobian = Output {
        var: internal("jacobian"),
        target: Target::ZeroedSlice,
        writes,
    };
    // the entries it writes (those not zero by structure), by columns
    let mut nonzeros: Vec<usize> = (k.jacobian.iter().enumerate())
        .flat_map(|(i, row)| {
            (row.iter().enumerate())
                .filter(|&(_, &id)| jacobian.writes_entry(&model.arena, id))
                .map(move |(j, _)| j * size + i)
        })
        .collect();
    nonzeros.sort_unstable();
    let nonzeros = nonzeros
        .into_iter()
        .map(|k| proc_macro2::Literal::u32_unsuffixed(k as u32));
    let outputs = [residual, jacobian];
    let statements = body(model, Mode::F64, &outputs);
    let staged = staged_items(model, k, &a_lit);

    // the jets the body reads: unknowns from z, the load's from gamma
    let roots = k.residual.iter().chain(k.jacobian.iter().flatten()).copied();
    let reads = jet_reads(model, k, &model.arena.reachable(roots));
    let [res_var, jac_var] = [&outputs[0].var, &outputs[1].var];
    let layout = super::doc(format!(
        "Unknowns `z` in order: {}; equations in order: {}.",
        k.unknowns
            .iter()
            .map(|&(j, order)| format!("`{}`", jet_label(model, j as u16, order)))
            .collect::<Vec<_>>()
            .join(", "),
        k.equations
            .iter()
            .map(|&(i, order)| {
                let equation = if i < n {
                    format!("dynamics of `{}`", model.coords[i])
                } else {
                    format!("constraint `{}`", model.constraints[i - n].name)
                };
                if order == 0 {
                    equation
                } else {
                    format!("{equation} (derivative {order})")
                }
            })
            .collect::<Vec<_>>()
            .join(", ")
    ));
    quote! {
        #lints
        impl __crane_runtime::DummyDerivatives<#n_lit, #m_lit, #a_lit, #j_lit> for #name {
            const OFFSETS: &'static [u8] = &[#(#offsets),*];
            const PATH_ORDER: usize = #path_order;
            #dimension
            const JACOBIAN_NONZEROS: &'static [u32] = &[#(#nonzeros),*];

            /// The residual of the dummy-derivative system and its Jacobian
            /// `d residual / d z` (by columns), the Jacobian's entries that
            /// are zero by structure left as they are.
            ///
            #layout
            fn dummy_derivative_system_into(
                &self,
                #gamma: &[#sv<f64, #a_lit>],
                #z: &[f64],
                #res_var: &mut [f64],
                #jac_var: &mut [f64],
            ) {
                // one check of each length (the constant indices below are
                // then within them)
                let #z = &#z[..#j_lit];
                let #res_var = &mut #res_var[..#j_lit];
                let #jac_var = &mut #jac_var[..#jj_lit];
                #reads
                #statements
            }

            #staged
        }
    }
}

/// The jets `(unknown, order)` among the nodes `reachable`, sorted.
fn jets_in(model: &Model, reachable: &[Id]) -> Vec<(u16, u8)> {
    let mut jets: Vec<(u16, u8)> = (reachable.iter())
        .filter_map(|&id| match model.arena.node(id) {
            Node::Sym(Sym::Jet(j, order)) => Some((*j, *order)),
            _ => None,
        })
        .collect();
    jets.sort_unstable();
    jets
}

/// `let` for each jet among the nodes `reachable` (those the body reads):
/// an unknown's from `z`, the load's from `gamma`.
fn jet_reads(model: &Model, k: &DummyKernels, reachable: &[Id]) -> TokenStream {
    let name = &model.name;
    let (n, nr) = (model.n(), model.n_robot);
    let (gamma, z) = (internal("gamma"), internal("z"));
    jets_in(model, reachable)
        .iter()
        .map(|&(j, order)| {
            let local = jet_name(model, j, order);
            let (j, order_usize) = (j as usize, order as usize);
            if (nr..n).contains(&j) {
                let (r, order) = (index(j - nr), index(order_usize));
                quote!(let #local = #gamma[#order][#r];)
            } else {
                match k.unknowns.iter().position(|&u| u == (j, order)) {
                    Some(slot) => {
                        let slot = index(slot);
                        quote!(let #local = #z[#slot];)
                    }
                    // the system reads a jet beyond the offsets: a fault of the
                    // reduction, reported rather than read from a wrong slot
                    None => {
                        let message = format!(
                            "the dummy-derivative system of `{name}` reads `{}`, which is not among its unknowns: \
                             please report this declaration",
                            jet_label(model, j as u16, order)
                        );
                        quote::quote_spanned!(name.span() => ::core::compile_error!(#message);)
                    }
                }
            }
        })
        .collect()
}

/// The system stage by stage (Pryce's stages: row `(i, k)`, derivative `k`
/// of equation `i`, in stage `k - d_i`; the jet `(j, l)` in stage `l -
/// c_j`): the consts `SYSTEM_ROWS` and `SYSTEM_COLUMNS` (the system
/// Jacobian's equations and unknowns in nested order: those of the lowest
/// stage first, then those each next stage adds) and
/// `dummy_derivative_stages_into`, which writes the system Jacobian and the
/// lowest stage's residual at the jets it is given, hands them to the
/// caller's solve, and goes on with each next stage's residual at the jets
/// the solves left. Nothing (the trait's defaults: no stages) where the
/// stages are not square.
fn staged_items(model: &Model, k: &DummyKernels, a_lit: &proc_macro2::Literal) -> TokenStream {
    let (n, m, nr) = (model.n(), model.m(), model.n_robot);
    let size = k.unknowns.len();
    let c = &k.offsets;
    // d_i: the highest derivative of each equation
    let mut d = vec![0u8; n + m];
    for &(i, order) in &k.equations {
        d[i] = d[i].max(order);
    }
    let top = i32::from(d.iter().copied().max().unwrap_or(0));
    let block_of = |order: u8, offset: u8| usize::try_from(i32::from(order) - i32::from(offset) + top).ok();
    let row_blocks: Option<Vec<usize>> = k.equations.iter().map(|&(i, order)| block_of(order, d[i])).collect();
    let col_blocks: Option<Vec<usize>> = k.unknowns.iter().map(|&(j, order)| block_of(order, c[j])).collect();
    let (Some(row_blocks), Some(col_blocks)) = (row_blocks, col_blocks) else {
        return TokenStream::new();
    };
    let blocks = top as usize + 1;
    let square = (0..blocks).all(|b| {
        let rows = row_blocks.iter().filter(|&&r| r == b).count();
        rows > 0 && rows == col_blocks.iter().filter(|&&c| c == b).count()
    });
    if !square || row_blocks.len() != size || col_blocks.len() != size {
        return TokenStream::new();
    }
    // the system Jacobian's rows and columns in nested order, and where
    // each entry is among the last stage's rows and columns
    let mut row_labels: Vec<usize> = (0..n + m).collect();
    row_labels.sort_by_key(|&i| (std::cmp::Reverse(d[i]), i));
    let mut col_labels: Vec<usize> = (0..c.len()).filter(|j| !(nr..n).contains(j)).collect();
    col_labels.sort_by_key(|&j| (std::cmp::Reverse(c[j]), j));
    let system = row_labels.len();
    let (Some(rows), Some(cols)) = (
        (row_labels.iter())
            .map(|&i| k.equations.iter().position(|&e| e == (i, d[i])))
            .collect::<Option<Vec<usize>>>(),
        (col_labels.iter())
            .map(|&j| k.unknowns.iter().position(|&u| u == (j, c[j])))
            .collect::<Option<Vec<usize>>>(),
    ) else {
        return TokenStream::new();
    };
    if system != col_labels.len() {
        return TokenStream::new();
    }
    let mut writes = Vec::new();
    for (col, &jc) in cols.iter().enumerate() {
        for (row, &ir) in rows.iter().enumerate() {
            let at = index(col * system + row);
            writes.push((at.into_token_stream(), k.jacobian[ir][jc]));
        }
    }
    let (residual, system_jacobian, z, solve) = (
        internal("residual"),
        internal("system_jacobian"),
        internal("z"),
        internal("solve"),
    );
    let jacobian_output = Output {
        var: system_jacobian.clone(),
        target: Target::ZeroedSlice,
        writes,
    };
    let stage_output = |b: usize| Output {
        var: residual.clone(),
        target: Target::Slice,
        writes: (k.residual.iter().enumerate())
            .filter(|&(e, _)| row_blocks[e] == b)
            .map(|(e, &id)| (index(e).into_token_stream(), id))
            .collect(),
    };
    // the stage of the latest jet each node reads (-1: none, only the
    // path's and parameters)
    let mut level = vec![-1i32; model.arena.node_count()];
    for id in model.arena.ids() {
        level[id.index()] = match model.arena.node(id) {
            Node::Sym(Sym::Jet(j, order)) => match k.unknowns.iter().position(|&u| u == (*j as usize, *order)) {
                Some(slot) => col_blocks[slot] as i32,
                None => -1,
            },
            node => node
                .children()
                .iter()
                .map(|child| level[child.index()])
                .max()
                .unwrap_or(-1),
        };
    }
    let mut roots: Vec<Id> = k.residual.clone();
    roots.extend(jacobian_output.writes.iter().map(|&(_, id)| id));
    let reachable = model.arena.reachable(roots.iter().copied());
    let mut reads = reads(model, Mode::F64, &reachable);
    reads.extend(jet_reads(model, k, &reachable));
    let mut body = Blocks::new(model, Mode::F64);
    let mut statements = body.prelude(&roots, |id| level[id.index()] < 0);
    for b in 0..blocks {
        let stage = index(b);
        statements.extend(if b == 0 {
            body.block(&[jacobian_output.clone(), stage_output(0)])
        } else {
            body.block(&[stage_output(b)])
        });
        statements.extend(quote! {
            if !#solve(#stage, &*#system_jacobian, &mut *#z, &*#residual) {
                return false;
            }
        });
        // what read this stage's jets is stale; the later stages read them
        // as the solve left them
        body.forget(|id| level[id.index()] >= b as i32);
        if b + 1 < blocks {
            let later: Vec<Id> = (k.residual.iter().enumerate())
                .filter(|&(e, _)| row_blocks[e] > b)
                .map(|(_, &id)| id)
                .collect();
            let read = jets_in(model, &model.arena.reachable(later));
            for (slot, &(j, order)) in k.unknowns.iter().enumerate() {
                if col_blocks[slot] == b && read.binary_search(&(j as u16, order)).is_ok() {
                    let (local, slot) = (jet_name(model, j as u16, order), index(slot));
                    statements.extend(quote!(let #local = #z[#slot];));
                }
            }
        }
    }
    let size_lit = index(size);
    let square_lit = index(system * system);
    let row_labels = row_labels.iter().map(|&i| index(i));
    let col_labels = col_labels.iter().map(|&j| index(j));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let gamma = internal("gamma");
    quote! {
        const SYSTEM_ROWS: &'static [u16] = &[#(#row_labels),*];
        const SYSTEM_COLUMNS: &'static [u16] = &[#(#col_labels),*];

        /// The system stage by stage: the system Jacobian (rows
        /// `SYSTEM_ROWS`, columns `SYSTEM_COLUMNS`, by columns) and the
        /// lowest stage's residual at `z`, then each next stage's residual
        /// at the jets the solves of the stages before it left in `z`.
        fn dummy_derivative_stages_into(
            &self,
            #gamma: &[#sv<f64, #a_lit>],
            #z: &mut [f64],
            #residual: &mut [f64],
            #system_jacobian: &mut [f64],
            #solve: &mut __crane_runtime::StageSolve<'_>,
        ) -> bool {
            let #z = &mut #z[..#size_lit];
            let #residual = &mut #residual[..#size_lit];
            let #system_jacobian = &mut #system_jacobian[..#square_lit];
            #reads
            #statements
            true
        }
    }
}
