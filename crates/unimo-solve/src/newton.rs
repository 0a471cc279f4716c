//! Newton's method for the algebraic blocks of a simulation: damped (Armijo) iterations
//! on a small dense system with its own Jacobian, converged at rounding level and
//! accepted otherwise only within the simulation's tolerances.
//!
//! # The tolerance rule
//! An iterate is **converged** when every component of the last Newton step is at
//! rounding level, `|dx_k| <= 1e-13 (1 + |x_k|)`, whatever the simulation's tolerance:
//! the blocks feed the integrator's difference quotients and error estimates, which need
//! their variables to rounding (a block solved to 1e-9 makes a difference quotient of
//! step 1e-8 wrong by 10 %). A block whose Newton iteration does not get there in
//! [`MAX_ITERATIONS`] (a multiple root, a residual with kinks, rounding noise in a badly
//! scaled residual) is **accepted** only when its last step was within the simulation's
//! error weights: `|dx_k| <= ACCEPT_FRACTION (atol + rtol |x_k|)`. There is no absolute
//! residual threshold: the residual's scale is the model's (an equation multiplied by
//! 1e-12 has residuals 1e-12 times smaller and the same solution), the step's is the
//! unknowns', which the tolerances describe.
//!
//! A **linear** block is solved by one step and refined with the same factors. When the
//! step did not halve the residual, or a refinement's correction is at least half the
//! step before it (no contraction, in the error weights `atol + rtol |x_k|`), the
//! iterates are at the limit rounding and the block's conditioning set (the next step
//! would undo this one), and the iterate is taken, as a direct solver takes its one solve
//! (LU with partial pivoting is backward stable). Measured on two MSL examples, whose
//! linear blocks failed after 50 iterations and stopped the run:
//! - DifferenceAmplifier (two transistors' currents and two capacitor derivatives):
//!   residuals 5e-17 to 1e-16, the step of `der(C5.v)` about 1e-7 V/s forward and back,
//!   iteration after iteration, whether `der(C5.v)` was 40 or 0.045 V/s;
//! - ActuatorWithNoise at rtol 1e-8 (two current derivatives of a motor, one near 3e-12,
//!   the other 9,158): the residual one rounding unit of 9,158 (9.1e-13) at both ends of
//!   the cycle, the near-zero derivative's step 5.6e-13, five times its acceptance
//!   weight.

use crate::dense::{lu_resolve, lu_solve};

/// Iterations of Newton's method before a block fails.
pub const MAX_ITERATIONS: usize = 50;

/// The share of the integrator's error weight within which a non-converged Newton
/// iterate is accepted.
pub const ACCEPT_FRACTION: f64 = 1e-3;

/// A step below this (relative to `1 + |x|`) is rounding.
const ROUNDING: f64 = 1e-13;

/// The tolerances a block's solution is accepted with (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonTolerance {
    pub relative: f64,
    pub absolute: f64,
}

impl NewtonTolerance {
    /// The simulation's relative and absolute tolerances.
    pub fn new(relative: f64, absolute: f64) -> Self {
        NewtonTolerance { relative, absolute }
    }

    /// The weight of component `x`: `ACCEPT_FRACTION (atol + rtol |x|)`.
    pub fn weight(&self, x: f64) -> f64 {
        ACCEPT_FRACTION * (self.absolute + self.relative * x.abs())
    }

    /// Whether the step `dx` from `x` is at rounding level.
    pub fn is_rounding(x: f64, dx: f64) -> bool {
        dx.abs() <= ROUNDING * (1.0 + x.abs())
    }

    /// Whether the step `dx` from `x` is within the accepted weight.
    pub fn accepts(&self, x: f64, dx: f64) -> bool {
        dx.abs() <= self.weight(x) || Self::is_rounding(x, dx)
    }
}

impl Default for NewtonTolerance {
    /// The solver's default tolerances (rtol 1e-6, atol 1e-8).
    fn default() -> Self {
        NewtonTolerance::new(1e-6, 1e-8)
    }
}

