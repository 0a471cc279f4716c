//! High-index chains and an index-2 circuit through the whole pipeline.

mod common;

use common::MockSystem;
use unimo_structure::dump::{dump_analysis, dump_pantelides};
use unimo_structure::verify::verify_analysis;
use unimo_structure::{analyze, pantelides, IndexReductionSystem, StateSelectPriority, VarId};

fn default_priority(_: VarId) -> StateSelectPriority {
    StateSelectPriority::Default
}

/// x1 = sin(time); x_k = der(x_{k-1}) for k = 2..=n: structural index n.
fn derivative_chain(n: usize) -> MockSystem {
    let mut s = MockSystem::new();
    let xs: Vec<VarId> = (1..=n).map(|k| s.var(&format!("x{k}"))).collect();
    s.eq("c1", &[xs[0]]); // x1 = sin(time)
    for k in 1..n {
        let d = s.der(xs[k - 1]);
        s.eq(&format!("c{}", k + 1), &[xs[k], d]); // x_{k+1} = der(x_k)
    }
    s
}

#[test]
fn chain_reaches_structural_index_five() {
    for n in 1..=5 {
        let mut s = derivative_chain(n);
        let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
        verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
        let counts: Vec<u32> = analysis.pantelides.differentiation_count[..n].to_vec();
        let expected: Vec<u32> = (0..n).map(|k| (n - 1 - k) as u32).collect();
        assert_eq!(counts, expected, "n = {n}");
        assert_eq!(analysis.pantelides.max_differentiations() as usize, n - 1);
        assert_eq!(analysis.dummies.dummies.len(), n * (n - 1) / 2);
        assert!(
            analysis.dummies.states.is_empty(),
            "every derivative is forced by time"
        );
        assert!(
            analysis.torn.iter().all(|t| t.is_explicit()),
            "a chain needs no iteration"
        );
    }
}

#[test]
fn chain_of_index_five_snapshot() {
    let mut s = derivative_chain(5);
    let result = pantelides(&mut s).unwrap();
    insta::assert_snapshot!("chain5_pantelides", dump_pantelides(&result, &s));
}

/// A capacitor directly across an ideal voltage source (index 2):
/// e0: vs = sin(time); e1: vc = vs; e2: C der(vc) = ic; e3: is + ic = 0.
fn capacitor_on_voltage_source() -> MockSystem {
    let mut s = MockSystem::new();
    let vs = s.var("vs"); // source voltage
    let vc = s.var("vc"); // capacitor voltage (would-be state)
    let ic = s.var("ic"); // capacitor current
    let is = s.var("is"); // source current
    let dvc = s.der(vc);
    s.eq("e0", &[vs]);
    s.eq("e1", &[vc, vs]);
    s.eq("e2", &[dvc, ic]);
    s.eq("e3", &[is, ic]);
    s
}

#[test]
fn capacitor_across_voltage_source_is_index_two() {
    let mut s = capacitor_on_voltage_source();
    let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
    verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
    assert_eq!(analysis.pantelides.differentiation_count[..4], [1, 1, 0, 0]);
    assert_eq!(analysis.pantelides.max_differentiations(), 1);
    assert!(
        analysis.dummies.states.is_empty(),
        "the capacitor voltage is not a state"
    );
    assert_eq!(s.names(&analysis.dummies.dummy_states), ["vs", "vc"]);
    insta::assert_snapshot!("capacitor", dump_analysis(s.graph(), &analysis, &s));
}

#[test]
fn an_ode_needs_no_reduction() {
    // e0: der(x) = -x; e1: y = x (an output).
    let mut s = MockSystem::new();
    let x = s.var("x");
    let y = s.var("y");
    let dx = s.der(x);
    s.eq("e0", &[dx, x]);
    s.eq("e1", &[y, x]);
    let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
    verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
    assert_eq!(analysis.pantelides.max_differentiations(), 0);
    assert_eq!(s.names(&analysis.dummies.states), ["x"]);
    assert_eq!(s.graph().n_eqs(), 2);
    assert_eq!(analysis.blocks.len(), 2);
}

#[test]
fn derivative_variables_that_do_not_occur_are_skipped() {
    // der(x) exists but occurs nowhere: x is an algebraic unknown, not a state.
    let mut s = MockSystem::new();
    let x = s.var("x");
    let _dx = s.der(x);
    s.eq("e0", &[x]);
    let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
    verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
    assert!(analysis.dummies.states.is_empty());
    assert_eq!(analysis.pantelides.max_differentiations(), 0);
}
