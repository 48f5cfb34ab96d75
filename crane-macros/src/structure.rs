//! The structure of the servo-constrained system (eqs. 22a-d): how many of
//! its states the load path leaves free, read off the sparsity of the
//! kernels, for the generated docs and `CraneModel::INTERNAL_DIMENSION`.
//!
//! The unknowns are `q` (`n`), `lambda` (`m`) and `u` (`a`); the equations
//! the `n` rows of the dynamics `M q'' = f + B^T u - G^T lambda`, the `m`
//! constraints `g(q) = 0` and the `a` servo constraints `x = gamma(t)`.
//! Pryce's signature method: `sigma_ij` is the highest derivative of unknown
//! `j` in equation `i` (2 through `M`, 1 through `df/dq'`, 0 through any
//! other dependence, absent otherwise), and the number of states the
//! equations leave free, the dimension of the internal dynamics, is the
//! largest sum of `sigma` over a transversal (one entry per row and per
//! column). The count is structural: it holds for generic parameter values
//! (a parameter that vanishes, like a coupling `c = 0`, can lower it; the
//! runtime's `internal_dynamics` gives the numeric dimension at a state).

use crate::model::{Kernels, Model};

/// No entry in the signature matrix.
const ABSENT: i64 = i64::MIN / 4;

/// The structure of eqs. (22a-d).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Structure {
    /// `dimension` states are not fixed by the path (0: flat); the offsets
    /// `c` of the unknowns `[q, lambda, u]` and `d` of the equations
    /// `[dynamics, constraints, servo]` (equation `i` is differentiated
    /// `d_i` times; `dimension = sum c - sum d`).
    Internal {
        /// The number of free states.
        dimension: usize,
        /// `c_j`.
        unknowns: Vec<u8>,
        /// `d_i`.
        equations: Vec<u8>,
    },
    /// No transversal: the equations cannot determine `q, lambda, u` from a
    /// path for any parameter values.
    Singular,
}

/// The signature matrix `sigma`, rows = equations, columns = unknowns
/// `[q, lambda, u]`.
fn signature(model: &Model, k: &Kernels) -> Vec<Vec<i64>> {
    let (n, m, a) = (model.n(), model.m(), model.a());
    let size = n + m + a;
    let zero = |id| model.arena.is_zero(id);
    let mut sigma = vec![vec![ABSENT; size]; size];
    for i in 0..n {
        for j in 0..n {
            sigma[i][j] = if !zero(k.mass[i][j]) {
                2
            } else if !zero(k.df_dv[i][j]) {
                1
            } else if !(zero(k.df_dq[i][j]) && zero(k.dbtu_dq[i][j]) && zero(k.hessian[i][j])) {
                0
            } else {
                ABSENT
            };
        }
        for c in 0..m {
            if !zero(k.jacobian[c][i]) {
                sigma[i][n + c] = 0;
            }
        }
        for r in 0..a {
            if !zero(k.bt[i][r]) {
                sigma[i][n + m + r] = 0;
            }
        }
    }
    for c in 0..m {
        for j in 0..n {
            if !zero(k.jacobian[c][j]) {
                sigma[n + c][j] = 0;
            }
        }
    }
    for r in 0..a {
        sigma[n + m + r][n - a + r] = 0;
    }
    sigma
}

/// A transversal of `weight` (square) with the largest sum, as the column
/// of each row, or `None` if every transversal meets an absent entry.
/// Hungarian method with potentials on the costs `-weight`, `O(size^3)`.
fn max_transversal(weight: &[Vec<i64>]) -> Option<Vec<usize>> {
    let size = weight.len();
    // an absent entry costs more than any transversal of present ones
    let big = 3 * (size as i64 + 1);
    let cost = |i: usize, j: usize| if weight[i][j] == ABSENT { big } else { -weight[i][j] };
    // 1-based rows and columns, column 0 is the virtual start
    let mut u = vec![0i64; size + 1];
    let mut v = vec![0i64; size + 1];
    let mut row_of = vec![0usize; size + 1];
    let mut way = vec![0usize; size + 1];
    for row in 1..=size {
        row_of[0] = row;
        let mut col0 = 0;
        let mut min_to = vec![i64::MAX; size + 1];
        let mut used = vec![false; size + 1];
        loop {
            used[col0] = true;
            let i0 = row_of[col0];
            let (mut delta, mut col1) = (i64::MAX, 0);
            for col in 1..=size {
                if !used[col] {
                    let reduced = cost(i0 - 1, col - 1) - u[i0] - v[col];
                    if reduced < min_to[col] {
                        min_to[col] = reduced;
                        way[col] = col0;
                    }
                    if min_to[col] < delta {
                        delta = min_to[col];
                        col1 = col;
                    }
                }
            }
            for col in 0..=size {
                if used[col] {
                    u[row_of[col]] += delta;
                    v[col] -= delta;
                } else {
                    min_to[col] -= delta;
                }
            }
            col0 = col1;
            if row_of[col0] == 0 {
                break;
            }
        }
        loop {
            let col1 = way[col0];
            row_of[col0] = row_of[col1];
            col0 = col1;
            if col0 == 0 {
                break;
            }
        }
    }
    let mut column = vec![0; size];
    for col in 1..=size {
        if weight[row_of[col] - 1][col - 1] == ABSENT {
            return None;
        }
        column[row_of[col] - 1] = col - 1;
    }
    Some(column)
}

