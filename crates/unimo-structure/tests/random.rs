//! Randomized checks on sparse graphs from a deterministic LCG (no proptest): every
//! result must pass `verify`, matchings must be maximum, BLT must agree with petgraph.

mod common;

use common::Lcg;
use petgraph::graph::DiGraph;
use unimo_structure::verify::{verify_analysis, verify_blt, verify_matching, verify_torn_block};
use unimo_structure::{
    analyze, blt, dulmage_mendelsohn, maximum_matching, tear_blocks, BipartiteGraph, EqId,
    IndexReductionSystem, Matching, StateSelectPriority, StructuralSystem, VarId,
};

fn random_graph(rng: &mut Lcg, n_eqs: usize, n_vars: usize, edges_per_eq: usize) -> BipartiteGraph {
    let adjacency = (0..n_eqs)
        .map(|_| {
            (0..1 + rng.below(edges_per_eq))
                .map(|_| VarId::new(rng.below(n_vars)))
                .collect()
        })
        .collect();
    BipartiteGraph::from_adjacency(n_vars, adjacency).unwrap()
}

/// Kuhn's simple augmenting-path algorithm, as a reference for the matching size.
fn reference_matching_size(g: &BipartiteGraph) -> usize {
    fn try_eq(g: &BipartiteGraph, e: EqId, seen: &mut [bool], mate: &mut [Option<EqId>]) -> bool {
        for &v in g.eq_vars(e) {
            if seen[v.index()] {
                continue;
            }
            seen[v.index()] = true;
            if mate[v.index()].is_none_or(|other| try_eq(g, other, seen, mate)) {
                mate[v.index()] = Some(e);
                return true;
            }
        }
        false
    }
    let mut mate = vec![None; g.n_vars()];
    g.eqs()
        .filter(|&e| try_eq(g, e, &mut vec![false; g.n_vars()], &mut mate))
        .count()
}

#[test]
fn matchings_are_maximum_and_dulmage_mendelsohn_counts_agree() {
    let mut rng = Lcg(7);
    for _ in 0..400 {
        let (n_eqs, n_vars) = (1 + rng.below(40), 1 + rng.below(40));
        let g = random_graph(&mut rng, n_eqs, n_vars, 3);
        let m = maximum_matching(&g);
        verify_matching(&g, &m).unwrap();
        assert_eq!(m.size(), reference_matching_size(&g));
        let dm = dulmage_mendelsohn(&g, &m);
        let unmatched_eqs = n_eqs - m.size();
        let unmatched_vars = n_vars - m.size();
        assert_eq!(dm.over.eqs.len() - dm.over.vars.len(), unmatched_eqs);
        assert_eq!(dm.under.vars.len() - dm.under.eqs.len(), unmatched_vars);
        assert_eq!(dm.well.eqs.len(), dm.well.vars.len());
        assert_eq!(
            dm.over.eqs.len() + dm.under.eqs.len() + dm.well.eqs.len(),
            n_eqs
        );
        assert_eq!(
            dm.over.vars.len() + dm.under.vars.len() + dm.well.vars.len(),
            n_vars
        );
        // Over-determined equations use only over-determined variables.
        for &e in &dm.over.eqs {
            assert!(g
                .eq_vars(e)
                .iter()
                .all(|v| dm.over.vars.binary_search(v).is_ok()));
        }
    }
}

/// A square graph with a perfect matching: a random permutation plus random edges.
fn random_square(rng: &mut Lcg, n: usize, extra: usize) -> BipartiteGraph {
    let mut permutation: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        permutation.swap(i, rng.below(i + 1));
    }
    let adjacency = (0..n)
        .map(|e| {
            let mut row = vec![VarId::new(permutation[e])];
            row.extend((0..rng.below(extra + 1)).map(|_| VarId::new(rng.below(n))));
            row
        })
        .collect();
    BipartiteGraph::from_adjacency(n, adjacency).unwrap()
}

fn solvable_by_hash(seed: u64) -> impl Fn(EqId, VarId) -> bool {
    move |e, v| {
        let h = (u64::from(e.0) * 0x9E37_79B9 + u64::from(v.0) * 0x85EB_CA6B) ^ seed;
        h.wrapping_mul(0xC2B2_AE35) % 100 < 70
    }
}

/// The strongly connected components of the dependency graph, by petgraph.
fn petgraph_components(g: &BipartiteGraph, m: &Matching) -> Vec<Vec<EqId>> {
    let mut dg = DiGraph::<(), ()>::new();
    let nodes: Vec<_> = g.eqs().map(|_| dg.add_node(())).collect();
    for e in g.eqs() {
        for &v in g.eq_vars(e) {
            let producer = m.eq_of(v).unwrap();
            if producer != e {
                dg.add_edge(nodes[e.index()], nodes[producer.index()], ());
            }
        }
    }
    let mut components: Vec<Vec<EqId>> = petgraph::algo::kosaraju_scc(&dg)
        .into_iter()
        .map(|c| {
            let mut eqs: Vec<EqId> = c.into_iter().map(|n| EqId::new(n.index())).collect();
            eqs.sort_unstable();
            eqs
        })
        .collect();
    components.sort_unstable();
    components
}

