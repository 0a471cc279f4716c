//! Tearing of an algebraic block (Cellier's heuristic): choose few iteration variables
//! so that the other variables follow by explicit assignments in order.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use crate::blt::Block;
use crate::error::StructError;
use crate::graph::BipartiteGraph;
use crate::ids::{EqId, VarId};

/// A torn block. Given values of `iteration_vars`, the `inner` assignments compute their
/// variables explicitly, in order, each from its equation (solvable for it, using only
/// iteration variables, earlier inner variables and variables outside the block); the
/// `residual_eqs` then close the loop. `|iteration_vars| == |residual_eqs|`; a block
/// that needs no iteration has neither.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TornBlock {
    pub iteration_vars: Vec<VarId>,
    pub residual_eqs: Vec<EqId>,
    pub inner: Vec<(EqId, VarId)>,
}

impl TornBlock {
    /// Whether the block is solved by assignments alone.
    pub fn is_explicit(&self) -> bool {
        self.iteration_vars.is_empty()
    }
}

/// Tears one block. `solvable(e, v)`: e can be solved explicitly for v.
pub fn tear_block(
    graph: &BipartiteGraph,
    block: &Block,
    solvable: impl Fn(EqId, VarId) -> bool,
) -> Result<TornBlock, StructError> {
    Tearing::new().tear(graph, block, &solvable)
}

/// Tears every block, sharing one workspace.
pub fn tear_blocks(
    graph: &BipartiteGraph,
    blocks: &[Block],
    solvable: impl Fn(EqId, VarId) -> bool,
) -> Result<Vec<TornBlock>, StructError> {
    let mut tearing = Tearing::new();
    blocks
        .iter()
        .map(|block| tearing.tear(graph, block, &solvable))
        .collect()
}

/// A reusable tearing workspace: a map from graph variables to block positions and the
/// buffers of the heuristic, kept between blocks so that many small blocks cost no
/// allocations.
#[derive(Clone, Debug, Default)]
pub struct Tearing {
    local_of: Vec<u32>,
    block: LocalBlock,
    state: TearState,
}

const NOT_LOCAL: u32 = u32::MAX;

impl Tearing {
    /// An empty workspace.
    pub fn new() -> Tearing {
        Tearing::default()
    }

    /// Tears one block.
    pub fn tear(
        &mut self,
        graph: &BipartiteGraph,
        block: &Block,
        solvable: &dyn Fn(EqId, VarId) -> bool,
    ) -> Result<TornBlock, StructError> {
        if block.eqs.len() != block.vars.len() {
            return Err(StructError::BlockNotSquare {
                eqs: block.eqs.len(),
                vars: block.vars.len(),
            });
        }
        if let ([e], [v]) = (block.eqs.as_slice(), block.vars.as_slice()) {
            return Ok(tear_single(graph, *e, *v, solvable));
        }
        self.localize(graph, block, solvable);
        self.state.run(&self.block);
        Ok(self.state.torn_block(block))
    }

    fn localize(
        &mut self,
        graph: &BipartiteGraph,
        block: &Block,
        solvable: &dyn Fn(EqId, VarId) -> bool,
    ) {
        if self.local_of.len() < graph.n_vars() {
            self.local_of.resize(graph.n_vars(), NOT_LOCAL);
        }
        for (i, v) in block.vars.iter().enumerate() {
            self.local_of[v.index()] = i as u32;
        }
        let local = &mut self.block;
        local.row_start.clear();
        local.row_entries.clear();
        local.row_start.push(0);
        for &e in &block.eqs {
            let start = local.row_entries.len();
            for &v in graph.eq_vars(e) {
                let at = self.local_of[v.index()];
                if at != NOT_LOCAL {
                    local.row_entries.push((at, solvable(e, v)));
                }
            }
            local.row_entries[start..].sort_unstable();
            local.row_start.push(local.row_entries.len() as u32);
        }
        for v in &block.vars {
            self.local_of[v.index()] = NOT_LOCAL;
        }
        local.build_columns(block.vars.len());
    }
}

fn tear_single(
    graph: &BipartiteGraph,
    e: EqId,
    v: VarId,
    solvable: &dyn Fn(EqId, VarId) -> bool,
) -> TornBlock {
    if graph.contains_edge(e, v) && solvable(e, v) {
        TornBlock {
            inner: vec![(e, v)],
            ..TornBlock::default()
        }
    } else {
        TornBlock {
            iteration_vars: vec![v],
            residual_eqs: vec![e],
            inner: Vec::new(),
        }
    }
}

