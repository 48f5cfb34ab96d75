//! The parser: precedence and associativity of the expression language,
//! and the sections of a declaration.

use syn::parse::Parser;

use super::{navy_minimal_source, navy_planar, tokens};
use crate::ctxt::Ctxt;
use crate::parse::{BinOp, Expr, Function, MinimalStmt, parse, parse_expr};

/// Fully parenthesized prefix form, to see the tree the parser built.
fn sexp(e: &Expr) -> String {
    match e {
        Expr::Num { text, .. } => text.clone(),
        Expr::Name(ident) => ident.to_string(),
        Expr::Dot { coord, .. } => format!("(dot {coord})"),
        Expr::Neg { operand, .. } => format!("(neg {})", sexp(operand)),
        Expr::Binary { op, lhs, rhs } => {
            let op = match op {
                BinOp::Add => "+",
                BinOp::Sub => "-",
                BinOp::Mul => "*",
                BinOp::Div => "/",
                BinOp::Pow => "^",
            };
            format!("({op} {} {})", sexp(lhs), sexp(rhs))
        }
        Expr::Call { name, args, .. } => {
            let args: Vec<String> = args.iter().map(sexp).collect();
            format!("({name} {})", args.join(" "))
        }
        Expr::Paren { inner, .. } => sexp(inner),
    }
}

fn parsed(source: &str) -> String {
    match parse_expr.parse2(tokens(source)) {
        Ok(e) => sexp(&e),
        Err(error) => panic!("`{source}` does not parse: {error}"),
    }
}

fn parse_error(source: &str) -> String {
    match parse_expr.parse2(tokens(source)) {
        Ok(e) => panic!("`{source}` parsed as {}", sexp(&e)),
        Err(error) => error.to_string(),
    }
}

#[test]
fn power_binds_tighter_than_unary_minus() {
    assert_eq!(parsed("-x^2"), "(neg (^ x 2))");
    assert_eq!(parsed("-2^2"), "(neg (^ 2 2))");
    assert_eq!(parsed("(-x)^2"), "(^ (neg x) 2)");
}

#[test]
fn unary_minus_binds_tighter_than_products() {
    assert_eq!(parsed("-x*y"), "(* (neg x) y)");
    assert_eq!(parsed("a * -b"), "(* a (neg b))");
    assert_eq!(parsed("a - -b"), "(- a (neg b))");
    assert_eq!(parsed("-a + b"), "(+ (neg a) b)");
}

#[test]
fn power_takes_signed_exponents_and_parenthesised_chains() {
    assert_eq!(parsed("x^-1"), "(^ x (neg 1))");
    assert_eq!(parsed("x^0.5"), "(^ x 0.5)");
    assert_eq!(parsed("2^(3^2)"), "(^ 2 (^ 3 2))");
    assert_eq!(parsed("(L^(1/2))^4"), "(^ (^ L (/ 1 2)) 4)");
}

/// `L^(1/2)^4` is `L^(1/16)` to a mathematician and `L^2` to a
/// spreadsheet: a chain of powers without parentheses is an error at the
/// first `^`, minus signs between them included.
#[test]
fn chained_powers_need_parentheses() {
    for chain in ["2^3^2", "L^(1/2)^4", "x^-y^2", "a*b^c^d + 1"] {
        let message = parse_error(chain);
        assert!(
            message.contains("chained `^` without parentheses"),
            "{chain}: {message}"
        );
    }
}

#[test]
fn products_and_sums_are_left_associative() {
    assert_eq!(parsed("a - b - c"), "(- (- a b) c)");
    assert_eq!(parsed("a / b * c"), "(* (/ a b) c)");
    assert_eq!(parsed("a + b * c ^ d"), "(+ a (* b (^ c d)))");
    assert_eq!(
        parsed("0.5*J1/r1^2*dot(L1)^2"),
        "(* (/ (* 0.5 J1) (^ r1 2)) (^ (dot L1) 2))"
    );
}

#[test]
fn calls_velocities_and_constants() {
    assert_eq!(parsed("atan2(y, x - 1)"), "(atan2 y (- x 1))");
    assert_eq!(parsed("sin(alpha)*cos(PI/3)"), "(* (sin alpha) (cos (/ PI 3)))");
    assert_eq!(parsed("dot(x)^2 + 1e-3"), "(+ (^ (dot x) 2) 1e-3)");
    assert_eq!(parsed("sqrt(exp(ln(tan(x))))"), "(sqrt (exp (ln (tan x))))");
}

#[test]
fn display_prints_what_the_user_wrote() {
    let e = parse_expr
        .parse2(tokens("-(a + b)^2 * c / (d - e) - PI / 3.0"))
        .unwrap();
    assert_eq!(e.to_string(), "-(a + b)^2 * c / (d - e) - PI / 3.0");
    let e = parse_expr.parse2(tokens("atan2(1, 2)^-1")).unwrap();
    assert_eq!(e.to_string(), "atan2(1, 2)^(-1)");
}

