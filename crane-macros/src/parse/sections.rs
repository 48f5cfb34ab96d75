//! The sections of a declaration: the struct body is split at the section
//! keywords, each section is parsed and stored once, and list sections are
//! split into items at top-level separators, so that parsing recovers at
//! section and item boundaries and one typo does not hide the others.

use proc_macro2::{Delimiter, Ident, Span, TokenStream, TokenTree};
use syn::Token;
use syn::parse::{ParseStream, Parser};
use syn::punctuated::Punctuated;

use super::ast::{MinimalDecl, Section, Sections};
use super::expr::parse_expr;
use super::items::{parse_constraint, parse_force, parse_minimal_stmt, parse_mu, parse_param, parse_sample};
use crate::ctxt::{Ctxt, SpanRange};

/// Section keywords and what follows each.
const SECTIONS: &[(&str, Follow)] = &[
    ("params", Follow::Brace),
    ("robot", Follow::Bracket),
    ("load", Follow::Bracket),
    ("inputs", Follow::Bracket),
    ("kinetic", Follow::Eq),
    ("forces", Follow::Brace),
    ("constraints", Follow::Brace),
    ("minimal", Follow::Bracket),
    ("sample", Follow::Brace),
];

/// The list of section names for error messages.
pub const SECTION_NAMES: &str = "params, robot, load, inputs, kinetic, forces, constraints, minimal, sample";

#[derive(Clone, Copy, PartialEq, Eq)]
enum Follow {
    Brace,
    Bracket,
    Eq,
}

impl Follow {
    fn matches(self, tt: Option<&TokenTree>) -> bool {
        match (self, tt) {
            (Follow::Brace, Some(TokenTree::Group(g))) => g.delimiter() == Delimiter::Brace,
            (Follow::Bracket, Some(TokenTree::Group(g))) => g.delimiter() == Delimiter::Bracket,
            (Follow::Eq, Some(TokenTree::Punct(p))) => p.as_char() == '=',
            _ => false,
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Follow::Brace => "`{ ... }`",
            Follow::Bracket => "`[ ... ]`",
            Follow::Eq => "`= <expression>;`",
        }
    }
}

/// Whether a section starts at `tts[i]`: a section keyword followed by what
/// that section expects (so a parameter called `load` in an expression is
/// not mistaken for a section).
fn section_starts_at(tts: &[TokenTree], i: usize) -> bool {
    let Some(TokenTree::Ident(ident)) = tts.get(i) else {
        return false;
    };
    let name = ident.to_string();
    SECTIONS
        .iter()
        .any(|(kw, follow)| *kw == name && follow.matches(tts.get(i + 1)))
}

pub(super) fn parse_sections(body: TokenStream, cx: &Ctxt) -> Sections {
    let tts: Vec<TokenTree> = body.into_iter().collect();
    let mut sections = Sections::default();
    let mut i = 0;
    while i < tts.len() {
        let keyword = match &tts[i] {
            TokenTree::Ident(ident) => ident.clone(),
            other => {
                cx.error_at(other.span(), format!("expected a section: {SECTION_NAMES}"));
                i = skip_to_section(&tts, i + 1);
                continue;
            }
        };
        let name = keyword.to_string();
        let Some(&(_, follow)) = SECTIONS.iter().find(|(kw, _)| *kw == name) else {
            let hint = match name.as_str() {
                "potential" | "gravity" | "V" | "energy" => {
                    "; gravity and other potential forces are generalized forces in `forces`, `-dV/dq` \
                     (for a load of mass m_l at height z: `forces { z: -m_l*g }`)"
                }
                "outputs" | "outputs_map" => "; the outputs are the `load` coordinates",
                _ => "",
            };
            cx.error_at(
                keyword.span(),
                format!("unknown section `{keyword}`; expected one of: {SECTION_NAMES}{hint}"),
            );
            i = skip_to_section(&tts, i + 1);
            continue;
        };
        if !follow.matches(tts.get(i + 1)) {
            let span = tts.get(i + 1).map_or(keyword.span(), TokenTree::span);
            cx.error_at(span, format!("expected {} after `{keyword}`", follow.describe()));
            i = skip_to_section(&tts, i + 1);
            continue;
        }
        // the tokens of this section: up to the next section start
        let end = match follow {
            Follow::Eq => kinetic_end(&tts, i + 2),
            Follow::Brace => i + 2,
            Follow::Bracket if name == "minimal" && Follow::Brace.matches(tts.get(i + 2)) => i + 3,
            Follow::Bracket => i + 2,
        }
        .min(tts.len());
        let range = SpanRange {
            first: keyword.span(),
            last: tts[end - 1].span(),
        };
        parse_section(&keyword, &tts[i + 1..end], range, &mut sections, cx);
        i = end;
    }
    sections
}

