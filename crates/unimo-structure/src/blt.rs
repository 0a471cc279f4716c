//! Block-lower-triangular ordering: strongly connected components (iterative Tarjan) of
//! the equation dependency graph induced by a perfect matching.

use crate::dm::dulmage_mendelsohn_where;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::{maximum_matching_where, Matching};

/// A block of equations solved together for as many variables: `eqs[i]` is matched to
/// `vars[i]`, pairs sorted by equation.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Block {
    pub eqs: Vec<EqId>,
    pub vars: Vec<VarId>,
}

impl Block {
    /// The number of equations (and variables).
    pub fn size(&self) -> usize {
        self.eqs.len()
    }

    /// The matched pairs.
    pub fn pairs(&self) -> impl Iterator<Item = (EqId, VarId)> + '_ {
        self.eqs.iter().copied().zip(self.vars.iter().copied())
    }
}

/// Orders the equations into blocks such that every block comes after each block that
/// computes a variable it uses. The unknowns are the variables with `is_unknown`; all
/// others (states, parameters) are known. `matching` must pair every equation with an
/// unknown and every unknown with an equation; otherwise the error gives the
/// Dulmage–Mendelsohn parts of the equations × unknowns graph.
pub fn blt(
    graph: &BipartiteGraph,
    matching: &Matching,
    is_unknown: impl Fn(VarId) -> bool,
) -> Result<Vec<Block>, StructError> {
    let unknown: Vec<bool> = graph.vars().map(&is_unknown).collect();
    let complete = graph
        .eqs()
        .all(|e| matching.var_of(e).is_some_and(|v| unknown[v.index()]))
        && graph
            .vars()
            .all(|v| !unknown[v.index()] || matching.eq_of(v).is_some());
    if !complete {
        let eq_ok = |_: EqId| true;
        let var_ok = |v: VarId| unknown[v.index()];
        let maximum = maximum_matching_where(graph, eq_ok, var_ok);
        let dm = dulmage_mendelsohn_where(graph, &maximum, eq_ok, var_ok);
        if dm.is_nonsingular() {
            return Err(StructError::invalid(
                "blt",
                "the matching does not pair every equation with an unknown, though a perfect matching exists",
            ));
        }
        return Err(dm.into_error());
    }
    let mut tarjan = Tarjan::new(graph.n_eqs());
    for root in graph.eqs() {
        if tarjan.index[root.index()] == UNVISITED {
            tarjan.run(graph, matching, &unknown, root);
        }
    }
    Ok(tarjan.blocks)
}

const UNVISITED: u32 = u32::MAX;

/// Iterative Tarjan on the implicit graph "e depends on the equation matched to each
/// unknown of e". Components come out dependencies first.
struct Tarjan {
    index: Vec<u32>,
    lowlink: Vec<u32>,
    on_stack: Vec<bool>,
    stack: Vec<EqId>,
    calls: Vec<(EqId, u32)>,
    counter: u32,
    blocks: Vec<Block>,
}

impl Tarjan {
    fn new(n_eqs: usize) -> Tarjan {
        Tarjan {
            index: vec![UNVISITED; n_eqs],
            lowlink: vec![0; n_eqs],
            on_stack: vec![false; n_eqs],
            stack: Vec::new(),
            calls: Vec::new(),
            counter: 0,
            blocks: Vec::new(),
        }
    }

    fn enter(&mut self, e: EqId) {
        self.index[e.index()] = self.counter;
        self.lowlink[e.index()] = self.counter;
        self.counter += 1;
        self.stack.push(e);
        self.on_stack[e.index()] = true;
        self.calls.push((e, 0));
    }

    fn run(&mut self, graph: &BipartiteGraph, matching: &Matching, unknown: &[bool], root: EqId) {
        self.enter(root);
        while let Some(&(e, position)) = self.calls.last() {
            let vars = graph.eq_vars(e);
            if (position as usize) < vars.len() {
                self.calls.last_mut().expect("nonempty").1 += 1;
                let v = vars[position as usize];
                if !unknown[v.index()] {
                    continue;
                }
                let w = matching.eq_of(v).expect("unknowns are matched");
                if w == e {
                    continue;
                }
                if self.index[w.index()] == UNVISITED {
                    self.enter(w);
                } else if self.on_stack[w.index()] {
                    self.lowlink[e.index()] = self.lowlink[e.index()].min(self.index[w.index()]);
                }
                continue;
            }
            self.calls.pop();
            if let Some(&(parent, _)) = self.calls.last() {
                self.lowlink[parent.index()] =
                    self.lowlink[parent.index()].min(self.lowlink[e.index()]);
            }
            if self.lowlink[e.index()] == self.index[e.index()] {
                self.emit(e, matching);
            }
        }
    }

    fn emit(&mut self, root: EqId, matching: &Matching) {
        let mut eqs = Vec::new();
        loop {
            let e = self.stack.pop().expect("root is on the stack");
            self.on_stack[e.index()] = false;
            eqs.push(e);
            if e == root {
                break;
            }
        }
        eqs.sort_unstable();
        let vars = eqs
            .iter()
            .map(|&e| matching.var_of(e).expect("matched"))
            .collect();
        self.blocks.push(Block { eqs, vars });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matching::maximum_matching;

    #[test]
    fn orders_a_loop_after_its_input() {
        // e0: v0 (input). e1: v0 v1 v2, e2: v1 v2 (loop on v1 v2).
        let g = BipartiteGraph::from_edges(3, 3, &[(0, 0), (1, 0), (1, 1), (1, 2), (2, 1), (2, 2)])
            .unwrap();
        let m = maximum_matching(&g);
        let blocks = blt(&g, &m, |_| true).unwrap();
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].eqs, vec![EqId(0)]);
        assert_eq!(blocks[1].eqs, vec![EqId(1), EqId(2)]);
    }

    #[test]
    fn a_partial_matching_of_a_nonsingular_graph_is_a_bug_not_a_model_error() {
        let g = BipartiteGraph::from_edges(2, 2, &[(0, 0), (1, 1)]).unwrap();
        let mut m = Matching::for_graph(&g);
        m.set(EqId(0), VarId(0));
        assert_eq!(blt(&g, &m, |_| true).unwrap_err().code(), "E3290");
    }

    #[test]
    fn long_dependency_chain_does_not_overflow() {
        // e_i: v_i v_{i+1}; the last equation only its own variable. Starting at e_0 the
        // search goes 300000 equations deep.
        let n = 300_000u32;
        let mut edges = Vec::new();
        for i in 0..n {
            edges.push((i, i));
            if i + 1 < n {
                edges.push((i, i + 1));
            }
        }
        let g = BipartiteGraph::from_edges(n as usize, n as usize, &edges).unwrap();
        let mut m = Matching::for_graph(&g);
        for i in 0..n {
            m.set(EqId(i), VarId(i));
        }
        let blocks = blt(&g, &m, |_| true).unwrap();
        assert_eq!(blocks.len(), n as usize);
        assert_eq!(blocks[0].eqs, vec![EqId(n - 1)]);
        assert_eq!(blocks[n as usize - 1].eqs, vec![EqId(0)]);
    }
}
