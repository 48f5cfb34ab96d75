//! The items of a `minimal` block: the inherent methods `phi_p`, `phi_x`,
//! `D1_phi_x`, `D2_phi_x`, `w` and the `MinimalMap` implementation.

use proc_macro2::TokenStream;
use quote::quote;

use super::body::{body, matrix_output, single, vector_output};
use super::printer::Mode;
use super::{doc, index, internal, names_list, str_list};
use crate::model::{Minimal, MinimalKernels, Model};

/// The items of a `minimal` block: inherent methods with the paper's names
/// and sizes, and the `MinimalMap` implementation.
pub(super) fn generate_minimal(
    model: &Model,
    minimal: &Minimal,
    k: &MinimalKernels,
    lints: &TokenStream,
) -> TokenStream {
    let inherent = minimal_inherent_impl(model, minimal, k, lints);
    let minimal_map = minimal_map_impl(model, minimal, k, lints);
    quote! {
        #inherent

        #minimal_map
    }
}

/// `impl Name { ... }` with `MINIMAL_SPLIT` and the parts of `phi`, `P` and
/// `P'` the servo problem needs (eqs. 6, 12, 15-17).
fn minimal_inherent_impl(model: &Model, minimal: &Minimal, k: &MinimalKernels, lints: &TokenStream) -> TokenStream {
    let name = &model.name;
    let (n, a, f) = (model.n(), model.a(), minimal.mu.len());
    let nr = model.n_robot;
    let f1 = minimal.n_mu1;
    let (a_lit, nr_lit, f_lit, f1_lit) = (index(a), index(nr), index(f), index(f1));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let mu = internal("mu");
    let mu_dot = internal("mu_dot");
    let (doc_split, doc_phi_p, doc_phi_x) = minimal_docs(model, minimal);

    let phi_p_body = single(model, vector_output("out", nr, &k.phi[..nr]));
    let phi_x_body = single(model, vector_output("out", a, &k.phi[nr..]));
    let d1_body = single(model, matrix_output("out", &k.p, nr..n, 0..f1));
    let d2_body = single(model, matrix_output("out", &k.p, nr..n, f1..f));
    let w_body = single(model, vector_output("out", a, &k.w));

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
    }
}

/// The doc comments of `MINIMAL_SPLIT`, `phi_p` and `phi_x`, with the
/// declared names.
fn minimal_docs(model: &Model, minimal: &Minimal) -> (TokenStream, TokenStream, TokenStream) {
    let nr = model.n_robot;
    let (mu1, mu2) = minimal.mu.split_at(minimal.n_mu1);
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
    (doc_split, doc_phi_p, doc_phi_x)
}

/// `impl MinimalMap<N, M, A, F> for Name { ... }`: `phi` (documented with
/// the declared map), `P` and `P'`.
fn minimal_map_impl(model: &Model, minimal: &Minimal, k: &MinimalKernels, lints: &TokenStream) -> TokenStream {
    let name = &model.name;
    let (n, m, a, f) = (model.n(), model.m(), model.a(), minimal.mu.len());
    let (n_lit, m_lit, a_lit, f_lit) = (index(n), index(m), index(a), index(f));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let mu = internal("mu");
    let mu_dot = internal("mu_dot");
    let declared: Vec<TokenStream> = minimal.source.iter().map(doc).collect();

    let phi_body = single(model, vector_output("out", n, &k.phi));
    let p_body = single(model, matrix_output("out", &k.p, 0..n, 0..f));
    let p_rate_body = single(model, matrix_output("out", &k.p_rate, 0..n, 0..f));
    let derivatives_body = map_derivatives_body(model, k);
    let mu_names = str_list(minimal.mu.iter().map(ToString::to_string));

    quote! {
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

            /// `phi`, `P`, `dP/dmu_k` and `d(P' mu')/dmu` in one pass, sharing
            /// their subexpressions: what the minimal Newton matrix needs.
            fn map_derivatives<T: #scalar>(
                &self,
                #mu: &#sv<T, #f_lit>,
                #mu_dot: &#sv<T, #f_lit>,
            ) -> __crane_runtime::MapDerivatives<T, #n_lit, #f_lit> {
                #derivatives_body
            }
        }
    }
}

/// The body of `map_derivatives`: one function body (one set of common
/// subexpressions) for `phi`, `P`, the `f` matrices `dP/dmu_k` and
/// `d(P' mu')/dmu`.
fn map_derivatives_body(model: &Model, k: &MinimalKernels) -> TokenStream {
    let (n, f) = (model.n(), k.second.len());
    let mut outputs = vec![
        vector_output("phi", n, &k.phi),
        matrix_output("null_space", &k.p, 0..n, 0..f),
        matrix_output("curvature_jacobian", &k.curvature_jacobian, 0..n, 0..f),
    ];
    for (i, second) in k.second.iter().enumerate() {
        outputs.push(matrix_output(&format!("d_null_space_{i}"), second, 0..n, 0..f));
    }
    let statements = body(model, Mode::Generic, &outputs);
    let [phi, p, curvature] = [&outputs[0].var, &outputs[1].var, &outputs[2].var];
    let second = outputs[3..].iter().map(|o| &o.var);
    quote! {
        #statements
        __crane_runtime::MapDerivatives {
            phi: #phi,
            null_space: #p,
            null_space_derivatives: [#(#second),*],
            curvature_jacobian: #curvature,
        }
    }
}
