//! The whole structural pipeline: Pantelides, dummy derivatives, index-1 matching, BLT,
//! tearing.

use crate::blt::{blt, Block};
use crate::dummy::{select_dummy_derivatives, DummyDerivatives, StateSelectPriority};
use crate::error::StructError;
use crate::ids::{EqId, VarId};
use crate::matching::Matching;
use crate::pantelides::{pantelides, IndexReductionSystem, PantelidesResult};
use crate::tearing::{tear_blocks, TornBlock};

/// Everything structural analysis hands on. `matching` pairs every equation of the
/// reduced system with an unknown (`dummies.is_unknown`); `blocks` are in evaluation
/// order; `torn[i]` is `blocks[i]` torn.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StructuralAnalysis {
    pub pantelides: PantelidesResult,
    pub dummies: DummyDerivatives,
    pub matching: Matching,
    pub blocks: Vec<Block>,
    pub torn: Vec<TornBlock>,
}

/// Runs index reduction on `system`, selects dummy derivatives with `priority`, orders
/// the index-1 system into blocks and tears them with `solvable`.
pub fn analyze<S: IndexReductionSystem + ?Sized>(
    system: &mut S,
    priority: impl Fn(VarId) -> StateSelectPriority,
    solvable: impl Fn(EqId, VarId) -> bool,
) -> Result<StructuralAnalysis, StructError> {
    let pantelides = pantelides(system)?;
    let graph = system.graph();
    let dummies = select_dummy_derivatives(graph, &pantelides, priority)?;
    let matching = dummies.index_one_matching(graph)?;
    let blocks = blt(graph, &matching, |v| dummies.is_unknown[v.index()])?;
    let torn = tear_blocks(graph, &blocks, solvable)?;
    Ok(StructuralAnalysis {
        pantelides,
        dummies,
        matching,
        blocks,
        torn,
    })
}
