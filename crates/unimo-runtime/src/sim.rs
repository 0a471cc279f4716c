//! The simulation driver: initialization, integration with one of our solvers, output
//! on a grid, and Modelica event semantics (zero crossings located on the dense
//! output, event iteration with `pre` values, `reinit` at the end of the event step,
//! sample time events, restart after each event).

use crate::eval::{eval_steps, BlockFailure, Workspace};
use crate::exec::EventState;
use crate::exec::{Instance, Run};
use crate::native::RhsCall;
use starts::LoopStarts;
use std::time::Instant;
use unimo_codegen::model::CompiledModel;
use unimo_dae::expr::RelOp;
use unimo_solve::dense::{abs_det, pick_columns};
use unimo_solve::{Direction, EvalError, Invariants, Method, Solver, System};

mod crossings;
mod delays;
mod events;
mod init;
mod pattern;
mod refine;
mod run;
mod starts;
pub mod stepper;
mod zeno;

/// Internal steps of one simulation before it is stopped.
const MAX_STEPS: u64 = 20_000_000;
/// Event iterations at one instant before the event is declared non-converging.
const MAX_EVENT_ITERATIONS: usize = 100;
/// Events closer than this (relative to the time scale) count towards chattering.
const CHATTER_WINDOW: f64 = 1e-9;
/// Consecutive close events that mean chattering (Zeno behaviour).
const CHATTER_COUNT: usize = 200;

#[derive(Clone, Debug)]
pub struct SimOptions {
    pub start: f64,
    pub stop: f64,
    pub rtol: f64,
    pub atol: f64,
    pub method: Method,
    /// Output grid spacing (points at start + k * interval), plus every event.
    pub interval: f64,
    /// Also write a row after every internal step.
    pub every_step: bool,
    /// Rows between the grid's points where a straight line between the written rows
    /// would miss a state by more than this fraction of its largest magnitude so far
    /// (`sim/refine.rs`); 0: the grid and the events only.
    pub output_rtol: f64,
}

/// The default [`SimOptions::output_rtol`]: what a plot or a linear interpolation of
/// the result resolves.
pub const OUTPUT_RTOL: f64 = 1e-3;

/// What a caller sets of a run (the command line's options); `None` leaves it to the
/// model's `experiment` annotation, then to the default ([`SimOptions::resolve`]).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub start: Option<f64>,
    pub stop: Option<f64>,
    pub rtol: Option<f64>,
    pub atol: Option<f64>,
    pub interval: Option<f64>,
    /// Output points over the run (an interval of `(stop - start) / points`).
    pub points: Option<usize>,
}

impl SimOptions {
    /// The settings of a run, in one place for every command: the override, else the
    /// `experiment` annotation (a method of `Auto`: its `__unimo_method`), else the
    /// default — StartTime 0, StopTime 1, Tolerance
    /// 1e-6, absolute tolerance rtol / 100, Interval (stop - start) / 500. A
    /// zero-length run writes the initial values only. Err: a message for the user
    /// (stop before start, tolerances or interval not positive).
    pub fn resolve(
        ex: &unimo_dae::dae::Experiment,
        o: &Overrides,
        method: Method,
        every_step: bool,
    ) -> Result<SimOptions, String> {
        let start = o.start.or(ex.start_time).unwrap_or(0.0);
        let stop = o.stop.or(ex.stop_time).unwrap_or(1.0);
        if !(stop - start).is_finite() || stop < start {
            return Err(format!(
                "the stop time {stop} is before the start time {start}"
            ));
        }
        // `Auto` (no method chosen by the caller) takes the model's
        // `__unimo_method`, which lowering checked to be one of its names.
        let method = match (method, ex.method.as_deref().and_then(Method::from_name)) {
            (Method::Auto, Some(asked)) => asked,
            (chosen, _) => chosen,
        };
        let rtol = o.rtol.or(ex.tolerance).unwrap_or(1e-6);
        let atol = o.atol.unwrap_or(rtol / 100.0);
        let interval = match (o.interval, o.points) {
            (Some(dt), _) => dt,
            (None, Some(n)) => (stop - start) / n.max(1) as f64,
            (None, None) => ex.interval.unwrap_or((stop - start) / 500.0),
        };
        // A zero-length interval writes the initial values only.
        let interval = if stop == start { 1.0 } else { interval };
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(interval) || !positive(rtol) || atol.is_nan() || atol < 0.0 {
            return Err("the interval and tolerances must be positive".into());
        }
        Ok(SimOptions {
            start,
            stop,
            rtol,
            atol,
            method,
            interval,
            every_step,
            output_rtol: OUTPUT_RTOL,
        })
    }
}