fn skip_to_section(tts: &[TokenTree], mut i: usize) -> usize {
    while i < tts.len() && !section_starts_at(tts, i) {
        i += 1;
    }
    i
}

/// End (exclusive) of `kinetic = ... ;`: just after the `;`, or at the next
/// section if the `;` is missing.
fn kinetic_end(tts: &[TokenTree], start: usize) -> usize {
    let mut i = start;
    while i < tts.len() {
        match &tts[i] {
            TokenTree::Punct(p) if p.as_char() == ';' => return i + 1,
            _ if section_starts_at(tts, i) => return i,
            _ => i += 1,
        }
    }
    i
}

fn group_stream(tt: &TokenTree) -> TokenStream {
    match tt {
        TokenTree::Group(g) => g.stream(),
        _ => TokenStream::new(),
    }
}

fn parse_section(keyword: &Ident, tts: &[TokenTree], range: SpanRange, sections: &mut Sections, cx: &Ctxt) {
    fn store<T>(slot: &mut Option<Section<T>>, keyword: &Ident, range: SpanRange, body: T, cx: &Ctxt) {
        if slot.is_some() {
            cx.error_at(keyword.span(), format!("duplicate section `{keyword}`"));
        } else {
            *slot = Some(Section {
                keyword: keyword.clone(),
                range,
                body,
            });
        }
    }
    match keyword.to_string().as_str() {
        "params" => {
            let items = parse_items(group_stream(&tts[0]), ',', parse_param, cx);
            store(&mut sections.params, keyword, range, items, cx);
        }
        "robot" => store(&mut sections.robot, keyword, range, parse_names(&tts[0], cx), cx),
        "load" => store(&mut sections.load, keyword, range, parse_names(&tts[0], cx), cx),
        "inputs" => store(&mut sections.inputs, keyword, range, parse_names(&tts[0], cx), cx),
        "kinetic" => {
            // tts = `=` expr... [;]
            let ends_with_semi = matches!(tts.last(), Some(TokenTree::Punct(p)) if p.as_char() == ';');
            let expr_tokens: TokenStream = if ends_with_semi {
                tts[1..tts.len() - 1].iter().cloned().collect()
            } else {
                cx.error_at(range.last, "expected `;` after the kinetic energy");
                tts[1..].iter().cloned().collect()
            };
            if expr_tokens.is_empty() {
                cx.error_spanned_by(
                    range,
                    "empty section `kinetic`: write the kinetic energy, e.g. `kinetic = 0.5*m*dot(x)^2;`",
                );
                return;
            }
            let end = expr_tokens.clone().into_iter().last().map(|tt| tt.span());
            match parse_expr.parse2(expr_tokens) {
                Ok(expr) => store(&mut sections.kinetic, keyword, range, expr, cx),
                Err(error) => cx.syn_error(at_end_of(error, end)),
            }
        }
        "forces" => {
            let items = parse_items(group_stream(&tts[0]), ',', parse_force, cx);
            store(&mut sections.forces, keyword, range, items, cx);
        }
        "constraints" => {
            let items = parse_items(group_stream(&tts[0]), ',', parse_constraint, cx);
            store(&mut sections.constraints, keyword, range, items, cx);
        }
        "sample" => {
            let items = parse_items(group_stream(&tts[0]), ',', parse_sample, cx);
            store(&mut sections.sample, keyword, range, items, cx);
        }
        "minimal" => {
            let split = tts[0].span();
            let (mu1, mu2) = match parse_mu(group_stream(&tts[0]), split) {
                Ok(mu) => mu,
                Err(error) => {
                    cx.syn_error(error);
                    (Vec::new(), Vec::new())
                }
            };
            let body = match tts.get(1) {
                Some(body @ TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace => {
                    parse_items(group_stream(body), ';', parse_minimal_stmt, cx)
                }
                other => {
                    let span = other.map_or(range.last, TokenTree::span);
                    cx.error_at(
                        span,
                        "expected `{ ... }` with the map `q = phi(mu)` after `minimal [...]`",
                    );
                    Vec::new()
                }
            };
            store(
                &mut sections.minimal,
                keyword,
                range,
                MinimalDecl { split, mu1, mu2, body },
                cx,
            );
        }
        _ => {}
    }
}

/// Splits `tokens` at top-level `separator`s and parses each item with
/// `parser`, reporting (and skipping) items that fail.
fn parse_items<T>(
    tokens: TokenStream,
    separator: char,
    parser: fn(ParseStream) -> syn::Result<T>,
    cx: &Ctxt,
) -> Vec<T> {
    let mut items = Vec::new();
    let mut current = TokenStream::new();
    let mut chunks = Vec::new();
    for tt in tokens {
        match &tt {
            TokenTree::Punct(p) if p.as_char() == separator => {
                chunks.push((std::mem::take(&mut current), Some(p.span())));
            }
            _ => current.extend([tt]),
        }
    }
    chunks.push((current, None));
    for (chunk, separator_span) in chunks {
        if chunk.is_empty() {
            // a trailing separator is fine, a doubled one is not
            if let Some(span) = separator_span {
                cx.error_at(span, format!("unexpected `{separator}`"));
            }
            continue;
        }
        // `m_l = 100.0; J = 0.1`: a separator of statements between items
        if separator == ',' {
            let semicolon = chunk.clone().into_iter().find_map(|tt| match tt {
                TokenTree::Punct(p) if p.as_char() == ';' => Some(p.span()),
                _ => None,
            });
            if let Some(span) = semicolon {
                cx.error_at(span, "expected `,` between the items of a section, found `;`");
                continue;
            }
        }
        let end = chunk.clone().into_iter().last().map(|tt| tt.span());
        // a token missing at the very end (`params { g }`: "expected `=`")
        // is reported by syn at the macro call; move it to the chunk's end
        let parse_chunk = |input: ParseStream| {
            parser(input).map_err(|error| {
                let missing_token = input.is_empty() && error.to_string().starts_with("expected `");
                match end {
                    Some(span) if missing_token => syn::Error::new(span, error.to_string()),
                    _ => error,
                }
            })
        };
        match parse_chunk.parse2(chunk) {
            Ok(item) => items.push(item),
            Err(error) => cx.syn_error(at_end_of(error, end)),
        }
    }
    items
}

/// syn reports "unexpected end of input" at the macro call when a re-parsed
/// chunk ends too early (`params { g }`); point at the chunk's last token
/// instead, where the user has to continue.
fn at_end_of(error: syn::Error, end: Option<Span>) -> syn::Error {
    match end {
        Some(span) if error.to_string().starts_with("unexpected end of input") => {
            syn::Error::new(span, error.to_string())
        }
        _ => error,
    }
}

fn parse_names(group: &TokenTree, cx: &Ctxt) -> Vec<Ident> {
    // `/// the trolley` above a coordinate: doc comments document the
    // struct and its parameters, which are its fields
    if let Some(TokenTree::Punct(p)) = group_stream(group)
        .into_iter()
        .find(|tt| matches!(tt, TokenTree::Punct(p) if p.as_char() == '#'))
    {
        cx.error_at(
            p.span(),
            "attributes and doc comments are not allowed on coordinates and inputs: describe them in a `//` \
             comment or in the crane's doc comment (doc comments are for the crane and its parameters)",
        );
        return Vec::new();
    }
    let parser = Punctuated::<Ident, Token![,]>::parse_terminated;
    match parser.parse2(group_stream(group)) {
        Ok(names) => names.into_iter().collect(),
        Err(error) => {
            cx.syn_error(error);
            Vec::new()
        }
    }
}
