//! Tearing of algebraic loops with per-edge solvability.

use unimo_structure::dump::dump_torn_blocks;
use unimo_structure::verify::{verify_blt, verify_torn_block};
use unimo_structure::{
    blt, maximum_matching, tear_block, BipartiteGraph, Block, EqId, IdNaming, VarId,
};

fn whole_block(g: &BipartiteGraph) -> Block {
    let m = maximum_matching(g);
    let blocks = blt(g, &m, |_| true).unwrap();
    verify_blt(g, &blocks, |_| true).unwrap();
    assert_eq!(
        blocks.len(),
        1,
        "the fixture is one strongly connected block"
    );
    blocks.into_iter().next().unwrap()
}

#[test]
fn a_cycle_tears_to_one_iteration_variable() {
    // e_i: v_i = f(v_{i+1 mod 6}) — one loop through six equations.
    let n = 6u32;
    let edges: Vec<(u32, u32)> = (0..n).flat_map(|i| [(i, i), (i, (i + 1) % n)]).collect();
    let g = BipartiteGraph::from_edges(n as usize, n as usize, &edges).unwrap();
    let block = whole_block(&g);
    let torn = tear_block(&g, &block, |_, _| true).unwrap();
    verify_torn_block(&g, &block, &torn, |_, _| true).unwrap();
    assert_eq!(torn.iteration_vars.len(), 1);
    assert_eq!(torn.inner.len(), 5);
    insta::assert_snapshot!("cycle", dump_torn_blocks(&[torn], &IdNaming));
}

#[test]
fn solvability_decides_the_tear() {
    // Resistive divider loop: e0: i = (u0 - u1)/R (solvable for i, u1),
    // e1: u1 = R2 i (solvable for u1, i), e2: u0 = f(i) where f is not invertible.
    // v0 = i, v1 = u1, v2 = u0.
    let g = BipartiteGraph::from_edges(
        3,
        3,
        &[(0, 0), (0, 1), (0, 2), (1, 1), (1, 0), (2, 2), (2, 0)],
    )
    .unwrap();
    let block = whole_block(&g);
    let solvable = |e: EqId, v: VarId| !(e == EqId(2) && v == VarId(0));
    let torn = tear_block(&g, &block, solvable).unwrap();
    verify_torn_block(&g, &block, &torn, solvable).unwrap();
    assert_eq!(torn.iteration_vars.len(), 1);
    assert!(torn.inner.iter().all(|&(e, v)| solvable(e, v)));
}

#[test]
fn nothing_solvable_means_everything_iterates() {
    let edges: Vec<(u32, u32)> = (0..3).flat_map(|e| (0..3).map(move |v| (e, v))).collect();
    let g = BipartiteGraph::from_edges(3, 3, &edges).unwrap();
    let block = whole_block(&g);
    let torn = tear_block(&g, &block, |_, _| false).unwrap();
    verify_torn_block(&g, &block, &torn, |_, _| false).unwrap();
    assert_eq!(torn.iteration_vars.len(), 3);
    assert_eq!(torn.residual_eqs.len(), 3);
}

#[test]
fn two_coupled_loops_tear_to_one_shared_variable() {
    // Two loops sharing v0: v0 -> v1 -> v2 -> v0 and v0 -> v3 -> v4 -> v0.
    // e0: v0 v2 v4 (v0 = v2 + v4), e1: v1 v0, e2: v2 v1, e3: v3 v0, e4: v4 v3.
    let edges = [
        (0, 0),
        (0, 2),
        (0, 4),
        (1, 1),
        (1, 0),
        (2, 2),
        (2, 1),
        (3, 3),
        (3, 0),
        (4, 4),
        (4, 3),
    ];
    let g = BipartiteGraph::from_edges(5, 5, &edges).unwrap();
    let block = whole_block(&g);
    let torn = tear_block(&g, &block, |_, _| true).unwrap();
    verify_torn_block(&g, &block, &torn, |_, _| true).unwrap();
    assert_eq!(torn.iteration_vars, vec![VarId(0)]);
}

#[test]
fn backward_assignment_goes_last() {
    // Not a BLT block but any square set: v2 occurs only in e2, so e2 computes v2, and
    // only after the loop e0/e1 has produced v0 and v1.
    // e0: v0 v1; e1: v1 v0; e2: v2 v0 v1.
    let edges = [(0, 0), (0, 1), (1, 1), (1, 0), (2, 2), (2, 0), (2, 1)];
    let g = BipartiteGraph::from_edges(3, 3, &edges).unwrap();
    let block = Block {
        eqs: vec![EqId(0), EqId(1), EqId(2)],
        vars: vec![VarId(0), VarId(1), VarId(2)],
    };
    let torn = tear_block(&g, &block, |_, _| true).unwrap();
    verify_torn_block(&g, &block, &torn, |_, _| true).unwrap();
    assert_eq!(torn.iteration_vars.len(), 1);
    assert_eq!(torn.inner.last(), Some(&(EqId(2), VarId(2))));
}
