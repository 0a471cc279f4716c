//! Coordinate projection onto invariants (Hairer, Lubich and Wanner, *Geometric
//! Numerical Integration*, IV.4 "projection methods"; SUNDIALS CVODE's projection): a
//! system may declare invariants `c(t, x) = 0` that its solution keeps where they are
//! active ([`System::n_invariants`]). After each accepted step, and wherever the caller
//! asks (an event's state), the state is moved to the nearest point of `c = 0` in the
//! error-weighted norm: Gauss–Newton steps `Δx = -D Jᵀ (J D Jᵀ)⁻¹ c` with
//! `D = diag(w_i²)`, `w_i = atol_i + rtol_i |x_i|` (the weights of the methods' error
//! tests, so that a state with a loose tolerance takes more of the correction) and
//! `J = ∂c/∂x` of the active rows by forward differences.
//!
//! The Jacobian is kept between projections while the same invariants are active and
//! the iteration contracts by at least [`REFRESH_CONTRACTION`] per step (the corrections
//! are of the size of the integration error, so a Jacobian a few steps old still moves
//! the state onto the manifold in a few cheap iterations); it is evaluated again after a
//! slower contraction, and only in the columns where it was found nonzero the last time
//! all columns were evaluated (when the active set changed).

use crate::dense::lu_solve;
use crate::error::EvalError;
use crate::system::{Invariants, System};

/// Gauss–Newton iterations per projection at most.
const MAX_ITERATIONS: usize = 8;
/// A contraction of the residual slower than this asks for a new Jacobian.
const REFRESH_CONTRACTION: f64 = 0.1;
/// A correction whose every component is below this many rounding units of its state
/// ends the iteration: the residual is at the level of rounding.
const ROUNDING_UNITS: f64 = 8.0;
/// An invariant within this many rounding units of the size of its terms holds: `|c_i|
/// <= ROUNDING_UNITS_C eps Σ_j |∂c_i/∂x_j x_j|` (the rounding of evaluating it).
const ROUNDING_UNITS_C: f64 = 4.0;

/// Work counters of the projections (also after failures).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ProjectionStats {
    /// Projections that moved the state.
    pub projections: u64,
    /// Evaluations of the invariants (Jacobian columns included).
    pub evaluations: u64,
    /// Jacobians evaluated.
    pub jacobians: u64,
}

/// The projection's state between calls: the Jacobian it may reuse and scratch space.
#[derive(Debug, Clone, Default)]
pub struct Projector {
    /// The invariants at the state being projected.
    now: Invariants,
    /// Active rows now; `jacobian_rows`: those the Jacobian was made for.
    rows: Vec<usize>,
    jacobian_rows: Vec<usize>,
    /// Row-major `rows × n` Jacobian of the active invariants.
    jacobian: Vec<f64>,
    jacobian_valid: bool,
    /// Columns found nonzero in the last full evaluation.
    columns: Vec<usize>,
    weights: Vec<f64>,
    start: Vec<f64>,
    step: Vec<f64>,
    matrix: Vec<f64>,
    rhs: Vec<f64>,
    perm: Vec<usize>,
    /// The active invariants before the last step (the secant update).
    old: Vec<f64>,
    perturbed: Vec<f64>,
    /// The invariants at `perturbed`.
    at_perturbed: Invariants,
    pub stats: ProjectionStats,
}

impl Projector {
    /// Forgets the Jacobian (after an event: other states, another active set).
    pub fn invalidate(&mut self) {
        self.jacobian_valid = false;
    }

