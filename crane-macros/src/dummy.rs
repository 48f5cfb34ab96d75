//! Structural index reduction of the servo problem by dummy derivatives
//! (Mattsson and Soderlind 1993), driven by Pryce's offsets of
//! `structure.rs`.
//!
//! Equation `i` of eqs. (22a-d) (the dynamics `M q'' - f(q, q') - B^T(q) u +
//! G^T(q) lambda = 0`, the constraints `g(q) = 0`, the servo constraints
//! `x = gamma(t)`) is differentiated `d_i` times in time, and every
//! derivative `y^(k)`, `k <= c_j`, of an unknown `y_j` of `[q, lambda, u]`
//! becomes an algebraic unknown of its own: a jet variable
//! [`Sym::Jet`]. For a flat crane (`sum c = sum d`, no internal dynamics)
//! every derivative is a dummy derivative: the enlarged system is square and
//! purely algebraic at each time, its unknowns the jets of `p`, `lambda` and
//! `u`, the load's jets `x^(k) = gamma^(k)(t)` given. Its Jacobian is block
//! triangular with the square blocks of Pryce's system Jacobian on the
//! diagonal (one per derivative level), so it is regular exactly where
//! Pryce's `J` is, and no derivative is approximated by a difference: the
//! inputs come out exact to round-off at any time step. A crane with
//! internal dynamics of dimension `d` gets the same system with `d` more
//! unknowns than equations: the jets the load path leaves free, which the
//! runtime selects as states and integrates (state selection).

use std::collections::HashMap;

use crate::diff::Differentiator;
use crate::expr::{Arena, Id, Sym};
use crate::model::{Kernels, Matrix, Model};
use crate::structure::Structure;

/// The highest derivative of the load path the runtime carries
/// (`crane_runtime::dummy_derivative::MAX_PATH_ORDER`): no system is
/// generated for a crane whose inputs need more.
pub const MAX_PATH_ORDER: u8 = 10;

/// The dummy-derivative system of a flat crane, as IR.
pub struct DummyKernels {
    /// Pryce's offset `c_j` of each unknown of `[q, lambda, u]`.
    pub offsets: Vec<u8>,
    /// The unknowns `z` in order, as `(unknown of [q, lambda, u], derivative
    /// order)`: for each robot coordinate, multiplier and input its jets
    /// `0..=c_j`.
    pub unknowns: Vec<(usize, u8)>,
    /// The equations in order, as `(equation of [dynamics, constraints],
    /// derivative order)`: each equation and its derivatives `1..=d_i`.
    pub equations: Vec<(usize, u8)>,
    /// The highest derivative of the load path the system reads.
    pub path_order: u8,
    /// How many more unknowns than equations: the structural dimension of
    /// the internal dynamics (0 for a flat crane).
    pub dimension: usize,
    /// The residual, one entry per equation.
    pub residual: Vec<Id>,
    /// `d residual / d z`, rows = equations, columns = unknowns.
    pub jacobian: Matrix,
}

/// The time derivative of `e`, whose symbols are jets and parameters:
/// `sum_(j, k) de/dy_j^(k) y_j^(k+1)`.
fn time_derivative(d: &mut Differentiator<'_>, e: Id) -> Id {
    let symbols = d.arena().symbols(e);
    let mut terms = Vec::new();
    for s in symbols {
        if let Sym::Jet(j, k) = s {
            let partial = d.diff(e, s);
            let next = d.arena().sym(Sym::Jet(j, k + 1));
            terms.push(d.arena().mul2(partial, next));
        }
    }
    d.arena().add(terms)
}

impl DummyKernels {
    /// The system of a crane with a regular structure (`dimension` more
    /// unknowns than equations where it has internal dynamics); `None` for
    /// a singular structure.
    pub fn derive(model: &mut Model, k: &Kernels, structure: &Structure) -> Option<DummyKernels> {
        let &Structure::Internal {
            dimension,
            unknowns: ref c,
            equations: ref d,
        } = structure
        else {
            return None;
        };
        if !model.dummy_derivatives {
            return None;
        }
        let (n, m, a, nr) = (model.n(), model.m(), model.a(), model.n_robot);
        // the runtime refuses a system that reads more of the path than it
        // carries: not generated (its cost grows steeply with the order)
        if c[nr..n].iter().any(|&order| order > MAX_PATH_ORDER) {
            return None;
        }
        let jet = |j: usize, order: u8| Sym::Jet(j as u16, order);
        let arena = &mut model.arena;

        // eqs. (1a, 1b) in jets: Coord -> y^(0), Vel -> y^(1), Input, Lambda
        // -> their jets of order 0
        let mut leaves = HashMap::new();
        for i in 0..n {
            leaves.insert(Sym::Coord(i as u16), arena.sym(jet(i, 0)));
            leaves.insert(Sym::Vel(i as u16), arena.sym(jet(i, 1)));
        }
        for l in 0..m {
            leaves.insert(Sym::Lambda(l as u16), arena.sym(jet(n + l, 0)));
        }
        for r in 0..a {
            leaves.insert(Sym::Input(r as u16), arena.sym(jet(n + m + r, 0)));
        }
        let lower = |arena: &mut Arena, e: Id| arena.substitute(e, &mut |s| leaves.get(&s).copied());
        let mut base = Vec::with_capacity(n + m);
        for i in 0..n {
            let mut terms = Vec::new();
            for j in 0..n {
                if !arena.is_zero(k.mass[i][j]) {
                    let acceleration = arena.sym(jet(j, 2));
                    terms.push(arena.mul2(k.mass[i][j], acceleration));
                }
            }
            let force = lower(arena, model.forces[i]);
            terms.push(arena.neg(force));
            for (l, row) in k.jacobian.iter().enumerate() {
                let g_li = lower(arena, row[i]);
                let lambda = arena.sym(jet(n + l, 0));
                terms.push(arena.mul2(g_li, lambda));
            }
            base.push(arena.add(terms));
        }
        for &g in &k.g {
            base.push(lower(arena, g));
        }

        let mut diff = Differentiator::new(arena);
        let mut equations = Vec::new();
        let mut residual = Vec::new();
        for (i, &e) in base.iter().enumerate() {
            let mut current = e;
            for order in 0..=d[i] {
                if order > 0 {
                    current = time_derivative(&mut diff, current);
                }
                equations.push((i, order));
                residual.push(current);
            }
        }
        let unknowns: Vec<(usize, u8)> = (0..n + m + a)
            .filter(|&j| j < nr || j >= n)
            .flat_map(|j| (0..=c[j]).map(move |order| (j, order)))
            .collect();
        if unknowns.len() != equations.len() + dimension {
            return None;
        }
        let jacobian = residual
            .iter()
            .map(|&e| unknowns.iter().map(|&(j, order)| diff.diff(e, jet(j, order))).collect())
            .collect();
        let path_order = c[nr..n].iter().copied().max().unwrap_or(0);
        Some(DummyKernels {
            offsets: c.clone(),
            unknowns,
            equations,
            path_order,
            dimension,
            residual,
            jacobian,
        })
    }
}
