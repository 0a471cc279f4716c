//! Pantelides index reduction: match every equation to a highest-derivative variable,
//! differentiating the equations of each failed augmenting-path search.

use crate::chains::DerivativeChains;
use crate::dm::dulmage_mendelsohn_where;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::{maximum_matching_where, AugmentingPathSearch, Matching};

/// What the structural algorithms need from the symbolic side (compare StateSelection.jl's
/// `interface.jl`): the incidence graph, the derivative relations, and two callbacks
/// that grow the system. Contract: ids are dense; `add_var_derivative` and
/// `differentiate_eq` add to `graph()` and keep `var_derivative`/`eq_derivative`
/// consistent with what they added; a derivative is never removed.
pub trait IndexReductionSystem {
    fn graph(&self) -> &BipartiteGraph;
    /// The derivative variable of v if the system has one (der(x) for x).
    fn var_derivative(&self, v: VarId) -> Option<VarId>;
    /// Adds the derivative variable of v (no equations change); returns its id. The graph gains a var.
    fn add_var_derivative(&mut self, v: VarId) -> VarId;
    /// The differentiated form of e if already made.
    fn eq_derivative(&self, e: EqId) -> Option<EqId>;
    /// Differentiates e w.r.t. time, adding a new equation (and any derivative variables
    /// it needs via the system's own bookkeeping); returns the new equation's id, whose
    /// incidence is in graph(). Err when it cannot be differentiated (e.g. contains a
    /// non-differentiable function or a discrete variable), with a reason string.
    fn differentiate_eq(&mut self, e: EqId) -> Result<EqId, String>;
}

/// Limits of [`pantelides_with_options`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PantelidesOptions {
    /// How many times one equation may be differentiated; default: number of equations
    /// plus number of variables of the input, plus one.
    pub max_differentiations: Option<u32>,
}

/// The outcome of index reduction. Invariants: `matching` pairs every equation that has
/// no derivative (a "top" equation) with a variable marked in `highest_vars`, and only
/// those; `highest_vars` marks, per derivative chain, the highest derivative occurring
/// in the system; `chains` are the system's relations after reduction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PantelidesResult {
    pub matching: Matching,
    pub chains: DerivativeChains,
    pub highest_vars: Vec<bool>,
    /// Per equation of the final graph: how many derivatives were made of it.
    pub differentiation_count: Vec<u32>,
}

impl PantelidesResult {
    /// The most any equation was differentiated. The structural index is this plus one,
    /// unless the reduced system is a pure ODE.
    pub fn max_differentiations(&self) -> u32 {
        self.differentiation_count
            .iter()
            .copied()
            .max()
            .unwrap_or(0)
    }

    /// The equations that were made by differentiation.
    pub fn differentiated_eqs(&self) -> Vec<EqId> {
        (0..self.chains.eq_integral.len())
            .filter(|&e| self.chains.eq_integral[e].is_some())
            .map(EqId::new)
            .collect()
    }
}

/// Runs Pantelides' algorithm with default limits.
pub fn pantelides<S: IndexReductionSystem + ?Sized>(
    system: &mut S,
) -> Result<PantelidesResult, StructError> {
    pantelides_with_options(system, &PantelidesOptions::default())
}

/// Runs Pantelides' algorithm. First checks that every equation can be matched to a
/// distinct variable family (a variable with all its derivatives); without that the
/// algorithm would never stop, and the error names the over-determined equations (its
/// variables are the undifferentiated variables of the families involved).
pub fn pantelides_with_options<S: IndexReductionSystem + ?Sized>(
    system: &mut S,
    options: &PantelidesOptions,
) -> Result<PantelidesResult, StructError> {
    let chains = DerivativeChains::from_system(system)?;
    let mut state = ReductionState::new(system.graph(), &chains, options);
    let n_eqs = system.graph().n_eqs();
    let all_top_matched = (0..n_eqs)
        .all(|e| chains.eq_derivative[e].is_some() || state.matching.eq_to_var[e].is_some());
    if !all_top_matched {
        check_families_matchable(system.graph(), &chains)?;
    }
    for e in (0..n_eqs).map(EqId::new) {
        // Equations differentiated while reducing an earlier one are no longer top.
        if state.eq_derivative[e.index()].is_none() && state.matching.var_of(e).is_none() {
            state.reduce_equation(system, e)?;
        }
    }
    let chains = DerivativeChains::from_system(system)?;
    let differentiation_count = chains.differentiation_counts();
    let graph = system.graph();
    state.matching.grow(graph.n_eqs(), graph.n_vars());
    state.highest.resize(graph.n_vars(), false);
    Ok(PantelidesResult {
        matching: state.matching,
        chains,
        highest_vars: state.highest,
        differentiation_count,
    })
}

/// Structural nonsingularity in the sense Pantelides needs: the top equations can be
/// matched to distinct variable families.
fn check_families_matchable(
    graph: &BipartiteGraph,
    chains: &DerivativeChains,
) -> Result<(), StructError> {
    let roots = chains.var_roots();
    let adjacency: Vec<Vec<VarId>> = graph
        .eqs()
        .map(|e| graph.eq_vars(e).iter().map(|v| roots[v.index()]).collect())
        .collect();
    let families = BipartiteGraph::from_adjacency(graph.n_vars(), adjacency)?;
    let is_top = |e: EqId| chains.eq_derivative(e).is_none();
    let is_root = |v: VarId| chains.var_integral(v).is_none();
    let matching = maximum_matching_where(&families, is_top, is_root);
    let all_matched = families
        .eqs()
        .all(|e| !is_top(e) || matching.var_of(e).is_some());
    if all_matched {
        return Ok(());
    }
    let dm = dulmage_mendelsohn_where(&families, &matching, is_top, is_root);
    Err(dm.into_error())
}

