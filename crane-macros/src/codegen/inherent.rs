//! The model's inherent items: the counts `N`, `M`, `A`, `F`, `new`, and
//! the blocks of the partitioned equations of motion (`g`, `G1`, `G2`, `M1`,
//! `M2`, `f1`, `f2`, `B1T`, eqs. 1b, 3, 11) under the paper's names.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::body::{matrix_output, single, vector_output};
use super::{doc, index, internal, names_list};
use crate::expr::{Arena, Id};
use crate::model::{Kernels, Model};

/// `impl Name { ... }` with the counts, `new` and the blocks.
pub(super) fn inherent_impl(model: &Model, k: &Kernels, lints: &TokenStream) -> TokenStream {
    let name = &model.name;
    let counts = counts(model);
    let blocks = block_methods(model, k);
    quote! {
        #lints
        impl #name {
            #counts

            /// The crane with the declared default parameters.
            pub fn new() -> Self {
                <Self as ::core::default::Default>::default()
            }

            #blocks
        }
    }
}

/// The constants `N`, `M`, `A`, `F`, documented with the declared names.
fn counts(model: &Model) -> TokenStream {
    let (n, m, a) = (model.n(), model.m(), model.a());
    let nr = model.n_robot;
    let (n_lit, m_lit, a_lit, f_lit) = (index(n), index(m), index(a), index(n - m));
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
        "Number of inputs `a` (eq. 1a), equal to the number of load coordinates prescribed by `x = gamma(t)` \
            (eq. 1c): {}.",
        names_list(&model.inputs)
    ));
    quote! {
        #doc_n
        pub const N: usize = #n_lit;
        #doc_m
        pub const M: usize = #m_lit;
        #doc_a
        pub const A: usize = #a_lit;
        /// Degrees of freedom `f = n - m`.
        pub const F: usize = #f_lit;
    }
}

/// The blocks `g`, `G1`, `G2`, `M1`, `M2`, `f1`, `f2`, `B1T`.
fn block_methods(model: &Model, k: &Kernels) -> TokenStream {
    let (n, m, a) = (model.n(), model.m(), model.a());
    let nr = model.n_robot;
    let (n_lit, m_lit, a_lit, nr_lit) = (index(n), index(m), index(a), index(nr));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let q = internal("q");
    let v = internal("v");

    let g_body = single(model, vector_output("out", m, &k.g));
    let g1_body = single(model, matrix_output("out", &k.jacobian, 0..m, 0..nr));
    let g2_body = single(model, matrix_output("out", &k.jacobian, 0..m, nr..n));
    let m1_body = single(model, matrix_output("out", &k.mass, 0..nr, 0..nr));
    let m2_body = single(model, matrix_output("out", &k.mass, nr..n, nr..n));
    let f1_body = single(model, vector_output("out", nr, &k.f[..nr]));
    let f2_body = single(model, vector_output("out", a, &k.f[nr..]));
    let b1t_body = single(model, matrix_output("out", &k.bt, 0..nr, 0..a));

    let coupling = if block_is_zero(&model.arena, &k.mass, 0..nr, nr..n) {
        " `M` is block diagonal, `M = diag(M1, M2)`."
    } else {
        " `M` also couples robot and load velocities; `mass_matrix` gives all of it."
    };
    let load_inputs_doc = " The load rows of `B^T = [B1^T; 0]` are zero.";

    quote! {
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
}

/// Whether every entry of the given block is the literal 0.
fn block_is_zero(arena: &Arena, m: &[Vec<Id>], rows: std::ops::Range<usize>, cols: std::ops::Range<usize>) -> bool {
    rows.into_iter().all(|i| cols.clone().all(|j| arena.is_zero(m[i][j])))
}
