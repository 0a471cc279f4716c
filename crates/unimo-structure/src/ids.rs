//! Typed indices for equations and variables of a bipartite graph.

use std::fmt;

/// An equation: a row of the incidence matrix. Displays as `e3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EqId(pub u32);

/// A variable: a column of the incidence matrix. Displays as `v3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VarId(pub u32);

impl EqId {
    /// The equation with this index. Panics past `u32::MAX` equations.
    pub fn new(index: usize) -> EqId {
        EqId(u32::try_from(index).expect("more than u32::MAX equations"))
    }

    /// The position of the equation, for indexing per-equation vectors.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl VarId {
    /// The variable with this index. Panics past `u32::MAX` variables.
    pub fn new(index: usize) -> VarId {
        VarId(u32::try_from(index).expect("more than u32::MAX variables"))
    }

    /// The position of the variable, for indexing per-variable vectors.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for EqId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "e{}", self.0)
    }
}

impl fmt::Display for VarId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "v{}", self.0)
    }
}

impl From<VarId> for u32 {
    fn from(v: VarId) -> u32 {
        v.0
    }
}

impl From<EqId> for u32 {
    fn from(e: EqId) -> u32 {
        e.0
    }
}

impl From<u32> for VarId {
    fn from(i: u32) -> VarId {
        VarId(i)
    }
}

impl From<u32> for EqId {
    fn from(i: u32) -> EqId {
        EqId(i)
    }
}
