//! Dormand–Prince 5(4) (Hairer's DOPRI5) for non-stiff ODEs.
//!
//! * Seven stages with FSAL (the last stage is `f` at the new point), fifth-order solution,
//!   embedded fourth-order error estimate `err = h Σ e_i k_i`.
//! * Error norm: `sqrt(mean((err_i / sc_i)^2))`, `sc_i = atol_i + rtol_i max(|x_i|, |x_new_i|)`;
//!   a step is accepted when the norm is at most 1.
//! * Step control: Hairer's PI controller `h_new = h / fac`,
//!   `fac = err^(0.2 - 0.75 β) / err_old^β / 0.9` with `β = 0.04`, the ratio limited to
//!   `[0.2, 10]`; after a rejection the step may not grow.
//! * Dense output: the free continuous extension of order 4 (Hairer's `CONTD5`), exact for
//!   polynomial solutions up to degree 4.
//! * Systems with algebraic rows are refused ([`SolveError::AlgebraicRowsNotSupported`]).

use crate::dense_output::{step_fraction, DenseOutput};
use crate::error::{EvalError, SolveError};
use crate::evaluate::rhs_checked;
use crate::integrator::{
    common_accessors, eval_failure, Aim, Initial, Integrator, ProblemSetup, StepStart,
};
use crate::norm::{weighted_rms, Tolerances};
use crate::options::Method;
use crate::stats::Stats;
use crate::step_control::{clip_to_limit, step_above_floor, step_after_accepted};
use crate::system::System;

/// The Butcher tableau, row by row: stage `i + 2` is evaluated at `t + c h` with the
/// state `x + h Σ_j a_j k_j`; the last row (`c = 1`, FSAL) gives the new state, whose
/// `f` is the seventh stage.
const TABLEAU: [(f64, &[f64]); 6] = [
    (0.2, &[0.2]),
    (0.3, &[3.0 / 40.0, 9.0 / 40.0]),
    (0.8, &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0]),
    (
        8.0 / 9.0,
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
    ),
    (
        1.0,
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
    ),
    (
        1.0,
        &[
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ),
];
/// The error estimate's weights: `err = h Σ e_i k_i`.
const ERROR: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// The dense output's fifth coefficient: `h Σ d_i k_i`.
const DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

const SAFETY: f64 = 0.9;
const BETA: f64 = 0.04;
const MAX_SHRINK_DIVISOR: f64 = 5.0; // h_new >= h / 5
const MAX_GROWTH_DIVISOR: f64 = 0.1; // h_new <= h * 10
const MAX_CONSECUTIVE_FAILURES: usize = 30;

/// Hairer's continuous extension, valid on `[start, end]`.
#[derive(Debug, Clone)]
pub struct Dopri5DenseOutput {
    start: f64,
    end: f64,
    coefficients: [Vec<f64>; 5],
    end_state: Vec<f64>,
}

impl DenseOutput for Dopri5DenseOutput {
    fn interval(&self) -> (f64, f64) {
        (self.start, self.end)
    }

    fn evaluate(&self, t: f64, out: &mut [f64]) {
        let Some(theta) = step_fraction(self.start, self.end, t, self.start) else {
            out.copy_from_slice(&self.end_state);
            return;
        };
        let theta1 = 1.0 - theta;
        let [r1, r2, r3, r4, r5] = &self.coefficients;
        for i in 0..out.len() {
            out[i] = r1[i] + theta * (r2[i] + theta1 * (r3[i] + theta * (r4[i] + theta1 * r5[i])));
        }
    }
}

/// Hairer's stiffness test of DOPRI5 (Hairer, Wanner II, IV.2): after an accepted
/// step, `h |λ| ≈ h ||f(x₁) - f(x₆)|| / ||x₁ - x₆||` from the last two stages, which
/// both sit at the step's end; beyond 3.25 (the edge of the method's stability region
/// on the negative axis) on 15 accepted steps in a row, the step size is limited by
/// stability, not accuracy. Six steps below it start the count again.
#[derive(Debug, Clone, Default)]
struct StiffnessTest {
    above: u32,
    below: u32,
    since: Option<f64>,
}

