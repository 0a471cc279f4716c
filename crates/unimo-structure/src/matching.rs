//! Maximum bipartite matching: Hopcroft–Karp after a greedy start, and a reusable
//! single-source augmenting-path search whose visited ("colored") sets Pantelides needs.
//!
//! Every search is iterative (explicit stacks), so long chains cannot overflow the stack.

use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};

/// A matching between equations and variables, stored in both directions. Invariant:
/// `eq_to_var[e] == Some(v)` exactly when `var_to_eq[v] == Some(e)`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Matching {
    pub eq_to_var: Vec<Option<VarId>>,
    pub var_to_eq: Vec<Option<EqId>>,
}

impl Matching {
    /// The empty matching for `n_eqs` equations and `n_vars` variables.
    pub fn new(n_eqs: usize, n_vars: usize) -> Matching {
        Matching {
            eq_to_var: vec![None; n_eqs],
            var_to_eq: vec![None; n_vars],
        }
    }

    /// The empty matching sized for a graph.
    pub fn for_graph(graph: &BipartiteGraph) -> Matching {
        Matching::new(graph.n_eqs(), graph.n_vars())
    }

    /// Extends the matching to more equations and variables (never shrinks).
    pub fn grow(&mut self, n_eqs: usize, n_vars: usize) {
        if self.eq_to_var.len() < n_eqs {
            self.eq_to_var.resize(n_eqs, None);
        }
        if self.var_to_eq.len() < n_vars {
            self.var_to_eq.resize(n_vars, None);
        }
    }

    /// The variable matched to an equation.
    pub fn var_of(&self, eq: EqId) -> Option<VarId> {
        self.eq_to_var.get(eq.index()).copied().flatten()
    }

    /// The equation matched to a variable.
    pub fn eq_of(&self, var: VarId) -> Option<EqId> {
        self.var_to_eq.get(var.index()).copied().flatten()
    }

    /// Matches `eq` with `var`, first releasing any partner either had.
    pub fn set(&mut self, eq: EqId, var: VarId) {
        self.unmatch_eq(eq);
        self.unmatch_var(var);
        self.eq_to_var[eq.index()] = Some(var);
        self.var_to_eq[var.index()] = Some(eq);
    }

    /// Releases an equation and its partner, if any.
    pub fn unmatch_eq(&mut self, eq: EqId) {
        if let Some(var) = self.eq_to_var[eq.index()].take() {
            self.var_to_eq[var.index()] = None;
        }
    }

    /// Releases a variable and its partner, if any.
    pub fn unmatch_var(&mut self, var: VarId) {
        if let Some(eq) = self.var_to_eq[var.index()].take() {
            self.eq_to_var[eq.index()] = None;
        }
    }

    /// The number of matched pairs.
    pub fn size(&self) -> usize {
        self.eq_to_var.iter().filter(|v| v.is_some()).count()
    }

    /// The matched pairs in equation order.
    pub fn pairs(&self) -> impl Iterator<Item = (EqId, VarId)> + '_ {
        self.eq_to_var
            .iter()
            .enumerate()
            .filter_map(|(e, v)| v.map(|v| (EqId::new(e), v)))
    }

    /// Equations without a partner.
    pub fn unmatched_eqs(&self) -> Vec<EqId> {
        (0..self.eq_to_var.len())
            .filter(|&e| self.eq_to_var[e].is_none())
            .map(EqId::new)
            .collect()
    }

    /// Variables without a partner.
    pub fn unmatched_vars(&self) -> Vec<VarId> {
        (0..self.var_to_eq.len())
            .filter(|&v| self.var_to_eq[v].is_none())
            .map(VarId::new)
            .collect()
    }
}

/// A maximum matching of the whole graph.
pub fn maximum_matching(graph: &BipartiteGraph) -> Matching {
    maximum_matching_where(graph, |_| true, |_| true)
}

/// A maximum matching of the subgraph of equations with `eq_allowed` and variables
/// with `var_allowed` (Pantelides matches only highest-derivative variables).
pub fn maximum_matching_where(
    graph: &BipartiteGraph,
    eq_allowed: impl Fn(EqId) -> bool,
    var_allowed: impl Fn(VarId) -> bool,
) -> Matching {
    let mut matching = Matching::for_graph(graph);
    complete_matching_where(graph, &mut matching, eq_allowed, var_allowed);
    matching
}

