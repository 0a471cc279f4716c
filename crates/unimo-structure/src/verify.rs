//! Independent checks of structural results: each returns `StructError::Invalid` naming
//! the broken invariant. Used by the tests; cheap enough to run on real models.

use std::collections::HashSet;

use crate::blt::Block;
use crate::dummy::DummyDerivatives;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};
use crate::matching::Matching;
use crate::pantelides::PantelidesResult;
use crate::pipeline::StructuralAnalysis;
use crate::tearing::TornBlock;

fn fail(check: &'static str, detail: String) -> Result<(), StructError> {
    Err(StructError::invalid(check, detail))
}

/// The matching is sized for the graph, consistent in both directions, and uses only
/// edges of the graph.
pub fn verify_matching(graph: &BipartiteGraph, matching: &Matching) -> Result<(), StructError> {
    if matching.eq_to_var.len() != graph.n_eqs() || matching.var_to_eq.len() != graph.n_vars() {
        return fail("matching", "sizes differ from the graph".into());
    }
    for (e, v) in matching.pairs() {
        if matching.eq_of(v) != Some(e) {
            return fail(
                "matching",
                format!("{e} -> {v}, but {v} -> {:?}", matching.eq_of(v)),
            );
        }
        if !graph.contains_edge(e, v) {
            return fail("matching", format!("{v} does not occur in {e}"));
        }
    }
    for (v, e) in matching.var_to_eq.iter().enumerate() {
        if let Some(e) = e {
            if matching.var_of(*e) != Some(VarId::new(v)) {
                return fail("matching", format!("v{v} -> {e}, but not back"));
            }
        }
    }
    Ok(())
}

/// The matching pairs exactly the top equations, each with a highest variable; each
/// derivative chain has exactly one highest variable.
pub fn verify_pantelides(
    graph: &BipartiteGraph,
    result: &PantelidesResult,
) -> Result<(), StructError> {
    verify_matching(graph, &result.matching)?;
    for e in graph.eqs() {
        let top = result.chains.eq_derivative(e).is_none();
        match result.matching.var_of(e) {
            None if top => return fail("pantelides", format!("top equation {e} is unmatched")),
            Some(v) if !top => {
                return fail(
                    "pantelides",
                    format!("differentiated {e} is matched to {v}"),
                )
            }
            Some(v) if !result.highest_vars[v.index()] => {
                return fail(
                    "pantelides",
                    format!("{e} is matched to {v}, not a highest derivative"),
                )
            }
            _ => {}
        }
    }
    for root in graph
        .vars()
        .filter(|&v| result.chains.var_integral(v).is_none())
    {
        let (mut v, mut count) = (root, u32::from(result.highest_vars[root.index()]));
        while let Some(above) = result.chains.var_derivative(v) {
            v = above;
            count += u32::from(result.highest_vars[v.index()]);
        }
        if count != 1 {
            return fail(
                "pantelides",
                format!("chain of {root} has {count} highest variables"),
            );
        }
    }
    Ok(())
}

/// As many dummies as differentiated equations (plus each state set's extra candidates),
/// all derivatives; states and dummy states disjoint; without state sets, the reduced
/// system has a perfect matching (index 1). With state sets it is index 1 only once the
/// caller has added the sets' equations, which this crate does not see.
pub fn verify_dummy_derivatives(
    graph: &BipartiteGraph,
    pantelides: &PantelidesResult,
    dummies: &DummyDerivatives,
) -> Result<(), StructError> {
    let differentiated = pantelides.differentiated_eqs().len()
        + dummies
            .state_sets
            .iter()
            .map(|s| s.candidates.len() - s.eqs.len())
            .sum::<usize>();
    if dummies.dummies.len() != differentiated {
        return fail(
            "dummy derivatives",
            format!(
                "{} dummies for {differentiated} differentiated equations",
                dummies.dummies.len()
            ),
        );
    }
    if let Some(d) = dummies
        .dummies
        .iter()
        .find(|d| pantelides.chains.var_integral(**d).is_none())
    {
        return fail(
            "dummy derivatives",
            format!("dummy {d} is not a derivative"),
        );
    }
    if let Some(v) = dummies
        .states
        .iter()
        .find(|v| dummies.dummy_states.binary_search(v).is_ok())
    {
        return fail(
            "dummy derivatives",
            format!("{v} is both a state and a dummy state"),
        );
    }
    if !dummies.state_sets.is_empty() {
        return Ok(());
    }
    let unknowns = dummies.is_unknown.iter().filter(|&&u| u).count();
    if unknowns != graph.n_eqs() {
        return fail(
            "dummy derivatives",
            format!("{unknowns} unknowns for {} equations", graph.n_eqs()),
        );
    }
    let matching = dummies
        .index_one_matching(graph)
        .map_err(|err| StructError::invalid("dummy derivatives", format!("not index 1: {err}")))?;
    verify_matching(graph, &matching)
}

