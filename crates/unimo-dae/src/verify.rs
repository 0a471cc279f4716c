//! Verifiers of the DAE and of the causal plan: the invariants the later stages rely
//! on without checking them. `analyze_model` runs both in debug and test builds.
//!
//! The DAE (`verify_dae`):
//! 1. every expression id an equation, binding, attribute, `when`, assertion or
//!    collision site holds lies in the arena, and every scalar a node names lies in
//!    the scalar table;
//! 2. derivative links are mutual: `s.derivative = d` exactly when
//!    `d.derivative_of = s`, and `d` is a `Derivative`;
//! 3. an external leaf names an existing collision site (or the world's gaps, when
//!    there is a world) and an output the site has (6 per body, 2 for the gaps).
//!
//! The plan (`verify_plan`):
//! 1. `states` and `derivatives` pair up: `derivatives[i]` is `der(states[i])`;
//! 2. no scalar is computed twice (by two steps, or by a step and as a state), and no
//!    parameter or constant is computed;
//! 3. a block has as many residuals as iteration variables, and an `n x n` Jacobian;
//! 4. every step reads only what is known when it runs: states, parameters,
//!    constants, discrete scalars, inputs, aliases, and the scalars earlier steps (or
//!    the block itself) computed.

use crate::dae::{Dae, ScalarKind, WhenAction, COLLISION_GAPS_SITE};
use crate::expr::{ExprId, Node, ScalarId};
use crate::plan::{Plan, PlanStep};

/// A broken invariant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{ir}: {message}")]
pub struct VerifyError {
    /// `DAE` or `plan`.
    pub ir: &'static str,
    pub message: String,
}

fn dae_error(message: String) -> VerifyError {
    VerifyError { ir: "DAE", message }
}

fn plan_error(message: String) -> VerifyError {
    VerifyError {
        ir: "plan",
        message,
    }
}

/// Every expression root the DAE holds, with where it is (for messages).
fn roots(dae: &Dae) -> Vec<(ExprId, String)> {
    let mut out = Vec::new();
    for (k, e) in dae.equations.iter().enumerate() {
        out.push((e.lhs, format!("equation {k}")));
        out.push((e.rhs, format!("equation {k}")));
    }
    for (k, e) in dae.initial_equations.iter().enumerate() {
        out.push((e.lhs, format!("initial equation {k}")));
        out.push((e.rhs, format!("initial equation {k}")));
    }
    for s in &dae.scalars {
        for e in [s.binding, s.start, s.nominal, s.min, s.max, s.alias]
            .into_iter()
            .flatten()
        {
            out.push((e, format!("an attribute of {}", s.name)));
        }
    }
    for (k, w) in dae.whens.iter().enumerate() {
        for b in &w.branches {
            for &c in &b.conditions {
                out.push((c, format!("when {k}")));
            }
            for (a, _) in &b.actions {
                match a {
                    WhenAction::Assign { value, .. } | WhenAction::Reinit { value, .. } => {
                        out.push((*value, format!("when {k}")))
                    }
                    _ => {}
                }
            }
        }
    }
    for (k, a) in dae.assertions.iter().enumerate() {
        out.push((a.condition, format!("assertion {k}")));
    }
    for (k, i) in dae.invariants.iter().enumerate() {
        out.push((i.value, format!("invariant {k}")));
        out.push((i.active, format!("invariant {k}'s condition")));
    }
    for (k, c) in dae.collision.iter().enumerate() {
        for e in c.args.to_flat() {
            out.push((e, format!("collision body {k}")));
        }
    }
    if let Some(w) = &dae.collision_world {
        for e in w.args.to_flat() {
            out.push((e, "the collision world".into()));
        }
    }
    for (k, d) in dae.delays.iter().enumerate() {
        out.push((d.input, format!("delay {k}")));
    }
    out
}

/// Checks the DAE's invariants (module docs).
pub fn verify_dae(dae: &Dae) -> Result<(), VerifyError> {
    let n_nodes = dae.arena.len();
    let n_scalars = dae.scalars.len();
    for (e, place) in roots(dae) {
        if e.index() >= n_nodes {
            return Err(dae_error(format!(
                "{place} holds expression {} of {n_nodes}",
                e.index()
            )));
        }
    }
    for k in 0..n_nodes {
        let id = ExprId(k as u32);
        match dae.arena.node(id) {
            Node::Var(s) | Node::Pre(s) if s.index() >= n_scalars => {
                return Err(dae_error(format!(
                    "expression {k} names scalar {} of {n_scalars}",
                    s.index()
                )));
            }
            Node::External(site, out) => {
                let outputs = if site == COLLISION_GAPS_SITE {
                    dae.collision_world.as_ref().map(|_| 2)
                } else {
                    dae.collision.get(site as usize).map(|_| 6)
                };
                match outputs {
                    Some(n) if out < n => {}
                    _ => {
                        return Err(dae_error(format!(
                            "expression {k} reads output {out} of external site {site}, \
                             which does not exist"
                        )))
                    }
                }
            }
            _ => {}
        }
        for c in dae.arena.children(id) {
            if c.index() >= k {
                return Err(dae_error(format!(
                    "expression {k} has child {} that is not older",
                    c.index()
                )));
            }
        }
    }
    for (k, s) in dae.scalars.iter().enumerate() {
        if let Some(d) = s.derivative {
            let ok = dae.scalars.get(d.index()).is_some_and(|ds| {
                ds.kind == ScalarKind::Derivative && ds.derivative_of == Some(ScalarId(k as u32))
            });
            if !ok {
                return Err(dae_error(format!(
                    "{} names {} as its derivative, which does not name it back",
                    s.name,
                    dae.scalars.get(d.index()).map_or("nothing", |x| &x.name)
                )));
            }
        }
        if let Some(of) = s.derivative_of {
            let ok = dae
                .scalars
                .get(of.index())
                .is_some_and(|b| b.derivative == Some(ScalarId(k as u32)));
            if !ok {
                return Err(dae_error(format!(
                    "{} is the derivative of a scalar that does not name it",
                    s.name
                )));
            }
        }
    }
    Ok(())
}

