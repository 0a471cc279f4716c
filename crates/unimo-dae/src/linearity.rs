//! Whether a Newton block is linear in each mode: the degree (constant, affine or
//! otherwise) of its residuals and Jacobian in the iteration variables while the
//! model's zero-crossing relations keep their outcome.

use crate::dae::Dae;
use crate::expr::{ExprId, Node, ScalarId};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The relations and held roundings of the model's equations (the runtime's zero
/// crossings): between events, and inside each round of a block's mode iteration at an
/// event, they keep their outcome whatever their operands.
pub(crate) fn frozen_between_events(dae: &Dae) -> HashSet<ExprId> {
    let c = crate::events::zero_crossings(dae);
    c.relations.into_iter().chain(c.held).collect()
}

/// How an expression depends on a block's iteration variables: not at all, affinely,
/// or otherwise.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Degree {
    Constant,
    Affine,
    Nonlinear,
}

/// Whether the block's residuals, computed as its residual tape computes them (inner
/// assignments in order, then the residual expressions), are affine in the iteration
/// variables while its relations are frozen: then one Newton step solves each mode.
/// A relation or held rounding counts as constant only if it is one of the model's
/// zero crossings and not inside `noEvent` (the tape evaluates exactly those from the
/// stored outcome); `abs`, `min`, `max` and relations under `noEvent` are kinks.
pub(crate) fn affine_while_frozen(
    dae: &Dae,
    iteration: &[ScalarId],
    inner: &[(ScalarId, ExprId)],
    residuals: &[ExprId],
    frozen: &HashSet<ExprId>,
) -> bool {
    let mut of_var: HashMap<ScalarId, Degree> =
        iteration.iter().map(|&v| (v, Degree::Affine)).collect();
    let mut memo = HashMap::default();
    for &(v, e) in inner {
        let d = degree(dae, e, false, &of_var, frozen, &mut memo);
        // Memoized degrees may depend on this variable's: start afresh per inner.
        memo.clear();
        of_var.insert(v, d);
    }
    residuals
        .iter()
        .all(|&r| degree(dae, r, false, &of_var, frozen, &mut memo) != Degree::Nonlinear)
}

pub(crate) fn degree(
    dae: &Dae,
    e: ExprId,
    no_event: bool,
    of_var: &HashMap<ScalarId, Degree>,
    frozen: &HashSet<ExprId>,
    memo: &mut HashMap<(ExprId, bool), Degree>,
) -> Degree {
    use Degree::*;
    if let Some(&d) = memo.get(&(e, no_event)) {
        return d;
    }
    let mut of = |x: ExprId, ne: bool| degree(dae, x, ne, of_var, frozen, memo);
    let node = dae.arena.node(e);
    let d = match node {
        Node::Var(v) => of_var.get(&v).copied().unwrap_or(Constant),
        Node::Const(_) | Node::Sample(..) | crate::run_time_leaf!() => Constant,
        Node::Add(a, b) => of(a, no_event).max(of(b, no_event)),
        Node::Neg(a) => of(a, no_event),
        Node::Mul(a, b) => match (of(a, no_event), of(b, no_event)) {
            (Constant, d) | (d, Constant) => d,
            _ => Nonlinear,
        },
        Node::Div(a, b) => match (of(a, no_event), of(b, no_event)) {
            (d, Constant) => d,
            _ => Nonlinear,
        },
        Node::NoEvent(a) => of(a, true),
        Node::If(c, a, b) => match of(c, no_event) {
            Constant => of(a, no_event).max(of(b, no_event)),
            _ => Nonlinear,
        },
        Node::Rel(..) | Node::Fn1(..) | Node::Fn2(..) if !no_event && frozen.contains(&e) => {
            Constant
        }
        _ => {
            let moving = dae
                .arena
                .children(e)
                .into_iter()
                .any(|c| of(c, no_event) != Constant);
            if moving {
                Nonlinear
            } else {
                Constant
            }
        }
    };
    memo.insert((e, no_event), d);
    d
}
