//! The intermediate representation: a hash-consed expression arena.
//!
//! Every expression the macro works with (constraints, kinetic energy,
//! forces and all their derivatives) lives in one [`Arena`]. Nodes are
//! interned: structurally identical subexpressions are the same [`Id`], so
//! equality of expressions is equality of ids, derivatives of shared
//! subexpressions are computed once, and the code generator finds common
//! subexpressions by counting references (see `codegen/body.rs`).
//!
//! Nodes are immutable and children are always interned before their
//! parents, so ids grow along every edge: sorting ids is a topological order.
//!
//! The arena stores expressions in the canonical form built by the smart
//! constructors of `simplify.rs`: sums and products are n-ary and sorted,
//! negation is a product with the coefficient `-1` and division a product
//! with a power `-1` (the code generator prints them back as `-x` and
//! `a / b`). [`Arena::intern`] itself stores whatever it is given.

use std::collections::HashMap;

/// Handle of a node in an [`Arena`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Id(u32);

impl Id {
    /// Position of the node in the arena.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A leaf that stands for a value known only at run time.
///
/// The indices refer to the declaration order of the model (`Coord` and
/// `Vel` to the redundant coordinates `q = [p; x]`, `Lambda` to the
/// constraints, `Mu` and `MuDot` to the minimal coordinates
/// `mu = [mu1; mu2]` of a `minimal` block, paper sect. 3.2).
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Sym {
    /// A parameter of the model (a field of the generated struct).
    Param(u16),
    /// A redundant coordinate `q_i`.
    Coord(u16),
    /// A velocity `q_i'`, written `dot(q_i)` in the DSL.
    Vel(u16),
    /// An input `u_k`.
    Input(u16),
    /// A Lagrange multiplier `lambda_k` (only in the constraint Hessian).
    Lambda(u16),
    /// A minimal coordinate `mu_k` (only in the map `q = phi(mu)`, eq. 6,
    /// and its derivatives).
    Mu(u16),
    /// A minimal velocity `mu_k'` (only in `P'` and `w`, eqs. 9 and 17).
    MuDot(u16),
    /// The derivative of order `k` of unknown `j` of `[q, lambda, u]` (only
    /// in the dummy-derivative system of `dummy.rs`).
    Jet(u16, u8),
}

/// An `f64` that can be hashed: its bit pattern, with `-0.0` stored as `0.0`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct F64(u64);

impl F64 {
    /// Wraps `value` (`-0.0` becomes `0.0`).
    pub fn new(value: f64) -> Self {
        let value = if value == 0.0 { 0.0 } else { value };
        F64(value.to_bits())
    }

    /// The wrapped value.
    pub fn get(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// Elementary functions of one argument.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Sqrt,
    Exp,
    Ln,
}

impl Func {
    /// Name in the DSL and of the generated method call.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
        }
    }

    /// Value at `x`.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
        }
    }
}

/// A node of the expression graph.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// A numeric constant.
    Const(F64),
    /// A run-time value.
    Sym(Sym),
    /// `a + b + ...` (canonically: at least two terms, no nested sums, sorted).
    Add(Vec<Id>),
    /// `a * b * ...` (canonically: at least two factors, a constant
    /// coefficient first if any, the other factors sorted).
    Mul(Vec<Id>),
    /// `a^n` with an integer exponent (`a^-1` is the reciprocal).
    Powi(Id, i32),
    /// `a^r` with a real, non-integer exponent.
    Powf(Id, F64),
    /// `sin(a)`, `cos(a)`, ...
    Func(Func, Id),
    /// `atan2(y, x)`, the angle of the point `(x, y)`.
    Atan2(Id, Id),
}

impl Node {
    /// Children in order.
    pub fn children(&self) -> Vec<Id> {
        match self {
            Node::Const(_) | Node::Sym(_) => Vec::new(),
            Node::Add(ids) | Node::Mul(ids) => ids.clone(),
            Node::Powi(a, _) | Node::Powf(a, _) | Node::Func(_, a) => vec![*a],
            Node::Atan2(y, x) => vec![*y, *x],
        }
    }
}