/// Why a simulation stopped early; its message is its `Display` (thiserror).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    #[error("initialization failed: {message} (variables: {})", .culprits.join(", "))]
    Init {
        message: String,
        culprits: Vec<String>,
    },
    #[error("the solver failed at t = {time}{}: {message}; worst variables: {}", step_note(.step), .culprits.join(", "))]
    Solver {
        time: f64,
        step: Option<f64>,
        message: String,
        culprits: Vec<String>,
    },
    #[error("an algebraic loop failed at t = {time}: {} (residual {:e}); its iteration variables: {}", .failure.reason, .failure.residual, .failure.variables.join(", "))]
    Block { time: f64, failure: BlockFailure },
    #[error("assertion failed at t = {time}: {message}")]
    Assert { time: f64, message: String },
    #[error("event iteration did not converge at t = {time} after {} iterations; still changing: {}", MAX_EVENT_ITERATIONS, .culprits.join(", "))]
    EventIteration { time: f64, culprits: Vec<String> },
    #[error("chattering at t = {time}: {events} events in a row {}", chatter_note(.crossing, .sliding))]
    Chattering {
        time: f64,
        crossing: String,
        events: usize,
        /// The events were a sliding mode (the flow drives the crossing function back
        /// across zero from both sides), not close in time.
        sliding: bool,
    },
    /// The events of a zero crossing accumulated below the rounding noise, and after
    /// the last one's reinit its function went on past zero instead of back (see
    /// `sim/zeno.rs`).
    #[error("Zeno point near t = {time}: the events of the zero crossing `{crossing}` accumulated until its function no longer left its rounding-noise band (relative {ROOT_NOISE:e}) between them, and after the last one's reinit it went on past zero instead of back ({events} events): the model's motion is lost here (a bouncing ball would fall through its floor); the model does not say what follows the accumulation, e.g. a resting or sticking state that ends it")]
    Zeno {
        time: f64,
        crossing: String,
        events: usize,
    },
    /// A result value became NaN or infinite.
    #[error("`{variable}` is {value} at t = {time}{}{}", step_note(.step), .equation.map(|e| format!(", computed by equation #{}", e.0)).unwrap_or_default())]
    NonFinite {
        time: f64,
        step: Option<f64>,
        variable: String,
        value: f64,
        /// The equation computing it (a state: its derivative's), for the caller to
        /// show with its source.
        equation: Option<unimo_dae::dae::EqId>,
    },
}

/// `, step size 1e-3` when the step size is known.
fn step_note(step: &Option<f64>) -> String {
    step.map(|h| format!(", step size {h:e}"))
        .unwrap_or_default()
}

/// How chattering events followed each other, and from which crossing.
fn chatter_note(crossing: &str, sliding: &bool) -> String {
    if *sliding {
        format!("where the flow drives the zero crossing `{crossing}` back across zero from both sides (a sliding mode)")
    } else {
        format!("less than {CHATTER_WINDOW:e} apart, from the zero crossing `{crossing}`")
    }
}

impl SimError {
    pub fn code(&self) -> &'static str {
        match self {
            SimError::Init { .. } => "E4001",
            SimError::Solver { .. } => "E4002",
            SimError::Block { .. } => "E4003",
            SimError::Assert { .. } => "E4004",
            SimError::EventIteration { .. } => "E4005",
            SimError::Chattering { .. } => "E4006",
            SimError::NonFinite { .. } => "E4007",
            SimError::Zeno { .. } => "E4008",
        }
    }

    /// The message (its `Display`).
    pub fn message(&self) -> String {
        self.to_string()
    }
}

/// One logged event.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRecord {
    pub time: f64,
    pub what: String,
}

/// Counters of a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimStats {
    pub solver: unimo_solve::Stats,
    pub events: usize,
    pub event_iterations: usize,
    pub rhs_evaluations: u64,
    /// The collision world's counters, when the model has one.
    pub collision: Option<crate::collision::CollisionStats>,
    /// Times a dynamically selected state set changed its states (after the start).
    pub state_selections: usize,
    /// Nonzeros of the Jacobian's sparsity pattern (symbolic or structural); `None`:
    /// no pattern, the Jacobian is dense (differences column by column).
    pub jacobian_nonzeros: Option<usize>,
    /// The implicit method factored its iteration matrices with the sparse LU.
    pub sparse_lu: bool,
    /// The LU of the implicit method's iteration matrices (`None`: an explicit method).
    pub linear_solver: Option<unimo_solve::LinearSolverKind>,
    /// The projection onto the model's invariants (`Unimo.invariant`), when it has any.
    pub projection: Option<unimo_solve::ProjectionStats>,
}

