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
            Section::Equation(es) => for_each_equation_expr(&es.equations, note),
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
        st.for_each_nested(&mut |n| for_each_statement(std::slice::from_ref(n), f));
    }
}

/// The expressions a statement itself holds (not those of nested statements).
fn statement_exprs(st: &Statement, note: &mut dyn FnMut(&Expr)) {
    st.for_each_expr(note);
}

/// Calls `f` with every equation of `eqs`, nested ones included (outer first).
pub(crate) fn for_each_equation(eqs: &[Equation], f: &mut dyn FnMut(&Equation)) {
    for eq in eqs {
        f(eq);
        eq.for_each_nested(&mut |n| for_each_equation(std::slice::from_ref(n), f));
    }
}

/// What [`outside_when`] visits: the condition of an `if` equation, or an equation that
/// is neither `if`, `for` nor `when`.
pub(crate) enum OutsideWhen<'a> {
    Condition(&'a Expr),
    Equation(&'a Equation),
}

/// Calls `f` with every `if` condition and every other equation of `eqs` outside `when`
/// clauses, inside `if` branches and `for` bodies (the `when` clauses, their conditions
/// included, are left out).
pub(crate) fn outside_when<'a>(eqs: &'a [Equation], f: &mut dyn FnMut(OutsideWhen<'a>)) {
    for eq in eqs {
        match &eq.kind {
            EquationKind::When { .. } => {}
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (c, b) in branches {
                    f(OutsideWhen::Condition(c));
                    outside_when(b, f);
                }
                outside_when(otherwise, f);
            }
            EquationKind::For { body, .. } => outside_when(body, f),
            _ => f(OutsideWhen::Equation(eq)),
        }
    }
}
