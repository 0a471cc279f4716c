//! Radau IIA of order 5 (three stages), after Hairer and Wanner's RADAU5.
//!
//! * The stage equations for `M x' = f` are solved by simplified Newton iterations on the
//!   transformed system: `T^-1 A^-1 T` is block diagonal, so each iteration solves one real
//!   system with `E1 = (γ/h) M - J` and one complex system with `E2 = ((α + iβ)/h) M - J`
//!   (dense LU, ours below 32 unknowns and faer's above, or faer's sparse LU). Newton
//!   starts from the previous step's collocation polynomial.
//!   The contraction `θ` is monitored; a predicted failure (`θ ≥ 0.99`, or
//!   `θ^(k_max - k) / (1 - θ) ||Δ|| > κ`) shrinks the step at once. The iteration stops when
//!   `θ / (1 - θ) ||Δ|| ≤ κ`; at its first iteration `θ` is the last step's (Hairer's
//!   `FACCON ** 0.8`) only while the factorization is the same, and 1 after a new one.
//! * Tolerances are transformed as in RADAU5 (`rtol' = 0.1 rtol^(2/3)`,
//!   `atol' = rtol' atol / rtol`) because the embedded estimate is of order 3 while the method
//!   has order 5: the achieved accuracy then tracks the requested one.
//! * Error estimate: `err = (γ/h M - J)^-1 (f(t, x) + M (e1 z1 + e2 z2 + e3 z3)/h)`, the filter
//!   `(γ/h M - J)^-1` damps the stiff components; at the first step and after a rejection it is
//!   applied a second time (`f` re-evaluated at `x + err`). Norm: RMS of `err_i / sc_i`,
//!   `sc_i = atol'_i + rtol'_i |x_i|` with `x` at the step's start, as RADAU5's `SCAL`
//!   (algebraic components included, unscaled: index 1).
//! * Step control: `h_new = h / clamp(err^(1/4) / fac, 1/8, 5)` with
//!   `fac = min(0.9, 0.9 (1 + 2 k_max) / (k + 2 k_max))`, combined with Gustafsson's
//!   predictive controller. The Jacobian is reused while `θ ≤ 0.001`; the LU is reused when in
//!   addition `h_new / h ∈ [1, 1.2]` (the step is then kept).
//! * Dense output: the collocation polynomial of the last step (degree 3), exact for
//!   polynomial solutions up to degree 3.
//! * Algebraic rows (`M_ii = 0`) enter only through `M` in the iteration matrices: index-1
//!   DAEs are integrated directly (Radau IIA is stiffly accurate).

// The transformation matrices are quoted with all the digits Hairer and Wanner publish.
#![allow(clippy::excessive_precision)]

use faer::c64;

use crate::dense_output::{step_fraction, DenseOutput};
use crate::error::{EvalError, SolveError};
use crate::evaluate::rhs_checked;
use crate::integrator::{
    common_accessors, eval_failure, Aim, Initial, Integrator, ProblemSetup, StepStart,
};
use crate::jacobian::JacobianEvaluator;
use crate::linear::{use_sparse, LinearSolverKind, LuPair};
use crate::norm::{weighted_rms, worst_components, Tolerances};
use crate::options::{Method, SPARSE_AUTO_THRESHOLD};
use crate::stats::Stats;
use crate::step_control::{clip_to_limit, step_above_floor, step_after_accepted};
use crate::system::System;

const SQRT6: f64 = 2.449_489_742_783_178;
const C1: f64 = (4.0 - SQRT6) / 10.0;
const C2: f64 = (4.0 + SQRT6) / 10.0;
const C1M1: f64 = C1 - 1.0;
const C2M1: f64 = C2 - 1.0;
const C1MC2: f64 = C1 - C2;
const DD1: f64 = -(13.0 + 7.0 * SQRT6) / 3.0;
const DD2: f64 = (-13.0 + 7.0 * SQRT6) / 3.0;
const DD3: f64 = -1.0 / 3.0;
const T11: f64 = 9.123_239_487_089_294_279_2e-2;
const T12: f64 = -0.141_255_295_020_954_208_43;
const T13: f64 = -3.002_919_410_514_742_449_2e-2;
const T21: f64 = 0.241_717_932_707_107_018_96;
const T22: f64 = 0.204_129_352_293_799_931_99;
const T23: f64 = 0.382_942_112_757_261_937_79;
const T31: f64 = 0.966_048_182_615_092_936_19;
const TI11: f64 = 4.325_579_890_063_155_351_0;
const TI12: f64 = 0.339_199_251_815_809_869_54;
const TI13: f64 = 0.541_770_539_935_874_871_19;
const TI21: f64 = -4.178_718_591_551_904_727_3;
const TI22: f64 = -0.327_682_820_761_062_387_08;
const TI23: f64 = 0.476_623_554_500_550_451_96;
const TI31: f64 = -0.502_872_634_945_786_875_95;
const TI32: f64 = 2.571_926_949_855_605_429_2;
const TI33: f64 = -0.596_039_204_828_224_924_97;

