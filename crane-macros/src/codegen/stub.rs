//! What is emitted after errors: a placeholder struct that implements the
//! traits a user's code asks of a crane, so that the declaration's own
//! errors are the only ones shown.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::parse::Declaration;

/// What is emitted after errors (besides the `compile_error!`s): the struct
/// with its defaults and, where the declaration's sections give the sizes
/// (`n` coordinates, `m` constraints, `a` load coordinates), `CraneModel`
/// (and `MinimalMap` with a `minimal` section) with bodies that are never
/// run (the crate does not compile), so that uses of the name elsewhere
/// (`simulate(&Gantry::default(), ...)`, `impl Crane for ...`) do not add
/// follow-on errors.
pub fn stub(decl: &Declaration) -> TokenStream {
    let name = &decl.name;
    let vis = &decl.vis;
    let docs = decl.attrs.iter().filter(|a| a.path().is_ident("doc"));
    let traits = trait_stubs(decl).unwrap_or_default();
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

        #traits
    }
}

/// The trait impls of the stub; `None` where a section that gives a size
/// is missing.
fn trait_stubs(decl: &Declaration) -> Option<TokenStream> {
    let sections = &decl.sections;
    let robot = sections.robot.as_ref()?.body.len();
    let a = sections.load.as_ref()?.body.len();
    let m = sections.constraints.as_ref()?.body.len();
    let n = robot + a;
    if a == 0 || m == 0 || m >= n {
        return None;
    }
    let name = &decl.name;
    // the options were reported with the declaration's other errors
    let runtime = crate::check::crane_options(&decl.attrs, &crate::ctxt::Ctxt::new()).runtime;
    let lit = Literal::usize_unsuffixed;
    let (n, m, a, f) = (lit(n), lit(m), lit(a), lit(robot + a - m));
    let sv = quote!(#runtime::nalgebra::SVector);
    let sm = quote!(#runtime::nalgebra::SMatrix);
    let scalar = quote!(#runtime::Scalar);
    let never = quote!(::core::unreachable!("the declaration of this crane has errors"));
    let minimal = sections.minimal.as_ref().map(|_| {
        quote! {
            impl #runtime::MinimalMap<#n, #m, #a, #f> for #name {
                const MINIMAL_COORDINATES: &'static [&'static str] = &[];
                fn phi<T: #scalar>(&self, _: &#sv<T, #f>) -> #sv<T, #n> { #never }
                fn null_space<T: #scalar>(&self, _: &#sv<T, #f>) -> #sm<T, #n, #f> { #never }
                fn null_space_rate<T: #scalar>(&self, _: &#sv<T, #f>, _: &#sv<T, #f>) -> #sm<T, #n, #f> { #never }
                fn map_derivatives<T: #scalar>(&self, _: &#sv<T, #f>, _: &#sv<T, #f>)
                    -> #runtime::MapDerivatives<T, #n, #f> { #never }
            }
        }
    });
    Some(quote! {
        #[allow(unused_variables, clippy::all)]
        impl #runtime::CraneModel<#n, #m, #a> for #name {
            const INFO: #runtime::ModelInfo = #runtime::ModelInfo {
                name: "",
                description: "",
                coordinates: &[],
                inputs: &[],
                constraints: &[],
                ropes: &[],
                parameters: &[],
                positive: &[],
            };
            fn parameter_values(&self) -> ::std::vec::Vec<f64> { #never }
            fn set_parameter(&mut self, _: &str, _: f64) -> ::core::result::Result<(), #runtime::UnknownParameter> { #never }
            fn constraints<T: #scalar>(&self, _: &#sv<T, #n>) -> #sv<T, #m> { #never }
            fn constraint_jacobian<T: #scalar>(&self, _: &#sv<T, #n>) -> #sm<T, #m, #n> { #never }
            fn constraint_hessian<T: #scalar>(&self, _: &#sv<T, #n>, _: &#sv<T, #m>) -> #sm<T, #n, #n> { #never }
            fn mass_matrix<T: #scalar>(&self) -> #sm<T, #n, #n> { #never }
            fn forces<T: #scalar>(&self, _: &#sv<T, #n>, _: &#sv<T, #n>) -> #sv<T, #n> { #never }
            fn force_jacobians<T: #scalar>(&self, _: &#sv<T, #n>, _: &#sv<T, #n>) -> (#sm<T, #n, #n>, #sm<T, #n, #n>) { #never }
            fn input_matrix<T: #scalar>(&self, _: &#sv<T, #n>) -> #sm<T, #n, #a> { #never }
            fn input_jacobian<T: #scalar>(&self, _: &#sv<T, #n>, _: &#sv<T, #a>) -> #sm<T, #n, #n> { #never }
            fn rope_lengths(&self, _: &#sv<f64, #n>, _: &mut [f64]) { #never }
        }

        #minimal
    })
}
