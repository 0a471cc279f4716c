//! Work counters kept by every integrator.

/// Counters of one solver since its creation (resets keep counting).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts (error test, Newton failure, evaluation failure).
    pub rejected_steps: u64,
    /// Calls of `System::rhs`, including those for finite-difference Jacobians.
    pub rhs_evals: u64,
    /// Jacobian evaluations (analytic or finite differences).
    pub jacobian_evals: u64,
    /// Factorizations of the iteration matrix (Radau5's real and complex pair counts as one).
    pub lu_factorizations: u64,
    /// Newton iterations (one linear solve each).
    pub newton_iterations: u64,
    /// Calls of `System::roots`.
    pub root_evals: u64,
    /// Roots reported to the caller.
    pub events: u64,
}

impl Stats {
    /// Names and values, in declaration order (for hand-written serialization).
    pub fn fields(&self) -> [(&'static str, u64); 8] {
        [
            ("steps", self.steps),
            ("rejected_steps", self.rejected_steps),
            ("rhs_evals", self.rhs_evals),
            ("jacobian_evals", self.jacobian_evals),
            ("lu_factorizations", self.lu_factorizations),
            ("newton_iterations", self.newton_iterations),
            ("root_evals", self.root_evals),
            ("events", self.events),
        ]
    }

    /// One `name: value` line per counter.
    pub fn to_text(&self) -> String {
        self.fields()
            .iter()
            .map(|(name, value)| format!("{name}: {value}\n"))
            .collect()
    }
}
