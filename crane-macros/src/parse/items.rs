//! The items of the sections: a parameter, a force, a constraint with its
//! `#[rope(...)]` attribute, a `sample` range, the `[mu1 | mu2]` split and
//! the statements of a `minimal` block.

use proc_macro2::{Ident, Span, TokenStream, TokenTree};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Token};

use super::ast::{ConstraintDecl, ForceDecl, MinimalStmt, ParamDecl, RopeAttr, SampleDecl};
use super::expr::parse_expr;

pub(super) fn parse_param(input: ParseStream) -> syn::Result<ParamDecl> {
    let attrs = input.call(Attribute::parse_outer)?;
    for attr in &attrs {
        if !attr.path().is_ident("doc") {
            return Err(syn::Error::new_spanned(
                attr,
                "only doc comments are allowed on parameters",
            ));
        }
    }
    let name: Ident = input.parse()?;
    // `name: positive = value` declares a parameter that must be > 0
    let positive = if input.peek(Token![:]) {
        input.parse::<Token![:]>()?;
        let kind: Ident = input.parse()?;
        if kind != "positive" {
            return Err(syn::Error::new(
                kind.span(),
                format!("unknown parameter kind `{kind}`; the only one is `positive`, e.g. `{name}: positive = 1.0`"),
            ));
        }
        true
    } else {
        false
    };
    input.parse::<Token![=]>()?;
    let default = parse_expr(input)?;
    Ok(ParamDecl {
        docs: attrs,
        name,
        positive,
        default,
    })
}

/// `name = low .. high` (or `..=`); the bounds are split at the `..` token
/// pair.
pub(super) fn parse_sample(input: ParseStream) -> syn::Result<SampleDecl> {
    let name: Ident = input.parse()?;
    input.parse::<Token![=]>()?;
    let rest: TokenStream = input.parse()?;
    let tts: Vec<TokenTree> = rest.into_iter().collect();
    let dots = tts.windows(2).position(|w| {
        matches!((&w[0], &w[1]), (TokenTree::Punct(a), TokenTree::Punct(b))
            if a.as_char() == '.' && a.spacing() == proc_macro2::Spacing::Joint && b.as_char() == '.')
    });
    let Some(dots) = dots else {
        return Err(syn::Error::new(
            name.span(),
            format!("expected a range `{name} = low .. high` (constant bounds)"),
        ));
    };
    let low: TokenStream = tts[..dots].iter().cloned().collect();
    // `low ..= high` is the same box for continuous draws
    let inclusive = matches!(tts.get(dots + 2), Some(TokenTree::Punct(p)) if p.as_char() == '=');
    let high: TokenStream = tts[dots + 2 + usize::from(inclusive)..].iter().cloned().collect();
    if low.is_empty() || high.is_empty() {
        return Err(syn::Error::new(
            tts[dots].span(),
            format!("a range needs both bounds: `{name} = low .. high`"),
        ));
    }
    Ok(SampleDecl {
        name,
        low: parse_expr.parse2(low)?,
        high: parse_expr.parse2(high)?,
    })
}

pub(super) fn parse_force(input: ParseStream) -> syn::Result<ForceDecl> {
    let coord: Ident = input.parse()?;
    input.parse::<Token![:]>()?;
    let force = parse_expr(input)?;
    Ok(ForceDecl { coord, force })
}

pub(super) fn parse_constraint(input: ParseStream) -> syn::Result<ConstraintDecl> {
    let attrs = input.call(Attribute::parse_outer)?;
    let mut rope = None;
    for attr in &attrs {
        if attr.path().is_ident("doc") {
            continue;
        }
        if !attr.path().is_ident("rope") {
            return Err(syn::Error::new_spanned(
                attr,
                "unknown attribute on a constraint; expected `#[rope(Tension = length)]`",
            ));
        }
        if rope.is_some() {
            return Err(syn::Error::new_spanned(attr, "duplicate `#[rope(...)]` attribute"));
        }
        rope = Some(attr.parse_args_with(|input: ParseStream| {
            let tension: Ident = input.parse()?;
            input.parse::<Token![=]>()?;
            let length = parse_expr(input)?;
            Ok(RopeAttr { tension, length })
        })?);
    }
    let name: Ident = input.parse()?;
    input.parse::<Token![:]>()?;
    let expr = parse_expr(input)?;
    Ok(ConstraintDecl { rope, name, expr })
}

/// What the error messages show as the form of the split.
const SPLIT_FORM: &str = "`minimal [mu1, ... | mu2, ...]`, with one mu2 per load coordinate \
     (chosen so that D2 phi_x is regular, eq. 12)";

/// `mu1, ... | mu2, ...`, the content of the `[...]` group at `split`.
pub(super) fn parse_mu(tokens: TokenStream, split: Span) -> syn::Result<(Vec<Ident>, Vec<Ident>)> {
    let bars: Vec<Span> = tokens
        .clone()
        .into_iter()
        .filter_map(|tt| match tt {
            TokenTree::Punct(p) if p.as_char() == '|' => Some(p.span()),
            _ => None,
        })
        .collect();
    match bars[..] {
        [] => {
            return Err(syn::Error::new(
                split,
                format!("missing `|` between mu1 and mu2: write {SPLIT_FORM}"),
            ));
        }
        [_] => {}
        [_, second, ..] => {
            return Err(syn::Error::new(
                second,
                format!("only one `|` is allowed: write {SPLIT_FORM}"),
            ));
        }
    }
    let parser = |input: ParseStream| -> syn::Result<(Vec<Ident>, Vec<Ident>)> {
        let names = |input: ParseStream| -> syn::Result<Vec<Ident>> {
            let mut names = Vec::new();
            while !input.is_empty() && !input.peek(Token![|]) {
                names.push(input.parse()?);
                if input.is_empty() || input.peek(Token![|]) {
                    break;
                }
                input.parse::<Token![,]>()?;
            }
            Ok(names)
        };
        let mu1 = names(input)?;
        input.parse::<Token![|]>()?;
        let mu2 = names(input)?;
        Ok((mu1, mu2))
    };
    parser.parse2(tokens)
}

pub(super) fn parse_minimal_stmt(input: ParseStream) -> syn::Result<MinimalStmt> {
    if input.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value = parse_expr(input)?;
        Ok(MinimalStmt::Let { name, value })
    } else {
        let coord: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value = parse_expr(input)?;
        Ok(MinimalStmt::Assign { coord, value })
    }
}