/// Per chain, the highest derivative that occurs in some equation (the chain's top
/// when none occurs): the variables Pantelides may match.
fn highest_occurring_vars(graph: &BipartiteGraph, chains: &DerivativeChains) -> Vec<bool> {
    let degrees = graph.var_degrees();
    let mut highest = vec![false; graph.n_vars()];
    for top in graph.vars() {
        if chains.var_derivative(top).is_some() {
            continue;
        }
        let mut v = top;
        while degrees[v.index()] == 0 {
            match chains.var_integral(v) {
                Some(below) => v = below,
                None => {
                    v = top;
                    break;
                }
            }
        }
        highest[v.index()] = true;
    }
    highest
}

struct ReductionState {
    matching: Matching,
    highest: Vec<bool>,
    eq_derivative: Vec<Option<EqId>>,
    eq_level: Vec<u32>,
    eq_origin: Vec<EqId>,
    search: AugmentingPathSearch,
    limit: u32,
}

impl ReductionState {
    fn new(
        graph: &BipartiteGraph,
        chains: &DerivativeChains,
        options: &PantelidesOptions,
    ) -> ReductionState {
        let highest = highest_occurring_vars(graph, chains);
        let matching = maximum_matching_where(
            graph,
            |e| chains.eq_derivative(e).is_none(),
            |v| highest[v.index()],
        );
        let default_limit = graph.n_eqs() + graph.n_vars() + 1;
        ReductionState {
            matching,
            highest,
            eq_derivative: chains.eq_derivative.clone(),
            eq_level: graph.eqs().map(|e| chains.eq_level(e)).collect(),
            eq_origin: graph.eqs().map(|e| chains.eq_root(e)).collect(),
            search: AugmentingPathSearch::new(),
            limit: options
                .max_differentiations
                .unwrap_or(u32::try_from(default_limit).unwrap_or(u32::MAX)),
        }
    }

    /// Grows the per-item vectors to the graph's current size.
    fn grow(&mut self, graph: &BipartiteGraph) {
        let (n_eqs, n_vars) = (graph.n_eqs(), graph.n_vars());
        self.matching.grow(n_eqs, n_vars);
        self.highest.resize(n_vars.max(self.highest.len()), false);
        self.eq_derivative
            .resize(n_eqs.max(self.eq_derivative.len()), None);
        self.eq_level.resize(n_eqs.max(self.eq_level.len()), 0);
        while self.eq_origin.len() < n_eqs {
            self.eq_origin.push(EqId::new(self.eq_origin.len()));
        }
    }

    /// Matches `start`, differentiating the colored subsystem after each failed search
    /// and retrying from the derivative of the current equation.
    fn reduce_equation<S: IndexReductionSystem + ?Sized>(
        &mut self,
        system: &mut S,
        start: EqId,
    ) -> Result<(), StructError> {
        let mut current = start;
        loop {
            let highest = &self.highest;
            let found =
                self.search
                    .augment_from_eq(system.graph(), &mut self.matching, current, |v| {
                        highest.get(v.index()).copied().unwrap_or(false)
                    });
            if found {
                return Ok(());
            }
            let colored_eqs = self.search.colored_eqs().to_vec();
            let colored_vars = self.search.colored_vars().to_vec();
            for &e in &colored_eqs {
                if self.eq_level[e.index()] >= self.limit {
                    return Err(StructError::DifferentiationLimit {
                        eq: self.eq_origin[e.index()],
                        limit: self.limit,
                    });
                }
            }
            self.differentiate(system, &colored_eqs, &colored_vars)?;
            current = self.eq_derivative[current.index()].expect("the start equation is colored");
        }
    }

    /// Differentiates colored variables and equations; the derivatives inherit the
    /// colored pairs of the matching and become the highest derivatives.
    fn differentiate<S: IndexReductionSystem + ?Sized>(
        &mut self,
        system: &mut S,
        colored_eqs: &[EqId],
        colored_vars: &[VarId],
    ) -> Result<(), StructError> {
        let mut var_pairs = Vec::with_capacity(colored_vars.len());
        for &v in colored_vars {
            let dv = match system.var_derivative(v) {
                Some(dv) => dv,
                None => system.add_var_derivative(v),
            };
            check_new_id(dv.index(), system.graph().n_vars(), "add_var_derivative")?;
            var_pairs.push((v, dv));
        }
        self.grow(system.graph());
        for &e in colored_eqs {
            let de = match system.eq_derivative(e) {
                Some(de) => de,
                None => system
                    .differentiate_eq(e)
                    .map_err(|reason| StructError::IndexReductionFailed { eq: e, reason })?,
            };
            check_new_id(de.index(), system.graph().n_eqs(), "differentiate_eq")?;
            self.grow(system.graph());
            self.eq_derivative[e.index()] = Some(de);
            self.eq_level[de.index()] = self.eq_level[e.index()] + 1;
            self.eq_origin[de.index()] = self.eq_origin[e.index()];
        }
        for (v, dv) in var_pairs {
            self.highest[v.index()] = false;
            self.highest[dv.index()] = true;
            let Some(e) = self.matching.eq_of(v) else {
                continue;
            };
            self.matching.unmatch_var(v);
            if let Some(de) = self.eq_derivative[e.index()] {
                self.matching.set(de, dv);
            }
        }
        Ok(())
    }
}

fn check_new_id(index: usize, bound: usize, what: &'static str) -> Result<(), StructError> {
    if index < bound {
        Ok(())
    } else {
        Err(StructError::invalid(
            what,
            format!("returned id #{index}, but the graph has {bound}"),
        ))
    }
}