const MAX_NEWTON_ITERATIONS: usize = 7;
const SAFETY: f64 = 0.9;
const FACTOR_MIN: f64 = 1.0 / 8.0; // h_new <= 8 h
const FACTOR_MAX: f64 = 5.0; // h_new >= h / 5
const MAX_CONSECUTIVE_FAILURES: usize = 30;
const MAX_SINGULAR: usize = 6;

/// When a Jacobian is kept and when a factorization is kept: Hairer's `WORK(3)` (the
/// Newton contraction up to which the Jacobian is reused) and `WORK(5)`, `WORK(6)` (the
/// range of step-size ratios in which the step size, and so the factorization, stays).
#[derive(Debug, Clone, Copy)]
struct ReusePolicy {
    theta: f64,
    quot_low: f64,
    quot_high: f64,
}

impl ReusePolicy {
    /// Hairer's defaults, for systems whose factorization costs about as much as a few
    /// Newton iterations.
    const SMALL: ReusePolicy = ReusePolicy {
        theta: 0.001,
        quot_low: 1.0,
        quot_high: 1.2,
    };

    /// Hairer's advice for large systems (`WORK(3) = 0.1`, `WORK(5) = 0.99`,
    /// `WORK(6) = 2`): there the real and the complex factorization of a step cost as much
    /// as tens of Newton iterations (BRUSS2D, 2,048 unknowns: 20 ms against 1 ms), so a
    /// slower contraction and a step size kept in a wider band pay.
    const LARGE: ReusePolicy = ReusePolicy {
        theta: 0.1,
        quot_low: 0.99,
        quot_high: 2.0,
    };

    /// [`Self::LARGE`] from [`SPARSE_AUTO_THRESHOLD`] unknowns on (where a sparse LU, or a
    /// dense one of at least that size, is used), [`Self::SMALL`] below.
    fn for_size(size: usize) -> ReusePolicy {
        if size >= SPARSE_AUTO_THRESHOLD {
            ReusePolicy::LARGE
        } else {
            ReusePolicy::SMALL
        }
    }
}

/// Real eigenvalue `γ` and complex pair `α ± iβ` of the inverse Radau IIA matrix.
fn eigenvalues() -> (f64, f64, f64) {
    let cbrt81 = 81f64.cbrt();
    let cbrt9 = 9f64.cbrt();
    let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
    let alpha = (12.0 - cbrt81 + cbrt9) / 60.0;
    let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
    let norm = alpha * alpha + beta * beta;
    (1.0 / u1, alpha / norm, beta / norm)
}

/// The collocation polynomial of the last step.
#[derive(Debug, Clone)]
pub struct Radau5DenseOutput {
    start: f64,
    end: f64,
    /// `cont[0]` is the state at `end`; the polynomial in `s = (t - end) / (end - start)` is
    /// `cont0 + s (cont1 + (s - c2 + 1) (cont2 + (s - c1 + 1) cont3))`.
    cont: [Vec<f64>; 4],
}

impl DenseOutput for Radau5DenseOutput {
    fn interval(&self) -> (f64, f64) {
        (self.start, self.end)
    }

    fn evaluate(&self, t: f64, out: &mut [f64]) {
        let Some(s) = step_fraction(self.start, self.end, t, self.end) else {
            out.copy_from_slice(&self.cont[0]);
            return;
        };
        let [c0, c1, c2, c3] = &self.cont;
        for i in 0..out.len() {
            out[i] = c0[i] + s * (c1[i] + (s - C2M1) * (c2[i] + (s - C1M1) * c3[i]));
        }
    }
}

