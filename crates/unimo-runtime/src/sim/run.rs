//! The run: the solver set up from the options, the integration loop (steps, crossings
//! the root search missed, output on the grid, sample, state and terminal events), and
//! the result with its counters.

use super::{SimError, SimOptions, SimResult, Simulator, MAX_STEPS};
use std::time::Instant;
use unimo_solve::newton::NewtonTolerance;
use unimo_solve::{fine_timing, linear_algebra_seconds};
use unimo_solve::{Direction, Options, SolveError, Solver, StopReason, System};

/// The integration loop's state between its steps.
pub(super) struct Integration<'o> {
    pub(super) o: &'o SimOptions,
    /// The step cap of the options (the collision world may lower it further).
    pub(super) max_step: f64,
    /// The next output grid point.
    pub(super) next_output: usize,
    /// Interpolated states.
    pub(super) buf: Vec<f64>,
    pub(super) steps_taken: u64,
}

impl Integration<'_> {
    /// Output grid point `k`.
    fn grid(&self, k: usize) -> f64 {
        self.o.start + k as f64 * self.o.interval
    }
}

/// Seconds since the last reading of `clock`, which moves to now; 0 without a clock.
fn lap(clock: &mut Option<Instant>) -> f64 {
    let Some(last) = clock.as_mut() else {
        return 0.0;
    };
    let now = Instant::now();
    let seconds = now.duration_since(*last).as_secs_f64();
    *last = now;
    seconds
}

