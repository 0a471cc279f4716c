//! Solver settings: method choice, tolerances (scalar or per component), step limits and the
//! choice of linear solver.

use crate::error::SolveError;

/// The integration method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Variable-step variable-order BDF (orders 1–5), IDA/DASSL style; stiff problems and DAEs.
    Bdf,
    /// Radau IIA of order 5 (RADAU5); stiff problems and DAEs, high accuracy.
    Radau5,
    /// Dormand–Prince 5(4); non-stiff ODEs only.
    Dopri5,
    /// Let the caller decide; [`Solver::new`](crate::Solver::new) resolves it to BDF.
    Auto,
}

impl Method {
    /// The concrete method `Auto` stands for: BDF, which handles stiff systems and DAEs.
    pub fn resolved(self) -> Method {
        match self {
            Method::Auto => Method::Bdf,
            other => other,
        }
    }

    /// The method a lower-case name stands for (`"bdf"`, `"radau5"`, `"dopri5"`, `"auto"`:
    /// the CLI's `--method` values and `experiment(__unimo_method = ...)`).
    pub fn from_name(name: &str) -> Option<Method> {
        match name {
            "auto" => Some(Method::Auto),
            "bdf" => Some(Method::Bdf),
            "radau5" => Some(Method::Radau5),
            "dopri5" => Some(Method::Dopri5),
            _ => None,
        }
    }

    /// Short name for messages.
    pub fn name(self) -> &'static str {
        match self {
            Method::Bdf => "BDF",
            Method::Radau5 => "Radau5",
            Method::Dopri5 => "Dopri5",
            Method::Auto => "Auto",
        }
    }
}

/// A tolerance: one value for all components or one per component.
#[derive(Debug, Clone, PartialEq)]
pub enum Tolerance {
    Scalar(f64),
    PerComponent(Vec<f64>),
}

impl Tolerance {
    /// Expands to one value per component, checking length and sign.
    pub(crate) fn expand(&self, len: usize, what: &str) -> Result<Vec<f64>, SolveError> {
        let values = match self {
            Tolerance::Scalar(value) => vec![*value; len],
            Tolerance::PerComponent(values) => {
                if values.len() != len {
                    return Err(SolveError::invalid(format!(
                        "{what} has {} entries, the system has {len} unknowns",
                        values.len()
                    )));
                }
                values.clone()
            }
        };
        if let Some(bad) = values.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return Err(SolveError::invalid(format!(
                "{what} must be finite and non-negative, got {bad}"
            )));
        }
        Ok(values)
    }
}

/// Which linear solver factors the iteration matrix of the implicit methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearSolverChoice {
    /// Sparse LU when the system gives a sparsity pattern and has at least
    /// [`SPARSE_AUTO_THRESHOLD`] unknowns, dense LU otherwise.
    Auto,
    /// Dense partial-pivoting LU.
    Dense,
    /// Sparse LU on the system's pattern (dense pattern when it gives none).
    Sparse,
}

/// Size from which `LinearSolverChoice::Auto` picks the sparse LU (given a pattern).
pub const SPARSE_AUTO_THRESHOLD: usize = 100;

impl LinearSolverChoice {
    /// Whether the implicit methods factor a system of `size` unknowns with the sparse
    /// LU (`has_pattern`: the system gives a sparsity pattern).
    pub fn picks_sparse(self, size: usize, has_pattern: bool) -> bool {
        match self {
            LinearSolverChoice::Dense => false,
            LinearSolverChoice::Sparse => has_pattern,
            LinearSolverChoice::Auto => has_pattern && size >= SPARSE_AUTO_THRESHOLD,
        }
    }
}

/// Settings shared by all methods.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance (default 1e-6).
    pub relative_tolerance: Tolerance,
    /// Absolute tolerance (default 1e-8).
    pub absolute_tolerance: Tolerance,
    /// Largest step size (default: unbounded).
    pub max_step: f64,
    /// First step size; `None` selects it with Hairer's algorithm.
    pub initial_step: Option<f64>,
    /// Most internal steps in one `step_until` call (default 500 000).
    pub max_steps_per_call: usize,
    /// BDF only: leave algebraic components out of the local error test (IDA's
    /// `suppressalg`, default false).
    pub suppress_algebraic_error: bool,
    /// BDF only: highest order, 1..=5 (default 5).
    pub max_order: usize,
    /// Linear solver for BDF and Radau5.
    pub linear_solver: LinearSolverChoice,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            relative_tolerance: Tolerance::Scalar(1e-6),
            absolute_tolerance: Tolerance::Scalar(1e-8),
            max_step: f64::INFINITY,
            initial_step: None,
            max_steps_per_call: 500_000,
            suppress_algebraic_error: false,
            max_order: 5,
            linear_solver: LinearSolverChoice::Auto,
        }
    }
}

impl Options {
    /// Default options with scalar tolerances.
    pub fn with_tolerances(relative: f64, absolute: f64) -> Self {
        Options {
            relative_tolerance: Tolerance::Scalar(relative),
            absolute_tolerance: Tolerance::Scalar(absolute),
            ..Options::default()
        }
    }

    /// Checks the settings that do not depend on the system.
    pub(crate) fn validate(&self) -> Result<(), SolveError> {
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(SolveError::invalid(format!(
                "max_step must be positive, got {}",
                self.max_step
            )));
        }
        if let Some(step) = self.initial_step {
            if !(step > 0.0 && step.is_finite()) {
                return Err(SolveError::invalid(format!(
                    "initial_step must be positive and finite, got {step}"
                )));
            }
        }
        if !(1..=5).contains(&self.max_order) {
            return Err(SolveError::invalid(format!(
                "max_order must be within 1..=5, got {}",
                self.max_order
            )));
        }
        if self.max_steps_per_call == 0 {
            return Err(SolveError::invalid("max_steps_per_call must be positive"));
        }
        Ok(())
    }
}
