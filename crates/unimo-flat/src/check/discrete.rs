//! The discrete-valued equation rule (spec 3.8.4): outside `when` clauses and initial
//! sections, a discrete-time variable (an Integer, Boolean, String or enumeration
//! variable, or a Real declared `discrete` that no `when` clause assigns, spec 4.5.3)
//! is only given discrete-time values (`E2033`). `b = x > 0` and `i = integer(x)` are fine (relations and `integer` are
//! discrete-time); `i = x` with a continuous Real `x`, `b = noEvent(x > 0)` and
//! `discrete Real d; d = time` are not.
//!
//! Calls of user functions count as discrete-time whatever their arguments (the
//! specification asks for discrete-time inputs unless the function has
//! `GenerateEvents`, an annotation the flat model does not keep): the check errs on the
//! side of accepting.

use super::walk::{outside_when, OutsideWhen};
use crate::error::FlatError;
use crate::eval::var_key;
use crate::flat::{FlatModel, FlatType, FlatVar, Variability};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::{
    BinaryOp, ComponentRef, Equation, EquationKind, Expr, ExprKind, RelOp, StatementKind,
};

/// Built-in operators whose result is discrete-time whatever their arguments.
const DISCRETE_CALLS: &[&str] = &[
    "pre",
    "edge",
    "change",
    "initial",
    "terminal",
    "sample",
    "integer",
    "floor",
    "ceil",
    "div",
    "size",
    "ndims",
    "cardinality",
    "hold",
    "previous",
    "interval",
    "Clock",
    "subSample",
    "superSample",
    "shiftSample",
    "backSample",
    "noClock",
    "firstTick",
];

/// Built-in functions whose result varies as their arguments do.
const PROPAGATING_CALLS: &[&str] = &[
    "abs",
    "sign",
    "sqrt",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "exp",
    "log",
    "log10",
    "max",
    "min",
    "sum",
    "product",
    "mod",
    "rem",
    "semiLinear",
    "homotopy",
    "delay",
    "transpose",
    "fill",
    "zeros",
    "ones",
    "cat",
    "vector",
    "matrix",
    "scalar",
    "identity",
    "cross",
    "skew",
    "outerProduct",
    "linspace",
    "array",
    "symmetric",
    "diagonal",
    "smooth",
    "Integer",
    "String",
    "noEvent",
];

/// The variables of a flat model by name, and which Reals `when` clauses assign.
struct Vars<'m> {
    index: HashMap<&'m str, &'m FlatVar>,
    in_when: HashSet<String>,
}

