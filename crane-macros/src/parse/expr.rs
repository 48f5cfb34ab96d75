//! The expression parser: a small Pratt parser from tokens to an [`Expr`].
//!
//! `syn::Expr` gives `^` the precedence of Rust's xor, which is wrong for a
//! power; here `^` binds tighter than unary minus, and a chain `a^b^c`
//! without parentheses is an error (tools read it either way).

use proc_macro2::{Ident, Span};
use syn::parse::ParseStream;
use syn::{LitFloat, LitInt, Token};

use super::ast::{BinOp, Expr, Function, PREFIX_BP};
use crate::ctxt::SpanRange;

/// What the error messages list as supported functions.
pub const SUPPORTED_FUNCTIONS: &str = "sin, cos, tan, sqrt, exp, ln, atan2(y, x), and dot(coordinate) for a velocity";

/// What the error messages list as supported operators.
pub const SUPPORTED_OPERATORS: &str = "+ - * / ^ (power) and parentheses";

/// The deepest nesting of parentheses, function calls, unary minus and
/// powers the parser follows (its own recursion; 2000 nested parentheses
/// overflowed the compiler's stack inside the macro).
pub const MAX_NESTING: usize = 256;

/// The deepest expression tree the macro takes (a sum of `n` terms is `n`
/// deep): the checks and the lowering walk the tree recursively, and a sum
/// of 20000 terms overflowed the compiler's 8 MiB stack (10000 did not).
pub const MAX_DEPTH: usize = 4096;

/// Parses one expression; stops at the end of the input, a `,` or a `;`.
pub fn parse_expr(input: ParseStream) -> syn::Result<Expr> {
    expr_bp(input, 0, 0).map(|(expr, _)| expr)
}

/// The expression and its depth, at `nesting` levels of recursion.
fn expr_bp(input: ParseStream, min_bp: u8, nesting: usize) -> syn::Result<(Expr, usize)> {
    if nesting > MAX_NESTING {
        return Err(input.error(format!(
            "expression nested more than {MAX_NESTING} levels deep (parentheses, function calls, minus signs, \
             powers): the macro stops here rather than overflow the compiler's stack"
        )));
    }
    let (mut lhs, mut depth) = if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        let (operand, depth) = expr_bp(input, PREFIX_BP, nesting + 1)?;
        let neg = Expr::Neg {
            minus: minus.span,
            operand: Box::new(operand),
        };
        (neg, depth + 1)
    } else {
        primary(input, nesting)?
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
        let op_span = input.step(|cursor| match cursor.punct() {
            Some((punct, rest)) => Ok((punct.span(), rest)),
            None => Err(cursor.error("expected an operator")),
        })?;
        let (rhs, rhs_depth) = expr_bp(input, right_bp, nesting + 1)?;
        if op == BinOp::Pow && is_power(&rhs) {
            return Err(syn::Error::new(
                op_span,
                "chained `^` without parentheses: `a^b^c` reads as `a^(b^c)` in mathematics and as `(a^b)^c` in \
                 many tools; write the parentheses you mean",
            ));
        }
        depth = depth.max(rhs_depth) + 1;
        if depth > MAX_DEPTH {
            return Err(input.error(format!(
                "expression more than {MAX_DEPTH} operations deep (a sum of that many terms): the macro stops here \
                 rather than overflow the compiler's stack"
            )));
        }
        lhs = Expr::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        };
    }
    Ok((lhs, depth))
}

