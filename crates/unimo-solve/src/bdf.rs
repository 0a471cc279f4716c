//! Variable-step, variable-order BDF (orders 1–5) in the fixed-leading-coefficient form of
//! DASSL/IDA, applied to `M x' = f(t, x)` written as the residual `G = M x' - f(t, x) = 0`.
//!
//! * History: modified divided differences `φ_0 … φ_k` with the step ratios `ψ_j`, so
//!   changing the step size needs no interpolation. Predictor: `x_p = Σ φ_j`,
//!   `x_p' = Σ γ_j φ_j`; corrector: `x = x_p + e`, `x' = x_p' + c_j e` with
//!   `c_j = -α_s / h`, `α_s = -Σ_{j≤k} 1/j`.
//! * Newton on `G(e) = 0` with the iteration matrix `c_j M - J` (dense LU, ours below 32
//!   unknowns and faer's above, or faer's sparse LU), at most four iterations, converged
//!   when `s ||δ|| ≤ 0.33` (`s = ρ / (1 - ρ)` from the observed rate `ρ`). The LU is
//!   refactored when `c_j` moved by more than the ratio `[0.6, 1.67]` since the
//!   factorization (in between, corrections are scaled by `2 / (1 + c_j / c_j,old)`); the
//!   Jacobian is re-evaluated only after a convergence failure with a stale Jacobian or
//!   when it is 50 steps old.
//! * Local error test: `C ||e|| ≤ 1` with `C = max(|α_k + α_s - α_0|, α_k)` in the weighted RMS
//!   norm with weights `1 / (rtol_i |x_i| + atol_i)` taken at the start of the step. Algebraic
//!   components are included unless `suppress_algebraic_error` is set (IDA's `suppressalg`).
//! * Order and step selection as IDA: the start-up phase raises the order and doubles the
//!   step each step until a failure, an order decrease or the maximum order; afterwards the
//!   order is lowered, kept or raised from the error estimates at orders `k-1`, `k`, `k+1`
//!   (raising needs `k+1` steps of constant size) and the step ratio is
//!   `r = (2 err + 1e-4)^(-1/(k+1))`. Two differences. The step grows by `min(r, 2)` as
//!   soon as `r ≥ 1/0.6` (IDA doubles only when `r ≥ 2`); below 1 it shrinks by `r`
//!   limited to `[0.5, 0.9]`, in between it is kept. IDA's band lets each step's error
//!   sit anywhere between `2^-(k+2)` and 0.5 of the tolerance (0.008 at order 5); with
//!   `1/0.6` it is `[0.5 · 0.6^(k+1), 0.5]` (0.023 at order 5), and a growth refactors
//!   the iteration matrix as a doubling does (`c_j` leaves `[0.6, 1/0.6]`). And at orders 3–5
//!   the step grows only after `k+1` steps of constant size and order. Growing at
//!   every step, which IDA does while the error estimate is tiny (a polynomial solution),
//!   is not zero-stable there: with steps 2, 4, 8, … the fixed-leading-coefficient formulas
//!   multiply rounding errors by about 4, 12 and 33 per step at orders 3, 4 and 5 (power
//!   iteration of the recurrence for `x' = 0`; zero-stable for constant ratios below about
//!   1.42, 1.21, 1.11). Measured on the bouncing ball: flights at order 3 with ten
//!   doublings in a row grew rounding to 6e-8 m.
//!   Failures: error test (order down, `h` times 0.25–0.9), Newton or evaluation failure (`h`
//!   times 0.25); ten failures in a row end the integration.
//! * Tolerance calibration: the error test and the Newton test use `rtol / 100` and
//!   `atol / 100` for the differential rows (`rtol` not below `100 ε`, nor below the
//!   requested value; algebraic rows as requested), so that a given
//!   `rtol` buys the global error Radau5's transformed tolerances buy. IDA's test holds
//!   the local error of each step to `rtol`, and over the run the global error came out
//!   1.0–1.9 digits larger than Radau5's at the same `rtol` (per-problem medians over the
//!   oscillator, ROBER, HIRES, VDPOL at rtol 1e-4 to 1e-10); the factor 100 brings the
//!   median difference over those problems and POLLU to +0.2 digits (docs/backend.md,
//!   section 7). It moves each run along the work-precision curve, not the curve.
//! * Start and restart (after every event): `x'(t0)` of differential rows is `f`; for
//!   algebraic rows it comes from differentiating the constraints,
//!   `J_aa x_a' = -(J_ad x_d' + ∂f_a/∂t)` (finite differences in `t`); when that block is
//!   singular they start from zero. The first step `h` is Hairer's estimate for an order-1
//!   start; IDA's bound `||h x'(t0)|| <= 0.5` applies only when the algebraic derivatives
//!   could not be computed (with an exact `x'(t0)` it is not needed, and at tight tolerances
//!   on a fast solution it fell below the smallest step). The integration then starts at
//!   order 2 from the Taylor quadratic `x0 + s x'(t0) + s^2 x''(t0)/2`: `x''(t0)` of the
//!   differential rows is the difference quotient of `f` along `(1, x'(t0))` over `h`
//!   (algebraic rows: zero), and the history is that quadratic at the fictitious points
//!   `t0 - h`, `t0 - 2h` (`φ_2 = h^2 x''`, `φ_1 = h x' - φ_2 / 2`, `ψ = (h, 2h)`). The start
//!   is exact on quadratics (free flight; with IDA's order-1 start the bouncing ball's height
//!   drifted by up to 7e-14 m per flight). Without `x''(t0)` (`f` fails there, or
//!   `max_order` 1) it starts at order 1 with `φ_1 = h x'(t0)`.
//! * Dense output: IDA's interpolating polynomial of degree `k_used` through the history,
//!   valid on `[t_n - h_used, t_n]`.

