//! Dummy-derivative selection (Mattsson–Söderlind, structural form): which derivatives
//! become algebraic so that the reduced system is index 1, and which variables are states.

use std::cmp::Reverse;

use crate::dm::dulmage_mendelsohn_where;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::{maximum_matching_where, AugmentingPathSearch, Matching};
use crate::pantelides::PantelidesResult;
use crate::regular::{regular_choice, Coefficient};

/// How much a variable should be a state (Modelica's `stateSelect`), ordered from
/// "make it algebraic first" to "must stay a state".
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum StateSelectPriority {
    Never,
    Avoid,
    #[default]
    Default,
    Prefer,
    Always,
}

/// One step of the selection: the differentiated equations considered at this level and
/// the derivative each is solved for (those derivatives are the level's dummies).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DummyLevel {
    /// 1 for the highest differentiated equations, 2 for their integrals, ...
    pub level: u32,
    pub assignments: Vec<(EqId, VarId)>,
}

/// The selection. Invariants: there are as many dummies as differentiated equations;
/// every dummy is a derivative; `states` are the variables whose derivative occurs
/// (itself or through a higher derivative) and is not a dummy; `dummy_states` those
/// whose derivative is a dummy (they become algebraic); `is_unknown` marks the
/// unknowns of the index-1 system — every occurring variable that is not a state.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DummyDerivatives {
    pub is_dummy: Vec<bool>,
    pub dummies: Vec<VarId>,
    pub states: Vec<VarId>,
    pub dummy_states: Vec<VarId>,
    pub is_unknown: Vec<bool>,
    pub levels: Vec<DummyLevel>,
    /// Variables with priority `Always` that could not stay states.
    pub always_not_states: Vec<VarId>,
    /// Candidate sets whose choice is made at run time (dynamic state selection): all
    /// their candidates are dummies here, and the symbolic side adds the set's states.
    pub state_sets: Vec<StateSetSpec>,
}

/// A group of a level's equations and candidates (a connected component of the level's
/// graph with more candidates than equations) whose dummies are chosen at run time.
/// Every candidate is a dummy in [`DummyDerivatives`]; `initial` are the dummies the
/// static order would have chosen (the first selection). The set has
/// `candidates.len() - eqs.len()` states, each one of the candidates' integrals.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StateSetSpec {
    pub level: u32,
    pub eqs: Vec<EqId>,
    pub candidates: Vec<VarId>,
    pub initial: Vec<VarId>,
}

impl DummyDerivatives {
    /// Whether `v` is a state of the index-1 system.
    pub fn is_state(&self, v: VarId) -> bool {
        self.states.binary_search(&v).is_ok()
    }

    /// A perfect matching of all equations (original and differentiated) with the
    /// unknowns; Err with the Dulmage–Mendelsohn parts when there is none.
    pub fn index_one_matching(&self, graph: &BipartiteGraph) -> Result<Matching, StructError> {
        let unknown = |v: VarId| self.is_unknown.get(v.index()).copied().unwrap_or(false);
        let matching = maximum_matching_where(graph, |_| true, unknown);
        let perfect = matching.size() == graph.n_eqs()
            && graph
                .vars()
                .all(|v| !unknown(v) || matching.eq_of(v).is_some());
        if perfect {
            return Ok(matching);
        }
        Err(dulmage_mendelsohn_where(graph, &matching, |_| true, unknown).into_error())
    }
}

/// Selects dummy derivatives on the result of Pantelides' algorithm.
///
/// Level 1 takes the highest differentiated equations and, as candidates, the highest
/// derivative variables that are derivatives of something; a matching restricted to
/// the candidates picks one dummy per equation. Level k+1 takes the integrals of level
/// k's equations that are themselves differentiated, and as candidates the integrals of
/// level k's dummies. Candidates are tried in order of the priority of the variable
/// that would lose its state (`priority(integral)`: `Never` first, `Always` last), then
/// higher-order derivatives first, then derivatives that occur only in differentiated
/// equations before those the input already has, then by id; the greedy order gives the
/// best set in
/// that order (transversal matroid).
pub fn select_dummy_derivatives(
    graph: &BipartiteGraph,
    pantelides: &PantelidesResult,
    priority: impl Fn(VarId) -> StateSelectPriority,
) -> Result<DummyDerivatives, StructError> {
    select_dummy_derivatives_with_sets(graph, pantelides, priority, |_| false, |_, _| false, None)
}

