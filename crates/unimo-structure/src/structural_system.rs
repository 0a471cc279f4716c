//! A system known only by its incidence, differentiated by the structural rule: the
//! derivative of an equation contains every variable `v` of it and `der(v)`.

use crate::dump::Naming;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::IndexReductionSystem;

/// An [`IndexReductionSystem`] for tests, benchmarks and callers that have only the
/// incidence. Derivative variables are created on demand; names are optional, and a
/// derivative's name is its integral's name with a prime (`x'`, `x''`), an equation
/// derivative's likewise (`e3'`).
#[derive(Clone, Debug, Default)]
pub struct StructuralSystem {
    graph: BipartiteGraph,
    var_derivative: Vec<Option<VarId>>,
    var_integral: Vec<Option<VarId>>,
    eq_derivative: Vec<Option<EqId>>,
    eq_integral: Vec<Option<EqId>>,
    var_names: Vec<Option<String>>,
    eq_names: Vec<Option<String>>,
    not_differentiable: Vec<Option<String>>,
}

impl StructuralSystem {
    /// An empty system.
    pub fn new() -> StructuralSystem {
        StructuralSystem::default()
    }

    /// A system with an existing graph and no derivative relations.
    pub fn from_graph(graph: BipartiteGraph) -> StructuralSystem {
        let (n_eqs, n_vars) = (graph.n_eqs(), graph.n_vars());
        StructuralSystem {
            graph,
            var_derivative: vec![None; n_vars],
            var_integral: vec![None; n_vars],
            eq_derivative: vec![None; n_eqs],
            eq_integral: vec![None; n_eqs],
            var_names: vec![None; n_vars],
            eq_names: vec![None; n_eqs],
            not_differentiable: vec![None; n_eqs],
        }
    }

    /// Adds a variable; an empty name means "unnamed" (printed by id).
    pub fn add_var(&mut self, name: &str) -> VarId {
        let v = self.graph.add_var();
        self.var_derivative.push(None);
        self.var_integral.push(None);
        self.var_names
            .push((!name.is_empty()).then(|| name.to_string()));
        v
    }

    /// The derivative of `v`, created when missing.
    pub fn derivative(&mut self, v: VarId) -> VarId {
        if let Some(dv) = self.var_derivative[v.index()] {
            return dv;
        }
        let dv = self.add_var("");
        self.var_derivative[v.index()] = Some(dv);
        self.var_integral[dv.index()] = Some(v);
        dv
    }

    /// Adds an equation over the given variables; an empty name means "unnamed".
    pub fn add_eq(&mut self, name: &str, vars: &[VarId]) -> Result<EqId, StructError> {
        let e = self.graph.add_eq(vars.iter().copied())?;
        self.eq_derivative.push(None);
        self.eq_integral.push(None);
        self.eq_names
            .push((!name.is_empty()).then(|| name.to_string()));
        self.not_differentiable.push(None);
        Ok(e)
    }

    /// Makes `differentiate_eq(e)` fail with `reason`.
    pub fn set_not_differentiable(&mut self, e: EqId, reason: &str) {
        self.not_differentiable[e.index()] = Some(reason.to_string());
    }

    /// The variable this one is the derivative of.
    pub fn var_integral(&self, v: VarId) -> Option<VarId> {
        self.var_integral[v.index()]
    }
}

impl IndexReductionSystem for StructuralSystem {
    fn graph(&self) -> &BipartiteGraph {
        &self.graph
    }

    fn var_derivative(&self, v: VarId) -> Option<VarId> {
        self.var_derivative.get(v.index()).copied().flatten()
    }

    fn add_var_derivative(&mut self, v: VarId) -> VarId {
        self.derivative(v)
    }

    fn eq_derivative(&self, e: EqId) -> Option<EqId> {
        self.eq_derivative.get(e.index()).copied().flatten()
    }

    fn differentiate_eq(&mut self, e: EqId) -> Result<EqId, String> {
        if let Some(de) = self.eq_derivative[e.index()] {
            return Ok(de);
        }
        if let Some(reason) = &self.not_differentiable[e.index()] {
            return Err(reason.clone());
        }
        let vars = self.graph.eq_vars(e).to_vec();
        let mut row = Vec::with_capacity(2 * vars.len());
        for v in vars {
            row.push(v);
            row.push(self.derivative(v));
        }
        let de = self.add_eq("", &row).map_err(|err| err.to_string())?;
        self.eq_derivative[e.index()] = Some(de);
        self.eq_integral[de.index()] = Some(e);
        Ok(de)
    }
}

impl Naming for StructuralSystem {
    fn var_name(&self, v: VarId) -> String {
        let (mut root, mut primes) = (v, 0);
        while let Some(below) = self.var_integral.get(root.index()).copied().flatten() {
            root = below;
            primes += 1;
        }
        let base = self.var_names.get(root.index()).cloned().flatten();
        format!(
            "{}{}",
            base.unwrap_or_else(|| root.to_string()),
            "'".repeat(primes)
        )
    }

    fn eq_name(&self, e: EqId) -> String {
        let (mut root, mut primes) = (e, 0);
        while let Some(below) = self.eq_integral.get(root.index()).copied().flatten() {
            root = below;
            primes += 1;
        }
        let base = self.eq_names.get(root.index()).cloned().flatten();
        format!(
            "{}{}",
            base.unwrap_or_else(|| root.to_string()),
            "'".repeat(primes)
        )
    }
}
