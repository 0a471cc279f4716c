//! Compiling the initialization: the initial equations (residuals, or assignments of
//! discrete variables), `v = start` for the fixed unknowns that are not states, with
//! the texts and orders the simulator's messages and pivoting use, and the constraints
//! fully fixed by start values.

use super::compile::show;
use super::FixedConstraint;
use crate::tape::{Compiler, Layout, Reg, Tape};
use rustc_hash::FxHashMap as HashMap;
use std::collections::HashSet;
use unimo_dae::dae::{Dae, EqId, ScalarKind};
use unimo_dae::expr::{ExprId, ScalarId};
use unimo_dae::plan::{Plan, PlanStep};

/// The initial equations in compiled form (see the `initial_*` fields of
/// [`CompiledModel`](super::CompiledModel)).
#[derive(Default)]
pub(super) struct InitialEquations {
    pub tape: Tape,
    pub residuals: Vec<Reg>,
    pub names: Vec<(String, Option<String>)>,
    pub orders: Vec<u32>,
    pub parameter_only: Vec<bool>,
    pub assigned: Vec<(Reg, String)>,
    pub pre_assigned: Vec<Reg>,
}

/// Initial equations, plus `v = start` for every unknown that is not a state and has
/// `fixed = true` (states with fixed start are simply not free).
pub(super) fn compile_initial(dae: &Dae, plan: &Plan, c: &mut Compiler<'_>) -> InitialEquations {
    let layout = c.layout;
    let mut out = InitialEquations::default();
    let mut memo = HashMap::default();
    let pairs: Vec<(ExprId, ExprId)> = dae
        .initial_equations
        .iter()
        .map(|e| (e.lhs, e.rhs))
        .collect();
    let state_set: HashSet<ScalarId> = plan.states.iter().copied().collect();
    let mut arena_starts = Vec::new();
    for s in dae.ids() {
        let sc = dae.scalar(s);
        if sc.fixed == Some(true)
            && sc.alias.is_none()
            && !state_set.contains(&s)
            && matches!(sc.kind, ScalarKind::Continuous | ScalarKind::Derivative)
        {
            if let Some(st) = sc.start {
                arena_starts.push((s, st));
            }
        }
    }
    let selectors: HashSet<ScalarId> = plan
        .state_sets
        .iter()
        .flat_map(|s| s.selectors.iter().copied())
        .collect();
    let step_equations = step_equations(plan);
    for (l, r) in pairs {
        if assignment(dae, layout, c, &mut out, &mut memo, l, r) {
            continue;
        }
        let lr = c.expr(l, &mut out.tape, &mut memo);
        let rr = c.expr(r, &mut out.tape, &mut memo);
        let d = c.temp_public();
        out.tape.ops.push(crate::tape::Op::Sub(d, lr, rr));
        out.residuals.push(d);
        out.names
            .push((format!("{} = {}", show(dae, l), show(dae, r)), None));
        out.orders.push(u32::MAX);
        out.parameter_only.push(
            dae.arena
                .vars(l)
                .into_iter()
                .chain(dae.arena.vars(r))
                .all(|v| {
                    matches!(
                        dae.scalar(v).kind,
                        ScalarKind::Parameter | ScalarKind::Constant
                    )
                }),
        );
    }
    for (s, st) in arena_starts {
        let rr = c.expr(st, &mut out.tape, &mut memo);
        let d = c.temp_public();
        out.tape
            .ops
            .push(crate::tape::Op::Sub(d, layout.var(s), rr));
        out.residuals.push(d);
        // The model equations of the step computing `s` (a differentiated one as
        // `d/dt (...)` of its original; the selection of a state set left out).
        let constraint = step_equations
            .get(&s)
            .map(|eqs| constraint_text(dae, eqs, &selectors));
        out.names.push((
            format!("{} = {} (fixed start)", dae.name(s), show(dae, st)),
            constraint,
        ));
        // Position-like variables (more derivatives above them) are decided first.
        let mut order = 0;
        let mut cur = dae.scalar(s).derivative;
        while let Some(d) = cur {
            order += 1;
            cur = dae.scalar(d).derivative;
        }
        out.orders.push(order);
        out.parameter_only.push(false);
    }
    out
}

/// Per variable the plan computes, the equations of its step.
fn step_equations(plan: &Plan) -> HashMap<ScalarId, Vec<EqId>> {
    let mut step_equations: HashMap<ScalarId, Vec<EqId>> = HashMap::default();
    for step in &plan.steps {
        match step {
            PlanStep::Assign { var, eq, .. } => {
                step_equations.insert(*var, vec![*eq]);
            }
            PlanStep::Block(b) => {
                for v in b
                    .iteration_vars
                    .iter()
                    .chain(b.inner.iter().map(|(v, _)| v))
                {
                    step_equations.insert(*v, b.equations.clone());
                }
            }
        }
    }
    step_equations
}

