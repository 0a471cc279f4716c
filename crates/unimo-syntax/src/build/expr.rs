//! Expressions: the operator-precedence (Pratt) parser over operands, primaries,
//! component references, subscripts and call arguments.

use super::{empty, kids, Builder};
use crate::ast::*;
use crate::grammar::Rule;
use crate::shared;
use pest::iterators::{Pair, Pairs};
use pest::pratt_parser::{Assoc, Op, PrattParser};
use std::sync::LazyLock;
use unimo_source::Span;

static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::or_op, Assoc::Left))
        .op(Op::infix(Rule::and_op, Assoc::Left))
        .op(Op::prefix(Rule::not_op))
        .op(Op::infix(Rule::lt_op, Assoc::Left)
            | Op::infix(Rule::le_op, Assoc::Left)
            | Op::infix(Rule::gt_op, Assoc::Left)
            | Op::infix(Rule::ge_op, Assoc::Left)
            | Op::infix(Rule::eq_eq_op, Assoc::Left)
            | Op::infix(Rule::ne_op, Assoc::Left))
        .op(Op::infix(Rule::add_op, Assoc::Left)
            | Op::infix(Rule::sub_op, Assoc::Left)
            | Op::infix(Rule::ew_add, Assoc::Left)
            | Op::infix(Rule::ew_sub, Assoc::Left))
        // pest binds a prefix operator's operand at one level below the operator's own
        // level, so unary minus gets a level of its own above `+`: `-a + b` is
        // `(-a) + b`, while `-a * b` is `-(a * b)` and `-a ^ 2` is `-(a ^ 2)`.
        .op(Op::prefix(Rule::neg_op) | Op::prefix(Rule::pos_op))
        .op(Op::infix(Rule::mul_op, Assoc::Left)
            | Op::infix(Rule::div_op, Assoc::Left)
            | Op::infix(Rule::ew_mul, Assoc::Left)
            | Op::infix(Rule::ew_div, Assoc::Left))
        .op(Op::infix(Rule::pow_op, Assoc::Right) | Op::infix(Rule::ew_pow, Assoc::Right))
});

