//! The driver the runtime uses: integrate to an output time without passing it (`t_stop`),
//! stop at zero crossings with the state at the root (left limit), restart after events.
//!
//! The driver keeps an output position `(time, state)` that may lag behind the method's
//! internal time: after a root or an output time inside a step, the next call first searches
//! the rest of that step and only then takes new steps. A step is never taken past the
//! `t_stop` of the current call.

use crate::bdf::Bdf;
use crate::dopri5::Dopri5;
use crate::error::SolveError;
use crate::integrator::Integrator;
use crate::options::{Method, Options};
use crate::radau5::Radau5;
use crate::roots::{Direction, RootTracker};
use crate::stats::Stats;
use crate::system::System;

/// Why `step_until` or `step` returned.
#[derive(Debug, Clone, PartialEq)]
pub enum StopReason {
    /// The solver is at `t_stop`; `state()` is the solution there.
    ReachedStop,
    /// A zero crossing at `t`; `state()` is the solution there (the left limit, before the
    /// caller applies event changes). `components` lists every root function that changes sign
    /// at `t`, with its direction, in increasing index order.
    Root {
        t: f64,
        components: Vec<(usize, Direction)>,
    },
    /// `step` reached the end of an internal step (or of the rest of one after a root) without
    /// a root; the solver is at its end and `interpolate` covers the way there.
    InternalStep,
}

/// A system-independent solver: one method plus output positioning and root location.
pub struct Solver {
    integrator: Box<dyn Integrator + Send>,
    time: f64,
    state: Vec<f64>,
    roots: RootTracker,
    /// Root functions reported at `time` (reference zero after a reset there).
    reported_at_time: Vec<usize>,
    driver_stats: Stats,
    max_steps_per_call: usize,
}

impl std::fmt::Debug for Solver {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter
            .debug_struct("Solver")
            .field("method", &self.integrator.method())
            .field("time", &self.time)
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

impl Solver {
    /// Creates a solver at `(t0, x0)`. `Method::Auto` resolves to BDF. For DAEs `x0` must be
    /// consistent (algebraic rows satisfied).
    pub fn new(
        method: Method,
        system: &mut dyn System,
        t0: f64,
        x0: &[f64],
        options: Options,
    ) -> Result<Self, SolveError> {
        let max_steps_per_call = options.max_steps_per_call;
        let integrator: Box<dyn Integrator + Send> = match method.resolved() {
            Method::Dopri5 => Box::new(Dopri5::new(system, t0, x0, options)?),
            Method::Radau5 => Box::new(Radau5::new(system, t0, x0, options)?),
            _ => Box::new(Bdf::new(system, t0, x0, options)?),
        };
        let mut solver = Solver {
            integrator,
            time: t0,
            state: x0.to_vec(),
            roots: RootTracker::new(system.n_roots(), x0.len()),
            reported_at_time: Vec::new(),
            driver_stats: Stats::default(),
            max_steps_per_call,
        };
        solver.restart_roots(system, &[])?;
        Ok(solver)
    }

    /// Integrates until `t_stop` (returning `ReachedStop` with the state at `t_stop`) or the
    /// first root before or at it (returning `Root`), whichever comes first.
    pub fn step_until(
        &mut self,
        system: &mut dyn System,
        t_stop: f64,
    ) -> Result<StopReason, SolveError> {
        self.advance(system, t_stop, false)
    }

    /// Like [`step_until`](Solver::step_until) but returns `InternalStep` at the end of the
    /// next internal step (or of the rest of the current one, after a root) when it reaches
    /// neither `t_stop` nor a root. For output grids: interpolate the points between the
    /// previous and the new `current_time`.
    pub fn step(&mut self, system: &mut dyn System, t_stop: f64) -> Result<StopReason, SolveError> {
        self.advance(system, t_stop, true)
    }

    /// Restarts at `(t, x)` after the caller applied event changes: BDF back to order 1, Radau
    /// fresh, a new initial step; roots reported at `t` are not reported again.
    pub fn reset(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError> {
        if x.len() != self.state.len() {
            return Err(SolveError::invalid(format!(
                "reset state has {} entries, the system has {}",
                x.len(),
                self.state.len()
            )));
        }
        if !t.is_finite() || x.iter().any(|v| !v.is_finite()) {
            return Err(SolveError::invalid(format!(
                "reset at t = {t} with a non-finite time or state"
            )));
        }
        self.integrator.reset(system, t, x)?;
        let known_zero = if t == self.time {
            std::mem::take(&mut self.reported_at_time)
        } else {
            Vec::new()
        };
        self.time = t;
        self.state.copy_from_slice(x);
        self.restart_roots(system, &known_zero)?;
        self.reported_at_time = known_zero;
        Ok(())
    }

    /// The solution at `t` within the last internal step (for output grids).
    pub fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), SolveError> {
        let dense = self.integrator.dense_output();
        let (start, end) = dense.interval();
        let fuzz = 100.0 * f64::EPSILON * (start.abs().max(end.abs()) + (end - start).abs());
        if !(t >= start - fuzz && t <= end + fuzz) {
            return Err(SolveError::OutsideDenseOutput {
                time: t,
                start,
                end,
            });
        }
        if out.len() != self.state.len() {
            return Err(SolveError::invalid(
                "interpolate output has the wrong length",
            ));
        }
        if t == self.time {
            out.copy_from_slice(&self.state);
        } else {
            dense.evaluate(t, out);
        }
        Ok(())
    }

