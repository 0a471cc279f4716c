//! The simulation driver: initialization, integration with one of our solvers, output
//! on a grid, and Modelica event semantics (zero crossings located on the dense
//! output, event iteration with `pre` values, `reinit` at the end of the event step,
//! sample time events, restart after each event).

use crate::eval::{eval_steps, eval_steps_lenient, BlockFailure, Workspace};
use crate::model::{Action, CompiledModel};
use crate::tape::EventState;
use unimo_dae::expr::RelOp;
use unimo_solve::dense::{
    abs_det, independent_rows_and_columns, independent_rows_in_order, newton_step, pick_columns,
};
use unimo_solve::newton::NewtonTolerance;
use unimo_solve::{Direction, EvalError, Method, Options, SolveError, Solver, StopReason, System};

mod crossings;

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
}

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
    /// `experiment` annotation, else the default — StartTime 0, StopTime 1, Tolerance
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
        })
    }
}

/// Why a simulation stopped early.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    Init {
        message: String,
        culprits: Vec<String>,
    },
    Solver {
        time: f64,
        step: Option<f64>,
        message: String,
        culprits: Vec<String>,
    },
    Block {
        time: f64,
        failure: BlockFailure,
    },
    Assert {
        time: f64,
        message: String,
    },
    EventIteration {
        time: f64,
        culprits: Vec<String>,
    },
    Chattering {
        time: f64,
        crossing: String,
        events: usize,
        /// The events were a sliding mode (the flow drives the crossing function back
        /// across zero from both sides), not close in time.
        sliding: bool,
    },
    /// A result value became NaN or infinite.
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
        }
    }

    pub fn message(&self) -> String {
        match self {
            SimError::Init { message, culprits } => {
                format!("initialization failed: {message} (variables: {})", culprits.join(", "))
            }
            SimError::Solver { time, step, message, culprits } => format!(
                "the solver failed at t = {time}{}: {message}; worst variables: {}",
                step.map(|h| format!(", step size {h:e}")).unwrap_or_default(),
                culprits.join(", ")
            ),
            SimError::Block { time, failure } => format!(
                "an algebraic loop failed at t = {time}: {} (residual {:e}); its iteration variables: {}",
                failure.reason,
                failure.residual,
                failure.variables.join(", ")
            ),
            SimError::Assert { time, message } => format!("assertion failed at t = {time}: {message}"),
            SimError::EventIteration { time, culprits } => format!(
                "event iteration did not converge at t = {time} after {MAX_EVENT_ITERATIONS} iterations; still changing: {}",
                culprits.join(", ")
            ),
            SimError::NonFinite { time, step, variable, value, equation } => format!(
                "`{variable}` is {value} at t = {time}{}{}",
                step.map(|h| format!(", step size {h:e}")).unwrap_or_default(),
                equation
                    .map(|e| format!(", computed by equation #{}", e.0))
                    .unwrap_or_default()
            ),
            SimError::Chattering { time, crossing, events, sliding: false } => format!(
                "chattering at t = {time}: {events} events in a row less than {CHATTER_WINDOW:e} apart, from the zero crossing `{crossing}`"
            ),
            SimError::Chattering { time, crossing, events, sliding: true } => format!(
                "chattering at t = {time}: {events} events in a row where the flow drives the zero crossing `{crossing}` back across zero from both sides (a sliding mode)"
            ),
        }
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
}

/// Results computed so far (also after a failure).
#[derive(Clone, Debug, Default)]
pub struct SimResult {
    pub names: Vec<String>,
    pub times: Vec<f64>,
    pub rows: Vec<Vec<f64>>,
    pub events: Vec<EventRecord>,
    pub stats: SimStats,
    pub error: Option<SimError>,
    pub terminated: Option<String>,
    /// Final state values (for references).
    pub final_states: Vec<f64>,
}

/// The ODE in the states that the solvers see.
struct Ode<'a> {
    m: &'a CompiledModel,
    regs: Vec<f64>,
    ev: EventState,
    work: Workspace,
    differential: Vec<bool>,
    evaluations: u64,
    last_failure: Option<BlockFailure>,
    /// Nonzeros of the symbolic Jacobian (large systems then use the sparse LU).
    pattern: Option<unimo_solve::SparsityPattern>,
    /// A model without states but with events gets one constant state, so that the
    /// solvers step through time and locate its crossings and sample instants.
    clock: bool,
    /// The relations disagreeing with their operands at the latest time the root
    /// functions were evaluated since the last event (see `crossings::disagreements`).
    last_roots: (f64, Crossed),
}

