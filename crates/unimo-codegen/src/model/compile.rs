//! `compile`: the DAE and its causal plan to a [`CompiledModel`], one tape per concern
//! (parameters, start values, the plan's steps, zero crossings, samples, `when`
//! clauses, assertions and aliases), in a fixed order so the registers are stable.

use super::compile_external::{compile_collision, compile_objects, symbolic_jacobian};
use super::compile_initial::{compile_fixed_constraints, compile_initial};
use super::{Action, CompiledBlock, CompiledModel, CompiledStateSet, CompiledStep, CompiledWhen};
use crate::tape::{Compiler, Layout, Op, Reg, Tape};
use rustc_hash::FxHashMap as HashMap;
use unimo_dae::dae::{Dae, ScalarKind, WhenAction};
use unimo_dae::events::{zero_crossings_except, Crossings};
use unimo_dae::expr::{ExprId, Node, ScalarId};
use unimo_dae::plan::{Plan, PlanStep};

/// Each expression's position in `es`.
fn index_of(es: &[ExprId]) -> HashMap<ExprId, u32> {
    es.iter().enumerate().map(|(k, &e)| (e, k as u32)).collect()
}

/// An expression as text for messages: cut at 300 bytes (a shared expression written
/// as a tree can be exponentially long).
pub(super) fn show(dae: &Dae, e: ExprId) -> String {
    dae.arena.to_short_string(e, &|s| dae.name(s), 300)
}

/// Output registers of the collision world, known to every tape: per body its force
/// and torque, and the world's two gaps.
fn external_outputs(dae: &Dae, c: &mut Compiler<'_>) -> (Vec<[Reg; 6]>, [Reg; 2]) {
    let external = |c: &mut Compiler<'_>, site: u32, out: u32| -> Reg {
        let reg = c.temp_public();
        if let Some(e) = dae.arena.find(Node::External(site, out)) {
            c.shared.insert(e, reg);
        }
        reg
    };
    let body_outputs: Vec<[Reg; 6]> = (0..dae.collision.len() as u32)
        .map(|k| std::array::from_fn(|o| external(c, k, o as u32)))
        .collect();
    let gaps: [Reg; 2] =
        std::array::from_fn(|o| external(c, unimo_dae::dae::COLLISION_GAPS_SITE, o as u32));
    (body_outputs, gaps)
}

/// The parameters' tape, the free parameters (register and name) and the tape of the
/// parameters that depend on them.
fn compile_parameters(
    dae: &Dae,
    layout: Layout,
    c: &mut Compiler<'_>,
) -> (Tape, Vec<(Reg, String)>, Tape) {
    let mut parameters = Tape::default();
    let mut memo = HashMap::default();
    // `parameter Real k(fixed = false)` without a binding is an unknown of the
    // initialization (its start value is the first guess); the parameters that depend
    // on it are computed again by `dependent_parameters` while it is solved for.
    let free = |p: ScalarId| dae.scalar(p).fixed == Some(false) && dae.scalar(p).binding.is_none();
    let mut free_parameters = Vec::new();
    let mut dependent_parameters = Tape::default();
    let mut dependent_memo = HashMap::default();
    for p in parameter_order(dae) {
        let value = dae.scalar(p).binding.or(dae.scalar(p).start);
        if let Some(v) = value {
            c.assign(p, v, &mut parameters, &mut memo);
        }
        if free(p) {
            free_parameters.push((layout.var(p), dae.name(p)));
        } else if let Some(v) = value {
            c.assign(p, v, &mut dependent_parameters, &mut dependent_memo);
        }
    }
    if free_parameters.is_empty() {
        dependent_parameters = Tape::default();
    }
    (parameters, free_parameters, dependent_parameters)
}

/// The start values of everything but parameters, constants and aliases.
fn compile_starts(dae: &Dae, c: &mut Compiler<'_>) -> Tape {
    let mut starts = Tape::default();
    let mut memo = HashMap::default();
    for s in dae.ids() {
        let sc = dae.scalar(s);
        if matches!(sc.kind, ScalarKind::Parameter | ScalarKind::Constant) || sc.alias.is_some() {
            continue;
        }
        if let Some(st) = sc.start {
            c.assign(s, st, &mut starts, &mut memo);
        }
    }
    starts
}

