//! Overconstrained connections (spec 9.4): the arguments of `Connections.root`,
//! `potentialRoot`, `branch`, `isRoot` and `rooted` are variables of an overdetermined
//! type or record, one that declares an `equalityConstraint` function (`E2036`).

use super::elements::{component_class, component_type, find_component};
use super::walk::for_each_equation;
use super::Ctx;
use crate::error::FlatError;
use crate::lookup::Found;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

/// The operators of `Connections` whose arguments are overdetermined variables (the
/// other arguments, a priority, are numbers).
const OPERATORS: &[&str] = &["root", "potentialRoot", "branch", "isRoot", "rooted"];

impl Ctx<'_, '_> {
    /// `E2036` for the `Connections.*` operators of class `id` applied to variables
    /// whose type has no `equalityConstraint`.
    pub(super) fn overconstrained(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let mut calls: Vec<(String, ComponentRef)> = Vec::new();
        let mut note = |e: &Expr| {
            crate::flat::for_each_call(e, &mut |_| {}, &mut |f, args| {
                let [first, op] = f.parts.as_slice() else {
                    return;
                };
                if first.text != "Connections" || !OPERATORS.contains(&op.text.as_str()) {
                    return;
                }
                let n = if op.text == "branch" { 2 } else { 1 };
                for a in args.positional.iter().take(n) {
                    if let ExprKind::Ref(r) = &a.kind {
                        calls.push((op.text.to_string(), r.clone()));
                    }
                }
            });
        };
        for s in &composition.sections {
            if let Section::Equation(es) = s {
                for_each_equation(&es.equations, &mut |eq| match &eq.kind {
                    EquationKind::Call(e) => note(e),
                    EquationKind::Simple { lhs, rhs } => {
                        note(lhs);
                        note(rhs);
                    }
                    EquationKind::If { branches, .. } => {
                        for (c, _) in branches {
                            note(c);
                        }
                    }
                    _ => {}
                });
            }
        }
        for (op, r) in calls {
            self.overdetermined_argument(id, &op, &r);
        }
    }

    /// `E2036` when `r` (an argument of `Connections.op`) resolves to a variable whose
    /// type declares no `equalityConstraint`.
    fn overdetermined_argument(&mut self, id: ClassId, op: &str, r: &ComponentRef) {
        let Some(mut cur) = find_component(self.tree, id, &r.parts[0].name.text) else {
            return;
        };
        for p in &r.parts[1..] {
            let Some(c) = component_class(self.tree, &cur) else {
                return;
            };
            let Some(next) = find_component(self.tree, c, &p.name.text) else {
                return;
            };
            cur = next;
        }
        let what = match component_type(self.tree, &cur) {
            Some(Found::Builtin(b)) => format!("of the predefined type {b}"),
            Some(Found::Class(c)) => {
                if self.has_equality_constraint(c, 0) {
                    return;
                }
                format!(
                    "of type `{}`, which declares no `equalityConstraint`",
                    self.tree.full_name(c)
                )
            }
            _ => return,
        };
        self.out.push(
            FlatError::NotOverdetermined {
                operator: op.to_owned(),
                name: unimo_syntax::print::cref(r),
                what,
                span: r.span,
                declared: cur.name_span,
            }
            .into(),
        );
    }

    /// Whether class `c` (or a class it is defined from) declares `equalityConstraint`.
    fn has_equality_constraint(&mut self, c: ClassId, depth: usize) -> bool {
        if depth > 16 {
            return true; // give up: accept
        }
        if self.tree.member_class(c, "equalityConstraint").is_some() {
            return true;
        }
        self.tree
            .bases(c)
            .into_iter()
            .filter(|&b| b != c)
            .any(|b| self.has_equality_constraint(b, depth + 1))
    }
}
