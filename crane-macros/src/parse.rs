//! Syntax: the tokens of a `crane_model!` invocation → a [`Declaration`].
//!
//! The AST keeps the user's identifiers and the spans of every expression,
//! so that later stages can point at the culprit. Parsing recovers at
//! section and item boundaries (items are separated by top-level commas), so
//! one typo does not hide the others.
//!
//! Expressions are parsed by a small Pratt parser: `syn::Expr` gives `^` the
//! precedence of Rust's xor, which is wrong for a power.

use std::fmt;

use proc_macro2::{Delimiter, Ident, Span, TokenStream, TokenTree};
use syn::parse::{ParseStream, Parser};
use syn::punctuated::Punctuated;
use syn::{Attribute, LitFloat, LitInt, Token, Visibility};

use crate::ctxt::{Ctxt, SpanRange};
use crate::expr::Func;

/// A whole declaration: `[attrs] [vis] struct Name { sections }`.
pub struct Declaration {
    /// Outer attributes and doc comments, passed through to the struct.
    pub attrs: Vec<Attribute>,
    /// Visibility of the struct.
    pub vis: Visibility,
    /// Name of the struct.
    pub name: Ident,
    /// The sections in their canonical order; `None` if absent.
    pub sections: Sections,
}

/// The sections of a declaration.
#[derive(Default)]
pub struct Sections {
    /// `params { name = default, ... }`.
    pub params: Option<Section<Vec<ParamDecl>>>,
    /// `robot [p1, p2, ...]`: the robot coordinates `p`.
    pub robot: Option<Section<Vec<Ident>>>,
    /// `load [x1, ...]`: the load coordinates `x` (the outputs).
    pub load: Option<Section<Vec<Ident>>>,
    /// `inputs [u1, ...]`.
    pub inputs: Option<Section<Vec<Ident>>>,
    /// `kinetic = expr;`: the kinetic energy.
    pub kinetic: Option<Section<Expr>>,
    /// `forces { coord: expr, ... }`: generalized forces.
    pub forces: Option<Section<Vec<ForceDecl>>>,
    /// `constraints { [#[rope(N = L)]] name: expr, ... }`.
    pub constraints: Option<Section<Vec<ConstraintDecl>>>,
    /// `minimal [mu1.. | mu2..] { ... }`: a minimal-coordinate map.
    pub minimal: Option<Section<MinimalDecl>>,
    /// `sample { name = low .. high, ... }`: where the generated self-test
    /// draws its random points (coordinates, and minimal coordinates).
    pub sample: Option<Section<Vec<SampleDecl>>>,
}

/// `name = low .. high` in `sample`.
pub struct SampleDecl {
    /// A coordinate or minimal coordinate.
    pub name: Ident,
    /// Lower bound, a constant expression.
    pub low: Expr,
    /// Upper bound, a constant expression.
    pub high: Expr,
}

/// A section: its keyword, where it is, and what it holds.
pub struct Section<T> {
    /// The section keyword as written.
    pub keyword: Ident,
    /// From the keyword to the end of the section.
    pub range: SpanRange,
    /// The content.
    pub body: T,
}

/// `name = default` in `params`.
pub struct ParamDecl {
    /// Doc comments on the parameter.
    pub docs: Vec<Attribute>,
    /// Name of the parameter (a field of the struct).
    pub name: Ident,
    /// Default value, a constant expression.
    pub default: Expr,
}

/// `coord: force` in `forces`.
pub struct ForceDecl {
    /// The coordinate the generalized force acts on.
    pub coord: Ident,
    /// The generalized force.
    pub force: Expr,
}

/// `name: g` in `constraints`, optionally marked as a rope.
pub struct ConstraintDecl {
    /// `#[rope(N1 = L1)]`, if present.
    pub rope: Option<RopeAttr>,
    /// Name of the constraint.
    pub name: Ident,
    /// The constraint function `g_k(q)`.
    pub expr: Expr,
}