/// The plan's steps, and the equation defining each variable they compute.
fn compile_steps(
    dae: &Dae,
    plan: &Plan,
    layout: Layout,
    c: &mut Compiler<'_>,
) -> (Vec<CompiledStep>, HashMap<Reg, unimo_dae::dae::EqId>) {
    let mut steps: Vec<CompiledStep> = Vec::new();
    let mut definitions = HashMap::default();
    let mut memo = HashMap::default();
    for step in &plan.steps {
        match step {
            PlanStep::Assign { var, eq, .. } => {
                definitions.insert(layout.var(*var), *eq);
            }
            PlanStep::Block(b) => {
                if let Some(&eq) = b.equations.first() {
                    for &v in b
                        .iteration_vars
                        .iter()
                        .chain(b.inner.iter().map(|(v, _)| v))
                    {
                        definitions.insert(layout.var(v), eq);
                    }
                }
            }
        }
        match step {
            PlanStep::Assign { var, value, .. } => {
                // Consecutive assignments share one tape (one dispatch loop) and its
                // memo: a subexpression is computed once per tape (every value it
                // reads is assigned before it and not again within the pass).
                if !matches!(steps.last(), Some(CompiledStep::Explicit(_))) {
                    steps.push(CompiledStep::Explicit(Tape::default()));
                    memo.clear();
                }
                let Some(CompiledStep::Explicit(t)) = steps.last_mut() else {
                    unreachable!("pushed above")
                };
                c.assign(*var, *value, t, &mut memo);
            }
            PlanStep::Block(b) => steps.push(CompiledStep::Block(compile_block(dae, b, layout, c))),
        }
    }
    (steps, definitions)
}

/// One Newton block: its residual tape (inner assignments, then residuals) and its
/// Jacobian tape.
fn compile_block(
    dae: &Dae,
    b: &unimo_dae::plan::Block,
    layout: Layout,
    c: &mut Compiler<'_>,
) -> CompiledBlock {
    let mut rt = Tape::default();
    let mut memo = HashMap::default();
    for &(v, e) in &b.inner {
        c.assign(v, e, &mut rt, &mut memo);
    }
    let residuals = b
        .residuals
        .iter()
        .map(|&r| c.expr(r, &mut rt, &mut memo))
        .collect();
    let mut jt = Tape::default();
    let mut memo = HashMap::default();
    let jacobian = b
        .jacobian
        .iter()
        .map(|&j| c.expr(j, &mut jt, &mut memo))
        .collect();
    let mut relations: Vec<u32> = rt
        .ops
        .iter()
        .filter_map(|o| match o {
            Op::RelEvent(.., k) => Some(*k),
            _ => None,
        })
        .collect();
    relations.sort_unstable();
    relations.dedup();
    CompiledBlock {
        relations,
        iteration: b.iteration_vars.iter().map(|&v| layout.var(v)).collect(),
        residual_tape: rt,
        residuals,
        jacobian_tape: jt,
        jacobian,
        linear: b.linear,
        names: b.iteration_vars.iter().map(|&v| dae.name(v)).collect(),
    }
}

/// The zero crossings in compiled form.
struct Roots {
    tape: Tape,
    /// The operands of each root function.
    roots: Vec<(Reg, Reg)>,
    ops: Vec<unimo_dae::expr::RelOp>,
    names: Vec<String>,
}

/// The relations' operands, then each held rounding's two bounds.
fn compile_roots(dae: &Dae, zc: &Crossings, c: &mut Compiler<'_>) -> Roots {
    let mut roots_tape = Tape::default();
    let mut memo = HashMap::default();
    let mut roots = Vec::new();
    let mut root_ops = Vec::new();
    for &r in &zc.relations {
        let Node::Rel(op, a, b) = dae.arena.node(r) else {
            unreachable!("zero crossings are relations")
        };
        let ra = c.expr(a, &mut roots_tape, &mut memo);
        let rb = c.expr(b, &mut roots_tape, &mut memo);
        roots.push((ra, rb));
        root_ops.push(op);
    }
    for (k, &h) in zc.held.iter().enumerate() {
        let (argument, lo, hi) = c.held_crossings(h, k as u32, &mut roots_tape, &mut memo);
        roots.push((argument, lo));
        roots.push((argument, hi));
    }
    let mut root_names: Vec<String> = zc.relations.iter().map(|&r| show(dae, r)).collect();
    for &h in &zc.held {
        let text = show(dae, h);
        root_names.push(format!("{text} (its lower bound)"));
        root_names.push(format!("{text} (its upper bound)"));
    }
    Roots {
        tape: roots_tape,
        roots,
        ops: root_ops,
        names: root_names,
    }
}