/// [`select_dummy_derivatives`] with dynamic state selection: a connected component of
/// a level (its equations and the candidates they contain) with more candidates than
/// equations for which `dynamic(eqs, candidates)` holds becomes a [`StateSetSpec`]:
/// all its candidates are dummies, and the next level takes all their integrals as
/// candidates. The caller adds, per set, the set's states `s = A x` (`x` the
/// candidates' integrals, `A` a selection switched at run time) and `der(s) = A der(x)`;
/// without that the system is not index 1.
///
/// With `coefficient` (an equation's constant partial derivative with respect to a
/// variable, where it has one), a level's choice that is structurally valid but
/// numerically singular is replaced per connected component by the first regular one
/// in the candidates' order ([`crate::regular`]).
///
/// `fixed_start(integral)` breaks ties of priority: at equal `stateSelect`, a variable
/// the model gives a fixed start value (its initial condition) keeps its state before
/// one it does not (the modeller's coordinates: a joint angle rather than the length of
/// a line force that depends on it, and is stationary in it where the joint starts).
pub fn select_dummy_derivatives_with_sets(
    graph: &BipartiteGraph,
    pantelides: &PantelidesResult,
    priority: impl Fn(VarId) -> StateSelectPriority,
    fixed_start: impl Fn(VarId) -> bool,
    mut dynamic: impl FnMut(&[EqId], &[VarId]) -> bool,
    mut coefficient: Option<Coefficient<'_>>,
) -> Result<DummyDerivatives, StructError> {
    let chains = &pantelides.chains;
    let n_vars = graph.n_vars();
    let var_levels = chains.var_levels();
    let mut allowed: Vec<bool> = graph
        .vars()
        .map(|v| {
            pantelides
                .highest_vars
                .get(v.index())
                .copied()
                .unwrap_or(false)
                && chains.var_integral(v).is_some()
        })
        .collect();
    let mut eqs: Vec<EqId> = graph
        .eqs()
        .filter(|&e| chains.eq_derivative(e).is_none() && chains.eq_integral(e).is_some())
        .collect();
    let in_input = in_input(graph, pantelides);
    let mut selector = LevelSelector::new(n_vars);
    let mut result = DummyDerivatives {
        is_dummy: vec![false; n_vars],
        ..DummyDerivatives::default()
    };
    let mut level = 1u32;
    while !eqs.is_empty() {
        let mut candidates = selector.candidates(graph, &eqs, &allowed);
        candidates.sort_by_key(|&d| {
            let state = chains.var_integral(d).expect("candidates are derivatives");
            (
                priority(state),
                fixed_start(state),
                Reverse(var_levels[state.index()]),
                in_input[d.index()],
                d,
            )
        });
        let assignments = level_assignments(
            graph,
            &mut selector,
            &eqs,
            &candidates,
            level,
            &mut coefficient,
        )?;
        allowed.fill(false);
        for &(_, d) in &assignments {
            result.is_dummy[d.index()] = true;
            let state = chains.var_integral(d).expect("candidates are derivatives");
            if priority(state) == StateSelectPriority::Always {
                result.always_not_states.push(state);
            }
            if chains.var_integral(state).is_some() {
                allowed[state.index()] = true;
            }
        }
        for (comp_eqs, comp_vars) in components(graph, &eqs, &candidates) {
            if comp_vars.len() <= comp_eqs.len() || !dynamic(&comp_eqs, &comp_vars) {
                continue;
            }
            let initial: Vec<VarId> = assignments
                .iter()
                .map(|&(_, d)| d)
                .filter(|d| comp_vars.contains(d))
                .collect();
            for &d in &comp_vars {
                result.is_dummy[d.index()] = true;
                let state = chains.var_integral(d).expect("candidates are derivatives");
                if chains.var_integral(state).is_some() {
                    allowed[state.index()] = true;
                }
            }
            result.state_sets.push(StateSetSpec {
                level,
                eqs: comp_eqs,
                candidates: comp_vars,
                initial,
            });
        }
        result.levels.push(DummyLevel { level, assignments });
        eqs = eqs
            .iter()
            .filter_map(|&e| chains.eq_integral(e))
            .filter(|&e| chains.eq_integral(e).is_some())
            .collect();
        level += 1;
    }
    classify_variables(graph, pantelides, &mut result);
    Ok(result)
}

