//! The compiled model: every expression the runtime evaluates, compiled to tapes over
//! one register file: parameters, start values, the plan's steps (explicit assignments
//! and Newton blocks with their symbolic Jacobians), zero crossings, `when` conditions
//! and actions, assertions and alias outputs.

use crate::collision::{CollisionBodyRegs, CollisionModel};
use crate::tape::{Compiler, EventState, Layout, Op, Reg, Tape};
use rustc_hash::FxHashMap as HashMap;
use unimo_dae::dae::{Dae, ScalarKind, WhenAction};
use unimo_dae::events::zero_crossings;
use unimo_dae::expr::{ExprId, Node, ScalarId};
use unimo_dae::plan::{Plan, PlanStep};

/// A Newton block in compiled form.
#[derive(Clone, Debug)]
pub struct CompiledBlock {
    pub iteration: Vec<Reg>,
    /// Inner assignments then residuals.
    pub residual_tape: Tape,
    pub residuals: Vec<Reg>,
    pub jacobian_tape: Tape,
    /// Row-major, `residuals.len() x iteration.len()`.
    pub jacobian: Vec<Reg>,
    pub linear: bool,
    /// The residuals hold relations that are decided at events.
    pub has_relations: bool,
    /// Names of the iteration variables (for errors).
    pub names: Vec<String>,
}

#[derive(Clone, Debug)]
pub enum CompiledStep {
    Explicit(Tape),
    Block(CompiledBlock),
}

/// A compiled `when` action.
#[derive(Clone, Debug)]
pub enum Action {
    Assign { target: Reg, value: Reg },
    Reinit { target: Reg, value: Reg },
    Terminate(String),
    Assert { condition: Reg, message: String },
}

#[derive(Clone, Debug)]
pub struct CompiledWhen {
    /// Per branch: condition registers and actions.
    pub branches: Vec<(Vec<Reg>, Vec<Action>)>,
}

/// The compiled symbolic Jacobian: its tape and its nonzeros (row, column, register).
pub type SymbolicJacobian = (Tape, Vec<(usize, usize, Reg)>);

