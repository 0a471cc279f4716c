//! The modes of a Newton block at events: its relations decided with its solution
//! (rounds, then a bounded search over their outcomes), and blocks whose Jacobian is
//! singular but whose equations are consistent (statically indeterminate loops).

use crate::exec::Run;
use unimo_solve::dense::{independent_rows_and_columns, newton_step};
use unimo_solve::newton::{NewtonProblem, MAX_ITERATIONS};

use crate::eval::{newton_smooth, residual_norm, BlockFailure, BlockProblem, Workspace};
use crate::exec::EventState;
use unimo_codegen::model::CompiledBlock;

/// Rounds of "solve with the relations frozen, then decide them again" for a block
/// whose equations hold relations, at an event.
const MAX_MODE_ROUNDS: usize = 16;

/// Most solves of one search over the outcomes of a block's relations: every
/// combination of up to 12 relations, fewer of a larger set (those with the fewest
/// true outcomes first).
const MAX_SEARCHED_SOLVES: usize = 4096;

/// A residual of a singular block counts as satisfied when it is below this share of
/// its row's scale (`1 + sum |J_ij x_j|`).
const CONSISTENT: f64 = 1e-9;

/// Solves a block. Outside events its relations are frozen (they change only at
/// located crossings), so Newton sees a smooth residual. At an event the relations of
/// the block are decided as for the whole model's event iteration: Newton solves with
/// them frozen at their current outcome, then they are evaluated at the solution; when
/// one changed (a `Real` state indicator inside the loop switched its branch), the
/// block is solved again with the new outcomes, until they agree with the solution.
/// Newton never sees a residual that jumps between its iterates. When the rounds cycle
/// or a solve fails (the previous mode has no solution: both clutches of a loop stuck
/// while it must slide), the outcomes are searched ([`search`]).
pub(crate) fn newton(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
) -> Result<(), BlockFailure> {
    if !ev.event_mode || b.relations.is_empty() {
        return newton_smooth(b, r, ev, w);
    }
    // Decide the relations at the current iterate (the previous mode), then iterate.
    b.residual_tape.run(r, ev);
    let start: Vec<f64> = b.iteration.iter().map(|&g| r[g as usize]).collect();
    let mut switched = vec![false; ev.relations.len()];
    let mut failure = None;
    for _ in 0..MAX_MODE_ROUNDS {
        w.relations.clear();
        w.relations.extend_from_slice(&ev.relations);
        ev.event_mode = false;
        let solved = newton_smooth(b, r, ev, w);
        ev.event_mode = true;
        if let Err(f) = solved {
            failure = Some(f);
            break;
        }
        b.residual_tape.run(r, ev);
        if w.relations == ev.relations {
            return Ok(());
        }
        // Outcomes that changed without changing the solution (a relation on a quantity
        // that is exactly 0 in the active branch and flips with rounding): consistent.
        let norm = residual_norm(b, r);
        if norm <= 1e-10 {
            return Ok(());
        }
        for (k, s) in switched.iter_mut().enumerate() {
            *s |= w.relations[k] != ev.relations[k];
        }
    }
    // The rounds cycle (friction: stuck implies sliding and sliding implies stuck,
    // starting from the previous mode): the outcomes that kept switching are searched.
    // A solve failed: any outcome of the block may be the wrong one.
    let candidates: Vec<u32> = match failure {
        Some(_) => b.relations.clone(),
        None => (0..switched.len() as u32)
            .filter(|&k| switched[k as usize])
            .collect(),
    };
    let base = w.relations.clone();
    if search(b, r, ev, w, &candidates, &start) {
        return Ok(());
    }
    // No outcome of the switching relations is consistent (a positive-feedback loop
    // past the fold of its branch, switching between that branch and the unstable
    // one): the consistent mode changes other relations of the block too (the other
    // limit of the comparator).
    if candidates.len() < b.relations.len() {
        ev.relations.copy_from_slice(&base);
        if search(b, r, ev, w, &b.relations, &start) {
            return Ok(());
        }
    }
    ev.relations.copy_from_slice(&base);
    if let Some(f) = failure {
        return Err(f);
    }
    let flipping: Vec<String> = candidates.iter().map(|k| format!("z{k}")).collect();
    Err(BlockFailure {
        variables: b.names.clone(),
        residual: residual_norm(b, r),
        reason: format!(
            "the conditions inside the loop did not settle in {MAX_MODE_ROUNDS} rounds \
             (no branch choice is consistent with its own solution; still switching: {})",
            flipping.join(", ")
        ),
    })
}

