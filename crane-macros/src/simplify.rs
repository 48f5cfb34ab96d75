//! Simplifying constructors and IR → IR rewrites.
//!
//! Every expression the macro builds goes through the constructors below,
//! which keep the arena in a canonical form:
//! - constants are folded (`2 * 3 → 6`, `sin(0) → 0`) as long as the result
//!   is finite;
//! - sums are flat and sorted, like terms are collected (`x + 2 x → 3 x`,
//!   `x - x → 0`) and zero terms dropped (`x + 0 → x`);
//! - products are flat and sorted with the numeric coefficient first, powers
//!   of the same base are merged (`x * x → x^2`, `x / x → 1`), a zero factor
//!   makes the product zero (`0 * x → 0`) and a unit coefficient disappears
//!   (`1 * x → x`);
//! - `-a` is `(-1) * a` (distributed over sums: `-(a - b) → b - a`),
//!   `a / b` is `a * b^-1`;
//! - integer powers distribute over products (`(2 x)^2 → 4 x^2`) and nest
//!   (`(x^2)^3 → x^6`), `x^0 → 1`, `x^1 → x`, `x^0.5 → sqrt(x)`;
//! - `sin(-x) → -sin(x)`, `tan(-x) → -tan(x)`, `cos(-x) → cos(x)`,
//!   `ln(exp(x)) → x`.
//!
//! Because of this, derivatives that vanish identically (say the third
//! derivative of a quadratic form) come out as the literal constant 0.
//! The rules assume that the expressions are defined where they are
//! evaluated (`x / x → 1` ignores `x = 0`), as every computer algebra
//! system does.

use std::collections::HashMap;

use crate::expr::{Arena, F64, Func, Id, Node, Sym};