/// Everything the simulator runs.
#[derive(Clone, Debug, Default)]
pub struct CompiledModel {
    pub layout: Layout,
    /// Registers holding constants, written once before anything runs.
    pub constants: Vec<(Reg, f64)>,
    pub n_registers: usize,
    pub parameters: Tape,
    pub starts: Tape,
    pub steps: Vec<CompiledStep>,
    /// Zero-crossing functions: `g_k = reg_a - reg_b` of relation k.
    pub roots_tape: Tape,
    pub roots: Vec<(Reg, Reg)>,
    /// The relation each of the first `root_ops.len()` roots belongs to (its kind
    /// decides the post-crossing value). The roots after them come in pairs, the lower
    /// and upper bound of held rounding `j` (roots `n + 2j`, `n + 2j + 1`).
    pub root_ops: Vec<unimo_dae::expr::RelOp>,
    /// Every root in Modelica syntax (for messages), e.g. `h <= 0` or `floor(time / 0.1)`.
    pub root_names: Vec<String>,
    /// Number of held roundings (`floor`, `integer`, `mod`, ... with events).
    pub n_held: usize,
    /// The equation that computes each scalar's register (explicit assignments, and
    /// a block's first equation for its unknowns), for errors naming the culprit.
    pub definitions: HashMap<Reg, unimo_dae::dae::EqId>,
    /// `sample(start, interval)`: registers of start and interval.
    pub samples: Vec<(Reg, Reg)>,
    /// Conditions and action values of every `when`, computed in event mode.
    pub when_tape: Tape,
    pub whens: Vec<CompiledWhen>,
    /// Every distinct condition register (their previous values decide edges).
    pub conditions: Vec<Reg>,
    pub assert_tape: Tape,
    pub assertions: Vec<(Reg, String, bool)>,
    pub alias_tape: Tape,
    pub states: Vec<Reg>,
    pub derivatives: Vec<Reg>,
    pub discretes: Vec<Reg>,
    pub state_names: Vec<String>,
    /// Scalars written to results: name and register.
    pub outputs: Vec<(String, Reg)>,
    /// The symbolic Jacobian d der(x) / dx when the plan is fully explicit (no Newton
    /// blocks): its tape (run after the plan) and its nonzero entries (row, column,
    /// register). `None`: the solvers use finite differences.
    pub jacobian: Option<SymbolicJacobian>,
    /// Nominal values of the states (for tolerances).
    pub nominals: Vec<f64>,
    /// Start attributes: which states have `fixed = true`.
    pub fixed: Vec<bool>,
    /// Parameters with `fixed = false` and no binding: solved for by the initial
    /// equations (register, name).
    pub free_parameters: Vec<(Reg, String)>,
    /// The other parameters, computed again from the free ones.
    pub dependent_parameters: Tape,
    /// Initial equations as residual registers, computed by `initial_tape` after steps.
    /// The tape also assigns the discrete variables an initial equation or initial
    /// algorithm gives explicitly (`count = integer(...)`), in their order.
    pub initial_tape: Tape,
    pub initial_residuals: Vec<Reg>,
    /// Per initial residual: the equation as text (`x = 0.6 (fixed start)` for a fixed
    /// start), and for a fixed start of a variable the plan computes, the first
    /// equation of the step computing it (the constraint a contradiction runs through).
    pub initial_names: Vec<(String, Option<String>)>,
    /// Per initial residual: how many derivatives the fixed variable has above it
    /// (`u32::MAX` for an initial equation). With more equations than unknowns the
    /// independent ones are taken in decreasing order: positions before velocities.
    pub initial_orders: Vec<u32>,
    /// Per initial residual: it reads parameters and constants only (the free
    /// parameters' own equations, solved before the rest).
    pub initial_parameter_only: Vec<bool>,
    /// Constraints (equations index reduction differentiated) whose every variable has
    /// a fixed start: checked at the start values before anything is solved. The tape
    /// computes, per constraint, its two sides.
    pub fixed_constraints_tape: Tape,
    pub fixed_constraints: Vec<FixedConstraint>,
    /// Discrete variables `initial_tape` assigns (register, name).
    pub initial_assigned: Vec<(Reg, String)>,
    /// The discrete variables whose `pre` values `initial_tape` sets (`initial
    /// equation pre(y) = y0`): at initialization, where their `when` is not active,
    /// they equal those values.
    pub initial_pre_assigned: Vec<Reg>,
    pub ops_total: usize,
    /// Relations whose value some tape holds between events (a relation that only an
    /// assertion reads is compared literally and never held).
    pub relation_held: Vec<bool>,
    /// The collision world, when the model has collision bodies.
    pub collision: Option<CollisionModel>,
    /// External objects (tables): the tape computing their constructors' arguments
    /// from the parameters, and where each object's arguments are.
    pub objects_tape: Tape,
    pub objects: Vec<ObjectSite>,
    /// The model reads `terminal()`: the run ends with a terminal event.
    pub uses_terminal: bool,
    /// Dynamically selected state sets (`unimo_dae::plan::StateSet`).
    pub state_sets: Vec<CompiledStateSet>,
    /// Some equation reads `initial()`: after initialization the simulator runs one
    /// more event iteration at the start time with it false.
    pub equations_read_initial: bool,
}

/// A constraint all of whose variables have fixed start values.
#[derive(Clone, Debug)]
pub struct FixedConstraint {
    pub lhs: Reg,
    pub rhs: Reg,
    /// The equation as text.
    pub text: String,
    /// Its variables (name and register).
    pub variables: Vec<(String, Reg)>,
}

/// A state set in compiled form: `jacobian_tape` (run after the plan) fills
/// `jacobian` (`rows x candidates.len()`, row-major).
#[derive(Clone, Debug)]
pub struct CompiledStateSet {
    /// Index of each set state in [`CompiledModel::states`].
    pub states: Vec<usize>,
    pub candidates: Vec<Reg>,
    /// `k x n`, row-major.
    pub selectors: Vec<Reg>,
    pub jacobian_tape: Tape,
    pub jacobian: Vec<Reg>,
    pub rows: usize,
    pub candidate_names: Vec<String>,
    pub initial: Vec<usize>,
}

