//! Numerically regular dummy derivatives: a structurally valid choice of a level's
//! dummies can still leave the equations' Jacobian with respect to them singular when
//! constant coefficients cancel (`phi_rel = b - a` of a gearbox and `phi_rel = b - a`
//! of the elastic element inside it: `b` and `a` cannot both be dummies). With the
//! coefficients the caller knows (constants; entries that vary are taken as generic
//! values), the choice is checked and, when singular, replaced by the first regular
//! one in the candidates' order (greedy over the columns' linear matroid).

use crate::ids::{EqId, VarId};

/// Largest component (equations) examined: dense elimination.
const MAX_EQUATIONS: usize = 400;

/// A relative pivot below this share of the matrix's largest entry counts as zero.
const TOLERANCE: f64 = 1e-10;

/// Where an equation's partial derivative with respect to a variable is known:
/// `Some(value)` for a constant, `None` for an entry that varies.
pub type Coefficient<'a> = &'a mut dyn FnMut(EqId, VarId) -> Option<f64>;

/// A generic value in [0.5, 1.5) for an entry that varies, fixed per (equation,
/// variable) so that the check is deterministic (splitmix64 of the pair).
fn generic(e: EqId, v: VarId) -> f64 {
    let mut z = (u64::from(e.0) << 32 | u64::from(v.0)).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    0.5 + (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The column of `v` over `eqs` (zero where `v` does not occur).
fn column(
    eqs: &[EqId],
    occurs: &dyn Fn(EqId, VarId) -> bool,
    v: VarId,
    coefficient: Coefficient<'_>,
) -> Vec<f64> {
    eqs.iter()
        .map(|&e| {
            if !occurs(e, v) {
                0.0
            } else {
                coefficient(e, v).unwrap_or_else(|| generic(e, v))
            }
        })
        .collect()
}

/// An echelon basis of columns: each reduced column with its pivot row.
struct Basis {
    vectors: Vec<(Vec<f64>, usize)>,
}

impl Basis {
    /// Adds `c` when it is independent of the basis; tells whether it was.
    fn insert(&mut self, mut c: Vec<f64>, scale: f64) -> bool {
        for (b, p) in &self.vectors {
            let f = c[*p] / b[*p];
            if f != 0.0 {
                for (x, y) in c.iter_mut().zip(b) {
                    *x -= f * y;
                }
            }
        }
        let (p, v) = c
            .iter()
            .enumerate()
            .map(|(i, x)| (i, x.abs()))
            .fold((0, 0.0), |b, x| if x.1 > b.1 { x } else { b });
        if v <= TOLERANCE * scale {
            return false;
        }
        self.vectors.push((c, p));
        true
    }
}

/// When the columns `chosen` of the equations `eqs` are numerically dependent, the
/// first independent set of `eqs.len()` columns among `candidates` (in their order,
/// which is the order of preference); None when `chosen` is regular, when no regular
/// choice exists, or when the component is too large to examine.
pub(crate) fn regular_choice(
    eqs: &[EqId],
    candidates: &[VarId],
    chosen: &[VarId],
    occurs: &dyn Fn(EqId, VarId) -> bool,
    coefficient: Coefficient<'_>,
) -> Option<Vec<VarId>> {
    if eqs.len() > MAX_EQUATIONS || chosen.len() != eqs.len() {
        return None;
    }
    let columns: Vec<Vec<f64>> = candidates
        .iter()
        .map(|&v| column(eqs, occurs, v, coefficient))
        .collect();
    let scale = columns.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
    if scale == 0.0 {
        return None;
    }
    let mut basis = Basis {
        vectors: Vec::new(),
    };
    let regular = candidates
        .iter()
        .zip(&columns)
        .filter(|(v, _)| chosen.contains(v))
        .all(|(_, c)| basis.insert(c.clone(), scale));
    if regular {
        return None;
    }
    let mut basis = Basis {
        vectors: Vec::new(),
    };
    let mut choice = Vec::new();
    for (&v, c) in candidates.iter().zip(&columns) {
        if choice.len() == eqs.len() {
            break;
        }
        if basis.insert(c.clone(), scale) {
            choice.push(v);
        }
    }
    (choice.len() == eqs.len()).then_some(choice)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_singular_choice_is_replaced_by_the_first_regular_one() {
        // e0: x0 = b - a, e1: x1 = b - a, e2: b = 3 s, e3: p = 10 a (columns b, a, s,
        // p, x0, x1 in that order of preference).
        let eqs = [EqId(0), EqId(1), EqId(2), EqId(3)];
        let (b, a, s, p, x0, x1) = (VarId(0), VarId(1), VarId(2), VarId(3), VarId(4), VarId(5));
        let table = |e: EqId, v: VarId| -> Option<f64> {
            match (e.0, v.0) {
                (0, 4) | (1, 5) | (2, 0) | (3, 3) => Some(1.0),
                (0 | 1, 0) => Some(-1.0),
                (0 | 1, 1) => Some(1.0),
                (2, 2) => Some(-3.0),
                (3, 1) => Some(-10.0),
                _ => None,
            }
        };
        let occurs = |e: EqId, v: VarId| table(e, v).is_some();
        let mut coefficient = |e: EqId, v: VarId| table(e, v);
        let candidates = [b, a, s, p, x0, x1];
        let got = regular_choice(&eqs, &candidates, &[b, a, s, p], &occurs, &mut coefficient);
        assert_eq!(got, Some(vec![b, a, s, x0]));
        // A regular choice stays.
        let got = regular_choice(&eqs, &candidates, &[b, a, s, x0], &occurs, &mut coefficient);
        assert_eq!(got, None);
    }
}
