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
    /// Residuals are affine in the iteration variables once the block's relations are
    /// frozen (each mode of a switched block is linear): one Newton step solves it.
    pub linear: bool,
    /// Residuals switch with a condition (`if`-equations solving different variables).
    pub switched: bool,
    /// The equations of the block (original and differentiated).
    pub equations: Vec<EqId>,
}

/// A set of candidates of which the simulator picks, at run time, which are states
/// (dynamic state selection, as in Mattsson & Söderlind's dummy derivatives with
/// run-time pivoting). The set's `k` states are `s = A x`, `x` = `candidates` (`n` of
/// them), `A` the `k x n` 0/1 matrix in the discrete scalars `selectors` (row-major);
/// the plan solves `s = A x` with the constraints for `x` and computes
/// `der(s) = A der(x)`. `jacobian` (`equations x n`, row-major) is the Jacobian of the
/// set's equations in the candidates' derivatives (which equals that of their integrals
/// in `x`): the simulator keeps as states the candidates whose columns it does not need
/// for a well-conditioned pivot, and switches `A` (and sets `s` from `x`) when the
/// current choice becomes ill-conditioned.
#[derive(Clone, Debug)]
pub struct StateSet {
    pub states: Vec<ScalarId>,
    pub candidates: Vec<ScalarId>,
    /// `der(candidates[j])`.
    pub derivatives: Vec<ScalarId>,
    pub selectors: Vec<ScalarId>,
    pub equations: Vec<EqId>,
    pub jacobian: Vec<ExprId>,
    /// The first selection: the candidate each state is (`k` indices).
    pub initial: Vec<usize>,
}

/// Counts after each analysis step (`unimo check --stats`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlanStats {
    pub flat_scalars: usize,
    /// Parameters folded into the code as constants.
    pub parameters_folded: usize,
    pub aliases_removed: usize,
    pub constants_removed: usize,
    pub equations: usize,
    pub differentiated_equations: usize,
    pub states: usize,
    pub dummy_derivatives: usize,
    /// Dynamically selected state sets.
    pub state_sets: usize,
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
    /// Dynamically selected state sets (their states are among `states`).
    pub state_sets: Vec<StateSet>,
    /// Equations [`crate::prune::prune`] left out: their relations are no zero
    /// crossings (nothing computes their operands).
    pub pruned: Vec<EqId>,
    pub stats: PlanStats,
}
