//! The physics lints as compiler warnings.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use crate::check::Lint;

/// Each lint as the use of a deprecated constant, the one warning a
/// function-like macro can make rustc print on stable:
///
/// ```text
/// warning: use of deprecated constant `z_has_a_force_but_no_inertia`: `z` carries a constant force ...
/// ```
///
/// pointing at the culprit. Both the constant and its use live in an
/// anonymous `const _` block, so no name reaches the user's scope.
pub fn lints(lints: &[Lint]) -> TokenStream {
    lints
        .iter()
        .map(|lint| {
            let name = Ident::new(&lint.name, lint.span);
            let message = &lint.message;
            quote! {
                const _: () = {
                    #[deprecated(note = #message)]
                    #[allow(non_upper_case_globals)]
                    const #name: () = ();
                    #name
                };
            }
        })
        .collect()
}
