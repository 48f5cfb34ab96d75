//! The IR: hash-consing, simplification and differentiation.
//!
//! Derivatives are checked structurally where the expected form is clear
//! and numerically everywhere: the evaluator of the IR against central
//! finite differences at several points.

use syn::parse::Parser;

use super::tokens;
use crate::diff::{Differentiator, diff};
use crate::expr::{Arena, F64, Func, Id, Node, Sym};
use crate::parse::{BinOp, Expr, Function, parse_expr};

const X: Sym = Sym::Coord(0);
const Y: Sym = Sym::Coord(1);
const Z: Sym = Sym::Coord(2);
const A: Sym = Sym::Param(0);
const B: Sym = Sym::Param(1);

/// Lowers `source` with `x y z` as coordinates, `vx vy vz` as their
/// velocities and `a b` as parameters (a test-sized version of `check.rs`).
fn build(arena: &mut Arena, source: &str) -> Id {
    fn lower(arena: &mut Arena, e: &Expr) -> Id {
        match e {
            Expr::Num { value, .. } => arena.constant(*value),
            Expr::Name(ident) => {
                let sym = match ident.to_string().as_str() {
                    "PI" => return arena.constant(std::f64::consts::PI),
                    "x" => X,
                    "y" => Y,
                    "z" => Z,
                    "vx" => Sym::Vel(0),
                    "vy" => Sym::Vel(1),
                    "vz" => Sym::Vel(2),
                    "a" => A,
                    "b" => B,
                    other => panic!("unknown test symbol {other}"),
                };
                arena.sym(sym)
            }
            Expr::Dot { .. } => panic!("use vx, vy, vz"),
            Expr::Neg { operand, .. } => {
                let o = lower(arena, operand);
                arena.neg(o)
            }
            Expr::Binary { op, lhs, rhs } => {
                let l = lower(arena, lhs);
                let r = lower(arena, rhs);
                match op {
                    BinOp::Add => arena.add2(l, r),
                    BinOp::Sub => arena.sub(l, r),
                    BinOp::Mul => arena.mul2(l, r),
                    BinOp::Div => arena.div(l, r),
                    BinOp::Pow => {
                        let exponent = arena.as_const(r).expect("constant exponent");
                        arena.powf(l, exponent)
                    }
                }
            }
            Expr::Call { func, args, .. } => {
                let args: Vec<Id> = args.iter().map(|a| lower(arena, a)).collect();
                match func {
                    Function::Unary(f) => arena.func(*f, args[0]),
                    Function::Atan2 => arena.atan2(args[0], args[1]),
                }
            }
            Expr::Paren { inner, .. } => lower(arena, inner),
        }
    }
    let e = parse_expr.parse2(tokens(source)).expect("test expression parses");
    lower(arena, &e)
}

/// Values of the test symbols at a point `[x, y, z]`.
fn env(point: [f64; 3]) -> impl Fn(Sym) -> f64 {
    move |s| match s {
        Sym::Coord(i) => point[i as usize],
        Sym::Vel(i) => 0.5 + point[i as usize],
        Sym::Param(0) => 1.7,
        Sym::Param(_) => -0.6,
        _ => f64::NAN,
    }
}

const POINTS: [[f64; 3]; 4] = [[0.7, 1.3, 0.4], [1.9, 0.6, -0.8], [0.3, 2.2, 1.7], [1.1, 0.45, -2.5]];

/// Central difference of `e` along coordinate `var`.
fn central_difference(arena: &Arena, e: Id, var: usize, point: [f64; 3]) -> f64 {
    let h = 1e-6;
    let mut plus = point;
    let mut minus = point;
    plus[var] += h;
    minus[var] -= h;
    (arena.eval(e, &env(plus)) - arena.eval(e, &env(minus))) / (2.0 * h)
}