/// Seconds spent in each phase of a run (`unimo simulate --stats`). `integrate` is the
/// solver's steps (root search included); `evaluation` and `linear_algebra` are the
/// parts of `integrate` spent evaluating the plan (right-hand sides, Jacobians, root
/// functions) and factoring and solving the iteration matrices. `events` is the
/// handling of state, time and terminal events (event iteration, reinit, restart),
/// `output` the rows kept on the output grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunTimes {
    pub initialize: f64,
    pub integrate: f64,
    pub evaluation: f64,
    pub linear_algebra: f64,
    pub events: f64,
    pub output: f64,
}

/// Results computed so far (also after a failure).
#[derive(Clone, Debug, Default)]
pub struct SimResult {
    pub names: Vec<String>,
    pub times: Vec<f64>,
    pub rows: Vec<Vec<f64>>,
    pub events: Vec<EventRecord>,
    pub stats: SimStats,
    /// Wall time of the run's phases (apart from `stats`: counters compare equal
    /// between runs, times do not).
    pub phase_times: RunTimes,
    pub error: Option<SimError>,
    pub terminated: Option<String>,
    /// When the explicit method found the problem stiff (its step size limited by
    /// stability, not accuracy): an implicit method would take fewer steps.
    pub stiff_since: Option<f64>,
    /// Final state values (for references).
    pub final_states: Vec<f64>,
    /// Every scalar's value (indexed by `ScalarId`) right after initialization:
    /// parameters, also those initialization solved for, and start values. Empty
    /// when initialization failed.
    pub initial_values: Vec<f64>,
}

/// The ODE in the states that the solvers see.
struct Ode<'a> {
    m: &'a CompiledModel,
    regs: Vec<f64>,
    ev: EventState,
    work: Workspace,
    differential: Vec<bool>,
    evaluations: u64,
    /// Seconds spent evaluating the plan and the Jacobian's tape.
    eval_seconds: f64,
    last_failure: Option<BlockFailure>,
    /// Nonzeros of the symbolic Jacobian (large systems then use the sparse LU).
    pattern: Option<unimo_solve::SparsityPattern>,
    /// A model without states but with events gets one constant state, so that the
    /// solvers step through time and locate its crossings and sample instants.
    clock: bool,
    /// The relations disagreeing with their operands at the latest time the root
    /// functions were evaluated since the last event (see `crossings::disagreements`).
    last_roots: (f64, Crossed),
    /// Per root function: the earliest time since its last event at which it was
    /// outside twice its rounding-noise band (inside the band [`Ode::roots`] reports it
    /// as exactly zero): `+inf` if never, `-inf` before its first event (which is so
    /// never quiet; see `zeno`).
    left_noise: Vec<f64>,
    /// Per root function: after an event of it that happened inside its noise band and
    /// reinitialized a state, the side it crossed to (true: negative). Cleared when it
    /// leaves twice the band on the other side or fires again (see `zeno`).
    zeno_watch: Vec<Option<bool>>,
    /// A watched root function left twice its band on the side it had crossed to:
    /// (root, time). The run stops at a Zeno point (`SimError::Zeno`).
    zeno_hit: Option<(usize, f64)>,
    /// Where the nonlinear loops' Newton iterations start (see [`starts`]).
    loop_starts: LoopStarts,
    /// While a solver step runs (`Some`): the point the registers hold the plan's
    /// values of, if any. The solver asks for the right-hand side at the end of each
    /// step and then for the root functions at the same point: the second evaluation
    /// is skipped. Outside a step (`None`) the simulator writes the registers itself.
    evaluated_at: Option<Option<(f64, Vec<f64>)>>,
    /// The model's whole right-hand side as one native call, if it has one (not while
    /// the plan's steps are profiled).
    native: Option<RhsCall<'a>>,
    /// The last evaluation was a native right-hand side: the registers hold its time
    /// and states but not the plan's values there (see `RhsCall`), until the plan runs.
    plan_stale: bool,
}