use crate::dense_output::DenseOutput;
use crate::error::{EvalError, SolveError};
use crate::evaluate::rhs_checked;
use crate::integrator::{common_accessors, eval_failure, Initial, Integrator, ProblemSetup};
use crate::jacobian::JacobianEvaluator;
use crate::linear::{iteration_lu, use_sparse, LinearSolverKind, ShiftedLu};
use crate::norm::{weighted_rms, weighted_rms_masked, worst_components, Tolerances};
use crate::options::Method;
use crate::stats::Stats;
use crate::step_control::{clip_to_limit, initial_step, minimum_step, step_above_floor};
use crate::system::System;

const MAX_ORDER: usize = 5;
const MAX_NEWTON_ITERATIONS: usize = 4;
const NEWTON_TOLERANCE: f64 = 0.33;
const MAX_RATE: f64 = 0.9;
const CJ_RATIO_LOW: f64 = 0.6;
const CJ_RATIO_HIGH: f64 = 1.0 / 0.6;
const MAX_JACOBIAN_AGE: usize = 50;
const MAX_ERROR_TEST_FAILURES: usize = 10;
const MAX_NEWTON_FAILURES: usize = 10;
/// The step grows when it could grow by at least this ratio (IDA: 2): the ratio at which
/// `c_j` leaves the range of the factored matrix, so that a growth costs the one
/// factorization IDA's doubling costs (a smaller growth keeps the old matrix and costs
/// Newton iterations: 1.2 took 7 % more evaluations at equal accuracy, ROBER up to 41 %).
const GROWTH_THRESHOLD: f64 = CJ_RATIO_HIGH;
/// The largest growth of the step after a successful step.
const MAX_GROWTH: f64 = 2.0;
/// The requested tolerances are divided by this before use (see the module's notes).
const TOLERANCE_DIVISOR: f64 = 100.0;
/// The calibrated relative tolerance is not taken below this (unless requested).
const SMALLEST_RELATIVE_TOLERANCE: f64 = 100.0 * f64::EPSILON;

/// IDA's interpolating polynomial of the last step.
#[derive(Debug, Clone)]
pub struct BdfDenseOutput {
    end: f64,
    step_used: f64,
    order_used: usize,
    psi: [f64; MAX_ORDER + 1],
    phi: Vec<Vec<f64>>,
}

impl DenseOutput for BdfDenseOutput {
    fn interval(&self) -> (f64, f64) {
        (self.end - self.step_used, self.end)
    }

    fn evaluate(&self, t: f64, out: &mut [f64]) {
        out.copy_from_slice(&self.phi[0]);
        if t == self.end || self.order_used == 0 {
            return;
        }
        let delta = t - self.end;
        let mut c = 1.0;
        let mut gamma = delta / self.psi[0];
        for j in 1..=self.order_used {
            c *= gamma;
            gamma = (delta + self.psi[j - 1]) / self.psi[j];
            for (value, difference) in out.iter_mut().zip(&self.phi[j]) {
                *value += c * difference;
            }
        }
    }
}

/// Why a corrector solve failed.
enum CorrectorFailure {
    Convergence,
    Singular,
    Eval(EvalError),
}

/// Error estimates of one step at orders k, k-1, k-2.
#[derive(Debug, Clone, Copy, Default)]
struct ErrorEstimates {
    at_order: f64,
    at_order_minus_1: f64,
    new_order: usize,
    passed: bool,
}