/// Whether `expr` is a power as parsed, under any minus signs (not one in
/// parentheses).
fn is_power(expr: &Expr) -> bool {
    match expr {
        Expr::Binary { op: BinOp::Pow, .. } => true,
        Expr::Neg { operand, .. } => is_power(operand),
        _ => false,
    }
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
        let message = match c {
            '.' => "unsupported operator `.`: write functions as `sin(x)` and powers as `x^2`, not `x.sin()` or \
                    `x.powi(2)`"
                .to_owned(),
            ':' => "paths are not expressions: write `PI` for pi (not `std::f64::consts::PI`) and declare other \
                    constants as parameters"
                .to_owned(),
            '=' => "a constraint is an expression g(q) that the motion keeps at zero, not an equation: for \
                    `a = b` write `a - (b)`"
                .to_owned(),
            '\'' => "write a velocity as `dot(x)`, not `x'`".to_owned(),
            _ => format!("unsupported operator `{c}`; supported: {SUPPORTED_OPERATORS}"),
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

/// A primary expression and its depth (1 for a leaf).
fn primary(input: ParseStream, nesting: usize) -> syn::Result<(Expr, usize)> {
    if input.peek(LitInt) {
        let lit: LitInt = input.parse()?;
        return number(lit.suffix(), lit.span(), lit.base10_digits(), || lit.base10_parse()).map(|e| (e, 1));
    }
    if input.peek(LitFloat) {
        let lit: LitFloat = input.parse()?;
        return number(lit.suffix(), lit.span(), lit.base10_digits(), || lit.base10_parse()).map(|e| (e, 1));
    }
    if input.peek(syn::token::Paren) {
        let content;
        let paren = syn::parenthesized!(content in input);
        let (inner, depth) = expr_bp(&content, 0, nesting + 1)?;
        if !content.is_empty() {
            return Err(content.error("unexpected token in parentheses"));
        }
        let paren = Expr::Paren {
            open: paren.span.open(),
            inner: Box::new(inner),
            close: paren.span.close(),
        };
        return Ok((paren, depth + 1));
    }
    if input.peek(syn::Ident) {
        let name: Ident = input.parse()?;
        if !input.peek(syn::token::Paren) {
            return Ok((Expr::Name(name), 1));
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
            let dot = Expr::Dot {
                dot: name,
                coord,
                close,
            };
            return Ok((dot, 1));
        }
        let Some(func) = Function::from_name(&name.to_string()) else {
            let hint = match name.to_string().as_str() {
                "log" | "log10" | "log2" => " (the natural logarithm is `ln`; log_b(x) is `ln(x)/ln(b)`)",
                "pow" | "powi" | "powf" => " (write powers as `x^n`)",
                "sq" | "square" => " (write `x^2`)",
                "cbrt" => " (write `x^(1/3)` as `x^0.3333333333333333`, or better a parameter)",
                "atan" | "arctan" => " (write `atan2(y, x)`)",
                "abs" => {
                    " (`sqrt(x^2)`; a crane's expressions are smooth where it moves, so an `abs` usually \
                           means a sign to choose once, e.g. a rope length that stays positive)"
                }
                "asin" | "arcsin" => " (write `atan2(x, sqrt(1 - x^2))`)",
                "acos" | "arccos" => " (write `atan2(sqrt(1 - x^2), x)`)",
                "sinh" => " (write `0.5*(exp(x) - exp(-x))`)",
                "cosh" => " (write `0.5*(exp(x) + exp(-x))`)",
                "tanh" => " (write `(exp(2*x) - 1)/(exp(2*x) + 1)`)",
                _ => "",
            };
            return Err(syn::Error::new(
                name.span(),
                format!("unsupported function `{name}`{hint}; supported: {SUPPORTED_FUNCTIONS}"),
            ));
        };
        // the arguments, separated by commas (a trailing one allowed)
        let (mut args, mut deepest) = (Vec::new(), 0);
        while !content.is_empty() {
            let (arg, depth) = expr_bp(&content, 0, nesting + 1)?;
            args.push(arg);
            deepest = deepest.max(depth);
            if content.is_empty() {
                break;
            }
            content.parse::<Token![,]>()?;
        }
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
        let call = Expr::Call {
            func,
            name,
            args,
            close,
        };
        return Ok((call, deepest + 1));
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