impl Ode<'_> {
    /// Evaluates the plan at `t` with the loops started from the stored solution
    /// [`LoopStarts::choose`] picks; when that fails, once more from each fallback
    /// ([`LoopStarts::fallbacks`]) until one succeeds.
    fn eval_from_starts(&mut self, t: f64) -> Result<(), BlockFailure> {
        self.plan_stale = false;
        let start = self.loop_starts.choose(t);
        if let Some(s) = start {
            self.loop_starts.write(s, &mut self.regs);
        }
        let mut evaluated = eval_steps(self.m, &mut self.regs, &mut self.ev, &mut self.work);
        if evaluated.is_ok() {
            return evaluated;
        }
        for fallback in self.loop_starts.fallbacks(start) {
            self.loop_starts.write(fallback, &mut self.regs);
            evaluated = eval_steps(self.m, &mut self.regs, &mut self.ev, &mut self.work);
            if evaluated.is_ok() {
                break;
            }
        }
        evaluated
    }

    /// Runs the plan at the time and states in the registers when the last evaluation
    /// was a native right-hand side, so that the plan's values there can be read from
    /// the registers (as after the tape's right-hand side).
    fn refresh(&mut self) -> Result<(), BlockFailure> {
        if self.plan_stale {
            let t = self.regs[self.m.layout.time as usize];
            self.eval_from_starts(t)?;
        }
        Ok(())
    }

    /// Starts (`true`) or ends a solver step: see `evaluated_at`.
    fn within_step(&mut self, on: bool) {
        self.evaluated_at = on.then_some(None);
    }

    fn load(&mut self, t: f64, x: &[f64]) -> Result<(), EvalError> {
        if let Some(at) = self.evaluated_at.as_mut() {
            if at
                .as_ref()
                .is_some_and(|(t0, x0)| *t0 == t && x0[..] == x[..])
            {
                return Ok(());
            }
            *at = None;
        }
        self.load_anew(t, x)?;
        if let Some(at) = self.evaluated_at.as_mut() {
            *at = Some((t, x.to_vec()));
        }
        Ok(())
    }

    fn load_anew(&mut self, t: f64, x: &[f64]) -> Result<(), EvalError> {
        self.regs[self.m.layout.time as usize] = t;
        for (k, &reg) in self.m.states.iter().enumerate() {
            self.regs[reg as usize] = x[k];
        }
        self.evaluations += 1;
        let started = unimo_solve::fine_timing().then(Instant::now);
        let evaluated = self.eval_from_starts(t);
        if evaluated.is_ok() {
            self.loop_starts.note_latest(t, &self.regs);
        }
        self.eval_seconds += started.map_or(0.0, |s| s.elapsed().as_secs_f64());
        evaluated.map_err(|f| {
            let msg = format!("{} in the loop of {}", f.reason, f.variables.join(", "));
            self.last_failure = Some(f);
            EvalError::failed(msg)
        })
    }
}

