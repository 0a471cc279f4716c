//! Walks over flat expressions: every expression of a list of equations, every
//! component reference or call in an expression (read or rewritten), every child.

use unimo_syntax::ast::{ComponentRef, Equation, EquationKind, Expr, ExprKind, Name};

/// Calls `note` with every expression of `eqs` (conditions included, nested equations
/// too; the references of `connect` are not expressions).
pub fn for_each_equation_expr(eqs: &[Equation], note: &mut dyn FnMut(&Expr)) {
    for e in eqs {
        match &e.kind {
            EquationKind::Simple { lhs, rhs } => {
                note(lhs);
                note(rhs);
            }
            EquationKind::Call(c) => note(c),
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (c, b) in branches {
                    note(c);
                    for_each_equation_expr(b, note);
                }
                for_each_equation_expr(otherwise, note);
            }
            EquationKind::When { branches } => {
                for (c, b) in branches {
                    note(c);
                    for_each_equation_expr(b, note);
                }
            }
            EquationKind::For { body, .. } => for_each_equation_expr(body, note),
            EquationKind::Connect { .. } => {}
        }
    }
}

/// Calls `f` with every component reference in `e` (not function names), subscripts
/// of references included.
pub fn for_each_ref(e: &Expr, f: &mut dyn FnMut(&ComponentRef)) {
    refs(e, f, false, &mut |_, _| {});
}

/// Calls `on_call` with the function name and arguments of every call in `e` (outer
/// calls first), and `f` with every component reference.
pub fn for_each_call(
    e: &Expr,
    f: &mut dyn FnMut(&ComponentRef),
    on_call: &mut dyn FnMut(&Name, &unimo_syntax::ast::CallArgs),
) {
    refs(e, f, false, on_call);
}

/// [`for_each_ref`] without the arguments of `size`, `ndims`, `cardinality` and
/// `isPresent`, which read a variable's structure, not its value.
pub fn for_each_value_ref(e: &Expr, f: &mut dyn FnMut(&ComponentRef)) {
    refs(e, f, true, &mut |_, _| {});
}

fn refs(
    e: &Expr,
    f: &mut dyn FnMut(&ComponentRef),
    values_only: bool,
    on_call: &mut dyn FnMut(&Name, &unimo_syntax::ast::CallArgs),
) {
    match &e.kind {
        ExprKind::Ref(r) => {
            for p in &r.parts {
                for s in &p.subscripts {
                    if let unimo_syntax::ast::Subscript::Expr(x) = s {
                        refs(x, f, values_only, on_call);
                    }
                }
            }
            f(r);
        }
        ExprKind::Call { func, args } => {
            on_call(func, args);
            // `size(x, 1)` reads x's shape, not its value.
            if values_only
                && matches!(
                    func.to_dotted().as_str(),
                    "size" | "ndims" | "cardinality" | "isPresent"
                )
            {
                return;
            }
            for a in &args.positional {
                refs(a, f, values_only, on_call);
            }
            for a in &args.named {
                refs(&a.value, f, values_only, on_call);
            }
            for i in &args.iterators {
                if let Some(r) = &i.range {
                    refs(r, f, values_only, on_call);
                }
            }
        }
        ExprKind::Unary { operand, .. } => refs(operand, f, values_only, on_call),
        ExprKind::Binary { lhs, rhs, .. } => {
            refs(lhs, f, values_only, on_call);
            refs(rhs, f, values_only, on_call);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                refs(c, f, values_only, on_call);
                refs(v, f, values_only, on_call);
            }
            refs(otherwise, f, values_only, on_call);
        }
        ExprKind::Range { start, step, stop } => {
            refs(start, f, values_only, on_call);
            if let Some(s) = step {
                refs(s, f, values_only, on_call);
            }
            refs(stop, f, values_only, on_call);
        }
        ExprKind::Array(items) => items.iter().for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Matrix(rows) => rows
            .iter()
            .flatten()
            .for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Tuple(items) => items
            .iter()
            .flatten()
            .for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Comprehension { body, indices } => {
            for i in indices {
                if let Some(r) = &i.range {
                    refs(r, f, values_only, on_call);
                }
            }
            refs(body, f, values_only, on_call);
        }
        ExprKind::PartialApplication { args, .. } => {
            for a in args {
                refs(&a.value, f, values_only, on_call);
            }
        }
        ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
    }
}

