//! Alias elimination: `a = b`, `a = -b` and `a = <constant or parameter expression>`
//! are removed and `a` replaced everywhere; the alias stays known for output
//! ([`crate::dae::Scalar::alias`]).
//!
//! Only continuous scalars without a derivative are eliminated (a state candidate is
//! kept as the representative); derivatives, discrete variables, inputs and `reinit`
//! targets are never eliminated.

use crate::dae::{Dae, ScalarKind, WhenAction};
use crate::diff::solve_linear;
use crate::expr::{ExprId, Node, ScalarId};
use rustc_hash::FxHashMap as HashMap;

/// What alias elimination did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct AliasStats {
    /// `a = b` and `a = -b`.
    pub aliases: usize,
    /// `a = <constant or parameter expression>`.
    pub constants: usize,
}

fn eliminable(dae: &Dae, s: ScalarId) -> bool {
    let sc = dae.scalar(s);
    sc.kind == ScalarKind::Continuous && sc.derivative.is_none() && !sc.input && sc.alias.is_none()
}

/// A rank: the higher one stays as the representative.
fn rank(dae: &Dae, s: ScalarId) -> (bool, bool, usize, std::cmp::Reverse<u32>) {
    let sc = dae.scalar(s);
    (
        sc.derivative.is_some(),
        sc.fixed == Some(true) || sc.start.is_some(),
        usize::MAX - sc.name.matches('.').count(),
        std::cmp::Reverse(s.0),
    )
}

pub fn eliminate_aliases(dae: &mut Dae) -> AliasStats {
    let mut stats = AliasStats::default();
    let reinit_targets = reinit_targets(dae);
    let mut map: HashMap<ScalarId, ExprId> = HashMap::default();
    // Representative -> the scalars currently mapped onto it (so that map values never
    // mention an eliminated scalar).
    let mut members: HashMap<ScalarId, Vec<ScalarId>> = HashMap::default();
    let mut keep = vec![true; dae.equations.len()];
    // Passes until nothing changes: an elimination can turn an earlier equation into
    // an alias.
    for _pass in 0..8 {
        let before = stats.clone();
        for (k, kept) in keep.iter_mut().enumerate() {
            if !*kept {
                continue;
            }
            let (l, r) = (dae.equations[k].lhs, dae.equations[k].rhs);
            let residual = dae.arena.sub(l, r);
            let residual =
                dae.arena
                    .substitute(residual, &|s| map.get(&s).copied(), &mut HashMap::default());
            if dae.arena.vars(residual).len() > 2 {
                continue;
            }
            let vars = dae.arena.vars(residual);
            let unknown: Vec<ScalarId> = vars
                .iter()
                .copied()
                .filter(|&s| {
                    !matches!(
                        dae.scalar(s).kind,
                        ScalarKind::Parameter | ScalarKind::Constant
                    )
                })
                .collect();
            if has_time_or_events(dae, residual) {
                continue;
            }
            match unknown.as_slice() {
                [a] if eliminable(dae, *a) && !reinit_targets.contains(a) => {
                    if let Some((value, _)) = solve_linear(&mut dae.arena, residual, *a) {
                        eliminate(dae, &mut map, &mut members, *a, value, None);
                        *kept = false;
                        stats.constants += 1;
                    }
                }
                [a, b] => {
                    let (a, b) = (*a, *b);
                    let (elim, rep) = if rank(dae, a) >= rank(dae, b) {
                        (b, a)
                    } else {
                        (a, b)
                    };
                    if !eliminable(dae, elim) || reinit_targets.contains(&elim) {
                        continue;
                    }
                    let Some((value, _)) = solve_linear(&mut dae.arena, residual, elim) else {
                        continue;
                    };
                    let rep_var = dae.arena.var(rep);
                    let is_alias = value == rep_var
                        || matches!(dae.arena.node(value), Node::Neg(x) if x == rep_var);
                    if is_alias {
                        eliminate(dae, &mut map, &mut members, elim, value, Some(rep));
                        *kept = false;
                        stats.aliases += 1;
                        inherit_start(dae, elim, rep, value == rep_var);
                    }
                }
                _ => {}
            }
        }
        if stats == before {
            break;
        }
    }
    if map.is_empty() {
        return stats;
    }
    resolve_chains(dae, &mut map);
    for (&s, &v) in &map {
        dae.scalars[s.index()].alias = Some(v);
    }
    let mut k = 0;
    dae.equations.retain(|_| {
        k += 1;
        keep[k - 1]
    });
    substitute_aliases(dae, &map);
    stats
}

/// The states some `reinit` assigns: they are never eliminated.
fn reinit_targets(dae: &Dae) -> rustc_hash::FxHashSet<ScalarId> {
    let mut reinit_targets = rustc_hash::FxHashSet::default();
    for w in &dae.whens {
        for b in &w.branches {
            for (a, _) in &b.actions {
                if let WhenAction::Reinit { state, .. } = a {
                    reinit_targets.insert(*state);
                }
            }
        }
    }
    reinit_targets
}