impl Arena {
    /// `a + b`.
    pub fn add2(&mut self, a: Id, b: Id) -> Id {
        self.add(vec![a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let minus_b = self.neg(b);
        self.add(vec![a, minus_b])
    }

    /// `a * b`.
    pub fn mul2(&mut self, a: Id, b: Id) -> Id {
        self.mul(vec![a, b])
    }

    /// `c * a` for a number `c`.
    pub fn scale(&mut self, c: f64, a: Id) -> Id {
        let c = self.constant(c);
        self.mul(vec![c, a])
    }

    /// `-a = (-1) a`.
    pub fn neg(&mut self, a: Id) -> Id {
        self.scale(-1.0, a)
    }

    /// `a / b = a b^-1`.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let inv = self.powi(b, -1);
        self.mul(vec![a, inv])
    }

    /// Sum of `terms`: flattened, like terms collected, sorted.
    pub fn add(&mut self, terms: Vec<Id>) -> Id {
        let mut constant = 0.0;
        // (body, coefficient) in order of first appearance
        let mut bodies: Vec<(Id, f64)> = Vec::new();
        let mut position: HashMap<Id, usize> = HashMap::new();
        let mut stack = terms;
        stack.reverse();
        while let Some(term) = stack.pop() {
            match self.node(term).clone() {
                // flatten: (a + b) + c → a + b + c
                Node::Add(inner) => stack.extend(inner.into_iter().rev()),
                // fold constants: 1 + 2 → 3
                Node::Const(c) => constant += c.get(),
                _ => {
                    // collect like terms: 2 x + 3 x → 5 x
                    let (c, body) = self.split_coefficient(term);
                    match position.get(&body) {
                        Some(&i) => bodies[i].1 += c,
                        None => {
                            position.insert(body, bodies.len());
                            bodies.push((body, c));
                        }
                    }
                }
            }
        }
        let mut out = Vec::with_capacity(bodies.len() + 1);
        for (body, c) in bodies {
            // drop zero terms: x - x → 0 x → nothing
            if c != 0.0 {
                out.push(self.with_coefficient(c, body));
            }
        }
        if constant != 0.0 {
            out.push(self.constant(constant));
        }
        out.sort();
        match out.len() {
            0 => self.zero(),
            1 => out[0],
            _ => self.intern(Node::Add(out)),
        }
    }

    /// Splits a canonical term into its numeric coefficient and the rest:
    /// `3 x y → (3, x y)`, `x → (1, x)`.
    fn split_coefficient(&mut self, term: Id) -> (f64, Id) {
        if let Node::Mul(factors) = self.node(term)
            && let Node::Const(c) = self.node(factors[0])
        {
            let c = c.get();
            let rest = factors[1..].to_vec();
            let body = if rest.len() == 1 {
                rest[0]
            } else {
                self.intern(Node::Mul(rest))
            };
            return (c, body);
        }
        (1.0, term)
    }

    /// Inverse of [`Self::split_coefficient`] for a canonical body without
    /// coefficient.
    fn with_coefficient(&mut self, c: f64, body: Id) -> Id {
        if c == 1.0 {
            return body;
        }
        let c = self.constant(c);
        let mut factors = vec![c];
        match self.node(body) {
            Node::Mul(fs) => factors.extend(fs.iter().copied()),
            _ => factors.push(body),
        }
        self.intern(Node::Mul(factors))
    }

    /// Product of `factors`: flattened, constants folded into one leading
    /// coefficient, powers of equal bases merged, sorted.
    pub fn mul(&mut self, factors: Vec<Id>) -> Id {
        let mut coefficient = 1.0;
        // (base, exponent) in order of first appearance
        let mut powers: Vec<(Id, i32)> = Vec::new();
        let mut position: HashMap<Id, usize> = HashMap::new();
        let mut unmerged: Vec<Id> = Vec::new();
        let mut stack = factors;
        stack.reverse();
        while let Some(factor) = stack.pop() {
            let (base, exponent) = match self.node(factor).clone() {
                // flatten: (a b) c → a b c
                Node::Mul(inner) => {
                    stack.extend(inner.into_iter().rev());
                    continue;
                }
                // fold constants: 2 * 3 → 6
                Node::Const(c) => {
                    coefficient *= c.get();
                    continue;
                }
                Node::Powi(base, n) => (base, n),
                _ => (factor, 1),
            };
            // merge powers: x^a x^b → x^(a + b)
            match position.get(&base) {
                Some(&i) => match powers[i].1.checked_add(exponent) {
                    Some(sum) => powers[i].1 = sum,
                    None => unmerged.push(factor),
                },
                None => {
                    position.insert(base, powers.len());
                    powers.push((base, exponent));
                }
            }
        }
        // zero factor: 0 x → 0
        if coefficient == 0.0 {
            return self.zero();
        }
        let mut out = unmerged;
        for (base, exponent) in powers {
            match exponent {
                // x^0 → 1
                0 => {}
                // x^1 → x
                1 => out.push(base),
                // canonical bases are never products or constants, so no
                // further rule applies
                n => out.push(self.intern(Node::Powi(base, n))),
            }
        }
        out.sort();
        if out.is_empty() {
            return self.constant(coefficient);
        }
        if coefficient == 1.0 && out.len() == 1 {
            return out[0];
        }
        // negated sum: -(a - b) → b - a
        if coefficient == -1.0
            && out.len() == 1
            && let Node::Add(terms) = self.node(out[0]).clone()
        {
            let negated = terms.into_iter().map(|t| self.neg(t)).collect();
            return self.add(negated);
        }
        if coefficient != 1.0 {
            let c = self.constant(coefficient);
            out.insert(0, c);
        }
        self.intern(Node::Mul(out))
    }

    /// `a^n` for an integer `n`.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        match n {
            // x^0 → 1
            0 => return self.one(),
            // x^1 → x
            1 => return a,
            _ => {}
        }
        match self.node(a).clone() {
            // fold constants: 2^3 → 8
            Node::Const(c) => {
                let value = c.get().powi(n);
                if value.is_finite() {
                    return self.constant(value);
                }
            }
            // nested powers: (x^m)^n → x^(m n)
            Node::Powi(base, m) => {
                if let Some(mn) = m.checked_mul(n) {
                    return self.powi(base, mn);
                }
            }
            // distribute over products: (x y)^n → x^n y^n
            Node::Mul(factors) => {
                let powered = factors.into_iter().map(|f| self.powi(f, n)).collect();
                return self.mul(powered);
            }
            _ => {}
        }
        self.intern(Node::Powi(a, n))
    }

    /// `a^r` for a real `r`.
    pub fn powf(&mut self, a: Id, r: f64) -> Id {
        // integer exponent: x^2.0 → x^2
        if r.fract() == 0.0 && r.abs() <= f64::from(i32::MAX) {
            return self.powi(a, r as i32);
        }
        // x^0.5 → sqrt(x)
        if r == 0.5 {
            return self.func(Func::Sqrt, a);
        }
        // fold constants: 4^1.5 → 8
        if let Some(c) = self.as_const(a) {
            let value = c.powf(r);
            if value.is_finite() {
                return self.constant(value);
            }
        }
        self.intern(Node::Powf(a, F64::new(r)))
    }

    /// `f(a)` for an elementary function `f`.
    pub fn func(&mut self, f: Func, a: Id) -> Id {
        // fold constants: sin(0) → 0
        if let Some(c) = self.as_const(a) {
            let value = f.apply(c);
            if value.is_finite() {
                return self.constant(value);
            }
        }
        // symmetry: sin(-x) → -sin(x), tan(-x) → -tan(x), cos(-x) → cos(x)
        if matches!(f, Func::Sin | Func::Tan | Func::Cos) {
            let (c, body) = self.split_coefficient(a);
            if c < 0.0 {
                let positive = self.with_coefficient(-c, body);
                let value = self.intern(Node::Func(f, positive));
                return if f == Func::Cos { value } else { self.neg(value) };
            }
        }
        // inverse functions: ln(exp(x)) → x
        if f == Func::Ln
            && let Node::Func(Func::Exp, inner) = *self.node(a)
        {
            return inner;
        }
        self.intern(Node::Func(f, a))
    }

    /// `atan2(y, x)`.
    pub fn atan2(&mut self, y: Id, x: Id) -> Id {
        // fold constants: atan2(1, 1) → pi/4
        if let (Some(cy), Some(cx)) = (self.as_const(y), self.as_const(x)) {
            return self.constant(cy.atan2(cx));
        }
        self.intern(Node::Atan2(y, x))
    }

    /// Rebuilds `id` bottom-up through the simplifying constructors: the
    /// canonical form of an expression interned raw with [`Arena::intern`].
    #[cfg(test)]
    pub fn simplify(&mut self, id: Id) -> Id {
        self.rebuild(id, &mut |_| None, &mut HashMap::new())
    }

    /// `id` with every symbol `s` for which `replace(s)` is `Some(e)`
    /// replaced by `e`, simplified.
    pub fn substitute(&mut self, id: Id, replace: &mut dyn FnMut(Sym) -> Option<Id>) -> Id {
        self.rebuild(id, replace, &mut HashMap::new())
    }

    fn rebuild(&mut self, id: Id, replace: &mut dyn FnMut(Sym) -> Option<Id>, memo: &mut HashMap<Id, Id>) -> Id {
        if let Some(&done) = memo.get(&id) {
            return done;
        }
        let out = match self.node(id).clone() {
            Node::Const(_) => id,
            Node::Sym(s) => replace(s).unwrap_or(id),
            Node::Add(terms) => {
                let terms = terms.into_iter().map(|t| self.rebuild(t, replace, memo)).collect();
                self.add(terms)
            }
            Node::Mul(factors) => {
                let factors = factors.into_iter().map(|f| self.rebuild(f, replace, memo)).collect();
                self.mul(factors)
            }
            Node::Powi(a, n) => {
                let a = self.rebuild(a, replace, memo);
                self.powi(a, n)
            }
            Node::Powf(a, r) => {
                let a = self.rebuild(a, replace, memo);
                self.powf(a, r.get())
            }
            Node::Func(f, a) => {
                let a = self.rebuild(a, replace, memo);
                self.func(f, a)
            }
            Node::Atan2(y, x) => {
                let y = self.rebuild(y, replace, memo);
                let x = self.rebuild(x, replace, memo);
                self.atan2(y, x)
            }
        };
        memo.insert(id, out);
        out
    }
}
