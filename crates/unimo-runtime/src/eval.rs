//! Evaluating the compiled plan: explicit steps in order, Newton on each block (the
//! solve crate's, on the block's residual and symbolic Jacobian tapes).

use crate::exec::{Instance, Run};
use crate::native::RhsCall;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use unimo_solve::newton::{self, NewtonProblem, NewtonTolerance, NewtonWork};

use crate::exec::EventState;
use crate::modes::newton;
use unimo_codegen::model::{CompiledBlock, CompiledModel, CompiledStep};

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
    if work.profile.is_some() {
        return eval_steps_timed(m, r, ev, work);
    }
    for s in &m.steps {
        match s {
            CompiledStep::Explicit(t) => t.run(r, ev),
            CompiledStep::Block(b) => newton(b, r, ev, work)?,
        }
    }
    Ok(())
}

/// [`eval_steps`] timing each step into the workspace's profile.
fn eval_steps_timed(
    m: &CompiledModel,
    r: &mut [f64],
    ev: &mut EventState,
    work: &mut Workspace,
) -> Result<(), BlockFailure> {
    for (k, s) in m.steps.iter().enumerate() {
        let started = Instant::now();
        let outcome = match s {
            CompiledStep::Explicit(t) => {
                t.run(r, ev);
                Ok(())
            }
            CompiledStep::Block(b) => newton(b, r, ev, work),
        };
        if let Some(p) = work.profile.as_mut() {
            p.add(k, started.elapsed());
        }
        outcome?;
    }
    Ok(())
}

/// The time spent in each plan step, kept while profiling (`unimo simulate --cost`):
/// summed locally without locks and added to the shared `sink` when the simulation's
/// workspace is dropped.
#[derive(Debug)]
pub struct StepProfile {
    local: Vec<Duration>,
    sink: Arc<Mutex<Vec<Duration>>>,
}

impl StepProfile {
    pub fn new(sink: Arc<Mutex<Vec<Duration>>>) -> StepProfile {
        StepProfile {
            local: Vec::new(),
            sink,
        }
    }

    fn add(&mut self, step: usize, d: Duration) {
        if self.local.len() <= step {
            self.local.resize(step + 1, Duration::ZERO);
        }
        self.local[step] += d;
    }
}

impl Drop for StepProfile {
    fn drop(&mut self) {
        // A poisoned lock (a panicking reader) loses the profile, nothing else.
        if let Ok(mut sink) = self.sink.lock() {
            if sink.len() < self.local.len() {
                sink.resize(self.local.len(), Duration::ZERO);
            }
            for (total, d) in sink.iter_mut().zip(&self.local) {
                *total += *d;
            }
        }
    }
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

/// Scratch memory for Newton (allocated once per simulation) and the tolerances its
/// solutions are accepted with.
#[derive(Default, Debug)]
pub struct Workspace {
    pub(crate) relations: Vec<f64>,
    /// A block's iteration variables.
    pub(crate) x: Vec<f64>,
    /// Their values before the solve (restored when it fails).
    pub(crate) start: Vec<f64>,
    pub(crate) newton: NewtonWork,
    /// Time per plan step, when profiling.
    pub profile: Option<StepProfile>,
    /// The simulation's tolerances (the solver's defaults until a run sets them).
    pub tolerance: NewtonTolerance,
}

/// Newton on a block with its relations frozen: the solve crate's damped Newton
/// (`unimo_solve::newton`, converged at rounding, accepted within the simulation's
/// tolerances) on the block's residual and Jacobian tapes.
pub(crate) fn newton_smooth(
    b: &CompiledBlock,
    r: &mut [f64],
    ev: &mut EventState,
    w: &mut Workspace,
) -> Result<(), BlockFailure> {
    w.x.clear();
    w.x.extend(b.iteration.iter().map(|&g| r[g as usize]));
    w.start.clear();
    w.start.extend_from_slice(&w.x);
    let mut problem = BlockProblem { b, r, ev };
    match newton::solve(&mut problem, &mut w.x, &w.tolerance, &mut w.newton) {
        Ok(_) => Ok(()),
        Err(e) => Err({
            // The failed iterate (NaN, or far off) must not be the next solve's start:
            // the integrator retries with a smaller step from the registers.
            for (k, &g) in b.iteration.iter().enumerate() {
                r[g as usize] = w.start[k];
            }
            // A singular Jacobian whose equations are consistent (a statically
            // indeterminate loop) has solutions: one of them.
            if matches!(e, newton::NewtonError::Singular { .. })
                && crate::modes::solve_indeterminate(b, r, ev, w)
            {
                return Ok(());
            }
            BlockFailure {
                variables: b.names.clone(),
                residual: e.residual(),
                reason: e.reason(),
            }
        }),
    }
}

/// A block's equations as a Newton problem on the registers: the iteration variables
/// are written into their registers, the residual tape computes the torn variables and
/// the residuals, the Jacobian tape the symbolic Jacobian at the same point.
pub(crate) struct BlockProblem<'a> {
    pub(crate) b: &'a CompiledBlock,
    pub(crate) r: &'a mut [f64],
    pub(crate) ev: &'a mut EventState,
}

