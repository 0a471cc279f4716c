//! Derivative chains: variable → its derivative and equation → its differentiated form,
//! with the inverse ("integral") maps and differentiation levels.

use crate::error::StructError;
use crate::ids::{EqId, VarId};
use crate::IndexReductionSystem;

/// The derivative relations of a system. A chain is `x → der(x) → der(der(x)) → ...`;
/// each variable has at most one derivative and at most one integral, chains have no
/// cycles. The same holds for equations.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DerivativeChains {
    pub var_derivative: Vec<Option<VarId>>,
    pub var_integral: Vec<Option<VarId>>,
    pub eq_derivative: Vec<Option<EqId>>,
    pub eq_integral: Vec<Option<EqId>>,
}

impl DerivativeChains {
    /// Reads the relations from a system and checks that they form chains.
    pub fn from_system<S: IndexReductionSystem + ?Sized>(
        system: &S,
    ) -> Result<DerivativeChains, StructError> {
        let graph = system.graph();
        let var_derivative: Vec<Option<VarId>> =
            graph.vars().map(|v| system.var_derivative(v)).collect();
        let eq_derivative: Vec<Option<EqId>> =
            graph.eqs().map(|e| system.eq_derivative(e)).collect();
        DerivativeChains::from_derivatives(var_derivative, eq_derivative)
    }

    /// Builds the chains from the forward maps and checks them.
    pub fn from_derivatives(
        var_derivative: Vec<Option<VarId>>,
        eq_derivative: Vec<Option<EqId>>,
    ) -> Result<DerivativeChains, StructError> {
        let var_integral = invert(&var_derivative, "variable derivatives")?;
        let eq_integral = invert(&eq_derivative, "equation derivatives")?;
        let chains = DerivativeChains {
            var_derivative,
            var_integral,
            eq_derivative,
            eq_integral,
        };
        check_acyclic(
            &chains.var_derivative,
            &chains.var_integral,
            "variable derivatives",
        )?;
        check_acyclic(
            &chains.eq_derivative,
            &chains.eq_integral,
            "equation derivatives",
        )?;
        Ok(chains)
    }

    /// The derivative of a variable.
    pub fn var_derivative(&self, v: VarId) -> Option<VarId> {
        self.var_derivative.get(v.index()).copied().flatten()
    }

    /// The variable this one is the derivative of.
    pub fn var_integral(&self, v: VarId) -> Option<VarId> {
        self.var_integral.get(v.index()).copied().flatten()
    }

    /// The differentiated form of an equation.
    pub fn eq_derivative(&self, e: EqId) -> Option<EqId> {
        self.eq_derivative.get(e.index()).copied().flatten()
    }

    /// The equation this one was differentiated from.
    pub fn eq_integral(&self, e: EqId) -> Option<EqId> {
        self.eq_integral.get(e.index()).copied().flatten()
    }

    /// How many times the chain's root was differentiated to give `v` (0 for a root).
    pub fn var_level(&self, mut v: VarId) -> u32 {
        let mut level = 0;
        while let Some(below) = self.var_integral(v) {
            v = below;
            level += 1;
        }
        level
    }

    /// How many times the chain's root was differentiated to give `e` (0 for a root).
    pub fn eq_level(&self, mut e: EqId) -> u32 {
        let mut level = 0;
        while let Some(below) = self.eq_integral(e) {
            e = below;
            level += 1;
        }
        level
    }

    /// The undifferentiated variable of `v`'s chain.
    pub fn var_root(&self, mut v: VarId) -> VarId {
        while let Some(below) = self.var_integral(v) {
            v = below;
        }
        v
    }

    /// The undifferentiated (original) equation of `e`'s chain.
    pub fn eq_root(&self, mut e: EqId) -> EqId {
        while let Some(below) = self.eq_integral(e) {
            e = below;
        }
        e
    }

    /// How many derivatives were made of `e` (the length of its chain above it).
    pub fn differentiation_count(&self, mut e: EqId) -> u32 {
        let mut count = 0;
        while let Some(above) = self.eq_derivative(e) {
            e = above;
            count += 1;
        }
        count
    }

    /// [`Self::differentiation_count`] for every equation, in linear time.
    pub fn differentiation_counts(&self) -> Vec<u32> {
        let mut counts = vec![0u32; self.eq_derivative.len()];
        for top in 0..counts.len() {
            if self.eq_derivative[top].is_some() {
                continue;
            }
            let (mut e, mut count) = (EqId::new(top), 0);
            while let Some(below) = self.eq_integral(e) {
                count += 1;
                counts[below.index()] = count;
                e = below;
            }
        }
        counts
    }

    /// [`Self::var_level`] for every variable, in linear time.
    pub fn var_levels(&self) -> Vec<u32> {
        let mut levels = vec![0u32; self.var_derivative.len()];
        for root in 0..levels.len() {
            if self.var_integral[root].is_some() {
                continue;
            }
            let mut v = VarId::new(root);
            while let Some(above) = self.var_derivative(v) {
                levels[above.index()] = levels[v.index()] + 1;
                v = above;
            }
        }
        levels
    }

    /// The root variable of every variable's chain, in linear time.
    pub fn var_roots(&self) -> Vec<VarId> {
        let mut roots: Vec<VarId> = (0..self.var_derivative.len()).map(VarId::new).collect();
        for root in 0..roots.len() {
            if self.var_integral[root].is_some() {
                continue;
            }
            let mut v = VarId::new(root);
            while let Some(above) = self.var_derivative(v) {
                roots[above.index()] = VarId::new(root);
                v = above;
            }
        }
        roots
    }
}

fn invert<T: Copy + Into<u32>, U: From<u32> + Copy>(
    forward: &[Option<T>],
    what: &'static str,
) -> Result<Vec<Option<U>>, StructError> {
    let mut inverse: Vec<Option<U>> = vec![None; forward.len()];
    for (from, to) in forward.iter().enumerate() {
        let Some(to) = to else { continue };
        let to = (*to).into() as usize;
        let slot = inverse.get_mut(to).ok_or_else(|| {
            StructError::invalid(what, format!("#{from} maps to #{to}, outside the graph"))
        })?;
        if slot.is_some() {
            return Err(StructError::invalid(
                what,
                format!("#{to} is the derivative of two items"),
            ));
        }
        *slot = Some(U::from(from as u32));
    }
    Ok(inverse)
}

/// Every item must be reachable from a chain root; items on a cycle are not.
fn check_acyclic<T: Copy + Into<u32>>(
    derivative: &[Option<T>],
    integral: &[Option<T>],
    what: &'static str,
) -> Result<(), StructError> {
    let mut reached = 0usize;
    let roots = integral
        .iter()
        .enumerate()
        .filter(|(_, below)| below.is_none());
    for (root, _) in roots {
        let mut at = root;
        reached += 1;
        while let Some(above) = derivative[at] {
            at = above.into() as usize;
            reached += 1;
        }
    }
    if reached != derivative.len() {
        return Err(StructError::invalid(
            what,
            "the derivative relation has a cycle",
        ));
    }
    Ok(())
}
