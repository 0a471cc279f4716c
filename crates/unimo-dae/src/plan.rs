//! The causal plan: which scalars are states, and the ordered steps that compute every
//! other unknown from the states, parameters, discrete values and time. It is a
//! separate artifact from the DAE (the DAE only gains the equations index reduction
//! differentiated).

use crate::dae::EqId;
use crate::expr::{ExprId, ScalarId};

/// One step of the plan.
#[derive(Clone, Debug)]
pub enum PlanStep {
    /// `var := value`, from equation `eq` solved explicitly.
    Assign {
        var: ScalarId,
        value: ExprId,
        eq: EqId,
    },
    /// A block solved simultaneously by Newton's method on its iteration variables:
    /// given the iteration variables, `inner` computes the torn variables in order,
    /// then `residuals` must vanish. `jacobian` is d residuals / d iteration variables
    /// (row-major, inner assignments substituted), symbolic.
    Block(Block),
}

#[derive(Clone, Debug)]
pub struct Block {
    pub iteration_vars: Vec<ScalarId>,
    pub residuals: Vec<ExprId>,
    pub inner: Vec<(ScalarId, ExprId)>,
    pub jacobian: Vec<ExprId>,
    /// Residuals are linear in the iteration variables (one Newton step solves it).
    pub linear: bool,
    /// Residuals switch with a condition (`if`-equations solving different variables).
    pub switched: bool,
    /// The equations of the block (original and differentiated).
    pub equations: Vec<EqId>,
}

/// Counts after each analysis step (`unimo check --stats`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlanStats {
    pub flat_scalars: usize,
    pub aliases_removed: usize,
    pub constants_removed: usize,
    pub equations: usize,
    pub differentiated_equations: usize,
    pub states: usize,
    pub dummy_derivatives: usize,
    pub algebraic: usize,
    pub blocks: usize,
    pub torn_blocks: usize,
    pub largest_block: usize,
    pub zero_crossings: usize,
    pub pruned_equations: usize,
}

/// The causal plan of a model.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// The states, in a fixed order; `derivatives[i]` is the scalar of `der(states[i])`.
    pub states: Vec<ScalarId>,
    pub derivatives: Vec<ScalarId>,
    pub dummy_derivatives: Vec<ScalarId>,
    /// Steps computing every unknown from the states.
    pub steps: Vec<PlanStep>,
    pub stats: PlanStats,
}