fn assert_derivative_matches(arena: &mut Arena, source: &str, e: Id) {
    let mut d = Differentiator::new(arena);
    let derivatives: Vec<(usize, Id, Vec<Id>)> = (0..3)
        .map(|i| {
            let di = d.diff(e, Sym::Coord(i as u16));
            let second = (0..3).map(|j| d.diff(di, Sym::Coord(j as u16))).collect();
            (i, di, second)
        })
        .collect();
    for point in POINTS {
        for (i, di, second) in &derivatives {
            let exact = arena.eval(*di, &env(point));
            let numerical = central_difference(arena, e, *i, point);
            assert!(
                (exact - numerical).abs() <= 1e-7 * (1.0 + numerical.abs()),
                "d/dq{i} of {source} at {point:?}: symbolic {exact}, numerical {numerical}"
            );
            for (j, dij) in second.iter().enumerate() {
                let exact = arena.eval(*dij, &env(point));
                let numerical = central_difference(arena, *di, j, point);
                assert!(
                    (exact - numerical).abs() <= 1e-6 * (1.0 + numerical.abs()),
                    "d2/dq{i}dq{j} of {source} at {point:?}: symbolic {exact}, numerical {numerical}"
                );
            }
        }
    }
}

#[test]
fn derivatives_match_central_differences() {
    let sources = [
        "x^3",
        "sin(x)*cos(x)",
        "sin(x)*cos(y) - tan(z/3)",
        "atan2(y, x)",
        "atan2(x*y, z - 3)",
        "sqrt(x^2 + y^2 + z^2)",
        "exp(-x*y)/(1 + z^2)",
        "ln(x^2 + 1)*tan(y/3)",
        "x^2.5 * y^-3 + (x + y)^(1/3)",
        "(x - y - 5)^-2",
        "a*x^2 + b*y*z - a/b",
        "0.5*((x + a*sin(b))^2 + (z + a*cos(b))^2 - y^2)",
        "sin(x^2)",
        "exp(sin(x*y)) * ln(3 + cos(z))",
        "-x^2 + -(y - z)^3",
    ];
    let mut arena = Arena::new();
    for source in sources {
        let e = build(&mut arena, source);
        assert_derivative_matches(&mut arena, source, e);
    }
}

#[test]
fn power_rule() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "x^3");
    let expected = build(&mut arena, "3*x^2");
    assert_eq!(diff(&mut arena, e, X), expected);
    let e = build(&mut arena, "x^-1");
    let expected = build(&mut arena, "-1/x^2");
    assert_eq!(diff(&mut arena, e, X), expected);
}

#[test]
fn product_rule() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "sin(x)*cos(x)");
    let expected = build(&mut arena, "cos(x)^2 - sin(x)^2");
    assert_eq!(diff(&mut arena, e, X), expected);
}

#[test]
fn chain_rule() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "sin(x^2)");
    let expected = build(&mut arena, "2*x*cos(x^2)");
    assert_eq!(diff(&mut arena, e, X), expected);
    let e = build(&mut arena, "sqrt(1 + y^2)");
    let expected = build(&mut arena, "y/sqrt(1 + y^2)");
    assert_eq!(diff(&mut arena, e, Y), expected);
}

#[test]
fn atan2_rule() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "atan2(y, x)");
    let dx = build(&mut arena, "-y/(x^2 + y^2)");
    let dy = build(&mut arena, "x/(x^2 + y^2)");
    assert_eq!(diff(&mut arena, e, X), dx);
    assert_eq!(diff(&mut arena, e, Y), dy);
    let dz = diff(&mut arena, e, Z);
    assert!(arena.is_zero(dz));
}

#[test]
fn derivative_of_a_constant_or_other_symbol_is_zero() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "a*sin(b) + y^2");
    let dx = diff(&mut arena, e, X);
    assert!(arena.is_zero(dx));
}

