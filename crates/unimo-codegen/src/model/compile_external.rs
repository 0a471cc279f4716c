//! Compiling what lies outside the plan's equations: external objects' constructor
//! arguments, the collision world's arguments, and the symbolic Jacobian of the states'
//! derivatives.

use super::{CollisionBodyRegs, CollisionModel};
use super::{ObjectSite, SymbolicJacobian};
use crate::tape::{Compiler, Reg, Tape};
use rustc_hash::FxHashMap as HashMap;
use unimo_dae::dae::{Dae, ScalarKind};
use unimo_dae::expr::{ExprId, Node, ScalarId};
use unimo_dae::plan::{Plan, PlanStep};

pub(super) fn compile_objects(dae: &Dae, c: &mut Compiler<'_>) -> (Tape, Vec<ObjectSite>) {
    let mut tape = Tape::default();
    let mut memo = HashMap::default();
    let sites = dae
        .external_objects
        .iter()
        .map(|o| {
            let mut regs = |es: &[ExprId], tape: &mut Tape| -> Vec<Reg> {
                es.iter().map(|&e| c.expr(e, tape, &mut memo)).collect()
            };
            let table = regs(&o.table, &mut tape);
            let columns = regs(&o.columns, &mut tape);
            let s = regs(
                &[
                    o.smoothness,
                    o.extrapolation,
                    o.start_time,
                    o.shift_time,
                    o.time_events,
                ],
                &mut tape,
            );
            ObjectSite {
                kind: o.kind,
                table,
                rows: o.rows,
                cols: o.cols,
                columns,
                settings: [s[0], s[1], s[2], s[3], s[4]],
            }
        })
        .collect();
    (tape, sites)
}

/// d der(x_i) / d x_j symbolically, when every step of the plan is an explicit
/// assignment: the assignments are substituted into the derivatives (shared through the
/// hash-consed arena) and differentiated with respect to each state they mention.
pub(super) fn symbolic_jacobian(
    dae: &Dae,
    plan: &Plan,
    c: &mut Compiler<'_>,
) -> Option<SymbolicJacobian> {
    const MAX_NONZEROS: usize = 200_000;
    if plan.states.is_empty() || plan.steps.iter().any(|s| matches!(s, PlanStep::Block(_))) {
        return None;
    }
    // The arena is shared with the compiler; differentiate on a copy.
    let mut arena = dae.arena.clone();
    let mut full: HashMap<ScalarId, ExprId> = HashMap::default();
    for step in &plan.steps {
        if let PlanStep::Assign { var, value, .. } = step {
            let v = arena.substitute(*value, &|s| full.get(&s).copied(), &mut HashMap::default());
            full.insert(*var, v);
        }
    }
    let column: HashMap<ScalarId, usize> = plan
        .states
        .iter()
        .enumerate()
        .map(|(j, &s)| (s, j))
        .collect();
    let mut entries = Vec::new();
    for (i, d) in plan.derivatives.iter().enumerate() {
        let e = full.get(d).copied().unwrap_or_else(|| arena.var(*d));
        for s in arena.vars(e) {
            let Some(&j) = column.get(&s) else { continue };
            let p = unimo_dae::diff::partial(&mut arena, e, s);
            if arena.as_const(p) != Some(0.0) {
                entries.push((i, j, p));
            }
            if entries.len() > MAX_NONZEROS {
                return None;
            }
        }
    }
    let mut compiler = Compiler::new(&arena, c.layout, c.relation_index, c.sample_index);
    compiler.held_index = c.held_index;
    compiler.continue_from(c);
    let mut tape = Tape::default();
    let mut memo = HashMap::default();
    let regs = entries
        .into_iter()
        .map(|(i, j, p)| (i, j, compiler.expr(p, &mut tape, &mut memo)))
        .collect();
    c.continue_from(&compiler);
    Some((tape, regs))
}

/// The collision world: argument tape, registers, and the arguments that a world
/// evaluated before the plan cannot read.
pub(super) fn compile_collision(
    dae: &Dae,
    plan: &Plan,
    c: &mut Compiler<'_>,
    body_outputs: Vec<[Reg; 6]>,
    gaps: [Reg; 2],
) -> Option<CollisionModel> {
    if dae.collision.is_empty() && dae.collision_world.is_none() {
        return None;
    }
    let layout = c.layout;
    let states: std::collections::HashSet<ScalarId> = plan.states.iter().copied().collect();
    let mut inputs = Tape::default();
    let mut memo = HashMap::default();
    let mut problems = Vec::new();
    let check = |e: ExprId, problems: &mut Vec<String>| {
        for s in dae.arena.vars(e) {
            let sc = dae.scalar(s);
            let ok = match sc.kind {
                ScalarKind::Parameter | ScalarKind::Constant | ScalarKind::Discrete => true,
                ScalarKind::Continuous => states.contains(&s),
                ScalarKind::Derivative => false,
            };
            if !ok && !problems.contains(&dae.name(s)) {
                problems.push(dae.name(s));
            }
        }
    };
    let mut bodies = Vec::new();
    for (k, site) in dae.collision.iter().enumerate() {
        let args = site.args.map(|e| {
            check(e, &mut problems);
            c.expr(e, &mut inputs, &mut memo)
        });
        let state_reg = |e: ExprId| match dae.arena.node(e) {
            Node::Var(s) if states.contains(&s) => Some(layout.var(s)),
            _ => None,
        };
        let (v, w) = (site.args.velocity, site.args.angular_velocity);
        let velocity_states = v
            .iter()
            .chain(&w)
            .map(|&e| state_reg(e))
            .collect::<Option<Vec<Reg>>>()
            .map(|v| std::array::from_fn(|i| v[i]));
        // Name the body by the position variable it reads, else by its number.
        let name = dae
            .arena
            .vars(site.args.position[0])
            .first()
            .map(|&s| {
                let n = dae.name(s);
                n.rsplit_once('.').map(|(p, _)| p.to_string()).unwrap_or(n)
            })
            .unwrap_or_else(|| format!("collision body {}", k + 1));
        bodies.push(CollisionBodyRegs {
            args,
            outputs: body_outputs[k],
            velocity_states,
            name,
        });
    }
    let world_args = match &dae.collision_world {
        Some(w) => w.args.map(|e| c.expr(e, &mut inputs, &mut memo)),
        None => {
            problems.push("(no Unimo.Collision.CollisionWorld: collision bodies need one)".into());
            unimo_dae::collision_args::CollisionWorldArgs {
                margin: layout.time,
                tolerance: layout.time,
                broadphase: layout.time,
                sweep: layout.time,
            }
        }
    };
    Some(CollisionModel {
        inputs,
        bodies,
        world_args,
        gaps,
        problems,
    })
}