/// Applies `f` to every component reference in `e` (not to function names).
pub fn rewrite_refs(e: &mut Expr, f: &mut dyn FnMut(&mut ComponentRef)) {
    match &mut e.kind {
        ExprKind::Ref(r) => {
            for p in &mut r.parts {
                for s in &mut p.subscripts {
                    if let unimo_syntax::ast::Subscript::Expr(x) = s {
                        rewrite_refs(x, f);
                    }
                }
            }
            f(r);
        }
        ExprKind::Call { args, .. } => {
            for a in &mut args.positional {
                rewrite_refs(a, f);
            }
            for a in &mut args.named {
                rewrite_refs(&mut a.value, f);
            }
            for i in &mut args.iterators {
                if let Some(r) = &mut i.range {
                    rewrite_refs(r, f);
                }
            }
        }
        ExprKind::Unary { operand, .. } => rewrite_refs(operand, f),
        ExprKind::Binary { lhs, rhs, .. } => {
            rewrite_refs(lhs, f);
            rewrite_refs(rhs, f);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                rewrite_refs(c, f);
                rewrite_refs(v, f);
            }
            rewrite_refs(otherwise, f);
        }
        ExprKind::Range { start, step, stop } => {
            rewrite_refs(start, f);
            if let Some(s) = step {
                rewrite_refs(s, f);
            }
            rewrite_refs(stop, f);
        }
        ExprKind::Array(items) => items.iter_mut().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Matrix(rows) => rows.iter_mut().flatten().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Tuple(items) => items.iter_mut().flatten().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Comprehension { body, indices } => {
            for i in indices.iter_mut() {
                if let Some(r) = &mut i.range {
                    rewrite_refs(r, f);
                }
            }
            rewrite_refs(body, f);
        }
        ExprKind::PartialApplication { args, .. } => {
            for a in args {
                rewrite_refs(&mut a.value, f);
            }
        }
        ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
    }
}

/// Children of an expression, mutably (subscripts of references excluded).
pub(super) fn for_each_child(e: &mut Expr, f: &mut dyn FnMut(&mut Expr)) {
    match &mut e.kind {
        ExprKind::Call { args, .. } => {
            args.positional.iter_mut().for_each(&mut *f);
            args.named.iter_mut().for_each(|a| f(&mut a.value));
            for i in &mut args.iterators {
                if let Some(r) = &mut i.range {
                    f(r);
                }
            }
        }
        ExprKind::Unary { operand, .. } => f(operand),
        ExprKind::Binary { lhs, rhs, .. } => {
            f(lhs);
            f(rhs);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                f(c);
                f(v);
            }
            f(otherwise);
        }
        ExprKind::Range { start, step, stop } => {
            f(start);
            if let Some(s) = step {
                f(s);
            }
            f(stop);
        }
        ExprKind::Array(items) => items.iter_mut().for_each(f),
        ExprKind::Matrix(rows) => rows.iter_mut().flatten().for_each(f),
        ExprKind::Tuple(items) => items.iter_mut().flatten().for_each(f),
        ExprKind::Comprehension { body, indices } => {
            for i in indices.iter_mut() {
                if let Some(r) = &mut i.range {
                    f(r);
                }
            }
            f(body);
        }
        ExprKind::PartialApplication { args, .. } => {
            args.iter_mut().for_each(|a| f(&mut a.value));
        }
        ExprKind::Ref(_)
        | ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
    }
}