#[test]
fn third_derivatives_of_a_quadratic_form_are_literal_zero() {
    let mut arena = Arena::new();
    let t = build(
        &mut arena,
        "0.5*a/b^2*vx^2 + a*vx*vy + 0.5*(vy^2 + vz^2)*b + 0.25*(vx - vz)^2",
    );
    let vels = [Sym::Vel(0), Sym::Vel(1), Sym::Vel(2)];
    let mut d = Differentiator::new(&mut arena);
    for &i in &vels {
        for &j in &vels {
            let di = d.diff(t, i);
            let dij = d.diff(di, j);
            for &k in &vels {
                let dijk = d.diff(dij, k);
                assert_eq!(d.arena().node(dijk), &Node::Const(F64::new(0.0)));
            }
        }
    }
    // and the second derivatives are the (constant) coefficients
    let d0 = d.diff(t, vels[0]);
    let mixed = d.diff(d0, vels[1]);
    let a = d.arena().sym(A);
    assert_eq!(mixed, a);
    let xx = d.diff(d0, vels[0]);
    let expected = build(d.arena(), "a/b^2 + 0.5");
    assert_eq!(xx, expected);
}

#[test]
fn identical_subexpressions_are_one_node() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "sin(x)*cos(x) + sin(x)");
    let sin_x = build(&mut arena, "sin(x)");
    let Node::Add(terms) = arena.node(e).clone() else {
        panic!("a sum")
    };
    assert!(terms.contains(&sin_x));
    let Some(&product) = terms.iter().find(|&&t| t != sin_x) else {
        panic!("two terms")
    };
    let Node::Mul(factors) = arena.node(product) else {
        panic!("a product")
    };
    assert!(factors.contains(&sin_x));

    // commutativity: canonical order
    assert_eq!(build(&mut arena, "x*y"), build(&mut arena, "y*x"));
    assert_eq!(build(&mut arena, "x + y + z"), build(&mut arena, "z + (y + x)"));
    // the graph holds x, sin x, cos x, their product and the sum: sin x once
    assert_eq!(arena.reachable([e]).len(), 5);
    // building it again adds no node
    let nodes = arena.len();
    assert_eq!(build(&mut arena, "sin(x)*cos(x) + sin(x)"), e);
    assert_eq!(arena.len(), nodes);
}

fn assert_simplifies(source: &str, expected: &str) {
    let mut arena = Arena::new();
    let e = build(&mut arena, source);
    let expected_id = build(&mut arena, expected);
    assert_eq!(
        e,
        expected_id,
        "{source} should simplify to {expected}: {:?} vs {:?}",
        arena.node(e),
        arena.node(expected_id)
    );
}

#[test]
fn simplification_rules() {
    // 0/1 identities
    assert_simplifies("0*x", "0");
    assert_simplifies("x*0 + y", "y");
    assert_simplifies("x + 0", "x");
    assert_simplifies("1*x", "x");
    assert_simplifies("x^1", "x");
    assert_simplifies("x^0", "1");
    assert_simplifies("x/1", "x");
    // cancellation and collection
    assert_simplifies("x - x", "0");
    assert_simplifies("x*y - y*x", "0");
    assert_simplifies("2*x + 3*x", "5*x");
    assert_simplifies("x*x", "x^2");
    assert_simplifies("x/x", "1");
    assert_simplifies("x^2/x", "x");
    assert_simplifies("a - (a - b)", "b");
    assert_simplifies("-(x - y)", "y - x");
    assert_simplifies("-(-x)", "x");
    // powers
    assert_simplifies("(2*x)^2", "4*x^2");
    assert_simplifies("(x^2)^3", "x^6");
    assert_simplifies("x^2.0", "x^2");
    assert_simplifies("x^0.5", "sqrt(x)");
    // functions
    assert_simplifies("sin(-x)", "-sin(x)");
    assert_simplifies("cos(-2*x)", "cos(2*x)");
    assert_simplifies("ln(exp(x))", "x");
}