/// Result of one Newton solve.
enum NewtonOutcome {
    Converged {
        iterations: usize,
    },
    /// Retry with `h * factor`.
    Failed {
        factor: f64,
        eval_error: Option<EvalError>,
    },
}

/// The Radau IIA (order 5) integrator.
pub struct Radau5 {
    setup: ProblemSetup,
    start: StepStart,
    step_size: Option<f64>,
    jacobian: JacobianEvaluator,
    /// A Jacobian exists and may be reused.
    jacobian_valid: bool,
    /// The Jacobian was evaluated at the current `(t, x)`.
    jacobian_fresh: bool,
    /// The real and the complex iteration matrix's LU.
    lu: LuPair,
    factored_for: Option<f64>,
    /// [`eigenvalues`], computed once (two cube roots: a few percent of a small step).
    eigenvalues: (f64, f64, f64),
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    stage_state: Vec<f64>,
    complex_rhs: Vec<c64>,
    scale: Vec<f64>,
    inverse_scale: Vec<f64>,
    error_vector: Vec<f64>,
    theta: f64,
    /// `θ / (1 - θ)` of the last Newton iteration that measured `θ`: with it, an iteration
    /// whose first correction is small enough counts as converged.
    contraction_factor: f64,
    /// The iteration matrices were factored anew since the last Newton iteration: the
    /// contraction measured with the old ones does not carry over.
    refactored: bool,
    reuse: ReusePolicy,
    newton_tolerance: f64,
    first_step: bool,
    last_rejected: bool,
    previous_step: f64,
    gustafsson: Option<(f64, f64)>,
    dense: Radau5DenseOutput,
    /// The start of the last accepted step: the state and `f` there, the polynomial of the
    /// step before (the Newton start) and the controller's values (what
    /// [`Integrator::rewind`] goes back to).
    before: Radau5Rewind,
    /// The last accepted step's error estimate in units of the requested tolerance (the
    /// estimate is of the stage order, like the collocation polynomial between the ends).
    interpolation_error: f64,
    /// `rtol' / rtol` of the transformed tolerances (the smallest ratio).
    tolerance_ratio: f64,
    stats: Stats,
}

/// What Radau5 needs to take its last accepted step again from that step's start.
#[derive(Debug, Clone)]
struct Radau5Rewind {
    /// The last accepted step can be taken back.
    valid: bool,
    x: Vec<f64>,
    f: Vec<f64>,
    /// The polynomial of the step before the last (the Newton start of the last).
    dense: Radau5DenseOutput,
    t: f64,
    step: f64,
    previous_step: f64,
    first_step: bool,
    last_rejected: bool,
    jacobian_fresh: bool,
    gustafsson: Option<(f64, f64)>,
}

impl Radau5 {
    /// Creates the integrator at the consistent point `(t0, x0)`.
    pub(crate) fn new(system: &mut dyn System, initial: Initial<'_>) -> Result<Self, SolveError> {
        let Initial { mut setup, t0, x0 } = initial;
        let requested = setup.tolerances.relative.clone();
        transform_tolerances(&mut setup.tolerances);
        let tolerance_ratio = requested
            .iter()
            .zip(&setup.tolerances.relative)
            .filter(|(r, _)| **r > 0.0)
            .map(|(r, t)| t / r)
            .fold(f64::INFINITY, f64::min);
        let smallest_rtol = setup
            .tolerances
            .relative
            .iter()
            .copied()
            .filter(|r| *r > 0.0)
            .fold(f64::INFINITY, f64::min);
        let newton_tolerance = if smallest_rtol.is_finite() {
            (10.0 * f64::EPSILON / smallest_rtol).max(0.03f64.min(smallest_rtol.sqrt()))
        } else {
            0.03
        };
        let size = setup.size;
        let sparse = use_sparse(system, setup.options.linear_solver);
        let lu = LuPair::new(system, setup.options.linear_solver);
        let zeros = || vec![0.0; size];
        let mut integrator = Radau5 {
            jacobian: JacobianEvaluator::new(system, sparse && system.sparsity().is_some()),
            setup,
            start: StepStart::new(t0, x0),
            step_size: None,
            jacobian_valid: false,
            jacobian_fresh: false,
            lu,
            factored_for: None,
            eigenvalues: eigenvalues(),
            z: std::array::from_fn(|_| zeros()),
            w: std::array::from_fn(|_| zeros()),
            stage_state: zeros(),
            complex_rhs: vec![c64::new(0.0, 0.0); size],
            scale: zeros(),
            inverse_scale: zeros(),
            error_vector: zeros(),
            theta: ReusePolicy::for_size(size).theta,
            contraction_factor: 1.0,
            refactored: true,
            reuse: ReusePolicy::for_size(size),
            newton_tolerance,
            first_step: true,
            last_rejected: false,
            previous_step: 0.0,
            gustafsson: None,
            dense: Radau5DenseOutput {
                start: t0,
                end: t0,
                cont: std::array::from_fn(|_| zeros()),
            },
            before: Radau5Rewind {
                valid: false,
                x: zeros(),
                f: zeros(),
                dense: Radau5DenseOutput {
                    start: t0,
                    end: t0,
                    cont: std::array::from_fn(|_| zeros()),
                },
                t: t0,
                step: 0.0,
                previous_step: 0.0,
                first_step: true,
                last_rejected: false,
                jacobian_fresh: false,
                gustafsson: None,
            },
            interpolation_error: 0.0,
            tolerance_ratio: if tolerance_ratio.is_finite() {
                tolerance_ratio
            } else {
                1.0
            },
            stats: Stats::default(),
        };
        integrator.restart(system, t0, x0)?;
        Ok(integrator)
    }