impl NewtonProblem for BlockProblem<'_> {
    fn size(&self) -> usize {
        self.b.iteration.len()
    }

    fn is_linear(&self) -> bool {
        self.b.linear
    }

    fn residual(&mut self, x: &[f64], f: &mut [f64]) {
        for (k, &g) in self.b.iteration.iter().enumerate() {
            self.r[g as usize] = x[k];
        }
        self.b.residual_tape.run(self.r, self.ev);
        for (k, &g) in self.b.residuals.iter().enumerate() {
            f[k] = self.r[g as usize];
        }
    }

    fn jacobian(&mut self, j: &mut [f64]) {
        self.b.jacobian_tape.run(self.r, self.ev);
        for (k, &g) in self.b.jacobian.iter().enumerate() {
            j[k] = self.r[g as usize];
        }
    }
}

/// The largest absolute residual of a block (its residual tape must have run).
pub(crate) fn residual_norm(b: &CompiledBlock, r: &[f64]) -> f64 {
    b.residuals
        .iter()
        .map(|&g| r[g as usize].abs())
        .fold(0.0, f64::max)
}

/// Evaluates a compiled model's right-hand side outside a simulation (benchmarks,
/// tests): parameters and start values are set once, then `rhs` runs the plan.
pub struct RhsEvaluator<'m> {
    model: &'m CompiledModel,
    /// Boxed: its length cannot change after `new` checked the native code fits it.
    registers: Box<[f64]>,
    events: EventState,
    work: Workspace,
    /// The model's whole right-hand side as one native call, if it has one.
    native: Option<RhsCall<'m>>,
}

impl<'m> RhsEvaluator<'m> {
    pub fn new(model: &'m CompiledModel) -> RhsEvaluator<'m> {
        let mut registers = model.new_registers();
        let mut events = model.new_event_state();
        // A table that cannot be built leaves its lookups NaN (the simulator reports it).
        let _ = model.run_parameters(&mut registers, &mut events);
        model.starts.run(&mut registers, &mut events);
        let registers = registers.into_boxed_slice();
        let native = RhsCall::new(model).filter(|c| c.fits(&registers, &events));
        RhsEvaluator {
            model,
            registers,
            events,
            work: Workspace::default(),
            native,
        }
    }

    /// The state derivatives at `(t, x)`.
    #[inline]
    pub fn rhs(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), BlockFailure> {
        if let Some(native) = &self.native {
            // SAFETY: `new` checked that the code fits this register file, whose length
            // a boxed slice keeps, and this event state, whose relation vector nothing
            // resizes (the plan's instructions and native code write its values only).
            let done =
                unsafe { native.call_fitted(t, x, out, &mut self.registers, &mut self.events) };
            if done {
                return Ok(());
            }
        }
        self.rhs_by_plan(t, x, out)
    }

    /// [`RhsEvaluator::rhs`] by running the plan.
    #[inline(never)]
    fn rhs_by_plan(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), BlockFailure> {
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
