//! From the hybrid DAE to the causal plan: the DAE seen as an integer graph by
//! `unimo-structure` (the symbolic side behind its `IndexReductionSystem` trait),
//! Pantelides, dummy derivatives, BLT, tearing, and the plan's steps with solved
//! expressions and symbolic block Jacobians.

use crate::dae::{Dae, EqId, Equation, ScalarKind, WhenAction};
use crate::diff::{partial, solve_linear};
use crate::error::{DaeError, SingularReport};
use crate::expr::{ExprId, Node, ScalarId};
use crate::linearity::{affine_while_frozen, degree, frozen_between_events, Degree};
use crate::plan::{Block, Plan, PlanStats, PlanStep, StateSet};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use unimo_structure as st;

mod selection;
use selection::{select_dummies, selection_ranks};

/// The DAE as the structural algorithms see it.
pub struct DaeSystem<'d> {
    pub dae: &'d mut Dae,
    graph: st::BipartiteGraph,
    var_of_scalar: Vec<Option<st::VarId>>,
    scalar_of_var: Vec<ScalarId>,
    /// Graph equation -> DAE equation (the same index: every continuous equation is in
    /// the graph).
    eq_derivative: Vec<Option<st::EqId>>,
}

/// Whether a scalar is an unknown of the continuous system.
fn in_graph(dae: &Dae, s: ScalarId, when_assigned: &HashSet<ScalarId>) -> bool {
    let sc = dae.scalar(s);
    sc.alias.is_none()
        && !sc.input
        && match sc.kind {
            ScalarKind::Continuous | ScalarKind::Derivative => true,
            ScalarKind::Discrete => !when_assigned.contains(&s),
            ScalarKind::Parameter | ScalarKind::Constant => false,
        }
}

impl<'d> DaeSystem<'d> {
    pub fn new(dae: &'d mut Dae) -> DaeSystem<'d> {
        let mut when_assigned = HashSet::default();
        for w in &dae.whens {
            for b in &w.branches {
                for (a, _) in &b.actions {
                    if let WhenAction::Assign { target, .. } = a {
                        when_assigned.insert(*target);
                    }
                }
            }
        }
        let mut sys = DaeSystem {
            graph: st::BipartiteGraph::new(0),
            var_of_scalar: vec![None; dae.scalars.len()],
            scalar_of_var: Vec::new(),
            eq_derivative: Vec::new(),
            dae,
        };
        for s in sys.dae.ids().collect::<Vec<_>>() {
            if in_graph(sys.dae, s, &when_assigned) {
                sys.add_graph_var(s);
            }
        }
        for k in 0..sys.dae.equations.len() {
            let vars = sys.incidence(EqId(k as u32));
            sys.graph
                .add_eq(vars)
                .expect("incidence uses graph variables only");
            sys.eq_derivative.push(None);
        }
        sys
    }

    /// Adds an equation to the DAE and the graph (its incidence from its residual).
    fn add_equation(&mut self, eq: Equation) -> st::EqId {
        self.dae.equations.push(eq);
        let vars = self.incidence(EqId(self.dae.equations.len() as u32 - 1));
        self.eq_derivative.push(None);
        self.graph
            .add_eq(vars)
            .expect("incidence uses graph variables only")
    }

    fn add_graph_var(&mut self, s: ScalarId) -> st::VarId {
        if self.var_of_scalar.len() <= s.index() {
            self.var_of_scalar.resize(s.index() + 1, None);
        }
        if let Some(v) = self.var_of_scalar[s.index()] {
            return v;
        }
        let v = self.graph.add_var();
        self.var_of_scalar[s.index()] = Some(v);
        self.scalar_of_var.push(s);
        v
    }

    pub fn var(&self, s: ScalarId) -> Option<st::VarId> {
        self.var_of_scalar.get(s.index()).copied().flatten()
    }

    pub fn scalar(&self, v: st::VarId) -> ScalarId {
        self.scalar_of_var[v.index()]
    }

    pub fn graph_ref(&self) -> &st::BipartiteGraph {
        &self.graph
    }

    fn incidence(&mut self, e: EqId) -> Vec<st::VarId> {
        let r = self.dae.residual(e);
        self.dae
            .arena
            .vars(r)
            .into_iter()
            .filter_map(|s| self.var(s))
            .collect()
    }
}

impl st::IndexReductionSystem for DaeSystem<'_> {
    fn graph(&self) -> &st::BipartiteGraph {
        &self.graph
    }

