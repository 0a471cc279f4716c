//! The one parameter evaluator of lowering and analysis: the value a parameter or
//! constant has when the model is translated.
//!
//! The rule (Modelica 3.6, 8.6 and 4.9.x), in [`translation_expr`]:
//! - a constant has the value of its binding (its start value when it has none);
//! - a parameter with `fixed = false` has **no** value at translation: initial
//!   equations compute it, and its start value is only Newton's first guess;
//! - any other parameter has the value of its binding, else of its start value;
//! - a binding is evaluated after the parameters it reads, whatever their order of
//!   declaration; a binding that reads a non-parameter (time, a variable, `pre`, a
//!   sample, an external function) or itself (a cycle) has no value at translation.
//!
//! Lowering (folding, `if` conditions on parameters, array sizes), the structural
//! analysis (zero tearing pivots) and the hidden-constraint search (`singular.rs`) all
//! read values through [`ParameterValues`], so they cannot disagree on a parameter.

use crate::dae::{Dae, Scalar, ScalarKind};
use crate::expr::{EvalEnv, ExprId, Node, ScalarId};
use std::collections::{HashMap, HashSet};

/// The expression that gives `sc` its value at translation, by the rule of the
/// module's doc (None: no value then).
pub fn translation_expr(sc: &Scalar) -> Option<ExprId> {
    match sc.kind {
        ScalarKind::Constant => sc.binding.or(sc.start),
        ScalarKind::Parameter if sc.fixed == Some(false) => None,
        ScalarKind::Parameter => sc.binding.or(sc.start),
        _ => None,
    }
}

/// Whether every leaf of `e` is a literal, a parameter or a constant (no time, `pre`,
/// `initial()`, sample or external call).
pub fn parameters_only(dae: &Dae, e: ExprId) -> bool {
    let mut stack = vec![e];
    let mut seen = HashSet::new();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        match dae.arena.node(x) {
            Node::Const(_) => {}
            Node::Var(s) => {
                if !matches!(
                    dae.scalar(s).kind,
                    ScalarKind::Parameter | ScalarKind::Constant
                ) {
                    return false;
                }
            }
            crate::run_time_leaf!() | Node::Sample(..) => return false,
            // A table's value or an FFT's output exists only at run time (evaluated
            // here it would be NaN, and a comparison of NaN a definite false).
            Node::Ext(f, _) if !f.is_pure() => return false,
            _ => stack.extend(dae.arena.children(x)),
        }
    }
    true
}

/// Parameter values at translation, memoised (NaN: no value).
#[derive(Clone, Debug, Default)]
pub struct ParameterValues {
    values: HashMap<ScalarId, f64>,
}

impl EvalEnv for ParameterValues {
    fn value(&self, s: ScalarId) -> f64 {
        self.values.get(&s).copied().unwrap_or(f64::NAN)
    }
}

impl ParameterValues {
    /// The value of parameter or constant `s` at translation (None: it has none).
    pub fn of_scalar(&mut self, dae: &Dae, s: ScalarId) -> Option<f64> {
        if let Some(&v) = self.values.get(&s) {
            return v.is_finite().then_some(v);
        }
        // Marked before its binding is read: a cycle back to `s` finds no value.
        self.values.insert(s, f64::NAN);
        let value = match translation_expr(dae.scalar(s)) {
            Some(b) if parameters_only(dae, b) => {
                let mut known = true;
                for d in dae.arena.vars(b) {
                    known &= self.of_scalar(dae, d).is_some();
                }
                if known {
                    dae.arena.eval(b, self)
                } else {
                    f64::NAN
                }
            }
            _ => f64::NAN,
        };
        self.values.insert(s, value);
        value.is_finite().then_some(value)
    }

    /// The value of an expression of literals, parameters and constants at
    /// translation (None when it reads anything else or a parameter without a value).
    pub fn of_expr(&mut self, dae: &Dae, e: ExprId) -> Option<f64> {
        if let Some(c) = dae.arena.as_const(e) {
            return Some(c);
        }
        if !parameters_only(dae, e) {
            return None;
        }
        for s in dae.arena.vars(e) {
            self.of_scalar(dae, s)?;
        }
        let v = dae.arena.eval(e, self);
        v.is_finite().then_some(v)
    }

    /// Whether `e` is zero at translation: a zero literal, or an expression of
    /// parameters that evaluates to zero. Unknown values count as nonzero.
    pub fn is_zero(&mut self, dae: &Dae, e: ExprId) -> bool {
        self.of_expr(dae, e) == Some(0.0)
    }

    /// Forgets the parameters found to have no value, so that they are evaluated again
    /// (lowering sets bindings in rounds: a binding may become known later).
    pub fn forget_unknown(&mut self) {
        self.values.retain(|_, x| x.is_finite());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dae::ScalarType;
    use unimo_source::Span;

    fn parameter(dae: &mut Dae, name: &str, kind: ScalarKind) -> ScalarId {
        dae.add_scalar(Scalar::new(
            name.into(),
            kind,
            ScalarType::Real,
            Span::default(),
        ))
    }

    #[test]
    fn fixed_false_has_no_value_even_with_a_start() {
        let mut dae = Dae::default();
        let a = parameter(&mut dae, "a", ScalarKind::Parameter);
        let one = dae.arena.constant(1.0);
        dae.scalars[a.index()].start = Some(one);
        dae.scalars[a.index()].fixed = Some(false);
        let b = parameter(&mut dae, "b", ScalarKind::Parameter);
        let two = dae.arena.constant(2.0);
        let va = dae.arena.var(a);
        let e = dae.arena.mul(two, va);
        dae.scalars[b.index()].binding = Some(e);
        let mut p = ParameterValues::default();
        assert_eq!(p.of_scalar(&dae, a), None);
        assert_eq!(
            p.of_scalar(&dae, b),
            None,
            "b reads a parameter without a value"
        );
        dae.scalars[a.index()].fixed = None;
        let mut p = ParameterValues::default();
        assert_eq!(p.of_scalar(&dae, b), Some(2.0));
    }

    #[test]
    fn bindings_in_any_order_and_cycles() {
        let mut dae = Dae::default();
        let x = parameter(&mut dae, "x", ScalarKind::Parameter);
        let y = parameter(&mut dae, "y", ScalarKind::Constant);
        let vy = dae.arena.var(y);
        let three = dae.arena.constant(3.0);
        let bx = dae.arena.add(vy, three);
        dae.scalars[x.index()].binding = Some(bx);
        let four = dae.arena.constant(4.0);
        dae.scalars[y.index()].binding = Some(four);
        let mut p = ParameterValues::default();
        assert_eq!(p.of_scalar(&dae, x), Some(7.0));
        // A cycle: y = x + 3, x = y + 3.
        let vx = dae.arena.var(x);
        let by = dae.arena.add(vx, three);
        dae.scalars[y.index()].binding = Some(by);
        let mut p = ParameterValues::default();
        assert_eq!(p.of_scalar(&dae, x), None);
        assert_eq!(p.of_scalar(&dae, y), None);
        let t = dae.arena.time();
        assert!(!parameters_only(&dae, t));
        assert!(!p.is_zero(&dae, vx), "unknown counts as nonzero");
    }
}
