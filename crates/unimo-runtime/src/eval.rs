//! Evaluating the compiled plan: explicit steps in order, Newton on each block with its
//! symbolic Jacobian and a small dense LU.

use crate::model::{CompiledBlock, CompiledModel, CompiledStep};
use crate::tape::EventState;

/// Iterations of Newton's method on a block before it fails.
const MAX_NEWTON_ITERATIONS: usize = 50;

/// Rounds of "solve with the relations frozen, then decide them again" for a block
/// whose equations hold relations, at an event.
const MAX_MODE_ROUNDS: usize = 16;

/// Most relations of one block whose combinations are searched when its rounds cycle
/// (2^8 = 256 solves at most).
const MAX_SEARCHED_RELATIONS: usize = 8;

/// A block whose Newton iteration did not converge.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockFailure {
    pub variables: Vec<String>,
    pub residual: f64,
    pub reason: String,
}

/// Runs every step of the plan: afterwards all unknowns are consistent with the states.
pub fn eval_steps(
    m: &CompiledModel,
    r: &mut [f64],
    ev: &mut EventState,
    work: &mut Workspace,
) -> Result<(), BlockFailure> {
    collide(m, r, ev)?;
    for s in &m.steps {
        match s {
            CompiledStep::Explicit(t) => t.run(r, ev),
            CompiledStep::Block(b) => newton(b, r, ev, work)?,
        }
    }
    Ok(())
}

/// Runs every step of the plan like [`eval_steps`] but goes on past a block that fails
/// (its variables keep their last iterate) and returns the first failure. For the
/// iterates of initialization, where a block that the initial equations do not need may
/// be singular at the start values (e.g. a multiplier that starts at 0).
pub fn eval_steps_lenient(
    m: &CompiledModel,
    r: &mut [f64],
    ev: &mut EventState,
    work: &mut Workspace,
) -> Option<BlockFailure> {
    let mut first = collide(m, r, ev).err();
    for s in &m.steps {
        match s {
            CompiledStep::Explicit(t) => t.run(r, ev),
            CompiledStep::Block(b) => {
                if let Err(f) = newton(b, r, ev, work) {
                    first.get_or_insert(f);
                }
            }
        }
    }
    first
}

/// Evaluates the collision world (before the plan, which reads its outputs).
fn collide(m: &CompiledModel, r: &mut [f64], ev: &mut EventState) -> Result<(), BlockFailure> {
    let Some(cm) = &m.collision else {
        return Ok(());
    };
    cm.inputs.run(r, ev);
    let mut st = ev.collision.take().unwrap_or_default();
    let res = st.evaluate(cm, r, ev.event_mode);
    ev.collision = Some(st);
    res.map_err(|f| BlockFailure {
        variables: vec![f.body],
        residual: f64::NAN,
        reason: f.reason,
    })
}

/// Scratch memory for Newton (allocated once per simulation).
#[derive(Default, Debug)]
pub struct Workspace {
    relations: Vec<f64>,
    matrix: Vec<f64>,
    rhs: Vec<f64>,
    perm: Vec<usize>,
    /// The iterate before a Newton step (for the line search).
    saved: Vec<f64>,
}

