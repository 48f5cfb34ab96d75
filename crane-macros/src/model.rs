//! The checked model and the quantities derived from it.
//!
//! [`Model`] is what `check.rs` makes of a declaration: names resolved,
//! every expression lowered into the IR arena and validated. [`Kernels`]
//! differentiates it into everything the generated code evaluates (paper
//! eqs. 1a-1b, 3, 11a-11c, and for a `minimal` block eqs. 6, 8, 9, 12, 17);
//! `codegen.rs` only prints these.

use proc_macro2::{Ident, TokenStream};
use syn::{Attribute, Visibility};

use crate::diff::Differentiator;
use crate::expr::{Arena, Id, Sym};
use crate::parse::Expr;

/// A checked crane declaration.
pub struct Model {
    /// The IR of every expression below.
    pub arena: Arena,
    /// Path of the runtime crate (`::crane_runtime` unless `#[crane(runtime = ...)]`).
    pub runtime: TokenStream,
    /// Attributes and doc comments of the struct.
    pub attrs: Vec<Attribute>,
    /// Visibility of the struct.
    pub vis: Visibility,
    /// Name of the struct.
    pub name: Ident,
    /// First line of the doc comment.
    pub description: String,
    /// Parameters, in declaration order.
    pub params: Vec<Param>,
    /// Redundant coordinates `q = [p; x]`: robot coordinates first.
    pub coords: Vec<Ident>,
    /// Number of robot coordinates `n - a`.
    pub n_robot: usize,
    /// Inputs `u`.
    pub inputs: Vec<Ident>,
    /// Holonomic constraints `g`.
    pub constraints: Vec<Constraint>,
    /// Kinetic energy `T(q')`, a quadratic form with constant coefficients.
    pub kinetic: Id,
    /// Generalized force on each coordinate, inputs included (`0` where none
    /// was declared): `f(q, q') + B^T(q) u`.
    pub forces: Vec<Id>,
    /// The map to minimal coordinates, if declared.
    pub minimal: Option<Minimal>,
    /// Where the generated self-test samples, if a `sample` section is
    /// declared and `#[crane(no_self_test)]` is not given.
    pub self_test: Option<SelfTest>,
    /// Whether to generate the dummy-derivative system (for a crane
    /// without internal dynamics; off with `#[crane(no_dummy_derivatives)]`).
    pub dummy_derivatives: bool,
}

/// The sampling boxes of the generated self-test: `(low, high)` constant
/// expressions per coordinate and, for a minimal map, per minimal coordinate.
pub struct SelfTest {
    /// One range per redundant coordinate, in coordinate order.
    pub q: Vec<(Expr, Expr)>,
    /// One range per minimal coordinate, in `mu` order, if there is a map.
    pub mu: Option<Vec<(Expr, Expr)>>,
}

/// A checked `minimal` block: the map `q = phi(mu)` (eq. 6).
pub struct Minimal {
    /// The minimal coordinates `mu = [mu1; mu2]` as declared.
    pub mu: Vec<Ident>,
    /// Number of coordinates in `mu1`, `f - a`.
    pub n_mu1: usize,
    /// `phi(mu)`, one entry per redundant coordinate, in the parameters and
    /// `mu` only (`let`s and mapped coordinates are substituted).
    pub phi: Vec<Id>,
    /// The `let` abbreviations and their values; where a value is bound to
    /// a local in the generated code, the local takes the user's name.
    pub lets: Vec<(Ident, Id)>,
    /// The statements as written (`L1 = l * sin(beta) / sin(gamma)`), for
    /// the docs of the generated functions.
    pub source: Vec<String>,
}

/// A parameter: a field of the generated struct.
pub struct Param {
    /// Name of the field.
    pub name: Ident,
    /// The default as declared (a constant expression).
    pub default: Expr,
    /// The default lowered (a constant of the IR).
    pub value: Id,
    /// Declared `positive`: the runtime refuses a value <= 0.
    pub positive: bool,
    /// Doc comments on the parameter.
    pub docs: Vec<Attribute>,
}

/// A holonomic constraint `g_k(q) = 0`.
pub struct Constraint {
    /// Name of the constraint.
    pub name: Ident,
    /// The constraint function.
    pub g: Id,
    /// The rope it models, if any.
    pub rope: Option<Rope>,
}

/// A rope: its tension's name and its length `L` (the tension is
/// `N = -lambda dg/dL`, [`rope_tension`]).
pub struct Rope {
    /// Name of the tension.
    pub tension: Ident,
    /// Length `L(q)`.
    pub length: Id,
}