impl Simulator<'_> {
    pub(super) fn solver_error(&self, e: SolveError) -> SimError {
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
        let started = Instant::now();
        if !o.every_step {
            self.refine = super::refine::Refine::new(o.output_rtol, o.atol);
        }
        let initialized = self.initialize(o.start);
        self.result.phase_times.initialize = started.elapsed().as_secs_f64();
        if let Err(e) = initialized {
            self.result.error = Some(e);
            return self.result;
        }
        let n_scalars = m.layout.n_scalars as usize;
        self.result.initial_values = self.ode.regs[..n_scalars].to_vec();
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
        let options = self.solver_options(o);
        if m.states.is_empty() && !self.ode.clock {
            return self.run_without_states(o);
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
        let pattern = self.ode.pattern.as_ref();
        self.result.stats.jacobian_nonzeros = pattern.map(|p| p.nonzeros());
        let mut run = Integration {
            o,
            max_step: options_max_step,
            next_output: 1,
            buf: vec![0.0; self.ode.len()],
            steps_taken: 0,
        };
        // Without the fine timers the loop is timed once, as `integrate` (the split into
        // output and events is only reported with them, `--stats`).
        let loop_started = (!fine_timing()).then(Instant::now);
        loop {
            match self.integration_step(&mut solver, &mut run, progress) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    self.result.error = Some(e);
                    break;
                }
            }
        }
        if let Some(started) = loop_started {
            self.result.phase_times.integrate += started.elapsed().as_secs_f64();
        }
        self.finish(&solver)
    }

    /// The solver's options: the tolerances (the absolute one scaled by the states'
    /// nominal values) and the largest step.
    pub(super) fn solver_options(&self, o: &SimOptions) -> Options {
        let m = self.m();
        let mut options = Options::with_tolerances(o.rtol, o.atol);
        if !m.states.is_empty() {
            options.absolute_tolerance = unimo_solve::Tolerance::PerComponent(
                m.nominals.iter().map(|n| o.atol * n).collect(),
            );
        }
        options.max_step = (o.stop - o.start).abs().max(f64::MIN_POSITIVE);
        // A step no longer than a constant delay reads only accepted history (no
        // extrapolation past the last accepted point, `delay.rs`).
        options.max_step = options
            .max_step
            .min(self.ode.ev.delays.smallest_constant_delay());
        if self.ode.clock {
            // Nothing limits the steps of a constant state: the zero crossings (all of
            // time) are searched one output interval at a time, so none pair up and
            // cancel within a step.
            options.max_step = options.max_step.min(o.interval);
        }
        options
    }

    /// One step of the integration loop and what it stopped at. Ok(false): the run
    /// is over without error.
    fn integration_step(
        &mut self,
        solver: &mut Solver,
        run: &mut Integration<'_>,
        progress: &mut dyn FnMut(f64),
    ) -> Result<bool, SimError> {
        let t_sample = self
            .sample_next
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        // The steps also end where a constant delay moves a discontinuity.
        let t_event = t_sample.min(self.ode.ev.delays.next_breakpoint(solver.current_time()));
        // Three clock readings a step, and only with the fine timers (`--stats`): for a
        // small model they cost a tenth of the step.
        let mut clock = fine_timing().then(Instant::now);
        let (eval_before, linear_before) = (self.ode.eval_seconds, linear_algebra_seconds());
        let advanced = self.advance(solver, run, t_event, progress);
        let times = &mut self.result.phase_times;
        times.integrate += lap(&mut clock);
        times.evaluation += self.ode.eval_seconds - eval_before;
        times.linear_algebra += linear_algebra_seconds() - linear_before;
        let (prev, now, reason) = advanced?;
        self.write_grid(&mut *solver, run, prev, now, &reason)?;
        self.refine_step(solver, now, &reason)?;
        if let Some(e) = self.take_non_finite(Some(now - prev)) {
            return Err(e);
        }
        if matches!(reason, StopReason::InternalStep) {
            // The loops' fallback starts: the last evaluation of the accepted step.
            self.ode.loop_starts.accept_latest();
        }
        if run.o.every_step && matches!(reason, StopReason::InternalStep) {
            let x = solver.state().to_vec();
            self.load_state(now, &x)?;
            self.record(now);
        }
        self.result.phase_times.output += lap(&mut clock);
        let go_on = match reason {
            StopReason::InternalStep => {
                self.check_assertions(now)?;
                true
            }
            StopReason::ReachedStop => self.reached_stop(solver, run.o, now, t_sample)?,
            StopReason::Root { t, components } => self.root_stop(solver, run, t, &components)?,
        };
        self.result.phase_times.events += lap(&mut clock);
        if !go_on {
            return Ok(false);
        }
        self.reselect_after_step(solver)?;
        if let Some(e) = self.take_non_finite(Some(now - prev)) {
            return Err(e);
        }
        Ok(true)
    }

    /// The solver's step towards the stop time or the next sample instant, stopped at
    /// a crossing the root search missed: (previous time, time reached, why).
    pub(super) fn advance(
        &mut self,
        solver: &mut Solver,
        run: &mut Integration<'_>,
        t_event: f64,
        progress: &mut dyn FnMut(f64),
    ) -> Result<(f64, f64, StopReason), SimError> {
        let t_stop = run.o.stop.min(t_event);
        let prev = solver.current_time();
        self.ode.within_step(true);
        let stepped = solver.step(&mut self.ode, t_stop);
        self.ode.within_step(false);
        let mut reason = stepped.map_err(|e| self.solver_error(e))?;
        let mut now = solver.current_time();
        if !matches!(reason, StopReason::Root { .. }) {
            if let Some((t, components)) = self.missed_crossing(solver, prev, now)? {
                now = t;
                reason = StopReason::Root { t, components };
            }
        }
        // A Zeno point inside the step: its rows would show the lost motion.
        self.take_zeno(now)?;
        run.steps_taken += 1;
        if !matches!(reason, StopReason::Root { .. }) && self.m().collision.is_some() {
            let x = solver.state().to_vec();
            self.commit_collision(now, &x)?;
        }
        if !matches!(reason, StopReason::Root { .. }) {
            self.commit_delays(prev, now, solver.state(), Some(&*solver))?;
        }
        if run.steps_taken.is_multiple_of(256) {
            progress(now);
        }
        if run.steps_taken > MAX_STEPS {
            return Err(SimError::Solver {
                time: now,
                step: None,
                message: format!("more than {MAX_STEPS} steps; the problem may be stiffer or more oscillatory than the method can handle"),
                culprits: Vec::new(),
            });
        }
        Ok((prev, now, reason))
    }

    /// Output grid points inside (prev, now].
    fn write_grid(
        &mut self,
        solver: &mut Solver,
        run: &mut Integration<'_>,
        prev: f64,
        now: f64,
        reason: &StopReason,
    ) -> Result<(), SimError> {
        let stop = run.o.stop;
        while run.grid(run.next_output) <= now * (1.0 + 1e-14) && run.grid(run.next_output) <= stop
        {
            let tg = run.grid(run.next_output).min(now);
            if tg > prev && solver.interpolate(tg, &mut run.buf).is_ok() {
                if tg < solver.internal_time() {
                    // An interpolated row lies on the invariants to the interpolant's
                    // error only: written projected onto them.
                    let mut buf = std::mem::take(&mut run.buf);
                    let projected = self.project(Some(&mut *solver), tg, &mut buf);
                    run.buf = buf;
                    projected?;
                }
                if let Some((tp, xp)) = self.refine.needed_before(tg, &run.buf) {
                    self.load_state(tp, &xp)?;
                    self.record(tp);
                }
                self.load_state(tg, &run.buf)?;
                if tg < now || !matches!(reason, StopReason::Root { .. }) {
                    self.record(tg);
                }
            }
            run.next_output += 1;
        }
        Ok(())
    }

    /// After the grid's rows of a step: the step not written before it that the chord
    /// to this step's end would misstate, then this step's end kept as pending (an
    /// event's rows, written next, start a new chord).
    fn refine_step(
        &mut self,
        solver: &Solver,
        now: f64,
        reason: &StopReason,
    ) -> Result<(), SimError> {
        if !self.refine.enabled() || self.result.times.last() == Some(&now) {
            return Ok(());
        }
        let mut x = self.refine.take_scratch();
        x.extend_from_slice(solver.state());
        if matches!(reason, StopReason::Root { .. }) && solver.interpolate(now, &mut x).is_err() {
            self.refine.put_scratch(x);
            return Ok(());
        }
        if let Some((tp, xp)) = self.refine.needed_before(now, &x) {
            self.load_state(tp, &xp)?;
            self.record(tp);
            // The registers hold the step's end again (assertions, loop starts).
            self.load_state(now, &x)?;
        }
        if matches!(reason, StopReason::InternalStep) {
            self.refine.step_ended(now, &x);
        }
        self.refine.put_scratch(x);
        Ok(())
    }

    /// The solver reached the stop time or a sample instant. Ok(false): the run is
    /// over.
    fn reached_stop(
        &mut self,
        solver: &mut Solver,
        o: &SimOptions,
        now: f64,
        t_event: f64,
    ) -> Result<bool, SimError> {
        let x = solver.state().to_vec();
        self.load_state(now, &x)?;
        if now >= o.stop {
            // A sample instant at the stop time is an event like any other.
            if t_event <= now {
                self.sample_event(now, Some(solver))?;
            }
            if self.result.times.last() != Some(&now) {
                self.record(now);
            }
            self.terminal_event(now)?;
            return Ok(false);
        }
        if self.restart_at_breakpoint(solver, now, &x)? {
            return Ok(true);
        }
        // A sample instant.
        self.sample_event(now, Some(solver))?;
        Ok(true)
    }

    /// A zero crossing at `t`: the state event. Ok(false): the model terminated.
    pub(super) fn root_stop(
        &mut self,
        solver: &mut Solver,
        run: &mut Integration<'_>,
        t: f64,
        components: &[(usize, Direction)],
    ) -> Result<bool, SimError> {
        let mut x = solver.state().to_vec();
        if t != solver.current_time() {
            // A crossing the driver found inside the step.
            let _ = solver.interpolate(t, &mut x);
        }
        self.state_event(t, &x, components, Some(solver))?;
        if self.m().collision.is_some() {
            let x = solver.state().to_vec();
            self.commit_collision(solver.current_time(), &x)?;
            let cap = self
                .ode
                .ev
                .collision
                .as_ref()
                .map_or(f64::INFINITY, |c| c.step_cap());
            solver.set_max_step(run.max_step.min(cap));
        }
        if let Some(msg) = self.terminate.take() {
            self.result.terminated = Some(msg);
            return Ok(false);
        }
        // Grid points at exactly t were written as the left limit.
        while run.grid(run.next_output) <= t && run.grid(run.next_output) <= run.o.stop {
            run.next_output += 1;
        }
        Ok(true)
    }

    fn finish(mut self, solver: &Solver) -> SimResult {
        if let Some(e) = self.take_non_finite(None) {
            self.result.error.get_or_insert(e);
        }
        self.result.stats.solver = solver.stats();
        self.result.stats.linear_solver = solver.linear_solver();
        self.result.stats.sparse_lu =
            self.result.stats.linear_solver == Some(unimo_solve::LinearSolverKind::Sparse);
        self.result.stiff_since = solver.stiff_since();
        self.result.stats.projection = solver.projection_stats();
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
            self.record_delays(t);
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
    /// After an accepted step or an event: the collision world's sweep starts here.
    pub(super) fn commit_collision(&mut self, t: f64, x: &[f64]) -> Result<(), SimError> {
        if self.m().collision.is_none() {
            return Ok(());
        }
        self.load_state(t, x)?;
        if let Some(c) = self.ode.ev.collision.as_mut() {
            c.commit();
        }
        Ok(())
    }
}