impl Builder<'_> {
    // ------------------------------------------------------------ expressions

    pub fn expression(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::expression | Rule::function_argument | Rule::subscript => {
                match pair.into_inner().next() {
                    Some(inner) => self.expression(inner),
                    None => empty(span),
                }
            }
            Rule::if_expression => {
                let mut it = kids(pair).peekable();
                let mut branches = Vec::new();
                if let (Some(c), Some(t)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.expression(t)));
                }
                let mut otherwise = empty(span);
                for p in it {
                    if p.as_rule() == Rule::elseif_expr {
                        let mut q = kids(p);
                        if let (Some(c), Some(t)) = (q.next(), q.next()) {
                            branches.push((self.expression(c), self.expression(t)));
                        }
                    } else {
                        otherwise = self.expression(p);
                    }
                }
                Expr {
                    kind: ExprKind::If {
                        branches,
                        otherwise: Box::new(otherwise),
                    },
                    span,
                }
            }
            Rule::simple_expression => {
                let mut parts: Vec<Expr> =
                    pair.into_inner().map(|p| self.operand_expr(p)).collect();
                match parts.len() {
                    1 => parts.pop().unwrap_or_else(|| empty(span)),
                    2 => {
                        let stop = parts.pop().unwrap_or_else(|| empty(span));
                        let start = parts.pop().unwrap_or_else(|| empty(span));
                        Expr {
                            kind: ExprKind::Range {
                                start: Box::new(start),
                                step: None,
                                stop: Box::new(stop),
                            },
                            span,
                        }
                    }
                    _ => {
                        let stop = parts.pop().unwrap_or_else(|| empty(span));
                        let step = parts.pop().unwrap_or_else(|| empty(span));
                        let start = parts.pop().unwrap_or_else(|| empty(span));
                        Expr {
                            kind: ExprKind::Range {
                                start: Box::new(start),
                                step: Some(Box::new(step)),
                                stop: Box::new(stop),
                            },
                            span,
                        }
                    }
                }
            }
            Rule::operand_expr => self.operand_expr(pair),
            Rule::function_partial_application => {
                let mut it = kids(pair);
                let func = it.next().map(|n| self.name(n));
                let args = it.next().map(|p| self.named_args(p)).unwrap_or_default();
                Expr {
                    kind: ExprKind::PartialApplication {
                        func: Box::new(func.unwrap_or(Name::empty(span))),
                        args,
                    },
                    span,
                }
            }
            _ => {
                self.internal(&pair);
                empty(span)
            }
        }
    }

    fn operand_expr(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let file = self.file;
        let pairs: Pairs<'_, Rule> = pair.into_inner();
        PRATT
            .map_primary(|p| self.primary(p))
            .map_prefix(move |op, operand| {
                let s = op.as_span();
                let span = Span::new(file, s.start(), s.end()).to(operand.span);
                let op = match op.as_rule() {
                    Rule::not_op => UnaryOp::Not,
                    Rule::neg_op => UnaryOp::Neg,
                    _ => UnaryOp::Plus,
                };
                Expr {
                    kind: ExprKind::Unary {
                        op,
                        operand: Box::new(operand),
                    },
                    span,
                }
            })
            .map_infix(|lhs, op, rhs| {
                let span = lhs.span.to(rhs.span);
                let op = match op.as_rule() {
                    Rule::or_op => BinaryOp::Or,
                    Rule::and_op => BinaryOp::And,
                    Rule::lt_op => BinaryOp::Rel(RelOp::Lt),
                    Rule::le_op => BinaryOp::Rel(RelOp::Le),
                    Rule::gt_op => BinaryOp::Rel(RelOp::Gt),
                    Rule::ge_op => BinaryOp::Rel(RelOp::Ge),
                    Rule::eq_eq_op => BinaryOp::Rel(RelOp::Eq),
                    Rule::ne_op => BinaryOp::Rel(RelOp::Ne),
                    Rule::add_op => BinaryOp::Add,
                    Rule::sub_op => BinaryOp::Sub,
                    Rule::mul_op => BinaryOp::Mul,
                    Rule::div_op => BinaryOp::Div,
                    Rule::pow_op => BinaryOp::Pow,
                    Rule::ew_add => BinaryOp::ElemAdd,
                    Rule::ew_sub => BinaryOp::ElemSub,
                    Rule::ew_mul => BinaryOp::ElemMul,
                    Rule::ew_div => BinaryOp::ElemDiv,
                    _ => BinaryOp::ElemPow,
                };
                Expr {
                    kind: ExprKind::Binary {
                        op,
                        lhs: Box::new(lhs),
                        rhs: Box::new(rhs),
                    },
                    span,
                }
            })
            .parse(pairs)
    }

    fn primary(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        let Some(p) = pair.into_inner().next() else {
            return empty(span);
        };
        let kind = match p.as_rule() {
            Rule::unsigned_integer | Rule::unsigned_real => {
                shared::number(p.as_str(), span, self.diags)
            }
            Rule::string => ExprKind::String(self.string_value(&p)),
            Rule::true_lit => ExprKind::Bool(true),
            Rule::false_lit => ExprKind::Bool(false),
            Rule::end_expr => ExprKind::End,
            Rule::builtin_call => {
                let mut it = p.into_inner();
                let name = it.next();
                let args = it.next().map(|a| self.call_args(a)).unwrap_or_default();
                let func = match name {
                    Some(n) => Name {
                        global: false,
                        parts: vec![self.ident(n)],
                        span,
                    },
                    None => return empty(span),
                };
                ExprKind::Call { func, args }
            }
            Rule::ref_or_call => {
                let mut it = p.into_inner();
                let cref = match it.next() {
                    Some(c) => self.component_reference(c),
                    None => return empty(span),
                };
                match it.next() {
                    Some(args) => {
                        let func = self.callee(&cref);
                        ExprKind::Call {
                            func,
                            args: self.call_args(args),
                        }
                    }
                    None => ExprKind::Ref(cref),
                }
            }
            Rule::paren_expr => {
                let list = p.into_inner().next();
                let mut items = list.map(|l| self.output_list(l)).unwrap_or_default();
                if items.len() == 1 && items[0].is_some() {
                    // Plain parentheses: keep the inner expression, widen its span.
                    let mut e = items.pop().flatten().unwrap_or_else(|| empty(span));
                    e.span = span;
                    return e;
                }
                ExprKind::Tuple(items)
            }
            Rule::array_expr => {
                let Some(args) = p.into_inner().next() else {
                    return empty(span);
                };
                let mut it = args.into_inner();
                let first = match it.next() {
                    Some(f) => self.expression(f),
                    None => return empty(span),
                };
                match it.next() {
                    Some(q) if q.as_rule() == Rule::for_kw => {
                        let indices = it.next().map(|i| self.for_indices(i)).unwrap_or_default();
                        ExprKind::Comprehension {
                            body: Box::new(first),
                            indices,
                        }
                    }
                    Some(q) => {
                        let mut items = vec![first, self.expression(q)];
                        items.extend(it.map(|e| self.expression(e)));
                        ExprKind::Array(items)
                    }
                    None => ExprKind::Array(vec![first]),
                }
            }
            Rule::matrix_expr => ExprKind::Matrix(
                p.into_inner()
                    .map(|row| row.into_inner().map(|e| self.expression(e)).collect())
                    .collect(),
            ),
            _ => {
                self.internal(&p);
                return empty(span);
            }
        };
        Expr { kind, span }
    }

    pub(crate) fn output_list(&mut self, pair: Pair<'_, Rule>) -> Vec<Option<Expr>> {
        let mut items = vec![None];
        for p in pair.into_inner() {
            if p.as_rule() == Rule::comma {
                items.push(None);
            } else if let Some(last) = items.last_mut() {
                *last = Some(self.expression(p));
            }
        }
        if items.len() == 1 && items[0].is_none() {
            items.clear();
        }
        items
    }

    pub(crate) fn callee(&mut self, cref: &ComponentRef) -> Name {
        shared::callee(cref, self.diags)
    }

    pub fn component_reference(&mut self, pair: Pair<'_, Rule>) -> ComponentRef {
        let span = self.span(&pair);
        let mut global = false;
        let mut parts = Vec::new();
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::global_dot => global = true,
                Rule::ref_part => {
                    let mut it = p.into_inner();
                    let name = match it.next() {
                        Some(n) => self.ident(n),
                        None => continue,
                    };
                    let subscripts = it.next().map(|s| self.subscripts(s)).unwrap_or_default();
                    parts.push(RefPart { name, subscripts });
                }
                _ => self.internal(&p),
            }
        }
        ComponentRef {
            global,
            parts,
            span,
        }
    }

    pub(crate) fn subscripts(&mut self, pair: Pair<'_, Rule>) -> Vec<Subscript> {
        pair.into_inner()
            .map(|s| {
                let span = self.span(&s);
                match s.into_inner().next() {
                    Some(c) if c.as_rule() == Rule::colon_sub => Subscript::Colon(span),
                    Some(e) => Subscript::Expr(self.expression(e)),
                    None => Subscript::Colon(span),
                }
            })
            .collect()
    }

    pub(crate) fn call_args(&mut self, pair: Pair<'_, Rule>) -> Box<CallArgs> {
        let span = self.span(&pair);
        let mut args = CallArgs {
            span,
            ..CallArgs::default()
        };
        let mut next = pair.into_inner().next();
        while let Some(fa) = next.take() {
            let mut it = fa.into_inner();
            let Some(first) = it.next() else { break };
            if first.as_rule() == Rule::named_arguments {
                args.named.extend(self.named_args(first));
                break;
            }
            args.positional.push(self.expression(first));
            match it.next() {
                Some(q) if q.as_rule() == Rule::for_kw => {
                    args.iterators = it.next().map(|i| self.for_indices(i)).unwrap_or_default();
                }
                Some(rest) => next = Some(rest),
                None => {}
            }
        }
        Box::new(args)
    }

    fn named_args(&mut self, pair: Pair<'_, Rule>) -> Vec<NamedArg> {
        pair.into_inner()
            .filter_map(|na| {
                let mut it = na.into_inner();
                let name = self.ident(it.next()?);
                let value = self.expression(it.next()?);
                Some(NamedArg { name, value })
            })
            .collect()
    }
}
