//! Text dumps of structural results for snapshots and debugging, with optional names.

use std::fmt::Write;

use crate::blt::Block;
use crate::chains::DerivativeChains;
use crate::dm::{DulmageMendelsohn, Part};
use crate::dummy::DummyDerivatives;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::Matching;
use crate::pantelides::PantelidesResult;
use crate::pipeline::StructuralAnalysis;
use crate::tearing::TornBlock;

/// How dumps name variables and equations; the defaults print ids (`v3`, `e3`).
pub trait Naming {
    fn var_name(&self, v: VarId) -> String {
        v.to_string()
    }
    fn eq_name(&self, e: EqId) -> String {
        e.to_string()
    }
}

/// Names by id.
#[derive(Clone, Copy, Debug, Default)]
pub struct IdNaming;

impl Naming for IdNaming {}

/// Names from two closures.
pub struct FnNaming<V, E>(pub V, pub E);

impl<V: Fn(VarId) -> String, E: Fn(EqId) -> String> Naming for FnNaming<V, E> {
    fn var_name(&self, v: VarId) -> String {
        (self.0)(v)
    }
    fn eq_name(&self, e: EqId) -> String {
        (self.1)(e)
    }
}

fn var_list(vars: impl IntoIterator<Item = VarId>, naming: &dyn Naming) -> String {
    vars.into_iter()
        .map(|v| naming.var_name(v))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A list that reads `(none)` when empty, for lines that would otherwise end in a space.
fn var_list_or_none(vars: &[VarId], naming: &dyn Naming) -> String {
    if vars.is_empty() {
        "(none)".to_string()
    } else {
        var_list(vars.iter().copied(), naming)
    }
}

fn eq_list(eqs: impl IntoIterator<Item = EqId>, naming: &dyn Naming) -> String {
    eqs.into_iter()
        .map(|e| naming.eq_name(e))
        .collect::<Vec<_>>()
        .join(" ")
}

/// One line per equation: `e0: x x'`.
pub fn dump_incidence(graph: &BipartiteGraph, naming: &dyn Naming) -> String {
    let mut out = format!(
        "incidence: {} equations, {} variables, {} edges\n",
        graph.n_eqs(),
        graph.n_vars(),
        graph.n_edges()
    );
    for e in graph.eqs() {
        let _ = writeln!(
            out,
            "{}: {}",
            naming.eq_name(e),
            var_list(graph.eq_vars(e).iter().copied(), naming)
        );
    }
    out
}

/// One line per matched pair (`e0 -> x'`), then the unmatched equations if any.
pub fn dump_matching(matching: &Matching, naming: &dyn Naming) -> String {
    let mut out = String::new();
    for (e, v) in matching.pairs() {
        let _ = writeln!(out, "{} -> {}", naming.eq_name(e), naming.var_name(v));
    }
    let unmatched = matching.unmatched_eqs();
    if !unmatched.is_empty() {
        let _ = writeln!(out, "unmatched equations: {}", eq_list(unmatched, naming));
    }
    out
}

/// One line per derivative relation by id, `v7 = der(v2)`, variables then equations;
/// when the naming knows a name for the derivative it follows as `  # der(x)`.
pub fn dump_chains(chains: &DerivativeChains, naming: &dyn Naming) -> String {
    let mut out = String::new();
    for (v, d) in chains.var_derivative.iter().enumerate() {
        if let Some(d) = d {
            let _ = write!(out, "{d} = der({})", VarId::new(v));
            append_name(&mut out, &d.to_string(), naming.var_name(*d));
        }
    }
    for (e, d) in chains.eq_derivative.iter().enumerate() {
        if let Some(d) = d {
            let _ = write!(out, "{d} = der({})", EqId::new(e));
            append_name(&mut out, &d.to_string(), naming.eq_name(*d));
        }
    }
    out
}

fn append_name(out: &mut String, id: &str, name: String) {
    if name != id {
        let _ = write!(out, "  # {name}");
    }
    out.push('\n');
}

/// Differentiation counts of the differentiated equations, derivative chains, and the
/// final matching of the highest equations.
pub fn dump_pantelides(result: &PantelidesResult, naming: &dyn Naming) -> String {
    let mut out = String::from("differentiated:\n");
    for (e, &count) in result.differentiation_count.iter().enumerate() {
        let e = EqId::new(e);
        if count > 0 && result.chains.eq_integral(e).is_none() {
            let _ = writeln!(out, "  {}: {count} time(s)", naming.eq_name(e));
        }
    }
    out.push_str("chains:\n");
    for line in dump_chains(&result.chains, naming).lines() {
        let _ = writeln!(out, "  {line}");
    }
    out.push_str("matching (highest equations):\n");
    for (e, v) in result.matching.pairs() {
        let _ = writeln!(out, "  {} -> {}", naming.eq_name(e), naming.var_name(v));
    }
    out
}

/// Dummy derivatives per level, then states and dummy states.
pub fn dump_dummies(dummies: &DummyDerivatives, naming: &dyn Naming) -> String {
    let mut out = format!(
        "dummy derivatives: {}\n",
        var_list_or_none(&dummies.dummies, naming)
    );
    for level in &dummies.levels {
        let pairs: Vec<String> = level
            .assignments
            .iter()
            .map(|&(e, v)| format!("{} -> {}", naming.eq_name(e), naming.var_name(v)))
            .collect();
        let _ = writeln!(out, "  level {}: {}", level.level, pairs.join(", "));
    }
    let _ = writeln!(out, "states: {}", var_list_or_none(&dummies.states, naming));
    let _ = writeln!(
        out,
        "dummy states: {}",
        var_list_or_none(&dummies.dummy_states, naming)
    );
    if !dummies.always_not_states.is_empty() {
        let _ = writeln!(
            out,
            "always but not state: {}",
            var_list_or_none(&dummies.always_not_states, naming)
        );
    }
    out
}

/// One line per block: `b0 v1 := e0` for a single pair, `b1 {e1 e2 | v1 v2}` otherwise.
pub fn dump_blocks(blocks: &[Block], naming: &dyn Naming) -> String {
    let mut out = String::new();
    for (i, block) in blocks.iter().enumerate() {
        if let ([e], [v]) = (block.eqs.as_slice(), block.vars.as_slice()) {
            let _ = writeln!(
                out,
                "b{i} {} := {}",
                naming.var_name(*v),
                naming.eq_name(*e)
            );
        } else {
            let eqs = eq_list(block.eqs.iter().copied(), naming);
            let vars = var_list(block.vars.iter().copied(), naming);
            let _ = writeln!(out, "b{i} {{{eqs} | {vars}}}");
        }
    }
    out
}

/// One line per torn block: `b0 v1 := e0` when explicit, otherwise
/// `b2 torn{iter v5; res e8; v3 := e6}`.
pub fn dump_torn_blocks(torn: &[TornBlock], naming: &dyn Naming) -> String {
    let mut out = String::new();
    for (i, block) in torn.iter().enumerate() {
        let assignments: Vec<String> = block
            .inner
            .iter()
            .map(|&(e, v)| format!("{} := {}", naming.var_name(v), naming.eq_name(e)))
            .collect();
        if block.is_explicit() {
            let _ = writeln!(out, "b{i} {}", assignments.join("; "));
        } else {
            let mut parts = vec![
                format!(
                    "iter {}",
                    var_list(block.iteration_vars.iter().copied(), naming)
                ),
                format!(
                    "res {}",
                    eq_list(block.residual_eqs.iter().copied(), naming)
                ),
            ];
            parts.extend(assignments);
            let _ = writeln!(out, "b{i} torn{{{}}}", parts.join("; "));
        }
    }
    out
}

fn dump_part(title: &str, part: &Part, naming: &dyn Naming) -> String {
    format!(
        "{title}: {{{} | {}}}\n",
        eq_list(part.eqs.iter().copied(), naming),
        var_list(part.vars.iter().copied(), naming)
    )
}

/// The three parts, `over: {e0 e1 | v0}`.
pub fn dump_dm(dm: &DulmageMendelsohn, naming: &dyn Naming) -> String {
    dump_part("over", &dm.over, naming)
        + &dump_part("under", &dm.under, naming)
        + &dump_part("well", &dm.well, naming)
}

/// Everything: incidence after index reduction, Pantelides, dummies, torn blocks.
pub fn dump_analysis(
    graph: &BipartiteGraph,
    analysis: &StructuralAnalysis,
    naming: &dyn Naming,
) -> String {
    let mut out = String::from("== incidence\n");
    out += &dump_incidence(graph, naming);
    out += "== pantelides\n";
    out += &dump_pantelides(&analysis.pantelides, naming);
    out += "== dummy derivatives\n";
    out += &dump_dummies(&analysis.dummies, naming);
    out += "== blocks\n";
    out += &dump_torn_blocks(&analysis.torn, naming);
    out
}
