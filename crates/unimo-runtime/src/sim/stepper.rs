//! A run driven from outside one call at a time, as an FMU is: Model Exchange (the
//! importer sets time and states, reads derivatives and event indicators, and calls
//! the event update at the events it locates) and Co-Simulation (our own solver steps
//! from one communication point to the next, with our events in between).

use super::run::Integration;
use super::{after_crossing, crossings, Crossed, SimError, SimOptions, Simulator};
use crate::exec::Run;
use unimo_codegen::model::CompiledModel;
use unimo_dae::expr::RelOp;
use unimo_solve::newton::NewtonTolerance;
use unimo_solve::{Direction, Solver, StopReason, System};

/// What an event update found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EventOutcome {
    /// The model called `terminate(message)`.
    pub terminated: Option<String>,
    /// A `reinit` (or a state set's change) gave a state a new value.
    pub states_changed: bool,
    /// The next sample instant, when the model has one.
    pub next_time: Option<f64>,
}

/// A simulation advanced by its caller (see the module's documentation).
pub struct Stepper<'a> {
    sim: Simulator<'a>,
    options: SimOptions,
    /// Co-Simulation: our solver, once integration started.
    solver: Option<Solver>,
    steps_taken: u64,
    /// The event indicators at the end of the last event (or of initialization): a
    /// function that is zero now crossed from that side.
    reference: Vec<f64>,
    /// Which indicators of held relations sat at zero (within the Newton noise) at the
    /// end of the last event: one still at zero has not moved, so it did not cross.
    zero_at_event: Vec<bool>,
    /// Time and states at the end of the last event: an event update at that same
    /// point (a sample instant at the start time) finds no crossing of a function
    /// left at its zero there (`time >= startTime`).
    last_event: (f64, Vec<f64>),
    /// The registers changed since the plan was last evaluated.
    dirty: bool,
}

impl<'a> Stepper<'a> {
    /// A stepper for `m` with these tolerances, method and start time (`stop` bounds
    /// the solver's largest step in Co-Simulation).
    pub fn new(m: &'a CompiledModel, options: SimOptions) -> Stepper<'a> {
        let mut sim = Simulator::new(m);
        sim.ode.work.tolerance = NewtonTolerance::new(options.rtol, options.atol);
        Stepper {
            sim,
            options,
            solver: None,
            steps_taken: 0,
            reference: vec![0.0; m.roots.len()],
            zero_at_event: vec![false; m.roots.len()],
            last_event: (f64::NAN, Vec::new()),
            dirty: true,
        }
    }

    pub fn model(&self) -> &'a CompiledModel {
        self.sim.m()
    }

    /// Consistent initial values and the initial event at the start time.
    pub fn initialize(&mut self) -> Result<(), SimError> {
        self.sim.initialize(self.options.start)?;
        self.sim.eval_plan()?;
        self.finish_event()
    }

    /// Every register (by `ScalarId` for the model's scalars), as last evaluated.
    pub fn registers(&self) -> &[f64] {
        &self.sim.ode.regs
    }

    /// Sets a register (a parameter's or an input's) before the next evaluation.
    pub fn set_register(&mut self, reg: u32, value: f64) {
        self.sim.ode.regs[reg as usize] = value;
        self.dirty = true;
    }

    pub fn time(&self) -> f64 {
        self.sim.ode.regs[self.model().layout.time as usize]
    }

    pub fn set_time(&mut self, t: f64) {
        let time = self.model().layout.time as usize;
        self.sim.ode.regs[time] = t;
        self.dirty = true;
    }

    /// The model's states (without the clock state of a model that has none).
    pub fn states(&self) -> Vec<f64> {
        let m = self.model();
        m.states
            .iter()
            .map(|&r| self.sim.ode.regs[r as usize])
            .collect()
    }

    pub fn set_states(&mut self, x: &[f64]) {
        let m = self.model();
        for (k, &r) in m.states.iter().enumerate() {
            self.sim.ode.regs[r as usize] = x[k];
        }
        self.dirty = true;
    }

    /// Evaluates the plan (and the aliases) at the current time, states and inputs,
    /// unless nothing changed since the last evaluation.
    pub fn evaluate(&mut self) -> Result<(), SimError> {
        if self.dirty {
            self.sim.eval_plan()?;
            let m = self.model();
            m.alias_tape
                .run(&mut self.sim.ode.regs, &mut self.sim.ode.ev);
            self.dirty = false;
        }
        Ok(())
    }

    /// The state derivatives at the current point.
    pub fn derivatives(&mut self, out: &mut [f64]) -> Result<(), SimError> {
        self.evaluate()?;
        let m = self.model();
        for (k, &r) in m.derivatives.iter().enumerate() {
            out[k] = self.sim.ode.regs[r as usize];
        }
        Ok(())
    }

