//! Syntax: the tokens of a `crane_model!` invocation → a [`Declaration`].
//!
//! The AST keeps the user's identifiers and the spans of every expression,
//! so that later stages can point at the culprit. Parsing recovers at
//! section and item boundaries (items are separated by top-level commas), so
//! one typo does not hide the others.
//!
//! Expressions are parsed by a small Pratt parser: `syn::Expr` gives `^` the
//! precedence of Rust's xor, which is wrong for a power.
//!
//! This module holds the entry point [`parse`] (the struct header); the
//! stages below it are `ast` (the syntax tree), `sections` (splitting the
//! body into sections and the sections into items), `items` (the parsers of
//! the items) and `expr` (the expression parser).

mod ast;
mod expr;
mod items;
mod sections;

use proc_macro2::{Ident, TokenStream};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Token, Visibility};

use crate::ctxt::Ctxt;

pub use ast::{
    BinOp, ConstraintDecl, Declaration, Expr, Function, MinimalDecl, MinimalStmt, ParamDecl, SampleDecl, Section,
};
/// For the unit tests, which parse expressions on their own.
#[cfg(test)]
pub use expr::{MAX_DEPTH, MAX_NESTING, parse_expr};

/// Parses a whole invocation. Returns `None` if not even the struct header
/// could be read; every problem is reported to `cx`.
pub fn parse(tokens: TokenStream, cx: &Ctxt) -> Option<Declaration> {
    let header = |input: ParseStream| -> syn::Result<(Vec<Attribute>, Visibility, Ident, TokenStream)> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis: Visibility = input.parse()?;
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        let content;
        syn::braced!(content in input);
        let body: TokenStream = content.parse()?;
        Ok((attrs, vis, name, body))
    };
    let (attrs, vis, name, body) = match header.parse2(tokens) {
        Ok(header) => header,
        Err(error) => {
            cx.syn_error(error);
            return None;
        }
    };
    let sections = sections::parse_sections(body, cx);
    Some(Declaration {
        attrs,
        vis,
        name,
        sections,
    })
}