impl System for Ode<'_> {
    /// The states, and the constant clock state of a model without states that has
    /// events (see `clock`).
    fn len(&self) -> usize {
        self.m.states.len() + usize::from(self.clock)
    }

    fn differential(&self) -> &[bool] {
        &self.differential
    }

    fn rhs(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let n = self.m.states.len();
        // The whole right-hand side in one native call (a plan of one explicit step).
        let started = unimo_solve::fine_timing().then(Instant::now);
        let native = match &self.native {
            // SAFETY: `fits` holds on these registers and this event state.
            Some(native) if native.fits(&self.regs, &self.ev) => unsafe {
                native.call_fitted(t, &x[..n], &mut out[..n], &mut self.regs, &mut self.ev)
            },
            _ => false,
        };
        if native {
            self.evaluations += 1;
            self.plan_stale = true;
            if let Some(at) = self.evaluated_at.as_mut() {
                *at = None;
            }
            self.eval_seconds += started.map_or(0.0, |s| s.elapsed().as_secs_f64());
        } else {
            self.load(t, x)?;
            for (k, &reg) in self.m.derivatives.iter().enumerate() {
                out[k] = self.regs[reg as usize];
            }
        }
        for (k, &v) in out[..n].iter().enumerate() {
            if !v.is_finite() {
                return Err(EvalError::domain(format!(
                    "der({}) is {v}",
                    self.m.state_names[k]
                )));
            }
        }
        if self.clock {
            out[self.m.states.len()] = 0.0;
        }
        Ok(())
    }

    fn jacobian(
        &mut self,
        t: f64,
        x: &[f64],
        jacobian: &mut unimo_solve::JacobianMatrix,
    ) -> Result<bool, EvalError> {
        let Some((tape, entries)) = &self.m.jacobian else {
            return Ok(false);
        };
        self.load(t, x)?;
        let started = unimo_solve::fine_timing().then(Instant::now);
        tape.run(&mut self.regs, &mut self.ev);
        self.eval_seconds += started.map_or(0.0, |s| s.elapsed().as_secs_f64());
        for &(i, j, r) in entries {
            let v = self.regs[r as usize];
            if !v.is_finite() {
                return Err(EvalError::domain(format!(
                    "d der({}) / d {} is {v}",
                    self.m.state_names[i], self.m.state_names[j]
                )));
            }
            jacobian.set(i, j, v);
        }
        Ok(true)
    }

    fn sparsity(&self) -> Option<&unimo_solve::SparsityPattern> {
        self.pattern.as_ref()
    }

    fn n_roots(&self) -> usize {
        self.m.roots.len()
    }

    fn roots(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.load(t, x)?;
        self.m.roots_tape.run(&mut self.regs, &mut self.ev);
        for (k, &(a, b)) in self.m.roots.iter().enumerate() {
            let (a, b) = (self.regs[a as usize], self.regs[b as usize]);
            let g = a - b;
            // Operands computed by a Newton block are exact only to its tolerance: a
            // difference inside that noise counts as exactly zero, which the root tracker
            // never reports while it stays there (e.g. a contact force that is 0 in flight
            // and comes out of its block as +-1e-50).
            let noise = ROOT_NOISE * a.abs().max(b.abs()).max(1.0);
            out[k] = if g.abs() <= noise { 0.0 } else { g };
            // A located crossing lies just outside the band: twice its width is out.
            if g.abs() > 2.0 * noise {
                zeno::outside(self, k, t, g < 0.0);
            }
        }
        if t >= self.last_roots.0 {
            self.last_roots = (t, crossings::disagreements(self.m, &self.regs, &self.ev));
        }
        Ok(())
    }

    fn n_invariants(&self) -> usize {
        self.m.invariants.len()
    }

    /// The model's `Unimo.invariant`s after a pass of the plan at `(t, x)`; active
    /// while their if-equation branches are taken (relations read without events).
    fn invariants(&mut self, t: f64, x: &[f64], out: &mut Invariants) -> Result<(), EvalError> {
        self.load(t, x)?;
        self.m.invariant_tape.run(&mut self.regs, &mut self.ev);
        for (k, &(g, on)) in self.m.invariants.iter().enumerate() {
            out.values[k] = self.regs[g as usize];
            out.active[k] = self.regs[on as usize] != 0.0;
        }
        Ok(())
    }
}

/// The names of the outputs held in `regs` (for messages).
fn output_names(m: &CompiledModel, regs: &[u32]) -> Vec<String> {
    regs.iter()
        .filter_map(|&r| {
            m.outputs
                .iter()
                .find(|(_, x)| *x == r)
                .map(|(n, _)| n.clone())
        })
        .collect()
}

/// Roots with the direction they crossed in.
type Crossed = Vec<(usize, Direction)>;

/// Relative size below which a root function counts as zero (blocks converge to 1e-13).
const ROOT_NOISE: f64 = crate::exec::RELATION_NOISE;

/// The relation's value just after its zero crossing went in `dir`.
fn after_crossing(op: RelOp, dir: Direction) -> Option<f64> {
    let falling = dir == Direction::Falling;
    match op {
        RelOp::Lt | RelOp::Le => Some(f64::from(falling)),
        RelOp::Gt | RelOp::Ge => Some(f64::from(!falling)),
        RelOp::Eq | RelOp::Ne => None,
    }
}

/// The Jacobian's sparsity pattern: the symbolic Jacobian's nonzeros when the plan has
/// one, else the structural pattern of the plan (see `pattern`).
pub fn jacobian_pattern(m: &CompiledModel) -> Option<unimo_solve::SparsityPattern> {
    if m.states.is_empty() {
        return None;
    }
    match &m.jacobian {
        Some((_, entries)) => unimo_solve::SparsityPattern::from_entries(
            m.states.len(),
            entries.iter().map(|&(i, j, _)| (i, j)),
        )
        .ok(),
        None => pattern::structural_pattern(m),
    }
}