/// The variable-order BDF integrator.
pub struct Bdf {
    setup: ProblemSetup,
    max_order: usize,
    t: f64,
    started: bool,
    phi: Vec<Vec<f64>>,
    psi: [f64; MAX_ORDER + 1],
    alpha: [f64; MAX_ORDER + 1],
    beta: [f64; MAX_ORDER + 1],
    sigma: [f64; MAX_ORDER + 1],
    gamma: [f64; MAX_ORDER + 1],
    order: usize,
    order_used: usize,
    h: f64,
    h_used: f64,
    constant_steps: usize,
    startup_phase: bool,
    steps_since_start: usize,
    cj: f64,
    cj_last: f64,
    cj_factored: f64,
    error_constant: f64,
    convergence_rate: f64,
    jacobian: JacobianEvaluator,
    jacobian_valid: bool,
    jacobian_age: usize,
    lu: ShiftedLu<f64>,
    lu_valid: bool,
    y: Vec<f64>,
    yp: Vec<f64>,
    y_pred: Vec<f64>,
    yp_pred: Vec<f64>,
    correction: Vec<f64>,
    delta: Vec<f64>,
    /// Scratch for the error estimates at neighbouring orders (no allocation per step).
    difference: Vec<f64>,
    f_value: Vec<f64>,
    scale: Vec<f64>,
    error_mask: Vec<bool>,
    dense: BdfDenseOutput,
    stats: Stats,
}

impl Bdf {
    /// Creates the integrator at the consistent point `(t0, x0)`.
    pub(crate) fn new(system: &mut dyn System, initial: Initial<'_>) -> Result<Self, SolveError> {
        let Initial { mut setup, t0, x0 } = initial;
        calibrate_tolerances(&mut setup.tolerances, &setup.differential);
        let size = setup.size;
        let sparse = use_sparse(system, setup.options.linear_solver);
        let lu = iteration_lu(system, setup.options.linear_solver);
        let error_mask = if setup.options.suppress_algebraic_error {
            setup.differential.clone()
        } else {
            vec![true; size]
        };
        let zeros = || vec![0.0; size];
        let mut phi: Vec<Vec<f64>> = (0..MAX_ORDER + 2).map(|_| zeros()).collect();
        phi[0].copy_from_slice(x0);
        Ok(Bdf {
            max_order: setup.options.max_order,
            jacobian: JacobianEvaluator::new(system, sparse && system.sparsity().is_some()),
            setup,
            t: t0,
            started: false,
            phi,
            psi: [0.0; MAX_ORDER + 1],
            alpha: [0.0; MAX_ORDER + 1],
            beta: [0.0; MAX_ORDER + 1],
            sigma: [0.0; MAX_ORDER + 1],
            gamma: [0.0; MAX_ORDER + 1],
            order: 1,
            order_used: 0,
            h: 0.0,
            h_used: 0.0,
            constant_steps: 0,
            startup_phase: true,
            steps_since_start: 0,
            cj: 0.0,
            cj_last: 0.0,
            cj_factored: 0.0,
            error_constant: 1.0,
            convergence_rate: 20.0,
            jacobian_valid: false,
            jacobian_age: 0,
            lu,
            lu_valid: false,
            y: zeros(),
            yp: zeros(),
            y_pred: zeros(),
            yp_pred: zeros(),
            correction: zeros(),
            delta: zeros(),
            difference: zeros(),
            f_value: zeros(),
            scale: zeros(),
            error_mask,
            dense: BdfDenseOutput {
                end: t0,
                step_used: 0.0,
                order_used: 0,
                psi: [1.0; MAX_ORDER + 1],
                phi: vec![x0.to_vec()],
            },
            stats: Stats::default(),
        })
    }

    /// Start at the current `(t, φ_0)`: `x'(t)`, first step, order-2 Taylor history.
    fn start(&mut self, system: &mut dyn System, t_limit: f64) -> Result<(), SolveError> {
        let t = self.t;
        let x = self.phi[0].clone();
        rhs_checked(system, t, &x, &mut self.f_value, &mut self.stats)
            .map_err(|error| eval_failure(t, error))?;
        self.update_scale();
        self.jacobian_valid = false;
        self.lu_valid = false;
        let mut derivative = self.f_value.clone();
        for (value, differential) in derivative.iter_mut().zip(&self.setup.differential) {
            if !differential {
                *value = 0.0;
            }
        }
        let consistent = self.setup.algebraic_rows() == 0
            || self.algebraic_derivatives(system, &x, &mut derivative)?;
        let taylor = self.max_order >= 2;
        let mut h = match self.setup.options.initial_step {
            Some(step) => step,
            None => {
                let problem = self
                    .setup
                    .initial_step_problem(t, &x, &self.f_value, 1, t_limit);
                initial_step(&problem, system, &mut self.stats)?
            }
        };
        // IDA's bound on an automatic first step, ||h x'(t0)|| <= 0.5, guards against an
        // inaccurate x'(t0): only when the algebraic derivatives could not be computed.
        let derivative_norm = weighted_rms(&derivative, &self.scale);
        if self.setup.options.initial_step.is_none() && !consistent && derivative_norm * h > 0.5 {
            h = 0.5 / derivative_norm;
        }
        h = h.min(self.setup.options.max_step).max(minimum_step(t));
        let second = if taylor {
            self.second_derivative(system, &x, &derivative, h)
        } else {
            None
        };
        match second {
            Some(second) => {
                // Taylor start at order 2: history of the quadratic x0 + s x' + s^2 x''/2 at
                // the fictitious points t - h, t - 2h.
                for i in 0..self.setup.size {
                    self.phi[2][i] = h * h * second[i];
                    self.phi[1][i] = h * derivative[i] - 0.5 * self.phi[2][i];
                }
                self.psi[0] = h;
                self.psi[1] = 2.0 * h;
                self.order = 2;
            }
            None => {
                for (target, value) in self.phi[1].iter_mut().zip(&derivative) {
                    *target = h * value;
                }
                self.psi[0] = h;
                self.order = 1;
            }
        }
        self.h = h;
        self.order_used = 0;
        self.h_used = 0.0;
        self.constant_steps = 0;
        self.startup_phase = true;
        self.steps_since_start = 0;
        self.cj = 0.0;
        self.cj_last = 0.0;
        self.convergence_rate = 20.0;
        self.started = true;
        Ok(())
    }

