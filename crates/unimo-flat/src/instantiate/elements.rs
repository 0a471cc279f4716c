//! Array elements: dimensions evaluated at compile time, and the modifier or binding
//! of one element of a component array picked out.

use super::{int_expr, Instantiator};
use crate::error::FlatError;
use crate::eval::{self, Value};
use crate::modif::{Mod, Scope};
use smol_str::SmolStr;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// An array dimension evaluated at compile time (`E2003` when it is not a
    /// non-negative Integer).
    pub(super) fn dimension(&mut self, e: &Expr, scope: &Scope) -> Option<usize> {
        let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
        match eval::eval(&flat, self, &mut Vec::new()).map(|v| v.as_int()) {
            Ok(Some(n)) if n >= 0 => Some(n as usize),
            Ok(_) => {
                self.report(FlatError::BadDimension { span: e.span });
                None
            }
            Err(err) => {
                self.eval_error(err, "array dimension");
                None
            }
        }
    }

    /// The modification of element `index` of a component array: the bindings of
    /// modifiers without `each` are subscripted (a literal array gives its element, a
    /// reference gets the subscripts, a constant is evaluated and picked).
    pub(super) fn element_mod(&mut self, m: &Mod, index: &[i64]) -> Mod {
        let mut out = m.clone();
        out.children = self.element_children(m, index);
        out
    }

    /// The children of `m` as modifiers of element `index`.
    fn element_children(&mut self, m: &Mod, index: &[i64]) -> Vec<(SmolStr, Mod)> {
        (m.children.iter())
            .map(|(n, c)| (n.clone(), self.element_child(c, index)))
            .collect()
    }

    fn element_child(&mut self, m: &Mod, index: &[i64]) -> Mod {
        if m.each {
            return m.clone();
        }
        let mut out = m.clone();
        if let Some(b) = &m.binding {
            if let Some(e) = self.pick_element(&b.expr, &b.scope, index) {
                out.binding = Some(crate::modif::Bound {
                    expr: e,
                    scope: b.scope.clone(),
                });
            }
        }
        out.children = self.element_children(m, index);
        out
    }

    pub(crate) fn pick_element(&mut self, e: &Expr, scope: &Scope, index: &[i64]) -> Option<Expr> {
        let Some((&first, rest)) = index.split_first() else {
            return Some(e.clone());
        };
        match &e.kind {
            ExprKind::Array(items) => {
                let item = items.get(usize::try_from(first - 1).ok()?)?;
                self.pick_element(item, scope, rest)
            }
            ExprKind::Ref(r) => {
                // Subscripted only when it names an array: a parameter array is
                // evaluated, a variable is looked up; a scalar is left as it is.
                let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
                if let Ok(v) = eval::eval(&flat, self, &mut Vec::new()) {
                    return self.pick_value(v, index, e.span);
                }
                let key = match &flat.kind {
                    ExprKind::Ref(fr) => eval::var_key(fr),
                    _ => return None,
                };
                let id = self.var_id(&key)?;
                if self.model.vars[id.0 as usize].dims.len() < index.len() {
                    return None;
                }
                let mut r = r.clone();
                let last = r.parts.last_mut()?;
                last.subscripts
                    .extend(index.iter().map(|&i| Subscript::Expr(int_expr(i, e.span))));
                Some(Expr {
                    kind: ExprKind::Ref(r),
                    span: e.span,
                })
            }
            _ => {
                // A constant array: evaluate it and pick the element.
                let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
                if let Ok(v) = eval::eval(&flat, self, &mut Vec::new()) {
                    return self.pick_value(v, index, e.span);
                }
                if let ExprKind::Comprehension { body, indices } = &e.kind {
                    return self.pick_iteration(body, indices, scope, index);
                }
                // An element-wise expression of arrays that are not constant
                // (`u = us + ones(n)`): the element of each operand.
                let picked = |this: &mut Self, x: &Expr| this.pick_element(x, scope, index);
                let kind = match &e.kind {
                    ExprKind::Binary { op, lhs, rhs } => {
                        let elementwise = crate::lookup::is_elementwise(*op);
                        let (l, r) = (picked(self, lhs), picked(self, rhs));
                        match (l, r) {
                            (Some(l), Some(r)) if elementwise => ExprKind::Binary {
                                op: *op,
                                lhs: Box::new(l),
                                rhs: Box::new(r),
                            },
                            // An array scaled by a scalar.
                            (Some(l), None)
                                if elementwise || matches!(op, BinaryOp::Mul | BinaryOp::Div) =>
                            {
                                ExprKind::Binary {
                                    op: *op,
                                    lhs: Box::new(l),
                                    rhs: rhs.clone(),
                                }
                            }
                            (None, Some(r)) if elementwise || matches!(op, BinaryOp::Mul) => {
                                ExprKind::Binary {
                                    op: *op,
                                    lhs: lhs.clone(),
                                    rhs: Box::new(r),
                                }
                            }
                            _ => return None,
                        }
                    }
                    ExprKind::Unary { op, operand } => ExprKind::Unary {
                        op: *op,
                        operand: Box::new(picked(self, operand)?),
                    },
                    ExprKind::Call { func, args } => {
                        let x = picked(self, crate::lookup::elementwise_arg(func, args)?)?;
                        ExprKind::Call {
                            func: func.clone(),
                            args: Box::new(CallArgs {
                                positional: vec![x],
                                named: Vec::new(),
                                iterators: Vec::new(),
                                span: args.span,
                            }),
                        }
                    }
                    _ => return None,
                };
                Some(Expr { kind, span: e.span })
            }
        }
    }

    /// Element `index` of `{body for i in range}` whose range is known: the body with
    /// `i` replaced by the range's value at the first index, then the rest picked.
    fn pick_iteration(
        &mut self,
        body: &Expr,
        indices: &[ForIndex],
        scope: &Scope,
        index: &[i64],
    ) -> Option<Expr> {
        let ([iterator], Some((&first, rest))) = (indices, index.split_first()) else {
            return None;
        };
        let flat = self.flat_expr(iterator.range.as_ref()?, scope);
        let Ok(Value::Array(values)) = eval::eval(&flat, self, &mut Vec::new()) else {
            return None;
        };
        let value = values
            .get(usize::try_from(first - 1).ok()?)?
            .to_expr(body.span);
        let mut item = body.clone();
        replace_iterator(&mut item, &iterator.name.text, &value);
        self.pick_element(&item, scope, rest)
    }

    /// Element `index` of an array value; `None` for a scalar (left to broadcast).
    fn pick_value(&self, mut v: Value, index: &[i64], span: Span) -> Option<Expr> {
        for &i in index {
            v = match v {
                Value::Array(items) => items.into_iter().nth(usize::try_from(i - 1).ok()?)?,
                _ => return None,
            };
        }
        Some(v.to_expr(span))
    }
}

/// `e` with each use of the iterator `name` replaced by `value` (a nested reduction or
/// comprehension that binds `name` again is left alone).
fn replace_iterator(e: &mut Expr, name: &str, value: &Expr) {
    match &e.kind {
        ExprKind::Ref(r)
            if !r.global
                && r.parts.len() == 1
                && r.parts[0].name.text == name
                && r.parts[0].subscripts.is_empty() =>
        {
            *e = value.clone();
            return;
        }
        ExprKind::Comprehension { indices, .. } if indices.iter().any(|i| i.name.text == name) => {
            return
        }
        ExprKind::Call { args, .. } if args.iterators.iter().any(|i| i.name.text == name) => return,
        _ => {}
    }
    e.for_each_child_mut(&mut |c| replace_iterator(c, name, value));
}
