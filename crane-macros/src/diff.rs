//! Symbolic differentiation, IR → IR.
//!
//! One function per rule, the rule in its doc comment. Results are built
//! with the simplifying constructors of `simplify.rs` and memoized per
//! `(node, variable)`, so shared subexpressions are differentiated once and
//! the derivative graph shares structure with the original.

use std::collections::HashMap;

use crate::expr::{Arena, Func, Id, Node, Sym};

/// A differentiator over one arena, remembering every derivative it took.
pub struct Differentiator<'a> {
    arena: &'a mut Arena,
    memo: HashMap<(Id, Sym), Id>,
}

impl<'a> Differentiator<'a> {
    /// A differentiator with an empty memo.
    pub fn new(arena: &'a mut Arena) -> Self {
        Self {
            arena,
            memo: HashMap::new(),
        }
    }

    /// The arena the derivatives are built in.
    pub fn arena(&mut self) -> &mut Arena {
        self.arena
    }

    /// `d e / d var`.
    pub fn diff(&mut self, e: Id, var: Sym) -> Id {
        if let Some(&d) = self.memo.get(&(e, var)) {
            return d;
        }
        let d = match self.arena.node(e).clone() {
            Node::Const(_) => self.constant(),
            Node::Sym(s) => self.symbol(s, var),
            Node::Add(terms) => self.sum(&terms, var),
            Node::Mul(factors) => self.product(&factors, var),
            Node::Powi(u, n) => self.integer_power(u, n, var),
            Node::Powf(u, r) => self.real_power(u, r.get(), var),
            Node::Func(Func::Sin, u) => self.sin(u, var),
            Node::Func(Func::Cos, u) => self.cos(u, var),
            Node::Func(Func::Tan, u) => self.tan(u, var),
            Node::Func(Func::Sqrt, u) => self.sqrt(e, u, var),
            Node::Func(Func::Exp, u) => self.exp(e, u, var),
            Node::Func(Func::Ln, u) => self.ln(u, var),
            Node::Atan2(y, x) => self.atan2(y, x, var),
        };
        self.memo.insert((e, var), d);
        d
    }

    /// Constant rule: `c' = 0`.
    fn constant(&mut self) -> Id {
        self.arena.zero()
    }

    /// Variable rule: `x' = 1` for the variable itself, `0` for any other symbol.
    fn symbol(&mut self, s: Sym, var: Sym) -> Id {
        if s == var { self.arena.one() } else { self.arena.zero() }
    }

    /// Sum rule: `(a + b + ...)' = a' + b' + ...`.
    fn sum(&mut self, terms: &[Id], var: Sym) -> Id {
        let derivatives = terms.iter().map(|&t| self.diff(t, var)).collect();
        self.arena.add(derivatives)
    }

    /// Product rule: `(f g h)' = f' g h + f g' h + f g h'`.
    fn product(&mut self, factors: &[Id], var: Sym) -> Id {
        let mut terms = Vec::new();
        for (i, &f) in factors.iter().enumerate() {
            let df = self.diff(f, var);
            if self.arena.is_zero(df) {
                continue;
            }
            let mut term: Vec<Id> = factors.to_vec();
            term[i] = df;
            terms.push(self.arena.mul(term));
        }
        self.arena.add(terms)
    }

    /// Power rule (integer exponent): `(u^n)' = n u^(n-1) u'`.
    fn integer_power(&mut self, u: Id, n: i32, var: Sym) -> Id {
        let du = self.diff(u, var);
        if self.arena.is_zero(du) {
            return du;
        }
        let n_minus_1 = self.arena.powi(u, n - 1);
        let n = self.arena.constant(f64::from(n));
        self.arena.mul(vec![n, n_minus_1, du])
    }

    /// Power rule (real exponent): `(u^r)' = r u^(r-1) u'`.
    fn real_power(&mut self, u: Id, r: f64, var: Sym) -> Id {
        let du = self.diff(u, var);
        if self.arena.is_zero(du) {
            return du;
        }
        let r_minus_1 = self.arena.powf(u, r - 1.0);
        let r = self.arena.constant(r);
        self.arena.mul(vec![r, r_minus_1, du])
    }

    /// Chain rule for sine: `sin(u)' = cos(u) u'`.
    fn sin(&mut self, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        let cos = self.arena.func(Func::Cos, u);
        self.arena.mul2(cos, du)
    }

    /// Chain rule for cosine: `cos(u)' = -sin(u) u'`.
    fn cos(&mut self, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        let sin = self.arena.func(Func::Sin, u);
        let minus_sin = self.arena.neg(sin);
        self.arena.mul2(minus_sin, du)
    }

    /// Chain rule for tangent: `tan(u)' = u' / cos(u)^2`.
    fn tan(&mut self, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        let cos = self.arena.func(Func::Cos, u);
        let cos2 = self.arena.powi(cos, 2);
        self.arena.div(du, cos2)
    }

    /// Chain rule for the square root: `sqrt(u)' = u' / (2 sqrt(u))`.
    fn sqrt(&mut self, sqrt_u: Id, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        let two_sqrt = self.arena.scale(2.0, sqrt_u);
        self.arena.div(du, two_sqrt)
    }

    /// Chain rule for the exponential: `exp(u)' = exp(u) u'`.
    fn exp(&mut self, exp_u: Id, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        self.arena.mul2(exp_u, du)
    }

    /// Chain rule for the natural logarithm: `ln(u)' = u' / u`.
    fn ln(&mut self, u: Id, var: Sym) -> Id {
        let du = self.diff(u, var);
        self.arena.div(du, u)
    }

    /// Two-argument arctangent: `atan2(y, x)' = (x y' - y x') / (x^2 + y^2)`.
    fn atan2(&mut self, y: Id, x: Id, var: Sym) -> Id {
        let dy = self.diff(y, var);
        let dx = self.diff(x, var);
        let x_dy = self.arena.mul2(x, dy);
        let y_dx = self.arena.mul2(y, dx);
        let numerator = self.arena.sub(x_dy, y_dx);
        if self.arena.is_zero(numerator) {
            return numerator;
        }
        let x2 = self.arena.powi(x, 2);
        let y2 = self.arena.powi(y, 2);
        let denominator = self.arena.add2(x2, y2);
        self.arena.div(numerator, denominator)
    }
}

/// `d e / d var` with a fresh memo (convenience for one-off derivatives).
#[cfg(test)]
pub fn diff(arena: &mut Arena, e: Id, var: Sym) -> Id {
    Differentiator::new(arena).diff(e, var)
}
