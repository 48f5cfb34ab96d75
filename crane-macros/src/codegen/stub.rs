//! What is emitted after errors: a placeholder struct.

use proc_macro2::TokenStream;
use quote::quote;

use crate::parse::Declaration;

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
