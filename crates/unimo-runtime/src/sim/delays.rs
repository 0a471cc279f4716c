//! The simulator's side of `delay` (`crate::delay`): the histories are appended after
//! every accepted step (`run.rs`, `stepper.rs`), before and after every event
//! (`events.rs`), and at initialization, which is iterated: a read at the start time
//! is the delayed expression's own value there (`e(time.start)`), which is known only
//! once initialization is done; the reads' guess starts at the expression's value at
//! the start values and becomes the initialized value until the two agree.

use super::{SimError, Simulator};
use crate::exec::{Instance, Run};
use unimo_solve::Solver;

/// Initializations before the delayed values at the start time must agree with the
/// values read.
const MAX_PASSES: usize = 30;
/// Halvings of an accepted step where the history's interpolant misses the delayed
/// expression's value at the middle.
const MAX_HALVINGS: u32 = 4;

impl Simulator<'_> {
    /// The delayed expressions' values at the registers' point (after a pass of the
    /// plan) appended to their histories at `t`.
    pub(super) fn record_delays(&mut self, t: f64) {
        let m = self.m();
        if m.delay_inputs.is_empty() {
            return;
        }
        m.delay_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        let regs = &self.ode.regs;
        let values = m.delay_inputs.iter().map(|&r| regs[r as usize]);
        self.ode.ev.delays.push(t, values);
    }

    /// After an accepted step from `prev` to `(t, x)`: the plan there, and the delays
    /// recorded; then, with the solver's dense output, the middle of the step where
    /// the history's interpolant misses the expression's value there by more than the
    /// tolerances (halved again where it does, [`MAX_HALVINGS`] times at most). The
    /// registers end at `(t, x)`.
    pub(super) fn commit_delays(
        &mut self,
        prev: f64,
        t: f64,
        x: &[f64],
        solver: Option<&Solver>,
    ) -> Result<(), SimError> {
        if self.m().delay_inputs.is_empty() {
            return Ok(());
        }
        self.load_state(t, x)?;
        self.record_delays(t);
        let Some(solver) = solver.filter(|_| prev < t) else {
            return Ok(());
        };
        let mut d = std::mem::take(&mut self.ode.ev.delays);
        d.saved.clone_from(&self.ode.regs);
        d.states.resize(x.len(), 0.0);
        self.ode.ev.delays = d;
        if self.refine_history(solver, prev, t, MAX_HALVINGS) {
            let d = &mut self.ode.ev.delays;
            self.ode.regs.copy_from_slice(&d.saved);
        }
        Ok(())
    }

    /// The middle of `(a, b)` added to the histories where they miss it (and its
    /// halves then refined, `depth` times at most). Whether the registers changed.
    fn refine_history(&mut self, solver: &Solver, a: f64, b: f64, depth: u32) -> bool {
        let mid = 0.5 * (a + b);
        if depth == 0 || mid <= a || mid >= b {
            return false;
        }
        let mut x = std::mem::take(&mut self.ode.ev.delays.states);
        let evaluated =
            solver.interpolate(mid, &mut x).is_ok() && self.ode.load_anew(mid, &x).is_ok();
        self.ode.ev.delays.states = x;
        if !evaluated {
            return true;
        }
        let m = self.m();
        m.delay_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        let tol = self.ode.work.tolerance;
        let regs = &self.ode.regs;
        let d = &mut self.ode.ev.delays;
        let missed = m.delay_inputs.iter().zip(&d.lines).any(|(&r, line)| {
            let v = regs[r as usize];
            (line.value(mid, false) - v).abs() > tol.relative * v.abs() + tol.absolute
        });
        if missed {
            for (&r, line) in m.delay_inputs.iter().zip(&mut d.lines) {
                line.insert(mid, regs[r as usize]);
            }
            self.refine_history(solver, a, mid, depth - 1);
            self.refine_history(solver, mid, b, depth - 1);
        }
        true
    }

    /// The solver stopped at `(t, x)` before the stop time: at no sample instant, this
    /// is a breakpoint of a constant delay (where it moves a discontinuity of its
    /// expression), and the solver restarts there, as after an event. Whether it was
    /// one.
    pub(super) fn restart_at_breakpoint(
        &mut self,
        solver: &mut Solver,
        t: f64,
        x: &[f64],
    ) -> Result<bool, SimError> {
        let sample_due = self
            .sample_next
            .iter()
            .any(|&s| s <= t * (1.0 + 1e-15) + 1e-300);
        if sample_due || self.m().delay_inputs.is_empty() {
            return Ok(false);
        }
        self.ode.ev.delays.split(t);
        self.ode.last_roots = (f64::NEG_INFINITY, Vec::new());
        solver
            .reset(&mut self.ode, t, x)
            .map_err(|e| self.solver_error(e))?;
        Ok(true)
    }

    /// The delayed expressions' values at the registers' point.
    fn delay_values(&mut self) -> Vec<f64> {
        let m = self.m();
        m.delay_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        m.delay_inputs
            .iter()
            .map(|&r| self.ode.regs[r as usize])
            .collect()
    }

    /// Consistent initial values (`init.rs`), with the delays' values at the start
    /// time iterated to agree with the initialized values; the histories then start
    /// with them.
    pub(super) fn initialize(&mut self, t0: f64) -> Result<(), SimError> {
        let m = self.m();
        if m.delay_inputs.is_empty() {
            return self.initialize_once(t0);
        }
        // The first guess: the values at the parameters and start values.
        self.ode.regs[m.layout.time as usize] = t0;
        if m.run_parameters(&mut self.ode.regs, &mut self.ode.ev)
            .is_ok()
        {
            m.starts.run(&mut self.ode.regs, &mut self.ode.ev);
        }
        let mut guesses = self.delay_values();
        for _ in 0..MAX_PASSES {
            let finite: Vec<f64> = guesses
                .iter()
                .map(|g| if g.is_finite() { *g } else { 0.0 })
                .collect();
            self.ode.ev.delays.restart(finite.iter().copied());
            self.initialize_once(t0)?;
            let values = self.delay_values();
            let agree = values
                .iter()
                .zip(&finite)
                .all(|(v, g)| (v - g).abs() <= 1e-12 * v.abs().max(g.abs()).max(1.0));
            guesses = values;
            if agree {
                self.record_delays(t0);
                self.ode.ev.delays.mark(t0);
                return Ok(());
            }
        }
        let names: Vec<String> = (0..guesses.len())
            .map(|k| format!("$delay{}", k + 1))
            .collect();
        Err(SimError::Init {
            message: format!(
                "the delayed values at the start time do not settle after {MAX_PASSES} \
                 initializations (`delay(e, d)` reads `e` itself there, and `e` depends on it)"
            ),
            culprits: names,
        })
    }
}
