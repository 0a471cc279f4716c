//! Zero crossings: every relation outside `noEvent` (in continuous equations and
//! `when` conditions) that involves a continuous-time quantity, plus `sample` time
//! events, plus the event-generating integer functions (`floor`, `ceil`, `integer`,
//! `div`, `mod`, `rem` of a continuous-time argument, MLS 3.7.2).

use crate::dae::{Dae, EqId};
use crate::expr::{ExprId, Node};
use rustc_hash::FxHashSet as HashSet;

/// The relations that generate state events, in first-occurrence order, and the
/// `sample` nodes (time events).
#[derive(Clone, Debug, Default)]
pub struct Crossings {
    pub relations: Vec<ExprId>,
    pub samples: Vec<ExprId>,
    /// `floor`/`ceil`/`integer`/`div`/`mod`/`rem` nodes whose argument moves between
    /// events: their value is held between events, and an event comes when the
    /// argument leaves the interval that rounds to the held value.
    pub held: Vec<ExprId>,
}

pub fn zero_crossings(dae: &Dae) -> Crossings {
    zero_crossings_except(dae, &[])
}

/// [`zero_crossings`] of the model without the equations `left_out` (those a pruned
/// plan does not compute): a relation only they hold is no crossing.
pub fn zero_crossings_except(dae: &Dae, left_out: &[EqId]) -> Crossings {
    let mut out = Crossings::default();
    let mut seen = HashSet::default();
    let mut roots: Vec<ExprId> = Vec::new();
    let mut skip = vec![false; dae.equations.len()];
    for &e in left_out {
        skip[e.index()] = true;
    }
    for (k, e) in dae.equations.iter().enumerate() {
        if !skip[k] {
            roots.push(e.lhs);
            roots.push(e.rhs);
        }
    }
    for w in &dae.whens {
        for b in &w.branches {
            roots.extend(&b.conditions);
        }
    }
    for a in &dae.assertions {
        roots.push(a.condition);
    }
    // The condition of an invariant is an if-equation's: event semantics (its value
    // changes at events only, with the equations of its branch).
    for i in &dae.invariants {
        roots.push(i.active);
    }
    for r in roots {
        collect(dae, r, &mut seen, &mut out);
    }
    out
}

fn collect(dae: &Dae, e: ExprId, seen: &mut HashSet<ExprId>, out: &mut Crossings) {
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        match dae.arena.node(x) {
            Node::NoEvent(_) => continue,
            Node::Rel(..) if moves(dae, x) => out.relations.push(x),
            Node::Fn1(f, _) if f.generates_events() && moves(dae, x) => out.held.push(x),
            Node::Fn2(f, ..) if f.generates_events() && moves(dae, x) => out.held.push(x),
            Node::Sample(..) => out.samples.push(x),
            _ => {}
        }
        stack.extend(dae.arena.children(x));
    }
}

/// The expression changes between events (a continuous-time variable or `time`).
fn moves(dae: &Dae, e: ExprId) -> bool {
    dae.arena.vars(e).iter().any(|&s| dae.is_continuous(s)) || depends_on_time(dae, e)
}

fn depends_on_time(dae: &Dae, e: ExprId) -> bool {
    let mut stack = vec![e];
    let mut seen = HashSet::default();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        if dae.arena.node(x) == Node::Time {
            return true;
        }
        stack.extend(dae.arena.children(x));
    }
    false
}