impl Ode<'_> {
    fn load(&mut self, t: f64, x: &[f64]) -> Result<(), EvalError> {
        self.regs[self.m.layout.time as usize] = t;
        for (k, &reg) in self.m.states.iter().enumerate() {
            self.regs[reg as usize] = x[k];
        }
        self.evaluations += 1;
        eval_steps(self.m, &mut self.regs, &mut self.ev, &mut self.work).map_err(|f| {
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
        self.load(t, x)?;
        for (k, &reg) in self.m.derivatives.iter().enumerate() {
            let v = self.regs[reg as usize];
            if !v.is_finite() {
                return Err(EvalError::domain(format!(
                    "der({}) is {v}",
                    self.m.state_names[k]
                )));
            }
            out[k] = v;
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
        tape.run(&mut self.regs, &mut self.ev);
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
            out[k] = if g.abs() <= ROOT_NOISE * a.abs().max(b.abs()).max(1.0) {
                0.0
            } else {
                g
            };
        }
        if t >= self.last_roots.0 {
            self.last_roots = (t, crossings::disagreements(self.m, &self.regs, &self.ev));
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
const ROOT_NOISE: f64 = crate::tape::RELATION_NOISE;

/// The relation's value just after its zero crossing went in `dir`.
fn after_crossing(op: RelOp, dir: Direction) -> Option<f64> {
    let falling = dir == Direction::Falling;
    match op {
        RelOp::Lt | RelOp::Le => Some(f64::from(falling)),
        RelOp::Gt | RelOp::Ge => Some(f64::from(!falling)),
        RelOp::Eq | RelOp::Ne => None,
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
}

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
            evaluations: 0,
            last_failure: None,
            pattern: m
                .jacobian
                .as_ref()
                .filter(|_| !m.states.is_empty())
                .and_then(|(_, entries)| {
                    unimo_solve::SparsityPattern::from_entries(
                        m.states.len(),
                        entries.iter().map(|&(i, j, _)| (i, j)),
                    )
                    .ok()
                }),
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
        }
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
            let x = self.states();
            self.ode.last_roots = (f64::NEG_INFINITY, Vec::new());
            solver
                .reset(&mut self.ode, t, &x)
                .map_err(|e| self.solver_error(e))?;
        }
        Ok(())
    }

    fn m(&self) -> &'a CompiledModel {
        self.ode.m
    }

    /// The solver's state: the model's states (and the clock state, see `Ode`).
    fn states(&self) -> Vec<f64> {
        let mut x: Vec<f64> = self
            .m()
            .states
            .iter()
            .map(|&r| self.ode.regs[r as usize])
            .collect();
        if self.ode.clock {
            x.push(0.0);
        }
        x
    }

    fn record(&mut self, t: f64) {
        if self.non_finite.is_some() {
            return;
        }
        let m = self.m();
        m.alias_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        let row: Vec<f64> = m
            .outputs
            .iter()
            .map(|&(_, r)| self.ode.regs[r as usize])
            .collect();
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
            return;
        }
        self.result.times.push(t);
        self.result.rows.push(row);
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
        let m = self.m();
        eval_steps(m, &mut self.ode.regs, &mut self.ode.ev, &mut self.ode.work)
            .map_err(|failure| SimError::Block { time: t, failure })
    }

    /// Consistent initial values: parameters, start values, initial equations solved
    /// for the states they determine, then the initial event (`initial()` true).
    fn initialize(&mut self, t0: f64) -> Result<(), SimError> {
        let m = self.m();
        if let Some(c) = m.collision.as_ref().filter(|c| !c.problems.is_empty()) {
            return Err(SimError::Init {
                message: "the collision world runs before the rest of the model, so a \
                          collision body's shape, placement and velocities must come from \
                          states and parameters, not from variables the model computes"
                    .into(),
                culprits: c.problems.clone(),
            });
        }
        let layout = m.layout;
        self.ode.regs[layout.time as usize] = t0;
        self.ode.regs[layout.initial as usize] = 1.0;
        if let Err(message) = m.run_parameters(&mut self.ode.regs, &mut self.ode.ev) {
            return Err(SimError::Init {
                message,
                culprits: Vec::new(),
            });
        }
        m.starts.run(&mut self.ode.regs, &mut self.ode.ev);
        // A constraint whose variables all have fixed starts must hold at them.
        m.fixed_constraints_tape
            .run(&mut self.ode.regs, &mut self.ode.ev);
        for c in &m.fixed_constraints {
            let (l, r) = (self.ode.regs[c.lhs as usize], self.ode.regs[c.rhs as usize]);
            if (l - r).abs() > 1e-9 * (1.0 + l.abs().max(r.abs())) || !(l - r).is_finite() {
                let values: Vec<String> = c
                    .variables
                    .iter()
                    .map(|(n, reg)| format!("{n} = {:?}", self.ode.regs[*reg as usize]))
                    .collect();
                return Err(SimError::Init {
                    message: format!(
                        "the fixed start values {} contradict the equation `{}` \
                         (its sides differ by {:e}); free one of them (fixed = false) or \
                         make them consistent",
                        values.join(", "),
                        c.text,
                        (l - r).abs()
                    ),
                    culprits: c.variables.iter().map(|(n, _)| n.clone()).collect(),
                });
            }
        }
        // Dynamic state sets start with the best choice at the start values.
        self.select_states(true);
        // pre(v) starts at the start value.
        for s in 0..layout.n_scalars {
            self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
        }
        self.ode.ev.event_mode = true;
        if !m.initial_residuals.is_empty() {
            self.solve_initial_equations()?;
        } else if !m.initial_assigned.is_empty() || !m.initial_pre_assigned.is_empty() {
            self.eval_plan()?;
            let m = self.m();
            m.initial_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        }
        // A discrete variable whose `pre` the initial equations set equals it at
        // initialization (its `when` is not active: `y = pre(y)`).
        let m = self.m();
        for &r in &m.initial_pre_assigned {
            self.ode.regs[r as usize] = self.ode.regs[(layout.pre_base + r) as usize];
        }
        // The discrete values the initial equations assigned are their `pre` values.
        let m = self.m();
        for &(r, _) in &m.initial_assigned {
            self.ode.regs[(layout.pre_base + r) as usize] = self.ode.regs[r as usize];
        }
        // `when` conditions fire at initialization only through `initial()`: their
        // values with initial() false are the baseline the edges are taken against.
        // Only the conditions are kept: the discrete values that evaluation computes
        // (a friction's mode, locked without `initial()`) would otherwise become the
        // `pre` values of the initial event.
        let initialized = self.ode.regs.clone();
        let relations = self.ode.ev.relations.clone();
        self.ode.regs[layout.initial as usize] = 0.0;
        let baseline = self.eval_plan();
        let m = self.m();
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        self.ode.regs.copy_from_slice(&initialized);
        self.ode.ev.relations = relations;
        baseline?;
        // The values of initialization, consistent with its `pre` values (an initial
        // equation `pre(y) = true`): the initial event starts from them.
        self.ode.regs[layout.initial as usize] = 1.0;
        self.eval_plan()?;
        self.event_iteration(t0, true)?;
        self.ode.regs[layout.initial as usize] = 0.0;
        if self.m().equations_read_initial {
            // After initialization `initial()` is false: the discrete variables whose
            // equations read it take their values for the run in one more event
            // iteration at the start time (a friction's `startForward`, true only
            // while initializing).
            self.ode.ev.event_mode = true;
            self.event_iteration(t0, false)?;
        }
        self.ode.ev.event_mode = false;
        let m = self.m();
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        // The consistent values may call for other states than the start values did.
        if self.select_states(true) {
            self.eval_plan()?;
        }
        let m = self.m();
        // Sample instants.
        self.sample_next = m
            .samples
            .iter()
            .map(|&(s, _)| self.ode.regs[s as usize])
            .collect();
        Ok(())
    }

    /// Newton on the initial equations; the unknowns are the states not `fixed` and
    /// the parameters with `fixed = false`, the ones that influence the residuals most
    /// chosen by pivoting when there are more unknowns than equations.
    fn solve_initial_equations(&mut self) -> Result<(), SimError> {
        let m = self.m();
        let n_eq = m.initial_residuals.len();
        // Unknowns as (register, name): free states, then free parameters.
        let unknowns: Vec<(usize, String)> = (0..m.states.len())
            .filter(|&k| !m.fixed[k])
            .map(|k| (m.states[k] as usize, m.state_names[k].clone()))
            .chain(
                m.free_parameters
                    .iter()
                    .map(|(r, n)| (*r as usize, n.clone())),
            )
            .collect();
        let free: Vec<usize> = (0..unknowns.len()).collect();
        let names = |ks: &[usize]| {
            ks.iter()
                .map(|&k| unknowns[k].1.clone())
                .collect::<Vec<_>>()
        };
        // More initial equations than unknowns is legal when the extra ones are
        // redundant and hold at the solution (fixed starts on both ends of a rigid
        // connection): the independent equations are solved, the others checked.
        // The equations that do not hold once the independent ones are solved, and the
        // model equations through which they contradict the solved ones.
        let explain = |f: &[f64], solved: &[usize]| -> (String, Vec<String>) {
            let mut off = Vec::new();
            let mut through: Vec<String> = Vec::new();
            let mut culprits = Vec::new();
            // The solved equations of the same order as one that is off take part.
            let orders: Vec<u32> = (0..f.len())
                .filter(|&i| f[i].abs() > 1e-9 && !solved.contains(&i))
                .map(|i| m.initial_orders.get(i).copied().unwrap_or(u32::MAX))
                .collect();
            let involved = |i: usize| {
                f[i].abs() > 1e-9
                    || (solved.contains(&i)
                        && orders.contains(&m.initial_orders.get(i).copied().unwrap_or(u32::MAX)))
            };
            for (i, (text, constraint)) in m.initial_names.iter().enumerate() {
                if involved(i) {
                    if !solved.contains(&i) {
                        off.push(format!("`{text}` is off by {:.3e}", f[i].abs()));
                    }
                    if let Some(c) = constraint.as_ref().filter(|c| !through.contains(c)) {
                        through.push(c.clone());
                    }
                    culprits.push(text.split(" = ").next().unwrap_or(text).to_string());
                }
            }
            let held: Vec<String> = solved
                .iter()
                .filter(|&&i| involved(i))
                .filter_map(|&i| m.initial_names.get(i).map(|(t, _)| format!("`{t}`")))
                .collect();
            let mut text = off.join(", ");
            if !held.is_empty() {
                text += &format!(
                    " when {} {}",
                    held.join(", "),
                    if held.len() == 1 { "holds" } else { "hold" }
                );
            }
            if !through.is_empty() {
                text += &format!(
                    "; they are related by the model's equations `{}`",
                    through.join("`, `")
                );
            }
            if culprits.is_empty() {
                culprits = names(&free);
            }
            (text, culprits)
        };
        let too_many = |f: &[f64], solved: &[usize]| {
            let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let (detail, culprits) = explain(f, solved);
            SimError::Init {
                message: format!(
                    "{n_eq} initial equations for {} unknowns (states without fixed = true, \
                     parameters with fixed = false), and the extra ones do not hold \
                     (residual {norm:e}): the fixed start values contradict each other{}",
                    free.len(),
                    if detail.is_empty() {
                        String::new()
                    } else {
                        format!(": {detail}")
                    },
                ),
                culprits,
            }
        };
        // Any other failure, with the initial equations that are off at the last iterate.
        let failed = |what: &str, f: &[f64], solved: &[usize]| {
            let (detail, culprits) = explain(f, solved);
            SimError::Init {
                message: if detail.is_empty() {
                    what.to_string()
                } else {
                    format!("{what}; at the last iterate {detail}")
                },
                culprits,
            }
        };
        // The plan is evaluated leniently at the iterates: a block that the initial
        // equations do not need may fail at the start values; that is an error only when
        // the residuals are not finite. The event iteration afterwards is strict.
        let residual = |me: &mut Self| -> Result<Vec<f64>, SimError> {
            let t = me.ode.regs[me.m().layout.time as usize];
            let m = me.m();
            if !m.free_parameters.is_empty() {
                m.dependent_parameters.run(&mut me.ode.regs, &mut me.ode.ev);
            }
            let failure =
                eval_steps_lenient(me.m(), &mut me.ode.regs, &mut me.ode.ev, &mut me.ode.work);
            if let Some(failure) = failure {
                let m = me.m();
                m.initial_tape.run(&mut me.ode.regs, &mut me.ode.ev);
                let f: Vec<f64> = m
                    .initial_residuals
                    .iter()
                    .map(|&r| me.ode.regs[r as usize])
                    .collect();
                if f.iter().any(|x| !x.is_finite()) {
                    return Err(SimError::Block { time: t, failure });
                }
            }
            let m = me.m();
            m.initial_tape.run(&mut me.ode.regs, &mut me.ode.ev);
            Ok(m.initial_residuals
                .iter()
                .map(|&r| me.ode.regs[r as usize])
                .collect())
        };
        // Finite differences of the residuals `rows` in the registers `regs` (row-major).
        let jacobian = |me: &mut Self,
                        regs: &[usize],
                        rows: &[usize],
                        f: &[f64]|
         -> Result<Vec<f64>, SimError> {
            let mut jac = vec![0.0; rows.len() * regs.len()];
            for (j, &reg) in regs.iter().enumerate() {
                let x = me.ode.regs[reg];
                let h = 1e-7 * x.abs().max(1e-3);
                me.ode.regs[reg] = x + h;
                let fp = residual(me)?;
                me.ode.regs[reg] = x;
                for (ii, &i) in rows.iter().enumerate() {
                    jac[ii * regs.len() + j] = (fp[i] - f[i]) / h;
                }
                // A step below the rounding of a large residual (`seed = 67867967`
                // from seed = 0) shows no change in it: such entries are taken from a
                // second difference with a step of 1e-8 of the largest residual.
                let big = 1e-8 * rows.iter().fold(0.0f64, |a, &i| a.max(f[i].abs()));
                let lost = |ii: usize, i: usize, jac: &[f64]| {
                    jac[ii * regs.len() + j] == 0.0 && f[i].abs() * 1e-15 > h
                };
                if big > h && rows.iter().enumerate().any(|(ii, &i)| lost(ii, i, &jac)) {
                    me.ode.regs[reg] = x + big;
                    let fp = residual(me)?;
                    me.ode.regs[reg] = x;
                    for (ii, &i) in rows.iter().enumerate() {
                        if lost(ii, i, &jac) {
                            jac[ii * regs.len() + j] = (fp[i] - f[i]) / big;
                        }
                    }
                }
            }
            Ok(jac)
        };
        // The initial equations of the free parameters alone (`cr = ...`, `r = -cr*w`
        // of a filter) first: the states' equations may be singular until they hold
        // (a steady state `der(x) = r*(x - u)` with r still 0).
        let parameter_rows: Vec<usize> = (0..n_eq)
            .filter(|&i| m.initial_parameter_only.get(i).copied().unwrap_or(false))
            .collect();
        let parameter_unknowns: Vec<usize> = (0..unknowns.len())
            .filter(|&k| k >= unknowns.len() - m.free_parameters.len())
            .collect();
        if !parameter_rows.is_empty() && !parameter_unknowns.is_empty() {
            for _ in 0..30 {
                let f = residual(self)?;
                let fr: Vec<f64> = parameter_rows.iter().map(|&i| f[i]).collect();
                if fr.iter().all(|x| x.abs() <= 1e-12) {
                    break;
                }
                let (nr, nc) = (parameter_rows.len(), parameter_unknowns.len());
                let regs: Vec<usize> = parameter_unknowns.iter().map(|&k| unknowns[k].0).collect();
                let jac = jacobian(self, &regs, &parameter_rows, &f)?;
                let (rows, cols) = independent_rows_and_columns(&jac, nr, nc);
                let Some(dx) = newton_step(&jac, nc, &rows, &cols, &fr) else {
                    break;
                };
                for (jj, &j) in cols.iter().enumerate() {
                    self.ode.regs[regs[j]] += dx[jj];
                }
            }
        }
        let mut chosen: Option<(Vec<usize>, Vec<usize>)> = None;
        let mut deficient_steps = 0;
        let mut last_accepted = false;
        for _ in 0..50 {
            let f = residual(self)?;
            let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if norm <= 1e-12 {
                return Ok(());
            }
            // Finite-difference Jacobian over the free states.
            let regs: Vec<usize> = free.iter().map(|&k| unknowns[k].0).collect();
            let all: Vec<usize> = (0..n_eq).collect();
            let jac = jacobian(self, &regs, &all, &f)?;
            let (rows, cols) = chosen.get_or_insert_with(|| {
                if n_eq > free.len() {
                    independent_rows_in_order(&jac, n_eq, free.len(), &m.initial_orders)
                } else {
                    independent_rows_and_columns(&jac, n_eq, free.len())
                }
            });
            let deficient = rows.len() < n_eq && n_eq <= free.len();
            if deficient {
                // Singular at this iterate: the equations that are independent here
                // take a step (e.g. the parameters a filter's steady state depends on,
                // which start at 0 and make that state's rows vanish), then the rank
                // is looked at again; singular for good is an error.
                deficient_steps += 1;
                if deficient_steps > 8 || rows.is_empty() {
                    return Err(failed(
                        "the initial equations do not determine the states (singular)",
                        &f,
                        &[],
                    ));
                }
            }
            let (rows, cols) = (rows.clone(), cols.clone());
            if deficient {
                chosen = None;
            }
            let (rows, cols) = (&rows, &cols);
            if rows.is_empty() {
                return Err(too_many(&f, &[]));
            }
            let Some(dx) = newton_step(&jac, free.len(), rows, cols, &f) else {
                return Err(failed(
                    "the initial equations have a singular Jacobian",
                    &f,
                    rows,
                ));
            };
            last_accepted = true;
            for (jj, &j) in cols.iter().enumerate() {
                let x = self.ode.regs[regs[j]];
                last_accepted &= self.ode.work.tolerance.accepts(x, dx[jj]);
                self.ode.regs[regs[j]] = x + dx[jj];
            }
        }
        let f = residual(self)?;
        let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        // Not converged to rounding in 50 steps: accepted when the last step was within
        // the simulation's tolerances (unimo_solve::newton's rule) and the redundant
        // equations, which take no step, hold.
        let redundant = chosen.as_ref().map_or(0.0, |(rows, _)| {
            (0..n_eq)
                .filter(|i| !rows.contains(i))
                .fold(0.0f64, |a, i| a.max(f[i].abs()))
        });
        if last_accepted && norm.is_finite() && redundant <= 1e-9 {
            return Ok(());
        }
        if let Some((rows, _)) = &chosen {
            let solved = rows.iter().fold(0.0f64, |a, &i| a.max(f[i].abs()));
            if rows.len() < n_eq && solved <= 1e-9 {
                return Err(too_many(&f, rows));
            }
        }
        let solved = chosen.as_ref().map(|(r, _)| r.clone()).unwrap_or_default();
        Err(failed(
            &format!("Newton on the initial equations did not converge (residual {norm:e})"),
            &f,
            &solved,
        ))
    }

    /// Modelica's event iteration at `t`: evaluate with `pre` values, fire `when`
    /// branches whose condition became true, repeat until no discrete value changes;
    /// then apply `reinit`s.
    fn event_iteration(&mut self, t: f64, initial: bool) -> Result<(), SimError> {
        let m = self.m();
        let layout = m.layout;
        self.ode.regs[layout.time as usize] = t;
        self.ode.ev.event_mode = true;
        self.ode.ev.sticky = !initial;
        self.reinit_buffer.clear();
        let mut iterations = 0;
        loop {
            iterations += 1;
            self.result.stats.event_iterations += 1;
            // pre := current, for every variable.
            for s in 0..layout.n_scalars {
                self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
            }
            // The assignments of the `when` branches that fire belong to this step like
            // any equation: the system is evaluated again with them until they agree, so
            // what depends on a `when`-assigned variable sees its new value before other
            // `when` conditions are decided (e.g. a mask closed at a lift-off must block
            // the impact test at the same instant).
            // A branch fires at most once per step (its condition became true against
            // the previous step), as a `when`-statement executes once per evaluation of
            // its algorithm; several clauses may assign the same variable, the later one
            // in declaration order wins within the step, and a clause that becomes true
            // because of another's assignment fires in this same step.
            let n_branches: usize = m.whens.iter().map(|w| w.branches.len()).sum();
            let mut fired = vec![false; n_branches];
            let mut settled = false;
            let mut unsettled: Vec<u32> = Vec::new();
            let mut pending: Vec<(u32, f64)> = Vec::new();
            for _ in 0..MAX_EVENT_ITERATIONS {
                self.eval_plan()?;
                m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
                let mut any = false;
                unsettled.clear();
                let mut b = 0;
                for w in &m.whens {
                    let first = b;
                    b += w.branches.len();
                    for (k, (conds, actions)) in w.branches.iter().enumerate() {
                        let active = conds.iter().any(|&c| self.ode.regs[c as usize] != 0.0);
                        let fires = !fired[first + k]
                            && conds.iter().any(|&c| {
                                self.ode.regs[c as usize] != 0.0
                                    && self.cond_prev[c as usize] == 0.0
                            });
                        // Every branch fired in this step is applied again in each
                        // pass, in declaration order (the later one wins a variable
                        // several assign): its equations hold at the instant with the
                        // values the other branches assigned since (`r = f(r_raw)`
                        // beside `r_raw = random(pre(state))`, whichever comes first).
                        if fires || fired[first + k] {
                            fired[first + k] = true;
                            any |= fires;
                            for a in actions {
                                if let Action::Assign { target, value } = a {
                                    let v = self.ode.regs[*value as usize];
                                    match pending.iter_mut().find(|(t, _)| t == target) {
                                        Some(p) => p.1 = v,
                                        None => pending.push((*target, v)),
                                    }
                                }
                            }
                        }
                        // elsewhen: later branches only when this one is not active.
                        if active || fired[first + k] {
                            break;
                        }
                    }
                }
                for (target, v) in pending.drain(..) {
                    if self.ode.regs[target as usize] != v {
                        self.ode.regs[target as usize] = v;
                        unsettled.push(target);
                        any = true;
                    }
                }
                if !any {
                    settled = true;
                    break;
                }
            }
            if !settled {
                let culprits = output_names(m, &unsettled);
                return Err(SimError::EventIteration { time: t, culprits });
            }
            let mut assigned: Vec<u32> = Vec::new();
            let mut b = 0;
            for w in &m.whens {
                for (_, actions) in &w.branches {
                    if fired[b] {
                        for a in actions {
                            match a {
                                Action::Assign { target, .. } => assigned.push(*target),
                                Action::Reinit { target, value } => self
                                    .reinit_buffer
                                    .push((*target, self.ode.regs[*value as usize])),
                                Action::Terminate(msg) => self.terminate = Some(msg.clone()),
                                Action::Assert { condition, message } => {
                                    if self.ode.regs[*condition as usize] == 0.0 {
                                        return Err(SimError::Assert {
                                            time: t,
                                            message: message.clone(),
                                        });
                                    }
                                }
                            }
                        }
                    }
                    b += 1;
                }
            }
            for &c in &m.conditions {
                self.cond_prev[c as usize] = self.ode.regs[c as usize];
            }
            let mut changed = Vec::new();
            for target in assigned {
                let pre = self.ode.regs[(layout.pre_base + target) as usize];
                if self.ode.regs[target as usize] != pre && !changed.contains(&target) {
                    changed.push(target);
                }
            }
            // Discrete variables defined by equations (not `when`) changed too?
            for &d in &m.discretes {
                let pre = self.ode.regs[(layout.pre_base + d) as usize];
                if self.ode.regs[d as usize] != pre && !changed.contains(&d) {
                    changed.push(d);
                }
            }
            // Relations forced by the located crossing hold only for the first pass.
            for f in self.ode.ev.forced.iter_mut() {
                *f = None;
            }
            // reinit at the end of this event iteration step (MLS 8.3.6), then another
            // step: what the new state values change (a condition that becomes true, e.g.
            // an `elsewhen`; discrete variables defined by equations) happens at this
            // event, instead of being recorded as the new `pre` without firing.
            let reinits = std::mem::take(&mut self.reinit_buffer);
            let reinitialized = !reinits.is_empty();
            for (target, v) in reinits {
                self.ode.regs[target as usize] = v;
            }
            if changed.is_empty() && !reinitialized {
                break;
            }
            if iterations >= MAX_EVENT_ITERATIONS {
                let culprits = output_names(m, &changed);
                return Err(SimError::EventIteration { time: t, culprits });
            }
        }
        for s in 0..layout.n_scalars {
            self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
        }
        self.ode.ev.event_mode = false;
        self.ode.ev.sticky = false;
        // A rounding whose bound was crossed keeps its new value through every pass of
        // the event (its argument may sit a rounding error before the bound).
        for f in self.ode.ev.held_forced.iter_mut() {
            *f = None;
        }
        Ok(())
    }

    fn solver_error(&self, e: SolveError) -> SimError {
        let m = self.m();
        let (time, step, worst) = match &e {
            SolveError::StepSizeTooSmall { time, step, worst }
            | SolveError::NewtonFailed { time, step, worst }
            | SolveError::ErrorTestFailed { time, step, worst } => {
                (*time, Some(*step), worst.clone())
            }
            SolveError::TooManySteps { time, .. } | SolveError::Eval { time, .. } => {
                (*time, None, Vec::new())
            }
            SolveError::SingularMatrix { time, step } => (*time, Some(*step), Vec::new()),
            _ => (f64::NAN, None, Vec::new()),
        };
        let mut culprits: Vec<String> = worst
            .iter()
            .take(5)
            .filter_map(|&(k, w)| m.state_names.get(k).map(|n| format!("{n} ({w:.3e})")))
            .collect();
        if let Some(f) = &self.ode.last_failure {
            culprits.extend(f.variables.iter().cloned());
        }
        SimError::Solver {
            time,
            step,
            message: e.to_string(),
            culprits,
        }
    }

    /// Runs the simulation. The result holds everything computed, also on failure.
    pub fn run(self, o: &SimOptions) -> SimResult {
        self.run_with_progress(o, &mut |_| {})
    }

    /// Like [`run`](Simulator::run), calling `progress(t)` now and then with the
    /// simulated time reached (for a progress bar; the runtime never prints).
    pub fn run_with_progress(mut self, o: &SimOptions, progress: &mut dyn FnMut(f64)) -> SimResult {
        let m = self.m();
        self.result.names = m.outputs.iter().map(|(n, _)| n.clone()).collect();
        self.ode.work.tolerance = NewtonTolerance::new(o.rtol, o.atol);
        if let Err(e) = self.initialize(o.start) {
            self.result.error = Some(e);
            return self.result;
        }
        self.record(o.start);
        if let Some(e) = self.take_non_finite(None) {
            self.result.error = Some(e);
            return self.result;
        }
        if o.stop == o.start {
            // A zero-length interval: the consistent initial values are the result.
            self.result.final_states = self.states();
            self.result.final_states.truncate(m.states.len());
            return self.result;
        }
        let x0 = self.states();
        let mut options = Options::with_tolerances(o.rtol, o.atol);
        if !m.states.is_empty() {
            options.absolute_tolerance = unimo_solve::Tolerance::PerComponent(
                m.nominals.iter().map(|n| o.atol * n).collect(),
            );
        }
        options.max_step = (o.stop - o.start).abs().max(f64::MIN_POSITIVE);
        if m.states.is_empty() && !self.ode.clock {
            return self.run_without_states(o);
        }
        if self.ode.clock {
            // Nothing limits the steps of a constant state: the zero crossings (all of
            // time) are searched one output interval at a time, so none pair up and
            // cancel within a step.
            options.max_step = options.max_step.min(o.interval);
        }
        let options_max_step = options.max_step;
        let mut solver = match Solver::new(o.method, &mut self.ode, o.start, &x0, options) {
            Ok(s) => s,
            Err(e) => {
                self.result.error = Some(self.solver_error(e));
                return self.result;
            }
        };
        if let Some(c) = self.ode.ev.collision.as_ref() {
            solver.set_max_step(options_max_step.min(c.step_cap()));
        }
        let mut next_output = 1usize;
        let grid = |k: usize| o.start + k as f64 * o.interval;
        let mut buf = vec![0.0; self.ode.len()];
        let mut steps_taken: u64 = 0;
        loop {
            let t_event = self
                .sample_next
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min);
            let t_stop = o.stop.min(t_event);
            let prev = solver.current_time();
            let reason = match solver.step(&mut self.ode, t_stop) {
                Ok(r) => r,
                Err(e) => {
                    self.result.error = Some(self.solver_error(e));
                    break;
                }
            };
            let mut now = solver.current_time();
            let mut reason = reason;
            if !matches!(reason, StopReason::Root { .. }) {
                match self.missed_crossing(&solver, prev, now) {
                    Ok(Some((t, components))) => {
                        now = t;
                        reason = StopReason::Root { t, components };
                    }
                    Ok(None) => {}
                    Err(e) => {
                        self.result.error = Some(e);
                        break;
                    }
                }
            }
            steps_taken += 1;
            if !matches!(reason, StopReason::Root { .. }) {
                let x = solver.state().to_vec();
                if let Err(e) = self.commit_collision(now, &x) {
                    self.result.error = Some(e);
                    break;
                }
            }
            if steps_taken.is_multiple_of(256) {
                progress(now);
            }
            if steps_taken > MAX_STEPS {
                self.result.error = Some(SimError::Solver {
                    time: now,
                    step: None,
                    message: format!("more than {MAX_STEPS} steps; the problem may be stiffer or more oscillatory than the method can handle"),
                    culprits: Vec::new(),
                });
                break;
            }
            // Output grid points inside (prev, now].
            while grid(next_output) <= now * (1.0 + 1e-14) && grid(next_output) <= o.stop {
                let tg = grid(next_output).min(now);
                if tg > prev && solver.interpolate(tg, &mut buf).is_ok() {
                    if let Err(e) = self.load_state(tg, &buf) {
                        self.result.error = Some(e);
                        return self.finish(&solver);
                    }
                    if tg < now || !matches!(reason, StopReason::Root { .. }) {
                        self.record(tg);
                    }
                }
                next_output += 1;
            }
            if let Some(e) = self.take_non_finite(Some(now - prev)) {
                self.result.error = Some(e);
                break;
            }
            match reason {
                StopReason::InternalStep => {
                    if o.every_step {
                        let x = solver.state().to_vec();
                        if let Err(e) = self.load_state(now, &x) {
                            self.result.error = Some(e);
                            break;
                        }
                        self.record(now);
                    }
                    if let Err(e) = self.check_assertions(now) {
                        self.result.error = Some(e);
                        break;
                    }
                }
                StopReason::ReachedStop => {
                    let x = solver.state().to_vec();
                    if let Err(e) = self.load_state(now, &x) {
                        self.result.error = Some(e);
                        break;
                    }
                    if now >= o.stop {
                        // A sample instant at the stop time is an event like any other.
                        if t_event <= now {
                            if let Err(e) = self.sample_event(now, &mut solver) {
                                self.result.error = Some(e);
                                break;
                            }
                        }
                        if self.result.times.last() != Some(&now) {
                            self.record(now);
                        }
                        if let Err(e) = self.terminal_event(now) {
                            self.result.error = Some(e);
                        }
                        break;
                    }
                    // A sample instant.
                    if let Err(e) = self.sample_event(now, &mut solver) {
                        self.result.error = Some(e);
                        break;
                    }
                }
                StopReason::Root { t, components } => {
                    let mut x = solver.state().to_vec();
                    if t != solver.current_time() {
                        // A crossing the driver found inside the step.
                        let _ = solver.interpolate(t, &mut x);
                    }
                    if let Err(e) = self.state_event(t, &x, &components, &mut solver) {
                        self.result.error = Some(e);
                        break;
                    }
                    if self.m().collision.is_some() {
                        let x = solver.state().to_vec();
                        if let Err(e) = self.commit_collision(solver.current_time(), &x) {
                            self.result.error = Some(e);
                            break;
                        }
                        let cap = self
                            .ode
                            .ev
                            .collision
                            .as_ref()
                            .map_or(f64::INFINITY, |c| c.step_cap());
                        solver.set_max_step(options_max_step.min(cap));
                    }
                    if let Some(msg) = self.terminate.take() {
                        self.result.terminated = Some(msg);
                        break;
                    }
                    // Grid points at exactly t were written as the left limit.
                    while grid(next_output) <= t && grid(next_output) <= o.stop {
                        next_output += 1;
                    }
                }
            }
            if let Err(e) = self.reselect_after_step(&mut solver) {
                self.result.error = Some(e);
                break;
            }
            if let Some(e) = self.take_non_finite(Some(now - prev)) {
                self.result.error = Some(e);
                break;
            }
        }
        self.finish(&solver)
    }

    fn finish(mut self, solver: &Solver) -> SimResult {
        if let Some(e) = self.take_non_finite(None) {
            self.result.error.get_or_insert(e);
        }
        self.result.stats.solver = solver.stats();
        self.result.stats.rhs_evaluations = self.ode.evaluations;
        self.result.stats.collision = self.ode.ev.collision.as_ref().map(|c| c.stats.clone());
        self.result.final_states = self.states();
        self.result.final_states.truncate(self.m().states.len());
        self.result
    }

    fn run_without_states(mut self, o: &SimOptions) -> SimResult {
        let n = ((o.stop - o.start) / o.interval).round().max(0.0) as usize;
        for k in 1..=n {
            let t = o.start + k as f64 * o.interval;
            if let Err(e) = self.load_state(t, &[]) {
                self.result.error = Some(e);
                break;
            }
            self.record(t);
            if let Some(e) = self.take_non_finite(Some(o.interval)) {
                self.result.error = Some(e);
                break;
            }
        }
        if self.result.error.is_none() {
            if let Err(e) = self.terminal_event(o.stop) {
                self.result.error = Some(e);
            }
        }
        self.result
    }

    /// At the end of a successful run of a model that reads `terminal()`: one more
    /// event at the stop time with `terminal()` true (its `when terminal()` clauses
    /// fire), recorded as the last row.
    fn terminal_event(&mut self, t: f64) -> Result<(), SimError> {
        let m = self.m();
        if !m.uses_terminal {
            return Ok(());
        }
        self.ode.regs[m.layout.terminal as usize] = 1.0;
        self.event_iteration(t, false)?;
        self.record(t);
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

    /// After an accepted step or an event: the collision world's sweep starts here.
    fn commit_collision(&mut self, t: f64, x: &[f64]) -> Result<(), SimError> {
        if self.m().collision.is_none() {
            return Ok(());
        }
        self.load_state(t, x)?;
        if let Some(c) = self.ode.ev.collision.as_mut() {
            c.commit();
        }
        Ok(())
    }

    fn check_assertions(&mut self, t: f64) -> Result<(), SimError> {
        let m = self.m();
        if m.assertions.is_empty() {
            return Ok(());
        }
        m.assert_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for (r, msg, warning) in &m.assertions {
            if self.ode.regs[*r as usize] == 0.0 && !warning {
                return Err(SimError::Assert {
                    time: t,
                    message: msg.clone(),
                });
            }
        }
        Ok(())
    }

    fn state_event(
        &mut self,
        t: f64,
        x: &[f64],
        components: &[(usize, Direction)],
        solver: &mut Solver,
    ) -> Result<(), SimError> {
        self.load_state(t, x)?;
        self.record(t);
        for &(k, dir) in components {
            self.force_crossing(k, dir);
        }
        let what = components
            .iter()
            .map(|&(k, d)| {
                format!(
                    "z{k} {}",
                    if d == Direction::Rising {
                        "rising"
                    } else {
                        "falling"
                    }
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        self.after_event(t, what, components.first().map(|c| c.0), solver)?;
        let mut settled = self.settle_relations(t, components);
        if settled.fires {
            // The relations just after t make a `when` condition true: it fires now.
            let what = "settled relations".to_string();
            self.after_event(t, what, components.first().map(|c| c.0), solver)?;
            settled = self.settle_relations(t, components);
            if settled.fires {
                // Keep the baseline consistent; the next crossing decides.
                let m = self.m();
                for &c in &m.conditions {
                    self.cond_prev[c as usize] = self.ode.regs[c as usize];
                }
            }
        }
        if settled.sliding {
            self.sliding_events += 1;
        } else {
            self.sliding_events = 0;
        }
        if self.sliding_events >= CHATTER_COUNT {
            let k = components[0].0;
            return Err(SimError::Chattering {
                time: t,
                crossing: format!("z{k}: {}", self.m().root_names[k]),
                events: self.sliding_events,
                sliding: true,
            });
        }
        Ok(())
    }

    fn sample_event(&mut self, t: f64, solver: &mut Solver) -> Result<(), SimError> {
        let m = self.m();
        let mut due = Vec::new();
        for (k, next) in self.sample_next.iter_mut().enumerate() {
            if *next <= t * (1.0 + 1e-15) + 1e-300 {
                due.push(k);
                // Instant n is start + n * interval (no accumulated rounding).
                let start = self.ode.regs[m.samples[k].0 as usize];
                let interval = self.ode.regs[m.samples[k].1 as usize];
                let n = ((t - start) / interval).round() + 1.0;
                *next = start + n * interval;
            }
        }
        self.record(t);
        for &k in &due {
            self.ode.ev.samples[k] = 1.0;
        }
        let r = self.after_event(t, format!("sample {due:?}"), None, solver);
        for s in self.ode.ev.samples.iter_mut() {
            *s = 0.0;
        }
        // The sample conditions are false again right after the instant, and so is a
        // discrete variable the plan computes from them (`trig = sample(0, 0.1)`): its
        // value between the instants is the left limit `pre(trig)` at the next one.
        // Record that, so the next instant is an edge of `when trig`.
        if r.is_ok() && self.eval_plan().is_ok() {
            let pre_base = m.layout.pre_base;
            for &d in &m.discretes {
                self.ode.regs[(pre_base + d) as usize] = self.ode.regs[d as usize];
            }
        }
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        r
    }

    fn after_event(
        &mut self,
        t: f64,
        what: String,
        crossing: Option<usize>,
        solver: &mut Solver,
    ) -> Result<(), SimError> {
        self.event_iteration(t, false)?;
        self.result.stats.events += 1;
        self.result.events.push(EventRecord { time: t, what });
        // Chattering: many events in a row at (almost) the same time.
        let scale = t.abs().max(1.0);
        if t - self.chatter.1 <= CHATTER_WINDOW * scale {
            self.chatter.0 += 1;
        } else {
            self.chatter.0 = 0;
        }
        self.chatter.1 = t;
        if self.chatter.0 >= CHATTER_COUNT {
            let m = self.m();
            let crossing = crossing
                .map(|k| format!("z{k}: {}", m.root_names[k]))
                .unwrap_or_else(|| "a time event".into());
            return Err(SimError::Chattering {
                time: t,
                crossing,
                events: self.chatter.0,
                sliding: false,
            });
        }
        self.record(t);
        let x = self.states();
        self.ode.last_roots = (f64::NEG_INFINITY, Vec::new());
        solver
            .reset(&mut self.ode, t, &x)
            .map_err(|e| self.solver_error(e))
    }
}

/// Convenience: compile-time model in, results out.
pub fn simulate(m: &CompiledModel, o: &SimOptions) -> SimResult {
    Simulator::new(m).run(o)
}