/// The start value the representative `rep` takes over from the eliminated `elim`
/// (`elim = rep` when `same_sign`, else `elim = -rep`), and its `stateSelect` when that
/// is stronger.
fn inherit_start(dae: &mut Dae, elim: ScalarId, rep: ScalarId, same_sign: bool) {
    // A fixed start of the alias fixes the representative (unless
    // it is fixed itself); otherwise the representative inherits a
    // start value it lacks.
    let elim_fixed = dae.scalar(elim).fixed == Some(true);
    let rep_fixed = dae.scalar(rep).fixed == Some(true);
    if let (true, false, Some(st)) = (elim_fixed, rep_fixed, dae.scalar(elim).start) {
        let st = if same_sign { st } else { dae.arena.neg(st) };
        dae.scalars[rep.index()].start = Some(st);
        dae.scalars[rep.index()].fixed = Some(true);
    } else if dae.scalar(rep).start.is_none() {
        if let Some(st) = dae.scalar(elim).start {
            let st = if same_sign { st } else { dae.arena.neg(st) };
            dae.scalars[rep.index()].start = Some(st);
        }
    }
    // The alias set's strongest `stateSelect`: MSL's `Parts.RollingWheel` declares its
    // `angles` `always` and equates them with its joint's, declared `avoid`.
    let select = dae.scalar(elim).state_select;
    if select > dae.scalar(rep).state_select {
        dae.scalars[rep.index()].state_select = select;
    }
}

/// Resolves chains (x -> y where y was eliminated later).
fn resolve_chains(dae: &mut Dae, map: &mut HashMap<ScalarId, ExprId>) {
    let keys: Vec<ScalarId> = {
        let mut k: Vec<_> = map.keys().copied().collect();
        k.sort();
        k
    };
    for _ in 0..keys.len() {
        let mut changed = false;
        for &s in &keys {
            let v = map[&s];
            let nv = dae.arena.substitute(
                v,
                &|x| if x != s { map.get(&x).copied() } else { None },
                &mut HashMap::default(),
            );
            if nv != v {
                map.insert(s, nv);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}

/// Rewrites the equations, initial equations, `when` clauses, assertions and external
/// sites' arguments with the eliminated scalars replaced by their values.
fn substitute_aliases(dae: &mut Dae, map: &HashMap<ScalarId, ExprId>) {
    let mut memo = HashMap::default();
    let lookup = |s: ScalarId| map.get(&s).copied();
    for e in dae
        .equations
        .iter_mut()
        .chain(dae.initial_equations.iter_mut())
    {
        e.lhs = dae.arena.substitute(e.lhs, &lookup, &mut memo);
        e.rhs = dae.arena.substitute(e.rhs, &lookup, &mut memo);
    }
    for w in &mut dae.whens {
        for b in &mut w.branches {
            for c in &mut b.conditions {
                *c = dae.arena.substitute(*c, &lookup, &mut memo);
            }
            for (a, _) in &mut b.actions {
                match a {
                    WhenAction::Assign { value, .. } | WhenAction::Reinit { value, .. } => {
                        *value = dae.arena.substitute(*value, &lookup, &mut memo)
                    }
                    WhenAction::Assert { condition, .. } => {
                        *condition = dae.arena.substitute(*condition, &lookup, &mut memo)
                    }
                    WhenAction::Terminate { .. } => {}
                }
            }
        }
    }
    for a in &mut dae.assertions {
        a.condition = dae.arena.substitute(a.condition, &lookup, &mut memo);
    }
    for i in &mut dae.invariants {
        i.value = dae.arena.substitute(i.value, &lookup, &mut memo);
        i.active = dae.arena.substitute(i.active, &lookup, &mut memo);
    }
    for k in 0..dae.collision.len() {
        let args = dae.collision[k].args;
        dae.collision[k].args = args.map(|x| dae.arena.substitute(x, &lookup, &mut memo));
    }
    if let Some(w) = dae.collision_world.as_mut() {
        w.args = w.args.map(|x| dae.arena.substitute(x, &lookup, &mut memo));
    }
    for d in &mut dae.delays {
        d.input = dae.arena.substitute(d.input, &lookup, &mut memo);
    }
}

/// Records `elim = value` and rewrites the scalars that were mapped onto `elim`.
fn eliminate(
    dae: &mut Dae,
    map: &mut HashMap<ScalarId, ExprId>,
    members: &mut HashMap<ScalarId, Vec<ScalarId>>,
    elim: ScalarId,
    value: ExprId,
    rep: Option<ScalarId>,
) {
    map.insert(elim, value);
    let moved = members.remove(&elim).unwrap_or_default();
    for &m in &moved {
        let old = map[&m];
        let new = dae.arena.substitute(
            old,
            &|s| if s == elim { Some(value) } else { None },
            &mut HashMap::default(),
        );
        map.insert(m, new);
    }
    if let Some(rep) = rep {
        let list = members.entry(rep).or_default();
        list.extend(moved);
        list.push(elim);
    }
}

/// Equations with `time`, `pre`, `initial()` or relations are not aliases.
fn has_time_or_events(dae: &Dae, e: ExprId) -> bool {
    let mut stack = vec![e];
    let mut seen = rustc_hash::FxHashSet::default();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        match dae.arena.node(x) {
            crate::run_time_leaf!() | Node::Rel(..) | Node::Sample(..) | Node::If(..) => {
                return true
            }
            _ => stack.extend(dae.arena.children(x)),
        }
    }
    false
}