/// Solves a block. Outside events its relations are frozen (they change only at
/// located crossings), so Newton sees a smooth residual. At an event the relations of
/// the block are decided as for the whole model's event iteration: Newton solves with
/// them frozen at their current outcome, then they are evaluated at the solution; when
/// one changed (a `Real` state indicator inside the loop switched its branch), the
/// block is solved again with the new outcomes, until they agree with the solution.
/// Newton never sees a residual that jumps between its iterates.
fn newton(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
) -> Result<(), BlockFailure> {
    if !ev.event_mode || !b.has_relations {
        return newton_smooth(b, r, ev, w);
    }
    // Decide the relations at the current iterate (the previous mode), then iterate.
    b.residual_tape.run(r, ev);
    let start: Vec<f64> = b.iteration.iter().map(|&g| r[g as usize]).collect();
    let mut switched = vec![false; ev.relations.len()];
    for _ in 0..MAX_MODE_ROUNDS {
        w.relations.clear();
        w.relations.extend_from_slice(&ev.relations);
        ev.event_mode = false;
        let solved = newton_smooth(b, r, ev, w);
        ev.event_mode = true;
        solved?;
        b.residual_tape.run(r, ev);
        if w.relations == ev.relations {
            return Ok(());
        }
        // Outcomes that changed without changing the solution (a relation on a quantity
        // that is exactly 0 in the active branch and flips with rounding): consistent.
        let norm = residual_norm(b, r);
        if norm <= 1e-10 {
            return Ok(());
        }
        for (k, s) in switched.iter_mut().enumerate() {
            *s |= w.relations[k] != ev.relations[k];
        }
    }
    // The rounds cycle (friction: stuck implies sliding and sliding implies stuck,
    // starting from the previous mode). Search: the outcomes that kept switching are
    // frozen in every combination, fewest true first, until one agrees with its own
    // solution (the combinatorial mixed-system search of Modelica tools).
    let flips: Vec<usize> = (0..switched.len()).filter(|&k| switched[k]).collect();
    if !flips.is_empty() && flips.len() <= MAX_SEARCHED_RELATIONS {
        let base = ev.relations.clone();
        let mut masks: Vec<u32> = (0..1u32 << flips.len()).collect();
        masks.sort_by_key(|m| m.count_ones());
        for mask in masks {
            let mut frozen = base.clone();
            for (i, &z) in flips.iter().enumerate() {
                frozen[z] = f64::from(mask >> i & 1 == 1);
            }
            ev.relations.copy_from_slice(&frozen);
            for (k, &g) in b.iteration.iter().enumerate() {
                r[g as usize] = start[k];
            }
            ev.event_mode = false;
            let solved = newton_smooth(b, r, ev, w);
            ev.event_mode = true;
            if solved.is_err() {
                continue;
            }
            b.residual_tape.run(r, ev);
            if flips.iter().all(|&z| ev.relations[z] == frozen[z]) {
                return Ok(());
            }
        }
        w.relations.clear();
        w.relations.extend_from_slice(&base);
    }
    let flipping: Vec<String> = (0..ev.relations.len())
        .filter(|&k| w.relations[k] != ev.relations[k])
        .map(|k| format!("z{k}"))
        .collect();
    let norm = residual_norm(b, r);
    Err(BlockFailure {
        variables: b.names.clone(),
        residual: norm,
        reason: format!(
            "the conditions inside the loop did not settle in {MAX_MODE_ROUNDS} rounds \
             (no branch choice is consistent with its own solution; still switching: {})",
            flipping.join(", ")
        ),
    })
}

fn newton_smooth(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
) -> Result<(), BlockFailure> {
    let n = b.iteration.len();
    w.matrix.resize(n * n, 0.0);
    w.rhs.resize(n, 0.0);
    w.perm.resize(n, 0);
    let fail = |reason: &str, res: f64| BlockFailure {
        variables: b.names.clone(),
        residual: res,
        reason: reason.to_owned(),
    };
    let mut last_norm = f64::INFINITY;
    // Whether the residual tape already ran at the current iterate (the line search's
    // last trial).
    let mut evaluated = false;
    for it in 0..MAX_NEWTON_ITERATIONS {
        if !evaluated {
            b.residual_tape.run(r, ev);
        }
        let mut norm = 0.0f64;
        for (k, &reg) in b.residuals.iter().enumerate() {
            let f = r[reg as usize];
            w.rhs[k] = -f;
            norm = norm.max(f.abs());
        }
        if !norm.is_finite() {
            return Err(fail("the residual is not finite", norm));
        }
        if norm == 0.0 {
            return Ok(());
        }
        b.jacobian_tape.run(r, ev);
        for (k, &reg) in b.jacobian.iter().enumerate() {
            w.matrix[k] = r[reg as usize];
        }
        if !lu_solve(n, &mut w.matrix, &mut w.rhs, &mut w.perm) {
            return Err(fail("the block's Jacobian is singular", norm));
        }
        let lambda = line_search(b, r, ev, w, norm);
        evaluated = lambda.is_some();
        let lambda = lambda.unwrap_or(1.0);
        let mut converged = true;
        for (k, &reg) in b.iteration.iter().enumerate() {
            let x = w.saved[k];
            let dx = lambda * w.rhs[k];
            r[reg as usize] = x + dx;
            if dx.abs() > 1e-13 * (1.0 + x.abs()) {
                converged = false;
            }
        }
        if b.linear && it >= 1 && norm >= last_norm {
            // A linear block is solved by the first step; more is rounding.
            b.residual_tape.run(r, ev);
            return Ok(());
        }
        if converged {
            // Bring the inner (torn) variables up to date with the final iterate.
            b.residual_tape.run(r, ev);
            return Ok(());
        }
        last_norm = norm;
    }
    b.residual_tape.run(r, ev);
    let norm = residual_norm(b, r);
    if norm <= 1e-10 {
        return Ok(());
    }
    Err(fail(
        "Newton's method did not converge in 50 iterations",
        norm,
    ))
}

