//! Which variables keep their states: the ranks of the candidates (`stateSelect`, a
//! fixed start, derivatives named by `v = der(x)`), the dummy derivatives with their
//! dynamic state sets, and which components of a level get run-time selection.

use super::DaeSystem;
use crate::dae::{Dae, EqId, ScalarKind};
use crate::diff::partial;
use crate::expr::{ExprId, Node, ScalarId};
use rustc_hash::FxHashMap as HashMap;
use unimo_structure as st;

/// Per variable of the structural graph, what decides which variables keep their
/// states: the priority of the variable that would lose its state, and whether it has
/// a fixed start (see `select_dummy_derivatives_with_sets`).
pub(super) fn selection_ranks(
    sys: &DaeSystem<'_>,
    n_vars: usize,
) -> (Vec<st::StateSelectPriority>, Vec<bool>) {
    // The priority of the variable that would lose its state: v's integral. A
    // derivative the model names (`w = der(phi)`) has the named variable's.
    let names = named_derivatives(sys.dae);
    let priorities: Vec<st::StateSelectPriority> = (0..n_vars)
        .map(|k| {
            let s = sys.scalar(st::VarId(k as u32));
            if let Some(&v) = names.get(&s) {
                return sys.dae.scalar(v).state_select;
            }
            let base = sys.dae.scalar(s).derivative_of.unwrap_or(s);
            sys.dae.scalar(base).state_select
        })
        .collect();
    // Whether v has a fixed start value of its own (ties of priority, see
    // `select_dummy_derivatives_with_sets`). A derivative has none (a position's initial
    // condition says nothing about which velocity is a state), unless the model names
    // it: `w = der(phi)` with `w` fixed.
    let fixed_starts: Vec<bool> = (0..n_vars)
        .map(|k| {
            let s = sys.scalar(st::VarId(k as u32));
            let own = names.get(&s).copied().unwrap_or(s);
            sys.dae.scalar(own).fixed == Some(true)
        })
        .collect();
    (priorities, fixed_starts)
}

/// The derivatives `der(x)` that an equation `v = der(x)` (either side) names by a
/// variable `v`, with the first such `v`: MSL's joints declare `w = der(phi)`, and
/// `Parts.RollingWheelSet` `der_theta1 = der(theta1)` with `der_theta1(fixed = true)`,
/// its wheel's rate. The named variable's `stateSelect` and `fixed` decide for the
/// derivative (not the position's: `x` always a state says nothing about which
/// velocity is one).
fn named_derivatives(dae: &Dae) -> HashMap<ScalarId, ScalarId> {
    let var = |e: ExprId| match dae.arena.node(e) {
        Node::Var(s) => Some(s),
        _ => None,
    };
    let mut named = HashMap::default();
    for eq in &dae.equations {
        let (Some(a), Some(b)) = (var(eq.lhs), var(eq.rhs)) else {
            continue;
        };
        for (v, d) in [(a, b), (b, a)] {
            if dae.scalar(d).kind == ScalarKind::Derivative
                && dae.scalar(v).kind != ScalarKind::Derivative
            {
                named.entry(d).or_insert(v);
            }
        }
    }
    named
}

/// Whether a component of a dummy level gets dynamic state selection: its candidates'
/// integrals share one `stateSelect` other than `always` and `never` (different
/// priorities decide statically), there are at most 64 of them, and the Jacobian of the
/// level's equations in the candidates depends on the continuous variables (with
/// constant coefficients, as in circuits and gears, a static choice is regular
/// everywhere or nowhere).
/// The dummy derivatives, with dynamic state sets and the equations' constant
/// coefficients (a structurally valid but numerically singular choice is replaced).
pub(super) fn select_dummies(
    sys: &mut DaeSystem<'_>,
    graph: &st::BipartiteGraph,
    pantelides: &st::PantelidesResult,
    priorities: &[st::StateSelectPriority],
    fixed_starts: &[bool],
) -> Result<st::DummyDerivatives, st::StructError> {
    let sys_cell = std::cell::RefCell::new(sys);
    let mut values = crate::params::ParameterValues::default();
    let mut coefficient = |e: st::EqId, v: st::VarId| {
        let mut guard = sys_cell.borrow_mut();
        let sys = &mut **guard;
        let r = sys.dae.residual(EqId(e.0));
        let s = sys.scalar(v);
        let d = partial(&mut sys.dae.arena, r, s);
        values.of_expr(sys.dae, d).filter(|c| c.is_finite())
    };
    st::select_dummy_derivatives_with_sets(
        graph,
        pantelides,
        |v| priorities[v.index()],
        |v| fixed_starts[v.index()],
        |eqs, candidates| is_dynamic_set(&mut sys_cell.borrow_mut(), priorities, eqs, candidates),
        Some(&mut coefficient),
    )
}

fn is_dynamic_set(
    sys: &mut DaeSystem<'_>,
    priorities: &[st::StateSelectPriority],
    eqs: &[st::EqId],
    candidates: &[st::VarId],
) -> bool {
    // `stateSelect` decides between candidates of different priorities, and `always`
    // or `never` leave nothing to choose; among candidates of one priority (the MSL's
    // quaternions are all `avoid`) the static order is arbitrary.
    let Some(first) = candidates.first().map(|v| priorities[v.index()]) else {
        return false;
    };
    if candidates.len() > 64
        || matches!(
            first,
            st::StateSelectPriority::Always | st::StateSelectPriority::Never
        )
        || candidates.iter().any(|v| priorities[v.index()] != first)
    {
        return false;
    }
    for &e in eqs {
        let r = sys.dae.residual(EqId(e.0));
        for &c in candidates {
            let s = sys.scalar(c);
            let d = partial(&mut sys.dae.arena, r, s);
            let varying = sys.dae.arena.vars(d).into_iter().any(|x| {
                matches!(
                    sys.dae.scalar(x).kind,
                    ScalarKind::Continuous | ScalarKind::Derivative
                )
            });
            if varying {
                return true;
            }
        }
    }
    false
}
