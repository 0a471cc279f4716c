//! Expandable connectors (spec 9.1.3): the variables an expandable connector declares
//! are only potentially present; those no equation, algorithm, binding or connection to
//! a non-bus connector uses, directly or through connected buses, are not part of the
//! model (a bus declares signals an example may not use).

use crate::eval::var_key;
use crate::flat::{for_each_equation_expr, for_each_ref, FlatModel, Variability};
use std::collections::BTreeSet;
use unimo_syntax::ast::{Equation, Expr, Statement, StatementKind};

/// Removes the declared members of the expandable connector instances `buses` (their
/// instance keys) that are not present, and the connection equations `conn_eqs` among
/// them. A member is present when the model uses it: in an equation, algorithm or
/// binding, or in a connection equation with a variable that is not a bus member (a
/// signal connected to the bus); presence spreads along the connections of buses to
/// buses (augmentation), and a set of bus members no component uses stays absent
/// (a bus declares signals an example may not use).
pub(crate) fn remove_unused_members(
    model: &mut FlatModel,
    conn_eqs: &mut Vec<Equation>,
    buses: &[String],
) {
    if buses.is_empty() {
        return;
    }
    let member = |name: &str| {
        buses.iter().any(|b| {
            name.len() > b.len()
                && name.starts_with(b.as_str())
                && matches!(name.as_bytes()[b.len()], b'.' | b'[')
        })
    };
    let mut used = used_names(model);
    // Connection equations among bus members only: they join presence sets.
    let mut internal = vec![false; conn_eqs.len()];
    let mut sets = Sets::default();
    for (k, eq) in conn_eqs.iter().enumerate() {
        let mut names = Vec::new();
        for_each_equation_expr(std::slice::from_ref(eq), &mut |e| {
            for_each_ref(e, &mut |r| names.push(var_key(r)));
        });
        if !names.is_empty() && names.iter().all(|n| member(n)) {
            internal[k] = true;
            for pair in names.windows(2) {
                sets.join(&pair[0], &pair[1]);
            }
        } else {
            used.extend(names);
        }
    }
    let present_roots: BTreeSet<String> = used.iter().map(|n| sets.root(n)).collect();
    let present = |name: &str, sets: &mut Sets| {
        used.contains(name) || present_roots.contains(&sets.root(name))
    };
    let mut removed = BTreeSet::new();
    model.vars.retain(|v| {
        let potential = member(&v.name)
            && v.binding.is_none()
            && !matches!(
                v.variability,
                Variability::Parameter | Variability::Constant
            );
        let keep = !potential || present(&v.name, &mut sets);
        if !keep {
            removed.insert(v.name.clone());
        }
        keep
    });
    if removed.is_empty() {
        return;
    }
    let mut k = 0;
    conn_eqs.retain(|eq| {
        let drop = internal[k] && {
            let mut any = false;
            for_each_equation_expr(std::slice::from_ref(eq), &mut |e| {
                for_each_ref(e, &mut |r| any |= removed.contains(&var_key(r)));
            });
            any
        };
        k += 1;
        !drop
    });
}

/// Union-find over variable names.
#[derive(Default)]
struct Sets {
    parent: std::collections::HashMap<String, String>,
}

impl Sets {
    fn root(&mut self, name: &str) -> String {
        let mut cur = name.to_owned();
        let mut path = Vec::new();
        while let Some(p) = self.parent.get(&cur) {
            if *p == cur {
                break;
            }
            path.push(cur.clone());
            cur = p.clone();
        }
        for n in path {
            self.parent.insert(n, cur.clone());
        }
        cur
    }

    fn join(&mut self, a: &str, b: &str) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent.insert(ra, rb);
        }
    }
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