/// The samples' start and interval registers; their tape is appended to the
/// parameters' (sample arguments are parameter expressions).
fn compile_samples(
    dae: &Dae,
    zc: &Crossings,
    c: &mut Compiler<'_>,
    parameters: &mut Tape,
) -> Vec<(Reg, Reg)> {
    let mut samples = Vec::new();
    let mut sample_memo = HashMap::default();
    let mut sample_tape = Tape::default();
    for &s in &zc.samples {
        let Node::Sample(a, b) = dae.arena.node(s) else {
            unreachable!("samples")
        };
        let ra = c.expr(a, &mut sample_tape, &mut sample_memo);
        let rb = c.expr(b, &mut sample_tape, &mut sample_memo);
        samples.push((ra, rb));
    }
    // Sample arguments are parameter expressions: computed with the parameters.
    parameters.ops.extend(sample_tape.ops);
    samples
}

/// The `when` clauses: their tape, branches, and every condition register (sorted).
fn compile_whens(
    dae: &Dae,
    layout: Layout,
    c: &mut Compiler<'_>,
) -> (Tape, Vec<CompiledWhen>, Vec<Reg>) {
    let mut when_tape = Tape::default();
    let mut memo = HashMap::default();
    let mut whens = Vec::new();
    let mut conditions = Vec::new();
    for w in &dae.whens {
        let mut branches = Vec::new();
        for b in &w.branches {
            let conds: Vec<Reg> = b
                .conditions
                .iter()
                .map(|&e| c.expr(e, &mut when_tape, &mut memo))
                .collect();
            conditions.extend(&conds);
            let mut actions = Vec::new();
            for (a, _) in &b.actions {
                actions.push(match a {
                    WhenAction::Assign { target, value } => Action::Assign {
                        target: layout.var(*target),
                        value: c.expr(*value, &mut when_tape, &mut memo),
                    },
                    WhenAction::Reinit { state, value } => Action::Reinit {
                        target: layout.var(*state),
                        value: c.expr(*value, &mut when_tape, &mut memo),
                    },
                    WhenAction::Terminate { message } => Action::Terminate(message.clone()),
                    WhenAction::Assert { condition, message } => Action::Assert {
                        condition: c.expr(*condition, &mut when_tape, &mut memo),
                        message: message.clone(),
                    },
                });
            }
            branches.push((conds, actions));
        }
        whens.push(CompiledWhen { branches });
    }
    conditions.sort();
    conditions.dedup();
    (when_tape, whens, conditions)
}

/// The assertions: their tape and (condition, message, warning) each.
fn compile_assertions(dae: &Dae, c: &mut Compiler<'_>) -> (Tape, Vec<(Reg, String, bool)>) {
    let mut assert_tape = Tape::default();
    let mut memo = HashMap::default();
    let assertions = dae
        .assertions
        .iter()
        .map(|a| {
            (
                c.expr_no_event(a.condition, &mut assert_tape, &mut memo),
                a.message.clone(),
                a.warning,
            )
        })
        .collect();
    (assert_tape, assertions)
}

/// The invariants: their tape and (value, condition) each; the condition with event
/// semantics (its relations hold their values between events, like the if-equation's).
fn compile_invariants(dae: &Dae, c: &mut Compiler<'_>) -> (Tape, Vec<(Reg, Reg)>) {
    let mut tape = Tape::default();
    // One memo per semantics: a relation shared by both is compiled twice.
    let (mut values, mut conditions) = (HashMap::default(), HashMap::default());
    let invariants = dae
        .invariants
        .iter()
        .map(|i| {
            (
                c.expr_no_event(i.value, &mut tape, &mut values),
                c.expr(i.active, &mut tape, &mut conditions),
            )
        })
        .collect();
    (tape, invariants)
}

/// The values the `delay` sites record: their tape and registers.
fn compile_delays(dae: &Dae, c: &mut Compiler<'_>) -> (Tape, Vec<Reg>) {
    let mut tape = Tape::default();
    let mut memo = HashMap::default();
    let inputs = dae
        .delays
        .iter()
        .map(|d| c.expr_no_event(d.input, &mut tape, &mut memo))
        .collect();
    (tape, inputs)
}

/// The aliases' tape.
fn compile_aliases(dae: &Dae, c: &mut Compiler<'_>) -> Tape {
    let mut alias_tape = Tape::default();
    let mut memo = HashMap::default();
    for s in dae.ids() {
        if let Some(v) = dae.scalar(s).alias {
            c.assign(s, v, &mut alias_tape, &mut memo);
        }
    }
    alias_tape
}