/// Pryce's smallest offsets for a transversal: `c_j - d_i >= sigma_ij`
/// everywhere, with equality on the transversal, `d >= 0` (fixed-point
/// iteration from `d = 0`; it ends for a transversal of largest sum).
fn offsets(sigma: &[Vec<i64>], column: &[usize]) -> (Vec<i64>, Vec<i64>) {
    let size = sigma.len();
    let mut d = vec![0i64; size];
    loop {
        let c: Vec<i64> = (0..size)
            .map(|j| {
                (0..size)
                    .filter(|&i| sigma[i][j] != ABSENT)
                    .map(|i| sigma[i][j] + d[i])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let next: Vec<i64> = (0..size).map(|i| c[column[i]] - sigma[i][column[i]]).collect();
        if next == d {
            return (c, d);
        }
        d = next;
    }
}

/// The structure of the model's servo-constrained system; an error (a
/// message for the declaration's name) where the offsets leave what the
/// runtime's `Structure` holds (an offset above 255) or break Pryce's
/// `sum c >= sum d`, which no declaration the checks accept reaches.
pub fn structure(model: &Model, k: &Kernels) -> Result<Structure, String> {
    let sigma = signature(model, k);
    let Some(column) = max_transversal(&sigma) else {
        return Ok(Structure::Singular);
    };
    let (c, d) = offsets(&sigma, &column);
    let dimension = c.iter().sum::<i64>() - d.iter().sum::<i64>();
    let small = |v: Vec<i64>| -> Result<Vec<u8>, String> {
        v.into_iter()
            .map(|x| {
                u8::try_from(x).map_err(|_| {
                    format!("the structure analysis gives an offset of {x}, beyond the 255 derivatives it can hold")
                })
            })
            .collect()
    };
    let dimension = usize::try_from(dimension).map_err(|_| {
        format!("the structure analysis gives a negative number of free states ({dimension}): please report this declaration")
    })?;
    Ok(Structure::Internal {
        dimension,
        unknowns: small(c)?,
        equations: small(d)?,
    })
}

/// Where a structurally singular system fails: a set of unknowns (columns
/// of `[q, lambda, u]`) that appear in fewer equations (rows of
/// `[dynamics, constraints, servo]`) than they are, found by alternating
/// paths from the unknowns a maximum matching leaves unmatched
/// (the underdetermined part of the Dulmage-Mendelsohn decomposition).
pub struct SingularBlock {
    /// The unknowns.
    pub unknowns: Vec<usize>,
    /// Every equation they appear in.
    pub equations: Vec<usize>,
}

/// The underdetermined block of a structurally singular model; `None` if a
/// transversal exists.
pub fn singular_block(model: &Model, k: &Kernels) -> Option<SingularBlock> {
    let sigma = signature(model, k);
    let size = sigma.len();
    let present = |i: usize, j: usize| sigma[i][j] != ABSENT;
    // maximum matching by augmenting paths: row_of[j] = the row matched to column j
    let mut row_of: Vec<Option<usize>> = vec![None; size];
    fn augment(
        i: usize,
        present: &dyn Fn(usize, usize) -> bool,
        row_of: &mut Vec<Option<usize>>,
        seen: &mut Vec<bool>,
    ) -> bool {
        for j in 0..row_of.len() {
            if present(i, j) && !seen[j] {
                seen[j] = true;
                if row_of[j].is_none_or(|other| augment(other, present, row_of, seen)) {
                    row_of[j] = Some(i);
                    return true;
                }
            }
        }
        false
    }
    for i in 0..size {
        augment(i, &present, &mut row_of, &mut vec![false; size]);
    }
    let mut column_of = vec![None; size];
    for (j, row) in row_of.iter().enumerate() {
        if let Some(i) = row {
            column_of[*i] = Some(j);
        }
    }
    let mut stack: Vec<usize> = (0..size).filter(|&j| row_of[j].is_none()).collect();
    if stack.is_empty() {
        return None;
    }
    let (mut columns, mut rows) = (vec![false; size], vec![false; size]);
    while let Some(j) = stack.pop() {
        if std::mem::replace(&mut columns[j], true) {
            continue;
        }
        for i in (0..size).filter(|&i| present(i, j)) {
            rows[i] = true;
            if let Some(next) = column_of[i] {
                stack.push(next);
            }
        }
    }
    let pick = |set: &[bool]| (0..size).filter(|&x| set[x]).collect();
    Some(SingularBlock {
        unknowns: pick(&columns),
        equations: pick(&rows),
    })
}

impl SingularBlock {
    /// The compile error's message, in the declaration's names.
    pub fn message(&self, model: &Model) -> String {
        let (n, m) = (model.n(), model.m());
        let unknown = |j: usize| {
            if j < n {
                format!("`{}`", model.coords[j])
            } else if j < n + m {
                format!("the multiplier of `{}`", model.constraints[j - n].name)
            } else {
                format!("`{}`", model.inputs[j - n - m])
            }
        };
        let equation = |i: usize| {
            if i < n {
                format!("the dynamics of `{}`", model.coords[i])
            } else if i < n + m {
                format!("the constraint `{}`", model.constraints[i - n].name)
            } else {
                format!("the servo constraint of `{}`", model.coords[model.n_robot + i - n - m])
            }
        };
        let list = |items: Vec<String>| items.join(", ");
        let count =
            |items: String, k: usize, noun: &str| format!("{items} ({k} {noun}{})", if k == 1 { "" } else { "s" });
        format!(
            "structurally singular: no load path determines the coordinates, multipliers and inputs, because {} \
             appear only in {}; each input must drive a coordinate of its own that the load path reaches through \
             the constraints",
            count(
                list(self.unknowns.iter().map(|&j| unknown(j)).collect()),
                self.unknowns.len(),
                "unknown"
            ),
            count(
                list(self.equations.iter().map(|&i| equation(i)).collect()),
                self.equations.len(),
                "equation"
            ),
        )
    }
}

impl Structure {
    /// The sentences for the generated docs (`a` servo constraints, the
    /// last equations).
    pub fn describe(&self, a: usize) -> String {
        let order = match self {
            Structure::Internal { equations, .. } => {
                equations[equations.len().saturating_sub(a)..].iter().copied().max()
            }
            Structure::Singular => None,
        };
        let smoothness = order
            .map(|d| {
                format!(
                    " The inputs depend on the load path's derivatives up to order {d}: a path \
                continuous only to a lower order gives them jumps or impulses."
                )
            })
            .unwrap_or_default();
        let count = match *self {
            Structure::Internal { dimension: 0, .. } => {
                "Internal dynamics (structural, eqs. 22a-d): none, the load path fixes every state (flat).".to_string()
            }
            Structure::Internal { dimension: k, .. } => format!(
                "Internal dynamics (structural, eqs. 22a-d): {k} states are not fixed by the load path (not flat): \
                 the inputs follow an ODE driven by the path, which may be unstable; \
                 `crane_runtime::internal::internal_dynamics` gives its eigenvalues at a state."
            ),
            Structure::Singular => "Internal dynamics (structural, eqs. 22a-d): the equations cannot fix coordinates, \
                    multipliers and inputs from a load path (structurally singular)."
                .to_string(),
        };
        count + &smoothness
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force over all permutations, for the Hungarian method's check.
    fn brute(weight: &[Vec<i64>]) -> Option<i64> {
        fn go(weight: &[Vec<i64>], row: usize, used: &mut Vec<bool>) -> Option<i64> {
            if row == weight.len() {
                return Some(0);
            }
            let mut best = None;
            for col in 0..weight.len() {
                if !used[col] && weight[row][col] != ABSENT {
                    used[col] = true;
                    if let Some(rest) = go(weight, row + 1, used) {
                        let total = rest + weight[row][col];
                        best = Some(best.map_or(total, |b: i64| b.max(total)));
                    }
                    used[col] = false;
                }
            }
            best
        }
        go(weight, 0, &mut vec![false; weight.len()])
    }

    /// The Hungarian method agrees with brute force on pseudo-random
    /// signature matrices of sizes 1 to 7 (entries absent, 0, 1 or 2).
    #[test]
    fn max_transversal_matches_brute_force() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut singular = 0;
        for size in 1..=7 {
            for _ in 0..200 {
                let weight: Vec<Vec<i64>> = (0..size)
                    .map(|_| {
                        (0..size)
                            .map(|_| match next() % 5 {
                                0 | 1 => ABSENT,
                                r => r as i64 - 2,
                            })
                            .collect()
                    })
                    .collect();
                let expected = brute(&weight);
                singular += usize::from(expected.is_none());
                let found = max_transversal(&weight);
                let sum = found
                    .as_ref()
                    .map(|column| (0..size).map(|i| weight[i][column[i]]).sum::<i64>());
                assert_eq!(sum, expected, "{weight:?}");
                if let Some(column) = found {
                    // the offsets bound sigma and meet it on the transversal
                    let (c, d) = offsets(&weight, &column);
                    for i in 0..size {
                        assert!(d[i] >= 0);
                        for j in 0..size {
                            assert!(weight[i][j] == ABSENT || c[j] - d[i] >= weight[i][j]);
                        }
                        assert_eq!(c[column[i]] - d[i], weight[i][column[i]]);
                    }
                    assert_eq!(c.iter().sum::<i64>() - d.iter().sum::<i64>(), expected.unwrap());
                }
            }
        }
        assert!(singular > 0 && singular < 1000, "both cases exercised: {singular}");
    }
}
