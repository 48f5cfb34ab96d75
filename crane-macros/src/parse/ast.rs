//! The syntax tree of a declaration, as the parser builds it: the
//! sections with the user's identifiers, and the expressions with the spans
//! of their tokens; plus the operators and functions of the expression
//! language and how an expression prints back (for doc comments).

use std::fmt;

use proc_macro2::{Ident, Span};
use syn::{Attribute, Visibility};

use crate::ctxt::SpanRange;
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
    /// Declared `name: positive = ...`: must be > 0 (masses, inertias, radii).
    pub positive: bool,
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

/// `#[rope(Tension = length)]`: the tension `N = -lambda dg/dlength`.
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
    /// `^`, a power (tighter than unary minus; chains need parentheses).
    Pow,
}

impl BinOp {
    /// Left and right binding power (Pratt): `+ -` < `* /` < unary minus < `^`.
    pub(super) fn binding_power(self) -> (u8, u8) {
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
pub(super) const PREFIX_BP: u8 = 5;

/// Functions of the expression language.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Function {
    /// `sin cos tan sqrt exp ln`.
    Unary(Func),
    /// `atan2(y, x)`.
    Atan2,
}

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

    pub(super) fn arity(self) -> usize {
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