impl CompiledModel {
    /// Instructions evaluated by one pass of the plan (explicit steps, and per block
    /// one residual and one Jacobian evaluation): the size of the compiled model.
    pub fn plan_ops(&self) -> usize {
        self.steps
            .iter()
            .map(|s| match s {
                CompiledStep::Explicit(t) => t.ops.len(),
                CompiledStep::Block(b) => b.residual_tape.ops.len() + b.jacobian_tape.ops.len(),
            })
            .sum()
    }

    /// A register file with the constants in place.
    pub fn new_registers(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.n_registers];
        for &(reg, v) in &self.constants {
            r[reg as usize] = v;
        }
        r
    }

    pub fn new_event_state(&self) -> EventState {
        EventState {
            event_mode: false,
            relations: vec![0.0; self.root_ops.len()],
            forced: vec![None; self.root_ops.len()],
            held: vec![0.0; self.n_held],
            held_forced: vec![None; self.n_held],
            sticky: false,
            samples: vec![0.0; self.samples.len()],
            collision: self.collision.as_ref().map(|_| Box::default()),
            objects: Vec::new(),
        }
    }
}

/// An external object's constructor arguments, in registers (see
/// `unimo_dae::external::ExternalObjectSite`).
#[derive(Clone, Debug)]
pub struct ObjectSite {
    pub kind: unimo_dae::external::ObjectKind,
    pub table: Vec<Reg>,
    pub rows: usize,
    pub cols: usize,
    pub columns: Vec<Reg>,
    /// Smoothness, extrapolation, start time, shift time, time events.
    pub settings: [Reg; 5],
}

fn compile_objects(dae: &Dae, c: &mut Compiler<'_>) -> (Tape, Vec<ObjectSite>) {
    let mut tape = Tape::default();
    let mut memo = HashMap::default();
    let sites = dae
        .external_objects
        .iter()
        .map(|o| {
            let mut regs = |es: &[ExprId], tape: &mut Tape| -> Vec<Reg> {
                es.iter().map(|&e| c.expr(e, tape, &mut memo)).collect()
            };
            let table = regs(&o.table, &mut tape);
            let columns = regs(&o.columns, &mut tape);
            let s = regs(
                &[
                    o.smoothness,
                    o.extrapolation,
                    o.start_time,
                    o.shift_time,
                    o.time_events,
                ],
                &mut tape,
            );
            ObjectSite {
                kind: o.kind,
                table,
                rows: o.rows,
                cols: o.cols,
                columns,
                settings: [s[0], s[1], s[2], s[3], s[4]],
            }
        })
        .collect();
    (tape, sites)
}