/// Extends an existing matching (pairs must lie in the allowed subgraph) to a maximum
/// matching of the allowed subgraph: greedy assignment, then Hopcroft–Karp phases.
pub fn complete_matching_where(
    graph: &BipartiteGraph,
    matching: &mut Matching,
    eq_allowed: impl Fn(EqId) -> bool,
    var_allowed: impl Fn(VarId) -> bool,
) {
    matching.grow(graph.n_eqs(), graph.n_vars());
    let eq_ok: Vec<bool> = graph.eqs().map(&eq_allowed).collect();
    let var_ok: Vec<bool> = graph.vars().map(&var_allowed).collect();
    greedy_assign(graph, matching, &eq_ok, &var_ok);
    let mut phases = HopcroftKarp::new(graph.n_eqs());
    while phases.layer(graph, matching, &eq_ok, &var_ok) {
        if phases.augment_all(graph, matching, &eq_ok, &var_ok) == 0 {
            break;
        }
    }
}

/// Cheap start: each free equation takes its first free variable, equations of degree
/// one first so that they are not starved by longer ones.
fn greedy_assign(graph: &BipartiteGraph, matching: &mut Matching, eq_ok: &[bool], var_ok: &[bool]) {
    for pass_low_degree in [true, false] {
        for e in graph.eqs() {
            if !eq_ok[e.index()] || matching.eq_to_var[e.index()].is_some() {
                continue;
            }
            let vars = graph.eq_vars(e);
            let allowed = vars.iter().filter(|v| var_ok[v.index()]);
            if pass_low_degree && allowed.clone().count() != 1 {
                continue;
            }
            let free = allowed
                .copied()
                .find(|v| matching.var_to_eq[v.index()].is_none());
            if let Some(v) = free {
                matching.eq_to_var[e.index()] = Some(v);
                matching.var_to_eq[v.index()] = Some(e);
            }
        }
    }
}

const UNREACHED: u32 = u32::MAX;

/// Workspace of the Hopcroft–Karp phases: BFS layers from free equations, then
/// vertex-disjoint shortest augmenting paths by iterative DFS along the layers.
struct HopcroftKarp {
    layer_of: Vec<u32>,
    queue: Vec<EqId>,
    next_edge: Vec<u32>,
    free_var_layer: u32,
    stack: Vec<EqId>,
    via: Vec<VarId>,
}

impl HopcroftKarp {
    fn new(n_eqs: usize) -> HopcroftKarp {
        HopcroftKarp {
            layer_of: vec![UNREACHED; n_eqs],
            queue: Vec::new(),
            next_edge: vec![0; n_eqs],
            free_var_layer: UNREACHED,
            stack: Vec::new(),
            via: Vec::new(),
        }
    }

    /// Builds the BFS layers; false when no augmenting path exists.
    fn layer(
        &mut self,
        graph: &BipartiteGraph,
        m: &Matching,
        eq_ok: &[bool],
        var_ok: &[bool],
    ) -> bool {
        self.layer_of.fill(UNREACHED);
        self.queue.clear();
        for e in graph.eqs() {
            if eq_ok[e.index()] && m.eq_to_var[e.index()].is_none() {
                self.layer_of[e.index()] = 0;
                self.queue.push(e);
            }
        }
        self.free_var_layer = UNREACHED;
        let mut head = 0;
        while head < self.queue.len() {
            let e = self.queue[head];
            head += 1;
            let next = self.layer_of[e.index()] + 1;
            if next > self.free_var_layer {
                break;
            }
            for &v in graph.eq_vars(e) {
                if !var_ok[v.index()] {
                    continue;
                }
                match m.var_to_eq[v.index()] {
                    None => self.free_var_layer = self.free_var_layer.min(next),
                    Some(mate) if self.layer_of[mate.index()] == UNREACHED => {
                        self.layer_of[mate.index()] = next;
                        self.queue.push(mate);
                    }
                    Some(_) => {}
                }
            }
        }
        self.free_var_layer != UNREACHED
    }

    /// Augments along vertex-disjoint shortest paths; returns how many.
    fn augment_all(
        &mut self,
        graph: &BipartiteGraph,
        m: &mut Matching,
        eq_ok: &[bool],
        var_ok: &[bool],
    ) -> usize {
        self.next_edge.fill(0);
        let mut count = 0;
        for root in graph.eqs() {
            if eq_ok[root.index()]
                && m.eq_to_var[root.index()].is_none()
                && self.layer_of[root.index()] == 0
            {
                count += usize::from(self.augment_from(graph, m, root, var_ok));
            }
        }
        count
    }

