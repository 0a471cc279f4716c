//! Errors: `EvalError` is what a [`System`](crate::System) reports from its own functions,
//! `SolveError` is what the integrators report, each with a stable code (`E45xx`) and the
//! context needed to act on it (time, step size, worst components).

/// A failure inside the system's own functions (right-hand side, Jacobian, root functions).
///
/// The integrators treat an `EvalError` during a step as a failed step: they reduce the step
/// size and try again, and give up with [`SolveError::Eval`] after repeated failures.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalError {
    /// A function was evaluated outside its domain (`sqrt(-1)`, `log(0)`, ...).
    #[error("domain error: {message}")]
    Domain { message: String },
    /// Any other failure of the system.
    #[error("{message}")]
    Failed { message: String },
}

impl EvalError {
    /// A domain error with a message.
    pub fn domain(message: impl Into<String>) -> Self {
        EvalError::Domain {
            message: message.into(),
        }
    }

    /// Any other failure with a message.
    pub fn failed(message: impl Into<String>) -> Self {
        EvalError::Failed {
            message: message.into(),
        }
    }
}

/// Component index and its weighted error (or weighted Newton correction), largest first.
pub type WorstComponents = Vec<(usize, f64)>;

/// Everything that can stop an integrator.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The caller passed something unusable (sizes, tolerances, times).
    #[error("E4501 invalid solver input: {message}")]
    InvalidInput { message: String },
    /// The method cannot integrate systems with algebraic rows (Dormand–Prince).
    #[error(
        "E4502 {method} cannot integrate a system with {algebraic_rows} algebraic row(s); use BDF or Radau5"
    )]
    AlgebraicRowsNotSupported {
        method: &'static str,
        algebraic_rows: usize,
    },
    /// The step size fell below the smallest step representable at `time`.
    #[error("E4503 step size {step:e} too small at t = {time} (worst components: {worst:?})")]
    StepSizeTooSmall {
        time: f64,
        step: f64,
        worst: WorstComponents,
    },
    /// The Newton iteration failed repeatedly, even with a fresh Jacobian and smaller steps.
    #[error("E4504 Newton iteration failed repeatedly at t = {time}, h = {step:e} (worst components: {worst:?})")]
    NewtonFailed {
        time: f64,
        step: f64,
        worst: WorstComponents,
    },
    /// The local error test failed repeatedly.
    #[error("E4505 error test failed repeatedly at t = {time}, h = {step:e} (worst components: {worst:?})")]
    ErrorTestFailed {
        time: f64,
        step: f64,
        worst: WorstComponents,
    },
    /// More steps than `Options::max_steps_per_call` in one call.
    #[error("E4506 more than {max_steps} steps in one call, stopped at t = {time}")]
    TooManySteps { time: f64, max_steps: usize },
    /// The system's functions failed (or produced NaN/inf) repeatedly, or at the initial point.
    #[error("E4507 evaluation failed at t = {time}: {message}")]
    Eval { time: f64, message: String },
    /// The iteration matrix stayed singular although the step size was reduced.
    #[error("E4508 singular iteration matrix at t = {time}, h = {step:e}")]
    SingularMatrix { time: f64, step: f64 },
    /// `interpolate` was asked for a time outside the last step.
    #[error("E4509 t = {time} is outside the last step [{start}, {end}]")]
    OutsideDenseOutput { time: f64, start: f64, end: f64 },
}

impl SolveError {
    /// The stable code of this error (`E45xx`).
    pub fn code(&self) -> &'static str {
        match self {
            SolveError::InvalidInput { .. } => "E4501",
            SolveError::AlgebraicRowsNotSupported { .. } => "E4502",
            SolveError::StepSizeTooSmall { .. } => "E4503",
            SolveError::NewtonFailed { .. } => "E4504",
            SolveError::ErrorTestFailed { .. } => "E4505",
            SolveError::TooManySteps { .. } => "E4506",
            SolveError::Eval { .. } => "E4507",
            SolveError::SingularMatrix { .. } => "E4508",
            SolveError::OutsideDenseOutput { .. } => "E4509",
        }
    }

    pub(crate) fn invalid(message: impl Into<String>) -> Self {
        SolveError::InvalidInput {
            message: message.into(),
        }
    }
}