    fn restart(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), SolveError> {
        self.start.move_to(system, (t, x), &mut self.stats)?;
        self.update_scale();
        self.step_size = self.setup.options.initial_step;
        self.jacobian_valid = false;
        self.jacobian_fresh = false;
        self.factored_for = None;
        self.theta = self.reuse.theta;
        self.contraction_factor = 1.0;
        self.first_step = true;
        self.last_rejected = false;
        self.gustafsson = None;
        self.before.valid = false;
        self.dense.start = t;
        self.dense.end = t;
        self.dense.cont[0].copy_from_slice(x);
        for coefficient in &mut self.dense.cont[1..] {
            coefficient.fill(0.0);
        }
        Ok(())
    }

    fn update_scale(&mut self) {
        self.setup
            .tolerances
            .scales_of(&self.start.x, &mut self.scale);
        Tolerances::guard_zero_scales(&mut self.scale);
        for (inverse, &s) in self.inverse_scale.iter_mut().zip(&self.scale) {
            *inverse = 1.0 / s;
        }
    }

    /// Evaluates the Jacobian at the current point if it is missing or stale.
    fn ensure_jacobian(&mut self, system: &mut dyn System) -> Result<(), SolveError> {
        if self.jacobian_valid {
            return Ok(());
        }
        self.jacobian
            .evaluate(
                system,
                self.start.t,
                &self.start.x,
                &self.start.f,
                &self.scale,
                &mut self.stats,
            )
            .map_err(|error| eval_failure(self.start.t, error))?;
        self.jacobian_valid = true;
        self.jacobian_fresh = true;
        self.factored_for = None;
        Ok(())
    }

    /// Factors both iteration matrices for step `h`; false when one is singular.
    fn factor(&mut self, h: f64) -> bool {
        if self.factored_for == Some(h) {
            return true;
        }
        let (gamma, alpha, beta) = self.eigenvalues;
        self.stats.lu_factorizations += 1;
        let matrix = self.jacobian.matrix();
        let differential = &self.setup.differential;
        let shifts = (gamma / h, c64::new(alpha / h, beta / h));
        let complex_ok = self.lu.factor(matrix, differential, shifts);
        self.factored_for = if complex_ok { Some(h) } else { None };
        self.refactored = true;
        complex_ok
    }