impl Model {
    /// Number of redundant coordinates `n`.
    pub fn n(&self) -> usize {
        self.coords.len()
    }

    /// Number of constraints `m`.
    pub fn m(&self) -> usize {
        self.constraints.len()
    }

    /// Number of inputs `a`.
    pub fn a(&self) -> usize {
        self.inputs.len()
    }

    /// The ropes in constraint order: `(constraint index, rope)`.
    pub fn ropes(&self) -> impl Iterator<Item = (usize, &Rope)> {
        self.constraints
            .iter()
            .enumerate()
            .filter_map(|(k, c)| c.rope.as_ref().map(|r| (k, r)))
    }
}

/// Row-major matrix of expressions.
pub type Matrix = Vec<Vec<Id>>;

/// Everything the generated code evaluates, as IR.
pub struct Kernels {
    /// `g(q)` (eq. 1b), `m` entries.
    pub g: Vec<Id>,
    /// `G = dg/dq` (eq. 3), `m x n`.
    pub jacobian: Matrix,
    /// `d(G^T lambda)/dq = sum_k lambda_k d^2 g_k/dq^2`, `n x n`, symmetric.
    pub hessian: Matrix,
    /// `M_ij = d^2 T / dq'_i dq'_j` (eq. 11a), `n x n`, constant.
    pub mass: Matrix,
    /// `f(q, q')`: the forces with all inputs zero (eq. 11b), `n` entries.
    pub f: Vec<Id>,
    /// `df/dq`, `n x n`.
    pub df_dq: Matrix,
    /// `df/dq'`, `n x n`.
    pub df_dv: Matrix,
    /// `B^T(q)`: column `k` is `d force / d u_k` (eq. 11c), `n x a`.
    pub bt: Matrix,
    /// `d(B^T(q) u)/dq`, `n x n`.
    pub dbtu_dq: Matrix,
    /// Rope lengths `L(q)`, in constraint order.
    pub rope_lengths: Vec<Id>,
    /// Rope tensions `N = -lambda dg/dL`, in the order of `rope_lengths`:
    /// the constraint's generalized force along the rope's length, the
    /// same whichever way `g` is written (see [`rope_tension`]).
    pub rope_tensions: Vec<Id>,
    /// `dg/dL` up to its positive normalisation (the numerator of
    /// [`rope_tension`]), per rope: structurally zero where the constraint
    /// does not depend on the rope's length.
    pub rope_along: Vec<Id>,
    /// The minimal-coordinate map and its derivatives, if declared.
    pub minimal: Option<MinimalKernels>,
}

/// The map `q = phi(mu)` and its derivatives (paper sect. 3.2).
pub struct MinimalKernels {
    /// `phi(mu) = [phi_p(mu); phi_x(mu)]` (eq. 6), `n` entries.
    pub phi: Vec<Id>,
    /// `P = D phi(mu)` (eq. 8), `n x f`; its load rows are
    /// `[D1 phi_x  D2 phi_x]` (eq. 12).
    pub p: Matrix,
    /// `P' = sum_k dP/dmu_k mu_k'` (eq. 9), `n x f`.
    pub p_rate: Matrix,
    /// `w = [P' mu']_x`, the second directional derivative of `phi_x` along
    /// `mu'` (eq. 17), `a` entries.
    pub w: Vec<Id>,
    /// `dP/dmu_k` for `k = 0 .. f`, each `n x f`: the second derivatives
    /// `d^2 phi_i / dmu_k dmu_l` (symmetric in `k`, `l`).
    pub second: Vec<Matrix>,
    /// `d(P' mu')/dmu`, `n x f`: the derivative of the curvature term of
    /// `q'' = P mu'' + P' mu'` (eq. 9) at fixed `mu'`.
    pub curvature_jacobian: Matrix,
}