impl StiffnessTest {
    /// `f` of the new state and of the sixth stage, and the two states.
    fn after_step(&mut self, t: f64, h: f64, f: (&[f64], &[f64]), x: (&[f64], &[f64])) {
        let squared =
            |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(p, q)| (p - q) * (p - q)).sum() };
        let (num, den) = (squared(f.0, f.1), squared(x.0, x.1));
        if den <= 0.0 {
            return;
        }
        if h * (num / den).sqrt() > 3.25 {
            self.below = 0;
            self.above += 1;
            if self.above == 15 && self.since.is_none() {
                self.since = Some(t);
            }
        } else {
            self.below += 1;
            if self.below == 6 {
                self.above = 0;
            }
        }
    }
}

/// The Dormand–Prince 5(4) integrator.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    setup: ProblemSetup,
    start: StepStart,
    step_size: Option<f64>,
    previous_error: f64,
    last_rejected: bool,
    stiffness: StiffnessTest,
    stages: [Vec<f64>; 7],
    stage_state: Vec<f64>,
    x_new: Vec<f64>,
    error_vector: Vec<f64>,
    scale: Vec<f64>,
    dense: Dopri5DenseOutput,
    stats: Stats,
}

impl Dopri5 {
    /// Creates the integrator at `(t0, x0)`; fails for systems with algebraic rows.
    pub(crate) fn new(system: &mut dyn System, initial: Initial<'_>) -> Result<Self, SolveError> {
        let Initial { setup, t0, x0 } = initial;
        if setup.algebraic_rows() > 0 {
            return Err(SolveError::AlgebraicRowsNotSupported {
                method: Method::Dopri5.name(),
                algebraic_rows: setup.algebraic_rows(),
            });
        }
        let size = setup.size;
        let zeros = || vec![0.0; size];
        let mut integrator = Dopri5 {
            setup,
            start: StepStart::new(t0, x0),
            step_size: None,
            previous_error: 1e-4,
            last_rejected: false,
            stiffness: StiffnessTest::default(),
            stages: std::array::from_fn(|_| zeros()),
            stage_state: zeros(),
            x_new: zeros(),
            error_vector: zeros(),
            scale: zeros(),
            dense: Dopri5DenseOutput {
                start: t0,
                end: t0,
                coefficients: std::array::from_fn(|_| zeros()),
                end_state: x0.to_vec(),
            },
            stats: Stats::default(),
        };
        integrator.restart(system, t0, x0)?;
        Ok(integrator)
    }

    fn restart(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError> {
        self.start.move_to(system, (t, x), &mut self.stats)?;
        self.step_size = self.setup.options.initial_step;
        self.previous_error = 1e-4;
        self.last_rejected = false;
        self.dense.start = t;
        self.dense.end = t;
        self.dense.end_state.copy_from_slice(x);
        Ok(())
    }

    /// Computes stages 2..7, the new state and the error vector for step `h`.
    fn attempt(&mut self, system: &mut dyn System, h: f64) -> Result<(), EvalError> {
        let t = self.start.t;
        let size = self.setup.size;
        self.stages[0].copy_from_slice(&self.start.f);
        for (stage, (c, row)) in TABLEAU.iter().enumerate() {
            let last = stage + 1 == TABLEAU.len();
            let state = if last {
                &mut self.x_new
            } else {
                &mut self.stage_state
            };
            for (i, value) in state.iter_mut().enumerate() {
                *value = self.start.x[i] + h * combination(row, &self.stages, i);
            }
            let (_, rest) = self.stages.split_at_mut(stage + 1);
            rhs_checked(system, t + c * h, state, &mut rest[0], &mut self.stats)?;
        }
        for i in 0..size {
            self.error_vector[i] = h * combination(&ERROR, &self.stages, i);
        }
        Ok(())
    }

    fn error_norm(&mut self) -> f64 {
        self.setup
            .tolerances
            .scales_of_pair(&self.start.x, &self.x_new, &mut self.scale);
        Tolerances::guard_zero_scales(&mut self.scale);
        weighted_rms(&self.error_vector, &self.scale)
    }

    /// Stores the continuous extension of the accepted step `[t, t + h]`.
    fn store_dense_output(&mut self, h: f64, t_end: f64) {
        let k = &self.stages;
        let [r1, r2, r3, r4, r5] = &mut self.dense.coefficients;
        for i in 0..self.setup.size {
            let difference = self.x_new[i] - self.start.x[i];
            let spline = h * k[0][i] - difference;
            r1[i] = self.start.x[i];
            r2[i] = difference;
            r3[i] = spline;
            r4[i] = difference - h * k[6][i] - spline;
            r5[i] = h * combination(&DENSE, k, i);
        }
        self.dense.start = self.start.t;
        self.dense.end = t_end;
        self.dense.end_state.copy_from_slice(&self.x_new);
    }
}

impl Integrator for Dopri5 {
    common_accessors!(Method::Dopri5, |s| s.start.t, &s.start.x);

