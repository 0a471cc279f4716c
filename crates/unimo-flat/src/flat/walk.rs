//! Walks over flat expressions: every expression of a list of equations, every
//! component reference or call in an expression (read or rewritten), every child.

use unimo_syntax::ast::{ComponentRef, Equation, Expr, ExprKind, Name};

/// Calls `note` with every expression of `eqs` (conditions included, nested equations
/// too; the references of `connect` are not expressions).
pub fn for_each_equation_expr(eqs: &[Equation], note: &mut dyn FnMut(&Expr)) {
    unimo_syntax::visit::equation_exprs(eqs, note);
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
            e.for_each_child(&mut |x| refs(x, f, values_only, on_call));
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
            e.for_each_child(&mut |x| refs(x, f, values_only, on_call));
        }
        _ => e.for_each_child(&mut |x| refs(x, f, values_only, on_call)),
    }
}

/// Applies `f` to every component reference in `e` (not to function names).
pub fn rewrite_refs(e: &mut Expr, f: &mut dyn FnMut(&mut ComponentRef)) {
    e.for_each_child_mut(&mut |x| rewrite_refs(x, f));
    if let ExprKind::Ref(r) = &mut e.kind {
        f(r);
    }
}
