//! The driver the runtime uses: integrate to an output time without passing it (`t_stop`),
//! stop at zero crossings with the state at the root (left limit), restart after events.
//!
//! The driver keeps an output position `(time, state)` that may lag behind the method's
//! internal time: after a root or an output time inside a step, the next call first searches
//! the rest of that step and only then takes new steps. A step is never taken past the
//! `t_stop` of the current call.
//!
//! A root found well inside a step whose dense output is less accurate than requested
//! (Radau5: its collocation polynomial has the stage order 3 between a step's ends, the
//! step order 5 at the end) is not reported from the dense output: the method takes the
//! step back and steps again to just after the root, and the root is located again on
//! that step, near its end (`Solver::step_to_root`). The state an event starts from then
//! has the method's accuracy. BDF's and Dormand–Prince's interpolants have the order of
//! their steps' error control; they are used as they are.

use crate::bdf::Bdf;
use crate::dopri5::Dopri5;
use crate::error::SolveError;
use crate::integrator::{Initial, Integrator, ProblemSetup};
use crate::linear::LinearSolverKind;
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
    /// Steps taken again to a located root since the last reported root.
    root_steps: usize,
    /// Projection onto the system's invariants after each accepted step (none when the
    /// system declares none).
    projection: Option<Box<Projection>>,
}

/// What the projection needs: the projector and the tolerances its weights come from.
struct Projection {
    projector: crate::project::Projector,
    relative: Vec<f64>,
    absolute: Vec<f64>,
    scratch: Vec<f64>,
}

/// A root located inside a step is reached by taking the step again to it at most this
/// many times in a row (the method's end point is then the state at the root).
const MAX_ROOT_STEPS: usize = 3;

/// A root this close to the start of its step, as a fraction of the step, is taken from
/// the dense output: the interpolant matches the step's start state, so its error grows
/// from zero there (linearly).
const ROOT_MARGIN_START: f64 = 1e-3;

/// The same near the step's end, where the interpolant matches the end state and its
/// derivative (Radau IIA collocates at the end, Dormand–Prince's extension is Hermite
/// there), so its error grows quadratically: one hundredth of the step leaves a ten
/// thousandth of the error inside.
const ROOT_MARGIN_END: f64 = 1e-2;