pub struct Simulator<'a> {
    ode: Ode<'a>,
    cond_prev: Vec<f64>,
    result: SimResult,
    reinit_buffer: Vec<(u32, f64)>,
    sample_next: Vec<f64>,
    chatter: (usize, f64),
    terminate: Option<String>,
    /// A row with a NaN or infinite value was about to be written (it is not).
    non_finite: Option<SimError>,
    /// Consecutive state events that ended in a sliding mode.
    sliding_events: usize,
    /// Per dynamic state set: the candidate each of its states is.
    selections: Vec<Vec<usize>>,
    /// Which steps between the grid's points get a row.
    refine: refine::Refine,
    /// Called with each row as it is recorded (see [`Simulator::on_row`]).
    row_sink: Option<RowSink<'a>>,
    /// The rows go into the result (else only to the sink: [`Simulator::on_row_only`]).
    keep_rows: bool,
    /// The row being recorded, reused when the rows are not kept.
    row_scratch: Vec<f64>,
}

/// A receiver of result rows as they are recorded: time, then the row (one value per
/// output, in the order of `SimResult::names`).
pub type RowSink<'a> = Box<dyn FnMut(f64, &[f64]) + 'a>;

/// A dynamic state set changes its states when the current choice's pivot falls below
/// this fraction of the best one's (hysteresis: no switching back and forth between two
/// choices of about equal quality).
const RESELECT_RATIO: f64 = 0.5;

impl<'a> Simulator<'a> {
    pub fn new(m: &'a CompiledModel) -> Simulator<'a> {
        let clock = m.states.is_empty() && (!m.roots.is_empty() || !m.samples.is_empty());
        let ode = Ode {
            m,
            regs: m.new_registers(),
            ev: m.new_event_state(),
            work: Workspace::default(),
            differential: vec![true; m.states.len() + usize::from(clock)],
            clock,
            last_roots: (f64::NEG_INFINITY, Vec::new()),
            left_noise: vec![f64::NEG_INFINITY; m.roots.len()],
            zeno_watch: vec![None; m.roots.len()],
            zeno_hit: None,
            evaluations: 0,
            eval_seconds: 0.0,
            last_failure: None,
            pattern: jacobian_pattern(m),
            loop_starts: LoopStarts::new(m),
            evaluated_at: None,
            native: RhsCall::new(m),
            plan_stale: false,
        };
        Simulator {
            ode,
            cond_prev: vec![0.0; m.n_registers],
            result: SimResult::default(),
            reinit_buffer: Vec::new(),
            sample_next: Vec::new(),
            chatter: (0, f64::NEG_INFINITY),
            terminate: None,
            non_finite: None,
            sliding_events: 0,
            selections: m.state_sets.iter().map(|s| s.initial.clone()).collect(),
            refine: refine::Refine::default(),
            row_sink: None,
            keep_rows: true,
            row_scratch: Vec::new(),
        }
    }

    /// Hands every result row to `sink` as soon as it is recorded (besides keeping it in
    /// the result): a caller can write the result file while the run goes on. Rows are
    /// only ever appended, so the rows the sink saw are the result's rows.
    pub fn on_row(mut self, sink: RowSink<'a>) -> Self {
        self.row_sink = Some(sink);
        self
    }

    /// Hands every result row to `sink` as it is recorded and keeps only its time in
    /// the result (`rows` stays empty): a caller that writes the result file while the
    /// run goes on needs no second copy of a large model's result in memory.
    pub fn on_row_only(mut self, sink: RowSink<'a>) -> Self {
        self.row_sink = Some(sink);
        self.keep_rows = false;
        self
    }

    /// Times every plan step of the run into `sink` (seconds per step, summed over the
    /// run; added when the simulation ends): `unimo simulate --cost`.
    pub fn profile(
        mut self,
        sink: std::sync::Arc<std::sync::Mutex<Vec<std::time::Duration>>>,
    ) -> Self {
        self.ode.work.profile = Some(crate::eval::StepProfile::new(sink));
        self.ode.native = None;
        self
    }

    /// Dynamic state selection: evaluates each set's Jacobian at the current registers
    /// and, where the current choice of states is ill-conditioned (or, with `best`,
    /// whenever another is better), switches to the choice with the best pivots: the
    /// selection `A` (and its `pre`) and the set's states `s = A x` are set from the
    /// current candidates. Returns whether any set changed.
    fn select_states(&mut self, best: bool) -> bool {
        let m = self.m();
        let mut changed = false;
        for (k, set) in m.state_sets.iter().enumerate() {
            set.jacobian_tape.run(&mut self.ode.regs, &mut self.ode.ev);
            let n = set.candidates.len();
            let a: Vec<f64> = set
                .jacobian
                .iter()
                .map(|&r| self.ode.regs[r as usize])
                .collect();
            if a.iter().any(|v| !v.is_finite()) {
                continue;
            }
            let dummies = pick_columns(&a, set.rows, n);
            if dummies.len() < set.rows {
                continue;
            }
            let states: Vec<usize> = (0..n).filter(|j| !dummies.contains(j)).collect();
            if states == self.selections[k] {
                continue;
            }
            let current: Vec<usize> = (0..n).filter(|j| !self.selections[k].contains(j)).collect();
            let det_current = abs_det(&a, set.rows, n, &current);
            let det_best = abs_det(&a, set.rows, n, &dummies);
            let switch = if best {
                det_best > det_current
            } else {
                det_current < RESELECT_RATIO * det_best
            };
            if !switch {
                continue;
            }
            let pre = m.layout.pre_base as usize;
            for (i, &j_state) in states.iter().enumerate() {
                for j in 0..n {
                    let r = set.selectors[i * n + j] as usize;
                    let v = f64::from(j == j_state);
                    self.ode.regs[r] = v;
                    self.ode.regs[pre + r] = v;
                }
                let value = self.ode.regs[set.candidates[j_state] as usize];
                self.ode.regs[m.states[set.states[i]] as usize] = value;
            }
            self.selections[k] = states;
            changed = true;
        }
        changed
    }

    /// After an accepted step or an event: dynamic state selection at the solver's
    /// current point; a switch restarts the solver there.
    fn reselect_after_step(&mut self, solver: &mut Solver) -> Result<(), SimError> {
        if self.m().state_sets.is_empty() {
            return Ok(());
        }
        let t = solver.current_time();
        let x = solver.state().to_vec();
        self.load_state(t, &x)?;
        if self.select_states(false) {
            self.result.stats.state_selections += 1;
            self.eval_plan()?;
            self.refine_after_switch(t);
            let x = self.states();
            self.ode.last_roots = (f64::NEG_INFINITY, Vec::new());
            solver
                .reset(&mut self.ode, t, &x)
                .map_err(|e| self.solver_error(e))?;
        }
        Ok(())
    }

    /// After a switch of the state set at `t` (registers at `t`, the new set chosen):
    /// the output refinement's last row and pending step hold the old set's states,
    /// which the new set's slots read as other variables, so the chord test starts
    /// again here, from a row at `t` (written unless the last row is at `t`).
    fn refine_after_switch(&mut self, t: f64) {
        if !self.refine.enabled() {
            return;
        }
        if self.result.times.last() == Some(&t) {
            let mut x = self.refine.take_scratch();
            self.states_into(&mut x);
            self.refine.written(t, &x);
            self.refine.put_scratch(x);
        } else {
            self.record(t);
        }
    }

    fn m(&self) -> &'a CompiledModel {
        self.ode.m
    }

