//! Test fixtures: a small mock `IndexReductionSystem` that differentiates by the
//! structural rule (der(e) uses v and der(v) for each v of e), and a deterministic LCG.
#![allow(dead_code)]

use unimo_structure::{BipartiteGraph, EqId, IndexReductionSystem, Naming, VarId};

/// A system known by incidence only, with names for dumps. Derivative variables are
/// named `der(x)`; differentiated equations get a prime (`e4'`).
#[derive(Default)]
pub struct MockSystem {
    pub graph: BipartiteGraph,
    var_derivative: Vec<Option<VarId>>,
    var_names: Vec<String>,
    eq_derivative: Vec<Option<EqId>>,
    eq_names: Vec<String>,
    not_differentiable: Vec<EqId>,
}

impl MockSystem {
    pub fn new() -> MockSystem {
        MockSystem::default()
    }

    pub fn var(&mut self, name: &str) -> VarId {
        self.var_derivative.push(None);
        self.var_names.push(name.to_string());
        self.graph.add_var()
    }

    /// der(v), created on demand.
    pub fn der(&mut self, v: VarId) -> VarId {
        if let Some(d) = self.var_derivative[v.index()] {
            return d;
        }
        let name = format!("der({})", self.var_names[v.index()]);
        let d = self.var(&name);
        self.var_derivative[v.index()] = Some(d);
        d
    }

    pub fn eq(&mut self, name: &str, vars: &[VarId]) -> EqId {
        self.eq_derivative.push(None);
        self.eq_names.push(name.to_string());
        self.graph.add_eq(vars.iter().copied()).unwrap()
    }

    pub fn forbid_differentiation(&mut self, e: EqId) {
        self.not_differentiable.push(e);
    }

    pub fn find_var(&self, name: &str) -> VarId {
        let at = self
            .var_names
            .iter()
            .position(|n| n == name)
            .unwrap_or_else(|| panic!("no variable {name}"));
        VarId::new(at)
    }

    pub fn names(&self, vars: &[VarId]) -> Vec<String> {
        vars.iter().map(|&v| self.var_name(v)).collect()
    }
}

impl IndexReductionSystem for MockSystem {
    fn graph(&self) -> &BipartiteGraph {
        &self.graph
    }

    fn var_derivative(&self, v: VarId) -> Option<VarId> {
        self.var_derivative[v.index()]
    }

    fn add_var_derivative(&mut self, v: VarId) -> VarId {
        self.der(v)
    }

    fn eq_derivative(&self, e: EqId) -> Option<EqId> {
        self.eq_derivative[e.index()]
    }

    fn differentiate_eq(&mut self, e: EqId) -> Result<EqId, String> {
        if self.not_differentiable.contains(&e) {
            return Err("contains a non-differentiable function".to_string());
        }
        let mut vars = Vec::new();
        for &v in self.graph.eq_vars(e).to_vec().iter() {
            vars.push(v);
            vars.push(self.der(v));
        }
        let name = format!("{}'", self.eq_names[e.index()]);
        let de = self.eq(&name, &vars);
        self.eq_derivative[e.index()] = Some(de);
        Ok(de)
    }
}

impl Naming for MockSystem {
    fn var_name(&self, v: VarId) -> String {
        self.var_names[v.index()].clone()
    }
    fn eq_name(&self, e: EqId) -> String {
        self.eq_names[e.index()].clone()
    }
}

/// Cartesian pendulum, index 3:
/// e0: der(x) = vx; e1: der(y) = vy; e2: m der(vx) = -F x; e3: m der(vy) = -F y - m g;
/// e4: x^2 + y^2 = L^2.
pub fn pendulum() -> MockSystem {
    let mut s = MockSystem::new();
    let x = s.var("x"); // horizontal position
    let y = s.var("y"); // vertical position
    let vx = s.var("vx"); // horizontal velocity
    let vy = s.var("vy"); // vertical velocity
    let f = s.var("F"); // rod force per length (Lagrange multiplier)
    let (dx, dy, dvx, dvy) = (s.der(x), s.der(y), s.der(vx), s.der(vy));
    s.eq("e0", &[dx, vx]);
    s.eq("e1", &[dy, vy]);
    s.eq("e2", &[dvx, f, x]);
    s.eq("e3", &[dvy, f, y]);
    s.eq("e4", &[x, y]);
    s
}

/// The pendulum's solvability ("linear with a constant or parameter coefficient"): the
/// constraint and its derivatives have coefficients 2x, 2y — never; the force equations
/// only for the acceleration (m der(vx)); the kinematic equations for both variables.
pub fn pendulum_solvable(s: &MockSystem) -> impl Fn(EqId, VarId) -> bool + '_ {
    move |e, v| {
        let eq = s.eq_name(e);
        match eq.trim_end_matches('\'') {
            "e4" => false,
            "e2" | "e3" => s.var_name(v).starts_with("der(v"),
            _ => true,
        }
    }
}

/// A deterministic linear congruential generator for reproducible random tests.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        self.0 >> 33
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }
}