impl Kernels {
    /// Differentiates the model.
    pub fn derive(model: &mut Model) -> Kernels {
        let n = model.n();
        let a = model.a();
        let coord = |i: usize| Sym::Coord(i as u16);
        let vel = |i: usize| Sym::Vel(i as u16);
        let input = |k: usize| Sym::Input(k as u16);

        let g: Vec<Id> = model.constraints.iter().map(|c| c.g).collect();
        let rope_lengths: Vec<Id> = model.ropes().map(|(_, r)| r.length).collect();
        let rope_constraints: Vec<usize> = model.ropes().map(|(k, _)| k).collect();
        let kinetic = model.kinetic;
        let forces = model.forces.clone();
        let arena = &mut model.arena;

        // f = force with u = 0 (eq. 11b)
        let zero = arena.zero();
        let f: Vec<Id> = forces
            .iter()
            .map(|&force| arena.substitute(force, &mut |s| matches!(s, Sym::Input(_)).then_some(zero)))
            .collect();

        let mut d = Differentiator::new(arena);
        let minimal = model
            .minimal
            .as_ref()
            .map(|minimal| MinimalKernels::derive(minimal, n - a, &mut d));
        let jacobian: Matrix = g
            .iter()
            .map(|&gk| (0..n).map(|j| d.diff(gk, coord(j))).collect())
            .collect();

        // sum_k lambda_k d^2 g_k / dq_i dq_j, from the rows of G; symmetric,
        // so each entry is computed once (for i <= j)
        let hessian = symmetric(n, |i, j| {
            let terms: Vec<Id> = jacobian
                .iter()
                .enumerate()
                .map(|(k, row)| {
                    let second = d.diff(row[i], coord(j));
                    let lambda = d.arena().sym(Sym::Lambda(k as u16));
                    d.arena().mul2(lambda, second)
                })
                .collect();
            d.arena().add(terms)
        });

        // M_ij = d^2 T / dq'_i dq'_j (eq. 11a)
        let mass = symmetric(n, |i, j| {
            let dt_dvi = d.diff(kinetic, vel(i));
            d.diff(dt_dvi, vel(j))
        });

        let df_dq: Matrix = f
            .iter()
            .map(|&fi| (0..n).map(|j| d.diff(fi, coord(j))).collect())
            .collect();
        let df_dv: Matrix = f
            .iter()
            .map(|&fi| (0..n).map(|j| d.diff(fi, vel(j))).collect())
            .collect();

        // B^T_ik = d force_i / d u_k (eq. 11c); linear in u, so this is free of u
        let bt: Matrix = forces
            .iter()
            .map(|&fi| (0..a).map(|k| d.diff(fi, input(k))).collect())
            .collect();

        // d(B^T u)/dq: sum_k u_k dB^T_ik/dq_j
        let bt_u: Vec<Id> = bt
            .iter()
            .map(|row| {
                let terms: Vec<Id> = row
                    .iter()
                    .enumerate()
                    .map(|(k, &b)| {
                        let u = d.arena().sym(input(k));
                        d.arena().mul2(u, b)
                    })
                    .collect();
                d.arena().add(terms)
            })
            .collect();
        let dbtu_dq: Matrix = bt_u
            .iter()
            .map(|&e| (0..n).map(|j| d.diff(e, coord(j))).collect())
            .collect();

        let (rope_tensions, rope_along) = rope_constraints
            .iter()
            .zip(&rope_lengths)
            .map(|(&k, &length)| rope_tension(&mut d, &g, &jacobian, k, length))
            .unzip();

        Kernels {
            g,
            jacobian,
            hessian,
            mass,
            f,
            df_dq,
            df_dv,
            bt,
            dbtu_dq,
            rope_lengths,
            rope_tensions,
            rope_along,
            minimal,
        }
    }
}

/// The tension of the rope of constraint `k` with length `L`, and the
/// numerator `dg/dL` of its factor: `N = -lambda_k dg_k/dL`, the generalized
/// force the constraint exerts along the rope's length (on a winch that
/// pays the rope out it is the rope's pull). `g` is differentiated along the
/// direction in which only `L` changes, `grad L / |grad L|^2` over the
/// coordinates and parameters `L` depends on, so `dg/dL = (grad g . grad L)
/// / |grad L|^2`. For `g = 1/2 (|d|^2 - L^2)` this is `N = lambda L`;
/// `|d|^2 - L^2` gives `2 lambda L` and `|d| - L` gives `lambda` with
/// their own `lambda`: the same force.
fn rope_tension(d: &mut Differentiator<'_>, g: &[Id], jacobian: &Matrix, k: usize, length: Id) -> (Id, Id) {
    let (mut along, mut norm) = (Vec::new(), Vec::new());
    for v in length_variables(d.arena(), length) {
        let dl = d.diff(length, v);
        let dg = match v {
            Sym::Coord(j) => jacobian[k][j as usize],
            _ => d.diff(g[k], v),
        };
        along.push(d.arena().mul2(dg, dl));
        norm.push(d.arena().mul2(dl, dl));
    }
    let along = d.arena().add(along);
    let norm = d.arena().add(norm);
    let dg_dl = d.arena().div(along, norm);
    let lambda = d.arena().sym(Sym::Lambda(k as u16));
    let pull = d.arena().mul2(lambda, dg_dl);
    (d.arena().neg(pull), along)
}