    /// The output position: `t_stop`, the root, or the end of the last internal step.
    /// Changes the largest step the method takes from now on (must be positive).
    pub fn set_max_step(&mut self, h: f64) {
        if h > 0.0 {
            self.integrator.set_max_step(h);
        }
    }

    pub fn current_time(&self) -> f64 {
        self.time
    }

    /// The state at [`current_time`](Solver::current_time).
    pub fn state(&self) -> &[f64] {
        &self.state
    }

    /// Work counters of the method plus root evaluations and reported events.
    pub fn stats(&self) -> Stats {
        let mut stats = self.integrator.stats().clone();
        stats.root_evals += self.driver_stats.root_evals;
        stats.events += self.driver_stats.events;
        stats
    }

    /// The method in use.
    pub fn method(&self) -> Method {
        self.integrator.method()
    }

    /// Internal time of the method (at or after `current_time`).
    pub fn internal_time(&self) -> f64 {
        self.integrator.current_time()
    }

    fn restart_roots(
        &mut self,
        system: &mut dyn System,
        known_zero: &[usize],
    ) -> Result<(), SolveError> {
        let time = self.time;
        self.roots
            .restart(
                system,
                time,
                &self.state,
                known_zero,
                &mut self.driver_stats,
            )
            .map_err(|error| SolveError::Eval {
                time,
                message: format!("root functions: {error}"),
            })
    }

    fn advance(
        &mut self,
        system: &mut dyn System,
        t_stop: f64,
        single_step: bool,
    ) -> Result<StopReason, SolveError> {
        if t_stop.is_nan() || t_stop < self.time || !t_stop.is_finite() {
            return Err(SolveError::invalid(format!(
                "t_stop = {t_stop} is before the current time {} (only forward integration)",
                self.time
            )));
        }
        let mut steps_taken = 0usize;
        loop {
            let time_before = self.time;
            if let Some(reason) = self.search_pending(system, t_stop)? {
                return Ok(reason);
            }
            // In single-step mode every return covers part of one internal step, so the
            // caller can interpolate its output points in `(previous time, current time]`.
            if single_step && (steps_taken > 0 || self.time > time_before) {
                return Ok(StopReason::InternalStep);
            }
            if steps_taken >= self.max_steps_per_call {
                return Err(SolveError::TooManySteps {
                    time: self.time,
                    max_steps: self.max_steps_per_call,
                });
            }
            self.integrator.step(system, t_stop)?;
            steps_taken += 1;
        }
    }

    /// Searches the part of the last internal step between the output position and
    /// `min(internal time, t_stop)` for roots, and moves the output position.
    fn search_pending(
        &mut self,
        system: &mut dyn System,
        t_stop: f64,
    ) -> Result<Option<StopReason>, SolveError> {
        let internal_time = self.integrator.current_time();
        let t_right = internal_time.min(t_stop);
        if t_right > self.time {
            let dense = self.integrator.dense_output();
            let found = self
                .roots
                .search(system, dense, self.time, t_right, &mut self.driver_stats)
                .map_err(|error| SolveError::Eval {
                    time: t_right,
                    message: format!("root functions: {error}"),
                })?;
            if let Some(root) = found {
                self.time = root.time;
                if root.time == internal_time {
                    self.state.copy_from_slice(self.integrator.state());
                } else {
                    dense.evaluate(root.time, &mut self.state);
                }
                self.driver_stats.events += 1;
                self.reported_at_time = root.components.iter().map(|(i, _)| *i).collect();
                return Ok(Some(StopReason::Root {
                    t: root.time,
                    components: root.components,
                }));
            }
            self.time = t_right;
            self.reported_at_time.clear();
            if t_right == internal_time {
                self.state.copy_from_slice(self.integrator.state());
            } else {
                dense.evaluate(t_right, &mut self.state);
            }
        }
        if self.time >= t_stop {
            return Ok(Some(StopReason::ReachedStop));
        }
        Ok(None)
    }
}