/// A square system `f(x) = 0` with its Jacobian.
pub trait NewtonProblem {
    /// The number of unknowns and of equations.
    fn size(&self) -> usize;

    /// Whether the equations are linear in the unknowns (one step solves them).
    fn is_linear(&self) -> bool {
        false
    }

    /// Evaluates the residuals at `x` into `f`.
    fn residual(&mut self, x: &[f64], f: &mut [f64]);

    /// The Jacobian `df/dx` (row-major, `len x len`) at the `x` of the last call of
    /// [`NewtonProblem::residual`].
    fn jacobian(&mut self, j: &mut [f64]);
}

/// Why Newton's method failed.
#[derive(Clone, Debug, PartialEq)]
pub enum NewtonError {
    /// A residual is NaN or infinite.
    NotFinite { residual: f64 },
    /// The Jacobian has a zero or non-finite pivot.
    Singular { residual: f64 },
    /// No convergence in [`MAX_ITERATIONS`], the last step outside the tolerances.
    NoConvergence { residual: f64 },
}

impl NewtonError {
    /// The largest absolute residual at the last iterate.
    pub fn residual(&self) -> f64 {
        match *self {
            NewtonError::NotFinite { residual }
            | NewtonError::Singular { residual }
            | NewtonError::NoConvergence { residual } => residual,
        }
    }

    /// What went wrong, in words.
    pub fn reason(&self) -> String {
        match self {
            NewtonError::NotFinite { .. } => "the residual is not finite".into(),
            NewtonError::Singular { .. } => "the block's Jacobian is singular".into(),
            NewtonError::NoConvergence { .. } => format!(
                "Newton's method did not converge in {MAX_ITERATIONS} iterations \
                 (its last step is larger than the tolerances allow)"
            ),
        }
    }
}

/// Scratch memory (allocated once, reused by every solve).
#[derive(Clone, Debug, Default)]
pub struct NewtonWork {
    matrix: Vec<f64>,
    step: Vec<f64>,
    residual: Vec<f64>,
    perm: Vec<usize>,
    saved: Vec<f64>,
    trial: Vec<f64>,
}

/// The largest absolute component; NaN when any is NaN (`f64::max` would drop it, and a
/// NaN residual would pass for 0).
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| {
        if m.is_nan() || x.is_nan() {
            f64::NAN
        } else {
            m.max(x.abs())
        }
    })
}

/// Solves `p` from the start `x`, leaving the solution in `x`. On return (success or
/// failure) the last call of `p.residual` was at the final `x`, so a problem that keeps
/// derived quantities beside its unknowns (torn variables) has them up to date. Returns
/// the number of Newton steps taken.
pub fn solve(
    p: &mut dyn NewtonProblem,
    x: &mut [f64],
    tol: &NewtonTolerance,
    w: &mut NewtonWork,
) -> Result<usize, NewtonError> {
    let n = p.size();
    w.matrix.resize(n * n, 0.0);
    w.step.resize(n, 0.0);
    w.residual.resize(n, 0.0);
    w.perm.resize(n, 0);
    let mut linear = p.is_linear();
    // Whether `w.residual` already holds f(x) (the line search's last trial).
    let mut evaluated = false;
    let mut accepted = false;
    for it in 0..MAX_ITERATIONS {
        if !evaluated {
            p.residual(x, &mut w.residual);
        }
        let norm = max_abs(&w.residual);
        if !norm.is_finite() {
            return Err(NewtonError::NotFinite { residual: norm });
        }
        if norm == 0.0 {
            return Ok(it);
        }
        p.jacobian(&mut w.matrix);
        for k in 0..n {
            w.step[k] = -w.residual[k];
        }
        if !lu_solve(n, &mut w.matrix, &mut w.step, &mut w.perm) {
            return Err(NewtonError::Singular { residual: norm });
        }
        w.saved.clear();
        w.saved.extend_from_slice(x);
        let lambda = if linear || norm <= 1e-10 {
            None
        } else {
            line_search(p, x, w, norm)
        };
        evaluated = lambda.is_some();
        let lambda = lambda.unwrap_or(1.0);
        let mut converged = true;
        accepted = true;
        for k in 0..n {
            let dx = lambda * w.step[k];
            converged &= NewtonTolerance::is_rounding(w.saved[k], dx);
            accepted &= tol.accepts(w.saved[k], dx);
            x[k] = w.saved[k] + dx;
        }
        if linear && !converged {
            match linear_refinement(p, x, norm, tol, w) {
                Refinement::Solved => return Ok(it + 1),
                Refinement::Corrected => {
                    evaluated = false;
                    continue;
                }
                Refinement::LeftDomain => {
                    // The full step left the residual's domain (a near-singular pivot):
                    // back to the start, on as a general block with its damped steps.
                    x.copy_from_slice(&w.saved);
                    linear = false;
                    evaluated = false;
                    continue;
                }
            }
        }
        if converged {
            if !evaluated {
                p.residual(x, &mut w.residual);
            }
            return Ok(it + 1);
        }
    }
    if !evaluated {
        p.residual(x, &mut w.residual);
    }
    let norm = max_abs(&w.residual);
    if accepted && norm.is_finite() {
        return Ok(MAX_ITERATIONS);
    }
    Err(NewtonError::NoConvergence { residual: norm })
}