    /// Starting values: zero at the first step, otherwise the extrapolated collocation
    /// polynomial of the previous step (`z`), and `w = T^-1 z`.
    fn newton_start(&mut self, h: f64) {
        if self.first_step {
            for k in 0..3 {
                self.z[k].fill(0.0);
                self.w[k].fill(0.0);
            }
            return;
        }
        let ratio = h / self.previous_step;
        let [_, a1, a2, a3] = &self.dense.cont;
        let [z0, z1, z2] = &mut self.z;
        let [w0, w1, w2] = &mut self.w;
        for i in 0..self.setup.size {
            let at = |c: f64| c * (a1[i] + (c - C2M1) * (a2[i] + (c - C1M1) * a3[i]));
            let (y1, y2, y3) = (at(C1 * ratio), at(C2 * ratio), at(ratio));
            z0[i] = y1;
            z1[i] = y2;
            z2[i] = y3;
            w0[i] = TI11 * y1 + TI12 * y2 + TI13 * y3;
            w1[i] = TI21 * y1 + TI22 * y2 + TI23 * y3;
            w2[i] = TI31 * y1 + TI32 * y2 + TI33 * y3;
        }
    }

    /// Replaces `z_k` by `f(t + c_k h, x + z_k)`.
    fn evaluate_stages(&mut self, system: &mut dyn System, h: f64) -> Result<(), EvalError> {
        for (k, c) in [C1, C2, 1.0].into_iter().enumerate() {
            let stage = self.start.x.iter().zip(&self.z[k]);
            for (state, (&x, &z)) in self.stage_state.iter_mut().zip(stage) {
                *state = x + z;
            }
            rhs_checked(
                system,
                self.start.t + c * h,
                &self.stage_state,
                &mut self.z[k],
                &mut self.stats,
            )?;
        }
        Ok(())
    }

    /// One simplified Newton correction: on entry `z` holds the stage values of `f`, on exit
    /// the transformed increments `Δw`.
    fn solve_correction(&mut self, h: f64) {
        let (gamma, alpha, beta) = self.eigenvalues;
        let (fac1, alphn, betan) = (gamma / h, alpha / h, beta / h);
        let [z0, z1, z2] = &mut self.z;
        let [w0, w1, w2] = &self.w;
        let differential = &self.setup.differential;
        for (i, complex) in self.complex_rhs.iter_mut().enumerate() {
            let (a1, a2, a3) = (z0[i], z1[i], z2[i]);
            let mut r1 = TI11 * a1 + TI12 * a2 + TI13 * a3;
            let mut r2 = TI21 * a1 + TI22 * a2 + TI23 * a3;
            let mut r3 = TI31 * a1 + TI32 * a2 + TI33 * a3;
            if differential[i] {
                let (s2, s3) = (-w1[i], -w2[i]);
                r1 -= w0[i] * fac1;
                r2 += s2 * alphn - s3 * betan;
                r3 += s3 * alphn + s2 * betan;
            }
            z0[i] = r1;
            *complex = c64::new(r2, r3);
        }
        self.lu.solve(z0, &mut self.complex_rhs);
        for ((re, im), complex) in z1.iter_mut().zip(z2.iter_mut()).zip(&self.complex_rhs) {
            *re = complex.re;
            *im = complex.im;
        }
    }

    /// Scaled RMS of the three corrections.
    fn correction_norm(&self) -> f64 {
        let size = self.setup.size;
        if size == 0 {
            return 0.0;
        }
        let sum: f64 = (0..size)
            .map(|i| {
                let s = self.inverse_scale[i];
                (self.z[0][i] * s).powi(2) + (self.z[1][i] * s).powi(2) + (self.z[2][i] * s).powi(2)
            })
            .sum();
        (sum / (3 * size) as f64).sqrt()
    }