/// The dynamic state sets.
fn compile_state_sets(
    dae: &Dae,
    plan: &Plan,
    layout: Layout,
    c: &mut Compiler<'_>,
) -> Vec<CompiledStateSet> {
    plan.state_sets
        .iter()
        .map(|set| {
            let mut jacobian_tape = Tape::default();
            let mut memo = HashMap::default();
            let jacobian = set
                .jacobian
                .iter()
                .map(|&e| c.expr(e, &mut jacobian_tape, &mut memo))
                .collect();
            CompiledStateSet {
                states: set
                    .states
                    .iter()
                    .map(|s| {
                        plan.states
                            .iter()
                            .position(|x| x == s)
                            .expect("a set's states are states")
                    })
                    .collect(),
                candidates: set.candidates.iter().map(|&x| layout.var(x)).collect(),
                selectors: set.selectors.iter().map(|&a| layout.var(a)).collect(),
                jacobian_tape,
                jacobian,
                rows: set.equations.len(),
                candidate_names: set.candidates.iter().map(|&x| dae.name(x)).collect(),
                initial: set.initial.clone(),
            }
        })
        .collect()
}

/// The discrete variables (registers) that are not aliases.
fn discretes(dae: &Dae, layout: Layout) -> Vec<Reg> {
    dae.ids()
        .filter(|&s| dae.scalar(s).kind == ScalarKind::Discrete && dae.scalar(s).alias.is_none())
        .map(|s| layout.var(s))
        .collect()
}

/// Every variable that is not a parameter or constant, by name.
fn outputs(dae: &Dae, layout: Layout) -> Vec<(String, Reg)> {
    dae.ids()
        .filter(|&s| {
            !matches!(
                dae.scalar(s).kind,
                ScalarKind::Parameter | ScalarKind::Constant
            )
        })
        .map(|s| (dae.name(s), layout.var(s)))
        .collect()
}

/// The states' nominal values (1 where none is given).
fn nominals(dae: &Dae, plan: &Plan) -> Vec<f64> {
    plan.states
        .iter()
        .map(|&s| {
            dae.scalar(s)
                .nominal
                .and_then(|e| dae.arena.as_const(e))
                .map(f64::abs)
                .unwrap_or(1.0)
        })
        .collect()
}

pub fn compile(dae: &Dae, plan: &Plan) -> CompiledModel {
    let layout = Layout::new(dae.scalars.len());
    let zc = zero_crossings_except(dae, &plan.pruned);
    let relation_index = index_of(&zc.relations);
    let sample_index = index_of(&zc.samples);
    let held_index = index_of(&zc.held);
    let mut c = Compiler::new(&dae.arena, layout, &relation_index, &sample_index);
    c.held_index = Some(&held_index);
    let (body_outputs, gaps) = external_outputs(dae, &mut c);
    let (mut parameters, free_parameters, dependent_parameters) =
        compile_parameters(dae, layout, &mut c);
    let collision = compile_collision(dae, plan, &mut c, body_outputs, gaps);
    let (objects_tape, objects) = compile_objects(dae, &mut c);
    let starts = compile_starts(dae, &mut c);
    let (steps, definitions) = compile_steps(dae, plan, layout, &mut c);
    let roots = compile_roots(dae, &zc, &mut c);
    let samples = compile_samples(dae, &zc, &mut c, &mut parameters);
    let (when_tape, whens, conditions) = compile_whens(dae, layout, &mut c);
    let (assert_tape, assertions) = compile_assertions(dae, &mut c);
    let (invariant_tape, invariants) = compile_invariants(dae, &mut c);
    let alias_tape = compile_aliases(dae, &mut c);
    let (delay_tape, delay_inputs) = compile_delays(dae, &mut c);
    let initial = compile_initial(dae, plan, &mut c);
    let (fixed_constraints_tape, fixed_constraints) = compile_fixed_constraints(dae, &mut c);
    // External objects have no symbolic derivatives: finite differences then.
    let jacobian = if collision.is_some() {
        None
    } else {
        symbolic_jacobian(dae, plan, &mut c)
    };
    let state_sets = compile_state_sets(dae, plan, layout, &mut c);
    let n_registers = c.n_registers();
    let constants = std::mem::take(&mut c.constants);
    let m = CompiledModel {
        constants,
        layout,
        n_registers,
        parameters,
        starts,
        steps,
        roots_tape: roots.tape,
        roots: roots.roots,
        root_ops: roots.ops,
        root_names: roots.names,
        n_held: zc.held.len(),
        definitions,
        samples,
        when_tape,
        whens,
        conditions,
        assert_tape,
        assertions,
        invariant_tape,
        invariants,
        alias_tape,
        jacobian,
        states: plan.states.iter().map(|&s| layout.var(s)).collect(),
        derivatives: plan.derivatives.iter().map(|&s| layout.var(s)).collect(),
        discretes: discretes(dae, layout),
        state_names: plan.states.iter().map(|&s| dae.name(s)).collect(),
        outputs: outputs(dae, layout),
        nominals: nominals(dae, plan),
        fixed: plan
            .states
            .iter()
            .map(|&s| dae.scalar(s).fixed == Some(true))
            .collect(),
        free_parameters,
        dependent_parameters,
        initial_tape: initial.tape,
        initial_residuals: initial.residuals,
        initial_names: initial.names,
        initial_orders: initial.orders,
        initial_parameter_only: initial.parameter_only,
        fixed_constraints_tape,
        fixed_constraints,
        initial_assigned: initial.assigned,
        initial_pre_assigned: initial.pre_assigned,
        ops_total: 0,
        relation_held: Vec::new(),
        collision,
        objects_tape,
        objects,
        delay_tape,
        delay_inputs,
        uses_terminal: dae.uses_terminal,
        state_sets,
        equations_read_initial: equations_hold(dae, Node::Initial),
        uses_homotopy: equations_hold(dae, Node::HomotopyStart),
        native_rhs: None,
    };
    finish(m)
}

