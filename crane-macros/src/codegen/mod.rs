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

mod body;
mod constants;
mod minimal;
mod printer;
mod self_test;
mod stub;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, quote};

use crate::expr::{Arena, Id};
use crate::model::{Kernels, Model};
use body::{Output, body, matrix_output, single, vector_output};
use constants::default_value;
use minimal::generate_minimal;
use printer::Mode;
use self_test::self_test;

pub use stub::stub;

fn internal(name: &str) -> Ident {
    Ident::new(name, Span::mixed_site())
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
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
