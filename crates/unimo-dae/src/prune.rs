//! Leaving out what a scene does not need: plan steps whose results reach no state
//! derivative, zero crossing, `when` clause, assertion or requested output are
//! removed (a whole algebraic loop with them: inside a strongly connected block every
//! variable feeds the others), so the compiled model only computes what is used. The
//! equations left out are listed in [`Plan::pruned`]: a relation only they hold is no
//! zero crossing (no root function, no event).

use crate::dae::{Dae, EqId, WhenAction};
use crate::events::{zero_crossings, zero_crossings_except, Crossings};
use crate::expr::{ExprId, ScalarId};
use crate::plan::{Plan, PlanStep};
use rustc_hash::FxHashSet as HashSet;

/// Removes unneeded steps; `wanted` are the outputs the user asked for (their alias
/// representatives are kept too). Returns the number of equations left out.
pub fn prune(dae: &Dae, plan: &mut Plan, wanted: &[ScalarId]) -> usize {
    let zc = zero_crossings(dae);
    let mut needed = needed_by_events_and_outputs(dae, plan, wanted, &zc);
    let add = |needed: &mut HashSet<ScalarId>, e| {
        needed.extend(dae.arena.vars(e));
    };
    // A held rounding (`floor`, `mod`, ... with events) takes its new value where the
    // step computing it runs, in event mode: that step must stay, or after an event its
    // zero crossings would be crossed again at once (chattering).
    let held: HashSet<ExprId> = zc.held.iter().copied().collect();
    let holds = |roots: &mut dyn Iterator<Item = ExprId>| -> bool {
        if held.is_empty() {
            return false;
        }
        let mut stack: Vec<ExprId> = roots.collect();
        let mut seen = HashSet::default();
        while let Some(x) = stack.pop() {
            if held.contains(&x) {
                return true;
            }
            if seen.insert(x) {
                stack.extend(dae.arena.children(x));
            }
        }
        false
    };
    let mut keep = vec![false; plan.steps.len()];
    for (k, step) in plan.steps.iter().enumerate().rev() {
        match step {
            PlanStep::Assign { var, value, eq } => {
                if needed.contains(var) || holds(&mut std::iter::once(*value)) {
                    keep[k] = true;
                    add(&mut needed, *value);
                    // The relations of the equation as written (its operands).
                    let e = &dae.equations[eq.index()];
                    add(&mut needed, e.lhs);
                    add(&mut needed, e.rhs);
                }
            }
            PlanStep::Block(b) => {
                let used = b.iteration_vars.iter().any(|v| needed.contains(v))
                    || b.inner.iter().any(|(v, _)| needed.contains(v))
                    || holds(
                        &mut b
                            .residuals
                            .iter()
                            .copied()
                            .chain(b.inner.iter().map(|i| i.1)),
                    );
                if used {
                    keep[k] = true;
                    for &eq in &b.equations {
                        let e = &dae.equations[eq.index()];
                        add(&mut needed, e.lhs);
                        add(&mut needed, e.rhs);
                    }
                    for &r in &b.residuals {
                        add(&mut needed, r);
                    }
                    for &(_, e) in &b.inner {
                        add(&mut needed, e);
                    }
                }
            }
        }
    }
    let mut pruned = 0;
    let mut left_out = Vec::new();
    let mut k = 0;
    plan.steps.retain(|step| {
        let kept = keep[k];
        k += 1;
        if !kept {
            match step {
                PlanStep::Assign { eq, .. } => {
                    pruned += 1;
                    left_out.push(*eq);
                }
                PlanStep::Block(b) => {
                    pruned += b.equations.len();
                    left_out.extend_from_slice(&b.equations);
                }
            }
        }
        kept
    });
    left_out.sort();
    left_out.dedup();
    plan.pruned = left_out;
    plan.stats.pruned_equations = pruned;
    pruned
}

/// The scalars needed whatever steps compute them: state derivatives, the outputs the
/// user asked for, what zero crossings, `when` clauses, assertions, invariants, initial equations
/// and start values read, variables with `fixed = true` and discrete variables.
fn needed_by_events_and_outputs(
    dae: &Dae,
    plan: &Plan,
    wanted: &[ScalarId],
    zc: &Crossings,
) -> HashSet<ScalarId> {
    let mut needed: HashSet<ScalarId> = plan.derivatives.iter().copied().collect();
    let add = |needed: &mut HashSet<ScalarId>, e| {
        needed.extend(dae.arena.vars(e));
    };
    for &s in wanted {
        needed.insert(s);
        if let Some(a) = dae.scalar(s).alias {
            add(&mut needed, a);
        }
    }
    // The relations of equations that a step computes are needed only if the step
    // is (its expression holds them); those of equations no step covers, of `when`
    // conditions and assertions always.
    let covered: Vec<EqId> = plan
        .steps
        .iter()
        .flat_map(|s| match s {
            PlanStep::Assign { eq, .. } => std::slice::from_ref(eq),
            PlanStep::Block(b) => b.equations.as_slice(),
        })
        .copied()
        .collect();
    let uncovered = zero_crossings_except(dae, &covered);
    for &r in uncovered
        .relations
        .iter()
        .chain(&zc.samples)
        .chain(&zc.held)
    {
        add(&mut needed, r);
    }
    for w in &dae.whens {
        for b in &w.branches {
            for &c in &b.conditions {
                add(&mut needed, c);
            }
            for (a, _) in &b.actions {
                match a {
                    WhenAction::Assign { target, value } => {
                        needed.insert(*target);
                        add(&mut needed, *value);
                    }
                    WhenAction::Reinit { value, .. } => add(&mut needed, *value),
                    WhenAction::Assert { condition, .. } => add(&mut needed, *condition),
                    WhenAction::Terminate { .. } => {}
                }
            }
        }
    }
    for a in &dae.assertions {
        add(&mut needed, a.condition);
    }
    for i in &dae.invariants {
        add(&mut needed, i.value);
        add(&mut needed, i.active);
    }
    // The values `delay` records after each step.
    for d in &dae.delays {
        add(&mut needed, d.input);
    }
    // Initialization reads what the initial equations and start values name, even when
    // nothing after the start does (e.g. a closed-form initial guess of an integrated
    // quantity).
    for e in &dae.initial_equations {
        add(&mut needed, e.lhs);
        add(&mut needed, e.rhs);
    }
    for s in dae.ids() {
        if let Some(start) = dae.scalar(s).start {
            add(&mut needed, start);
        }
        // `fixed = true` on a variable that is not a state is the initial equation
        // `v = start`: `v` must be computed at the start.
        if dae.scalar(s).fixed == Some(true) {
            needed.insert(s);
        }
    }
    // Discrete variables defined by equations take part in event iteration.
    for s in dae.ids() {
        if dae.scalar(s).kind == crate::dae::ScalarKind::Discrete {
            needed.insert(s);
        }
    }
    needed
}