    fn var_derivative(&self, v: st::VarId) -> Option<st::VarId> {
        let s = self.scalar(v);
        self.dae.scalar(s).derivative.and_then(|d| self.var(d))
    }

    fn add_var_derivative(&mut self, v: st::VarId) -> st::VarId {
        let s = self.scalar(v);
        let d = self.dae.derivative_of(s);
        self.add_graph_var(d)
    }

    fn eq_derivative(&self, e: st::EqId) -> Option<st::EqId> {
        self.eq_derivative[e.index()]
    }

    fn differentiate_eq(&mut self, e: st::EqId) -> Result<st::EqId, String> {
        let eq = EqId(e.0);
        let r = self.dae.residual(eq);
        if contains_non_differentiable(self.dae, r) {
            return Err("it contains `sample` or `initial()`".into());
        }
        let before = self.dae.scalars.len();
        let d = time_derivative(self.dae, r);
        // Derivative scalars made for variables in the graph join the graph.
        for k in before..self.dae.scalars.len() {
            let s = ScalarId(k as u32);
            if let Some(base) = self.dae.scalar(s).derivative_of {
                if self.var(base).is_some() {
                    self.add_graph_var(s);
                }
            }
        }
        let d = self.discrete_derivative(eq, d);
        let origin = self.dae.equations[eq.index()].origin;
        let zero = self.dae.arena.zero();
        self.dae.equations.push(Equation {
            lhs: d,
            rhs: zero,
            origin,
            derivative_of: Some(eq),
        });
        let new_eq = EqId(self.dae.equations.len() as u32 - 1);
        let vars = self.incidence(new_eq);
        let ge = self
            .graph
            .add_eq(vars)
            .map_err(|e| format!("internal: {e}"))?;
        self.eq_derivative.push(None);
        self.eq_derivative[e.index()] = Some(ge);
        Ok(ge)
    }
}

impl DaeSystem<'_> {
    /// The derivative `d` of equation `eq`, unless `eq` relates discrete variables
    /// alone (`b = a >= 1`): its derivative is identically zero, with no unknown
    /// Pantelides could match, and stands as `der(b) = 0` for the equation's discrete
    /// unknowns (their derivatives are zero between events), so that the discrete
    /// variables Pantelides colours keep a derivative equation.
    fn discrete_derivative(&mut self, eq: EqId, d: ExprId) -> ExprId {
        let r = self.dae.residual(eq);
        let vars: Vec<ScalarId> = self
            .dae
            .arena
            .vars(r)
            .into_iter()
            .filter(|&s| self.var(s).is_some())
            .collect();
        let discrete = |s: &ScalarId| self.dae.scalar(*s).kind == ScalarKind::Discrete;
        if vars.is_empty() || !vars.iter().all(discrete) {
            return d;
        }
        if self
            .dae
            .arena
            .vars(d)
            .iter()
            .any(|&s| self.var(s).is_some())
        {
            return d;
        }
        let mut sum = self.dae.arena.zero();
        for s in vars {
            let ds = self.dae.derivative_of(s);
            self.add_graph_var(ds);
            let x = self.dae.arena.var(ds);
            sum = self.dae.arena.add(sum, x);
        }
        sum
    }
}

fn contains_non_differentiable(dae: &Dae, e: ExprId) -> bool {
    let mut stack = vec![e];
    let mut seen = HashSet::default();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        if matches!(
            dae.arena.node(x),
            Node::Sample(..) | Node::Initial | Node::Terminal
        ) {
            return true;
        }
        stack.extend(dae.arena.children(x));
    }
    false
}