#[test]
fn constant_folding() {
    let mut arena = Arena::new();
    let fold = |arena: &mut Arena, s: &str| {
        let e = build(arena, s);
        arena
            .as_const(e)
            .unwrap_or_else(|| panic!("{s} is not folded: {:?}", arena.node(e)))
    };
    assert_eq!(fold(&mut arena, "2*3 + 4"), 10.0);
    assert_eq!(fold(&mut arena, "2^10"), 1024.0);
    assert_eq!(fold(&mut arena, "sqrt(16)"), 4.0);
    assert_eq!(fold(&mut arena, "PI/2"), std::f64::consts::FRAC_PI_2);
    assert_eq!(fold(&mut arena, "sin(0) + cos(0)"), 1.0);
    assert_eq!(fold(&mut arena, "atan2(1, 1)"), std::f64::consts::FRAC_PI_4);
    assert_eq!(fold(&mut arena, "4^1.5"), 8.0);
    // non-finite results are not folded
    let e = build(&mut arena, "ln(0)");
    assert!(arena.as_const(e).is_none());
}

#[test]
fn simplify_canonicalizes_raw_nodes() {
    let mut arena = Arena::new();
    let x = arena.sym(X);
    let zero = arena.zero();
    let one = arena.one();
    let two = arena.constant(2.0);
    let minus_one = arena.constant(-1.0);

    let raw = arena.intern(Node::Mul(vec![zero, x]));
    assert_eq!(arena.simplify(raw), zero);
    let raw = arena.intern(Node::Add(vec![x, zero]));
    assert_eq!(arena.simplify(raw), x);
    let raw = arena.intern(Node::Mul(vec![one, x]));
    assert_eq!(arena.simplify(raw), x);
    let minus_x = arena.intern(Node::Mul(vec![minus_one, x]));
    let raw = arena.intern(Node::Add(vec![x, minus_x]));
    assert_eq!(arena.simplify(raw), zero);
    let raw = arena.intern(Node::Powi(two, 3));
    let folded = arena.simplify(raw);
    assert_eq!(arena.as_const(folded), Some(8.0));
    let sin_zero = arena.intern(Node::Func(Func::Sin, zero));
    let raw = arena.intern(Node::Add(vec![sin_zero, x]));
    assert_eq!(arena.simplify(raw), x);
}

#[test]
fn substitution() {
    let mut arena = Arena::new();
    let e = build(&mut arena, "a*vx^2 + x*vy + sin(z)");
    let zero = arena.zero();
    let at_rest = arena.substitute(e, &mut |s| matches!(s, Sym::Vel(_)).then_some(zero));
    assert_eq!(at_rest, build(&mut arena, "sin(z)"));
}

