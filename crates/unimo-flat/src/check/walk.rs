//! Walks over a class as written: every expression of its declarations, modifiers,
//! equations and statements, and every statement with the section it is in.

use crate::flat::for_each_equation_expr;
use unimo_syntax::ast::*;

/// Calls `note` with every expression of a modification (nested ones included).
pub(crate) fn modification_exprs(m: &Modification, note: &mut dyn FnMut(&Expr)) {
    if let Some(cm) = &m.class_mod {
        class_mod_exprs(cm, note);
    }
    if let Some(b) = &m.binding {
        note(b);
    }
}

/// Calls `note` with every expression of a class modification.
pub(crate) fn class_mod_exprs(cm: &ClassModification, note: &mut dyn FnMut(&Expr)) {
    for a in &cm.args {
        match a {
            Argument::Modify {
                modification: Some(m),
                ..
            } => modification_exprs(m, note),
            Argument::Modify { .. } => {}
            Argument::Redeclare { element, .. } => {
                if let RedeclaredElement::Component(cc) = element {
                    for d in &cc.components {
                        if let Some(m) = &d.modification {
                            modification_exprs(m, note);
                        }
                    }
                }
            }
        }
    }
}

/// Calls `note` with every expression of a composition: bindings, modifiers,
/// conditions, dimensions, equations and statements (not those of nested classes).
pub(crate) fn composition_exprs(c: &Composition, note: &mut dyn FnMut(&Expr)) {
    for e in &c.elements {
        match &e.kind {
            ElementKind::Component(cc) => {
                for s in &cc.type_dims {
                    subscript_exprs(s, note);
                }
                for d in &cc.components {
                    for s in &d.dims {
                        subscript_exprs(s, note);
                    }
                    if let Some(m) = &d.modification {
                        modification_exprs(m, note);
                    }
                    if let Some(x) = &d.condition {
                        note(x);
                    }
                }
            }
            ElementKind::Extends(x) => {
                if let Some(m) = &x.modification {
                    class_mod_exprs(m, note);
                }
            }
            ElementKind::Import(_) | ElementKind::Class(_) => {}
        }
    }
    for s in &c.sections {
        match s {
            Section::Equation(es) => {
                for_each_equation_expr(&es.equations, note);
                for_each_equation(&es.equations, &mut |eq| {
                    if let EquationKind::For { indices, .. } = &eq.kind {
                        for r in indices.iter().filter_map(|i| i.range.as_ref()) {
                            note(r);
                        }
                    }
                });
            }
            Section::Algorithm(al) => {
                for_each_statement(&al.statements, &mut |st| statement_exprs(st, note))
            }
        }
    }
}

fn subscript_exprs(s: &Subscript, note: &mut dyn FnMut(&Expr)) {
    if let Subscript::Expr(x) = s {
        note(x);
    }
}

/// Calls `f` with every statement of `sts`, nested ones included (outer first).
pub(crate) fn for_each_statement(sts: &[Statement], f: &mut dyn FnMut(&Statement)) {
    for st in sts {
        f(st);
        match &st.kind {
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (_, b) in branches {
                    for_each_statement(b, f);
                }
                for_each_statement(otherwise, f);
            }
            StatementKind::When { branches } => {
                for (_, b) in branches {
                    for_each_statement(b, f);
                }
            }
            StatementKind::For { body, .. } | StatementKind::While { body, .. } => {
                for_each_statement(body, f)
            }
            _ => {}
        }
    }
}

/// The expressions a statement itself holds (not those of nested statements).
fn statement_exprs(st: &Statement, note: &mut dyn FnMut(&Expr)) {
    match &st.kind {
        StatementKind::Assign { target, value } => {
            for p in &target.parts {
                for s in &p.subscripts {
                    subscript_exprs(s, note);
                }
            }
            note(value);
        }
        StatementKind::MultiAssign { targets, value } => {
            for t in targets.iter().flatten() {
                note(t);
            }
            note(value);
        }
        StatementKind::Call(c) => note(c),
        StatementKind::If { branches, .. } | StatementKind::When { branches } => {
            for (c, _) in branches {
                note(c);
            }
        }
        StatementKind::For { indices, .. } => {
            for i in indices {
                if let Some(r) = &i.range {
                    note(r);
                }
            }
        }
        StatementKind::While { condition, .. } => note(condition),
        StatementKind::Return | StatementKind::Break => {}
    }
}

/// Calls `f` with every equation of `eqs`, nested ones included (outer first).
pub(crate) fn for_each_equation(eqs: &[Equation], f: &mut dyn FnMut(&Equation)) {
    for eq in eqs {
        f(eq);
        match &eq.kind {
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (_, b) in branches {
                    for_each_equation(b, f);
                }
                for_each_equation(otherwise, f);
            }
            EquationKind::When { branches } => {
                for (_, b) in branches {
                    for_each_equation(b, f);
                }
            }
            EquationKind::For { body, .. } => for_each_equation(body, f),
            _ => {}
        }
    }
}
