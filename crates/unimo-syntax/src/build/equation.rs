//! Equations and algorithm statements.

use super::{empty, kids, Builder};
use crate::ast::*;
use crate::grammar::Rule;
use crate::shared;
use pest::iterators::Pair;
use unimo_source::Span;

impl Builder<'_> {
    // ------------------------------------------------------------ equations

    pub(crate) fn equation(&mut self, pair: Pair<'_, Rule>) -> Equation {
        let span = self.span(&pair);
        let mut it = kids(pair);
        let body = it.next();
        let comment = it.next().map(|c| self.comment(c)).unwrap_or_default();
        let kind = match body {
            Some(b) => self.equation_kind(b),
            None => EquationKind::Call(Expr {
                kind: ExprKind::Tuple(Vec::new()),
                span,
            }),
        };
        Equation {
            kind,
            comment,
            span,
        }
    }

    fn equation_kind(&mut self, pair: Pair<'_, Rule>) -> EquationKind {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::simple_or_call_equation => {
                let mut it = pair.into_inner();
                let lhs = match it.next() {
                    Some(p) => self.expression(p),
                    None => return EquationKind::Call(empty(span)),
                };
                match (it.next(), it.next()) {
                    (Some(op), Some(rhs)) => {
                        if op.as_str() == ":=" {
                            let op_span = self.span(&op);
                            self.diags.push(shared::assign_in_equation(op_span));
                        }
                        EquationKind::Simple {
                            lhs,
                            rhs: self.expression(rhs),
                        }
                    }
                    _ => EquationKind::Call(lhs),
                }
            }
            Rule::connect_clause => {
                let mut it = kids(pair);
                let a = it.next().map(|p| self.component_reference(p));
                let b = it.next().map(|p| self.component_reference(p));
                match (a, b) {
                    (Some(a), Some(b)) => EquationKind::Connect { a, b },
                    _ => EquationKind::Call(empty(span)),
                }
            }
            Rule::if_equation => {
                let mut branches = Vec::new();
                let mut otherwise = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.eq_block(b)));
                }
                for p in it {
                    match p.as_rule() {
                        Rule::elseif_eq => {
                            let mut q = kids(p);
                            if let (Some(c), Some(b)) = (q.next(), q.next()) {
                                branches.push((self.expression(c), self.eq_block(b)));
                            }
                        }
                        Rule::else_eq => {
                            if let Some(b) = kids(p).next() {
                                otherwise = self.eq_block(b);
                            }
                        }
                        _ => self.internal(&p),
                    }
                }
                EquationKind::If {
                    branches,
                    otherwise,
                }
            }
            Rule::for_equation => {
                let mut it = kids(pair);
                let indices = it.next().map(|p| self.for_indices(p)).unwrap_or_default();
                let body = it.next().map(|p| self.eq_block(p)).unwrap_or_default();
                EquationKind::For { indices, body }
            }
            Rule::when_equation => {
                let mut branches = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.eq_block(b)));
                }
                for p in it {
                    let mut q = kids(p);
                    if let (Some(c), Some(b)) = (q.next(), q.next()) {
                        branches.push((self.expression(c), self.eq_block(b)));
                    }
                }
                EquationKind::When { branches }
            }
            _ => {
                self.internal(&pair);
                EquationKind::Call(empty(span))
            }
        }
    }

    fn eq_block(&mut self, pair: Pair<'_, Rule>) -> Vec<Equation> {
        kids(pair).map(|p| self.equation(p)).collect()
    }

    pub(crate) fn for_indices(&mut self, pair: Pair<'_, Rule>) -> Vec<ForIndex> {
        let mut out = Vec::new();
        for idx in pair.into_inner() {
            let mut it = kids(idx);
            if let Some(name) = it.next() {
                let name = self.ident(name);
                let range = it.next().map(|e| self.expression(e));
                out.push(ForIndex { name, range });
            }
        }
        out
    }

    // ------------------------------------------------------------ statements

    pub(crate) fn statement(&mut self, pair: Pair<'_, Rule>) -> Statement {
        let span = self.span(&pair);
        let mut it = kids(pair);
        let body = it.next();
        let comment = it.next().map(|c| self.comment(c)).unwrap_or_default();
        let kind = match body {
            Some(b) => self.statement_kind(b),
            None => StatementKind::Break,
        };
        Statement {
            kind,
            comment,
            span,
        }
    }

    fn st_block(&mut self, pair: Pair<'_, Rule>) -> Vec<Statement> {
        kids(pair).map(|p| self.statement(p)).collect()
    }

    fn statement_kind(&mut self, pair: Pair<'_, Rule>) -> StatementKind {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::assign_or_call => self.assign_or_call(pair, span),
            Rule::multi_assign => self.multi_assign(pair, span),
            Rule::return_stmt => StatementKind::Return,
            Rule::break_stmt => StatementKind::Break,
            Rule::if_statement => self.if_statement(pair),
            Rule::for_statement => {
                let mut it = kids(pair);
                let indices = it.next().map(|p| self.for_indices(p)).unwrap_or_default();
                let body = it.next().map(|p| self.st_block(p)).unwrap_or_default();
                StatementKind::For { indices, body }
            }
            Rule::while_statement => {
                let mut it = kids(pair);
                let condition = match it.next() {
                    Some(c) => self.expression(c),
                    None => empty(span),
                };
                let body = it.next().map(|p| self.st_block(p)).unwrap_or_default();
                StatementKind::While { condition, body }
            }
            Rule::when_statement => {
                let mut branches = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.st_block(b)));
                }
                for p in it {
                    let mut q = kids(p);
                    if let (Some(c), Some(b)) = (q.next(), q.next()) {
                        branches.push((self.expression(c), self.st_block(b)));
                    }
                }
                StatementKind::When { branches }
            }
            _ => {
                self.internal(&pair);
                StatementKind::Break
            }
        }
    }

    /// `if c then ... elseif d then ... else ... end if;`
    fn if_statement(&mut self, pair: Pair<'_, Rule>) -> StatementKind {
        let mut branches = Vec::new();
        let mut otherwise = Vec::new();
        let mut it = kids(pair);
        if let (Some(c), Some(b)) = (it.next(), it.next()) {
            branches.push((self.expression(c), self.st_block(b)));
        }
        for p in it {
            match p.as_rule() {
                Rule::elseif_st => {
                    let mut q = kids(p);
                    if let (Some(c), Some(b)) = (q.next(), q.next()) {
                        branches.push((self.expression(c), self.st_block(b)));
                    }
                }
                Rule::else_st => {
                    if let Some(b) = kids(p).next() {
                        otherwise = self.st_block(b);
                    }
                }
                _ => self.internal(&p),
            }
        }
        StatementKind::If {
            branches,
            otherwise,
        }
    }

    /// `(a, , b) := f(x);`
    fn multi_assign(&mut self, pair: Pair<'_, Rule>, span: Span) -> StatementKind {
        let mut it = pair.into_inner();
        let targets = it.next().map(|p| self.output_list(p)).unwrap_or_default();
        let func = it.next().map(|p| self.component_reference(p));
        let args = it.next().map(|p| self.call_args(p)).unwrap_or_default();
        let value = match func {
            Some(f) => Expr {
                kind: ExprKind::Call {
                    func: self.callee(&f),
                    args,
                },
                span,
            },
            None => empty(span),
        };
        StatementKind::MultiAssign { targets, value }
    }

    /// `x := e;`, `f(x);` or a bare reference (an error: a statement without effect).
    fn assign_or_call(&mut self, pair: Pair<'_, Rule>, span: Span) -> StatementKind {
        let mut it = pair.into_inner();
        let target = match it.next() {
            Some(t) => self.component_reference(t),
            None => return StatementKind::Break,
        };
        match it.next() {
            Some(args) if args.as_rule() == Rule::function_call_args => {
                let func = self.callee(&target);
                let args = self.call_args(args);
                StatementKind::Call(Expr {
                    kind: ExprKind::Call { func, args },
                    span,
                })
            }
            Some(op) => {
                if op.as_str() == "=" {
                    let op_span = self.span(&op);
                    self.diags.push(shared::equals_in_algorithm(op_span));
                }
                let value = match it.next() {
                    Some(v) => self.expression(v),
                    None => empty(span),
                };
                StatementKind::Assign { target, value }
            }
            None => {
                self.diags
                    .push(shared::statement_without_effect(target.span));
                StatementKind::Call(Expr {
                    kind: ExprKind::Ref(target),
                    span,
                })
            }
        }
    }
}
