//! Code generation: a checked [`Model`] and its [`Kernels`] → Rust items.
//!
//! Only printing happens here. Each generated function reads the parameters
//! and coordinates it needs into locals named as declared behind a `__`
//! (`let __m_l = T::from(self.m_l);`, `let __L1 = __q[0];`), binds every
//! subexpression used more than once to a `let __tN` (common-subexpression
//! elimination, read off the hash-consed graph), starts its outputs from
//! zeros and writes only the nonzero entries.
//!
//! The code is generic over `T: ::crane_runtime::Scalar`, which supports
//! `T op T` and `T op f64` but not `f64 op T`; the printer therefore keeps
//! numeric constants to the right (`x * 2.0`, `x - 1.0`, `r.recip()`).
//! No name of the user's scope can reach a generated local: every local and
//! argument starts with `__`, so a constant `J` or a unit struct `L` beside
//! the declaration cannot turn `let __J` into a pattern. Internal names
//! (`__q`, `__v`, `__lambda`, `__mu`, `__mu_dot`, `__out`, `__tN`,
//! `__dot_x`, and the jets `__q_L1_d2`, `__lambda_rope_d4`, `__u_u1_d0` of
//! the dummy-derivative system, which name the kind of unknown first so
//! that no two collide whatever is declared) are `Span::mixed_site()`, so
//! they cannot collide with the declared ones either (a coordinate `q` is
//! `__q` at the call site).
//! A common subexpression that is the value of a `let` of a `minimal` block
//! is bound under the user's name instead of a `tN`.
//!
//! [`generate`] emits the pieces in order: the struct (`model_struct`), its
//! inherent items (`inherent`), the `CraneModel` impl (`model_impl`), the
//! items of a `minimal` block (`minimal`) and the self-test (`self_test`).
//! They share the expression printer (`printer`), the function bodies
//! (`body`) and the `f64` code of constants (`constants`); `stub` is what is
//! emitted after errors.

mod body;
mod constants;
mod dummy;
mod inherent;
mod lints;
mod minimal;
mod model_impl;
mod model_struct;
mod printer;
mod self_test;
mod stub;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::dummy::DummyKernels;
use crate::model::{Kernels, Model};
use crate::structure::Structure;
use inherent::inherent_impl;
use minimal::generate_minimal;
use model_impl::crane_model_impl;
use model_struct::model_struct;
use self_test::self_test;

pub use lints::lints;
pub use stub::stub;

/// An internal name of the generated code (`q`, `out`, `t3` → `__q`,
/// `__out`, `__t3`, mixed-site): the prefix keeps any item of the user's
/// scope from capturing it, the span keeps it apart from [`local`]s.
fn internal(name: &str) -> Ident {
    Ident::new(&format!("__{name}"), Span::mixed_site())
}

/// The local holding a declared name (parameter, coordinate, input, minimal
/// coordinate, `let` of a `minimal` block): `J` → `__J`, with the
/// declaration's span. A constant, static or unit struct `J` of the
/// user's scope would turn `let J = ...` into a pattern against itself;
/// `__J` is out of its reach.
fn local(name: &Ident) -> Ident {
    Ident::new(&format!("__{}", bare(name)), name.span())
}

/// A declared name's text without a raw identifier's `r#`, to build other
/// names from.
fn bare(name: &Ident) -> String {
    let text = name.to_string();
    match text.strip_prefix("r#") {
        Some(bare) => bare.to_string(),
        None => text,
    }
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

fn doc(text: impl AsRef<str>) -> TokenStream {
    let text = format!(" {}", text.as_ref());
    quote!(#[doc = #text])
}

fn names_list(idents: &[Ident]) -> String {
    idents.iter().map(|i| format!("`{i}`")).collect::<Vec<_>>().join(", ")
}

fn str_list(idents: impl IntoIterator<Item = String>) -> TokenStream {
    let items: Vec<String> = idents.into_iter().collect();
    quote!(&[#(#items),*])
}

/// The complete expansion for a checked model.
pub fn generate(model: &Model, k: &Kernels, structure: &Structure, dummy: Option<&DummyKernels>) -> TokenStream {
    let runtime = &model.runtime;
    let lints = quote!(#[allow(non_snake_case, unused_variables, clippy::too_many_lines, clippy::unreadable_literal, clippy::identity_op, clippy::erasing_op)]);
    let model_struct = model_struct(model, structure);
    let inherent = inherent_impl(model, k, &lints);
    let dummy_size = dummy.map(|d| d.unknowns.len());
    let minimal_size = match (&model.minimal, &k.minimal) {
        (Some(_), Some(_)) => Some(model.n() - model.m()),
        _ => None,
    };
    let crane_model = crane_model_impl(model, k, structure, dummy_size, minimal_size, &lints);
    let minimal_items = match (&model.minimal, &k.minimal) {
        (Some(minimal), Some(kernels)) => generate_minimal(model, minimal, kernels, &lints),
        _ => TokenStream::new(),
    };
    let dummy_items = dummy
        .map(|d| dummy::dummy_derivatives_impl(model, d, &lints))
        .unwrap_or_default();
    let self_test = self_test(model);
    quote! {
        #model_struct

        // the model functions, naming the runtime crate through one alias
        const _: () = {
        use #runtime as __crane_runtime;

        #inherent

        #crane_model

        #minimal_items

        #dummy_items
        };

        #self_test
    }
}