/// d/dt of `e`: continuous scalars get (new) derivative scalars; discrete ones and
/// parameters have none.
pub fn time_derivative(dae: &mut Dae, e: ExprId) -> ExprId {
    let scalars = &mut dae.scalars;
    let mut var = |a: &mut crate::expr::ExprArena, s: ScalarId| -> Option<ExprId> {
        if !matches!(
            scalars[s.index()].kind,
            ScalarKind::Continuous | ScalarKind::Derivative
        ) || scalars[s.index()].alias.is_some()
        {
            return None;
        }
        let d = match scalars[s.index()].derivative {
            Some(d) => d,
            None => {
                let base = &scalars[s.index()];
                let mut d = crate::dae::Scalar::new(
                    format!("der({})", base.name),
                    ScalarKind::Derivative,
                    crate::dae::ScalarType::Real,
                    base.origin,
                );
                d.derivative_of = Some(s);
                let id = ScalarId(scalars.len() as u32);
                scalars.push(d);
                scalars[s.index()].derivative = Some(id);
                id
            }
        };
        Some(a.var(d))
    };
    let mut seed = crate::diff::Seed {
        var: &mut var,
        time: 1.0,
    };
    crate::diff::derivative(&mut dae.arena, e, &mut seed, &mut HashMap::default())
}

/// The structural result kept for dumps.
pub struct Analysis {
    pub plan: Plan,
    /// Text of the structural dump (incidence, chains, dummies, blocks).
    pub dump: String,
}

/// Analyses `dae` (alias elimination is done before, by the caller) and returns the
/// plan. Index reduction appends differentiated equations to `dae.equations`.
pub fn analyze(dae: &mut Dae) -> Result<Analysis, DaeError> {
    let n_original = dae.equations.len();
    let exposed = crate::singular::expose_hidden_constraints(dae);
    let mut sys = DaeSystem::new(dae);
    let pantelides = st::pantelides(&mut sys).map_err(|e| struct_error(&sys, e))?;
    let graph = sys.graph.clone();
    let (priorities, fixed_starts) = selection_ranks(&sys, graph.n_vars());
    let selected = select_dummies(&mut sys, &graph, &pantelides, &priorities, &fixed_starts);
    let mut dummies = selected.map_err(|e| struct_error(&sys, e))?;
    let state_sets = add_state_sets(&mut sys, &mut dummies);
    let graph = sys.graph.clone();
    let selectors: HashSet<ScalarId> = state_sets
        .iter()
        .flat_map(|s| s.selectors.iter().copied())
        .collect();
    let matching = dummies
        .index_one_matching(&graph)
        .map_err(|e| struct_error(&sys, e))?;
    let blocks = st::blt(&graph, &matching, |v| dummies.is_unknown[v.index()])
        .map_err(|e| struct_error(&sys, e))?;

    let (solvable, solutions) = solvable_edges(&mut sys, &graph, &blocks, &selectors);
    let mut tearing = st::Tearing::new();
    let solv = |e: st::EqId, v: st::VarId| solvable.contains(&(e.0, v.0));

    let mut plan = plan_with_states(&sys, &dummies);
    plan.state_sets = state_sets;
    let mut torn_count = 0;
    let mut largest = 0;
    let frozen = frozen_between_events(sys.dae);
    for b in &blocks {
        largest = largest.max(b.size());
        if b.size() == 1 {
            let step = single_step(&mut sys, b.eqs[0], b.vars[0], &selectors, &frozen);
            plan.steps.push(step);
            continue;
        }
        let torn = tearing
            .tear(&graph, b, &solv)
            .map_err(|e| struct_error(&sys, e))?;
        torn_count += 1;
        let inner: Vec<(ScalarId, ExprId)> = torn
            .inner
            .iter()
            .map(|&(e, v)| (sys.scalar(v), solutions[&(e.0, v.0)]))
            .collect();
        let iteration: Vec<ScalarId> = torn.iteration_vars.iter().map(|&v| sys.scalar(v)).collect();
        let residuals: Vec<ExprId> = torn
            .residual_eqs
            .iter()
            .map(|&e| sys.dae.residual(EqId(e.0)))
            .collect();
        let eqs: Vec<EqId> = b.eqs.iter().map(|e| EqId(e.0)).collect();
        let block = newton_block(sys.dae, &eqs, &iteration, &inner, &residuals, &frozen);
        plan.steps.push(PlanStep::Block(block));
    }
    let n_unknowns = dummies.is_unknown.iter().filter(|&&u| u).count();
    let dump = structure_dump(&sys, &pantelides, &dummies, &blocks, &plan, &exposed);
    let dae = sys.dae;
    plan.stats = PlanStats {
        flat_scalars: dae
            .scalars
            .iter()
            .filter(|s| !matches!(s.kind, ScalarKind::Derivative))
            .count(),
        equations: n_original,
        differentiated_equations: dae.equations.len() - n_original,
        states: plan.states.len(),
        dummy_derivatives: plan.dummy_derivatives.len(),
        state_sets: plan.state_sets.len(),
        algebraic: n_unknowns.saturating_sub(plan.derivatives.len()),
        blocks: blocks.len(),
        torn_blocks: torn_count,
        largest_block: largest,
        zero_crossings: crate::events::zero_crossings(dae).relations.len(),
        ..PlanStats::default()
    };
    Ok(Analysis { plan, dump })
}