    /// Projects `x` at `t` onto the active invariants of `system`, with the weights
    /// `atol_i + rtol_i |x_i|`. Ok(true): `x` moved; Ok(false): no invariant active, all
    /// hold already, or the iteration did not reduce the residual (`x` unchanged).
    pub fn project(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &mut [f64],
        rtol: &[f64],
        atol: &[f64],
    ) -> Result<bool, EvalError> {
        let m = system.n_invariants();
        if m == 0 {
            return Ok(false);
        }
        let n = x.len();
        self.now.resize(m);
        self.evaluate(system, t, x)?;
        self.rows.clear();
        self.rows
            .extend((0..m).filter(|&i| self.now.active[i] && self.now.values[i] != 0.0));
        if self.rows.is_empty() {
            return Ok(false);
        }
        self.rows.clear();
        self.rows.extend((0..m).filter(|&i| self.now.active[i]));
        if self.rows != self.jacobian_rows {
            self.jacobian_valid = false;
            self.columns.clear();
        }
        self.weights.clear();
        self.weights.extend((0..n).map(|i| {
            let w = atol[i] + rtol[i] * x[i].abs();
            w * w
        }));
        self.start.clear();
        self.start.extend_from_slice(x);
        let mut residual = self.residual();
        let initial = residual;
        for _ in 0..MAX_ITERATIONS {
            let fresh = !self.jacobian_valid;
            if fresh {
                self.evaluate_jacobian(system, t, x)?;
            }
            if self.at_rounding(x) {
                break;
            }
            if !self.gauss_newton_step(n) {
                if fresh {
                    break;
                }
                self.jacobian_valid = false;
                continue;
            }
            let rounding = self
                .step
                .iter()
                .zip(x.iter())
                .all(|(d, v)| d.abs() <= ROUNDING_UNITS * f64::EPSILON * v.abs());
            for (v, d) in x.iter_mut().zip(&self.step) {
                *v += d;
            }
            self.old.clear();
            self.old
                .extend(self.rows.iter().map(|&i| self.now.values[i]));
            self.evaluate(system, t, x)?;
            let new = self.residual();
            if new >= residual {
                // No progress: back to the better point before this step.
                for (v, d) in x.iter_mut().zip(&self.step) {
                    *v -= d;
                }
                if fresh || rounding {
                    break;
                }
                self.jacobian_valid = false;
                continue;
            }
            if new == 0.0 || rounding {
                residual = new;
                break;
            }
            if new > REFRESH_CONTRACTION * residual {
                self.jacobian_valid = false;
            } else {
                self.secant_update(n);
            }
            residual = new;
        }
        if residual >= initial {
            x.copy_from_slice(&self.start);
            return Ok(false);
        }
        self.stats.projections += 1;
        Ok(x != &self.start[..])
    }

    /// Broyden's update of the kept Jacobian after a step `Δx` that changed the active
    /// invariants from `old` to `values`: `J += (Δc - J Δx) Δxᵀ / (Δxᵀ Δx)`, so that the
    /// next step sees the change the last one made (superlinear convergence with a
    /// Jacobian evaluated steps ago).
    fn secant_update(&mut self, n: usize) {
        let norm2: f64 = self
            .columns
            .iter()
            .map(|&j| self.step[j] * self.step[j])
            .sum();
        if norm2 <= 0.0 {
            return;
        }
        for (r, &i) in self.rows.iter().enumerate() {
            let row = &mut self.jacobian[r * n..(r + 1) * n];
            let predicted: f64 = self.columns.iter().map(|&j| row[j] * self.step[j]).sum();
            let miss = (self.now.values[i] - self.old[r] - predicted) / norm2;
            for &j in &self.columns {
                row[j] += miss * self.step[j];
            }
        }
    }

    /// Whether every active invariant is within the rounding of its evaluation at `x`
    /// (estimated from the Jacobian's terms).
    fn at_rounding(&self, x: &[f64]) -> bool {
        let n = x.len();
        self.rows.iter().enumerate().all(|(r, &i)| {
            let size: f64 = self
                .columns
                .iter()
                .map(|&j| (self.jacobian[r * n + j] * x[j]).abs())
                .sum();
            self.now.values[i].abs() <= ROUNDING_UNITS_C * f64::EPSILON * size
        })
    }

    /// Largest absolute value of the active invariants.
    fn residual(&self) -> f64 {
        self.rows
            .iter()
            .map(|&i| self.now.values[i].abs())
            .fold(0.0, f64::max)
    }