/// The coordinates and parameters a rope's length depends on (none for a
/// length that is a number).
pub fn length_variables(arena: &Arena, length: Id) -> Vec<Sym> {
    arena
        .symbols(length)
        .into_iter()
        .filter(|s| matches!(s, Sym::Coord(_) | Sym::Param(_)))
        .collect()
}

impl MinimalKernels {
    /// Differentiates the map; `n_robot` is the number of rows of `phi_p`.
    fn derive(minimal: &Minimal, n_robot: usize, d: &mut Differentiator<'_>) -> Self {
        let f = minimal.mu.len();
        let mu = |k: usize| Sym::Mu(k as u16);
        let phi = minimal.phi.clone();

        // P_ik = d phi_i / d mu_k (eq. 8)
        let p: Matrix = phi
            .iter()
            .map(|&phi_i| (0..f).map(|k| d.diff(phi_i, mu(k))).collect())
            .collect();

        // chain rule along the motion: P'_ik = sum_l dP_ik/dmu_l mu_l' (eq. 9)
        let along = |d: &mut Differentiator<'_>, e: Id| {
            let terms: Vec<Id> = (0..f)
                .map(|l| {
                    let de = d.diff(e, mu(l));
                    let mu_dot = d.arena().sym(Sym::MuDot(l as u16));
                    d.arena().mul2(de, mu_dot)
                })
                .collect();
            d.arena().add(terms)
        };
        let p_rate: Matrix = p.iter().map(|row| row.iter().map(|&e| along(d, e)).collect()).collect();

        // w = [P' mu']_x = d/dt[D1 phi_x] mu1' + d/dt[D2 phi_x] mu2^ (eq. 17),
        // as the quadratic form sum_kl d^2 phi_x/dmu_k dmu_l mu_k' mu_l'
        // (mixed terms once, doubled)
        let w: Vec<Id> = p[n_robot..]
            .iter()
            .map(|row| {
                let mut terms = Vec::new();
                for (k, &p_ik) in row.iter().enumerate() {
                    for l in k..f {
                        let second = d.diff(p_ik, mu(l));
                        let twice = if k == l { 1.0 } else { 2.0 };
                        let arena = d.arena();
                        let (mu_dot_k, mu_dot_l) = (arena.sym(Sym::MuDot(k as u16)), arena.sym(Sym::MuDot(l as u16)));
                        let c = arena.constant(twice);
                        terms.push(arena.mul(vec![c, second, mu_dot_k, mu_dot_l]));
                    }
                }
                d.arena().add(terms)
            })
            .collect();

        // dP_il/dmu_k (already in the graph: P' is built from them)
        let second: Vec<Matrix> = (0..f)
            .map(|k| {
                p.iter()
                    .map(|row| row.iter().map(|&e| d.diff(e, mu(k))).collect())
                    .collect()
            })
            .collect();

        // d(P' mu')/dmu_j, with P' mu' = sum_l P'_il mu_l'
        let curvature_jacobian: Matrix = p_rate
            .iter()
            .map(|row| {
                let terms: Vec<Id> = row
                    .iter()
                    .enumerate()
                    .map(|(l, &e)| {
                        let mu_dot = d.arena().sym(Sym::MuDot(l as u16));
                        d.arena().mul2(e, mu_dot)
                    })
                    .collect();
                let curvature = d.arena().add(terms);
                (0..f).map(|j| d.diff(curvature, mu(j))).collect()
            })
            .collect();

        MinimalKernels {
            phi,
            p,
            p_rate,
            w,
            second,
            curvature_jacobian,
        }
    }
}

/// The symmetric `n x n` matrix with entries `entry(i, j)` for `i <= j`.
fn symmetric(n: usize, mut entry: impl FnMut(usize, usize) -> Id) -> Matrix {
    let mut rows: Matrix = Vec::with_capacity(n);
    for i in 0..n {
        let row = (0..n).map(|j| if j < i { rows[j][i] } else { entry(i, j) }).collect();
        rows.push(row);
    }
    rows
}