/// A plan with no steps yet: the selected states (sorted) with their derivatives, and
/// the dummy derivatives.
fn plan_with_states(sys: &DaeSystem<'_>, dummies: &st::DummyDerivatives) -> Plan {
    let mut plan = Plan::default();
    let mut states: Vec<ScalarId> = dummies.states.iter().map(|&v| sys.scalar(v)).collect();
    states.sort();
    for &s in &states {
        let d = sys
            .dae
            .scalar(s)
            .derivative
            .expect("a state has a derivative");
        plan.states.push(s);
        plan.derivatives.push(d);
    }
    plan.dummy_derivatives = dummies.dummies.iter().map(|&v| sys.scalar(v)).collect();
    plan
}

/// Solvability of the edges inside blocks of size > 1 (for tearing): the edges whose
/// equation is linear in the variable with a known coefficient that cannot be zero, and
/// the solution of each.
#[allow(clippy::type_complexity)]
fn solvable_edges(
    sys: &mut DaeSystem<'_>,
    graph: &st::BipartiteGraph,
    blocks: &[st::Block],
    selectors: &HashSet<ScalarId>,
) -> (HashSet<(u32, u32)>, HashMap<(u32, u32), ExprId>) {
    let mut parameter_values = crate::params::ParameterValues::default();
    let mut solvable: HashSet<(u32, u32)> = HashSet::default();
    let mut solutions: HashMap<(u32, u32), ExprId> = HashMap::default();
    for b in blocks {
        if b.size() <= 1 {
            continue;
        }
        for &e in &b.eqs {
            let r = sys.dae.residual(EqId(e.0));
            for &v in graph.eq_vars(e) {
                if !b.vars.contains(&v) {
                    continue;
                }
                let s = sys.scalar(v);
                if let Some((sol, coef)) = solve_linear(&mut sys.dae.arena, r, s) {
                    let known_coef = sys.dae.arena.vars(coef).iter().all(|&x| {
                        !matches!(
                            sys.dae.scalar(x).kind,
                            ScalarKind::Continuous | ScalarKind::Derivative
                        )
                    });
                    // A coefficient with a condition (an if-equation that solves this
                    // variable in one branch only) may be 0 in the other branch: the
                    // variable is then left to Newton, which sees the branch in force.
                    if known_coef
                        && !has_if(sys.dae, coef)
                        && !mentions(sys.dae, coef, selectors)
                        && !parameter_values.is_zero(sys.dae, coef)
                    {
                        solvable.insert((e.0, v.0));
                        solutions.insert((e.0, v.0), sol);
                    }
                }
            }
        }
    }
    (solvable, solutions)
}

