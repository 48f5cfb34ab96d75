//! The model's struct: one `f64` field per parameter with its docs, and
//! `Default` with the declared defaults.

use proc_macro2::TokenStream;
use quote::quote;

use super::constants::default_value;
use super::doc;
use crate::model::Model;
use crate::structure::Structure;

/// The struct, under the user's attributes and a summary of its sizes, and
/// its `Default` impl.
pub(super) fn model_struct(model: &Model, structure: &Structure) -> TokenStream {
    let name = &model.name;
    let vis = &model.vis;
    let attrs = &model.attrs;
    let (n, m, a) = (model.n(), model.m(), model.a());
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
        "Declared with `crane_model!`: n = {n} coordinates, m = {m} constraints, a = {a} inputs, f = n - m = \
            {} degrees of freedom.",
        n - m
    ));
    let structure_doc = doc(structure.describe(model.a()));
    let summary_separator = if attrs.iter().any(|a| a.path().is_ident("doc")) {
        doc("")
    } else {
        quote!()
    };
    quote! {
        #(#attrs)*
        #summary_separator
        #summary
        #[doc = ""]
        #structure_doc
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
    }
}