/// What one step of iterative refinement says of a linear block's Newton step.
enum Refinement {
    /// The correction is rounding: `x` (its residual evaluated) is the solution.
    Solved,
    /// The correction was added to `x` (an ill-conditioned block): iterate on.
    Corrected,
    /// The residual at the step is not finite.
    LeftDomain,
}

/// A linear block is solved by one step. Its residual at the new iterate (torn
/// variables up to date) gives one step of iterative refinement with the same factors
/// (`w.matrix`, `w.perm` from the step): when that correction is rounding, the iterate
/// is the solution, and so it is when the correction did not contract (see the module's
/// documentation); otherwise (an ill-conditioned block still contracting, or one not
/// linear after all) the correction is taken and Newton goes on.
fn linear_refinement(
    p: &mut dyn NewtonProblem,
    x: &mut [f64],
    before: f64,
    tol: &NewtonTolerance,
    w: &mut NewtonWork,
) -> Refinement {
    let n = x.len();
    // The step that led to `x`, in the error weights (before `w.step` takes the
    // correction).
    let step = weighted_max(x, &w.step[..n], tol);
    p.residual(x, &mut w.residual);
    let after = max_abs(&w.residual);
    if after == 0.0 {
        return Refinement::Solved;
    }
    if !after.is_finite() {
        return Refinement::LeftDomain;
    }
    // The step did not halve the residual: it is at the level rounding sets, and no
    // step can take it lower.
    if after >= 0.5 * before {
        return Refinement::Solved;
    }
    for k in 0..n {
        w.step[k] = -w.residual[k];
    }
    lu_resolve(n, &w.matrix, &w.perm, &mut w.step, &mut w.trial);
    if (0..n).all(|k| NewtonTolerance::is_rounding(x[k], w.step[k])) {
        return Refinement::Solved;
    }
    // No contraction (the correction at least half the step): the iterates are at the
    // limit the block's conditioning sets, and the next step would undo this correction;
    // `x` is as good as any of them.
    if weighted_max(x, &w.step[..n], tol) >= 0.5 * step {
        return Refinement::Solved;
    }
    for k in 0..n {
        x[k] += w.step[k];
    }
    Refinement::Corrected
}

/// The largest `|dx_k| / (atol + rtol |x_k|)`: a step in the integrator's error weights
/// (a weight of zero, `atol = 0` at `x_k = 0`, counts as the smallest positive number).
fn weighted_max(x: &[f64], dx: &[f64], tol: &NewtonTolerance) -> f64 {
    x.iter()
        .zip(dx)
        .map(|(x, dx)| dx.abs() / (tol.absolute + tol.relative * x.abs()).max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max)
}

