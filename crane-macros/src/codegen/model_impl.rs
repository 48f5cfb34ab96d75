//! The `CraneModel` implementation: `INFO`, the parameters by name, and the
//! kernels on all coordinates (`g`, `G`, the constraint Hessian, `M`, `f`
//! and its Jacobians, `B^T` and the Jacobian of `B^T u`, the rope lengths).

use proc_macro2::{Ident, TokenStream};
use quote::{ToTokens, quote};

use super::body::{Output, Target, body, matrix_output, single, vector_output};
use super::printer::Mode;
use super::{index, internal, str_list};
use crate::model::{Kernels, Model};
use crate::structure::Structure;

/// `impl CraneModel<N, M, A> for Name { ... }`.
///
/// `dummy_size` is the size `J` of the crane's dummy-derivative system if
/// it has one, `minimal_size` the number `F` of minimal coordinates if it
/// declares a map: what a run may ask of the model follows from them.
pub(super) fn crane_model_impl(
    model: &Model,
    k: &Kernels,
    structure: &Structure,
    dummy_size: Option<usize>,
    minimal_size: Option<usize>,
    lints: &TokenStream,
) -> TokenStream {
    let name = &model.name;
    let (n_lit, m_lit, a_lit) = (index(model.n()), index(model.m()), index(model.a()));
    let info = model_info(model);
    let parameters = parameter_methods(model);
    let kernels = kernel_methods(model, k);
    // read off the derivatives: a matrix of zero nodes is structurally zero
    let zero = |m: &[Vec<crate::expr::Id>]| m.iter().flatten().all(|&e| model.arena.is_zero(e));
    let on_velocity = !zero(&k.df_dv);
    let on_position = !(zero(&k.df_dq) && zero(&k.dbtu_dq));
    let structure = match structure {
        Structure::Internal {
            dimension,
            unknowns,
            equations,
        } => {
            let dimension = index(*dimension);
            let unknowns = unknowns.iter().map(|&c| index(c.into()));
            let equations = equations.iter().map(|&d| index(d.into()));
            quote!(::core::option::Option::Some(__crane_runtime::Structure {
                dimension: #dimension,
                unknowns: &[#(#unknowns),*],
                equations: &[#(#equations),*],
            }))
        }
        Structure::Singular => quote!(::core::option::Option::None),
    };
    let capabilities = capabilities(model, dummy_size, minimal_size);
    quote! {
        #lints
        impl __crane_runtime::CraneModel<#n_lit, #m_lit, #a_lit> for #name {
            #info

            const FORCES_DEPEND_ON_VELOCITY: bool = #on_velocity;
            const FORCES_DEPEND_ON_POSITION: bool = #on_position;
            const STRUCTURE: ::core::option::Option<__crane_runtime::Structure> = #structure;

            #parameters

            #kernels

            #capabilities
        }
    }
}

/// `HAS_MINIMAL_MAP` and the visits that hand a run the sizes of the
/// dummy-derivative system and of the minimal map.
fn capabilities(model: &Model, dummy_size: Option<usize>, minimal_size: Option<usize>) -> TokenStream {
    let (n_lit, m_lit, a_lit) = (index(model.n()), index(model.m()), index(model.a()));
    let visitor = internal("visitor");
    let visit = |result: TokenStream| {
        quote! {
            fn visit_dummy_derivatives<
                V: __crane_runtime::VisitDummyDerivatives<Self, #n_lit, #m_lit, #a_lit>,
            >(
                #visitor: V,
            ) -> ::core::result::Result<V::Output, __crane_runtime::NoDummyDerivatives> {
                #result
            }
        }
    };
    let dummy = match dummy_size {
        Some(j) => {
            let j = index(j);
            Some(visit(quote!(::core::result::Result::Ok(#visitor.visit::<#j>()))))
        }
        // (otherwise the runtime's default says why there is none)
        None if !model.dummy_derivatives => Some(visit(quote!(::core::result::Result::Err(
            __crane_runtime::NoDummyDerivatives::OptedOut
        )))),
        None => None,
    };
    let minimal = minimal_size.map(|f| {
        let f = index(f);
        quote! {
            const HAS_MINIMAL_MAP: bool = true;

            fn visit_minimal_map<V: __crane_runtime::VisitMinimalMap<Self, #n_lit, #m_lit, #a_lit>>(
                #visitor: V,
            ) -> ::core::option::Option<V::Output> {
                ::core::option::Option::Some(#visitor.visit::<#f>())
            }
        }
    });
    quote!(#dummy #minimal)
}

/// `const INFO`: the declared names.
fn model_info(model: &Model) -> TokenStream {
    let info_coords = str_list(model.coords.iter().map(ToString::to_string));
    let info_inputs = str_list(model.inputs.iter().map(ToString::to_string));
    let constraint_names: Vec<Ident> = model.constraints.iter().map(|c| c.name.clone()).collect();
    let info_constraints = str_list(constraint_names.iter().map(ToString::to_string));
    let info_params = str_list(model.params.iter().map(|p| p.name.to_string()));
    let ropes = model.ropes().map(|(index_k, r)| {
        let tension = r.tension.to_string();
        let index_k = index(index_k);
        quote!(__crane_runtime::Rope { tension: #tension, constraint: #index_k })
    });
    let description = &model.description;
    let name_str = model.name.to_string();
    let positive = model
        .params
        .iter()
        .enumerate()
        .filter(|(_, p)| p.positive)
        .map(|(i, _)| index(i));
    quote! {
        const INFO: __crane_runtime::ModelInfo = __crane_runtime::ModelInfo {
            name: #name_str,
            description: #description,
            coordinates: #info_coords,
            inputs: #info_inputs,
            constraints: #info_constraints,
            ropes: &[#(#ropes),*],
            parameters: #info_params,
            positive: &[#(#positive),*],
        };
    }
}

/// `parameter_values` and `set_parameter`.
fn parameter_methods(model: &Model) -> TokenStream {
    let param_names: Vec<&Ident> = model.params.iter().map(|p| &p.name).collect();
    let param_strs: Vec<String> = param_names.iter().map(ToString::to_string).collect();
    let known = param_strs.join(", ");
    let parameter_values = if param_names.is_empty() {
        quote!(::std::vec::Vec::new())
    } else {
        quote!(::std::vec![#(self.#param_names),*])
    };
    let (name, value) = (internal("name"), internal("value"));
    // every arm returns (an arm after the match would be unreachable for a
    // crane without parameters)
    quote! {
        fn parameter_values(&self) -> ::std::vec::Vec<f64> {
            #parameter_values
        }

        fn set_parameter(
            &mut self,
            #name: &str,
            #value: f64,
        ) -> ::core::result::Result<(), __crane_runtime::UnknownParameter> {
            match #name {
                #(#param_strs => {
                    self.#param_names = #value;
                    ::core::result::Result::Ok(())
                })*
                _ => ::core::result::Result::Err(__crane_runtime::UnknownParameter {
                    name: ::std::string::String::from(#name),
                    known: ::std::string::String::from(#known),
                }),
            }
        }
    }
}

/// The kernels, from `constraints` to `rope_lengths` and `rope_tensions`.
fn kernel_methods(model: &Model, k: &Kernels) -> TokenStream {
    let (n, m, a) = (model.n(), model.m(), model.a());
    let (n_lit, m_lit, a_lit) = (index(n), index(m), index(a));
    let sv = quote!(__crane_runtime::nalgebra::SVector);
    let sm = quote!(__crane_runtime::nalgebra::SMatrix);
    let scalar = quote!(__crane_runtime::Scalar);
    let q = internal("q");
    let v = internal("v");
    let u = internal("u");
    let lambda = internal("lambda");
    let out = internal("out");

    let jacobian_body = single(model, matrix_output("out", &k.jacobian, 0..m, 0..n));
    let hessian_body = single(model, matrix_output("out", &k.hessian, 0..n, 0..n));
    let mass_body = single(model, matrix_output("out", &k.mass, 0..n, 0..n));
    let forces_body = single(model, vector_output("out", n, &k.f));
    let force_jacobians_body = force_jacobians_body(model, k);
    let input_matrix_body = single(model, matrix_output("out", &k.bt, 0..n, 0..a));
    let input_jacobian_body = single(model, matrix_output("out", &k.dbtu_dq, 0..n, 0..n));
    let rope_lengths_body = rope_slice_body(model, "rope_lengths", &k.rope_lengths);
    let rope_tensions_body = rope_slice_body(model, "rope_tensions", &k.rope_tensions);

    quote! {
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

        fn rope_tensions(&self, #q: &#sv<f64, #n_lit>, #lambda: &#sv<f64, #m_lit>, #out: &mut [f64]) {
            #rope_tensions_body
        }
    }
}

/// The body of `force_jacobians`: both Jacobians of `f` from one set of
/// common subexpressions.
fn force_jacobians_body(model: &Model, k: &Kernels) -> TokenStream {
    let n = model.n();
    let outputs = [
        matrix_output("df_dq", &k.df_dq, 0..n, 0..n),
        matrix_output("df_dv", &k.df_dv, 0..n, 0..n),
    ];
    let statements = body(model, Mode::Generic, &outputs);
    let (a_var, b_var) = (&outputs[0].var, &outputs[1].var);
    quote!(#statements (#a_var, #b_var))
}

/// The body of `rope_lengths` or `rope_tensions` (`function`), in `f64`,
/// writing one value per rope into the caller's slice.
fn rope_slice_body(model: &Model, function: &str, values: &[crate::expr::Id]) -> TokenStream {
    let out = internal("out");
    let n_ropes = values.len();
    let output = Output {
        var: out.clone(),
        target: Target::Slice,
        writes: values
            .iter()
            .enumerate()
            .map(|(i, &id)| (index(i).into_token_stream(), id))
            .collect(),
    };
    let statements = body(model, Mode::F64, std::slice::from_ref(&output));
    let n_ropes_lit = index(n_ropes);
    let message = format!("{function}: `out` must have one entry per rope ({n_ropes})");
    quote!(::core::assert_eq!(#out.len(), #n_ropes_lit, #message); #statements)
}
