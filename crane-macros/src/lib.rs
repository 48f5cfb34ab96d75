//! The `crane_model!` DSL: declare a crane, get its equations of motion as
//! plain Rust, differentiated at compile time.
//!
//! A crane in the setting of the paper (sect. 2) has `n` redundant
//! coordinates `q = [p; x]` (robot coordinates `p`, load coordinates `x`
//! prescribed by `x = gamma(t)`), `m` holonomic constraints `g(q) = 0` and
//! `a` inputs, and moves by `M q'' = f + B^T u - G^T lambda` (eq. 1a). The
//! macro takes the kinetic energy, the generalized forces and the
//! constraints, and emits a struct implementing
//! `crane_runtime::CraneModel` with `g`, `G = dg/dq`, the constraint
//! Hessian, the constant mass matrix `M`, `f`, `B^T` and their derivatives.
//! With a `minimal` block (sect. 3.2) it also implements
//! `crane_runtime::MinimalMap`: the map `q = phi(mu)` to `f = n - m` minimal
//! coordinates, `P = D phi` and `P'`, plus `phi_p`, `phi_x`, `D1_phi_x`,
//! `D2_phi_x` and `w` (eqs. 6-17).
//!
//! ```
//! use crane_macros::crane_model;
//! use crane_runtime::{CraneModel, MinimalMap};
//! use crane_runtime::nalgebra::SVector;
//!
//! crane_model! {
//!     /// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
//!     pub struct NavyPlanar {
//!         params { m_l = 100.0, J1 = 0.1, J2 = 0.1, r1 = 0.1, r2 = 0.1,
//!                  alpha = PI / 3.0, l = 10.0, g = 9.81 }
//!         robot  [L1, L2, L0, x0, z0]
//!         load   [x, z]
//!         inputs [u1, u2]
//!         kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
//!         forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }
//!         constraints {
//!             #[rope(N1 = L1)]
//!             rope1: 0.5*((x0 + l*sin(alpha))^2 + (z0 + l*cos(alpha))^2 - L1^2),
//!             rope0: 0.5*(x0^2 + z0^2 - L0^2),
//!             #[rope(N2 = L2 - L0)]
//!             hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L2 - L0)^2),
//!         }
//!         minimal [beta, gamma | theta, L] {
//!             let d = l*sin(gamma - beta)/sin(gamma);
//!             L1 = l*sin(beta)/sin(gamma);  L2 = d + L;  L0 = d;
//!             x0 = -d*sin(alpha - beta);    z0 = -d*cos(alpha - beta);
//!             x  = x0 + L*sin(theta);       z  = z0 - L*cos(theta);
//!         }
//!     }
//! }
//!
//! let crane = NavyPlanar::new();
//! let s3 = 3f64.sqrt();
//! let q = SVector::<f64, 7>::from([5.0 * s3, 10.0, 5.0, 0.0, -5.0, 0.0, -10.0]);
//! assert!(crane.g(&q).norm() < 1e-12);
//! assert_eq!(crane.mass_matrix::<f64>()[(5, 5)], 100.0);
//! assert_eq!(NavyPlanar::INFO.ropes.len(), 2);
//!
//! // the same start in minimal coordinates mu = [beta, gamma, theta, L]
//! let mu = SVector::<f64, 4>::from([std::f64::consts::FRAC_PI_3, std::f64::consts::FRAC_PI_2, 0.0, 5.0]);
//! assert!((crane.phi(&mu) - q).norm() < 1e-12);
//! assert!((crane.constraint_jacobian(&q) * crane.null_space(&mu)).norm() < 1e-12);
//! ```
//!
//! # The DSL
//! - `params { name = default, ... }`: `f64` fields of the struct; defaults
//!   are constant expressions (numbers, `PI`, functions of them). Doc
//!   comments on a parameter become the field's docs. `name: positive =
//!   default` declares a parameter the runtime refuses at or below zero.
//! - `robot [...]`, `load [...]`: the coordinates `p` and `x`; `q = [p; x]`.
//! - `inputs [...]`: one per load coordinate.
//! - `kinetic = expr;`: a quadratic form in the velocities `dot(q_i)` with
//!   constant coefficients (so that `M` is constant), positive
//!   semi-definite (a negative constant diagonal entry is an error).
//! - `forces { coord: expr, ... }`: generalized forces, linear in the inputs
//!   (inputs on robot coordinates only); unlisted coordinates get 0.
//! - `constraints { name: expr, ... }`: `g(q)`; `#[rope(N = length)]` marks a
//!   rope whose tension is the constraint's force along its length,
//!   `N = -lambda dg/dlength` (`lambda * length` for `0.5*(|d|^2 - length^2)`).
//! - `minimal [mu1, ... | mu2, ...] { ... }` (optional): the map
//!   `q = phi(mu)` to `f = n - m` minimal coordinates; the `a` names after
//!   `|` are `mu2`, chosen so that `D2 phi_x` is regular (eq. 12). The body
//!   has one `coord = expr;` per redundant coordinate and any number of
//!   `let name = expr;` abbreviations. A right-hand side may use the
//!   parameters, the minimal coordinates, and the `let`s and coordinates
//!   defined above it (a coordinate stands for its mapping, so
//!   `x = x0 + L*sin(theta)` reuses `x0`'s); reading top to bottom rules
//!   out circular definitions. Minimal coordinates and `let`s need names of
//!   their own.
//!
//! Expressions: `+ - * /`, unary minus, `^` (integer or real constant
//! exponent; binds tighter than unary minus; a chain `a^b^c` needs
//! parentheses), parentheses,
//! `sin cos tan sqrt exp ln atan2(y, x)`, numbers, `PI`, and the declared
//! names (nested at most 256 levels and 4096 operations deep: beyond, an
//! error instead of an overflow of the compiler's stack). Mistakes are
//! compile errors pointing at the culprit.
//!
//! # Physics checks
//! Beyond the form, the macro checks what the declaration says physically:
//! constraints must be independent (their gradients are compared at
//! pseudo-random configurations; a duplicated or combined constraint is an
//! error naming the constraints it depends on), a rope's constraint must
//! involve its length and change with it the same way wherever the length
//! is positive (a trolley's position declared as the length is an error),
//! and a kinetic energy with a configuration-dependent
//! mass matrix in an angle is shown its rewrite in the load's position. A
//! coordinate that carries a constant force (a weight) but has no inertia
//! compiles with a warning at the force (`use of deprecated constant
//! z_has_a_force_but_no_inertia: ...`, the one warning a macro can emit),
//! which `#![deny(warnings)]` makes an error.
#![warn(missing_docs)]