/// The fields computed from the rest: which relations are held, the size; checked in
/// debug builds.
fn finish(mut m: CompiledModel) -> CompiledModel {
    m.relation_held = held_relations(&m);
    if cfg!(debug_assertions) {
        if let Err(e) = crate::verify::verify_compiled(&m) {
            panic!("{e}");
        }
    }
    m.ops_total = m
        .steps
        .iter()
        .map(|s| match s {
            CompiledStep::Explicit(t) => t.ops.len(),
            CompiledStep::Block(b) => b.residual_tape.ops.len() + b.jacobian_tape.ops.len(),
        })
        .sum();
    m
}

/// Parameters in dependency order (a binding is computed after what it uses).
fn parameter_order(dae: &Dae) -> Vec<ScalarId> {
    let mut order = Vec::new();
    let mut state = vec![0u8; dae.scalars.len()];
    for s in dae.ids() {
        if !matches!(
            dae.scalar(s).kind,
            ScalarKind::Parameter | ScalarKind::Constant
        ) {
            continue;
        }
        let mut stack = vec![(s, false)];
        while let Some((x, done)) = stack.pop() {
            if done {
                if state[x.index()] != 2 {
                    state[x.index()] = 2;
                    order.push(x);
                }
                continue;
            }
            if state[x.index()] != 0 {
                continue;
            }
            state[x.index()] = 1;
            stack.push((x, true));
            if let Some(b) = dae.scalar(x).binding {
                for d in dae.arena.vars(b) {
                    if state[d.index()] == 0
                        && matches!(
                            dae.scalar(d).kind,
                            ScalarKind::Parameter | ScalarKind::Constant
                        )
                    {
                        stack.push((d, false));
                    }
                }
            }
        }
    }
    order
}
/// Whether an equation of the model reads `initial()`.
/// Whether some equation holds the leaf `leaf` (`initial()`, the homotopy flag).
fn equations_hold(dae: &Dae, leaf: Node) -> bool {
    let mut seen = std::collections::HashSet::new();
    let mut stack: Vec<ExprId> = dae.equations.iter().flat_map(|e| [e.lhs, e.rhs]).collect();
    while let Some(e) = stack.pop() {
        if !seen.insert(e) {
            continue;
        }
        if dae.arena.node(e) == leaf {
            return true;
        }
        stack.extend(dae.arena.children(e));
    }
    false
}

/// Which relations are compiled with event semantics in some tape the runtime runs.
fn held_relations(m: &CompiledModel) -> Vec<bool> {
    let mut held = vec![false; m.root_ops.len()];
    let mut tapes: Vec<&Tape> = vec![
        &m.when_tape,
        &m.alias_tape,
        &m.initial_tape,
        &m.starts,
        &m.parameters,
    ];
    for step in &m.steps {
        match step {
            CompiledStep::Explicit(t) => tapes.push(t),
            CompiledStep::Block(b) => tapes.extend([&b.residual_tape, &b.jacobian_tape]),
        }
    }
    if let Some((t, _)) = &m.jacobian {
        tapes.push(t);
    }
    for tape in tapes {
        for op in &tape.ops {
            if let Op::RelEvent(.., k) = op {
                held[*k as usize] = true;
            }
        }
    }
    held
}