impl CompiledModel {
    /// Runs the parameters' tape; with external objects, builds them from the
    /// parameters and runs it again (parameters may read the objects: a friction
    /// table's value at zero speed).
    pub fn run_parameters(&self, regs: &mut [f64], ev: &mut EventState) -> Result<(), String> {
        self.parameters.run(regs, ev);
        if self.objects.is_empty() {
            return Ok(());
        }
        self.objects_tape.run(regs, ev);
        let values = |rs: &[Reg]| -> Vec<f64> { rs.iter().map(|&r| regs[r as usize]).collect() };
        let mut objects = Vec::with_capacity(self.objects.len());
        for site in &self.objects {
            let data = values(&site.table);
            let columns = values(&site.columns);
            let s = values(&site.settings);
            let object = crate::tables::TableObject::new(&crate::tables::TableArgs {
                kind: site.kind,
                data: &data,
                rows: site.rows,
                cols: site.cols,
                columns: &columns,
                smoothness: s[0],
                extrapolation: s[1],
                start_time: s[2],
                shift_time: s[3],
                time_events: s[4],
            })?;
            objects.push(object);
        }
        ev.objects = objects;
        self.parameters.run(regs, ev);
        Ok(())
    }
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

pub fn compile(dae: &Dae, plan: &Plan) -> CompiledModel {
    let layout = Layout::new(dae.scalars.len());
    let zc = zero_crossings(dae);
    let relation_index: HashMap<ExprId, u32> = zc
        .relations
        .iter()
        .enumerate()
        .map(|(k, &e)| (e, k as u32))
        .collect();
    let sample_index: HashMap<ExprId, u32> = zc
        .samples
        .iter()
        .enumerate()
        .map(|(k, &e)| (e, k as u32))
        .collect();
    let held_index: HashMap<ExprId, u32> = zc
        .held
        .iter()
        .enumerate()
        .map(|(k, &e)| (e, k as u32))
        .collect();
    let mut c = Compiler::new(&dae.arena, layout, &relation_index, &sample_index);
    c.held_index = Some(&held_index);
    // Output registers of the collision world, known to every tape.
    let external = |c: &mut Compiler<'_>, site: u32, out: u32| -> Reg {
        let reg = c.temp_public();
        if let Some(e) = dae.arena.find(Node::External(site, out)) {
            c.shared.insert(e, reg);
        }
        reg
    };
    let body_outputs: Vec<[Reg; 6]> = (0..dae.collision.len() as u32)
        .map(|k| std::array::from_fn(|o| external(&mut c, k, o as u32)))
        .collect();
    let gaps: [Reg; 2] =
        std::array::from_fn(|o| external(&mut c, unimo_dae::dae::COLLISION_GAPS_SITE, o as u32));

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
    let collision = compile_collision(dae, plan, &mut c, body_outputs, gaps);
    let (objects_tape, objects) = compile_objects(dae, &mut c);
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