    /// The solver's state: the model's states (and the clock state, see `Ode`).
    fn states(&self) -> Vec<f64> {
        let mut x = Vec::with_capacity(self.m().states.len() + 1);
        self.states_into(&mut x);
        x
    }

    /// [`Simulator::states`] appended to `x`.
    fn states_into(&self, x: &mut Vec<f64>) {
        x.extend(self.m().states.iter().map(|&r| self.ode.regs[r as usize]));
        if self.ode.clock {
            x.push(0.0);
        }
    }

    fn record(&mut self, t: f64) {
        if self.non_finite.is_some() {
            return;
        }
        let m = self.m();
        m.alias_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        let mut row = std::mem::take(&mut self.row_scratch);
        row.clear();
        row.extend(m.outputs.iter().map(|&(_, r)| self.ode.regs[r as usize]));
        if let Some(k) = row.iter().position(|v| !v.is_finite()) {
            let (name, reg) = &m.outputs[k];
            let defining = match m.states.iter().position(|s| s == reg) {
                Some(state) => m.derivatives[state],
                None => *reg,
            };
            self.non_finite = Some(SimError::NonFinite {
                time: t,
                step: None,
                variable: name.clone(),
                value: row[k],
                equation: m.definitions.get(&defining).copied(),
            });
            self.row_scratch = row;
            return;
        }
        if let Some(sink) = self.row_sink.as_mut() {
            sink(t, &row);
        }
        self.result.times.push(t);
        if self.keep_rows {
            self.result.rows.push(row);
        } else {
            self.row_scratch = row;
        }
        if self.refine.enabled() {
            let mut x = self.refine.take_scratch();
            self.states_into(&mut x);
            self.refine.written(t, &x);
            self.refine.put_scratch(x);
        }
    }