/// A block in local numbering, compressed: per equation its block variables (sorted)
/// with solvability, per variable its equations.
#[derive(Clone, Debug, Default)]
struct LocalBlock {
    row_start: Vec<u32>,
    row_entries: Vec<(u32, bool)>,
    col_start: Vec<u32>,
    col_entries: Vec<u32>,
    col_fill: Vec<u32>,
}

impl LocalBlock {
    fn build_columns(&mut self, n_vars: usize) {
        self.col_start.clear();
        self.col_start.resize(n_vars + 1, 0);
        for &(v, _) in &self.row_entries {
            self.col_start[v as usize + 1] += 1;
        }
        for i in 0..n_vars {
            self.col_start[i + 1] += self.col_start[i];
        }
        self.col_entries.clear();
        self.col_entries.resize(self.row_entries.len(), 0);
        self.col_fill.clear();
        self.col_fill.extend_from_slice(&self.col_start[..n_vars]);
        for e in 0..self.row_start.len() - 1 {
            for k in self.row_start[e] as usize..self.row_start[e + 1] as usize {
                let v = self.row_entries[k].0 as usize;
                self.col_entries[self.col_fill[v] as usize] = e as u32;
                self.col_fill[v] += 1;
            }
        }
    }

    fn n_eqs(&self) -> usize {
        self.row_start.len() - 1
    }

    fn row(&self, e: u32) -> &[(u32, bool)] {
        &self.row_entries
            [self.row_start[e as usize] as usize..self.row_start[e as usize + 1] as usize]
    }

    fn column(&self, v: u32) -> &[u32] {
        &self.col_entries
            [self.col_start[v as usize] as usize..self.col_start[v as usize + 1] as usize]
    }

    fn solvable(&self, e: u32, v: u32) -> bool {
        let row = self.row(e);
        row.binary_search_by_key(&v, |&(u, _)| u)
            .is_ok_and(|at| row[at].1)
    }
}

/// Score of a tearing candidate: (remaining equations it occurs in, equations that
/// become explicitly solvable when it is torn).
type Score = (u32, u32);

/// The state of Cellier's heuristic on one block. Forward: an equation with one unknown
/// left, solvable for it, computes it. Backward: a variable left in only one equation,
/// solvable there, is computed by it, after everything else (its assignment goes to the
/// end, latest first). Otherwise tear the variable with the best [`Score`].
#[derive(Clone, Debug, Default)]
struct TearState {
    unknown_count: Vec<u32>,
    unknown_sum: Vec<u64>,
    remaining_count: Vec<u32>,
    eq_done: Vec<bool>,
    var_known: Vec<bool>,
    forward_queue: VecDeque<u32>,
    backward_queue: Vec<u32>,
    score: Vec<Score>,
    heap: BinaryHeap<(Score, Reverse<u32>)>,
    forward: Vec<(u32, u32)>,
    backward: Vec<(u32, u32)>,
    tears: Vec<u32>,
    residuals: Vec<u32>,
}

impl TearState {
    fn reset(&mut self, block: &LocalBlock) {
        let n = block.n_eqs();
        self.unknown_count.clear();
        self.unknown_count
            .extend((0..n as u32).map(|e| block.row(e).len() as u32));
        self.unknown_sum.clear();
        self.unknown_sum.extend(
            (0..n as u32).map(|e| block.row(e).iter().map(|&(v, _)| u64::from(v)).sum::<u64>()),
        );
        self.remaining_count.clear();
        self.remaining_count
            .extend((0..n as u32).map(|v| block.column(v).len() as u32));
        for flags in [&mut self.eq_done, &mut self.var_known] {
            flags.clear();
            flags.resize(n, false);
        }
        self.score.clear();
        self.score.resize(n, (0, 0));
        self.forward_queue.clear();
        self.backward_queue.clear();
        self.heap.clear();
        self.forward.clear();
        self.backward.clear();
        self.tears.clear();
        self.residuals.clear();
    }