    fn augment_from(
        &mut self,
        graph: &BipartiteGraph,
        m: &mut Matching,
        root: EqId,
        var_ok: &[bool],
    ) -> bool {
        self.stack.clear();
        self.via.clear();
        self.stack.push(root);
        while let Some(&e) = self.stack.last() {
            let vars = graph.eq_vars(e);
            let position = self.next_edge[e.index()] as usize;
            if position == vars.len() {
                self.layer_of[e.index()] = UNREACHED;
                self.stack.pop();
                self.via.pop();
                continue;
            }
            self.next_edge[e.index()] += 1;
            let v = vars[position];
            if !var_ok[v.index()] {
                continue;
            }
            let layer = self.layer_of[e.index()];
            match m.var_to_eq[v.index()] {
                None if layer + 1 == self.free_var_layer => {
                    flip_path(m, &self.stack, &self.via, v);
                    return true;
                }
                None => {}
                Some(mate) if self.layer_of[mate.index()] == layer + 1 => {
                    self.via.push(v);
                    self.stack.push(mate);
                }
                Some(_) => {}
            }
        }
        false
    }
}

/// Applies an augmenting path: `eqs[i]` takes `via[i]` (which was matched to
/// `eqs[i + 1]`), the last equation takes the free variable.
fn flip_path(m: &mut Matching, eqs: &[EqId], via: &[VarId], free: VarId) {
    for (&e, &v) in eqs.iter().zip(via) {
        m.eq_to_var[e.index()] = Some(v);
        m.var_to_eq[v.index()] = Some(e);
    }
    let last = *eqs.last().expect("a path has a root");
    m.eq_to_var[last.index()] = Some(free);
    m.var_to_eq[free.index()] = Some(last);
}

/// A reusable single-source augmenting-path search (depth first, with a look-ahead for
/// a free variable at each equation). After a failed search, [`Self::colored_eqs`] and
/// [`Self::colored_vars`] are the equations and allowed variables it visited — the sets
/// Pantelides differentiates. Marks are time-stamped, so a search costs only what it
/// visits, not the size of the graph.
#[derive(Clone, Debug, Default)]
pub struct AugmentingPathSearch {
    eq_stamp: Vec<u32>,
    var_stamp: Vec<u32>,
    stamp: u32,
    eq_dead: Vec<bool>,
    var_dead: Vec<bool>,
    colored_eqs: Vec<EqId>,
    colored_vars: Vec<VarId>,
    stack: Vec<(EqId, u32)>,
    via: Vec<VarId>,
    /// Failed searches leave their region dead ([`Self::pruning`]).
    prune: bool,
}

impl AugmentingPathSearch {
    /// An empty workspace; it grows with the graphs it is used on.
    pub fn new() -> AugmentingPathSearch {
        AugmentingPathSearch::default()
    }

    /// An empty workspace whose searches prune: the region a failed search visited
    /// stays marked dead for later searches on the same graph and allowed set (no
    /// augmenting path can pass through it while the matching changes only by these
    /// searches). This makes a greedy sequence of searches (one per candidate root) near
    /// linear. Call [`Self::clear_dead`] before using the workspace on another problem.
    pub fn pruning() -> AugmentingPathSearch {
        AugmentingPathSearch {
            prune: true,
            ..AugmentingPathSearch::default()
        }
    }

    /// Equations visited by the last search.
    pub fn colored_eqs(&self) -> &[EqId] {
        &self.colored_eqs
    }

    /// Allowed variables visited by the last search.
    pub fn colored_vars(&self) -> &[VarId] {
        &self.colored_vars
    }

    /// Looks for an augmenting path from the free equation `root` through variables
    /// with `var_allowed`; applies it and returns true when found.
    pub fn augment_from_eq(
        &mut self,
        graph: &BipartiteGraph,
        matching: &mut Matching,
        root: EqId,
        var_allowed: impl Fn(VarId) -> bool,
    ) -> bool {
        self.search(graph, matching, root, &var_allowed)
    }

    /// Forgets the dead regions left by pruned searches.
    pub fn clear_dead(&mut self) {
        self.eq_dead.fill(false);
        self.var_dead.fill(false);
    }

    fn prepare(&mut self, graph: &BipartiteGraph) {
        let (n_eqs, n_vars) = (graph.n_eqs(), graph.n_vars());
        if self.eq_stamp.len() < n_eqs {
            self.eq_stamp.resize(n_eqs, 0);
            self.eq_dead.resize(n_eqs, false);
        }
        if self.var_stamp.len() < n_vars {
            self.var_stamp.resize(n_vars, 0);
            self.var_dead.resize(n_vars, false);
        }
        if self.stamp == u32::MAX {
            self.eq_stamp.fill(0);
            self.var_stamp.fill(0);
            self.stamp = 0;
        }
        self.stamp += 1;
        self.colored_eqs.clear();
        self.colored_vars.clear();
        self.stack.clear();
        self.via.clear();
    }

