//! The syntax tree's children in one place: the direct sub-expressions of an
//! expression ([`Expr::for_each_child`], [`Expr::for_each_child_mut`]), the expressions
//! of equations and statements, and a pre-order walk ([`walk_expr`]) that a pass
//! prunes where it needs to. A pass that looks for some kinds of node matches those
//! and hands every other node to these functions, instead of listing every
//! `ExprKind` again.

use crate::ast::*;

/// Whether a pre-order walk descends into the node just visited.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Walk {
    /// Visit the node's children next.
    Descend,
    /// Leave the node's children out.
    Skip,
}

/// The body of [`Expr::for_each_child`] and [`Expr::for_each_child_mut`], written
/// once: `$iter` and `$as_ref` are `iter`/`as_ref` or `iter_mut`/`as_mut`, `$subs` the
/// subscript walk of the same access, `$m` nothing or `mut`.
macro_rules! child_walk {
    ($(#[$doc:meta])* $name:ident, $iter:ident, $as_ref:ident, $subs:ident $(, $m:tt)?) => {
        $(#[$doc])*
        pub fn $name(&$($m)? self, f: &mut dyn FnMut(&$($m)? Expr)) {
            match &$($m)? self.kind {
                ExprKind::Ref(r) => r.$subs(f),
                ExprKind::Call { args, .. } => {
                    args.positional.$iter().for_each(&mut *f);
                    args.named.$iter().for_each(|a| f(&$($m)? a.value));
                    let ranges = args.iterators.$iter().filter_map(|i| i.range.$as_ref());
                    ranges.for_each(f);
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
                ExprKind::Array(items) => items.$iter().for_each(f),
                ExprKind::Matrix(rows) => rows.$iter().flatten().for_each(f),
                ExprKind::Tuple(items) => items.$iter().flatten().for_each(f),
                ExprKind::Comprehension { body, indices } => {
                    let ranges = indices.$iter().filter_map(|i| i.range.$as_ref());
                    ranges.for_each(&mut *f);
                    f(body);
                }
                ExprKind::PartialApplication { args, .. } => {
                    args.$iter().for_each(|a| f(&$($m)? a.value))
                }
                ExprKind::Integer(_)
                | ExprKind::Real(_)
                | ExprKind::Bool(_)
                | ExprKind::String(_)
                | ExprKind::End => {}
            }
        }
    };
}

/// [`ComponentRef::for_each_subscript`] and its `_mut` twin, written once.
macro_rules! subscript_walk {
    ($(#[$doc:meta])* $name:ident $(, $m:tt)?) => {
        $(#[$doc])*
        pub fn $name(&$($m)? self, f: &mut dyn FnMut(&$($m)? Expr)) {
            for p in &$($m)? self.parts {
                for s in &$($m)? p.subscripts {
                    if let Subscript::Expr(x) = s {
                        f(x);
                    }
                }
            }
        }
    };
}

impl Expr {
    child_walk!(
        /// Calls `f` with every direct sub-expression, in source order: subscripts of a
        /// reference; a call's positional arguments, named arguments and iterator
        /// ranges; operands; the conditions and values of `if` branches; range bounds;
        /// array and matrix elements; tuple items; a comprehension's index ranges, then
        /// its body; the arguments of a partial application.
        for_each_child, iter, as_ref, for_each_subscript
    );
    child_walk!(
        /// [`Expr::for_each_child`] with mutable access, in the same order.
        for_each_child_mut, iter_mut, as_mut, for_each_subscript_mut, mut
    );
}

impl ComponentRef {
    subscript_walk!(
        /// Calls `f` with the expression of every subscript (`a[i].b[j + 1]`: `i`, then
        /// `j + 1`); `:` has none.
        for_each_subscript
    );
    subscript_walk!(
        /// [`ComponentRef::for_each_subscript`] with mutable access.
        for_each_subscript_mut, mut
    );
}

fn index_ranges(indices: &[ForIndex], f: &mut dyn FnMut(&Expr)) {
    indices.iter().filter_map(|i| i.range.as_ref()).for_each(f);
}

/// Visits `e` and its sub-expressions in pre-order; `visit` decides per node whether
/// the walk descends into it.
pub fn walk_expr(e: &Expr, visit: &mut dyn FnMut(&Expr) -> Walk) {
    if visit(e) == Walk::Descend {
        e.for_each_child(&mut |c| walk_expr(c, visit));
    }
}

impl Equation {
    /// Calls `f` with every expression of this equation at its own level: both sides,
    /// a call, the conditions of `if`/`when` branches and the ranges of `for`
    /// indices. Nested equations are in [`Equation::for_each_nested`]; the references
    /// of `connect` are not expressions.
    pub fn for_each_expr(&self, f: &mut dyn FnMut(&Expr)) {
        match &self.kind {
            EquationKind::Simple { lhs, rhs } => {
                f(lhs);
                f(rhs);
            }
            EquationKind::Call(c) => f(c),
            EquationKind::If { branches, .. } | EquationKind::When { branches } => {
                branches.iter().for_each(|(c, _)| f(c))
            }
            EquationKind::For { indices, .. } => index_ranges(indices, f),
            EquationKind::Connect { .. } => {}
        }
    }

    /// Calls `f` with every equation nested directly in this one (the bodies of
    /// `if`, `when` and `for`, branch by branch).
    pub fn for_each_nested(&self, f: &mut dyn FnMut(&Equation)) {
        match &self.kind {
            EquationKind::If {
                branches,
                otherwise,
            } => {
                branches.iter().flat_map(|(_, b)| b).for_each(&mut *f);
                otherwise.iter().for_each(f);
            }
            EquationKind::When { branches } => branches.iter().flat_map(|(_, b)| b).for_each(f),
            EquationKind::For { body, .. } => body.iter().for_each(f),
            EquationKind::Simple { .. } | EquationKind::Call(_) | EquationKind::Connect { .. } => {}
        }
    }
}

/// Calls `f` with every expression of `eqs` and of the equations nested in them, in
/// source order (an equation's own expressions before its nested equations).
pub fn equation_exprs(eqs: &[Equation], f: &mut dyn FnMut(&Expr)) {
    for e in eqs {
        e.for_each_expr(f);
        e.for_each_nested(&mut |n| equation_exprs(std::slice::from_ref(n), f));
    }
}

impl Statement {
    /// Calls `f` with every expression of this statement at its own level: the
    /// assigned value (and the subscripts of the target), the targets of a multiple
    /// assignment, a call, conditions, and `for` ranges.
    pub fn for_each_expr(&self, f: &mut dyn FnMut(&Expr)) {
        match &self.kind {
            StatementKind::Assign { target, value } => {
                target.for_each_subscript(f);
                f(value);
            }
            StatementKind::MultiAssign { targets, value } => {
                targets.iter().flatten().for_each(&mut *f);
                f(value);
            }
            StatementKind::Call(c) => f(c),
            StatementKind::If { branches, .. } | StatementKind::When { branches } => {
                branches.iter().for_each(|(c, _)| f(c))
            }
            StatementKind::For { indices, .. } => index_ranges(indices, f),
            StatementKind::While { condition, .. } => f(condition),
            StatementKind::Return | StatementKind::Break => {}
        }
    }

    /// Calls `f` with every statement nested directly in this one.
    pub fn for_each_nested(&self, f: &mut dyn FnMut(&Statement)) {
        match &self.kind {
            StatementKind::If {
                branches,
                otherwise,
            } => {
                branches.iter().flat_map(|(_, b)| b).for_each(&mut *f);
                otherwise.iter().for_each(f);
            }
            StatementKind::When { branches } => branches.iter().flat_map(|(_, b)| b).for_each(f),
            StatementKind::For { body, .. } | StatementKind::While { body, .. } => {
                body.iter().for_each(f)
            }
            StatementKind::Assign { .. }
            | StatementKind::MultiAssign { .. }
            | StatementKind::Call(_)
            | StatementKind::Return
            | StatementKind::Break => {}
        }
    }
}

/// Calls `f` with every expression of `stmts` and of the statements nested in them.
pub fn statement_exprs(stmts: &[Statement], f: &mut dyn FnMut(&Expr)) {
    for s in stmts {
        s.for_each_expr(f);
        s.for_each_nested(&mut |n| statement_exprs(std::slice::from_ref(n), f));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_expr(src: &str) -> Expr {
        crate::parse_expression(unimo_source::FileId(0), src).expect("parses")
    }

    /// Every reference of a walk, in pre-order.
    fn refs(e: &Expr) -> Vec<String> {
        let mut out = Vec::new();
        walk_expr(e, &mut |x| {
            if let ExprKind::Ref(r) = &x.kind {
                out.push(r.to_dotted());
            }
            Walk::Descend
        });
        out
    }

    #[test]
    fn every_kind_of_child_is_reached() {
        let e = parse_expr(
            "if a > b[i] then f(c, e, n = d) else {g for g in 1:h} + [k, l; m, -o] \
             + sum(p[j] for j in q:r:s)",
        );
        assert_eq!(
            refs(&e),
            ["a", "b", "i", "c", "e", "d", "h", "g", "k", "l", "m", "o", "p", "j", "q", "r", "s"]
        );
    }

    #[test]
    fn skip_prunes_and_mut_rewrites() {
        let mut e = parse_expr("size(x, 1) + y");
        let mut seen = Vec::new();
        walk_expr(&e, &mut |x| match &x.kind {
            ExprKind::Call { .. } => Walk::Skip,
            ExprKind::Ref(r) => {
                seen.push(r.to_dotted());
                Walk::Descend
            }
            _ => Walk::Descend,
        });
        assert_eq!(seen, ["y"]);
        fn rename(e: &mut Expr) {
            if let ExprKind::Ref(r) = &mut e.kind {
                r.parts[0].name.text = format!("{}1", r.parts[0].name.text).into();
            }
            e.for_each_child_mut(&mut rename);
        }
        rename(&mut e);
        assert_eq!(refs(&e), ["x1", "y1"]);
    }
}