    /// Simplified Newton iteration for the stage increments of step `h`.
    fn newton(&mut self, system: &mut dyn System, h: f64) -> NewtonOutcome {
        self.newton_start(h);
        // Hairer carries the contraction over (`FACCON ** 0.8`), so that one iteration may
        // suffice; with a new factorization (another step size, or a new Jacobian) it is
        // that of another matrix, and a first correction far above the tolerance would be
        // accepted unchecked. As CVODE resets its rate at every new matrix, it starts at 1.
        self.contraction_factor = if std::mem::take(&mut self.refactored) {
            1.0
        } else {
            self.contraction_factor.max(f64::EPSILON).powf(0.8)
        };
        self.theta = self.reuse.theta;
        let mut iterations = 0usize;
        let mut previous_norm = 0.0f64;
        let mut previous_quotient = 0.0f64;
        loop {
            if iterations >= MAX_NEWTON_ITERATIONS {
                return NewtonOutcome::Failed {
                    factor: 0.5,
                    eval_error: None,
                };
            }
            if let Err(error) = self.evaluate_stages(system, h) {
                return NewtonOutcome::Failed {
                    factor: 0.5,
                    eval_error: Some(error),
                };
            }
            self.solve_correction(h);
            self.stats.newton_iterations += 1;
            iterations += 1;
            let norm = self.correction_norm();
            if !norm.is_finite() {
                return NewtonOutcome::Failed {
                    factor: 0.5,
                    eval_error: None,
                };
            }
            if iterations > 1 && iterations < MAX_NEWTON_ITERATIONS {
                let quotient = norm / previous_norm;
                self.theta = if iterations == 2 {
                    quotient
                } else {
                    (quotient * previous_quotient).sqrt()
                };
                previous_quotient = quotient;
                if self.theta >= 0.99 {
                    return NewtonOutcome::Failed {
                        factor: 0.5,
                        eval_error: None,
                    };
                }
                self.contraction_factor = self.theta / (1.0 - self.theta);
                let remaining = (MAX_NEWTON_ITERATIONS - 1 - iterations) as i32;
                let predicted = self.contraction_factor * norm * self.theta.powi(remaining)
                    / self.newton_tolerance;
                if predicted >= 1.0 {
                    let q = predicted.clamp(1e-4, 20.0);
                    let factor = 0.8 * q.powf(-1.0 / (4.0 + f64::from(remaining)));
                    return NewtonOutcome::Failed {
                        factor,
                        eval_error: None,
                    };
                }
            }
            previous_norm = norm.max(f64::EPSILON);
            let [z0, z1, z2] = &mut self.z;
            let [w0, w1, w2] = &mut self.w;
            for i in 0..self.setup.size {
                let v1 = w0[i] + z0[i];
                let v2 = w1[i] + z1[i];
                let v3 = w2[i] + z2[i];
                w0[i] = v1;
                w1[i] = v2;
                w2[i] = v3;
                z0[i] = T11 * v1 + T12 * v2 + T13 * v3;
                z1[i] = T21 * v1 + T22 * v2 + T23 * v3;
                z2[i] = T31 * v1 + v2;
            }
            if self.contraction_factor * norm <= self.newton_tolerance {
                return NewtonOutcome::Converged { iterations };
            }
        }
    }

    /// Hairer's `ESTRAD`: filtered embedded error estimate (uses `w` as scratch).
    fn error_estimate(&mut self, system: &mut dyn System, h: f64) -> f64 {
        let (e1, e2, e3) = (DD1 / h, DD2 / h, DD3 / h);
        let size = self.setup.size;
        let [z0, z1, z2] = &self.z;
        let (mass_terms, differential) = (&mut self.w[1], &self.setup.differential);
        for i in 0..size {
            let combination = e1 * z0[i] + e2 * z1[i] + e3 * z2[i];
            let mass_term = if differential[i] { combination } else { 0.0 };
            mass_terms[i] = mass_term;
            self.error_vector[i] = mass_term + self.start.f[i];
        }
        self.lu.real.solve(&mut self.error_vector);
        let error = weighted_rms(&self.error_vector, &self.scale).max(1e-10);
        if error < 1.0 || !(self.first_step || self.last_rejected) {
            return error;
        }
        let perturbed = self.start.x.iter().zip(&self.error_vector);
        for (state, (&x, &error)) in self.stage_state.iter_mut().zip(perturbed) {
            *state = x + error;
        }
        let t = self.start.t;
        let mut refreshed = std::mem::take(&mut self.w[0]);
        let result = rhs_checked(
            system,
            t,
            &self.stage_state,
            &mut refreshed,
            &mut self.stats,
        );
        self.w[0] = refreshed;
        if result.is_err() {
            return error;
        }
        let refreshed = self.w[0].iter().zip(&self.w[1]);
        for (error, (&f, &mass_term)) in self.error_vector.iter_mut().zip(refreshed) {
            *error = f + mass_term;
        }
        self.lu.real.solve(&mut self.error_vector);
        weighted_rms(&self.error_vector, &self.scale).max(1e-10)
    }