/// The step taken again ends this fraction of its length after the root located on the
/// discarded dense output, so that the root, moved by the interpolant's error, is still
/// inside it and within [`ROOT_MARGIN_END`] of its end.
const ROOT_STEP_BEYOND: f64 = 1e-3;

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
        let projection = if system.n_invariants() > 0 {
            Some(Box::new(Projection {
                projector: Default::default(),
                relative: options
                    .relative_tolerance
                    .expand(x0.len(), "relative tolerance")?,
                absolute: options
                    .absolute_tolerance
                    .expand(x0.len(), "absolute tolerance")?,
                scratch: Vec::with_capacity(x0.len()),
            }))
        } else {
            None
        };
        let initial = Initial {
            setup: ProblemSetup::new(system, t0, x0, options)?,
            t0,
            x0,
        };
        let integrator: Box<dyn Integrator + Send> = match method.resolved() {
            Method::Dopri5 => Box::new(Dopri5::new(system, initial)?),
            Method::Radau5 => Box::new(Radau5::new(system, initial)?),
            _ => Box::new(Bdf::new(system, initial)?),
        };
        let mut solver = Solver {
            integrator,
            time: t0,
            state: x0.to_vec(),
            roots: RootTracker::new(system.n_roots(), x0.len()),
            reported_at_time: Vec::new(),
            driver_stats: Stats::default(),
            max_steps_per_call,
            root_steps: 0,
            projection,
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
        if let Some(p) = self.projection.as_mut() {
            p.projector.invalidate();
        }
        self.root_steps = 0;
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

    /// The LU of the method's iteration matrices (`None` for explicit methods).
    pub fn linear_solver(&self) -> Option<LinearSolverKind> {
        self.integrator.linear_solver()
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
            self.project_step(system)?;
            steps_taken += 1;
        }
    }

    /// Searches the part of the last internal step between the output position and
    /// `min(internal time, t_stop)` for roots, and moves the output position. A root found
    /// well inside the step is reached by taking the step again to it
    /// ([`Solver::step_to_root`]), and searched for again on that step.
    fn search_pending(
        &mut self,
        system: &mut dyn System,
        t_stop: f64,
    ) -> Result<Option<StopReason>, SolveError> {
        loop {
            let internal_time = self.integrator.current_time();
            let t_right = internal_time.min(t_stop);
            if t_right > self.time {
                self.roots.save();
                let dense = self.integrator.dense_output();
                let found = self
                    .roots
                    .search(system, dense, self.time, t_right, &mut self.driver_stats)
                    .map_err(|error| SolveError::Eval {
                        time: t_right,
                        message: format!("root functions: {error}"),
                    })?;
                if let Some(root) = found {
                    if self.step_to_root(system, root.time, t_right)? {
                        self.roots.restore();
                        continue;
                    }
                    self.root_steps = 0;
                    self.time = root.time;
                    if root.time == internal_time {
                        self.state.copy_from_slice(self.integrator.state());
                    } else {
                        self.integrator
                            .dense_output()
                            .evaluate(root.time, &mut self.state);
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
            return Ok(None);
        }
    }

    /// A root at `t_root` inside the last step `[start, end]`, farther from its ends than
    /// [`ROOT_MARGIN_START`] and [`ROOT_MARGIN_END`] of the step, on a dense output whose
    /// estimated error exceeds the requested tolerance
    /// ([`Integrator::interpolation_error`]): the method takes the step back and steps from
    /// its start to just after `t_root` ([`ROOT_STEP_BEYOND`]; at most to `t_right`), true.
    /// The state at a root is where the event starts from; on the new step the root lies
    /// near the end, where the interpolant is as accurate as the step. False: the root is
    /// taken from the dense output (accurate enough, near an end, after
    /// [`MAX_ROOT_STEPS`] steps to it, or the method cannot take a step back).
    fn step_to_root(
        &mut self,
        system: &mut dyn System,
        t_root: f64,
        t_right: f64,
    ) -> Result<bool, SolveError> {
        let (start, end) = self.integrator.dense_output().interval();
        let inside = t_root - start > ROOT_MARGIN_START * (end - start)
            && end - t_root > ROOT_MARGIN_END * (end - start);
        if !inside
            || self.integrator.interpolation_error() <= 1.0
            || self.root_steps >= MAX_ROOT_STEPS
            || !self.integrator.rewind()
        {
            return Ok(false);
        }
        self.root_steps += 1;
        let beyond = ROOT_STEP_BEYOND * (t_root - start);
        self.integrator
            .step(system, (t_root + beyond).min(t_right))?;
        self.project_step(system)?;
        Ok(true)
    }

    /// Projects the state at the end of the step just taken onto the system's active
    /// invariants and hands the projected state to the method.
    fn project_step(&mut self, system: &mut dyn System) -> Result<(), SolveError> {
        let Some(p) = self.projection.as_mut() else {
            return Ok(());
        };
        let t = self.integrator.current_time();
        p.scratch.clear();
        p.scratch.extend_from_slice(self.integrator.state());
        let moved = p
            .projector
            .project(system, t, &mut p.scratch, &p.relative, &p.absolute)
            .map_err(|error| SolveError::Eval {
                time: t,
                message: format!("invariants: {error}"),
            })?;
        if moved {
            self.integrator.set_projected_state(system, &p.scratch)?;
        }
        Ok(())
    }

    /// Projects `x` at `t` onto the system's active invariants (an event's state, an
    /// interpolated output point), with the weights of the solver's tolerances; true
    /// when `x` moved. Nothing is handed to the method (a reset follows an event).
    pub fn project(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &mut [f64],
    ) -> Result<bool, SolveError> {
        let Some(p) = self.projection.as_mut() else {
            return Ok(false);
        };
        p.projector
            .project(system, t, x, &p.relative, &p.absolute)
            .map_err(|error| SolveError::Eval {
                time: t,
                message: format!("invariants: {error}"),
            })
    }

    /// The projection's counters (`None`: the system has no invariants).
    /// When an explicit method found the problem stiff ([`Integrator::stiff_since`]).
    pub fn stiff_since(&self) -> Option<f64> {
        self.integrator.stiff_since()
    }

    pub fn projection_stats(&self) -> Option<crate::project::ProjectionStats> {
        self.projection.as_ref().map(|p| p.projector.stats.clone())
    }
}
