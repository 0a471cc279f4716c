//! Expandable connectors (spec 9.1.3): the variables an expandable connector declares
//! are only potentially present; those no connection, equation, algorithm or binding
//! uses are not part of the model (a bus declares signals an example may not use).

use crate::eval::var_key;
use crate::flat::{for_each_equation_expr, for_each_ref, FlatModel, Variability};
use std::collections::BTreeSet;
use unimo_syntax::ast::{Expr, Statement, StatementKind};

/// Removes the declared members of the expandable connector instances `buses` (their
/// instance keys) that nothing in `model` uses.
pub(crate) fn remove_unused_members(model: &mut FlatModel, buses: &[String]) {
    if buses.is_empty() {
        return;
    }
    let used = used_names(model);
    let member = |name: &str| {
        buses.iter().any(|b| {
            name.len() > b.len()
                && name.starts_with(b.as_str())
                && matches!(name.as_bytes()[b.len()], b'.' | b'[')
        })
    };
    model.vars.retain(|v| {
        let potential = member(&v.name)
            && v.binding.is_none()
            && !matches!(
                v.variability,
                Variability::Parameter | Variability::Constant
            );
        !potential || used.contains(&v.name)
    });
}

/// Every variable name referenced anywhere in the model (equations of both kinds,
/// algorithms, bindings and attributes).
fn used_names(model: &FlatModel) -> BTreeSet<String> {
    let mut used = BTreeSet::new();
    let mut note = |e: &Expr| {
        for_each_ref(e, &mut |r| {
            used.insert(var_key(r));
        })
    };
    for eqs in [&model.equations, &model.initial_equations] {
        for_each_equation_expr(eqs, &mut note);
    }
    for alg in model.algorithms.iter().chain(&model.initial_algorithms) {
        statements(alg, &mut note);
    }
    for v in &model.vars {
        if let Some(b) = &v.binding {
            note(b);
        }
        for (_, a) in &v.attributes {
            note(a);
        }
    }
    used
}

fn statements(body: &[Statement], note: &mut dyn FnMut(&Expr)) {
    for s in body {
        match &s.kind {
            StatementKind::Assign { target, value } => {
                note(&Expr {
                    kind: unimo_syntax::ast::ExprKind::Ref(target.clone()),
                    span: s.span,
                });
                note(value);
            }
            StatementKind::MultiAssign { targets, value } => {
                targets.iter().flatten().for_each(&mut *note);
                note(value);
            }
            StatementKind::Call(c) => note(c),
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (c, b) in branches {
                    note(c);
                    statements(b, note);
                }
                statements(otherwise, note);
            }
            StatementKind::For { body, .. } => statements(body, note),
            StatementKind::While { condition, body } => {
                note(condition);
                statements(body, note);
            }
            StatementKind::When { branches } => {
                for (c, b) in branches {
                    note(c);
                    statements(b, note);
                }
            }
            StatementKind::Return | StatementKind::Break => {}
        }
    }
}
