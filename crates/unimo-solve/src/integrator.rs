//! The interface every method implements: take one accepted step without passing a limit,
//! expose the dense output of that step, restart from a given state.

use crate::dense_output::DenseOutput;
use crate::error::SolveError;
use crate::evaluate::rhs_checked;
use crate::linear::LinearSolverKind;
use crate::options::Method;
use crate::stats::Stats;
use crate::step_control::{initial_step, InitialStepProblem};
use crate::system::System;

/// One integration method (BDF, Radau5, Dormand–Prince) driven step by step.
///
/// [`Solver`](crate::Solver) builds on this: it adds output times, `t_stop` and root location.
pub trait Integrator {
    /// The method this integrator implements.
    fn method(&self) -> Method;

    /// Time of the last accepted step's end (the initial time before the first step).
    fn current_time(&self) -> f64;

    /// State at [`current_time`](Integrator::current_time).
    fn state(&self) -> &[f64];

    /// Takes one accepted step (retrying with smaller steps as needed) that ends at or before
    /// `t_limit`; it ends exactly on `t_limit` when the step-size control reaches it.
    fn step(&mut self, system: &mut dyn System, t_limit: f64) -> Result<(), SolveError>;

    /// The continuous solution on the last accepted step.
    fn dense_output(&self) -> &dyn DenseOutput;

    /// Restarts at `(t, x)`: history dropped (BDF back to order 1, Radau fresh), new initial
    /// step. `x` may differ from the current state (event changes).
    fn reset(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError>;

    /// Replaces the state at [`current_time`](Integrator::current_time) by `x`, a
    /// projection of it onto the system's invariants ([`crate::project`]), keeping the
    /// step size, order and history: the method continues as if its last step had
    /// ended at `x` (BDF: the step's correction is changed by `x - state`, as CVODE
    /// does with its projection's correction; one-step methods: `f` at the new state).
    fn set_projected_state(&mut self, system: &mut dyn System, x: &[f64])
        -> Result<(), SolveError>;

    /// Takes back the last accepted step: the method returns to that step's start, with the
    /// step size and history it had there, so that the step can be taken again to an
    /// earlier end (a root located inside it). False, with nothing changed, when the method
    /// cannot or there is no step to take back (none since the last restart, or already
    /// taken back).
    fn rewind(&mut self) -> bool {
        false
    }

    /// Estimated error of the dense output between the last step's ends, in units of the
    /// requested tolerance: above 1, a root inside the step is better reached by
    /// [`rewind`](Integrator::rewind) and a step to it. Zero for methods whose
    /// interpolant has the order of their steps' error control (BDF's polynomial through
    /// its history, Dormand–Prince's extension against its embedded estimate).
    fn interpolation_error(&self) -> f64 {
        0.0
    }

    /// The time from which the problem looked stiff to an explicit method (Hairer's
    /// test in DOPRI5: `h |λ| > 3.25` estimated on 15 accepted steps in a row), `None`
    /// for implicit methods and while it did not.
    fn stiff_since(&self) -> Option<f64> {
        None
    }

    /// The LU of the iteration matrices, `None` for explicit methods.
    fn linear_solver(&self) -> Option<LinearSolverKind> {
        None
    }

    /// Work counters.
    fn stats(&self) -> &Stats;

    /// Changes the largest step from the next step on (e.g. while a stiff contact lasts).
    fn set_max_step(&mut self, h: f64);
}

/// The [`Integrator`] functions that only read or set common fields (`dense`, `stats`,
/// `setup`), one definition for every method: `$time` and `$state` are the current time
/// and state of `self` named `$s`.
macro_rules! common_accessors {
    ($method:expr, |$s:ident| $time:expr, $state:expr) => {
        fn method(&self) -> Method {
            $method
        }

        fn current_time(&self) -> f64 {
            let $s = self;
            $time
        }

        fn state(&self) -> &[f64] {
            let $s = self;
            $state
        }

        fn dense_output(&self) -> &dyn DenseOutput {
            &self.dense
        }

        fn stats(&self) -> &Stats {
            &self.stats
        }

        fn set_max_step(&mut self, h: f64) {
            self.setup.options.max_step = h;
        }
    };
}
pub(crate) use common_accessors;

/// A step's aim: the time it does not pass and the step size tried first.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Aim {
    pub limit: f64,
    pub h: f64,
}

/// [`Integrator::step`], [`Integrator::reset`] and [`Integrator::set_projected_state`]
/// of a one-step method, one definition for Dormand–Prince and Radau5: `$order` is the
/// order of its local error (for a first step's estimate). The method keeps a
/// [`StepStart`] `start`, its next step size `step_size` (`None` after a restart without
/// a given initial step), and provides `step_from(system, aim)` (one accepted
/// step toward `aim.limit`, trying `aim.h` first), `restart(system, t, x)` and
/// `project_dense_output(x)`. A projection moves the next step's start to the projected
/// state, with `f` evaluated again; the step size and the controller's memory are kept,
/// and when the dense output ends there it gets the method's correction (before `start`
/// moves).
macro_rules! one_step_method {
    ($order:expr) => {
        fn step(&mut self, system: &mut dyn System, t_limit: f64) -> Result<(), SolveError> {
            let (start, stats) = (&self.start, &mut self.stats);
            match start.step_size(
                self.step_size,
                (&self.setup, $order),
                system,
                t_limit,
                stats,
            )? {
                Some(h) => self.step_from(system, $crate::integrator::Aim { limit: t_limit, h }),
                None => Ok(()),
            }
        }

        fn reset(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError> {
            self.setup.check_len(x)?;
            self.restart(system, t, x)
        }

        fn set_projected_state(
            &mut self,
            system: &mut dyn System,
            x: &[f64],
        ) -> Result<(), SolveError> {
            self.setup.check_len(x)?;
            if self.dense.end == self.start.t {
                self.project_dense_output(x);
            }
            let t = self.start.t;
            self.start.move_to(system, (t, x), &mut self.stats)
        }
    };
}
pub(crate) use one_step_method;

/// What an integrator's constructor starts from: the validated setup and the consistent
/// point `(t0, x0)` ([`crate::Solver::new`] builds it once for whichever method it creates).
pub(crate) struct Initial<'a> {
    pub setup: ProblemSetup,
    pub t0: f64,
    pub x0: &'a [f64],
}