    /// The event indicators (zero-crossing functions) at the current point, as an
    /// importer sees them: a held relation whose function sits at its zero (within the
    /// Newton noise) reads a tiny value on the side its held value says, so that
    /// leaving the zero on the other side is a sign change the importer locates (a
    /// clutch stuck at `w_rel = 0` that starts to slip backwards).
    pub fn event_indicators(&mut self, out: &mut [f64]) -> Result<(), SimError> {
        self.raw_indicators(out)?;
        let m = self.model();
        for (k, gk) in out.iter_mut().enumerate().take(m.root_ops.len()) {
            if *gk == 0.0 && m.relation_held[k] {
                *gk = f64::MIN_POSITIVE * self.held_side(k);
            }
        }
        Ok(())
    }

    /// The side of its zero a held relation's function is on by the relation's value:
    /// 1 above, -1 below, 0 for `==` and `<>`.
    fn held_side(&self, k: usize) -> f64 {
        let held = self.sim.ode.ev.relations[k] != 0.0;
        match (self.model().root_ops[k], held) {
            (RelOp::Lt | RelOp::Le, true) | (RelOp::Gt | RelOp::Ge, false) => -1.0,
            (RelOp::Lt | RelOp::Le, false) | (RelOp::Gt | RelOp::Ge, true) => 1.0,
            (RelOp::Eq | RelOp::Ne, _) => 0.0,
        }
    }

    /// The event indicators at the current point as our own solvers see them
    /// (differences within the Newton noise are zero).
    fn raw_indicators(&mut self, out: &mut [f64]) -> Result<(), SimError> {
        let t = self.time();
        let x = self.sim.states();
        self.dirty = true;
        self.sim
            .ode
            .roots(t, &x, out)
            .map_err(|e| SimError::Solver {
                time: t,
                step: None,
                message: e.to_string(),
                culprits: Vec::new(),
            })?;
        let m = self.model();
        m.alias_tape
            .run(&mut self.sim.ode.regs, &mut self.sim.ode.ev);
        self.dirty = false;
        Ok(())
    }

    /// The next sample instant, if any.
    pub fn next_time_event(&self) -> Option<f64> {
        let next = self
            .sim
            .sample_next
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        next.is_finite().then_some(next)
    }

    /// Model Exchange's event update at the current time and states: the crossings
    /// since the last event (held relations that disagree with their operands, and
    /// functions that came to zero), due sample instants, and the event iteration with
    /// our `when`/`reinit` semantics, then the relations settled along the flow.
    pub fn event_update(&mut self) -> Result<EventOutcome, SimError> {
        let t = self.time();
        let before = self.states();
        let crossed = self.crossed()?;
        let sample_due = self
            .next_time_event()
            .is_some_and(|s| s <= t * (1.0 + 1e-15) + 1e-300);
        if sample_due {
            self.sim.sample_event(t, None)?;
        }
        if !crossed.is_empty() {
            let x = self.sim.states();
            self.sim.state_event(t, &x, &crossed, None)?;
        } else if !sample_due {
            self.sim.after_event(t, "event update".into(), None, None)?;
        }
        self.sim.eval_plan()?;
        self.finish_event()?;
        self.completed_step()?;
        let states_changed = before != self.states();
        Ok(EventOutcome {
            terminated: self.sim.terminate.take(),
            states_changed,
            next_time: self.next_time_event(),
        })
    }

    /// Model Exchange, after each step the importer's integrator accepts and after each
    /// event: the collision world's sweep starts at the current placements, as after
    /// each of our own steps (`run.rs`). Nothing to do without a world.
    pub fn completed_step(&mut self) -> Result<(), SimError> {
        if self.model().collision.is_some() {
            let (t, x) = (self.time(), self.sim.states());
            self.sim.commit_collision(t, &x)?;
            self.dirty = true;
        }
        if !self.model().delay_inputs.is_empty() {
            let (t, x) = (self.time(), self.sim.states());
            self.sim.commit_delays(t, t, &x, None)?;
            self.dirty = true;
        }
        Ok(())
    }

    /// After initialization or an event: the aliases, the reference event indicators,
    /// no result rows kept (the caller reads the registers).
    fn finish_event(&mut self) -> Result<(), SimError> {
        let m = self.model();
        m.alias_tape
            .run(&mut self.sim.ode.regs, &mut self.sim.ode.ev);
        self.sim.result.times.clear();
        self.sim.result.rows.clear();
        if let Some(e) = self.sim.take_non_finite(None) {
            return Err(e);
        }
        let mut g = vec![0.0; m.roots.len()];
        self.raw_indicators(&mut g)?;
        self.last_event = (self.time(), self.states());
        // A relation left at its zero is on the side its held value says.
        self.zero_at_event = vec![false; g.len()];
        for (k, gk) in g.iter_mut().enumerate().take(m.root_ops.len()) {
            if *gk == 0.0 && m.relation_held[k] {
                self.zero_at_event[k] = true;
                *gk = self.held_side(k);
            }
        }
        self.reference = g;
        Ok(())
    }