#[test]
fn unsupported_syntax_is_an_error_not_a_panic() {
    assert_eq!(
        parse_error("x % 2"),
        "unsupported operator `%`; supported: + - * / ^ (power) and parentheses"
    );
    assert_eq!(
        parse_error("x.sin()"),
        "unsupported operator `.`: write functions as `sin(x)` and powers as `x^2`, not `x.sin()` or `x.powi(2)`"
    );
    assert_eq!(parse_error("x ** 2"), "unexpected `*`: write powers as `x^n`");
    assert_eq!(
        parse_error("cosh(x)"),
        "unsupported function `cosh` (write `0.5*(exp(x) + exp(-x))`); supported: sin, cos, tan, sqrt, exp, ln, \
         atan2(y, x), and dot(coordinate) for a velocity"
    );
    assert_eq!(
        parse_error("abs(x)"),
        "unsupported function `abs` (`sqrt(x^2)`; a crane's expressions are smooth where it moves, so an `abs` \
         usually means a sign to choose once, e.g. a rope length that stays positive); supported: sin, cos, tan, \
         sqrt, exp, ln, atan2(y, x), and dot(coordinate) for a velocity"
    );
    assert!(parse_error("asin(x)").contains("(write `atan2(x, sqrt(1 - x^2))`)"));
    assert!(parse_error("tanh(x)").contains("(write `(exp(2*x) - 1)/(exp(2*x) + 1)`)"));
    assert_eq!(parse_error("atan2(x)"), "`atan2` takes 2 arguments (y, x), found 1");
    assert_eq!(parse_error("sin(x, y)"), "`sin` takes 1 argument, found 2");
    assert_eq!(
        parse_error("dot(x + y)"),
        "dot() takes the name of a coordinate, e.g. `dot(x)`"
    );
    assert_eq!(
        parse_error("2 x"),
        "expected an operator (+ - * / ^) or the end of the expression"
    );
    assert_eq!(
        parse_error("2.0f32 * x"),
        "numeric literals take no suffix: every number is an f64"
    );
    assert!(parse_error("").contains("expected an expression"));
    assert!(parse_error("x +").contains("expected an expression"));
}

#[test]
fn sections_of_the_planar_crane() {
    let cx = Ctxt::new();
    let decl = parse(navy_planar(), &cx).expect("header parses");
    assert!(cx.check().is_ok());
    assert_eq!(decl.name, "NavyPlanar");
    let s = &decl.sections;
    let names = |v: &[proc_macro2::Ident]| v.iter().map(ToString::to_string).collect::<Vec<_>>().join(" ");
    let params = &s.params.as_ref().unwrap().body;
    assert_eq!(
        params.iter().map(|p| p.name.to_string()).collect::<Vec<_>>().join(" "),
        "m_l J1 J2 r1 r2 alpha l g"
    );
    assert_eq!(params[5].default.to_string(), "PI / 3.0");
    assert_eq!(names(&s.robot.as_ref().unwrap().body), "L1 L2 L0 x0 z0");
    assert_eq!(names(&s.load.as_ref().unwrap().body), "x z");
    assert_eq!(names(&s.inputs.as_ref().unwrap().body), "u1 u2");
    assert_eq!(
        s.kinetic.as_ref().unwrap().body.to_string(),
        "0.5 * J1 / r1^2 * dot(L1)^2 + 0.5 * J2 / r2^2 * dot(L2)^2 + 0.5 * m_l * (dot(x)^2 + dot(z)^2)"
    );
    let forces = &s.forces.as_ref().unwrap().body;
    assert_eq!(forces.len(), 3);
    assert_eq!(forces[2].coord, "z");
    assert_eq!(forces[2].force.to_string(), "-m_l * g");
    let constraints = &s.constraints.as_ref().unwrap().body;
    assert_eq!(constraints.len(), 3);
    let rope = constraints[2].rope.as_ref().unwrap();
    assert_eq!(
        (rope.tension.to_string(), rope.length.to_string()),
        ("N2".to_owned(), "L2 - L0".to_owned())
    );
    assert!(constraints[1].rope.is_none());
    assert!(s.minimal.is_none());
}

#[test]
fn sections_in_any_order() {
    let source = r#"
        struct Pendulum {
            constraints { rope: 0.5*(x^2 + z^2 - L^2) }
            minimal [theta | L] { let s = sin(theta); x = L*s; z = -L*cos(theta); }
            inputs [u]
            forces { L: u, z: -m*g }
            kinetic = 0.5*m*(dot(x)^2 + dot(z)^2);
            load [x]
            robot [L, z]
            params { m = 1, g = 9.81 }
        }
    "#;
    let cx = Ctxt::new();
    let decl = parse(tokens(source), &cx).expect("header parses");
    assert!(cx.check().is_ok());
    let minimal = &decl.sections.minimal.as_ref().unwrap().body;
    assert_eq!((minimal.mu1.len(), minimal.mu2.len(), minimal.body.len()), (1, 1, 3));
    assert!(matches!(&minimal.body[0], crate::parse::MinimalStmt::Let { name, .. } if name == "s"));
}