/// The step of a block of one equation `e` and one variable `v`: an assignment when
/// the equation is linear in `v` with a coefficient free of conditions and selectors,
/// otherwise a Newton block.
fn single_step(
    sys: &mut DaeSystem<'_>,
    e: st::EqId,
    v: st::VarId,
    selectors: &HashSet<ScalarId>,
    frozen: &HashSet<ExprId>,
) -> PlanStep {
    let eq = EqId(e.0);
    let s = sys.scalar(v);
    let r = sys.dae.residual(eq);
    match solve_linear(&mut sys.dae.arena, r, s) {
        Some((value, coef)) if !has_if(sys.dae, coef) && !mentions(sys.dae, coef, selectors) => {
            PlanStep::Assign { var: s, value, eq }
        }
        _ => PlanStep::Block(newton_block(sys.dae, &[eq], &[s], &[], &[r], frozen)),
    }
}

/// Adds each dynamic state set's states and selection (module docs of
/// [`crate::plan::StateSet`]): `k = candidates - equations` states `s`, a `k x n`
/// selection `A` (discrete, switched by the simulator), the equations `s = A x` and
/// `der(s) = A der(x)` (`x` the candidates' integrals), in the DAE and in the graph;
/// `dummies` gets the states and unknowns.
fn add_state_sets(sys: &mut DaeSystem<'_>, dummies: &mut st::DummyDerivatives) -> Vec<StateSet> {
    let specs = std::mem::take(&mut dummies.state_sets);
    let mut sets = Vec::new();
    for (number, spec) in specs.iter().enumerate() {
        let n = spec.candidates.len();
        let k = n - spec.eqs.len();
        let derivatives: Vec<ScalarId> = spec.candidates.iter().map(|&c| sys.scalar(c)).collect();
        let candidates: Vec<ScalarId> = derivatives
            .iter()
            .map(|&d| {
                sys.dae
                    .scalar(d)
                    .derivative_of
                    .expect("candidates are derivatives")
            })
            .collect();
        let equations: Vec<EqId> = spec.eqs.iter().map(|e| EqId(e.0)).collect();
        let origin = sys.dae.equations[equations[0].index()].origin;
        let jacobian = set_jacobian(sys, &equations, &derivatives);
        // The first selection: the candidates the static order keeps as states.
        let initial: Vec<usize> = (0..n)
            .filter(|&j| !spec.initial.contains(&spec.candidates[j]))
            .collect();
        let name = format!("$set{}", number + 1);
        let mut states = Vec::with_capacity(k);
        let mut selectors = Vec::with_capacity(k * n);
        for i in 0..k {
            let mut x = crate::dae::Scalar::new(
                format!("{name}.x[{}]", i + 1),
                ScalarKind::Continuous,
                crate::dae::ScalarType::Real,
                origin,
            );
            x.start = Some(sys.dae.arena.var(candidates[initial[i]]));
            x.description = Some("state of a dynamically selected set".into());
            let s = sys.dae.add_scalar(x);
            let ds = sys.dae.derivative_of(s);
            let (vs, vds) = (sys.add_graph_var(s), sys.add_graph_var(ds));
            dummies.is_unknown.resize(sys.graph.n_vars(), false);
            dummies.is_dummy.resize(sys.graph.n_vars(), false);
            dummies.is_unknown[vds.index()] = true;
            dummies.states.push(vs);
            let mut sel = sys.dae.arena.zero();
            let mut dsel = sys.dae.arena.zero();
            for j in 0..n {
                let a = add_selector(sys, &name, (i, j), initial[i] == j, origin);
                selectors.push(a);
                let av = sys.dae.arena.var(a);
                let xv = sys.dae.arena.var(candidates[j]);
                let dv = sys.dae.arena.var(derivatives[j]);
                let t = sys.dae.arena.mul(av, xv);
                sel = sys.dae.arena.add(sel, t);
                let t = sys.dae.arena.mul(av, dv);
                dsel = sys.dae.arena.add(dsel, t);
            }
            let sv = sys.dae.arena.var(s);
            let dsv = sys.dae.arena.var(ds);
            let e = sys.add_equation(Equation {
                lhs: sv,
                rhs: sel,
                origin,
                derivative_of: None,
            });
            // Written as `0 = der(s) - A der(x)`, like every differentiated equation.
            let residual = sys.dae.arena.sub(dsv, dsel);
            let zero = sys.dae.arena.zero();
            sys.add_equation(Equation {
                lhs: residual,
                rhs: zero,
                origin,
                derivative_of: Some(EqId(e.0)),
            });
            states.push(s);
        }
        sets.push(StateSet {
            states,
            candidates,
            derivatives,
            selectors,
            equations,
            jacobian,
            initial,
        });
    }
    dummies.states.sort_unstable();
    sets
}