/// `#[rope(Tension = length)]`: the tension `N = lambda * length`.
pub struct RopeAttr {
    /// Name of the tension.
    pub tension: Ident,
    /// Length of the rope, a function of the coordinates.
    pub length: Expr,
}

/// `minimal [mu1, ... | mu2, ...] { let a = e; coord = e; ... }`: the map
/// `q = phi(mu)` to minimal coordinates (paper sect. 3.2, eq. 6); `mu2`
/// (one per load coordinate) must make `D2 phi_x` regular (eq. 12).
pub struct MinimalDecl {
    /// The `[...]` group with the minimal coordinates (for errors about
    /// their number).
    pub split: Span,
    /// The minimal coordinates `mu1`.
    pub mu1: Vec<Ident>,
    /// The minimal coordinates `mu2`.
    pub mu2: Vec<Ident>,
    /// The body of the map `q = phi(mu)`, in the order written.
    pub body: Vec<MinimalStmt>,
}

/// A statement of a `minimal` block.
pub enum MinimalStmt {
    /// `let name = value;`: an abbreviation.
    Let {
        /// The abbreviation.
        name: Ident,
        /// Its value.
        value: Expr,
    },
    /// `coord = value;`: one component of `phi`.
    Assign {
        /// The redundant coordinate.
        coord: Ident,
        /// Its value as a function of `mu`.
        value: Expr,
    },
}

/// Binary operators, in the DSL's precedence order.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`, a power (right-associative, tighter than unary minus).
    Pow,
}

impl BinOp {
    /// Left and right binding power (Pratt): `+ -` < `* /` < unary minus < `^`.
    fn binding_power(self) -> (u8, u8) {
        match self {
            BinOp::Add | BinOp::Sub => (1, 2),
            BinOp::Mul | BinOp::Div => (3, 4),
            BinOp::Pow => (8, 7),
        }
    }

    fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}

/// Binding power of unary minus: `-x^2 = -(x^2)`, `-x * y = (-x) * y`.
const PREFIX_BP: u8 = 5;

/// Functions of the expression language.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Function {
    /// `sin cos tan sqrt exp ln`.
    Unary(Func),
    /// `atan2(y, x)`.
    Atan2,
}

/// What the error messages list as supported functions.
pub const SUPPORTED_FUNCTIONS: &str =
    "sin, cos, tan, sqrt, exp, ln, atan2(y, x), and dot(coordinate) for a velocity";

/// What the error messages list as supported operators.
pub const SUPPORTED_OPERATORS: &str = "+ - * / ^ (power) and parentheses";

impl Function {
    /// Looks up a function by name.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "sin" => Function::Unary(Func::Sin),
            "cos" => Function::Unary(Func::Cos),
            "tan" => Function::Unary(Func::Tan),
            "sqrt" => Function::Unary(Func::Sqrt),
            "exp" => Function::Unary(Func::Exp),
            "ln" => Function::Unary(Func::Ln),
            "atan2" => Function::Atan2,
            _ => return None,
        })
    }

    fn arity(self) -> usize {
        match self {
            Function::Unary(_) => 1,
            Function::Atan2 => 2,
        }
    }
}