    fn run(&mut self, block: &LocalBlock) {
        self.reset(block);
        let n = block.n_eqs() as u32;
        self.forward_queue
            .extend((0..n).filter(|&e| self.unknown_count[e as usize] <= 1));
        self.backward_queue
            .extend((0..n).filter(|&v| self.remaining_count[v as usize] == 1));
        for v in 0..n {
            self.rescore_with(block, v, true);
        }
        loop {
            if let Some(e) = self.forward_queue.pop_front() {
                self.try_forward(block, e);
            } else if let Some(v) = self.backward_queue.pop() {
                self.try_backward(block, v);
            } else if let Some(v) = self.pick_tear() {
                self.tears.push(v);
                self.make_known(block, v);
            } else {
                break;
            }
        }
        for e in 0..n {
            if !self.eq_done[e as usize] {
                self.eq_done[e as usize] = true;
                self.residuals.push(e);
            }
        }
    }

    fn try_forward(&mut self, block: &LocalBlock, e: u32) {
        if self.eq_done[e as usize] {
            return;
        }
        match self.unknown_count[e as usize] {
            0 => {
                self.eq_done[e as usize] = true;
                self.residuals.push(e);
            }
            1 => {
                // With one unknown left, the sum of the unknowns is that unknown.
                let v = self.unknown_sum[e as usize] as u32;
                if block.solvable(e, v) {
                    self.forward.push((e, v));
                    self.assign(block, e, v);
                }
            }
            _ => {}
        }
    }

    fn try_backward(&mut self, block: &LocalBlock, v: u32) {
        if self.var_known[v as usize] || self.remaining_count[v as usize] != 1 {
            return;
        }
        let e = *block
            .column(v)
            .iter()
            .find(|&&e| !self.eq_done[e as usize])
            .expect("one remaining equation");
        if block.solvable(e, v) {
            self.backward.push((e, v));
            self.assign(block, e, v);
        }
    }

    fn assign(&mut self, block: &LocalBlock, e: u32, v: u32) {
        self.make_known(block, v);
        self.eq_done[e as usize] = true;
        for &(u, _) in block.row(e) {
            if self.var_known[u as usize] {
                continue;
            }
            self.remaining_count[u as usize] -= 1;
            if self.remaining_count[u as usize] == 1 {
                self.backward_queue.push(u);
            }
            self.rescore_with(block, u, false);
        }
    }

    fn make_known(&mut self, block: &LocalBlock, v: u32) {
        self.var_known[v as usize] = true;
        for &e in block.column(v) {
            if self.eq_done[e as usize] {
                continue;
            }
            self.unknown_count[e as usize] -= 1;
            self.unknown_sum[e as usize] -= u64::from(v);
            let count = self.unknown_count[e as usize];
            if count <= 1 {
                self.forward_queue.push_back(e);
            }
            if count <= 2 {
                for &(u, _) in block.row(e) {
                    if !self.var_known[u as usize] {
                        self.rescore_with(block, u, false);
                    }
                }
            }
        }
    }

    /// Recomputes a variable's score; queues it when it changed or when `force`.
    fn rescore_with(&mut self, block: &LocalBlock, v: u32, force: bool) {
        let mut enabled = 0;
        for &e in block.column(v) {
            if self.eq_done[e as usize] || self.unknown_count[e as usize] != 2 {
                continue;
            }
            let other = (self.unknown_sum[e as usize] - u64::from(v)) as u32;
            enabled += u32::from(block.solvable(e, other));
        }
        let score = (self.remaining_count[v as usize], enabled);
        if score != self.score[v as usize] || force {
            self.score[v as usize] = score;
            self.heap.push((score, Reverse(v)));
        }
    }

    fn pick_tear(&mut self) -> Option<u32> {
        while let Some((score, Reverse(v))) = self.heap.pop() {
            if !self.var_known[v as usize] && score == self.score[v as usize] {
                return Some(v);
            }
        }
        None
    }

    fn torn_block(&self, block: &Block) -> TornBlock {
        let pair = |&(e, v): &(u32, u32)| (block.eqs[e as usize], block.vars[v as usize]);
        let mut inner: Vec<(EqId, VarId)> = self.forward.iter().map(pair).collect();
        inner.extend(self.backward.iter().rev().map(pair));
        TornBlock {
            iteration_vars: self.tears.iter().map(|&v| block.vars[v as usize]).collect(),
            residual_eqs: self
                .residuals
                .iter()
                .map(|&e| block.eqs[e as usize])
                .collect(),
            inner,
        }
    }
}