/// Damped Newton (Armijo backtracking): the step `w.rhs` from the iterate is halved
/// until the residual's largest component decreases, so that a residual with kinks and
/// saturations (a limited op-amp: slope 1e4 in a band 1e-3 wide, 0 outside) does not
/// send the iterates back and forth between its flat parts. Returns the step length
/// taken with the residual tape run at the new iterate, or `None` for a full step
/// left to the caller (linear blocks, iterates already at rounding level, and
/// directions along which the residual does not decrease at all).
fn line_search(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
    norm: f64,
) -> Option<f64> {
    w.saved.clear();
    w.saved
        .extend(b.iteration.iter().map(|&reg| r[reg as usize]));
    if b.linear || norm <= 1e-10 {
        return None;
    }
    let mut lambda = 1.0;
    loop {
        for (k, &reg) in b.iteration.iter().enumerate() {
            r[reg as usize] = w.saved[k] + lambda * w.rhs[k];
        }
        b.residual_tape.run(r, ev);
        let trial = residual_norm(b, r);
        if trial.is_finite() && trial <= (1.0 - 1e-4 * lambda) * norm {
            return Some(lambda);
        }
        lambda *= 0.5;
        if lambda < 1e-6 {
            // No decrease along the Newton direction (a flat part, or a loop with
            // several solutions such as a Schmitt trigger): the full step, as plain
            // Newton takes it.
            return None;
        }
    }
}

/// The largest absolute residual of a block (its residual tape must have run).
fn residual_norm(b: &CompiledBlock, r: &[f64]) -> f64 {
    b.residuals
        .iter()
        .map(|&g| r[g as usize].abs())
        .fold(0.0, f64::max)
}

/// Solves `a x = b` in place (LU with partial pivoting); false when singular.
pub fn lu_solve(n: usize, a: &mut [f64], b: &mut [f64], perm: &mut [usize]) -> bool {
    for (i, p) in perm.iter_mut().enumerate().take(n) {
        *p = i;
    }
    for k in 0..n {
        let mut piv = k;
        let mut best = a[k * n + k].abs();
        for i in k + 1..n {
            let v = a[i * n + k].abs();
            if v > best {
                best = v;
                piv = i;
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if piv != k {
            for j in 0..n {
                a.swap(k * n + j, piv * n + j);
            }
            b.swap(k, piv);
            perm.swap(k, piv);
        }
        let d = a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] / d;
            if f != 0.0 {
                a[i * n + k] = f;
                for j in k + 1..n {
                    a[i * n + j] -= f * a[k * n + j];
                }
                b[i] -= f * b[k];
            }
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s -= a[k * n + j] * b[j];
        }
        b[k] = s / a[k * n + k];
    }
    true
}

/// Evaluates a compiled model's right-hand side outside a simulation (benchmarks,
/// tests): parameters and start values are set once, then `rhs` runs the plan.
pub struct RhsEvaluator<'m> {
    model: &'m CompiledModel,
    registers: Vec<f64>,
    events: EventState,
    work: Workspace,
}

impl<'m> RhsEvaluator<'m> {
    pub fn new(model: &'m CompiledModel) -> RhsEvaluator<'m> {
        let mut registers = model.new_registers();
        let mut events = model.new_event_state();
        // A table that cannot be built leaves its lookups NaN (the simulator reports it).
        let _ = model.run_parameters(&mut registers, &mut events);
        model.starts.run(&mut registers, &mut events);
        RhsEvaluator {
            model,
            registers,
            events,
            work: Workspace::default(),
        }
    }

    /// The state derivatives at `(t, x)`.
    pub fn rhs(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), BlockFailure> {
        let m = self.model;
        self.registers[m.layout.time as usize] = t;
        for (k, &r) in m.states.iter().enumerate() {
            self.registers[r as usize] = x[k];
        }
        eval_steps(m, &mut self.registers, &mut self.events, &mut self.work)?;
        for (k, &r) in m.derivatives.iter().enumerate() {
            out[k] = self.registers[r as usize];
        }
        Ok(())
    }

    /// The names of the states, in the order `rhs` takes them.
    pub fn state_names(&self) -> &[String] {
        &self.model.state_names
    }
}