/// Every equation and every unknown is in exactly one block, pairs are edges, and each
/// block uses only unknowns computed in itself or in an earlier block.
pub fn verify_blt(
    graph: &BipartiteGraph,
    blocks: &[Block],
    is_unknown: impl Fn(VarId) -> bool,
) -> Result<(), StructError> {
    let mut eq_block = vec![usize::MAX; graph.n_eqs()];
    let mut var_block = vec![usize::MAX; graph.n_vars()];
    for (b, block) in blocks.iter().enumerate() {
        if block.eqs.len() != block.vars.len() {
            return fail("blt", format!("block b{b} is not square"));
        }
        for (e, v) in block.pairs() {
            if eq_block[e.index()] != usize::MAX || var_block[v.index()] != usize::MAX {
                return fail("blt", format!("{e} or {v} is in two blocks"));
            }
            if !is_unknown(v) || !graph.contains_edge(e, v) {
                return fail(
                    "blt",
                    format!("pair {e} -> {v} is not an edge to an unknown"),
                );
            }
            eq_block[e.index()] = b;
            var_block[v.index()] = b;
        }
    }
    if let Some(e) = graph.eqs().find(|e| eq_block[e.index()] == usize::MAX) {
        return fail("blt", format!("{e} is in no block"));
    }
    if let Some(v) = graph
        .vars()
        .find(|&v| is_unknown(v) && var_block[v.index()] == usize::MAX)
    {
        return fail("blt", format!("unknown {v} is in no block"));
    }
    for e in graph.eqs() {
        for &v in graph.eq_vars(e) {
            if is_unknown(v) && var_block[v.index()] > eq_block[e.index()] {
                return fail("blt", format!("{e} uses {v}, computed in a later block"));
            }
        }
    }
    Ok(())
}

/// The torn block covers the block exactly, `|iteration| == |residual|`, and each inner
/// assignment is solvable and uses only block variables known before it.
pub fn verify_torn_block(
    graph: &BipartiteGraph,
    block: &Block,
    torn: &TornBlock,
    solvable: impl Fn(EqId, VarId) -> bool,
) -> Result<(), StructError> {
    if torn.iteration_vars.len() != torn.residual_eqs.len() {
        return fail(
            "tearing",
            "iteration variables and residuals differ in number".into(),
        );
    }
    let mut eqs: Vec<EqId> = torn
        .residual_eqs
        .iter()
        .copied()
        .chain(torn.inner.iter().map(|p| p.0))
        .collect();
    let mut vars: Vec<VarId> = torn
        .iteration_vars
        .iter()
        .copied()
        .chain(torn.inner.iter().map(|p| p.1))
        .collect();
    let (mut block_eqs, mut block_vars) = (block.eqs.clone(), block.vars.clone());
    for list in [&mut eqs, &mut block_eqs] {
        list.sort_unstable();
    }
    for list in [&mut vars, &mut block_vars] {
        list.sort_unstable();
    }
    if eqs != block_eqs || vars != block_vars {
        return fail(
            "tearing",
            "torn block does not cover the block exactly once".into(),
        );
    }
    let mut known: HashSet<VarId> = torn.iteration_vars.iter().copied().collect();
    for &(e, v) in &torn.inner {
        if !graph.contains_edge(e, v) || !solvable(e, v) {
            return fail("tearing", format!("{e} cannot be solved for {v}"));
        }
        let unknown_use = graph
            .eq_vars(e)
            .iter()
            .find(|&&u| u != v && block_vars.binary_search(&u).is_ok() && !known.contains(&u));
        if let Some(u) = unknown_use {
            return fail(
                "tearing",
                format!("{v} := {e} uses {u} before it is computed"),
            );
        }
        known.insert(v);
    }
    Ok(())
}

/// All of the above on a pipeline result of the graph it was computed on.
pub fn verify_analysis(
    graph: &BipartiteGraph,
    analysis: &StructuralAnalysis,
    solvable: impl Fn(EqId, VarId) -> bool,
) -> Result<(), StructError> {
    verify_pantelides(graph, &analysis.pantelides)?;
    verify_dummy_derivatives(graph, &analysis.pantelides, &analysis.dummies)?;
    verify_matching(graph, &analysis.matching)?;
    verify_blt(graph, &analysis.blocks, |v| {
        analysis.dummies.is_unknown[v.index()]
    })?;
    if analysis.blocks.len() != analysis.torn.len() {
        return fail("tearing", "one torn block per block expected".into());
    }
    for (block, torn) in analysis.blocks.iter().zip(&analysis.torn) {
        verify_torn_block(graph, block, torn, &solvable)?;
    }
    Ok(())
}