/// The expression as written, interned node for node with no simplification
/// at all (`a - b` as `a + (-1) b`, `a / b` as `a b^-1`, `-a` as `(-1) a`):
/// the reference the simplifier is checked against.
fn build_raw(arena: &mut Arena, source: &str) -> Id {
    fn lower(arena: &mut Arena, e: &Expr) -> Id {
        let minus_one = |arena: &mut Arena| arena.intern(Node::Const(F64::new(-1.0)));
        match e {
            Expr::Num { value, .. } => arena.intern(Node::Const(F64::new(*value))),
            Expr::Name(ident) => {
                let sym = match ident.to_string().as_str() {
                    "x" => X,
                    "y" => Y,
                    "z" => Z,
                    "a" => A,
                    "b" => B,
                    other => panic!("unknown test symbol {other}"),
                };
                arena.intern(Node::Sym(sym))
            }
            Expr::Neg { operand, .. } => {
                let o = lower(arena, operand);
                let m = minus_one(arena);
                arena.intern(Node::Mul(vec![m, o]))
            }
            Expr::Binary { op, lhs, rhs } => {
                let l = lower(arena, lhs);
                let r = lower(arena, rhs);
                match op {
                    BinOp::Add => arena.intern(Node::Add(vec![l, r])),
                    BinOp::Sub => {
                        let m = minus_one(arena);
                        let neg = arena.intern(Node::Mul(vec![m, r]));
                        arena.intern(Node::Add(vec![l, neg]))
                    }
                    BinOp::Mul => arena.intern(Node::Mul(vec![l, r])),
                    BinOp::Div => {
                        let inv = arena.intern(Node::Powi(r, -1));
                        arena.intern(Node::Mul(vec![l, inv]))
                    }
                    BinOp::Pow => {
                        let value = constant(rhs).expect("constant exponent");
                        if value.fract() == 0.0 {
                            arena.intern(Node::Powi(l, value as i32))
                        } else {
                            arena.intern(Node::Powf(l, F64::new(value)))
                        }
                    }
                }
            }
            Expr::Call { func, args, .. } => {
                let args: Vec<Id> = args.iter().map(|a| lower(arena, a)).collect();
                match func {
                    Function::Unary(f) => arena.intern(Node::Func(*f, args[0])),
                    Function::Atan2 => arena.intern(Node::Atan2(args[0], args[1])),
                }
            }
            Expr::Paren { inner, .. } => lower(arena, inner),
            Expr::Dot { .. } => panic!("no velocities here"),
        }
    }
    fn constant(e: &Expr) -> Option<f64> {
        match e {
            Expr::Num { value, .. } => Some(*value),
            Expr::Neg { operand, .. } => constant(operand).map(|v| -v),
            Expr::Paren { inner, .. } => constant(inner),
            _ => None,
        }
    }
    let e = parse_expr.parse2(tokens(source)).expect("test expression parses");
    lower(arena, &e)
}

/// The simplifier keeps values: each expression, simplified as the macro
/// builds it, evaluates like the same expression interned without any
/// simplification, at 200 points of (x, y, z, a, b) in [0.5, 2.5] (positive,
/// so that fractional powers and logarithms are defined), to 1e-13 relative
/// (reassociated sums and products differ by round-off only).
#[test]
fn simplified_trees_evaluate_like_the_unsimplified_ones() {
    let sources = [
        "0*x",
        "x*0 + y",
        "x + 0",
        "1*x",
        "x^1",
        "x^0",
        "x/1",
        "x - x",
        "x*y - y*x",
        "2*x + 3*x",
        "x*x",
        "x/x",
        "x^2/x",
        "a - (a - b)",
        "-(x - y)",
        "-(-x)",
        "(2*x)^2",
        "(x^2)^3",
        "x^2.0",
        "x^0.5",
        "sin(-x)",
        "cos(-2*x)",
        "ln(exp(x))",
        "(x + y)^2.5 - exp(z/3)*x^-2 + y^0.3333333333333333*a",
        "a*cos(y) - b*x*sin(z) + a/(2 + x^2)",
        "ln(2 + x^2) - y*sin(z) + atan2(a, 2 + b^2)",
        "(x - y)*(x + y) - (x*x - y*y) + sqrt(a*b)/b",
        "((a*x - b*y)/(x + y))^3 * tan(z/4) - 3*(x - 2*y)/(x*y)",
    ];
    let mut rng_state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng_state ^= rng_state << 13;
        rng_state ^= rng_state >> 7;
        rng_state ^= rng_state << 17;
        0.5 + 2.0 * (rng_state >> 11) as f64 / (1u64 << 53) as f64
    };
    for source in sources {
        let mut arena = Arena::new();
        let simplified = build(&mut arena, source);
        let raw = build_raw(&mut arena, source);
        for _ in 0..200 {
            let values = [next(), next(), next(), next(), next()];
            let env = move |s: Sym| match s {
                s if s == X => values[0],
                s if s == Y => values[1],
                s if s == Z => values[2],
                s if s == A => values[3],
                s if s == B => values[4],
                other => panic!("{other:?}"),
            };
            let (got, want) = (arena.eval(simplified, &env), arena.eval(raw, &env));
            assert!(
                (got - want).abs() <= 1e-13 * want.abs().max(1.0),
                "{source} at {values:?}: simplified {got} vs as written {want}"
            );
        }
    }
}
