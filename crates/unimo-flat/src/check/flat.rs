//! Checks on the flat model: a constant's binding reads no parameter (`E2019`, spec
//! 3.8.1: a constant expression holds constants and literals only); `pre` of a
//! continuous-time Real only inside `when` (`E2032`, spec 3.7.5); a parameter with
//! neither a binding nor a start value (`W2001`, spec 8.6: a warning, its value is the
//! type's default start).

use super::walk::{for_each_equation, for_each_statement, outside_when, OutsideWhen};
use crate::error::FlatError;
use crate::eval::var_key;
use crate::flat::{
    for_each_call, for_each_equation_expr, for_each_value_ref, FlatModel, FlatType, Variability,
};
use rustc_hash::FxHashSet as HashSet;
use unimo_source::Diagnostic;
use unimo_syntax::ast::{ComponentRef, Equation, EquationKind, Expr, ExprKind, StatementKind};

/// `E2019` for every constant bound to an expression that reads a parameter.
pub(crate) fn constant_bindings(model: &FlatModel) -> Vec<Diagnostic> {
    let index = model.var_positions();
    let mut diags = Vec::new();
    for v in &model.vars {
        if v.variability != Variability::Constant {
            continue;
        }
        let Some(b) = &v.binding else { continue };
        let mut culprit: Option<usize> = None;
        for_each_value_ref(b, &mut |r| {
            if culprit.is_none() {
                let key = var_key(r);
                culprit = index
                    .get(key.as_str())
                    .copied()
                    .filter(|&j| model.vars[j].variability == Variability::Parameter);
            }
        });
        if let Some(j) = culprit {
            let p = &model.vars[j];
            diags.push(
                FlatError::ConstantReadsParameter {
                    name: v.name.clone(),
                    parameter: p.name.clone(),
                    span: b.span,
                    declared: p.origin,
                }
                .into(),
            );
        }
    }
    diags
}

/// The names of the variables `when` clauses assign (equations' left sides and
/// algorithms' targets inside `when`): the Real ones are discrete-time.
pub(super) fn assigned_in_when(model: &FlatModel) -> HashSet<String> {
    let mut out = HashSet::default();
    let mut note = |e: &Expr| {
        let refs: Vec<&ComponentRef> = match &e.kind {
            ExprKind::Ref(r) => vec![r],
            ExprKind::Tuple(items) => items
                .iter()
                .flatten()
                .filter_map(|x| match &x.kind {
                    ExprKind::Ref(r) => Some(r),
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        };
        for r in refs {
            out.insert(var_key(r));
        }
    };
    for_each_equation(&model.equations, &mut |eq| {
        if let EquationKind::When { branches } = &eq.kind {
            for (_, body) in branches {
                for_each_equation(body, &mut |inner| {
                    if let EquationKind::Simple { lhs, .. } = &inner.kind {
                        note(lhs);
                    }
                });
            }
        }
    });
    for alg in &model.algorithms {
        for_each_statement(alg, &mut |st| {
            if let StatementKind::When { branches } = &st.kind {
                for (_, body) in branches {
                    for_each_statement(body, &mut |inner| match &inner.kind {
                        StatementKind::Assign { target, .. } => {
                            note(&Expr {
                                kind: ExprKind::Ref(target.clone()),
                                span: target.span,
                            });
                        }
                        StatementKind::MultiAssign { targets, .. } => {
                            for t in targets.iter().flatten() {
                                note(t);
                            }
                        }
                        _ => {}
                    });
                }
            }
        });
    }
    out
}

/// The expressions of equations outside `when` clauses (the `when` clauses, their
/// conditions included, are left out).
fn exprs_outside_when(eqs: &[Equation], note: &mut dyn FnMut(&Expr)) {
    outside_when(eqs, &mut |item| match item {
        OutsideWhen::Condition(c) => note(c),
        OutsideWhen::Equation(eq) => for_each_equation_expr(std::slice::from_ref(eq), note),
    });
}

/// `E2032` for `pre(x)` outside `when` clauses, where `x` is a Real variable that
/// varies continuously (declared neither `discrete` nor assigned in a `when`).
pub(crate) fn pre_of_continuous(model: &FlatModel) -> Vec<Diagnostic> {
    let index = model.var_positions();
    let discrete = assigned_in_when(model);
    let mut diags = Vec::new();
    exprs_outside_when(&model.equations, &mut |e| {
        for_each_call(e, &mut |_| {}, &mut |f, args| {
            if f.to_dotted() != "pre" {
                return;
            }
            let Some(ExprKind::Ref(r)) = args.positional.first().map(|a| &a.kind) else {
                return;
            };
            let key = var_key(r);
            let Some(&k) = index.get(key.as_str()) else {
                return;
            };
            let v = &model.vars[k];
            if v.variability != Variability::Continuous
                || !matches!(v.ty, FlatType::Real)
                || discrete.contains(&key)
            {
                return;
            }
            diags.push(
                FlatError::PreOfContinuous {
                    name: v.name.clone(),
                    span: r.span,
                    declared: v.origin,
                }
                .into(),
            );
        })
    });
    diags
}

/// `W2001` for every parameter with neither a binding nor a `start` value that initial
/// equations do not compute (`fixed = false`): it takes its type's default start (0,
/// `false`, the first literal), which is rarely what the modeller meant (spec 8.6).
pub(crate) fn unbound_parameters(model: &FlatModel) -> Vec<Diagnostic> {
    let attribute = |v: &crate::flat::FlatVar, name: &str| {
        v.attributes
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| e.clone())
    };
    let mut diags = Vec::new();
    for v in &model.vars {
        if v.variability != Variability::Parameter
            || v.binding.is_some()
            || attribute(v, "start").is_some()
            || !matches!(
                v.ty,
                FlatType::Real
                    | FlatType::Integer
                    | FlatType::Boolean
                    | FlatType::Enumeration { .. }
            )
        {
            continue;
        }
        let fixed_false =
            attribute(v, "fixed").is_some_and(|e| matches!(e.kind, ExprKind::Bool(false)));
        if fixed_false {
            continue;
        }
        diags.push(
            FlatError::UnboundParameter {
                name: v.name.clone(),
                span: v.origin,
            }
            .into(),
        );
    }
    diags
}