    /// `f` at the end of the step into `w[0]` (the step is only accepted if this succeeds).
    fn evaluate_at_new_point(
        &mut self,
        system: &mut dyn System,
        t_end: f64,
    ) -> Result<(), EvalError> {
        let end = self.start.x.iter().zip(&self.z[2]);
        for (state, (&x, &z)) in self.stage_state.iter_mut().zip(end) {
            *state = x + z;
        }
        rhs_checked(
            system,
            t_end,
            &self.stage_state,
            &mut self.w[0],
            &mut self.stats,
        )
    }

    /// Moves to the end of the accepted step `h` and stores the collocation polynomial;
    /// `w[0]` holds `f` at the new point. The step's start is kept for a rewind.
    fn accept(&mut self, h: f64, t_end: f64) {
        self.keep_step_start(h);
        let [cont0, cont1, cont2, cont3] = &mut self.dense.cont;
        for i in 0..self.setup.size {
            let (z1, z2, z3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            self.start.x[i] += z3;
            cont0[i] = self.start.x[i];
            cont1[i] = (z2 - z3) * (1.0 / C2M1);
            let ak = (z1 - z2) * (1.0 / C1MC2);
            let acont3 = (ak - z1 * (1.0 / C1)) * (1.0 / C2);
            cont2[i] = (ak - cont1[i]) * (1.0 / C1M1);
            cont3[i] = cont2[i] - acont3;
        }
        self.dense.start = self.start.t;
        self.dense.end = t_end;
        self.start.t = t_end;
        self.previous_step = h;
        self.first_step = false;
        self.stats.steps += 1;
        self.update_scale();
        self.start.f.copy_from_slice(&self.w[0]);
        self.jacobian_fresh = false;
    }

    /// Before the step `h` from `self.start.t` is stored: keeps its start point and the previous
    /// polynomial (swapped, not copied; `accept` overwrites the whole polynomial).
    fn keep_step_start(&mut self, h: f64) {
        let before = &mut self.before;
        before.valid = true;
        before.x.copy_from_slice(&self.start.x);
        std::mem::swap(&mut before.f, &mut self.start.f);
        std::mem::swap(&mut before.dense, &mut self.dense);
        before.t = self.start.t;
        before.step = h;
        before.previous_step = self.previous_step;
        before.first_step = self.first_step;
        before.last_rejected = self.last_rejected;
        before.jacobian_fresh = self.jacobian_fresh;
        before.gustafsson = self.gustafsson;
    }

    /// Step-size proposal from the error and the Newton iteration count.
    fn proposal(&mut self, h: f64, error: f64, iterations: usize) -> f64 {
        let newton_weight = (1 + 2 * MAX_NEWTON_ITERATIONS) as f64;
        let fac =
            SAFETY.min(SAFETY * newton_weight / (iterations + 2 * MAX_NEWTON_ITERATIONS) as f64);
        let mut quot = (error.powf(0.25) / fac).clamp(FACTOR_MIN, FACTOR_MAX);
        if error < 1.0 {
            if let Some((h_accepted, error_accepted)) = self.gustafsson {
                let predictive =
                    (h_accepted / h) * (error * error / error_accepted).powf(0.25) / SAFETY;
                quot = quot.max(predictive.clamp(FACTOR_MIN, FACTOR_MAX));
            }
            self.gustafsson = Some((h, error.max(1e-2)));
        }
        h / quot
    }

    fn fail_or_shrink(
        &mut self,
        failures: &mut usize,
        h: f64,
        eval_error: Option<EvalError>,
    ) -> Result<(), SolveError> {
        *failures += 1;
        self.stats.rejected_steps += 1;
        self.last_rejected = true;
        if *failures < MAX_CONSECUTIVE_FAILURES {
            return Ok(());
        }
        Err(match eval_error {
            Some(error) => eval_failure(self.start.t, error),
            None => SolveError::NewtonFailed {
                time: self.start.t,
                step: h,
                worst: worst_components(&self.z[0], &self.scale),
            },
        })
    }
}

fn transform_tolerances(tolerances: &mut Tolerances) {
    for (relative, absolute) in tolerances.relative.iter_mut().zip(&mut tolerances.absolute) {
        if *relative > 0.0 {
            let ratio = *absolute / *relative;
            *relative = 0.1 * relative.powf(2.0 / 3.0);
            *absolute = *relative * ratio;
        }
    }
}

impl Integrator for Radau5 {
    common_accessors!(Method::Radau5, |s| s.start.t, &s.start.x);

