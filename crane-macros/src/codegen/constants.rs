//! Constant expressions of the declaration (parameter defaults, `sample`
//! bounds) as `f64` code.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::printer::float_literal;
use crate::parse::{BinOp, Expr, Function};

/// The default value of a parameter as `f64` code.
fn default_tokens(e: &Expr) -> TokenStream {
    match e {
        Expr::Num { value, .. } => float_literal(*value),
        Expr::Name(_) => quote!(::core::f64::consts::PI),
        Expr::Dot { .. } => quote!(::core::f64::NAN),
        Expr::Neg { operand, .. } => {
            let operand = default_tokens(operand);
            quote!(-(#operand))
        }
        Expr::Binary { op, lhs, rhs } => {
            let l = default_tokens(lhs);
            let r = default_tokens(rhs);
            match op {
                BinOp::Add => quote!((#l + #r)),
                BinOp::Sub => quote!((#l - #r)),
                BinOp::Mul => quote!((#l * #r)),
                BinOp::Div => quote!((#l / #r)),
                BinOp::Pow => quote!(f64::powf(#l, #r)),
            }
        }
        Expr::Call { func, args, .. } => {
            let args: Vec<TokenStream> = args.iter().map(default_tokens).collect();
            match func {
                Function::Unary(f) => {
                    let f = format_ident!("{}", f.name());
                    quote!(f64::#f(#(#args),*))
                }
                Function::Atan2 => quote!(f64::atan2(#(#args),*)),
            }
        }
        Expr::Paren { inner, .. } => default_tokens(inner),
    }
}

/// Removes the outermost parentheses that `default_tokens` adds.
pub(super) fn default_value(e: &Expr) -> TokenStream {
    let tokens = default_tokens(e);
    let mut iter = tokens.clone().into_iter();
    match (iter.next(), iter.next()) {
        (Some(proc_macro2::TokenTree::Group(g)), None) if g.delimiter() == proc_macro2::Delimiter::Parenthesis => {
            g.stream()
        }
        _ => tokens,
    }
}