extern crate proc_macro;

mod check;
mod codegen;
mod ctxt;
mod diff;
mod dummy;
mod expr;
mod model;
mod parse;
mod simplify;
mod structure;

#[cfg(test)]
mod tests;

use proc_macro2::TokenStream;

/// Declares a crane; see the crate documentation for the DSL.
#[proc_macro]
pub fn crane_model(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    expand(input.into()).into()
}

/// The whole macro on `proc_macro2` tokens: parse, check, differentiate,
/// generate. On errors: the `compile_error!`s and a stub struct.
fn expand(input: TokenStream) -> TokenStream {
    let cx = ctxt::Ctxt::new();
    let Some(decl) = parse::parse(input, &cx) else {
        return errors(cx);
    };
    let model = if cx.has_errors() {
        None
    } else {
        check::check(&decl, &cx)
    };
    match (model, cx.check()) {
        (Some(mut model), Ok(())) => {
            let kernels = model::Kernels::derive(&mut model);
            if let Some(error) = check::negative_inertia(&decl, &model, &kernels)
                .or_else(|| check::ropes_depend_on_their_lengths(&decl, &model, &kernels))
                .or_else(|| check::ropes_pull_along_their_lengths(&decl, &model, &kernels))
                .or_else(|| check::dependent_constraints(&model, &kernels))
            {
                let mut tokens = error.to_compile_error();
                tokens.extend(codegen::stub(&decl));
                return tokens;
            }
            let structure = match structure::structure(&model, &kernels) {
                Ok(structure) => structure,
                Err(message) => {
                    let mut tokens = syn::Error::new(model.name.span(), message).to_compile_error();
                    tokens.extend(codegen::stub(&decl));
                    return tokens;
                }
            };
            if let Some(block) = structure::singular_block(&model, &kernels) {
                let mut tokens = syn::Error::new(model.name.span(), block.message(&model)).to_compile_error();
                tokens.extend(codegen::stub(&decl));
                return tokens;
            }
            let lints = check::physics_lints(&decl, &model, &kernels);
            let dummy = dummy::DummyKernels::derive(&mut model, &kernels, &structure);
            let mut tokens = codegen::generate(&model, &kernels, &structure, dummy.as_ref());
            tokens.extend(codegen::lints(&lints));
            tokens
        }
        (_, Err(error)) => {
            let mut tokens = error.to_compile_error();
            tokens.extend(codegen::stub(&decl));
            tokens
        }
        // `check` returns `None` only after reporting an error
        (None, Ok(())) => codegen::stub(&decl),
    }
}

fn errors(cx: ctxt::Ctxt) -> TokenStream {
    match cx.check() {
        Ok(()) => TokenStream::new(),
        Err(error) => error.to_compile_error(),
    }
}