    /// The crossings at the current point since the last event.
    fn crossed(&mut self) -> Result<Crossed, SimError> {
        let m = self.model();
        let mut g = vec![0.0; m.roots.len()];
        self.raw_indicators(&mut g)?;
        let mut found = crossings::disagreements(m, &self.sim.ode.regs, &self.sim.ode.ev);
        let n_relations = m.root_ops.len();
        let stationary = self.last_event.0 == self.time() && self.last_event.1 == self.states();
        for (k, (&now, &before)) in g.iter().zip(&self.reference).enumerate() {
            if found.iter().any(|&(j, _)| j == k) || before == 0.0 || stationary {
                continue;
            }
            let unheld = k < n_relations && !m.relation_held[k];
            let at_zero = now == 0.0;
            let changed_sign = now != 0.0 && (now > 0.0) != (before > 0.0);
            let dir = if before > 0.0 {
                Direction::Falling
            } else {
                Direction::Rising
            };
            // A held relation at its zero crossed only if that changes its value.
            // One that sat at its zero at the last event and is there still has not moved
            // (`u < uMin` with `u = 0` and `uMin = 1e-16` reads zero throughout).
            let flips = k >= n_relations
                || !m.relation_held[k]
                || (!self.zero_at_event[k]
                    && after_crossing(m.root_ops[k], dir)
                        .is_some_and(|v| v != self.sim.ode.ev.relations[k]));
            if (at_zero && flips) || (unheld && changed_sign) {
                found.push((k, dir));
            }
        }
        found.sort_by_key(|c| c.0);
        Ok(found)
    }
}

impl Stepper<'_> {
    /// Co-Simulation: integrates from the current time to `until` with our solver
    /// (created at the first call), handling the state and sample events on the way.
    /// `Some(message)`: the model terminated (at the current time).
    pub fn do_step(&mut self, until: f64) -> Result<Option<String>, SimError> {
        let t = self.time();
        if until <= t {
            return Ok(None);
        }
        let m = self.model();
        if m.states.is_empty() && !self.sim.ode.clock {
            return self.step_without_states(until);
        }
        let mut solver = match self.solver.take() {
            Some(s) => s,
            None => {
                let x0 = self.sim.states();
                let options = self.sim.solver_options(&self.options);
                Solver::new(self.options.method, &mut self.sim.ode, t, &x0, options)
                    .map_err(|e| self.sim.solver_error(e))?
            }
        };
        let result = self.integrate(&mut solver, until);
        self.solver = Some(solver);
        self.sim.result.times.clear();
        self.sim.result.rows.clear();
        self.dirty = true;
        result
    }

    /// The loop of [`do_step`](Stepper::do_step) (`run.rs`'s, without output rows).
    fn integrate(&mut self, solver: &mut Solver, until: f64) -> Result<Option<String>, SimError> {
        let options = SimOptions {
            start: solver.current_time(),
            stop: until,
            interval: f64::INFINITY,
            ..self.options.clone()
        };
        let mut run = Integration {
            o: &options,
            max_step: self.sim.solver_options(&self.options).max_step,
            next_output: 1,
            buf: vec![0.0; self.sim.ode.len()],
            steps_taken: self.steps_taken,
        };
        loop {
            let t_event = self.next_time_event().unwrap_or(f64::INFINITY);
            let (prev, now, reason) = self.sim.advance(solver, &mut run, t_event, &mut |_| {})?;
            self.steps_taken = run.steps_taken;
            if let Some(e) = self.sim.take_non_finite(Some(now - prev)) {
                return Err(e);
            }
            match reason {
                StopReason::InternalStep => self.sim.check_assertions(now)?,
                StopReason::ReachedStop => {
                    let x = solver.state().to_vec();
                    self.sim.load_state(now, &x)?;
                    if t_event <= now {
                        self.sim.sample_event(now, Some(solver))?;
                    }
                    if now >= until {
                        return Ok(self.sim.terminate.take());
                    }
                }
                StopReason::Root { t, components } => {
                    if !self.sim.root_stop(solver, &mut run, t, &components)? {
                        return Ok(self.sim.result.terminated.take());
                    }
                }
            }
            self.sim.reselect_after_step(solver)?;
            self.sim.result.times.clear();
            self.sim.result.rows.clear();
        }
    }

    /// A model without states and events: its values at `until`.
    fn step_without_states(&mut self, until: f64) -> Result<Option<String>, SimError> {
        self.sim.load_state(until, &[])?;
        self.dirty = true;
        Ok(None)
    }

    /// The terminal event (`when terminal()`), when the importer ends the run.
    pub fn terminal(&mut self) -> Result<(), SimError> {
        let t = self.time();
        self.sim.terminal_event(t)?;
        self.sim.result.times.clear();
        self.sim.result.rows.clear();
        Ok(())
    }
}