    let mut steps: Vec<CompiledStep> = Vec::new();
    let mut definitions = HashMap::default();
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
                // Consecutive assignments share one tape (one dispatch loop).
                if !matches!(steps.last(), Some(CompiledStep::Explicit(_))) {
                    steps.push(CompiledStep::Explicit(Tape::default()));
                }
                let Some(CompiledStep::Explicit(t)) = steps.last_mut() else {
                    unreachable!("pushed above")
                };
                let mut memo = HashMap::default();
                c.assign(*var, *value, t, &mut memo);
            }
            PlanStep::Block(b) => {
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
                let has_relations = rt.ops.iter().any(|o| matches!(o, Op::RelEvent(..)));
                steps.push(CompiledStep::Block(CompiledBlock {
                    has_relations,
                    iteration: b.iteration_vars.iter().map(|&v| layout.var(v)).collect(),
                    residual_tape: rt,
                    residuals,
                    jacobian_tape: jt,
                    jacobian,
                    linear: b.linear,
                    names: b.iteration_vars.iter().map(|&v| dae.name(v)).collect(),
                }));
            }
        }
    }

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
    // Texts for messages: cut at 300 bytes (a shared expression written as a tree
    // can be exponentially long).
    let show = |e: ExprId| dae.arena.to_short_string(e, &|s| dae.name(s), 300);
    let mut root_names: Vec<String> = zc.relations.iter().map(|&r| show(r)).collect();
    for &h in &zc.held {
        let text = show(h);
        root_names.push(format!("{text} (its lower bound)"));
        root_names.push(format!("{text} (its upper bound)"));
    }
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

    let mut alias_tape = Tape::default();
    let mut memo = HashMap::default();
    for s in dae.ids() {
        if let Some(v) = dae.scalar(s).alias {
            c.assign(s, v, &mut alias_tape, &mut memo);
        }
    }

    // Initial equations, plus `v = start` for every unknown that is not a state and
    // has `fixed = true` (states with fixed start are simply not free).
    let mut initial_tape = Tape::default();
    let mut memo = HashMap::default();
    let mut pairs: Vec<(ExprId, ExprId)> = dae
        .initial_equations
        .iter()
        .map(|e| (e.lhs, e.rhs))
        .collect();
    let state_set: std::collections::HashSet<ScalarId> = plan.states.iter().copied().collect();
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
    let mut initial_regs = Vec::new();
    let mut initial_names = Vec::new();
    let mut initial_orders = Vec::new();
    let mut initial_parameter_only = Vec::new();
    let selectors: std::collections::HashSet<ScalarId> = plan
        .state_sets
        .iter()
        .flat_map(|s| s.selectors.iter().copied())
        .collect();
    let mut step_equations: HashMap<ScalarId, Vec<unimo_dae::dae::EqId>> = HashMap::default();
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
    let mut initial_assigned = Vec::new();
    let mut initial_pre_assigned = Vec::new();
    for (l, r) in pairs.drain(..) {
        // `d = expr` for a discrete `d` that `expr` does not mention is an assignment
        // (what an initial algorithm's `d := expr` lowers to): executed, not solved.
        // `pre(d) = expr` (`initial equation pre(y) = y_start`) sets the value `d` has
        // before the initial event.
        let (target, pre) = match dae.arena.node(l) {
            unimo_dae::expr::Node::Var(d) => (Some(d), false),
            unimo_dae::expr::Node::Pre(d) => (Some(d), true),
            _ => (None, false),
        };
        if let Some(d) = target {
            if dae.scalar(d).kind == ScalarKind::Discrete
                && dae.scalar(d).alias.is_none()
                && !dae.arena.vars(r).contains(&d)
            {
                let rr = c.expr(r, &mut initial_tape, &mut memo);
                let reg = if pre {
                    layout.pre_base + layout.var(d)
                } else {
                    layout.var(d)
                };
                initial_tape.ops.push(crate::tape::Op::Copy(reg, rr));
                if pre {
                    initial_pre_assigned.push(layout.var(d));
                } else {
                    initial_assigned.push((layout.var(d), dae.name(d)));
                }
                // Values computed before the assignment may have read the old value.
                memo.clear();
                continue;
            }
        }
        let lr = c.expr(l, &mut initial_tape, &mut memo);
        let rr = c.expr(r, &mut initial_tape, &mut memo);
        let d = c.temp_public();
        initial_tape.ops.push(crate::tape::Op::Sub(d, lr, rr));
        initial_regs.push(d);
        initial_names.push((format!("{} = {}", show(l), show(r)), None));
        initial_orders.push(u32::MAX);
        initial_parameter_only.push(dae.arena.vars(l).into_iter().chain(dae.arena.vars(r)).all(
            |v| {
                matches!(
                    dae.scalar(v).kind,
                    ScalarKind::Parameter | ScalarKind::Constant
                )
            },
        ));
    }
    for (s, st) in arena_starts {
        let rr = c.expr(st, &mut initial_tape, &mut memo);
        let d = c.temp_public();
        initial_tape
            .ops
            .push(crate::tape::Op::Sub(d, layout.var(s), rr));
        initial_regs.push(d);
        // The model equations of the step computing `s` (a differentiated one as
        // `d/dt (...)` of its original; the selection of a state set left out).
        let constraint = step_equations.get(&s).map(|eqs| {
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
                    let text = format!("{} = {}", show(e.lhs), show(e.rhs));
                    match order {
                        0 => text,
                        1 => format!("d/dt ({text})"),
                        n => format!("d^{n}/dt^{n} ({text})"),
                    }
                })
                .collect::<Vec<_>>()
                .join("`, `")
        });
        initial_names.push((
            format!("{} = {} (fixed start)", dae.name(s), show(st)),
            constraint,
        ));
        // Position-like variables (more derivatives above them) are decided first.
        let mut order = 0;
        let mut cur = dae.scalar(s).derivative;
        while let Some(d) = cur {
            order += 1;
            cur = dae.scalar(d).derivative;
        }
        initial_orders.push(order);
        initial_parameter_only.push(false);
    }

    // Constraints fully fixed by start values.
    let mut fixed_constraints_tape = Tape::default();
    let mut fixed_constraints = Vec::new();
    let mut memo = HashMap::default();
    let differentiated: std::collections::HashSet<unimo_dae::dae::EqId> = dae
        .equations
        .iter()
        .filter_map(|e| e.derivative_of)
        .collect();
    for (k, e) in dae.equations.iter().enumerate() {
        let id = unimo_dae::dae::EqId(k as u32);
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
            text: format!("{} = {}", show(e.lhs), show(e.rhs)),
            variables: vars.iter().map(|&v| (dae.name(v), layout.var(v))).collect(),
        });
    }

    let discretes = dae
        .ids()
        .filter(|&s| dae.scalar(s).kind == ScalarKind::Discrete && dae.scalar(s).alias.is_none())
        .map(|s| layout.var(s))
        .collect();
    let outputs = dae
        .ids()
        .filter(|&s| {
            !matches!(
                dae.scalar(s).kind,
                ScalarKind::Parameter | ScalarKind::Constant
            )
        })
        .map(|s| (dae.name(s), layout.var(s)))
        .collect();
    let nominals = plan
        .states
        .iter()
        .map(|&s| {
            dae.scalar(s)
                .nominal
                .and_then(|e| dae.arena.as_const(e))
                .map(f64::abs)
                .unwrap_or(1.0)
        })
        .collect();
    let fixed = plan
        .states
        .iter()
        .map(|&s| dae.scalar(s).fixed == Some(true))
        .collect();
    // External objects have no symbolic derivatives: finite differences then.
    let jacobian = if collision.is_some() {
        None
    } else {
        symbolic_jacobian(dae, plan, &mut c)
    };
    let state_sets = plan
        .state_sets
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
        .collect();
    let n_registers = c.n_registers();
    let constants = std::mem::take(&mut c.constants);
    let mut m = CompiledModel {
        constants,
        layout,
        n_registers,
        parameters,
        starts,
        steps,
        roots_tape,
        roots,
        root_ops,
        root_names,
        n_held: zc.held.len(),
        definitions,
        samples,
        when_tape,
        whens,
        conditions,
        assert_tape,
        assertions,
        alias_tape,
        jacobian,
        states: plan.states.iter().map(|&s| layout.var(s)).collect(),
        derivatives: plan.derivatives.iter().map(|&s| layout.var(s)).collect(),
        discretes,
        state_names: plan.states.iter().map(|&s| dae.name(s)).collect(),
        outputs,
        nominals,
        fixed,
        free_parameters,
        dependent_parameters,
        initial_tape,
        initial_residuals: initial_regs,
        initial_names,
        initial_orders,
        initial_parameter_only,
        fixed_constraints_tape,
        fixed_constraints,
        initial_assigned,
        initial_pre_assigned,
        ops_total: 0,
        relation_held: Vec::new(),
        collision,
        objects_tape,
        objects,
        uses_terminal: dae.uses_terminal,
        state_sets,
        equations_read_initial: reads_initial(dae),
    };
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