/// The Jacobian of a state set's equations by the candidates' derivatives, row by row.
fn set_jacobian(
    sys: &mut DaeSystem<'_>,
    equations: &[EqId],
    derivatives: &[ScalarId],
) -> Vec<ExprId> {
    let mut jacobian = Vec::with_capacity(equations.len() * derivatives.len());
    for &e in equations {
        let r = sys.dae.residual(e);
        for &d in derivatives {
            jacobian.push(partial(&mut sys.dae.arena, r, d));
        }
    }
    jacobian
}

/// The discrete selection entry `A[i,j]` of the state set `name`, starting at 1 where
/// the first selection picks candidate `j` for state `i`, else 0.
fn add_selector(
    sys: &mut DaeSystem<'_>,
    name: &str,
    (i, j): (usize, usize),
    selected: bool,
    origin: unimo_source::Span,
) -> ScalarId {
    let mut a = crate::dae::Scalar::new(
        format!("{name}.A[{},{}]", i + 1, j + 1),
        ScalarKind::Discrete,
        crate::dae::ScalarType::Real,
        origin,
    );
    a.start = Some(sys.dae.arena.constant(if selected { 1.0 } else { 0.0 }));
    sys.dae.add_scalar(a)
}

/// Whether `e` mentions one of `scalars`.
fn mentions(dae: &Dae, e: ExprId, scalars: &HashSet<ScalarId>) -> bool {
    !scalars.is_empty() && dae.arena.vars(e).iter().any(|s| scalars.contains(s))
}

/// A block: inner assignments substituted into the residuals for the symbolic Jacobian.
fn newton_block(
    dae: &mut Dae,
    eqs: &[EqId],
    iteration: &[ScalarId],
    inner: &[(ScalarId, ExprId)],
    residuals: &[ExprId],
    frozen: &HashSet<ExprId>,
) -> Block {
    let mut full: HashMap<ScalarId, ExprId> = HashMap::default();
    for &(v, e) in inner {
        let e = dae
            .arena
            .substitute(e, &|s| full.get(&s).copied(), &mut HashMap::default());
        full.insert(v, e);
    }
    let mut memo = HashMap::default();
    let substituted: Vec<ExprId> = residuals
        .iter()
        .map(|&r| {
            dae.arena
                .substitute(r, &|s| full.get(&s).copied(), &mut memo)
        })
        .collect();
    let mut jacobian = Vec::with_capacity(residuals.len() * iteration.len());
    for &r in &substituted {
        for &v in iteration {
            jacobian.push(partial(&mut dae.arena, r, v));
        }
    }
    let switched = substituted.iter().any(|&r| has_if(dae, r));
    // One step solves the block when its residual is affine and its Jacobian, as the
    // Jacobian tape evaluates it, constant in each frozen mode (a condition rebuilt by
    // the substitution is no zero crossing: evaluated live, it could pick another
    // mode's Jacobian than the residual's).
    let mut memo = HashMap::default();
    let of_iteration: HashMap<ScalarId, Degree> =
        iteration.iter().map(|&v| (v, Degree::Affine)).collect();
    let linear = affine_while_frozen(dae, iteration, inner, residuals, frozen)
        && jacobian
            .iter()
            .all(|&j| degree(dae, j, false, &of_iteration, frozen, &mut memo) == Degree::Constant);
    Block {
        iteration_vars: iteration.to_vec(),
        residuals: residuals.to_vec(),
        inner: inner.to_vec(),
        jacobian,
        linear,
        switched,
        equations: eqs.to_vec(),
    }
}