    /// `x''(t)` of the differential rows by a difference quotient of `f` along `(1, x')` over
    /// `delta` (zero for algebraic rows); `None` when `f` cannot be evaluated there.
    fn second_derivative(
        &mut self,
        system: &mut dyn System,
        x: &[f64],
        derivative: &[f64],
        delta: f64,
    ) -> Option<Vec<f64>> {
        let t = self.t;
        let shifted: Vec<f64> = x
            .iter()
            .zip(derivative)
            .map(|(value, slope)| value + delta * slope)
            .collect();
        let mut f_later = vec![0.0; self.setup.size];
        rhs_checked(system, t + delta, &shifted, &mut f_later, &mut self.stats).ok()?;
        let second: Vec<f64> = (0..self.setup.size)
            .map(|i| {
                if self.setup.differential[i] {
                    (f_later[i] - self.f_value[i]) / delta
                } else {
                    0.0
                }
            })
            .collect();
        second.iter().all(|v| v.is_finite()).then_some(second)
    }

    /// Algebraic parts of `x'(t)` from the differentiated constraints (zero when singular).
    fn algebraic_derivatives(
        &mut self,
        system: &mut dyn System,
        x: &[f64],
        derivative: &mut [f64],
    ) -> Result<bool, SolveError> {
        let t = self.t;
        self.jacobian
            .evaluate(system, t, x, &self.f_value, &self.scale, &mut self.stats)
            .map_err(|error| eval_failure(t, error))?;
        self.jacobian_valid = true;
        self.jacobian_age = 0;
        let time_step = f64::EPSILON.sqrt() * t.abs().max(1.0);
        let mut f_later = vec![0.0; self.setup.size];
        if rhs_checked(system, t + time_step, x, &mut f_later, &mut self.stats).is_err() {
            return Ok(false);
        }
        let mut constraint_matrix = self.jacobian.matrix().clone();
        constraint_matrix.zero_rows(&self.setup.differential);
        let mut lu = match constraint_matrix.pattern() {
            Some(pattern) => ShiftedLu::<f64>::sparse(pattern),
            None => ShiftedLu::<f64>::dense(self.setup.size),
        };
        self.stats.lu_factorizations += 1;
        if lu
            .factor(&constraint_matrix, &self.setup.differential, 1.0)
            .is_err()
        {
            return Ok(false);
        }
        // Rows: differential z_d = x_d'; algebraic -J_ad z_d - J_aa z_a = df_a/dt.
        let mut rhs: Vec<f64> = (0..self.setup.size)
            .map(|i| {
                if self.setup.differential[i] {
                    derivative[i]
                } else {
                    (f_later[i] - self.f_value[i]) / time_step
                }
            })
            .collect();
        lu.solve(&mut rhs);
        if !rhs.iter().all(|v| v.is_finite()) {
            return Ok(false);
        }
        for i in (0..self.setup.size).filter(|&i| !self.setup.differential[i]) {
            derivative[i] = rhs[i];
        }
        Ok(true)
    }

    fn update_scale(&mut self) {
        self.setup
            .tolerances
            .scales_of(&self.phi[0], &mut self.scale);
        Tolerances::guard_zero_scales(&mut self.scale);
    }

    fn error_norm(&self, values: &[f64]) -> f64 {
        weighted_rms_masked(values, &self.scale, &self.error_mask)
    }

