//! The crate's one coded error enum (`E3xxx`, structural analysis).

use std::fmt::{self, Display};

use crate::dm::Part;
use crate::ids::{EqId, VarId};

/// Everything that can go wrong in structural analysis. Each variant has a stable code
/// (see [`StructError::code`]); ids are those of the graph the failing step worked on,
/// so the symbolic side can name them in its diagnostics.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum StructError {
    /// E3201: no perfect matching exists. `over` are equations that together constrain
    /// fewer variables than their number (Dulmage–Mendelsohn over-determined part);
    /// `under` are variables that the equations cannot all determine.
    #[error(
        "structurally singular system: {} equation(s) over-determine {} variable(s) [{}]; \
         {} variable(s) are under-determined [{}]",
        over.eqs.len(), over.vars.len(), IdList(&over.eqs),
        under.vars.len(), IdList(&under.vars)
    )]
    Singular { over: Part, under: Part },

    /// E3202: index reduction needed to differentiate an equation that the symbolic
    /// side cannot differentiate.
    #[error("index reduction failed: equation {eq} cannot be differentiated: {reason}")]
    IndexReductionFailed { eq: EqId, reason: String },

    /// E3203: an equation (named by its original, undifferentiated id) would be
    /// differentiated more than `limit` times; guards against runaway index reduction.
    #[error(
        "index reduction stopped: equation {eq} would be differentiated more than {limit} times"
    )]
    DifferentiationLimit { eq: EqId, limit: u32 },

    /// E3204: at a differentiation level, the differentiated equations `eqs` cannot be
    /// solved for an equal number of derivative variables (dummy derivative selection).
    #[error(
        "dummy derivative selection failed at level {level}: equation(s) [{}] have no \
         derivative variable left to solve for",
        IdList(eqs)
    )]
    DummySelectionFailed { level: u32, eqs: Vec<EqId> },

    /// E3205: an edge names a variable that the graph does not have.
    #[error("equation {eq} refers to variable {var}, but the graph has {n_vars} variable(s)")]
    EdgeOutOfRange { eq: EqId, var: VarId, n_vars: usize },

    /// E3206: a block handed to tearing has different numbers of equations and variables.
    #[error("block is not square: {eqs} equation(s), {vars} variable(s)")]
    BlockNotSquare { eqs: usize, vars: usize },

    /// E3290: a result or an input broke an invariant (reported by `verify`, or a
    /// contract breach of an [`crate::IndexReductionSystem`]). Always a bug, never a model error.
    #[error("invalid structural data ({check}): {detail}")]
    Invalid { check: &'static str, detail: String },
}

impl StructError {
    /// The stable diagnostic code of this error.
    pub fn code(&self) -> &'static str {
        match self {
            StructError::Singular { .. } => "E3201",
            StructError::IndexReductionFailed { .. } => "E3202",
            StructError::DifferentiationLimit { .. } => "E3203",
            StructError::DummySelectionFailed { .. } => "E3204",
            StructError::EdgeOutOfRange { .. } => "E3205",
            StructError::BlockNotSquare { .. } => "E3206",
            StructError::Invalid { .. } => "E3290",
        }
    }

    /// Shorthand for an [`StructError::Invalid`].
    pub(crate) fn invalid(check: &'static str, detail: impl Into<String>) -> StructError {
        StructError::Invalid {
            check,
            detail: detail.into(),
        }
    }
}

/// Formats at most the first eight ids of a list, then how many were left out.
pub(crate) struct IdList<'a, T>(pub &'a [T]);

impl<T: Display> Display for IdList<'_, T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 8;
        for (i, item) in self.0.iter().take(SHOWN).enumerate() {
            if i > 0 {
                f.write_str(" ")?;
            }
            write!(f, "{item}")?;
        }
        if self.0.len() > SHOWN {
            write!(f, " ... (+{} more)", self.0.len() - SHOWN)?;
        }
        Ok(())
    }
}
