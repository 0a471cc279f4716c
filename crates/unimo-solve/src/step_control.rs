//! Step-size helpers shared by the methods: Hairer's initial step selection, the smallest
//! admissible step at a given time, the bound that keeps a step from passing `t_limit` and
//! the step after an accepted one.

use crate::error::{EvalError, SolveError};
use crate::evaluate::rhs_checked;
use crate::norm::{worst_components, Tolerances};
use crate::stats::Stats;
use crate::system::System;

/// Smallest step allowed at time `t` (a few ulps of `t`).
pub(crate) fn minimum_step(t: f64) -> f64 {
    16.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE.sqrt())
}

/// The step to try at `t`: `step`, raised to [`minimum_step`] when no attempt of this
/// call has failed yet (a step chosen at the floor, e.g. the first step after an event
/// from a state near zero, stays legal as `t` and with it the floor grows);
/// [`SolveError::StepSizeTooSmall`] naming the worst components of `errors` over `scale`
/// when failures have pushed it below the floor (the step size collapsed).
pub(crate) fn step_above_floor(
    step: f64,
    t: f64,
    failed: bool,
    errors: &[f64],
    scale: &[f64],
) -> Result<f64, SolveError> {
    let floor = minimum_step(t);
    if step >= floor {
        Ok(step)
    } else if !failed {
        Ok(floor)
    } else {
        Err(SolveError::StepSizeTooSmall {
            time: t,
            step,
            worst: worst_components(errors, scale),
        })
    }
}

/// Shortens `step` so that `t + step` does not pass `t_limit`; returns the step and whether it
/// ends exactly on `t_limit`. A step that would leave a sliver shorter than a tiny fraction of
/// itself before `t_limit` is stretched to end on it.
pub(crate) fn clip_to_limit(t: f64, step: f64, t_limit: f64) -> (f64, bool) {
    let remaining = t_limit - t;
    if step >= remaining * (1.0 - 1e-12) || remaining - step < minimum_step(t_limit) {
        (remaining, true)
    } else {
        (step, false)
    }
}

/// The step after an accepted step `h_try` of a one-step method: the controller's
/// `proposal`, at most `max_step`; no larger than `h_try` after a rejection
/// (`last_rejected`); and when the step was only cut to end on its limit (`hits_limit`,
/// `planned > h_try`), at least the `planned` step (at most `max_step`) again.
pub(crate) fn step_after_accepted(
    proposal: f64,
    (h_try, planned): (f64, f64),
    (last_rejected, hits_limit): (bool, bool),
    max_step: f64,
) -> f64 {
    let mut h_next = proposal.min(max_step);
    if last_rejected {
        h_next = h_next.min(h_try);
    }
    if hits_limit && planned > h_try {
        h_next = h_next.max(planned.min(max_step));
    }
    h_next
}

/// Inputs of [`initial_step`].
pub(crate) struct InitialStepProblem<'a> {
    pub t0: f64,
    pub x0: &'a [f64],
    /// `f(t0, x0)`.
    pub f0: &'a [f64],
    pub differential: &'a [bool],
    pub tolerances: &'a Tolerances,
    /// Order of the local error (`err ~ h^(order + 1)`).
    pub order: u32,
    pub max_step: f64,
    /// Distance to the first output time (bounds the step).
    pub span: f64,
}

/// Hairer's `HINIT` (Hairer, Nørsett, Wanner I, II.4) on the differential components: an
/// explicit Euler step of size `h0 = 0.01 ||x0|| / ||f0||` estimates the second derivative,
/// then `h = min(100 h0, (0.01 / max(||f0||, ||f''||))^(1/(order+1)))`.
/// Algebraic components are held fixed in the Euler step and left out of the norms.
pub(crate) fn initial_step(
    problem: &InitialStepProblem<'_>,
    system: &mut dyn System,
    stats: &mut Stats,
) -> Result<f64, SolveError> {
    let size = problem.x0.len();
    let scale: Vec<f64> = (0..size)
        .map(|i| {
            problem
                .tolerances
                .scale(i, problem.x0[i].abs())
                .max(f64::MIN_POSITIVE)
        })
        .collect();
    let norm_of = |values: &dyn Fn(usize) -> f64| -> f64 {
        (0..size)
            .filter(|&i| problem.differential[i])
            .map(|i| (values(i) / scale[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let bound = problem.max_step.min(problem.span.abs());
    let x_norm = norm_of(&|i| problem.x0[i]);
    let f_norm = norm_of(&|i| problem.f0[i]);
    let mut step = if x_norm <= 1e-5 || f_norm <= 1e-5 {
        1e-6
    } else {
        0.01 * x_norm / f_norm
    };
    step = step.min(bound);
    let mut x1 = problem.x0.to_vec();
    for i in (0..size).filter(|&i| problem.differential[i]) {
        x1[i] += step * problem.f0[i];
    }
    let mut f1 = vec![0.0; size];
    let second_derivative_norm = match rhs_checked(system, problem.t0 + step, &x1, &mut f1, stats) {
        Ok(()) => norm_of(&|i| f1[i] - problem.f0[i]) / step,
        Err(EvalError::Domain { .. } | EvalError::Failed { .. }) => f64::INFINITY,
    };
    let largest = second_derivative_norm.max(f_norm);
    let proposal = if largest <= 1e-15 {
        (step * 1e-3).max(1e-6)
    } else if largest.is_finite() {
        (0.01 / largest).powf(1.0 / f64::from(problem.order + 1))
    } else {
        step * 1e-3
    };
    let step = (100.0 * step).min(proposal).min(bound);
    Ok(step.max(minimum_step(problem.t0)))
}