    /// IDA's `IDASetCoeffs`: ψ, α, β, σ, γ for step `h` at order `k`, and `c_j`.
    fn set_coefficients(&mut self) {
        let k = self.order;
        if self.h != self.h_used || k != self.order_used {
            self.constant_steps = 0;
        }
        self.constant_steps = (self.constant_steps + 1).min(self.order_used + 2);
        if k + 1 >= self.constant_steps {
            self.beta[0] = 1.0;
            self.alpha[0] = 1.0;
            self.sigma[0] = 1.0;
            self.gamma[0] = 0.0;
            let mut temp1 = self.h;
            for i in 1..=k {
                let temp2 = self.psi[i - 1];
                self.psi[i - 1] = temp1;
                self.beta[i] = self.beta[i - 1] * self.psi[i - 1] / temp2;
                temp1 = temp2 + self.h;
                self.alpha[i] = self.h / temp1;
                self.sigma[i] = i as f64 * self.sigma[i - 1] * self.alpha[i];
                self.gamma[i] = self.gamma[i - 1] + self.alpha[i - 1] / self.h;
            }
            self.psi[k] = temp1;
        }
        let mut alpha_s = 0.0;
        let mut alpha_0 = 0.0;
        for i in 0..k {
            alpha_s -= 1.0 / (i as f64 + 1.0);
            alpha_0 -= self.alpha[i];
        }
        self.cj_last = self.cj;
        self.cj = -alpha_s / self.h;
        self.error_constant = (self.alpha[k] + alpha_s - alpha_0).abs().max(self.alpha[k]);
        if self.constant_steps <= k {
            for i in self.constant_steps..=k {
                let factor = self.beta[i];
                self.phi[i].iter_mut().for_each(|v| *v *= factor);
            }
        }
    }

    /// IDA's `IDARestore`: undoes `set_coefficients` after a failed attempt.
    fn restore(&mut self) {
        if self.constant_steps <= self.order {
            for i in self.constant_steps..=self.order {
                let factor = 1.0 / self.beta[i];
                self.phi[i].iter_mut().for_each(|v| *v *= factor);
            }
        }
        for j in 1..=self.order {
            self.psi[j - 1] = self.psi[j] - self.h;
        }
    }

    fn predict(&mut self) {
        let k = self.order;
        // Component by component, the sums in registers (the same order of additions as
        // difference by difference, without a store and load per difference).
        let phi = &self.phi[..=k];
        let gamma = &self.gamma[..=k];
        let predicted = self.y_pred.iter_mut().zip(self.yp_pred.iter_mut());
        for (i, (y_out, yp_out)) in predicted.enumerate() {
            let mut y = phi[0][i];
            let mut yp = 0.0;
            for (difference, g) in phi[1..].iter().zip(&gamma[1..]) {
                y += difference[i];
                yp += g * difference[i];
            }
            *y_out = y;
            *yp_out = yp;
        }
    }
}

impl Bdf {
    /// Residual `M x' - f(t, x)` at the current iterate into `delta`.
    fn residual(&mut self, system: &mut dyn System, t: f64) -> Result<(), EvalError> {
        rhs_checked(system, t, &self.y, &mut self.f_value, &mut self.stats)?;
        let terms = self
            .yp
            .iter()
            .zip(&self.f_value)
            .zip(&self.setup.differential);
        for (delta, ((&yp, &f), &differential)) in self.delta.iter_mut().zip(terms) {
            let mass_term = if differential { yp } else { 0.0 };
            *delta = mass_term - f;
        }
        Ok(())
    }

    /// Evaluates the Jacobian (when asked) at the current iterate and factors `c_j M - J`.
    fn setup_matrix(
        &mut self,
        system: &mut dyn System,
        t: f64,
        new_jacobian: bool,
    ) -> Result<(), CorrectorFailure> {
        if new_jacobian || !self.jacobian_valid {
            self.jacobian
                .evaluate(
                    system,
                    t,
                    &self.y,
                    &self.f_value,
                    &self.scale,
                    &mut self.stats,
                )
                .map_err(CorrectorFailure::Eval)?;
            self.jacobian_valid = true;
            self.jacobian_age = 0;
        }
        self.stats.lu_factorizations += 1;
        self.lu_valid = false;
        self.lu
            .factor(self.jacobian.matrix(), &self.setup.differential, self.cj)
            .map_err(|_| CorrectorFailure::Singular)?;
        self.lu_valid = true;
        self.cj_factored = self.cj;
        self.convergence_rate = 20.0;
        Ok(())
    }