#[test]
fn blt_and_tearing_verify_on_random_square_systems() {
    let mut rng = Lcg(11);
    for round in 0..300 {
        let n = 1 + rng.below(60);
        let g = random_square(&mut rng, n, 3);
        let m = maximum_matching(&g);
        assert_eq!(m.size(), n);
        let blocks = blt(&g, &m, |_| true).unwrap();
        verify_blt(&g, &blocks, |_| true).unwrap();
        let mut ours: Vec<Vec<EqId>> = blocks.iter().map(|b| b.eqs.clone()).collect();
        ours.sort_unstable();
        assert_eq!(ours, petgraph_components(&g, &m));
        let solvable = solvable_by_hash(round);
        let torn = tear_blocks(&g, &blocks, &solvable).unwrap();
        for (block, torn) in blocks.iter().zip(&torn) {
            verify_torn_block(&g, block, torn, &solvable).unwrap();
        }
    }
}

/// A random DAE of n variable families: each family has a base variable and, with some
/// probability, its derivative; equation i uses a member of family perm(i) and a few
/// random members of other families, so the families can always be matched.
fn random_dae(rng: &mut Lcg, n: usize) -> StructuralSystem {
    let mut s = StructuralSystem::new();
    let base: Vec<VarId> = (0..n).map(|i| s.add_var(&format!("x{i}"))).collect();
    let members: Vec<Vec<VarId>> = base
        .iter()
        .map(|&x| {
            if rng.chance(60) {
                vec![x, s.derivative(x)]
            } else {
                vec![x]
            }
        })
        .collect();
    let mut permutation: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        permutation.swap(i, rng.below(i + 1));
    }
    for (i, &family) in permutation.iter().enumerate() {
        let pick = |rng: &mut Lcg, f: usize| members[f][rng.below(members[f].len())];
        let mut vars = vec![pick(rng, family)];
        for _ in 0..rng.below(3) {
            let f = rng.below(n);
            vars.push(pick(rng, f));
        }
        s.add_eq(&format!("q{i}"), &vars).unwrap();
    }
    s
}

const PRIORITIES: [StateSelectPriority; 5] = [
    StateSelectPriority::Never,
    StateSelectPriority::Avoid,
    StateSelectPriority::Default,
    StateSelectPriority::Prefer,
    StateSelectPriority::Always,
];

#[test]
fn random_daes_reduce_to_verified_index_one_systems() {
    // Matchable families are all Pantelides needs; after dummy derivative selection the
    // reduced system must then have a perfect matching, whatever the priorities.
    let mut rng = Lcg(2024);
    let mut reduced = 0;
    for round in 0..400 {
        let n = 1 + rng.below(25);
        let mut s = random_dae(&mut rng, n);
        let solvable = solvable_by_hash(round);
        let priority_seed = round;
        let priority = |v: VarId| PRIORITIES[((u64::from(v.0) * 7 + priority_seed) % 5) as usize];
        let analysis = analyze(&mut s, priority, &solvable).unwrap();
        verify_analysis(s.graph(), &analysis, &solvable).unwrap();
        reduced += usize::from(analysis.pantelides.max_differentiations() > 0);
    }
    assert!(
        reduced > 100,
        "only {reduced} systems needed index reduction"
    );
}

#[test]
fn unconstrained_random_daes_either_reduce_or_are_reported_singular_up_front() {
    let mut rng = Lcg(5);
    let (mut ok, mut singular) = (0, 0);
    for _ in 0..400 {
        let n = 1 + rng.below(20);
        let mut s = StructuralSystem::new();
        let vars: Vec<VarId> = (0..n).map(|i| s.add_var(&format!("x{i}"))).collect();
        let mut pool = vars.clone();
        for &x in &vars {
            if rng.chance(50) {
                pool.push(s.derivative(x));
            }
        }
        for i in 0..n {
            let row: Vec<VarId> = (0..1 + rng.below(3))
                .map(|_| pool[rng.below(pool.len())])
                .collect();
            s.add_eq(&format!("q{i}"), &row).unwrap();
        }
        let pantelides = match unimo_structure::pantelides(&mut s) {
            Ok(result) => result,
            Err(err) => {
                assert_eq!(err.code(), "E3201", "{err}");
                singular += 1;
                continue;
            }
        };
        unimo_structure::verify::verify_pantelides(s.graph(), &pantelides).unwrap();
        let dummies = unimo_structure::select_dummy_derivatives(s.graph(), &pantelides, |_| {
            StateSelectPriority::Default
        })
        .unwrap();
        unimo_structure::verify::verify_dummy_derivatives(s.graph(), &pantelides, &dummies)
            .unwrap();
        ok += 1;
    }
    assert!(ok > 50 && singular > 50, "ok {ok}, singular {singular}");
}

#[test]
fn large_random_sparse_graph_matches_like_the_reference() {
    let mut rng = Lcg(99);
    let g = random_graph(&mut rng, 3000, 3000, 3);
    assert_eq!(maximum_matching(&g).size(), reference_matching_size(&g));
}
