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
    let unmatched_eqs = graph
        .eqs()
        .filter(|e| eq_ok[e.index()] && matching.var_of(*e).is_none())
        .collect();
    let (eqs, vars) = alternate(
        unmatched_eqs,
        (&mut eq_seen, &var_ok, &mut var_seen),
        |e| graph.eq_vars(e),
        |v| matching.eq_of(v),
    );
    let over = Part { eqs, vars };
    let incidence = graph.transpose();
    let unmatched_vars = graph
        .vars()
        .filter(|v| var_ok[v.index()] && matching.eq_of(*v).is_none() && !var_seen[v.index()])
        .collect();
    let (vars, eqs) = alternate(
        unmatched_vars,
        (&mut var_seen, &eq_ok, &mut eq_seen),
        |v| incidence.var_eqs(v),
        |e| matching.var_of(e),
    );
    let under = Part { eqs, vars };
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

/// An equation or a variable, for [`alternate`], which walks from either side.
trait Node: Copy + Ord {
    fn at(self) -> usize;
}

impl Node for EqId {
    fn at(self) -> usize {
        self.index()
    }
}

impl Node for VarId {
    fn at(self) -> usize {
        self.index()
    }
}

/// The nodes reached by alternating paths from `starts` (nodes of side A, marked seen
/// here): from an A node along `edges` to the allowed, unseen B nodes, from each of
/// these along the matching (`mate`) back to an A node. Returns the A and the B nodes
/// reached, each sorted; `seen` is `(A seen, B allowed, B seen)`.
fn alternate<'g, A: Node, B: Node + 'g>(
    starts: Vec<A>,
    (a_seen, b_ok, b_seen): (&mut [bool], &[bool], &mut [bool]),
    edges: impl Fn(A) -> &'g [B],
    mate: impl Fn(B) -> Option<A>,
) -> (Vec<A>, Vec<B>) {
    let mut queue = starts;
    for a in &queue {
        a_seen[a.at()] = true;
    }
    let (mut reached_a, mut reached_b) = (Vec::new(), Vec::new());
    while let Some(a) = queue.pop() {
        reached_a.push(a);
        for &b in edges(a) {
            if !b_ok[b.at()] || b_seen[b.at()] {
                continue;
            }
            b_seen[b.at()] = true;
            reached_b.push(b);
            if let Some(next) = mate(b) {
                if !a_seen[next.at()] {
                    a_seen[next.at()] = true;
                    queue.push(next);
                }
            }
        }
    }
    reached_a.sort_unstable();
    reached_b.sort_unstable();
    (reached_a, reached_b)
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