    /// Newton iteration for the corrector at `t`; retries once with a fresh Jacobian when the
    /// Jacobian in use is stale.
    fn solve_corrector(&mut self, system: &mut dyn System, t: f64) -> Result<(), CorrectorFailure> {
        let ratio = self.cj / self.cj_factored;
        let mut setup_needed = !self.lu_valid
            || !(CJ_RATIO_LOW..=CJ_RATIO_HIGH).contains(&ratio)
            || self.jacobian_age >= MAX_JACOBIAN_AGE;
        let mut new_jacobian = self.jacobian_age >= MAX_JACOBIAN_AGE;
        let mut fresh_jacobian = false;
        if self.cj != self.cj_last {
            self.convergence_rate = 100.0;
        }
        loop {
            let outcome = self.newton_iterations(system, t, setup_needed, new_jacobian);
            fresh_jacobian |= new_jacobian || (setup_needed && self.jacobian_age == 0);
            match outcome {
                Err(CorrectorFailure::Convergence) if !fresh_jacobian => {
                    setup_needed = true;
                    new_jacobian = true;
                }
                other => return other,
            }
        }
    }

    fn newton_iterations(
        &mut self,
        system: &mut dyn System,
        t: f64,
        setup_needed: bool,
        new_jacobian: bool,
    ) -> Result<(), CorrectorFailure> {
        self.y.copy_from_slice(&self.y_pred);
        self.yp.copy_from_slice(&self.yp_pred);
        self.correction.fill(0.0);
        let mut first_norm = 0.0;
        for iteration in 0..MAX_NEWTON_ITERATIONS {
            self.residual(system, t).map_err(CorrectorFailure::Eval)?;
            if iteration == 0 && setup_needed {
                self.setup_matrix(system, t, new_jacobian)?;
            }
            self.lu.solve(&mut self.delta);
            self.stats.newton_iterations += 1;
            let ratio = self.cj / self.cj_factored;
            if ratio != 1.0 {
                let factor = 2.0 / (1.0 + ratio);
                self.delta.iter_mut().for_each(|v| *v *= factor);
            }
            let cj = self.cj;
            let iterate = self.y.iter_mut().zip(self.yp.iter_mut());
            let predicted = self.y_pred.iter().zip(&self.yp_pred);
            let corrections = self.correction.iter_mut().zip(&self.delta);
            for (((y, yp), (&y_pred, &yp_pred)), (correction, &delta)) in
                iterate.zip(predicted).zip(corrections)
            {
                *correction -= delta;
                *y = y_pred + *correction;
                *yp = yp_pred + cj * *correction;
            }
            let norm = weighted_rms(&self.delta, &self.scale);
            if !norm.is_finite() {
                return Err(CorrectorFailure::Convergence);
            }
            if iteration == 0 {
                first_norm = norm;
                if norm <= 1e-4 * NEWTON_TOLERANCE {
                    return Ok(());
                }
            } else {
                let ratio = norm / first_norm;
                // The rate's root without `powf` in the usual cases (a libm call a step).
                let rate = match iteration {
                    1 => ratio,
                    2 => ratio.sqrt(),
                    _ => ratio.powf(1.0 / iteration as f64),
                };
                if rate > MAX_RATE {
                    return Err(CorrectorFailure::Convergence);
                }
                self.convergence_rate = rate / (1.0 - rate);
            }
            if self.convergence_rate * norm <= NEWTON_TOLERANCE {
                return Ok(());
            }
        }
        Err(CorrectorFailure::Convergence)
    }

    /// IDA's `IDATestError`: error estimates at orders k, k-1 (and k-2), the proposed order
    /// and whether the step passes.
    fn test_error(&mut self) -> ErrorEstimates {
        let k = self.order;
        let norm_k = self.error_norm(&self.correction);
        let error_k = self.sigma[k] * norm_k;
        let weighted_k = (k + 1) as f64 * error_k;
        let mut estimates = ErrorEstimates {
            at_order: error_k,
            at_order_minus_1: 0.0,
            new_order: k,
            passed: self.error_constant * norm_k <= 1.0,
        };
        if k > 1 {
            let mut difference = std::mem::take(&mut self.difference);
            for ((d, p), e) in difference
                .iter_mut()
                .zip(&self.phi[k])
                .zip(&self.correction)
            {
                *d = p + e;
            }
            let error_km1 = self.sigma[k - 1] * self.error_norm(&difference);
            let weighted_km1 = k as f64 * error_km1;
            estimates.at_order_minus_1 = error_km1;
            if k > 2 {
                difference
                    .iter_mut()
                    .zip(&self.phi[k - 1])
                    .for_each(|(d, p)| *d += p);
                let error_km2 = self.sigma[k - 2] * self.error_norm(&difference);
                let weighted_km2 = (k - 1) as f64 * error_km2;
                if weighted_km1.max(weighted_km2) <= weighted_k {
                    estimates.new_order = k - 1;
                }
            } else if weighted_km1 <= 0.5 * weighted_k {
                estimates.new_order = k - 1;
            }
            self.difference = difference;
        }
        if !norm_k.is_finite() {
            estimates.passed = false;
        }
        estimates
    }