#[test]
fn function_names_resolve() {
    assert_eq!(Function::from_name("atan2"), Some(Function::Atan2));
    assert_eq!(Function::from_name("log"), None);
}

/// The `minimal` block of `source` as `(mu1, mu2, statements)`, with the
/// statements printed back (`let d = ...`, `x = ...`).
fn minimal_block(source: &str) -> Result<(String, String, Vec<String>), String> {
    let cx = Ctxt::new();
    let decl = parse(tokens(source), &cx).expect("header parses");
    if let Err(error) = cx.check() {
        return Err(error.to_string());
    }
    let minimal = &decl.sections.minimal.as_ref().expect("a minimal block").body;
    let names = |v: &[proc_macro2::Ident]| v.iter().map(ToString::to_string).collect::<Vec<_>>().join(" ");
    let statements = minimal
        .body
        .iter()
        .map(|stmt| match stmt {
            MinimalStmt::Let { name, value } => format!("let {name} = {value}"),
            MinimalStmt::Assign { coord, value } => format!("{coord} = {value}"),
        })
        .collect();
    Ok((names(&minimal.mu1), names(&minimal.mu2), statements))
}

#[test]
fn the_minimal_block_of_the_planar_crane() {
    let (mu1, mu2, statements) = minimal_block(&navy_minimal_source()).unwrap();
    assert_eq!((mu1.as_str(), mu2.as_str()), ("beta gamma", "theta L"));
    assert_eq!(
        statements,
        [
            "let d = l * sin(gamma - beta) / sin(gamma)",
            "L1 = l * sin(beta) / sin(gamma)",
            "L2 = d + L",
            "L0 = d",
            "x0 = -d * sin(alpha - beta)",
            "z0 = -d * cos(alpha - beta)",
            "x = x0 + L * sin(theta)",
            "z = z0 - L * cos(theta)",
        ]
    );
}

#[test]
fn minimal_splits() {
    let block = |split: &str| {
        minimal_block(&format!("struct A {{ minimal [{split}] {{ x = a; }} }}"))
            .map(|(mu1, mu2, _)| format!("{mu1} | {mu2}"))
    };
    assert_eq!(block("a, b | c").unwrap(), "a b | c");
    assert_eq!(block("a, b, | c,").unwrap(), "a b | c");
    assert_eq!(block("| c").unwrap(), " | c");
    assert_eq!(block("a |").unwrap(), "a | ");
    assert!(
        block("a, b")
            .unwrap_err()
            .starts_with("missing `|` between mu1 and mu2")
    );
    assert!(block("a | b | c").unwrap_err().starts_with("only one `|` is allowed"));
    assert_eq!(block("a b | c").unwrap_err(), "expected `,`");
    assert_eq!(block("a, 1 | c").unwrap_err(), "expected identifier");
}

#[test]
fn minimal_statements() {
    let statements = |body: &str| {
        minimal_block(&format!("struct A {{ minimal [a | b] {{ {body} }} }}"))
            .map(|(_, _, statements)| statements.join("; "))
    };
    assert_eq!(statements("let c = a^2; x = c + b;; ").unwrap_err(), "unexpected `;`");
    assert_eq!(
        statements("let c = a^2; x = c + b; y = -x").unwrap(),
        "let c = a^2; x = c + b; y = -x"
    );
    assert_eq!(statements("let c a").unwrap_err(), "expected `=`");
    assert_eq!(statements("x: a").unwrap_err(), "expected `=`");
}

/// Nesting and depth the macro refuses with an error rather than overflow
/// the compiler's stack (2000 nested parentheses and a sum of 20000 terms
/// once crashed rustc with SIGSEGV inside the macro).
#[test]
fn expressions_too_deep_are_errors() {
    use crate::parse::{MAX_DEPTH, MAX_NESTING};
    let nested = |levels: usize| format!("{}x{}", "(".repeat(levels), ")".repeat(levels));
    assert_eq!(parsed(&nested(MAX_NESTING - 1)), "x");
    assert!(parse_error(&nested(MAX_NESTING + 1)).starts_with("expression nested more than 256 levels deep"));
    assert!(parse_error(&format!("{}x", "-".repeat(MAX_NESTING + 1))).starts_with("expression nested more than"));
    let sum = |terms: usize| vec!["x"; terms].join(" + ");
    assert!(parse_expr.parse2(tokens(&sum(MAX_DEPTH))).is_ok());
    assert!(parse_error(&sum(MAX_DEPTH + 2)).starts_with("expression more than 4096 operations deep"));
}