/// Checks the plan's invariants against its DAE (module docs).
pub fn verify_plan(dae: &Dae, plan: &Plan) -> Result<(), VerifyError> {
    let n = dae.scalars.len();
    let name = |s: ScalarId| dae.scalars.get(s.index()).map_or("?", |x| &x.name);
    verify_states(dae, plan)?;
    let mut known = known_before_plan(dae);
    let mut computed = vec![false; n];
    for &s in &plan.states {
        known[s.index()] = true;
        computed[s.index()] = true;
    }
    let mut compute = |s: ScalarId, step: usize| -> Result<(), VerifyError> {
        let k = s.index();
        if k >= n {
            return Err(plan_error(format!(
                "step {step} computes scalar {k} of {n}"
            )));
        }
        if computed[k] {
            return Err(plan_error(format!(
                "step {step} computes {}, which is already computed",
                name(s)
            )));
        }
        if matches!(
            dae.scalars[k].kind,
            ScalarKind::Constant | ScalarKind::Parameter
        ) {
            return Err(plan_error(format!(
                "step {step} computes the parameter {}",
                name(s)
            )));
        }
        computed[k] = true;
        Ok(())
    };
    let reads = |e: ExprId, known: &[bool], step: usize| -> Result<(), VerifyError> {
        match dae.arena.vars(e).into_iter().find(|s| !known[s.index()]) {
            Some(s) => Err(plan_error(format!(
                "step {step} reads {} before any step computes it",
                name(s)
            ))),
            None => Ok(()),
        }
    };
    for (k, step) in plan.steps.iter().enumerate() {
        match step {
            PlanStep::Assign { var, value, .. } => {
                reads(*value, &known, k)?;
                compute(*var, k)?;
                known[var.index()] = true;
            }
            PlanStep::Block(b) => {
                let m = b.iteration_vars.len();
                if b.residuals.len() != m || b.jacobian.len() != m * m {
                    return Err(plan_error(format!(
                        "step {k}: {m} iteration variables, {} residuals, {} Jacobian entries",
                        b.residuals.len(),
                        b.jacobian.len()
                    )));
                }
                for &v in &b.iteration_vars {
                    compute(v, k)?;
                    known[v.index()] = true;
                }
                for &(v, value) in &b.inner {
                    reads(value, &known, k)?;
                    compute(v, k)?;
                    known[v.index()] = true;
                }
                for &r in b.residuals.iter().chain(&b.jacobian) {
                    reads(r, &known, k)?;
                }
            }
        }
    }
    Ok(())
}

/// The plan's states, each paired with its derivative.
fn verify_states(dae: &Dae, plan: &Plan) -> Result<(), VerifyError> {
    let n = dae.scalars.len();
    let name = |s: ScalarId| dae.scalars.get(s.index()).map_or("?", |x| &x.name);
    if plan.states.len() != plan.derivatives.len() {
        return Err(plan_error(format!(
            "{} states and {} derivatives",
            plan.states.len(),
            plan.derivatives.len()
        )));
    }
    for (&s, &d) in plan.states.iter().zip(&plan.derivatives) {
        if s.index() >= n || d.index() >= n || dae.scalars[s.index()].derivative != Some(d) {
            return Err(plan_error(format!(
                "state {} does not have {} as its derivative",
                name(s),
                name(d)
            )));
        }
    }
    Ok(())
}

/// The scalars known before the plan runs: aliases, inputs, constants, parameters and
/// discrete variables.
fn known_before_plan(dae: &Dae) -> Vec<bool> {
    let n = dae.scalars.len();
    let mut known = vec![false; n];
    for (k, s) in dae.scalars.iter().enumerate() {
        known[k] = s.alias.is_some()
            || s.input
            || matches!(
                s.kind,
                ScalarKind::Constant | ScalarKind::Parameter | ScalarKind::Discrete
            );
    }
    known
}