    fn stiff_since(&self) -> Option<f64> {
        self.stiffness.since
    }

    crate::integrator::one_step_method!(4);
}

impl Dopri5 {
    /// [`Integrator::step`] toward `aim.limit`, trying `aim.h` first.
    fn step_from(&mut self, system: &mut dyn System, aim: Aim) -> Result<(), SolveError> {
        let Aim {
            limit: t_limit,
            mut h,
        } = aim;
        let exponent = 0.2 - BETA * 0.75;
        let mut failures = 0usize;
        loop {
            h = step_above_floor(
                h,
                self.start.t,
                failures > 0,
                &self.error_vector,
                &self.scale,
            )?;
            let (h_try, hits_limit) = clip_to_limit(self.start.t, h, t_limit);
            let error = match self.attempt(system, h_try) {
                Ok(()) => self.error_norm(),
                Err(error) => {
                    failures += 1;
                    self.stats.rejected_steps += 1;
                    if failures >= MAX_CONSECUTIVE_FAILURES {
                        return Err(eval_failure(self.start.t, error));
                    }
                    h = 0.25 * h_try;
                    self.last_rejected = true;
                    continue;
                }
            };
            if !error.is_finite() {
                failures += 1;
                self.stats.rejected_steps += 1;
                h = 0.25 * h_try;
                continue;
            }
            let factor_raw = error.powf(exponent);
            if error <= 1.0 {
                let factor = (factor_raw / self.previous_error.powf(BETA) / SAFETY)
                    .clamp(MAX_GROWTH_DIVISOR, MAX_SHRINK_DIVISOR);
                let h_new = step_after_accepted(
                    h_try / factor,
                    (h_try, h),
                    (self.last_rejected, hits_limit),
                    self.setup.options.max_step,
                );
                self.previous_error = error.max(1e-4);
                let t_end = if hits_limit {
                    t_limit
                } else {
                    self.start.t + h_try
                };
                self.stiffness.after_step(
                    t_end,
                    h_try,
                    (&self.stages[6], &self.stages[5]),
                    (&self.x_new, &self.stage_state),
                );
                self.store_dense_output(h_try, t_end);
                self.start.t = t_end;
                self.start.x.copy_from_slice(&self.x_new);
                self.start.f.copy_from_slice(&self.stages[6]);
                self.stats.steps += 1;
                self.last_rejected = false;
                self.step_size = Some(h_new);
                return Ok(());
            }
            self.stats.rejected_steps += 1;
            self.last_rejected = true;
            h = h_try / (factor_raw / SAFETY).min(MAX_SHRINK_DIVISOR);
        }
    }

    /// The step's end moved by a projection to `x`: the dense output gets the correction
    /// `θ Δ` (`Δ` at the step's end, 0 at its start).
    fn project_dense_output(&mut self, x: &[f64]) {
        for i in 0..x.len() {
            self.dense.coefficients[1][i] += x[i] - self.start.x[i];
        }
        self.dense.end_state.copy_from_slice(x);
    }
}

/// `Σ_j weights_j k_j[i]`, over the stages `k` the weights reach.
fn combination(weights: &[f64], k: &[Vec<f64>], i: usize) -> f64 {
    weights.iter().zip(k).map(|(w, k)| w * k[i]).sum()
}