    /// The error of a NaN or infinite value recorded since the last call, with the
    /// step size that produced it.
    fn take_non_finite(&mut self, step: Option<f64>) -> Option<SimError> {
        let mut e = self.non_finite.take()?;
        if let SimError::NonFinite { step: s, .. } = &mut e {
            *s = step;
        }
        Some(e)
    }

    fn eval_plan(&mut self) -> Result<(), SimError> {
        let t = self.ode.regs[self.m().layout.time as usize];
        let evaluated = self.ode.eval_from_starts(t);
        evaluated.map_err(|failure| SimError::Block { time: t, failure })?;
        self.ode.loop_starts.note_latest(t, &self.ode.regs);
        self.ode.loop_starts.commit(t, &self.ode.regs);
        Ok(())
    }

    fn load_state(&mut self, t: f64, x: &[f64]) -> Result<(), SimError> {
        let m = self.m();
        self.ode.regs[m.layout.time as usize] = t;
        for (k, &r) in m.states.iter().enumerate() {
            self.ode.regs[r as usize] = x[k];
        }
        self.eval_plan()
    }
}

/// Convenience: compile-time model in, results out.
pub fn simulate(m: &CompiledModel, o: &SimOptions) -> SimResult {
    Simulator::new(m).run(o)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each variant's message, with and without its optional parts.
    #[test]
    fn messages_of_every_variant() {
        let failure = BlockFailure {
            variables: vec!["a".into(), "b".into()],
            residual: 0.5,
            reason: "no convergence".into(),
        };
        let cases = [
            (
                SimError::Init { message: "m".into(), culprits: vec!["x".into(), "y".into()] },
                "initialization failed: m (variables: x, y)",
            ),
            (
                SimError::Solver { time: 1.5, step: Some(0.001), message: "m".into(), culprits: vec!["x".into()] },
                "the solver failed at t = 1.5, step size 1e-3: m; worst variables: x",
            ),
            (
                SimError::Solver { time: 2.0, step: None, message: "m".into(), culprits: vec![] },
                "the solver failed at t = 2: m; worst variables: ",
            ),
            (
                SimError::Block { time: 1.0, failure },
                "an algebraic loop failed at t = 1: no convergence (residual 5e-1); its iteration variables: a, b",
            ),
            (SimError::Assert { time: 0.5, message: "m".into() }, "assertion failed at t = 0.5: m"),
            (
                SimError::EventIteration { time: 3.0, culprits: vec!["x".into()] },
                "event iteration did not converge at t = 3 after 100 iterations; still changing: x",
            ),
            (
                SimError::Chattering { time: 1.0, crossing: "x > 0".into(), events: 7, sliding: false },
                "chattering at t = 1: 7 events in a row less than 1e-9 apart, from the zero crossing `x > 0`",
            ),
            (
                SimError::Chattering { time: 1.0, crossing: "x > 0".into(), events: 7, sliding: true },
                "chattering at t = 1: 7 events in a row where the flow drives the zero crossing `x > 0` back across zero from both sides (a sliding mode)",
            ),
            (
                SimError::Zeno { time: 4.0, crossing: "z0: h < 0".into(), events: 72 },
                "Zeno point near t = 4: the events of the zero crossing `z0: h < 0` accumulated until its function no longer left its rounding-noise band (relative 1e-14) between them, and after the last one's reinit it went on past zero instead of back (72 events): the model's motion is lost here (a bouncing ball would fall through its floor); the model does not say what follows the accumulation, e.g. a resting or sticking state that ends it",
            ),
            (
                SimError::NonFinite {
                    time: 1.0,
                    step: Some(0.25),
                    variable: "v".into(),
                    value: f64::NAN,
                    equation: Some(unimo_dae::dae::EqId(4)),
                },
                "`v` is NaN at t = 1, step size 2.5e-1, computed by equation #4",
            ),
            (
                SimError::NonFinite { time: 1.0, step: None, variable: "v".into(), value: f64::INFINITY, equation: None },
                "`v` is inf at t = 1",
            ),
        ];
        for (e, expected) in cases {
            assert_eq!(e.message(), expected, "{e:?}");
        }
    }
}