fn has_if(dae: &Dae, e: ExprId) -> bool {
    let mut stack = vec![e];
    let mut seen = HashSet::default();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        if matches!(dae.arena.node(x), Node::If(..)) {
            return true;
        }
        stack.extend(dae.arena.children(x));
    }
    false
}

/// A structural error as a diagnostic naming equations and variables.
fn struct_error(sys: &DaeSystem<'_>, e: st::StructError) -> DaeError {
    let name_eq = |e: st::EqId| {
        let eq = &sys.dae.equations[e.index()];
        format!("{} = {}", sys.dae.show(eq.lhs), sys.dae.show(eq.rhs))
    };
    let name_var = |v: st::VarId| sys.dae.name(sys.scalar(v));
    let span_of = |e: st::EqId| sys.dae.equations[e.index()].origin;
    match e {
        st::StructError::Singular { over, under } => {
            let span = over
                .eqs
                .first()
                .map(|&e| span_of(e))
                .or_else(|| {
                    under
                        .vars
                        .first()
                        .map(|&v| sys.dae.scalar(sys.scalar(v)).origin)
                })
                .unwrap_or_default();
            let debug = std::env::var_os("UNIMO_DEBUG_STRUCTURE")
                .is_some()
                .then(|| {
                    let all: Vec<String> = under.vars.iter().map(|&v| name_var(v)).collect();
                    let eqs: Vec<String> = under.eqs.iter().map(|&e| name_eq(e)).collect();
                    format!("all: {}\n eqs: {}", all.join(", "), eqs.join("\n "))
                });
            let report = SingularReport {
                too_many: (over.eqs.len().saturating_sub(over.vars.len()))
                    .max(usize::from(!over.eqs.is_empty())),
                undetermined: (under.vars.len().saturating_sub(under.eqs.len()))
                    .max(usize::from(!under.vars.is_empty())),
                over_equations: over.eqs.iter().take(8).map(|&e| name_eq(e)).collect(),
                over_variables: over.vars.iter().take(8).map(|&v| name_var(v)).collect(),
                under_variables: under.vars.iter().take(8).map(|&v| name_var(v)).collect(),
                debug,
            };
            DaeError::StructurallySingular {
                report: Box::new(report),
                span,
            }
        }
        st::StructError::IndexReductionFailed { eq, reason } => DaeError::CannotDifferentiate {
            equation: name_eq(eq),
            reason,
            span: span_of(eq),
        },
        st::StructError::DifferentiationLimit { eq, limit } => DaeError::DifferentiationLimit {
            equation: name_eq(eq),
            limit,
            span: span_of(eq),
        },
        st::StructError::DummySelectionFailed { level, eqs } => DaeError::NoDummyDerivatives {
            level,
            equations: eqs.iter().take(6).map(|&e| name_eq(e)).collect(),
            span: eqs.first().map(|&e| span_of(e)).unwrap_or_default(),
        },
        other => DaeError::InternalStructure {
            detail: other.to_string(),
            span: unimo_source::Span::default(),
        },
    }
}