    fn visit_eq(&mut self, e: EqId) {
        self.eq_stamp[e.index()] = self.stamp;
        self.colored_eqs.push(e);
        self.stack.push((e, 0));
    }

    fn search(
        &mut self,
        graph: &BipartiteGraph,
        m: &mut Matching,
        root: EqId,
        var_allowed: &dyn Fn(VarId) -> bool,
    ) -> bool {
        let prune = self.prune;
        m.grow(graph.n_eqs(), graph.n_vars());
        self.prepare(graph);
        if prune && self.eq_dead[root.index()] {
            return false;
        }
        self.visit_eq(root);
        while let Some(&(e, position)) = self.stack.last() {
            let vars = graph.eq_vars(e);
            if position == 0 {
                let free = vars.iter().copied().find(|&v| {
                    m.var_to_eq[v.index()].is_none()
                        && !(prune && self.var_dead[v.index()])
                        && var_allowed(v)
                });
                if let Some(v) = free {
                    let eqs: Vec<EqId> = self.stack.iter().map(|&(e, _)| e).collect();
                    flip_path(m, &eqs, &self.via, v);
                    return true;
                }
            }
            if position as usize == vars.len() {
                self.stack.pop();
                self.via.pop();
                continue;
            }
            self.stack.last_mut().expect("nonempty").1 += 1;
            let v = vars[position as usize];
            if self.var_stamp[v.index()] == self.stamp
                || (prune && self.var_dead[v.index()])
                || !var_allowed(v)
            {
                continue;
            }
            self.var_stamp[v.index()] = self.stamp;
            self.colored_vars.push(v);
            let Some(mate) = m.var_to_eq[v.index()] else {
                continue;
            };
            if self.eq_stamp[mate.index()] == self.stamp || (prune && self.eq_dead[mate.index()]) {
                continue;
            }
            self.via.push(v);
            self.visit_eq(mate);
        }
        if prune {
            for &e in &self.colored_eqs {
                self.eq_dead[e.index()] = true;
            }
            for &v in &self.colored_vars {
                self.var_dead[v.index()] = true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hopcroft_karp_reroutes_a_greedy_choice() {
        // e0: v0 v1, e1: v0 — greedy gives e1 v0 first (degree one), e0 then v1.
        // e2: v1 v2 must reroute.
        let g =
            BipartiteGraph::from_edges(3, 3, &[(0, 0), (0, 1), (1, 0), (2, 1), (2, 2)]).unwrap();
        let m = maximum_matching(&g);
        assert_eq!(m.size(), 3);
    }

    #[test]
    fn long_chain_matches_without_recursion() {
        // e_i: v_i v_{i+1}, the last equation only v_n; greedy order forces long paths.
        let n = 200_000u32;
        let mut edges = Vec::new();
        for i in 0..n {
            edges.push((i, i + 1));
            edges.push((i, i));
        }
        let g = BipartiteGraph::from_edges(n as usize, n as usize + 1, &edges).unwrap();
        let m = maximum_matching(&g);
        assert_eq!(m.size(), n as usize);
    }

    #[test]
    fn single_source_search_reports_colored_sets() {
        // e0: v0; e1: v0 — e1 cannot be matched; search visits e1, v0, e0.
        let g = BipartiteGraph::from_edges(2, 1, &[(0, 0), (1, 0)]).unwrap();
        let mut m = Matching::for_graph(&g);
        m.set(EqId(0), VarId(0));
        let mut s = AugmentingPathSearch::new();
        assert!(!s.augment_from_eq(&g, &mut m, EqId(1), |_| true));
        assert_eq!(s.colored_eqs(), &[EqId(1), EqId(0)]);
        assert_eq!(s.colored_vars(), &[VarId(0)]);
    }

    #[test]
    fn pruned_searches_keep_the_matching_maximum() {
        let g = BipartiteGraph::from_edges(4, 3, &[(0, 0), (1, 0), (2, 0), (2, 1), (3, 2), (3, 1)])
            .unwrap();
        let mut m = Matching::for_graph(&g);
        let mut s = AugmentingPathSearch::pruning();
        let found = g
            .eqs()
            .filter(|&e| s.augment_from_eq(&g, &mut m, e, |_| true))
            .count();
        assert_eq!(found, maximum_matching(&g).size());
    }
}
