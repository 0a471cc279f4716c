//! Dulmage–Mendelsohn coarse decomposition: over-, under- and well-determined parts,
//! read off a maximum matching by alternating-path reachability.

use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::{maximum_matching_where, Matching};

/// A set of equations with a set of variables, both sorted.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Part {
    pub eqs: Vec<EqId>,
    pub vars: Vec<VarId>,
}

impl Part {
    /// Whether the part has neither equations nor variables.
    pub fn is_empty(&self) -> bool {
        self.eqs.is_empty() && self.vars.is_empty()
    }
}

/// The coarse decomposition. `over`: equations reachable by alternating paths from an
/// unmatched equation, with their variables (more equations than variables). `under`:
/// variables reachable from an unmatched variable, with their equations (more variables
/// than equations). `well`: the rest, perfectly matched. The three parts are disjoint
/// and do not depend on which maximum matching was used.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DulmageMendelsohn {
    pub over: Part,
    pub under: Part,
    pub well: Part,
}

impl DulmageMendelsohn {
    /// Whether the allowed subgraph is structurally nonsingular (a perfect matching).
    pub fn is_nonsingular(&self) -> bool {
        self.over.is_empty() && self.under.is_empty()
    }

    /// The decomposition as a [`StructError::Singular`].
    pub fn into_error(self) -> StructError {
        StructError::Singular {
            over: self.over,
            under: self.under,
        }
    }
}

/// The decomposition of the whole graph, given a maximum matching of it.
pub fn dulmage_mendelsohn(graph: &BipartiteGraph, matching: &Matching) -> DulmageMendelsohn {
    dulmage_mendelsohn_where(graph, matching, |_| true, |_| true)
}

/// The decomposition of the subgraph of allowed equations and variables, given a
/// maximum matching of that subgraph.
pub fn dulmage_mendelsohn_where(
    graph: &BipartiteGraph,
    matching: &Matching,
    eq_allowed: impl Fn(EqId) -> bool,
    var_allowed: impl Fn(VarId) -> bool,
) -> DulmageMendelsohn {
    let eq_ok: Vec<bool> = graph.eqs().map(&eq_allowed).collect();
    let var_ok: Vec<bool> = graph.vars().map(&var_allowed).collect();
    let mut eq_seen = vec![false; graph.n_eqs()];
    let mut var_seen = vec![false; graph.n_vars()];
    let over = reach_from_unmatched_eqs(
        graph,
        matching,
        &eq_ok,
        &var_ok,
        &mut eq_seen,
        &mut var_seen,
    );
    let under = reach_from_unmatched_vars(
        graph,
        matching,
        &eq_ok,
        &var_ok,
        &mut eq_seen,
        &mut var_seen,
    );
    let well = Part {
        eqs: graph
            .eqs()
            .filter(|e| eq_ok[e.index()] && !eq_seen[e.index()])
            .collect(),
        vars: graph
            .vars()
            .filter(|v| var_ok[v.index()] && !var_seen[v.index()])
            .collect(),
    };
    DulmageMendelsohn { over, under, well }
}

/// The error describing why the allowed subgraph has no perfect matching, or None when
/// it has one. Computes its own maximum matching.
pub fn singularity(
    graph: &BipartiteGraph,
    eq_allowed: impl Fn(EqId) -> bool + Copy,
    var_allowed: impl Fn(VarId) -> bool + Copy,
) -> Option<StructError> {
    let matching = maximum_matching_where(graph, eq_allowed, var_allowed);
    let dm = dulmage_mendelsohn_where(graph, &matching, eq_allowed, var_allowed);
    (!dm.is_nonsingular()).then(|| dm.into_error())
}

fn reach_from_unmatched_eqs(
    graph: &BipartiteGraph,
    matching: &Matching,
    eq_ok: &[bool],
    var_ok: &[bool],
    eq_seen: &mut [bool],
    var_seen: &mut [bool],
) -> Part {
    let mut part = Part::default();
    let mut queue: Vec<EqId> = graph
        .eqs()
        .filter(|e| eq_ok[e.index()] && matching.var_of(*e).is_none())
        .collect();
    for e in &queue {
        eq_seen[e.index()] = true;
    }
    while let Some(e) = queue.pop() {
        part.eqs.push(e);
        for &v in graph.eq_vars(e) {
            if !var_ok[v.index()] || var_seen[v.index()] {
                continue;
            }
            var_seen[v.index()] = true;
            part.vars.push(v);
            if let Some(mate) = matching.eq_of(v) {
                if !eq_seen[mate.index()] {
                    eq_seen[mate.index()] = true;
                    queue.push(mate);
                }
            }
        }
    }
    part.eqs.sort_unstable();
    part.vars.sort_unstable();
    part
}

fn reach_from_unmatched_vars(
    graph: &BipartiteGraph,
    matching: &Matching,
    eq_ok: &[bool],
    var_ok: &[bool],
    eq_seen: &mut [bool],
    var_seen: &mut [bool],
) -> Part {
    let incidence = graph.transpose();
    let mut part = Part::default();
    let mut queue: Vec<VarId> = graph
        .vars()
        .filter(|v| var_ok[v.index()] && matching.eq_of(*v).is_none() && !var_seen[v.index()])
        .collect();
    for v in &queue {
        var_seen[v.index()] = true;
    }
    while let Some(v) = queue.pop() {
        part.vars.push(v);
        for &e in incidence.var_eqs(v) {
            if !eq_ok[e.index()] || eq_seen[e.index()] {
                continue;
            }
            eq_seen[e.index()] = true;
            part.eqs.push(e);
            if let Some(mate) = matching.var_of(e) {
                if !var_seen[mate.index()] {
                    var_seen[mate.index()] = true;
                    queue.push(mate);
                }
            }
        }
    }
    part.eqs.sort_unstable();
    part.vars.sort_unstable();
    part
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matching::maximum_matching;

    #[test]
    fn splits_over_under_and_well_parts() {
        // e0: x; e1: x (over on x). e2: y z (under). e3: w (well).
        let g =
            BipartiteGraph::from_edges(4, 4, &[(0, 0), (1, 0), (2, 1), (2, 2), (3, 3)]).unwrap();
        let dm = dulmage_mendelsohn(&g, &maximum_matching(&g));
        assert_eq!(dm.over.eqs, vec![EqId(0), EqId(1)]);
        assert_eq!(dm.over.vars, vec![VarId(0)]);
        assert_eq!(dm.under.eqs, vec![EqId(2)]);
        assert_eq!(dm.under.vars, vec![VarId(1), VarId(2)]);
        assert_eq!(dm.well.eqs, vec![EqId(3)]);
        assert_eq!(dm.well.vars, vec![VarId(3)]);
    }
}