/// Searches the outcomes of the relations `candidates` (the others keep their current
/// outcome): each combination is frozen, the block solved from `start`, and the first
/// combination that agrees with its own solution is kept (the combinatorial
/// mixed-system search of Modelica tools). Combinations with the fewest true outcomes
/// come first, in increasing binary order among equals, at most
/// [`MAX_SEARCHED_SOLVES`] of them: bounded and deterministic.
fn search(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
    candidates: &[u32],
    start: &[f64],
) -> bool {
    // A mask has 64 bits; further candidates keep their outcome.
    let candidates = &candidates[..candidates.len().min(63)];
    let n = candidates.len();
    if n == 0 {
        return false;
    }
    let base = ev.relations.clone();
    let mut solves = 0;
    for weight in 0..=n {
        let mut mask: u64 = (1u64 << weight) - 1;
        while mask < 1u64 << n {
            if solves == MAX_SEARCHED_SOLVES {
                return false;
            }
            solves += 1;
            if try_outcomes(b, r, ev, w, candidates, mask, &base, start) {
                return true;
            }
            if weight == 0 {
                break;
            }
            mask = next_with_same_weight(mask);
        }
    }
    false
}

/// The next larger integer with as many bits set (Gosper's hack); `mask` is not 0.
fn next_with_same_weight(mask: u64) -> u64 {
    let lowest = mask & mask.wrapping_neg();
    let ripple = mask + lowest;
    ripple | (((mask ^ ripple) >> 2) / lowest)
}

/// Freezes the outcomes `mask` of `candidates` (bit i for candidate i) on `base`,
/// solves the block from `start` and tells whether the outcomes agree with the
/// solution.
#[allow(clippy::too_many_arguments)]
fn try_outcomes(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
    candidates: &[u32],
    mask: u64,
    base: &[f64],
    start: &[f64],
) -> bool {
    ev.relations.copy_from_slice(base);
    for (i, &z) in candidates.iter().enumerate() {
        ev.relations[z as usize] = f64::from(mask >> i & 1 == 1);
    }
    w.relations.clear();
    w.relations.extend_from_slice(&ev.relations);
    for (k, &g) in b.iteration.iter().enumerate() {
        r[g as usize] = start[k];
    }
    ev.event_mode = false;
    let solved = newton_smooth(b, r, ev, w);
    ev.event_mode = true;
    if solved.is_err() {
        return false;
    }
    b.residual_tape.run(r, ev);
    candidates
        .iter()
        .all(|&z| ev.relations[z as usize] == w.relations[z as usize])
}

/// Newton on a block whose Jacobian is singular: each step solves a largest set of
/// independent equations for as many unknowns (rank-revealing pivoting), the other
/// unknowns keep their values. The result is kept only when every equation holds at
/// it, the dependent ones too (a statically indeterminate loop, e.g. two stuck
/// clutches in series, whose torques the equations do not decide); otherwise the
/// registers are restored and false is returned. Deterministic: the choice of
/// equations and unknowns is the pivoting's.
pub(crate) fn solve_indeterminate(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
) -> bool {
    let n = b.iteration.len();
    let start: Vec<f64> = b.iteration.iter().map(|&g| r[g as usize]).collect();
    let mut x = start.clone();
    let mut f = vec![0.0; n];
    let mut jac = vec![0.0; n * n];
    let mut problem = BlockProblem { b, r, ev };
    let mut converged = false;
    for _ in 0..MAX_ITERATIONS {
        problem.residual(&x, &mut f);
        if f.iter().any(|v| !v.is_finite()) {
            break;
        }
        problem.jacobian(&mut jac);
        let (rows, cols) = independent_rows_and_columns(&jac, n, n);
        if rows.is_empty() {
            converged = true;
            break;
        }
        let Some(dx) = newton_step(&jac, n, &rows, &cols, &f) else {
            break;
        };
        converged = true;
        for (k, &c) in cols.iter().enumerate() {
            converged &= w.tolerance.accepts(x[c], dx[k]);
            x[c] += dx[k];
        }
        if converged {
            break;
        }
    }
    problem.residual(&x, &mut f);
    let consistent = converged
        && (0..n).all(|i| {
            let scale: f64 = (0..n).map(|j| (jac[i * n + j] * x[j]).abs()).sum();
            f[i].abs() <= CONSISTENT * (1.0 + scale)
        });
    if !consistent {
        for (k, &g) in b.iteration.iter().enumerate() {
            problem.r[g as usize] = start[k];
        }
    }
    consistent
}

#[cfg(test)]
mod tests {
    use super::next_with_same_weight;

    #[test]
    fn masks_of_one_weight_come_in_increasing_order() {
        let mut masks = vec![0b0011u64];
        while let Some(&m) = masks.last() {
            let next = next_with_same_weight(m);
            if next >= 1 << 4 {
                break;
            }
            masks.push(next);
        }
        assert_eq!(masks, vec![0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100]);
    }
}