/// Damped Newton (Armijo backtracking): the step `w.step` from `w.saved` is halved
/// until the residual's largest component decreases, so that a residual with kinks and
/// saturations (a limited op-amp: slope 1e4 in a band 1e-3 wide, 0 outside) does not
/// send the iterates back and forth between its flat parts. Returns the step length
/// taken with `w.residual` evaluated at the new iterate, or `None` for a full step left
/// to the caller (directions along which the residual does not decrease at all).
fn line_search(
    p: &mut dyn NewtonProblem,
    x: &mut [f64],
    w: &mut NewtonWork,
    norm: f64,
) -> Option<f64> {
    let mut lambda = 1.0;
    w.trial.resize(x.len(), 0.0);
    loop {
        for k in 0..x.len() {
            x[k] = w.saved[k] + lambda * w.step[k];
        }
        p.residual(x, &mut w.trial);
        let trial = max_abs(&w.trial);
        if trial.is_finite() && trial <= (1.0 - 1e-4 * lambda) * norm {
            std::mem::swap(&mut w.residual, &mut w.trial);
            return Some(lambda);
        }
        lambda *= 0.5;
        if lambda < 1e-6 {
            // No decrease along the Newton direction (a flat part, or a loop with
            // several solutions such as a Schmitt trigger): the full step, as plain
            // Newton takes it.
            return None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `scale (x - 1)^3 = 0`: Newton converges linearly (ratio 2/3) to the triple root.
    struct TripleRoot {
        scale: f64,
        calls: usize,
        x: f64,
    }

    impl NewtonProblem for TripleRoot {
        fn size(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) {
            self.calls += 1;
            self.x = x[0];
            f[0] = self.scale * (x[0] - 1.0).powi(3);
        }
        fn jacobian(&mut self, j: &mut [f64]) {
            j[0] = 3.0 * self.scale * (self.x - 1.0).powi(2);
        }
    }

    /// The circle `x^2 + y^2 = 2` meets the line `x = y` at (1, 1).
    struct CircleWithJacobian {
        at: [f64; 2],
    }

    impl NewtonProblem for CircleWithJacobian {
        fn size(&self) -> usize {
            2
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) {
            self.at = [x[0], x[1]];
            f[0] = x[0] * x[0] + x[1] * x[1] - 2.0;
            f[1] = x[0] - x[1];
        }
        fn jacobian(&mut self, j: &mut [f64]) {
            j.copy_from_slice(&[2.0 * self.at[0], 2.0 * self.at[1], 1.0, -1.0]);
        }
    }

    #[test]
    fn quadratic_convergence_reaches_rounding() {
        let mut x = [3.0, 0.5];
        let mut p = CircleWithJacobian { at: [0.0; 2] };
        let steps = solve(
            &mut p,
            &mut x,
            &NewtonTolerance::new(1e-3, 1e-3),
            &mut NewtonWork::default(),
        )
        .unwrap();
        assert!(
            (x[0] - 1.0).abs() <= 1e-15 && (x[1] - 1.0).abs() <= 1e-15,
            "{x:?}"
        );
        assert!(steps <= 8, "{steps}");
        // The problem saw the final iterate last.
        assert_eq!(p.at, x);
    }

    /// A residual multiplied by 1e-6 reaches 1e-10 while the unknown is still 1e-2
    /// from the root: an absolute residual test would accept that. The step rule
    /// accepts only what the tolerances allow: at rtol 1e-12 the multiple root, which
    /// Newton approaches by a factor 2/3 per step, is not reached in 50 steps from 1
    /// away and the solve fails; at rtol 1e-3 it is accepted within the weights.
    #[test]
    fn acceptance_follows_the_tolerances_not_the_residual_scale() {
        let mut w = NewtonWork::default();
        let mut p = TripleRoot {
            scale: 1e-6,
            calls: 0,
            x: 0.0,
        };
        let mut x = [2.0];
        let tight = solve(&mut p, &mut x, &NewtonTolerance::new(1e-12, 1e-14), &mut w);
        assert!(
            matches!(tight, Err(NewtonError::NoConvergence { .. })),
            "{tight:?} at {x:?}"
        );
        let mut x = [2.0];
        let loose = solve(&mut p, &mut x, &NewtonTolerance::new(1e-3, 1e-3), &mut w);
        assert_eq!(loose, Ok(MAX_ITERATIONS));
        // After 50 steps of ratio 2/3 from 1 away: (2/3)^50 = 1.6e-9 from the root,
        // the last step a third of the distance before it, within 1e-3 * 2e-3.
        assert!((x[0] - 1.0).abs() <= 1e-8, "{x:?}");
    }

    /// `x + y = 1` and `x + y = 3`: no solution, a singular Jacobian.
    struct Parallel;

    impl NewtonProblem for Parallel {
        fn size(&self) -> usize {
            2
        }
        fn is_linear(&self) -> bool {
            true
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) {
            f[0] = x[0] + x[1] - 1.0;
            f[1] = x[0] + x[1] - 3.0;
        }
        fn jacobian(&mut self, j: &mut [f64]) {
            j.copy_from_slice(&[1.0, 1.0, 1.0, 1.0]);
        }
    }

    /// `2x + y = 3`, `x - y = 0` (solution (1, 1)), declared linear or not.
    struct Affine {
        linear: bool,
        residuals: usize,
        jacobians: usize,
    }

    impl NewtonProblem for Affine {
        fn size(&self) -> usize {
            2
        }
        fn is_linear(&self) -> bool {
            self.linear
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) {
            self.residuals += 1;
            f[0] = 2.0 * x[0] + x[1] - 3.0;
            f[1] = x[0] - x[1];
        }
        fn jacobian(&mut self, j: &mut [f64]) {
            self.jacobians += 1;
            j.copy_from_slice(&[2.0, 1.0, 1.0, -1.0]);
        }
    }

    #[test]
    fn a_linear_block_takes_one_step() {
        let tol = NewtonTolerance::default();
        let mut w = NewtonWork::default();
        let mut linear = Affine {
            linear: true,
            residuals: 0,
            jacobians: 0,
        };
        let mut x = [10.0, -7.0];
        assert_eq!(solve(&mut linear, &mut x, &tol, &mut w), Ok(1));
        assert!(
            (x[0] - 1.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15,
            "{x:?}"
        );
        // The start, then the solution (torn variables up to date): one Jacobian, one LU.
        assert_eq!((linear.residuals, linear.jacobians), (2, 1));
        // Not declared linear, the same system is solved by the general iteration.
        let mut general = Affine {
            linear: false,
            residuals: 0,
            jacobians: 0,
        };
        let mut x = [10.0, -7.0];
        assert!(solve(&mut general, &mut x, &tol, &mut w).is_ok());
        assert!(
            (x[0] - 1.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15,
            "{x:?}"
        );
    }

    #[test]
    fn singular_and_non_finite_residuals_are_reported() {
        let mut w = NewtonWork::default();
        let tol = NewtonTolerance::default();
        let r = solve(&mut Parallel, &mut [0.0, 0.0], &tol, &mut w);
        assert_eq!(r, Err(NewtonError::Singular { residual: 3.0 }));
        let mut p = TripleRoot {
            scale: 1.0,
            calls: 0,
            x: 0.0,
        };
        let r = solve(&mut p, &mut [f64::NAN], &tol, &mut w);
        assert!(matches!(r, Err(NewtonError::NotFinite { .. })), "{r:?}");
        assert!(max_abs(&[f64::NAN, 1.0]).is_nan() && max_abs(&[1.0, f64::NAN]).is_nan());
        // A residual exactly 0 at the start: solved without a step.
        assert_eq!(solve(&mut p, &mut [1.0], &tol, &mut w), Ok(0));
        assert_eq!(p.calls, 2);
    }
}