/// The initial equation `l = r` compiled as an assignment, when it is one (then true).
/// `d = expr` for a discrete `d` that `expr` does not mention is an assignment (what an
/// initial algorithm's `d := expr` lowers to): executed, not solved. `pre(d) = expr`
/// (`initial equation pre(y) = y_start`) sets the value `d` has before the initial
/// event.
fn assignment(
    dae: &Dae,
    layout: Layout,
    c: &mut Compiler<'_>,
    out: &mut InitialEquations,
    memo: &mut HashMap<ExprId, Reg>,
    l: ExprId,
    r: ExprId,
) -> bool {
    let (target, pre) = match dae.arena.node(l) {
        unimo_dae::expr::Node::Var(d) => (Some(d), false),
        unimo_dae::expr::Node::Pre(d) => (Some(d), true),
        _ => (None, false),
    };
    let Some(d) = target else {
        return false;
    };
    if dae.scalar(d).kind != ScalarKind::Discrete
        || dae.scalar(d).alias.is_some()
        || dae.arena.vars(r).contains(&d)
    {
        return false;
    }
    let rr = c.expr(r, &mut out.tape, memo);
    let reg = if pre {
        layout.pre_base + layout.var(d)
    } else {
        layout.var(d)
    };
    out.tape.ops.push(crate::tape::Op::Copy(reg, rr));
    if pre {
        out.pre_assigned.push(layout.var(d));
    } else {
        out.assigned.push((layout.var(d), dae.name(d)));
    }
    // Values computed before the assignment may have read the old value.
    memo.clear();
    true
}

/// The equations `eqs` as text (a differentiated one as `d/dt (...)` of its original),
/// leaving out those that read a state set's selection.
fn constraint_text(dae: &Dae, eqs: &[EqId], selectors: &HashSet<ScalarId>) -> String {
    eqs.iter()
        .filter(|eq| {
            let e = &dae.equations[eq.index()];
            !dae.arena
                .vars(e.lhs)
                .iter()
                .chain(&dae.arena.vars(e.rhs))
                .any(|v| selectors.contains(v))
        })
        .map(|eq| {
            let mut eq = *eq;
            let mut order = 0;
            while let Some(b) = dae.equations[eq.index()].derivative_of {
                eq = b;
                order += 1;
            }
            let e = &dae.equations[eq.index()];
            let text = format!("{} = {}", show(dae, e.lhs), show(dae, e.rhs));
            match order {
                0 => text,
                1 => format!("d/dt ({text})"),
                n => format!("d^{n}/dt^{n} ({text})"),
            }
        })
        .collect::<Vec<_>>()
        .join("`, `")
}

/// Constraints fully fixed by start values: the original equations (of those
/// differentiated) whose variables all have fixed starts.
pub(super) fn compile_fixed_constraints(
    dae: &Dae,
    c: &mut Compiler<'_>,
) -> (Tape, Vec<FixedConstraint>) {
    let layout = c.layout;
    let mut fixed_constraints_tape = Tape::default();
    let mut fixed_constraints = Vec::new();
    let mut memo = HashMap::default();
    let differentiated: HashSet<EqId> = dae
        .equations
        .iter()
        .filter_map(|e| e.derivative_of)
        .collect();
    for (k, e) in dae.equations.iter().enumerate() {
        let id = EqId(k as u32);
        if e.derivative_of.is_some() || !differentiated.contains(&id) {
            continue;
        }
        let mut vars = dae.arena.vars(e.lhs);
        vars.extend(dae.arena.vars(e.rhs));
        vars.sort();
        vars.dedup();
        vars.retain(|&v| {
            !matches!(
                dae.scalar(v).kind,
                ScalarKind::Parameter | ScalarKind::Constant
            )
        });
        let all_fixed = !vars.is_empty()
            && vars.iter().all(|&v| {
                let sc = dae.scalar(v);
                sc.fixed == Some(true)
                    && sc.start.is_some()
                    && sc.alias.is_none()
                    && matches!(sc.kind, ScalarKind::Continuous)
            });
        if !all_fixed {
            continue;
        }
        fixed_constraints.push(FixedConstraint {
            lhs: c.expr(e.lhs, &mut fixed_constraints_tape, &mut memo),
            rhs: c.expr(e.rhs, &mut fixed_constraints_tape, &mut memo),
            text: format!("{} = {}", show(dae, e.lhs), show(dae, e.rhs)),
            variables: vars.iter().map(|&v| (dae.name(v), layout.var(v))).collect(),
        });
    }
    (fixed_constraints_tape, fixed_constraints)
}