/// The arena that owns every node; see the module docs.
#[derive(Default, Debug)]
pub struct Arena {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
}

impl Arena {
    /// An empty arena.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of nodes.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Number of nodes: every id is below it.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Every node's id, children before parents.
    pub fn ids(&self) -> impl Iterator<Item = Id> + use<> {
        (0..self.nodes.len()).map(|i| Id(i as u32))
    }

    /// The id of `node`, adding it if it is new (no simplification).
    pub fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("fewer than 2^32 nodes"));
        self.nodes.push(node.clone());
        self.index.insert(node, id);
        id
    }

    /// The node behind `id`.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// The constant `value`.
    pub fn constant(&mut self, value: f64) -> Id {
        self.intern(Node::Const(F64::new(value)))
    }

    /// The constant 0.
    pub fn zero(&mut self) -> Id {
        self.constant(0.0)
    }

    /// The constant 1.
    pub fn one(&mut self) -> Id {
        self.constant(1.0)
    }

    /// The leaf `sym`.
    pub fn sym(&mut self, sym: Sym) -> Id {
        self.intern(Node::Sym(sym))
    }

    /// The value of `id` if it is a constant.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(c) => Some(c.get()),
            _ => None,
        }
    }

    /// Whether `id` is the literal constant 0.
    pub fn is_zero(&self, id: Id) -> bool {
        self.as_const(id) == Some(0.0)
    }

    /// All nodes reachable from `roots` (roots included), in increasing id
    /// order, which is a topological order (children first).
    pub fn reachable(&self, roots: impl IntoIterator<Item = Id>) -> Vec<Id> {
        self.reachable_until(roots, |_| false)
    }

    /// [`reachable`](Self::reachable), not looking into the nodes `leaf`
    /// holds for (they are listed, their children only where reached
    /// otherwise).
    pub fn reachable_until(&self, roots: impl IntoIterator<Item = Id>, leaf: impl Fn(Id) -> bool) -> Vec<Id> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<Id> = roots.into_iter().collect();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id.index()], true) || leaf(id) {
                continue;
            }
            stack.extend(self.node(id).children());
        }
        (0..self.nodes.len())
            .filter(|&i| seen[i])
            .map(|i| Id(i as u32))
            .collect()
    }

    /// The symbols `id` depends on, sorted.
    pub fn symbols(&self, id: Id) -> Vec<Sym> {
        let mut syms: Vec<Sym> = self
            .reachable([id])
            .into_iter()
            .filter_map(|n| match self.node(n) {
                Node::Sym(s) => Some(*s),
                _ => None,
            })
            .collect();
        syms.sort();
        syms
    }

    /// The first symbol (in the order of [`Sym`]) that `id` depends on and
    /// that satisfies `pred`.
    pub fn find_symbol(&self, id: Id, pred: impl Fn(Sym) -> bool) -> Option<Sym> {
        self.symbols(id).into_iter().find(|&s| pred(s))
    }

    /// Numerical value of `id` with the symbols valued by `env` (the
    /// compile-time checks at sample points; the tests' finite differences).
    pub fn eval(&self, id: Id, env: &dyn Fn(Sym) -> f64) -> f64 {
        let order = self.reachable([id]);
        let mut values: HashMap<Id, f64> = HashMap::with_capacity(order.len());
        for n in order {
            let v = |c: &Id| values[c];
            let value = match self.node(n) {
                Node::Const(c) => c.get(),
                Node::Sym(s) => env(*s),
                Node::Add(ts) => ts.iter().map(v).sum(),
                Node::Mul(fs) => fs.iter().map(v).product(),
                Node::Powi(a, k) => v(a).powi(*k),
                Node::Powf(a, r) => v(a).powf(r.get()),
                Node::Func(f, a) => f.apply(v(a)),
                Node::Atan2(y, x) => v(y).atan2(v(x)),
            };
            values.insert(n, value);
        }
        values[&id]
    }
}
