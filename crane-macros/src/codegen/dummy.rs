//! The `DummyDerivatives` implementation of a flat crane: the
//! dummy-derivative system of `dummy.rs` (its residual and Jacobian in one
//! function body) and its layout.

use proc_macro2::TokenStream;
use quote::{ToTokens, quote};

use super::body::{Output, Target, body};
use super::printer::{Mode, jet_label, jet_name};
use super::{index, internal};
use crate::dummy::DummyKernels;
use crate::expr::{Node, Sym};
use crate::model::Model;

/// `impl DummyDerivatives<N, M, A, J> for Name { ... }`.
pub(super) fn dummy_derivatives_impl(model: &Model, k: &DummyKernels, lints: &TokenStream) -> TokenStream {
    let name = &model.name;
    let (n, m, a, nr) = (model.n(), model.m(), model.a(), model.n_robot);
    let size = k.unknowns.len();
    let (n_lit, m_lit, a_lit, j_lit, jj_lit) = (index(n), index(m), index(a), index(size), index(size * size));
    let offsets = k.offsets.iter().map(|&c| index(c.into()));
    let path_order = index(k.path_order.into());
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

    // the jets the body reads: unknowns from z, the load's from gamma
    let roots = k.residual.iter().chain(k.jacobian.iter().flatten()).copied();
    let mut jets: Vec<(u16, u8)> = model
        .arena
        .reachable(roots)
        .into_iter()
        .filter_map(|id| match model.arena.node(id) {
            Node::Sym(Sym::Jet(j, order)) => Some((*j, *order)),
            _ => None,
        })
        .collect();
    jets.sort_unstable();
    let reads = jets.iter().map(|&(j, order)| {
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
    });
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
                #(#reads)*
                #statements
            }
        }
    }
}