    /// IDA's `IDACompleteStep`: order and step for the next step, history update.
    fn complete_step(&mut self, estimates: ErrorEstimates) {
        self.steps_since_start += 1;
        let order_change = self.order as isize - self.order_used as isize;
        self.order_used = self.order;
        self.h_used = self.h;
        if estimates.new_order + 1 == self.order || self.order == self.max_order {
            self.startup_phase = false;
        }
        if self.startup_phase {
            if self.steps_since_start > 1 {
                self.order += 1;
                self.h = (2.0 * self.h).min(self.setup.options.max_step);
            }
        } else {
            self.choose_order_and_step(estimates, order_change);
        }
        let k = self.order_used;
        if k < self.max_order {
            self.phi[k + 1].copy_from_slice(&self.correction);
        }
        for (value, correction) in self.phi[k].iter_mut().zip(&self.correction) {
            *value += correction;
        }
        for j in (0..k).rev() {
            let (low, high) = self.phi.split_at_mut(j + 1);
            for (value, above) in low[j].iter_mut().zip(&high[0]) {
                *value += above;
            }
        }
    }

    fn choose_order_and_step(&mut self, estimates: ErrorEstimates, order_change: isize) {
        let k = self.order;
        let error_k = estimates.at_order;
        let error_new = if estimates.new_order + 1 == k {
            self.order -= 1;
            estimates.at_order_minus_1
        } else if k == self.max_order || k + 1 >= self.constant_steps || order_change == 1 {
            error_k
        } else {
            let mut difference = std::mem::take(&mut self.difference);
            for ((d, e), p) in difference
                .iter_mut()
                .zip(&self.correction)
                .zip(&self.phi[k + 1])
            {
                *d = e - p;
            }
            let error_kp1 = self.error_norm(&difference) / (k + 2) as f64;
            self.difference = difference;
            let raise = if k == 1 {
                error_kp1 < 0.5 * error_k
            } else if estimates.at_order_minus_1 <= error_k.min(error_kp1) {
                self.order -= 1;
                return self.set_next_step(estimates.at_order_minus_1);
            } else {
                error_kp1 < error_k
            };
            if raise {
                self.order += 1;
                error_kp1
            } else {
                error_k
            }
        };
        self.set_next_step(error_new);
    }

    fn set_next_step(&mut self, error: f64) {
        let ratio = (2.0 * error + 1e-4).powf(-1.0 / (self.order as f64 + 1.0));
        // At orders 3-5 the step may grow again only after k + 1 steps of constant size and
        // order: growing at every step is not zero-stable there.
        let settled = self.order <= 2 || self.constant_steps > self.order;
        if ratio >= GROWTH_THRESHOLD && settled {
            self.h = (ratio.min(MAX_GROWTH) * self.h).min(self.setup.options.max_step);
        } else if ratio <= 1.0 {
            self.h *= ratio.clamp(0.5, 0.9);
        }
    }

    /// Copies the history the dense output needs.
    fn store_dense_output(&mut self) {
        let k = self.order_used;
        self.dense.end = self.t;
        self.dense.step_used = self.h_used;
        self.dense.order_used = k;
        self.dense.psi = self.psi;
        self.dense.phi.resize_with(k + 1, Vec::new);
        for j in 0..=k {
            self.dense.phi[j].clone_from(&self.phi[j]);
        }
    }

    /// The last step's end moved to `x` by a projection: the step's correction `e` (the
    /// corrector's `x - x_pred`) becomes `e + Δ`, `Δ = x - φ_0`, so every history term
    /// [`Bdf::complete_step`] added `e` to gets `Δ` too (`φ_0 … φ_k`, and `φ_{k+1}` where
    /// it holds `e`), and the dense output with them: the interpolant moves by `Δ` at
    /// the step's end and not at its start, like the corrector's change.
    fn add_projection(&mut self, x: &[f64]) {
        let k = self.order_used;
        let last = if k < self.max_order { k + 1 } else { k };
        for i in 0..self.setup.size {
            let delta = x[i] - self.phi[0][i];
            if delta != 0.0 {
                for j in 0..=last {
                    self.phi[j][i] += delta;
                }
                self.phi[0][i] = x[i];
                self.correction[i] += delta;
            }
        }
        if self.started && self.dense.order_used > 0 {
            self.store_dense_output();
        } else {
            self.dense.phi[0].copy_from_slice(x);
        }
    }