/// A level's dummies: the structural choice, made regular where `coefficient` shows
/// it singular.
fn level_assignments(
    graph: &BipartiteGraph,
    selector: &mut LevelSelector,
    eqs: &[EqId],
    candidates: &[VarId],
    level: u32,
    coefficient: &mut Option<Coefficient<'_>>,
) -> Result<Vec<(EqId, VarId)>, StructError> {
    let mut assignments = selector
        .select(graph, eqs, candidates)
        .map_err(|eqs| StructError::DummySelectionFailed { level, eqs })?;
    if let Some(coefficient) = coefficient.as_mut() {
        regularize(
            graph,
            selector,
            eqs,
            candidates,
            &mut assignments,
            &mut **coefficient,
        );
    }
    Ok(assignments)
}

/// Replaces, per connected component of the level, a numerically singular choice of
/// dummies by the first regular one ([`regular_choice`]).
fn regularize(
    graph: &BipartiteGraph,
    selector: &mut LevelSelector,
    eqs: &[EqId],
    candidates: &[VarId],
    assignments: &mut Vec<(EqId, VarId)>,
    coefficient: Coefficient<'_>,
) {
    let occurs = |e: EqId, v: VarId| graph.contains_edge(e, v);
    let comps = components(graph, eqs, candidates);
    let mut comp_of: std::collections::HashMap<VarId, usize> = Default::default();
    for (k, (_, vars)) in comps.iter().enumerate() {
        comp_of.extend(vars.iter().map(|&v| (v, k)));
    }
    let mut chosen: Vec<Vec<VarId>> = vec![Vec::new(); comps.len()];
    for &(_, d) in assignments.iter() {
        chosen[comp_of[&d]].push(d);
    }
    let mut replaced: Vec<Vec<(EqId, VarId)>> = vec![Vec::new(); comps.len()];
    let mut any = false;
    for (k, (comp_eqs, comp_vars)) in comps.iter().enumerate() {
        let Some(choice) = regular_choice(comp_eqs, comp_vars, &chosen[k], &occurs, coefficient)
        else {
            continue;
        };
        // A regular square matrix has a nonzero term in its determinant: a matching.
        if let Ok(matched) = selector.select(graph, comp_eqs, &choice) {
            replaced[k] = matched;
            any = true;
        }
    }
    if any {
        assignments.retain(|(_, d)| replaced[comp_of[d]].is_empty());
        assignments.extend(replaced.into_iter().flatten());
    }
}

/// The variables that occur in an equation of the input (not only in equations made by
/// index reduction): the model's own states. At equal priority the derivatives that
/// index reduction introduced become dummies first, so the model's states stay states
/// (the usual "natural states" rule). Without it the order by id prefers the input's
/// derivatives as dummies: a body's position then becomes algebraic and is solved from
/// the velocity of a contact point, v_P = v + omega x (r_P - r), whose Jacobian in r is
/// singular.
fn in_input(graph: &BipartiteGraph, pantelides: &PantelidesResult) -> Vec<bool> {
    let mut in_input = vec![false; graph.n_vars()];
    for e in graph.eqs() {
        if pantelides.chains.eq_integral(e).is_none() {
            for &v in graph.eq_vars(e) {
                in_input[v.index()] = true;
            }
        }
    }
    in_input
}

/// The connected components of a level's graph (equations × candidates, candidates in
/// their given order), each as (equations, candidates).
fn components(
    graph: &BipartiteGraph,
    eqs: &[EqId],
    candidates: &[VarId],
) -> Vec<(Vec<EqId>, Vec<VarId>)> {
    let local: std::collections::HashMap<VarId, usize> = candidates
        .iter()
        .enumerate()
        .map(|(i, &v)| (v, i))
        .collect();
    // Union-find over the candidates; each equation joins the candidates it contains.
    let mut parent: Vec<usize> = (0..candidates.len()).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut eq_root = Vec::with_capacity(eqs.len());
    for &e in eqs {
        let mut first = None;
        for v in graph.eq_vars(e) {
            if let Some(&i) = local.get(v) {
                match first {
                    None => first = Some(i),
                    Some(f) => {
                        let (a, b) = (find(&mut parent, f), find(&mut parent, i));
                        parent[a] = b;
                    }
                }
            }
        }
        eq_root.push(first);
    }
    let mut index_of_root: std::collections::HashMap<usize, usize> = Default::default();
    let mut out: Vec<(Vec<EqId>, Vec<VarId>)> = Vec::new();
    for (i, &v) in candidates.iter().enumerate() {
        let r = find(&mut parent, i);
        let k = *index_of_root.entry(r).or_insert_with(|| {
            out.push((Vec::new(), Vec::new()));
            out.len() - 1
        });
        out[k].1.push(v);
    }
    for (j, &e) in eqs.iter().enumerate() {
        if let Some(i) = eq_root[j] {
            let r = find(&mut parent, i);
            out[index_of_root[&r]].0.push(e);
        }
    }
    out
}

