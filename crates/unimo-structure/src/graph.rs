//! The equation × variable incidence graph, growable, with an on-demand transposed view.

use crate::error::StructError;
use crate::ids::{EqId, VarId};

/// Incidence of equations on variables: edge `(e, v)` when variable `v` occurs in
/// equation `e`. Each equation's variable list is kept sorted and free of duplicates.
/// Equations and variables can be added (index reduction grows the graph); nothing is
/// ever removed, so ids stay valid.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BipartiteGraph {
    eq_vars: Vec<Vec<VarId>>,
    n_vars: usize,
    n_edges: usize,
}

/// The transposed view: for each variable, the equations it occurs in (sorted), stored
/// compressed. A snapshot: it does not follow later additions to the graph.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VarIncidence {
    offsets: Vec<usize>,
    eqs: Vec<EqId>,
}

impl BipartiteGraph {
    /// A graph with `n_vars` variables and no equations.
    pub fn new(n_vars: usize) -> BipartiteGraph {
        BipartiteGraph {
            eq_vars: Vec::new(),
            n_vars,
            n_edges: 0,
        }
    }

    /// Builds a graph from `(equation, variable)` index pairs, for tests and fixtures.
    pub fn from_edges(
        n_eqs: usize,
        n_vars: usize,
        edges: &[(u32, u32)],
    ) -> Result<BipartiteGraph, StructError> {
        let mut adjacency = vec![Vec::new(); n_eqs];
        for &(e, v) in edges {
            let row = adjacency.get_mut(e as usize).ok_or_else(|| {
                StructError::invalid(
                    "edge list",
                    format!("edge ({e}, {v}) names a missing equation"),
                )
            })?;
            row.push(VarId(v));
        }
        BipartiteGraph::from_adjacency(n_vars, adjacency)
    }

    /// Builds a graph from one variable list per equation (any order, duplicates allowed).
    pub fn from_adjacency(
        n_vars: usize,
        adjacency: Vec<Vec<VarId>>,
    ) -> Result<BipartiteGraph, StructError> {
        let mut graph = BipartiteGraph::new(n_vars);
        graph.eq_vars.reserve(adjacency.len());
        for vars in adjacency {
            graph.add_eq(vars)?;
        }
        Ok(graph)
    }

    /// The number of equations.
    pub fn n_eqs(&self) -> usize {
        self.eq_vars.len()
    }

    /// The number of variables.
    pub fn n_vars(&self) -> usize {
        self.n_vars
    }

    /// The number of edges (occurrences of a variable in an equation).
    pub fn n_edges(&self) -> usize {
        self.n_edges
    }

    /// Adds a variable that occurs in no equation yet.
    pub fn add_var(&mut self) -> VarId {
        self.n_vars += 1;
        VarId::new(self.n_vars - 1)
    }

    /// Adds an equation over the given variables (any order, duplicates allowed).
    pub fn add_eq(&mut self, vars: impl IntoIterator<Item = VarId>) -> Result<EqId, StructError> {
        let eq = EqId::new(self.eq_vars.len());
        let mut row: Vec<VarId> = vars.into_iter().collect();
        if let Some(&var) = row.iter().find(|v| v.index() >= self.n_vars) {
            return Err(StructError::EdgeOutOfRange {
                eq,
                var,
                n_vars: self.n_vars,
            });
        }
        row.sort_unstable();
        row.dedup();
        self.n_edges += row.len();
        self.eq_vars.push(row);
        Ok(eq)
    }

    /// Adds the edge `(eq, var)`; returns false when it was already there.
    pub fn add_edge(&mut self, eq: EqId, var: VarId) -> Result<bool, StructError> {
        if var.index() >= self.n_vars {
            return Err(StructError::EdgeOutOfRange {
                eq,
                var,
                n_vars: self.n_vars,
            });
        }
        let n_eqs = self.n_eqs();
        let row = self.eq_vars.get_mut(eq.index()).ok_or_else(|| {
            StructError::invalid("add_edge", format!("{eq} is not one of {n_eqs} equations"))
        })?;
        match row.binary_search(&var) {
            Ok(_) => Ok(false),
            Err(at) => {
                row.insert(at, var);
                self.n_edges += 1;
                Ok(true)
            }
        }
    }

    /// The variables of an equation, sorted.
    pub fn eq_vars(&self, eq: EqId) -> &[VarId] {
        &self.eq_vars[eq.index()]
    }

    /// Whether variable `var` occurs in equation `eq`.
    pub fn contains_edge(&self, eq: EqId, var: VarId) -> bool {
        self.eq_vars
            .get(eq.index())
            .is_some_and(|row| row.binary_search(&var).is_ok())
    }

    /// All equation ids in order.
    pub fn eqs(&self) -> impl ExactSizeIterator<Item = EqId> {
        (0..self.n_eqs()).map(EqId::new)
    }

    /// All variable ids in order.
    pub fn vars(&self) -> impl ExactSizeIterator<Item = VarId> {
        (0..self.n_vars).map(VarId::new)
    }

    /// For each variable, the number of equations it occurs in.
    pub fn var_degrees(&self) -> Vec<u32> {
        let mut degrees = vec![0u32; self.n_vars];
        for row in &self.eq_vars {
            for v in row {
                degrees[v.index()] += 1;
            }
        }
        degrees
    }

    /// Builds the variable → equations view (counting sort, linear time).
    pub fn transpose(&self) -> VarIncidence {
        let mut offsets = vec![0usize; self.n_vars + 1];
        for row in &self.eq_vars {
            for v in row {
                offsets[v.index() + 1] += 1;
            }
        }
        for i in 0..self.n_vars {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut eqs = vec![EqId(0); self.n_edges];
        for (e, row) in self.eq_vars.iter().enumerate() {
            for v in row {
                eqs[fill[v.index()]] = EqId::new(e);
                fill[v.index()] += 1;
            }
        }
        VarIncidence { offsets, eqs }
    }
}

impl VarIncidence {
    /// The equations a variable occurs in, sorted.
    pub fn var_eqs(&self, var: VarId) -> &[EqId] {
        &self.eqs[self.offsets[var.index()]..self.offsets[var.index() + 1]]
    }

    /// The number of variables the view covers.
    pub fn n_vars(&self) -> usize {
        self.offsets.len() - 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_sorted_deduplicated_rows_and_transpose() {
        let g =
            BipartiteGraph::from_edges(2, 3, &[(0, 2), (0, 0), (0, 2), (1, 1), (1, 0)]).unwrap();
        assert_eq!(g.eq_vars(EqId(0)), &[VarId(0), VarId(2)]);
        assert_eq!(g.n_edges(), 4);
        let t = g.transpose();
        assert_eq!(t.var_eqs(VarId(0)), &[EqId(0), EqId(1)]);
        assert_eq!(t.var_eqs(VarId(2)), &[EqId(0)]);
        assert!(g.contains_edge(EqId(1), VarId(1)));
        assert!(!g.contains_edge(EqId(1), VarId(2)));
    }

    #[test]
    fn grows_and_rejects_unknown_variables() {
        let mut g = BipartiteGraph::new(1);
        let v = g.add_var();
        let e = g.add_eq([v]).unwrap();
        assert!(g.add_edge(e, VarId(0)).unwrap());
        assert!(!g.add_edge(e, VarId(0)).unwrap());
        let err = g.add_eq([VarId(7)]).unwrap_err();
        assert_eq!(err.code(), "E3205");
        assert_eq!(g.var_degrees(), vec![1, 1]);
    }
}