fn structure_dump(
    sys: &DaeSystem<'_>,
    pantelides: &st::PantelidesResult,
    dummies: &st::DummyDerivatives,
    blocks: &[st::Block],
    plan: &Plan,
    exposed: &[EqId],
) -> String {
    use std::fmt::Write;
    let dae = &*sys.dae;
    let mut o = String::new();
    let _ = writeln!(o, "structure {}", dae.name);
    let _ = writeln!(
        o,
        "equations: {} ({} differentiated), unknowns: {}",
        sys.graph.n_eqs(),
        dae.equations
            .iter()
            .filter(|e| e.derivative_of.is_some())
            .count(),
        dummies.is_unknown.iter().filter(|&&u| u).count()
    );
    let _ = writeln!(
        o,
        "max differentiations: {}",
        pantelides.max_differentiations()
    );
    if !exposed.is_empty() {
        let _ = writeln!(
            o,
            "hidden constraints (derivatives eliminated by a linear combination):"
        );
        for e in exposed {
            let _ = writeln!(
                o,
                "  e{}: 0 = {}",
                e.0,
                dae.show(dae.equations[e.index()].lhs)
            );
        }
    }
    let chains = derivative_chains(sys);
    if !chains.is_empty() {
        let _ = writeln!(o, "derivative chains:");
        for c in chains {
            let _ = writeln!(o, "  {c}");
        }
    }
    let diffs: Vec<String> = dae
        .equations
        .iter()
        .enumerate()
        .filter_map(|(k, e)| {
            e.derivative_of
                .map(|b| format!("e{k} = d/dt e{}: 0 = {}", b.0, dae.show(e.lhs)))
        })
        .collect();
    if !diffs.is_empty() {
        let _ = writeln!(o, "differentiated equations:");
        for d in diffs {
            let _ = writeln!(o, "  {d}");
        }
    }
    let names = |v: &[ScalarId]| scalar_names(dae, v);
    let _ = writeln!(o, "states: {}", names(&plan.states));
    let _ = writeln!(o, "dummy derivatives: {}", names(&plan.dummy_derivatives));
    for (k, set) in plan.state_sets.iter().enumerate() {
        let eqs: Vec<String> = set.equations.iter().map(|e| format!("e{}", e.0)).collect();
        let first: Vec<ScalarId> = set.initial.iter().map(|&j| set.candidates[j]).collect();
        let _ = writeln!(
            o,
            "state set {}: {} of {{{}}} by [{}], chosen at run time; first {{{}}}",
            k + 1,
            names(&set.states),
            names(&set.candidates),
            eqs.join(" "),
            names(&first)
        );
    }
    let _ = writeln!(o, "blocks: {}", blocks.len());
    write_blocks(&mut o, dae, blocks, plan);
    o
}

/// Derivative chains, one per base variable: `x -> der(x) -> der(der(x))`.
fn derivative_chains(sys: &DaeSystem<'_>) -> Vec<String> {
    let dae = &*sys.dae;
    let mut chains: Vec<String> = Vec::new();
    for k in 0..sys.graph.n_vars() {
        let s = sys.scalar(st::VarId(k as u32));
        let sc = dae.scalar(s);
        if sc.derivative_of.is_some() || sc.derivative.is_none() {
            continue;
        }
        let mut chain = vec![dae.name(s)];
        let mut cur = sc.derivative;
        while let Some(d) = cur {
            chain.push(dae.name(d));
            cur = dae.scalar(d).derivative;
        }
        chains.push(chain.join(" -> "));
    }
    chains
}

/// Scalars' names, separated by commas.
fn scalar_names(dae: &Dae, v: &[ScalarId]) -> String {
    v.iter()
        .map(|&s| dae.name(s))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The blocks of the structure dump, each with its plan step.
fn write_blocks(o: &mut String, dae: &Dae, blocks: &[st::Block], plan: &Plan) {
    use std::fmt::Write;
    let names = |v: &[ScalarId]| scalar_names(dae, v);
    for (k, (b, step)) in blocks.iter().zip(&plan.steps).enumerate() {
        match step {
            PlanStep::Assign { var, eq, value } => {
                let _ = writeln!(
                    o,
                    "  b{k}: {} := {}  (e{})",
                    dae.name(*var),
                    dae.show(*value),
                    eq.0
                );
            }
            PlanStep::Block(bl) => {
                let kind = match (bl.linear, bl.switched) {
                    (true, false) => "linear",
                    (true, true) => "switched linear",
                    (false, true) => "switched",
                    (false, false) => "nonlinear",
                };
                let eqs: Vec<String> = b.eqs.iter().map(|e| format!("e{}", e.0)).collect();
                let _ = writeln!(
                    o,
                    "  b{k}: {kind} block of {} [{}] iter {{{}}}",
                    b.size(),
                    eqs.join(" "),
                    names(&bl.iteration_vars)
                );
                for (v, e) in &bl.inner {
                    let _ = writeln!(o, "      {} := {}", dae.name(*v), dae.show(*e));
                }
                for r in &bl.residuals {
                    let _ = writeln!(o, "      0 = {}", dae.show(*r));
                }
            }
        }
    }
}