    fn linear_solver(&self) -> Option<LinearSolverKind> {
        Some(self.lu.real.kind())
    }

    crate::integrator::one_step_method!(3);

    fn interpolation_error(&self) -> f64 {
        self.interpolation_error
    }

    fn rewind(&mut self) -> bool {
        if !self.before.valid {
            return false;
        }
        let before = &mut self.before;
        before.valid = false;
        self.start.x.copy_from_slice(&before.x);
        std::mem::swap(&mut before.f, &mut self.start.f);
        std::mem::swap(&mut before.dense, &mut self.dense);
        self.start.t = before.t;
        self.step_size = Some(before.step);
        self.previous_step = before.previous_step;
        self.first_step = before.first_step;
        self.last_rejected = before.last_rejected;
        self.gustafsson = before.gustafsson;
        // The matrix the step was taken with (evaluated at its start or before) serves
        // again; only its factorization is for another step size.
        self.jacobian_valid = true;
        self.jacobian_fresh = before.jacobian_fresh;
        self.update_scale();
        true
    }
}

impl Radau5 {
    /// [`Integrator::step`] toward `aim.limit`, trying `aim.h` first.
    fn step_from(&mut self, system: &mut dyn System, aim: Aim) -> Result<(), SolveError> {
        let Aim {
            limit: t_limit,
            mut h,
        } = aim;
        let (mut failures, mut singular) = (0usize, 0usize);
        loop {
            h = step_above_floor(
                h,
                self.start.t,
                failures + singular > 0,
                &self.error_vector,
                &self.scale,
            )?;
            let (h_try, hits_limit) = clip_to_limit(self.start.t, h, t_limit);
            self.ensure_jacobian(system)?;
            if !self.factor(h_try) {
                singular += 1;
                if singular >= MAX_SINGULAR {
                    return Err(SolveError::SingularMatrix {
                        time: self.start.t,
                        step: h_try,
                    });
                }
                self.fail_or_shrink(&mut failures, h_try, None)?;
                h = 0.5 * h_try;
                continue;
            }
            let iterations = match self.newton(system, h_try) {
                NewtonOutcome::Converged { iterations } => iterations,
                NewtonOutcome::Failed { factor, eval_error } => {
                    self.fail_or_shrink(&mut failures, h_try, eval_error)?;
                    h = factor * h_try;
                    self.jacobian_valid = self.jacobian_fresh;
                    continue;
                }
            };
            let error = self.error_estimate(system, h_try);
            if !error.is_finite() {
                self.fail_or_shrink(&mut failures, h_try, None)?;
                h = 0.5 * h_try;
                continue;
            }
            let h_new = self.proposal(h_try, error, iterations);
            if error >= 1.0 {
                self.stats.rejected_steps += 1;
                h = if self.first_step { 0.1 * h_try } else { h_new };
                self.last_rejected = true;
                self.jacobian_valid = self.jacobian_fresh;
                continue;
            }
            let t_end = if hits_limit {
                t_limit
            } else {
                self.start.t + h_try
            };
            if let Err(error) = self.evaluate_at_new_point(system, t_end) {
                self.fail_or_shrink(&mut failures, h_try, Some(error))?;
                h = 0.5 * h_try;
                continue;
            }
            self.accept(h_try, t_end);
            self.interpolation_error = error * self.tolerance_ratio;
            let mut h_next = step_after_accepted(
                h_new,
                (h_try, h),
                (self.last_rejected, hits_limit),
                self.setup.options.max_step,
            );
            self.last_rejected = false;
            let quotient = h_next / h_try;
            if self.theta <= self.reuse.theta {
                if (self.reuse.quot_low..=self.reuse.quot_high).contains(&quotient) {
                    h_next = h_try;
                }
            } else {
                self.jacobian_valid = false;
            }
            self.step_size = Some(h_next);
            return Ok(());
        }
    }

    /// The step's end moved by a projection to `x`: the dense output gets the correction
    /// `Δ (1 + s)` (`Δ` at the step's end, 0 at its start: `cont0` and `cont1` plus `Δ`).
    fn project_dense_output(&mut self, x: &[f64]) {
        for i in 0..x.len() {
            let delta = x[i] - self.start.x[i];
            self.dense.cont[0][i] += delta;
            self.dense.cont[1][i] += delta;
        }
    }
}