    /// New step and order after an error test failure (IDA's `IDAHandleNFlag`).
    fn after_error_test_failure(&mut self, estimates: ErrorEstimates, failures: usize) {
        let ratio = if failures == 1 {
            let error = if estimates.new_order == self.order {
                estimates.at_order
            } else {
                estimates.at_order_minus_1
            };
            self.order = estimates.new_order;
            (0.9 * (2.0 * error + 1e-4).powf(-1.0 / (self.order as f64 + 1.0))).clamp(0.25, 0.9)
        } else {
            self.order = if failures == 2 {
                estimates.new_order
            } else {
                1
            };
            0.25
        };
        self.h *= if ratio.is_finite() { ratio } else { 0.25 };
    }
}

/// The tolerances BDF works with: of the differential rows, the requested ones divided by
/// [`TOLERANCE_DIVISOR`], the relative one not below [`SMALLEST_RELATIVE_TOLERANCE`] unless
/// it was requested so, the absolute one in the same ratio to the relative one as
/// requested (as Radau5 keeps it). Algebraic rows keep the requested tolerances: their
/// error does not accumulate over the run (they follow the differential rows at each
/// step), and an index-1 variable computed by cancellation (ROBER's `y3 = 1 - y1 - y2`)
/// carries rounding errors that a hundred times smaller `atol` would reject.
fn calibrate_tolerances(tolerances: &mut Tolerances, differential: &[bool]) {
    let rows = tolerances
        .relative
        .iter_mut()
        .zip(&mut tolerances.absolute)
        .zip(differential);
    for ((relative, absolute), _) in rows.filter(|(_, differential)| **differential) {
        if *relative > 0.0 {
            let calibrated =
                (*relative / TOLERANCE_DIVISOR).max(SMALLEST_RELATIVE_TOLERANCE.min(*relative));
            *absolute *= calibrated / *relative;
            *relative = calibrated;
        } else {
            *absolute /= TOLERANCE_DIVISOR;
        }
    }
}

impl Integrator for Bdf {
    common_accessors!(Method::Bdf, |s| s.t, &s.phi[0]);

    fn linear_solver(&self) -> Option<LinearSolverKind> {
        Some(self.lu.kind())
    }

    fn reset(&mut self, _system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError> {
        if x.len() != self.setup.size || !t.is_finite() {
            return Err(SolveError::invalid("reset state has the wrong length"));
        }
        self.t = t;
        self.phi[0].copy_from_slice(x);
        self.started = false;
        self.dense.end = t;
        self.dense.step_used = 0.0;
        self.dense.order_used = 0;
        self.dense.phi.truncate(1);
        self.dense.phi[0].copy_from_slice(x);
        Ok(())
    }

    fn set_projected_state(
        &mut self,
        _system: &mut dyn System,
        x: &[f64],
    ) -> Result<(), SolveError> {
        self.setup.check_len(x)?;
        self.add_projection(x);
        Ok(())
    }

    fn step(&mut self, system: &mut dyn System, t_limit: f64) -> Result<(), SolveError> {
        if t_limit <= self.t {
            return Ok(());
        }
        if !self.started {
            self.start(system, t_limit)?;
        }
        self.update_scale();
        let (mut error_failures, mut newton_failures) = (0usize, 0usize);
        loop {
            let failed = error_failures + newton_failures > 0;
            self.h = step_above_floor(self.h, self.t, failed, &self.correction, &self.scale)?;
            let (h_try, hits_limit) = clip_to_limit(self.t, self.h, t_limit);
            self.h = h_try;
            let t_new = if hits_limit { t_limit } else { self.t + h_try };
            self.set_coefficients();
            self.predict();
            let failure = self.solve_corrector(system, t_new).err();
            if let Some(failure) = failure {
                self.restore();
                self.startup_phase = false;
                self.stats.rejected_steps += 1;
                newton_failures += 1;
                self.h *= 0.25;
                if newton_failures >= MAX_NEWTON_FAILURES {
                    return Err(match failure {
                        CorrectorFailure::Eval(error) => eval_failure(t_new, error),
                        CorrectorFailure::Singular => SolveError::SingularMatrix {
                            time: self.t,
                            step: h_try,
                        },
                        CorrectorFailure::Convergence => SolveError::NewtonFailed {
                            time: self.t,
                            step: h_try,
                            worst: worst_components(&self.delta, &self.scale),
                        },
                    });
                }
                continue;
            }
            let estimates = self.test_error();
            if !estimates.passed {
                self.restore();
                self.startup_phase = false;
                self.stats.rejected_steps += 1;
                error_failures += 1;
                if error_failures >= MAX_ERROR_TEST_FAILURES {
                    return Err(SolveError::ErrorTestFailed {
                        time: self.t,
                        step: h_try,
                        worst: worst_components(&self.correction, &self.scale),
                    });
                }
                self.after_error_test_failure(estimates, error_failures);
                continue;
            }
            self.t = t_new;
            self.stats.steps += 1;
            self.jacobian_age += 1;
            self.complete_step(estimates);
            self.store_dense_output();
            return Ok(());
        }
    }
}
