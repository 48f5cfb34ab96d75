//! The expression parser: a small Pratt parser from tokens to an [`Expr`].
//!
//! `syn::Expr` gives `^` the precedence of Rust's xor, which is wrong for a
//! power; here `^` binds tighter than unary minus and is right-associative.

use proc_macro2::{Ident, Span};
use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{LitFloat, LitInt, Token};

use super::ast::{BinOp, Expr, Function, PREFIX_BP};
use crate::ctxt::SpanRange;

/// What the error messages list as supported functions.
pub const SUPPORTED_FUNCTIONS: &str = "sin, cos, tan, sqrt, exp, ln, atan2(y, x), and dot(coordinate) for a velocity";

/// What the error messages list as supported operators.
pub const SUPPORTED_OPERATORS: &str = "+ - * / ^ (power) and parentheses";

/// Parses one expression; stops at the end of the input, a `,` or a `;`.
pub fn parse_expr(input: ParseStream) -> syn::Result<Expr> {
    expr_bp(input, 0)
}

fn expr_bp(input: ParseStream, min_bp: u8) -> syn::Result<Expr> {
    let mut lhs = if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        let operand = expr_bp(input, PREFIX_BP)?;
        Expr::Neg {
            minus: minus.span,
            operand: Box::new(operand),
        }
    } else {
        primary(input)?
    };
    loop {
        if input.is_empty() || input.peek(Token![,]) || input.peek(Token![;]) {
            break;
        }
        let Some(op) = peek_binop(input) else {
            return Err(unexpected_after_operand(input));
        };
        let (left_bp, right_bp) = op.binding_power();
        if left_bp < min_bp {
            break;
        }
        input.step(|cursor| match cursor.punct() {
            Some((_, rest)) => Ok(((), rest)),
            None => Err(cursor.error("expected an operator")),
        })?;
        let rhs = expr_bp(input, right_bp)?;
        lhs = Expr::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        };
    }
    Ok(lhs)
}

fn peek_binop(input: ParseStream) -> Option<BinOp> {
    let (punct, _) = input.cursor().punct()?;
    Some(match punct.as_char() {
        '+' => BinOp::Add,
        '-' => BinOp::Sub,
        '*' => BinOp::Mul,
        '/' => BinOp::Div,
        '^' => BinOp::Pow,
        _ => return None,
    })
}

fn unexpected_after_operand(input: ParseStream) -> syn::Error {
    let cursor = input.cursor();
    if let Some((punct, _)) = cursor.punct() {
        let c = punct.as_char();
        let message = if c == '.' {
            "unsupported operator `.`: write functions as `sin(x)`, not `x.sin()`".to_owned()
        } else {
            format!("unsupported operator `{c}`; supported: {SUPPORTED_OPERATORS}")
        };
        return syn::Error::new(punct.span(), message);
    }
    input.error("expected an operator (+ - * / ^) or the end of the expression")
}

/// A number literal (integer or float): no type suffix, finite.
fn number(
    suffix: &str,
    span: proc_macro2::Span,
    digits: &str,
    value: impl FnOnce() -> syn::Result<f64>,
) -> syn::Result<Expr> {
    no_suffix(suffix, span)?;
    let value = finite(value()?, span)?;
    Ok(Expr::Num {
        value,
        text: digits.to_owned(),
        span,
    })
}

fn primary(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(LitInt) {
        let lit: LitInt = input.parse()?;
        return number(lit.suffix(), lit.span(), lit.base10_digits(), || lit.base10_parse());
    }
    if input.peek(LitFloat) {
        let lit: LitFloat = input.parse()?;
        return number(lit.suffix(), lit.span(), lit.base10_digits(), || lit.base10_parse());
    }
    if input.peek(syn::token::Paren) {
        let content;
        let paren = syn::parenthesized!(content in input);
        let inner = parse_expr(&content)?;
        if !content.is_empty() {
            return Err(content.error("unexpected token in parentheses"));
        }
        return Ok(Expr::Paren {
            open: paren.span.open(),
            inner: Box::new(inner),
            close: paren.span.close(),
        });
    }
    if input.peek(syn::Ident) {
        let name: Ident = input.parse()?;
        if !input.peek(syn::token::Paren) {
            return Ok(Expr::Name(name));
        }
        let content;
        let paren = syn::parenthesized!(content in input);
        let close = paren.span.close();
        if name == "dot" {
            let coord = content
                .parse::<Ident>()
                .ok()
                .filter(|_| content.is_empty())
                .ok_or_else(|| {
                    syn::Error::new_spanned(
                        SpanRange {
                            first: name.span(),
                            last: close,
                        },
                        "dot() takes the name of a coordinate, e.g. `dot(x)`",
                    )
                })?;
            return Ok(Expr::Dot {
                dot: name,
                coord,
                close,
            });
        }
        let Some(func) = Function::from_name(&name.to_string()) else {
            return Err(syn::Error::new(
                name.span(),
                format!("unsupported function `{name}`; supported: {SUPPORTED_FUNCTIONS}"),
            ));
        };
        let args: Vec<Expr> = Punctuated::<Expr, Token![,]>::parse_terminated_with(&content, parse_expr)?
            .into_iter()
            .collect();
        if args.len() != func.arity() {
            let expected = match func {
                Function::Unary(_) => "1 argument".to_owned(),
                Function::Atan2 => "2 arguments (y, x)".to_owned(),
            };
            return Err(syn::Error::new_spanned(
                SpanRange {
                    first: name.span(),
                    last: close,
                },
                format!("`{name}` takes {expected}, found {}", args.len()),
            ));
        }
        return Ok(Expr::Call {
            func,
            name,
            args,
            close,
        });
    }
    if let Some((punct, _)) = input.cursor().punct() {
        let message = match punct.as_char() {
            '*' => "unexpected `*`: write powers as `x^n`".to_owned(),
            '+' => "unexpected `+`: expected an expression".to_owned(),
            c => format!("unsupported operator `{c}`; supported: {SUPPORTED_OPERATORS}"),
        };
        return Err(syn::Error::new(punct.span(), message));
    }
    Err(input.error("expected an expression: a number, a name, `dot(coordinate)`, a function call or `( ... )`"))
}

fn finite(value: f64, span: Span) -> syn::Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(syn::Error::new(span, "number out of range for an f64"))
    }
}

fn no_suffix(suffix: &str, span: Span) -> syn::Result<()> {
    if suffix.is_empty() {
        Ok(())
    } else {
        Err(syn::Error::new(
            span,
            "numeric literals take no suffix: every number is an f64",
        ))
    }
}