/// An expression of the DSL, with spans.
#[derive(Clone, Debug)]
pub enum Expr {
    /// A numeric literal (integer or float).
    Num {
        /// Its value.
        value: f64,
        /// The literal as written.
        text: String,
        /// Its span.
        span: Span,
    },
    /// A name: `PI`, a parameter, coordinate or input.
    Name(Ident),
    /// `dot(coord)`: a velocity.
    Dot {
        /// The `dot` keyword.
        dot: Ident,
        /// The coordinate.
        coord: Ident,
        /// The closing parenthesis.
        close: Span,
    },
    /// `-operand`.
    Neg {
        /// The minus sign.
        minus: Span,
        /// The operand.
        operand: Box<Expr>,
    },
    /// `lhs op rhs`.
    Binary {
        /// The operator.
        op: BinOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// `name(args)`.
    Call {
        /// The function.
        func: Function,
        /// Its name as written.
        name: Ident,
        /// The arguments.
        args: Vec<Expr>,
        /// The closing parenthesis.
        close: Span,
    },
    /// `(inner)`.
    Paren {
        /// The opening parenthesis.
        open: Span,
        /// The parenthesized expression.
        inner: Box<Expr>,
        /// The closing parenthesis.
        close: Span,
    },
}

impl Expr {
    /// From the first to the last token of the expression.
    pub fn range(&self) -> SpanRange {
        match self {
            Expr::Num { span, .. } => SpanRange::single(*span),
            Expr::Name(ident) => SpanRange::single(ident.span()),
            Expr::Dot { dot, close, .. } => SpanRange {
                first: dot.span(),
                last: *close,
            },
            Expr::Neg { minus, operand } => SpanRange::single(*minus).to(operand.range()),
            Expr::Binary { lhs, rhs, .. } => lhs.range().to(rhs.range()),
            Expr::Call { name, close, .. } => SpanRange {
                first: name.span(),
                last: *close,
            },
            Expr::Paren { open, close, .. } => SpanRange {
                first: *open,
                last: *close,
            },
        }
    }

    fn precedence(&self) -> u8 {
        match self {
            Expr::Binary { op, .. } => op.binding_power().0,
            Expr::Neg { .. } => PREFIX_BP,
            _ => u8::MAX,
        }
    }
}

/// Prints the expression as the user would write it (used in doc comments).
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Expr::Num { text, .. } => f.write_str(text),
            Expr::Name(ident) => write!(f, "{ident}"),
            Expr::Dot { coord, .. } => write!(f, "dot({coord})"),
            Expr::Neg { operand, .. } => {
                if operand.precedence() < PREFIX_BP {
                    write!(f, "-({operand})")
                } else {
                    write!(f, "-{operand}")
                }
            }
            Expr::Binary { op, lhs, rhs, .. } => {
                let (l, r) = op.binding_power();
                let wrap = |e: &Expr, bp: u8| {
                    if e.precedence() < bp {
                        format!("({e})")
                    } else {
                        e.to_string()
                    }
                };
                let lhs = wrap(lhs, l);
                let rhs = wrap(rhs, r);
                if *op == BinOp::Pow {
                    write!(f, "{lhs}^{rhs}")
                } else {
                    write!(f, "{lhs} {} {rhs}", op.symbol())
                }
            }
            Expr::Call { name, args, .. } => {
                let args: Vec<String> = args.iter().map(ToString::to_string).collect();
                write!(f, "{name}({})", args.join(", "))
            }
            Expr::Paren { inner, .. } => write!(f, "({inner})"),
        }
    }
}

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
pub const SECTION_NAMES: &str =
    "params, robot, load, inputs, kinetic, forces, constraints, minimal, sample";

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