impl Vars<'_> {
    /// A variable that must be given discrete-time values: a non-Real one (not a
    /// parameter or constant), or a Real declared `discrete` that no `when` clause
    /// assigns (spec 4.5.x: it must be assigned in one; one that is may also appear in
    /// equations that give other variables its value, `y = y_last`).
    fn is_discrete_valued(&self, v: &FlatVar) -> bool {
        let non_real = matches!(
            v.ty,
            FlatType::Integer | FlatType::Boolean | FlatType::String | FlatType::Enumeration { .. }
        );
        match v.variability {
            Variability::Discrete if v.ty == FlatType::Real => !self.in_when.contains(&v.name),
            Variability::Discrete | Variability::Continuous => non_real,
            _ => false,
        }
    }

    /// A variable whose value changes only at events and that must be given
    /// discrete-time values: non-Real, or a Real declared `discrete`.
    fn discrete_valued(&self, r: &ComponentRef) -> Option<&FlatVar> {
        let v = *self.index.get(var_key(r).as_str())?;
        self.is_discrete_valued(v).then_some(v)
    }

    /// `E2033` when `target` is discrete-valued and `value` is not discrete-time.
    fn check(&self, target: &ComponentRef, value: &Expr, out: &mut Vec<Diagnostic>) {
        if let Some(v) = self.discrete_valued(target) {
            self.check_var(v, value, out);
        }
    }

    /// The first part of `e` that is not a discrete-time expression: a continuous-time
    /// Real, `time`, `der`, or a relation inside `noEvent`.
    fn continuous_part(&self, e: &Expr, no_event: bool) -> Option<(Span, String)> {
        match &e.kind {
            ExprKind::Ref(r) => {
                let key = var_key(r);
                match self.index.get(key.as_str()) {
                    Some(v)
                        if v.ty == FlatType::Real
                            && v.variability == Variability::Continuous
                            && !self.in_when.contains(&key) =>
                    {
                        Some((r.span, format!("`{}` is a continuous-time Real", v.name)))
                    }
                    None if key == "time" && !r.global => {
                        Some((r.span, "`time` is continuous".to_owned()))
                    }
                    _ => None,
                }
            }
            ExprKind::Call { func, args } => {
                let name = func.to_dotted();
                if name == "der" {
                    return Some((e.span, "a derivative is continuous-time".to_owned()));
                }
                if DISCRETE_CALLS.contains(&name.as_str())
                    || !PROPAGATING_CALLS.contains(&name.as_str())
                {
                    return None;
                }
                let inner = no_event || name == "noEvent";
                args.positional
                    .iter()
                    .chain(args.named.iter().map(|a| &a.value))
                    .find_map(|a| self.continuous_part(a, inner))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let relation = matches!(
                    op,
                    BinaryOp::Rel(RelOp::Lt | RelOp::Le | RelOp::Gt | RelOp::Ge)
                );
                if relation && !no_event {
                    return None;
                }
                self.continuous_part(lhs, no_event)
                    .or_else(|| self.continuous_part(rhs, no_event))
            }
            ExprKind::Unary { operand, .. } => self.continuous_part(operand, no_event),
            ExprKind::If {
                branches,
                otherwise,
            } => branches
                .iter()
                .flat_map(|(c, v)| [c, v])
                .find_map(|x| self.continuous_part(x, no_event))
                .or_else(|| self.continuous_part(otherwise, no_event)),
            ExprKind::Array(items) => items.iter().find_map(|x| self.continuous_part(x, no_event)),
            ExprKind::Matrix(rows) => rows
                .iter()
                .flatten()
                .find_map(|x| self.continuous_part(x, no_event)),
            _ => None,
        }
    }

    /// `E2033` when `value`, given to the discrete-valued `v`, is not discrete-time.
    fn check_var(&self, v: &FlatVar, value: &Expr, out: &mut Vec<Diagnostic>) {
        let Some((span, why)) = self.continuous_part(value, false) else {
            return;
        };
        let d = if v.ty == FlatType::Real {
            FlatError::DiscreteRealContinuous {
                name: v.name.clone(),
                why,
                span,
                declared: v.origin,
            }
        } else {
            let ty = match &v.ty {
                FlatType::Enumeration { name, .. } => format!("enumeration {name}"),
                other => format!("{other:?}"),
            };
            FlatError::DiscreteValuedContinuous {
                name: v.name.clone(),
                ty,
                why,
                span,
                declared: v.origin,
            }
        };
        out.push(d.into());
    }

    fn equations(&self, eqs: &[Equation], out: &mut Vec<Diagnostic>) {
        outside_when(eqs, &mut |item| {
            if let OutsideWhen::Equation(Equation {
                kind: EquationKind::Simple { lhs, rhs },
                ..
            }) = item
            {
                if let ExprKind::Ref(r) = &lhs.kind {
                    self.check(r, rhs, out);
                }
                if let ExprKind::Ref(r) = &rhs.kind {
                    self.check(r, lhs, out);
                }
            }
        });
    }
}

/// `E2033` for discrete-time variables given continuous-time values outside `when`
/// clauses: in equations, bindings and algorithm assignments.
pub(crate) fn discrete_equations(model: &FlatModel) -> Vec<Diagnostic> {
    let vars = Vars {
        index: model.vars.iter().map(|v| (v.name.as_str(), v)).collect(),
        in_when: super::flat::assigned_in_when(model),
    };
    let mut out = Vec::new();
    vars.equations(&model.equations, &mut out);
    for v in &model.vars {
        if let Some(b) = &v.binding {
            if vars.is_discrete_valued(v) {
                vars.check_var(v, b, &mut out);
            }
        }
    }
    for alg in &model.algorithms {
        statements(&vars, alg, &mut out);
    }
    // An unrolled `for` equation repeats its source position: one diagnostic each.
    let mut seen = HashSet::default();
    out.retain(|d| {
        let at = d.labels.iter().find(|l| l.primary).map(|l| l.span);
        seen.insert(format!("{at:?}"))
    });
    out
}

fn statements(vars: &Vars<'_>, sts: &[unimo_syntax::ast::Statement], out: &mut Vec<Diagnostic>) {
    for st in sts {
        match &st.kind {
            StatementKind::When { .. } => {}
            StatementKind::Assign { target, value } => vars.check(target, value, out),
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (_, b) in branches {
                    statements(vars, b, out);
                }
                statements(vars, otherwise, out);
            }
            StatementKind::For { body, .. } | StatementKind::While { body, .. } => {
                statements(vars, body, out)
            }
            _ => {}
        }
    }
}
