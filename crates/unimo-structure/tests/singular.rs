//! Structurally singular, over- and under-determined models, and failing index
//! reduction: errors with their codes and Dulmage–Mendelsohn parts.

mod common;

use common::{pendulum, MockSystem};
use unimo_structure::dump::dump_dm;
use unimo_structure::{
    analyze, blt, dulmage_mendelsohn, maximum_matching, pantelides, pantelides_with_options,
    singularity, BipartiteGraph, EqId, IdNaming, PantelidesOptions, Part, StateSelectPriority,
    StructError, VarId,
};

fn default_priority(_: VarId) -> StateSelectPriority {
    StateSelectPriority::Default
}

fn part(eqs: &[u32], vars: &[u32]) -> Part {
    Part {
        eqs: eqs.iter().map(|&e| EqId(e)).collect(),
        vars: vars.iter().map(|&v| VarId(v)).collect(),
    }
}

#[test]
fn square_but_singular_system_names_both_parts() {
    // e0: f(x) = 0; e1: g(x) = 0 (both only x); e2: h(y, z) = 0.
    let g = BipartiteGraph::from_edges(3, 3, &[(0, 0), (1, 0), (2, 1), (2, 2)]).unwrap();
    let m = maximum_matching(&g);
    let err = blt(&g, &m, |_| true).unwrap_err();
    assert_eq!(err.code(), "E3201");
    assert_eq!(
        err,
        StructError::Singular {
            over: part(&[0, 1], &[0]),
            under: part(&[2], &[1, 2]),
        }
    );
    let text = dump_dm(&dulmage_mendelsohn(&g, &m), &IdNaming);
    assert_eq!(
        text,
        "over: {e0 e1 | v0}\nunder: {e2 | v1 v2}\nwell: { | }\n"
    );
    assert!(err
        .to_string()
        .contains("2 equation(s) over-determine 1 variable(s) [e0 e1]"));
}

#[test]
fn over_determined_system() {
    // Three equations in two variables: e0: x, e1: x y, e2: y.
    let g = BipartiteGraph::from_edges(3, 2, &[(0, 0), (1, 0), (1, 1), (2, 1)]).unwrap();
    let err = singularity(&g, |_| true, |_| true).unwrap();
    assert_eq!(
        err,
        StructError::Singular {
            over: part(&[0, 1, 2], &[0, 1]),
            under: Part::default(),
        }
    );
}

#[test]
fn pantelides_refuses_a_singular_system_instead_of_looping() {
    // Two equations in the same algebraic x would be differentiated forever.
    let mut s = MockSystem::new();
    let x = s.var("x");
    let y = s.var("y");
    let dy = s.der(y);
    s.eq("e0", &[x]);
    s.eq("e1", &[x]);
    s.eq("e2", &[dy, y]);
    let err = pantelides(&mut s).unwrap_err();
    assert_eq!(err.code(), "E3201");
    let StructError::Singular { over, .. } = err else {
        panic!()
    };
    assert_eq!(over, part(&[0, 1], &[0]));
}

#[test]
fn an_equation_without_variables_is_over_determined() {
    let mut s = MockSystem::new();
    let x = s.var("x");
    s.eq("e0", &[x]);
    s.eq("e1", &[]);
    let err = pantelides(&mut s).unwrap_err();
    let StructError::Singular { over, .. } = err else {
        panic!("{err}")
    };
    assert_eq!(over.eqs, vec![EqId(1)]);
}

#[test]
fn under_determined_system_fails_at_the_index_one_matching() {
    // e0: der(x) = y + z with y and z free.
    let mut s = MockSystem::new();
    let x = s.var("x");
    let y = s.var("y");
    let z = s.var("z");
    let dx = s.der(x);
    s.eq("e0", &[dx, y, z]);
    let err = analyze(&mut s, default_priority, |_, _| true).unwrap_err();
    let StructError::Singular { over, under } = err else {
        panic!("{err}")
    };
    assert!(over.is_empty());
    assert_eq!(under.eqs, vec![EqId(0)]);
    assert_eq!(under.vars.len(), 3);
}

#[test]
fn non_differentiable_equation_is_reported() {
    let mut s = pendulum();
    s.forbid_differentiation(EqId(4));
    let err = pantelides(&mut s).unwrap_err();
    assert_eq!(err.code(), "E3202");
    assert_eq!(
        err,
        StructError::IndexReductionFailed {
            eq: EqId(4),
            reason: "contains a non-differentiable function".into()
        }
    );
}

#[test]
fn differentiation_limit_names_the_original_equation() {
    let mut s = pendulum();
    let options = PantelidesOptions {
        max_differentiations: Some(1),
    };
    let err = pantelides_with_options(&mut s, &options).unwrap_err();
    assert_eq!(
        err,
        StructError::DifferentiationLimit {
            eq: EqId(4),
            limit: 1
        }
    );
    assert_eq!(err.code(), "E3203");
}

#[test]
fn tearing_refuses_a_non_square_block() {
    let g = BipartiteGraph::from_edges(1, 2, &[(0, 0), (0, 1)]).unwrap();
    let block = unimo_structure::Block {
        eqs: vec![EqId(0)],
        vars: vec![VarId(0), VarId(1)],
    };
    let err = unimo_structure::tear_block(&g, &block, |_, _| true).unwrap_err();
    assert_eq!(err.code(), "E3206");
}
