//! Numerically singular derivative coefficients: equations whose derivatives enter
//! linearly with constant coefficients (circuits in nodal form, `C*der(U1 - U2)`) can
//! be structurally regular while their coefficient matrix is singular — the hidden
//! algebraic relation is a linear combination of the equations, which no graph
//! algorithm sees. Each such combination replaces one of its equations, so that
//! Pantelides finds the constraint and differentiates it.
//!
//! Only rows whose loss lowers the structural rank are replaced: a structurally
//! dependent row (two equations for one derivative) is Pantelides' job already.
//! Coefficients are evaluated at the parameter values (a model compiled for other
//! parameter values is analysed again).

use crate::dae::{Dae, EqId, ScalarKind};
use crate::diff::partial;
use crate::expr::{ExprId, ScalarId};
use rustc_hash::FxHashMap as HashMap;

/// Largest group of equations sharing derivatives that is examined (dense elimination).
const MAX_GROUP: usize = 200;

/// One equation: its residual and its derivatives' constant coefficients.
struct Row {
    eq: EqId,
    residual: ExprId,
    coefficients: Vec<(ScalarId, f64)>,
}

/// Replaces numerically dependent equations (see the module docs) by the combination
/// that eliminates their derivatives. Returns the equations replaced.
pub fn expose_hidden_constraints(dae: &mut Dae) -> Vec<EqId> {
    let mut values = crate::params::ParameterValues::default();
    let mut rows: Vec<Row> = Vec::new();
    'equations: for k in 0..dae.equations.len() {
        let eq = EqId(k as u32);
        let r = dae.residual(eq);
        let derivatives: Vec<ScalarId> = dae
            .arena
            .vars(r)
            .into_iter()
            .filter(|&s| dae.scalar(s).kind == ScalarKind::Derivative)
            .collect();
        if derivatives.is_empty() {
            continue;
        }
        let mut coefficients = Vec::with_capacity(derivatives.len());
        for d in derivatives {
            let c = partial(&mut dae.arena, r, d);
            match values.of_expr(dae, c) {
                Some(v) if v.is_finite() => coefficients.push((d, v)),
                _ => continue 'equations,
            }
        }
        rows.push(Row {
            eq,
            residual: r,
            coefficients,
        });
    }
    // Groups: rows connected through shared derivatives (union-find on rows).
    let mut parent: Vec<usize> = (0..rows.len()).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut owner: HashMap<ScalarId, usize> = HashMap::default();
    for (i, row) in rows.iter().enumerate() {
        for &(d, _) in &row.coefficients {
            match owner.get(&d) {
                Some(&j) => {
                    let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                    parent[a] = b;
                }
                None => {
                    owner.insert(d, i);
                }
            }
        }
    }
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::default();
    for i in 0..rows.len() {
        let r = find(&mut parent, i);
        groups.entry(r).or_default().push(i);
    }
    let mut groups: Vec<Vec<usize>> = groups.into_values().filter(|g| g.len() >= 2).collect();
    groups.sort();
    let mut replaced = Vec::new();
    for group in groups {
        if group.len() > MAX_GROUP {
            continue;
        }
        replaced.extend(eliminate(dae, &rows, &group));
    }
    replaced
}

/// Dense elimination on one group; replaces the rows found dependent whose loss lowers
/// the group's structural rank.
fn eliminate(dae: &mut Dae, rows: &[Row], group: &[usize]) -> Vec<EqId> {
    let mut columns: Vec<ScalarId> = group
        .iter()
        .flat_map(|&i| rows[i].coefficients.iter().map(|&(d, _)| d))
        .collect();
    columns.sort();
    columns.dedup();
    let col = |d: ScalarId| columns.binary_search(&d).expect("a group column");
    let (m, n) = (group.len(), columns.len());
    let mut a = vec![0.0; m * n];
    for (r, &i) in group.iter().enumerate() {
        for &(d, v) in &rows[i].coefficients {
            a[r * n + col(d)] += v;
        }
    }
    let pattern: Vec<Vec<usize>> = (0..m)
        .map(|r| (0..n).filter(|&j| a[r * n + j] != 0.0).collect())
        .collect();
    let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    if scale == 0.0 {
        return Vec::new();
    }
    // Row elimination in order with partial pivoting over columns; `w` tracks each
    // reduced row as a combination of the original rows.
    let mut w = vec![0.0; m * m];
    for r in 0..m {
        w[r * m + r] = 1.0;
    }
    let mut pivots: Vec<(usize, usize)> = Vec::new();
    let mut dependent = Vec::new();
    for r in 0..m {
        for &(p, c) in &pivots {
            let f = a[r * n + c] / a[p * n + c];
            if f != 0.0 {
                for j in 0..n {
                    a[r * n + j] -= f * a[p * n + j];
                }
                for j in 0..m {
                    w[r * m + j] -= f * w[p * m + j];
                }
            }
        }
        let (c, v) = (0..n)
            .map(|j| (j, a[r * n + j].abs()))
            .fold((0, 0.0), |b, x| if x.1 > b.1 { x } else { b });
        if v <= 1e-12 * scale {
            dependent.push(r);
        } else {
            pivots.push((r, c));
        }
    }
    let mut active = vec![true; m];
    let mut replaced = Vec::new();
    for r in dependent {
        let before = structural_rank(&pattern, &active, n);
        active[r] = false;
        if structural_rank(&pattern, &active, n) == before {
            // Structurally dependent already: left to Pantelides.
            active[r] = true;
            continue;
        }
        // 0 = sum_i w_i * (residual_i with its derivatives set to 0).
        let zero = dae.arena.zero();
        let set = |s: ScalarId| columns.binary_search(&s).ok().map(|_| zero);
        let mut combination = dae.arena.zero();
        for (j, &i) in group.iter().enumerate() {
            let wj = w[r * m + j];
            if wj.abs() <= 1e-14 {
                continue;
            }
            let mut memo = HashMap::default();
            let g = dae.arena.substitute(rows[i].residual, &set, &mut memo);
            let c = dae.arena.constant(wj);
            let term = dae.arena.mul(c, g);
            combination = dae.arena.add(combination, term);
        }
        let eq = rows[group[r]].eq;
        let e = &mut dae.equations[eq.index()];
        e.lhs = combination;
        e.rhs = zero;
        replaced.push(eq);
    }
    replaced
}

/// Size of a maximum matching of the active rows to columns (Kuhn's augmenting paths;
/// groups are small).
fn structural_rank(pattern: &[Vec<usize>], active: &[bool], n: usize) -> usize {
    let mut owner: Vec<Option<usize>> = vec![None; n];
    let mut size = 0;
    for (r, _) in active.iter().enumerate().filter(|(_, &a)| a) {
        let mut seen = vec![false; n];
        if augment(pattern, r, &mut owner, &mut seen) {
            size += 1;
        }
    }
    size
}

fn augment(
    pattern: &[Vec<usize>],
    r: usize,
    owner: &mut [Option<usize>],
    seen: &mut [bool],
) -> bool {
    for &c in &pattern[r] {
        if seen[c] {
            continue;
        }
        seen[c] = true;
        if owner[c].is_none_or(|o| augment(pattern, o, owner, seen)) {
            owner[c] = Some(r);
            return true;
        }
    }
    false
}