    fn evaluate(&mut self, system: &mut dyn System, t: f64, x: &[f64]) -> Result<(), EvalError> {
        self.stats.evaluations += 1;
        system.invariants(t, x, &mut self.now)?;
        match self.now.values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(EvalError::domain(format!("an invariant is {v}"))),
            None => Ok(()),
        }
    }

    /// Forward differences of the active rows at `x` (whose values are in `values`):
    /// every column after a change of the active set, else the columns found nonzero
    /// then.
    fn evaluate_jacobian(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &[f64],
    ) -> Result<(), EvalError> {
        let (n, m) = (x.len(), self.now.values.len());
        let rows = self.rows.len();
        let full = self.columns.is_empty();
        if full {
            self.columns.extend(0..n);
        }
        self.jacobian.clear();
        self.jacobian.resize(rows * n, 0.0);
        self.perturbed.clear();
        self.perturbed.extend_from_slice(x);
        self.at_perturbed.resize(m);
        self.stats.jacobians += 1;
        for &j in &self.columns {
            let h = f64::EPSILON.sqrt() * x[j].abs().max(self.weights[j].sqrt() * 1e3);
            let h = if h > 0.0 { h } else { f64::EPSILON.sqrt() };
            self.perturbed[j] = x[j] + h;
            let h = self.perturbed[j] - x[j];
            self.stats.evaluations += 1;
            system.invariants(t, &self.perturbed, &mut self.at_perturbed)?;
            self.perturbed[j] = x[j];
            for (r, &i) in self.rows.iter().enumerate() {
                self.jacobian[r * n + j] = (self.at_perturbed.values[i] - self.now.values[i]) / h;
            }
        }
        if full {
            let jacobian = &self.jacobian;
            self.columns
                .retain(|&j| (0..rows).any(|r| jacobian[r * n + j] != 0.0));
        }
        self.jacobian_rows.clone_from(&self.rows);
        self.jacobian_valid = true;
        // Back to the point itself (the system may keep the last evaluation).
        self.evaluate(system, t, x)
    }

    /// `step = -D Jᵀ (J D Jᵀ)⁻¹ c`; false when `J D Jᵀ` is singular or not finite.
    fn gauss_newton_step(&mut self, n: usize) -> bool {
        let rows = self.rows.len();
        self.matrix.clear();
        self.matrix.resize(rows * rows, 0.0);
        for a in 0..rows {
            for b in 0..rows {
                let (ra, rb) = (&self.jacobian[a * n..], &self.jacobian[b * n..]);
                self.matrix[a * rows + b] = self
                    .columns
                    .iter()
                    .map(|&j| ra[j] * self.weights[j] * rb[j])
                    .sum();
            }
        }
        self.rhs.clear();
        self.rhs
            .extend(self.rows.iter().map(|&i| self.now.values[i]));
        self.perm.resize(rows, 0);
        if !lu_solve(rows, &mut self.matrix, &mut self.rhs, &mut self.perm) {
            return false;
        }
        self.step.clear();
        self.step.resize(n, 0.0);
        for &j in &self.columns {
            let s: f64 = (0..rows)
                .map(|r| self.jacobian[r * n + j] * self.rhs[r])
                .sum();
            self.step[j] = -self.weights[j] * s;
        }
        self.step.iter().all(|d| d.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x' = (-y, x) on the unit circle; the invariant x² + y² - 1 (active while the
    /// third state is positive).
    struct Circle;

    impl System for Circle {
        fn len(&self) -> usize {
            3
        }
        fn differential(&self) -> &[bool] {
            &[true, true, true]
        }
        fn rhs(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
            out[0] = -x[1];
            out[1] = x[0];
            out[2] = 0.0;
            Ok(())
        }
        fn n_invariants(&self) -> usize {
            1
        }
        fn invariants(
            &mut self,
            _t: f64,
            x: &[f64],
            out: &mut Invariants,
        ) -> Result<(), EvalError> {
            out.values[0] = x[0] * x[0] + x[1] * x[1] - 1.0;
            out.active[0] = x[2] > 0.0;
            Ok(())
        }
    }

    #[test]
    fn projects_onto_the_circle_along_the_normal() {
        let mut p = Projector::default();
        let mut x = [0.7, 0.7, 1.0];
        let (rtol, atol) = ([1e-6; 3], [1e-8; 3]);
        assert!(p.project(&mut Circle, 0.0, &mut x, &rtol, &atol).unwrap());
        let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
        assert!((r - 1.0).abs() < 1e-15, "radius {r}");
        // Equal weights (equal components) on a radial error: the nearest point keeps
        // the direction.
        let half = 0.5f64.sqrt();
        assert!(
            (x[0] - half).abs() < 1e-12 && (x[1] - half).abs() < 1e-12,
            "{x:?}"
        );
        // The third state is no argument of the invariant: untouched.
        assert_eq!(x[2], 1.0);
        // Again with the kept Jacobian from a point near the first.
        let mut y = [0.6 * 0.999, 0.8 * 0.999 + 1e-4, 1.0];
        let jacobians = p.stats.jacobians;
        assert!(p.project(&mut Circle, 0.0, &mut y, &rtol, &atol).unwrap());
        let r = (y[0] * y[0] + y[1] * y[1]).sqrt();
        assert!((r - 1.0).abs() < 1e-15, "radius {r}");
        assert_eq!(p.stats.jacobians, jacobians, "the Jacobian was reused");
    }

    #[test]
    fn an_inactive_invariant_leaves_the_state() {
        let mut p = Projector::default();
        let mut x = [0.7, 0.8, -1.0];
        let before = x;
        assert!(!p
            .project(&mut Circle, 0.0, &mut x, &[1e-6; 3], &[1e-8; 3])
            .unwrap());
        assert_eq!(x, before);
    }
}