/// Fills states, dummy states and unknowns from the dummies.
fn classify_variables(
    graph: &BipartiteGraph,
    pantelides: &PantelidesResult,
    result: &mut DummyDerivatives,
) {
    let chains = &pantelides.chains;
    let degrees = graph.var_degrees();
    let mut present = vec![false; graph.n_vars()];
    for top in graph.vars() {
        if chains.var_derivative(top).is_some() {
            continue;
        }
        let (mut v, mut occurs) = (top, false);
        loop {
            occurs |= degrees[v.index()] > 0;
            present[v.index()] = occurs;
            match chains.var_integral(v) {
                Some(below) => v = below,
                None => break,
            }
        }
    }
    result.is_unknown = vec![false; graph.n_vars()];
    for v in graph.vars() {
        let derivative = chains.var_derivative(v).filter(|d| present[d.index()]);
        match derivative {
            Some(d) if result.is_dummy[d.index()] => result.dummy_states.push(v),
            Some(_) => result.states.push(v),
            None => {}
        }
        let is_state = derivative.is_some_and(|d| !result.is_dummy[d.index()]);
        result.is_unknown[v.index()] = degrees[v.index()] > 0 && !is_state;
        if result.is_dummy[v.index()] {
            result.dummies.push(v);
        }
    }
    result.always_not_states.sort_unstable();
}

/// Scratch space for one level: a local graph candidates × equations and a greedy
/// sequence of pruned augmenting-path searches from the candidates in order.
struct LevelSelector {
    local_of: Vec<u32>,
}

const NOT_LOCAL: u32 = u32::MAX;

impl LevelSelector {
    fn new(n_vars: usize) -> LevelSelector {
        LevelSelector {
            local_of: vec![NOT_LOCAL; n_vars],
        }
    }

    /// The allowed variables occurring in `eqs`, without duplicates.
    fn candidates(&mut self, graph: &BipartiteGraph, eqs: &[EqId], allowed: &[bool]) -> Vec<VarId> {
        let mut candidates = Vec::new();
        for &e in eqs {
            for &v in graph.eq_vars(e) {
                if allowed[v.index()] && self.local_of[v.index()] == NOT_LOCAL {
                    self.local_of[v.index()] = 0;
                    candidates.push(v);
                }
            }
        }
        for v in &candidates {
            self.local_of[v.index()] = NOT_LOCAL;
        }
        candidates
    }

    /// Assigns each equation a distinct candidate, preferring earlier candidates; Err
    /// with the equations left over when that is impossible.
    fn select(
        &mut self,
        graph: &BipartiteGraph,
        eqs: &[EqId],
        candidates: &[VarId],
    ) -> Result<Vec<(EqId, VarId)>, Vec<EqId>> {
        for (i, v) in candidates.iter().enumerate() {
            self.local_of[v.index()] = i as u32;
        }
        let mut adjacency = vec![Vec::new(); candidates.len()];
        for (j, &e) in eqs.iter().enumerate() {
            for v in graph.eq_vars(e) {
                let local = self.local_of[v.index()];
                if local != NOT_LOCAL {
                    adjacency[local as usize].push(VarId::new(j));
                }
            }
        }
        for v in candidates {
            self.local_of[v.index()] = NOT_LOCAL;
        }
        let local =
            BipartiteGraph::from_adjacency(eqs.len(), adjacency).expect("local ids are in range");
        let mut matching = Matching::for_graph(&local);
        let mut search = AugmentingPathSearch::pruning();
        let mut matched = 0;
        for candidate in local.eqs() {
            if matched == eqs.len() {
                break;
            }
            matched +=
                usize::from(search.augment_from_eq(&local, &mut matching, candidate, |_| true));
        }
        if matched < eqs.len() {
            let left: Vec<EqId> = local
                .vars()
                .filter(|j| matching.eq_of(*j).is_none())
                .map(|j| eqs[j.index()])
                .collect();
            return Err(left);
        }
        Ok(local
            .vars()
            .map(|j| {
                let candidate = matching.eq_of(j).expect("all matched");
                (eqs[j.index()], candidates[candidate.index()])
            })
            .collect())
    }
}