/// What every method needs from the problem, checked once at construction.
#[derive(Debug, Clone)]
pub(crate) struct ProblemSetup {
    pub size: usize,
    pub differential: Vec<bool>,
    pub tolerances: crate::norm::Tolerances,
    pub options: crate::options::Options,
}

impl ProblemSetup {
    /// Validates sizes, tolerances, options and the initial point.
    pub fn new(
        system: &dyn System,
        t0: f64,
        x0: &[f64],
        options: crate::options::Options,
    ) -> Result<Self, SolveError> {
        options.validate()?;
        let size = system.len();
        let differential = system.differential().to_vec();
        if differential.len() != size || x0.len() != size {
            return Err(SolveError::invalid(format!(
                "system has {size} unknowns, {} differential flags and {} initial values",
                differential.len(),
                x0.len()
            )));
        }
        if !t0.is_finite() {
            return Err(SolveError::invalid(format!(
                "initial time {t0} is not finite"
            )));
        }
        if let Some(i) = x0.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::invalid(format!(
                "initial value x[{i}] = {} is not finite",
                x0[i]
            )));
        }
        let relative = options
            .relative_tolerance
            .expand(size, "relative tolerance")?;
        let absolute = options
            .absolute_tolerance
            .expand(size, "absolute tolerance")?;
        if let Some(i) = (0..size).find(|&i| relative[i] == 0.0 && absolute[i] == 0.0) {
            return Err(SolveError::invalid(format!(
                "component {i} has zero relative and absolute tolerance"
            )));
        }
        Ok(ProblemSetup {
            size,
            differential,
            tolerances: crate::norm::Tolerances { relative, absolute },
            options,
        })
    }

    /// The inputs of [`initial_step`](crate::step_control::initial_step) for a first
    /// step from `(t0, x0)`, `f0 = f(t0, x0)`, towards `t_limit` by a method whose local
    /// error has order `order`.
    pub fn initial_step_problem<'a>(
        &'a self,
        t0: f64,
        x0: &'a [f64],
        f0: &'a [f64],
        order: u32,
        t_limit: f64,
    ) -> InitialStepProblem<'a> {
        InitialStepProblem {
            t0,
            x0,
            f0,
            differential: &self.differential,
            tolerances: &self.tolerances,
            order,
            max_step: self.options.max_step,
            span: t_limit - t0,
        }
    }

    /// Refuses a state of another length than the problem's (a reset's new state).
    pub fn check_len(&self, x: &[f64]) -> Result<(), SolveError> {
        if x.len() != self.size {
            return Err(SolveError::invalid("reset state has the wrong length"));
        }
        Ok(())
    }

    /// Number of algebraic rows.
    pub fn algebraic_rows(&self) -> usize {
        self.differential.iter().filter(|d| !**d).count()
    }
}

/// Where a one-step method's next step starts: the time, the state and `f` there (the
/// first stage of the next step). Dormand–Prince and Radau5 keep one; BDF starts from its
/// history instead.
#[derive(Debug, Clone)]
pub(crate) struct StepStart {
    pub t: f64,
    pub x: Vec<f64>,
    /// `f(t, x)`.
    pub f: Vec<f64>,
}

impl StepStart {
    /// At `(t0, x0)`, `f` not evaluated yet (zero): [`move_to`](Self::move_to) before
    /// the first step.
    pub fn new(t0: f64, x0: &[f64]) -> StepStart {
        StepStart {
            t: t0,
            x: x0.to_vec(),
            f: vec![0.0; x0.len()],
        }
    }

    /// The size of the next step from here toward `t_limit`, at most the largest step:
    /// the method's `step_size`, or when it has none (after a restart without a given
    /// initial step) the estimate of [`initial_step`] for a method whose local error has
    /// order `order` (its evaluations counted in `stats`). `None` when `t_limit` is not
    /// ahead: no step to take.
    pub fn step_size(
        &self,
        step_size: Option<f64>,
        (setup, order): (&ProblemSetup, u32),
        system: &mut dyn System,
        t_limit: f64,
        stats: &mut Stats,
    ) -> Result<Option<f64>, SolveError> {
        if t_limit <= self.t {
            return Ok(None);
        }
        let h = match step_size {
            Some(step) => step,
            None => {
                let problem = setup.initial_step_problem(self.t, &self.x, &self.f, order, t_limit);
                initial_step(&problem, system, stats)?
            }
        };
        Ok(Some(h.min(setup.options.max_step)))
    }

    /// Moves to `(t, x)` and evaluates `f` there (counted in `stats`).
    pub fn move_to(
        &mut self,
        system: &mut dyn System,
        (t, x): (f64, &[f64]),
        stats: &mut Stats,
    ) -> Result<(), SolveError> {
        self.t = t;
        self.x.copy_from_slice(x);
        rhs_checked(system, t, x, &mut self.f, stats).map_err(|error| eval_failure(t, error))
    }
}

/// Converts a failed evaluation at a point that cannot be retried into a [`SolveError`].
pub(crate) fn eval_failure(time: f64, error: crate::error::EvalError) -> SolveError {
    SolveError::Eval {
        time,
        message: error.to_string(),
    }
}