/// Parses a whole invocation. Returns `None` if not even the struct header
/// could be read; every problem is reported to `cx`.
pub fn parse(tokens: TokenStream, cx: &Ctxt) -> Option<Declaration> {
    let header =
        |input: ParseStream| -> syn::Result<(Vec<Attribute>, Visibility, Ident, TokenStream)> {
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
    let sections = parse_sections(body, cx);
    Some(Declaration {
        attrs,
        vis,
        name,
        sections,
    })
}

fn parse_sections(body: TokenStream, cx: &Ctxt) -> Sections {
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
            cx.error_at(
                keyword.span(),
                format!("unknown section `{keyword}`; expected one of: {SECTION_NAMES}"),
            );
            i = skip_to_section(&tts, i + 1);
            continue;
        };
        if !follow.matches(tts.get(i + 1)) {
            let span = tts.get(i + 1).map_or(keyword.span(), TokenTree::span);
            cx.error_at(
                span,
                format!("expected {} after `{keyword}`", follow.describe()),
            );
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

fn parse_section(
    keyword: &Ident,
    tts: &[TokenTree],
    range: SpanRange,
    sections: &mut Sections,
    cx: &Ctxt,
) {
    fn store<T>(
        slot: &mut Option<Section<T>>,
        keyword: &Ident,
        range: SpanRange,
        body: T,
        cx: &Ctxt,
    ) {
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
        "robot" => store(
            &mut sections.robot,
            keyword,
            range,
            parse_names(&tts[0], cx),
            cx,
        ),
        "load" => store(
            &mut sections.load,
            keyword,
            range,
            parse_names(&tts[0], cx),
            cx,
        ),
        "inputs" => store(
            &mut sections.inputs,
            keyword,
            range,
            parse_names(&tts[0], cx),
            cx,
        ),
        "kinetic" => {
            // tts = `=` expr... [;]
            let ends_with_semi =
                matches!(tts.last(), Some(TokenTree::Punct(p)) if p.as_char() == ';');
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
                MinimalDecl {
                    split,
                    mu1,
                    mu2,
                    body,
                },
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
    let parser = Punctuated::<Ident, Token![,]>::parse_terminated;
    match parser.parse2(group_stream(group)) {
        Ok(names) => names.into_iter().collect(),
        Err(error) => {
            cx.syn_error(error);
            Vec::new()
        }
    }
}

fn parse_param(input: ParseStream) -> syn::Result<ParamDecl> {
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
    input.parse::<Token![=]>()?;
    let default = parse_expr(input)?;
    Ok(ParamDecl {
        docs: attrs,
        name,
        default,
    })
}

/// `name = low .. high`; the bounds are split at the `..` token pair.
fn parse_sample(input: ParseStream) -> syn::Result<SampleDecl> {
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
    let high: TokenStream = tts[dots + 2..].iter().cloned().collect();
    if low.is_empty() || high.is_empty() {
        return Err(syn::Error::new(
            tts[dots].span(),
            format!("a range needs both bounds: `{name} = low .. high`"),
        ));
    }
    Ok(SampleDecl { name, low: parse_expr.parse2(low)?, high: parse_expr.parse2(high)? })
}

fn parse_force(input: ParseStream) -> syn::Result<ForceDecl> {
    let coord: Ident = input.parse()?;
    input.parse::<Token![:]>()?;
    let force = parse_expr(input)?;
    Ok(ForceDecl { coord, force })
}

fn parse_constraint(input: ParseStream) -> syn::Result<ConstraintDecl> {
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
            return Err(syn::Error::new_spanned(
                attr,
                "duplicate `#[rope(...)]` attribute",
            ));
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
fn parse_mu(tokens: TokenStream, split: Span) -> syn::Result<(Vec<Ident>, Vec<Ident>)> {
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

fn parse_minimal_stmt(input: ParseStream) -> syn::Result<MinimalStmt> {
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

fn primary(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(LitInt) {
        let lit: LitInt = input.parse()?;
        no_suffix(lit.suffix(), lit.span())?;
        let value = finite(lit.base10_parse::<f64>()?, lit.span())?;
        return Ok(Expr::Num {
            value,
            text: lit.base10_digits().to_owned(),
            span: lit.span(),
        });
    }
    if input.peek(LitFloat) {
        let lit: LitFloat = input.parse()?;
        no_suffix(lit.suffix(), lit.span())?;
        let value = finite(lit.base10_parse::<f64>()?, lit.span())?;
        return Ok(Expr::Num {
            value,
            text: lit.base10_digits().to_owned(),
            span: lit.span(),
        });
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
        let args: Vec<Expr> =
            Punctuated::<Expr, Token![,]>::parse_terminated_with(&content, parse_expr)?
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
    Err(input.error(
        "expected an expression: a number, a name, `dot(coordinate)`, a function call or `( ... )`",
    ))
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
