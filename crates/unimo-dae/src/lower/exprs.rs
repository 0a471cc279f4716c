//! Expressions lowered to tensors of arena expressions: operators, ranges, array
//! constructors and comprehensions, `if`-expressions.

use super::array_builtins::as_matrix;
use super::{unsupported, Local, Lowerer};
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprArena, ExprId};
use crate::tensor::{self, Tensor};
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Lowerer<'_> {
    pub(crate) fn scalar(&mut self, e: &Expr) -> DaeResult<ExprId> {
        self.expr(e)?.as_scalar(e.span)
    }

    /// A compile-time integer.
    pub(crate) fn constant_int(&mut self, e: &Expr) -> DaeResult<i64> {
        let x = self.scalar(e)?;
        match self.const_value(x) {
            Some(v) if v == v.trunc() => Ok(v as i64),
            _ => Err(DaeError::ConstantIntegerNeeded { span: e.span }),
        }
    }

    pub(crate) fn expr(&mut self, e: &Expr) -> DaeResult<Tensor> {
        let span = e.span;
        match &e.kind {
            ExprKind::Integer(i) => Ok(Tensor::scalar(self.a().constant(*i as f64))),
            ExprKind::Real(x) => Ok(Tensor::scalar(self.a().constant(*x))),
            ExprKind::Bool(b) => Ok(Tensor::scalar(self.a().boolean(*b))),
            ExprKind::String(_) => Err(unsupported("a String value in an expression", span)),
            ExprKind::Ref(r) => self.reference(r),
            ExprKind::End => match self.end_stack.last() {
                Some(&n) => Ok(Tensor::scalar(self.a().constant(n as f64))),
                None => Err(DaeError::EndOutsideSubscript { span }),
            },
            ExprKind::Call { func, args } => self.call(func, args, span),
            ExprKind::Unary { op, operand } => {
                let x = self.expr(operand)?;
                Ok(match op {
                    UnaryOp::Neg => x.map(|v| self.dae.arena.neg(v)),
                    UnaryOp::Plus => x,
                    UnaryOp::Not => x.map(|v| self.dae.arena.not(v)),
                })
            }
            ExprKind::Binary { op, lhs, rhs } => {
                if let Some(t) = self.string_comparison(*op, lhs, rhs)? {
                    return Ok(t);
                }
                let a = self.expr(lhs)?;
                let b = self.expr(rhs)?;
                self.binary(*op, &a, &b, span)
            }
            ExprKind::If {
                branches,
                otherwise,
            } => {
                // A branch whose condition is known at compile time (parameters only):
                // the branch taken (branches of different sizes, values the back end does
                // not have such as Strings, and a `der` in a branch not taken never reach
                // the structure).
                if let Some(e) = self.structural_if(branches, otherwise)? {
                    return self.expr(e);
                }
                let mut acc = self.expr(otherwise)?;
                for (c, v) in branches.iter().rev() {
                    let c = self.scalar(c)?;
                    let v = self.expr(v)?;
                    if v.dims != acc.dims {
                        return Err(tensor::size_error(&v.dims, &acc.dims, span));
                    }
                    let data = v
                        .data
                        .iter()
                        .zip(&acc.data)
                        .map(|(&x, &y)| self.dae.arena.if_(c, x, y))
                        .collect();
                    acc = Tensor { dims: v.dims, data };
                }
                Ok(acc)
            }
            ExprKind::Range { start, step, stop } => {
                let values = self.range_values(start, step.as_deref(), stop)?;
                let data = values.into_iter().map(|x| self.a().constant(x)).collect();
                Ok(Tensor::vector(data))
            }
            ExprKind::Array(items) => {
                let items = items
                    .iter()
                    .map(|x| self.expr(x))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)
            }
            ExprKind::Matrix(rows) => {
                let mut row_tensors = Vec::new();
                for row in rows {
                    let items = row
                        .iter()
                        .map(|x| self.expr(x).map(as_matrix))
                        .collect::<DaeResult<Vec<_>>>()?;
                    row_tensors.push(tensor::concatenate(&items, 1, span)?);
                }
                tensor::concatenate(&row_tensors, 0, span)
            }
            ExprKind::Comprehension { body, indices } => {
                let items = self.comprehension(body, indices)?;
                Tensor::stack(items, span)
            }
            ExprKind::Tuple(items) if items.len() == 1 && items[0].is_some() => {
                self.expr(items[0].as_ref().expect("checked"))
            }
            ExprKind::Tuple(_) => Err(unsupported("a tuple outside a multiple assignment", span)),
            ExprKind::PartialApplication { .. } => Err(unsupported("functional arguments", span)),
        }
    }

    pub(crate) fn range_values(
        &mut self,
        start: &Expr,
        step: Option<&Expr>,
        stop: &Expr,
    ) -> DaeResult<Vec<f64>> {
        let c = |me: &mut Self, e: &Expr| -> DaeResult<f64> {
            let x = me.scalar(e)?;
            me.const_value(x)
                .ok_or(DaeError::RangeBoundNotConstant { span: e.span })
        };
        let a = c(self, start)?;
        let h = match step {
            Some(s) => c(self, s)?,
            None => 1.0,
        };
        let b = c(self, stop)?;
        if h == 0.0 {
            return Err(DaeError::ZeroRangeStep { span: start.span });
        }
        let n = ((b - a) / h + 1e-10).floor();
        if n < 0.0 {
            return Ok(Vec::new());
        }
        if n > 1e7 {
            return Err(DaeError::RangeTooLong { span: start.span });
        }
        Ok((0..=n as usize).map(|k| a + k as f64 * h).collect())
    }

    /// Evaluates `body` once per combination of the iterators (last one fastest).
    pub(crate) fn comprehension(
        &mut self,
        body: &Expr,
        indices: &[ForIndex],
    ) -> DaeResult<Vec<Tensor>> {
        let Some((first, rest)) = indices.split_first() else {
            return Ok(vec![self.expr(body)?]);
        };
        let values = self.iterator_values(first)?;
        let mut out = Vec::new();
        for v in values {
            out.extend(self.with_iterator(first, v, |me| me.comprehension(body, rest))?);
        }
        Ok(out)
    }

    /// Runs `f` with the iterator `index` bound to `value` (a local while `f` runs).
    pub(crate) fn with_iterator<T>(
        &mut self,
        index: &ForIndex,
        value: Tensor,
        f: impl FnOnce(&mut Self) -> T,
    ) -> T {
        self.locals.push(Local {
            name: index.name.text.to_string(),
            value: Some(value),
            record: None,
            text: None,
        });
        let r = f(self);
        self.locals.pop();
        r
    }

    pub(crate) fn iterator_values(&mut self, index: &ForIndex) -> DaeResult<Vec<Tensor>> {
        let Some(range) = &index.range else {
            return Err(unsupported(
                "a `for` iterator without a range",
                index.name.span,
            ));
        };
        let t = self.expr(range)?;
        Ok(t.rows())
    }

    pub(crate) fn binary(
        &mut self,
        op: BinaryOp,
        a: &Tensor,
        b: &Tensor,
        span: Span,
    ) -> DaeResult<Tensor> {
        let ar = &mut self.dae.arena;
        use BinaryOp::*;
        match op {
            Add | Sub if !a.is_scalar() || !b.is_scalar() => {
                let f = if op == Add {
                    ExprArena::add
                } else {
                    ExprArena::sub
                };
                tensor::elementwise(ar, a, b, false, span, f)
            }
            Add | ElemAdd => tensor::elementwise(ar, a, b, true, span, ExprArena::add),
            Sub | ElemSub => tensor::elementwise(ar, a, b, true, span, ExprArena::sub),
            Mul => tensor::multiply(ar, a, b, span),
            ElemMul => tensor::elementwise(ar, a, b, true, span, ExprArena::mul),
            Div | ElemDiv => {
                if op == Div && !b.is_scalar() {
                    return Err(DaeError::DivisionByArray { span });
                }
                tensor::elementwise(ar, a, b, true, span, ExprArena::div)
            }
            Pow | ElemPow => {
                if op == Pow && (!a.is_scalar() || !b.is_scalar()) {
                    return Err(unsupported("matrix powers", span));
                }
                tensor::elementwise(ar, a, b, true, span, ExprArena::pow)
            }
            And => tensor::elementwise(ar, a, b, true, span, ExprArena::and),
            Or => tensor::elementwise(ar, a, b, true, span, ExprArena::or),
            Rel(rel) => {
                let x = a.as_scalar(span)?;
                let y = b.as_scalar(span)?;
                Ok(Tensor::scalar(ar.rel(rel, x, y)))
            }
        }
    }

    /// The time derivative of a lowered expression: a continuous variable's derivative
    /// is its derivative scalar (made on demand); parameters and discrete variables
    /// have none.
    pub(crate) fn time_derivative(&mut self, e: ExprId) -> ExprId {
        crate::analysis::time_derivative(&mut self.dae, e)
    }
}
