//! The attributes on the declared struct: the `#[crane(...)]` options, and
//! the first doc line as the model's description.

use proc_macro2::{Ident, TokenStream};

use crate::ctxt::Ctxt;

/// The `#[crane(...)]` options on the struct: `runtime = path` names the
/// runtime crate the generated code uses (default `::crane_runtime`; a facade
/// crate passes its own re-export so that its users need not depend on
/// `crane-runtime`), `no_self_test` turns off the generated self-test and
/// `no_dummy_derivatives` the dummy-derivative system (for a crane that
/// will only run eqs. 22 or 24: its system grows with the path order and
/// is the largest part of the expansion).
pub(crate) struct CraneOptions {
    /// The runtime crate's path.
    pub runtime: TokenStream,
    /// Whether the self-test is generated.
    pub self_test: bool,
    /// Whether the dummy-derivative system is generated.
    pub dummy_derivatives: bool,
    /// The other attributes, which pass through to the struct.
    pub rest: Vec<syn::Attribute>,
}

/// The [`CraneOptions`] of the struct's attributes.
pub(crate) fn crane_options(attrs: &[syn::Attribute], cx: &Ctxt) -> CraneOptions {
    let mut runtime = quote::quote!(::crane_runtime);
    let (mut self_test, mut dummy_derivatives) = (true, true);
    let mut rest = Vec::new();
    for attr in attrs {
        if !attr.path().is_ident("crane") {
            rest.push(attr.clone());
            continue;
        }
        let parsed = attr.parse_args_with(|input: syn::parse::ParseStream| {
            let key: Ident = input.parse()?;
            if key == "no_self_test" || key == "no_dummy_derivatives" {
                return Ok((key, None));
            }
            if key != "runtime" {
                return Err(syn::Error::new(
                    key.span(),
                    "unknown `crane` option: expected `runtime = path::to::crane_runtime`, `no_self_test` or \
                     `no_dummy_derivatives`",
                ));
            }
            input.parse::<syn::Token![=]>()?;
            Ok((key, Some(input.parse::<TokenStream>()?)))
        });
        match parsed {
            Ok((key, None)) if key == "no_self_test" => self_test = false,
            Ok((_, None)) => dummy_derivatives = false,
            Ok((_, Some(path))) if !path.is_empty() => runtime = path,
            Ok(_) => cx.error_spanned_by(attr, "`#[crane(runtime = ...)]` needs a path"),
            Err(error) => cx.syn_error(error),
        }
    }
    CraneOptions {
        runtime,
        self_test,
        dummy_derivatives,
        rest,
    }
}

/// The first line of the first doc comment, trimmed.
pub(super) fn first_doc_line(attrs: &[syn::Attribute]) -> String {
    for attr in attrs {
        if let syn::Meta::NameValue(nv) = &attr.meta
            && nv.path.is_ident("doc")
            && let syn::Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Str(s), ..
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