/// Whether an equation of the model reads `initial()`.
fn reads_initial(dae: &Dae) -> bool {
    let mut seen = std::collections::HashSet::new();
    let mut stack: Vec<ExprId> = dae.equations.iter().flat_map(|e| [e.lhs, e.rhs]).collect();
    while let Some(e) = stack.pop() {
        if !seen.insert(e) {
            continue;
        }
        if matches!(dae.arena.node(e), Node::Initial) {
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

/// d der(x_i) / d x_j symbolically, when every step of the plan is an explicit
/// assignment: the assignments are substituted into the derivatives (shared through the
/// hash-consed arena) and differentiated with respect to each state they mention.
fn symbolic_jacobian(dae: &Dae, plan: &Plan, c: &mut Compiler<'_>) -> Option<SymbolicJacobian> {
    const MAX_NONZEROS: usize = 200_000;
    if plan.states.is_empty() || plan.steps.iter().any(|s| matches!(s, PlanStep::Block(_))) {
        return None;
    }
    // The arena is shared with the compiler; differentiate on a copy.
    let mut arena = dae.arena.clone();
    let mut full: HashMap<ScalarId, ExprId> = HashMap::default();
    for step in &plan.steps {
        if let PlanStep::Assign { var, value, .. } = step {
            let v = arena.substitute(*value, &|s| full.get(&s).copied(), &mut HashMap::default());
            full.insert(*var, v);
        }
    }
    let column: HashMap<ScalarId, usize> = plan
        .states
        .iter()
        .enumerate()
        .map(|(j, &s)| (s, j))
        .collect();
    let mut entries = Vec::new();
    for (i, d) in plan.derivatives.iter().enumerate() {
        let e = full.get(d).copied().unwrap_or_else(|| arena.var(*d));
        for s in arena.vars(e) {
            let Some(&j) = column.get(&s) else { continue };
            let p = unimo_dae::diff::partial(&mut arena, e, s);
            if arena.as_const(p) != Some(0.0) {
                entries.push((i, j, p));
            }
            if entries.len() > MAX_NONZEROS {
                return None;
            }
        }
    }
    let mut compiler = Compiler::new(&arena, c.layout, c.relation_index, c.sample_index);
    compiler.held_index = c.held_index;
    compiler.continue_from(c);
    let mut tape = Tape::default();
    let mut memo = HashMap::default();
    let regs = entries
        .into_iter()
        .map(|(i, j, p)| (i, j, compiler.expr(p, &mut tape, &mut memo)))
        .collect();
    c.continue_from(&compiler);
    Some((tape, regs))
}

/// The collision world: argument tape, registers, and the arguments that a world
/// evaluated before the plan cannot read.
fn compile_collision(
    dae: &Dae,
    plan: &Plan,
    c: &mut Compiler<'_>,
    body_outputs: Vec<[Reg; 6]>,
    gaps: [Reg; 2],
) -> Option<CollisionModel> {
    if dae.collision.is_empty() && dae.collision_world.is_none() {
        return None;
    }
    let layout = c.layout;
    let states: std::collections::HashSet<ScalarId> = plan.states.iter().copied().collect();
    let mut inputs = Tape::default();
    let mut memo = HashMap::default();
    let mut problems = Vec::new();
    let check = |e: ExprId, problems: &mut Vec<String>| {
        for s in dae.arena.vars(e) {
            let sc = dae.scalar(s);
            let ok = match sc.kind {
                ScalarKind::Parameter | ScalarKind::Constant | ScalarKind::Discrete => true,
                ScalarKind::Continuous => states.contains(&s),
                ScalarKind::Derivative => false,
            };
            if !ok && !problems.contains(&dae.name(s)) {
                problems.push(dae.name(s));
            }
        }
    };
    let mut bodies = Vec::new();
    for (k, site) in dae.collision.iter().enumerate() {
        let args = site.args.map(|e| {
            check(e, &mut problems);
            c.expr(e, &mut inputs, &mut memo)
        });
        let state_reg = |e: ExprId| match dae.arena.node(e) {
            Node::Var(s) if states.contains(&s) => Some(layout.var(s)),
            _ => None,
        };
        let (v, w) = (site.args.velocity, site.args.angular_velocity);
        let velocity_states = v
            .iter()
            .chain(&w)
            .map(|&e| state_reg(e))
            .collect::<Option<Vec<Reg>>>()
            .map(|v| std::array::from_fn(|i| v[i]));
        // Name the body by the position variable it reads, else by its number.
        let name = dae
            .arena
            .vars(site.args.position[0])
            .first()
            .map(|&s| {
                let n = dae.name(s);
                n.rsplit_once('.').map(|(p, _)| p.to_string()).unwrap_or(n)
            })
            .unwrap_or_else(|| format!("collision body {}", k + 1));
        bodies.push(CollisionBodyRegs {
            args,
            outputs: body_outputs[k],
            velocity_states,
            name,
        });
    }
    let world_args = match &dae.collision_world {
        Some(w) => w.args.map(|e| c.expr(e, &mut inputs, &mut memo)),
        None => {
            problems.push("(no Unimo.Collision.CollisionWorld: collision bodies need one)".into());
            unimo_dae::collision_args::CollisionWorldArgs {
                margin: layout.time,
                tolerance: layout.time,
                broadphase: layout.time,
                sweep: layout.time,
            }
        }
    };
    Some(CollisionModel {
        inputs,
        bodies,
        world_args,
        gaps,
        problems,
    })
}
