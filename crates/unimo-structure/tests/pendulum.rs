//! Cartesian pendulums (index 3): Pantelides, dummy derivatives, BLT and tearing.

mod common;

use common::{pendulum, pendulum_solvable, MockSystem};
use unimo_structure::dump::dump_analysis;
use unimo_structure::verify::verify_analysis;
use unimo_structure::{
    analyze, pantelides, select_dummy_derivatives, EqId, IndexReductionSystem, Naming,
    StateSelectPriority, VarId,
};

fn default_priority(_: VarId) -> StateSelectPriority {
    StateSelectPriority::Default
}

/// The differentiation counts of the five original equations, by name.
fn counts_by_name(s: &MockSystem, counts: &[u32]) -> Vec<(String, u32)> {
    (0..5)
        .map(|e| (s.eq_name(EqId::new(e)), counts[e]))
        .collect()
}

#[test]
fn pantelides_differentiates_constraint_twice_and_kinematics_once() {
    let mut s = pendulum();
    let result = pantelides(&mut s).unwrap();
    let counts = counts_by_name(&s, &result.differentiation_count);
    let expected = [("e0", 1), ("e1", 1), ("e2", 0), ("e3", 0), ("e4", 2)];
    let expected: Vec<(String, u32)> = expected.iter().map(|(n, c)| (n.to_string(), *c)).collect();
    assert_eq!(counts, expected);
    assert_eq!(result.max_differentiations(), 2);
    assert_eq!(s.graph().n_eqs(), 9);
    unimo_structure::verify::verify_pantelides(s.graph(), &result).unwrap();
}

#[test]
fn dummy_derivatives_leave_two_states_and_index_one() {
    let mut s = pendulum();
    let result = pantelides(&mut s).unwrap();
    let dummies = select_dummy_derivatives(s.graph(), &result, default_priority).unwrap();
    assert_eq!(
        dummies.states.len(),
        2,
        "states: {:?}",
        s.names(&dummies.states)
    );
    assert_eq!(dummies.dummies.len(), 4);
    let states = s.names(&dummies.states);
    assert!(
        states == ["x", "vx"] || states == ["y", "vy"],
        "unexpected states {states:?}"
    );
    let matching = dummies.index_one_matching(s.graph()).unwrap();
    assert_eq!(matching.size(), s.graph().n_eqs());
}

#[test]
fn full_pipeline_snapshot() {
    let mut s = pendulum();
    let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
    verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
    // Re-tear with the pendulum's real solvability for the snapshot.
    let solvable = pendulum_solvable(&s);
    let torn = unimo_structure::tear_blocks(s.graph(), &analysis.blocks, &solvable).unwrap();
    let analysis = unimo_structure::StructuralAnalysis { torn, ..analysis };
    verify_analysis(s.graph(), &analysis, &solvable).unwrap();
    insta::assert_snapshot!("pendulum", dump_analysis(s.graph(), &analysis, &s));
}

#[test]
fn priorities_choose_which_coordinate_stays_a_state() {
    // Preferring a position alone keeps it a state; the velocity state is chosen at the
    // level above, so preferring a coordinate means preferring its position and velocity.
    for (preferred, expected) in [(["x", "vx"], ["x", "vx"]), (["y", "vy"], ["y", "vy"])] {
        let mut s = pendulum();
        let result = pantelides(&mut s).unwrap();
        let (p, q) = (s.find_var(preferred[0]), s.find_var(preferred[1]));
        let priority = |v: VarId| {
            if v == p || v == q {
                StateSelectPriority::Prefer
            } else {
                StateSelectPriority::Default
            }
        };
        let dummies = select_dummy_derivatives(s.graph(), &result, priority).unwrap();
        assert_eq!(s.names(&dummies.states), expected);
    }
    let mut s = pendulum();
    let result = pantelides(&mut s).unwrap();
    let x = s.find_var("x");
    let prefer_x = |v: VarId| {
        if v == x {
            StateSelectPriority::Prefer
        } else {
            StateSelectPriority::Default
        }
    };
    let dummies = select_dummy_derivatives(s.graph(), &result, prefer_x).unwrap();
    assert!(dummies.is_state(x));
}

#[test]
fn never_and_always_priorities() {
    let mut s = pendulum();
    let result = pantelides(&mut s).unwrap();
    let (x, vx, y) = (s.find_var("x"), s.find_var("vx"), s.find_var("y"));
    let priority = |v: VarId| match v {
        v if v == y => StateSelectPriority::Never,
        v if v == x || v == vx => StateSelectPriority::Always,
        _ => StateSelectPriority::Default,
    };
    let dummies = select_dummy_derivatives(s.graph(), &result, priority).unwrap();
    assert_eq!(s.names(&dummies.states), ["x", "vx"]);
    assert!(dummies.always_not_states.is_empty());

    // Always on both positions cannot hold: one of them must give way, and it is reported.
    let priority = |v: VarId| {
        if v == x || v == y {
            StateSelectPriority::Always
        } else {
            StateSelectPriority::Default
        }
    };
    let dummies = select_dummy_derivatives(s.graph(), &result, priority).unwrap();
    assert_eq!(dummies.states.len(), 2);
    assert_eq!(dummies.always_not_states.len(), 1);
}

/// Double pendulum in Cartesian coordinates:
/// e0..e3 first mass (kinematics, forces with both rods), e4..e7 second mass,
/// e8: x1^2 + y1^2 = L1^2, e9: (x2-x1)^2 + (y2-y1)^2 = L2^2.
fn double_pendulum() -> MockSystem {
    let mut s = MockSystem::new();
    let x1 = s.var("x1"); // first mass
    let y1 = s.var("y1");
    let vx1 = s.var("vx1");
    let vy1 = s.var("vy1");
    let x2 = s.var("x2"); // second mass
    let y2 = s.var("y2");
    let vx2 = s.var("vx2");
    let vy2 = s.var("vy2");
    let f1 = s.var("F1"); // rod forces (Lagrange multipliers)
    let f2 = s.var("F2");
    let (dx1, dy1, dvx1, dvy1) = (s.der(x1), s.der(y1), s.der(vx1), s.der(vy1));
    let (dx2, dy2, dvx2, dvy2) = (s.der(x2), s.der(y2), s.der(vx2), s.der(vy2));
    s.eq("e0", &[dx1, vx1]);
    s.eq("e1", &[dy1, vy1]);
    s.eq("e2", &[dvx1, f1, x1, f2, x2]);
    s.eq("e3", &[dvy1, f1, y1, f2, y2]);
    s.eq("e4", &[dx2, vx2]);
    s.eq("e5", &[dy2, vy2]);
    s.eq("e6", &[dvx2, f2, x2, x1]);
    s.eq("e7", &[dvy2, f2, y2, y1]);
    s.eq("e8", &[x1, y1]);
    s.eq("e9", &[x1, x2, y1, y2]);
    s
}

#[test]
fn double_pendulum_has_four_states() {
    let mut s = double_pendulum();
    let analysis = analyze(&mut s, default_priority, |_, _| true).unwrap();
    verify_analysis(s.graph(), &analysis, |_, _| true).unwrap();
    let counts: Vec<u32> = analysis.pantelides.differentiation_count[..10].to_vec();
    assert_eq!(counts, vec![1, 1, 0, 0, 1, 1, 0, 0, 2, 2]);
    assert_eq!(analysis.dummies.dummies.len(), 8);
    assert_eq!(
        analysis.dummies.states.len(),
        4,
        "{:?}",
        s.names(&analysis.dummies.states)
    );
    insta::assert_snapshot!("double_pendulum", dump_analysis(s.graph(), &analysis, &s));
}
