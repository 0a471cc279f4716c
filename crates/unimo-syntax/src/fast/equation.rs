//! Equations and algorithm statements, with the look-ahead that tells where each starts.

use super::P;
use crate::ast::*;
use crate::lexer::{Sym, TokenKind};
use crate::shared;
use unimo_source::Span;

impl<'a> P<'a, '_> {
    // ------------------------------------------------------------ equations

    pub(crate) fn at_expression_start(&self) -> bool {
        match self.tok(self.pos) {
            None => false,
            Some(t) => {
                matches!(
                    t.kind,
                    TokenKind::Ident
                        | TokenKind::QuotedIdent
                        | TokenKind::Number
                        | TokenKind::String
                ) || matches!(
                    t.sym,
                    Sym::LParen
                        | Sym::LBracket
                        | Sym::LBrace
                        | Sym::Dot
                        | Sym::Minus
                        | Sym::Plus
                        | Sym::KwNot
                        | Sym::KwTrue
                        | Sym::KwFalse
                        | Sym::KwDer
                        | Sym::KwInitial
                        | Sym::KwPure
                        | Sym::KwEnd
                        | Sym::KwIf
                )
            }
        }
    }

    pub(crate) fn at_equation_start(&self) -> bool {
        self.at_expression_start()
            || matches!(self.sym(), Sym::KwFor | Sym::KwConnect | Sym::KwWhen)
    }

    pub(crate) fn at_statement_start(&self) -> bool {
        self.at_ident()
            || matches!(
                self.sym(),
                Sym::Dot
                    | Sym::LParen
                    | Sym::KwIf
                    | Sym::KwFor
                    | Sym::KwWhile
                    | Sym::KwWhen
                    | Sym::KwReturn
                    | Sym::KwBreak
            )
    }

    pub(crate) fn equation(&mut self) -> Option<Equation> {
        let first = self.pos;
        let kind = if self.at(Sym::KwIf) {
            self.pos += 1;
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.eq_block()?));
            let mut otherwise = Vec::new();
            while self.eat(Sym::KwElseif) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.eq_block()?));
            }
            if self.eat(Sym::KwElse) {
                otherwise = self.eq_block()?;
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwIf)?;
            EquationKind::If {
                branches,
                otherwise,
            }
        } else if self.eat(Sym::KwFor) {
            let indices = self.for_indices()?;
            self.expect(Sym::KwLoop)?;
            let body = self.eq_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwFor)?;
            EquationKind::For { indices, body }
        } else if self.eat(Sym::KwConnect) {
            self.expect(Sym::LParen)?;
            let a = self.component_reference()?;
            self.expect(Sym::Comma)?;
            let b = self.component_reference()?;
            self.expect(Sym::RParen)?;
            EquationKind::Connect { a, b }
        } else if self.eat(Sym::KwWhen) {
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.eq_block()?));
            while self.eat(Sym::KwElsewhen) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.eq_block()?));
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwWhen)?;
            EquationKind::When { branches }
        } else {
            let lhs = self.simple_expression()?;
            if self.at(Sym::Equals) || self.at(Sym::Assign) {
                let op = self.toks[self.pos];
                self.pos += 1;
                if self.txt(&op) == ":=" {
                    self.diags.push(shared::assign_in_equation(Span::new(
                        self.file,
                        op.start(),
                        op.end(),
                    )));
                }
                let rhs = self.expression()?;
                EquationKind::Simple { lhs, rhs }
            } else {
                EquationKind::Call(lhs)
            }
        };
        let comment = self.comment()?;
        Some(Equation {
            kind,
            comment,
            span: self.span_from(first),
        })
    }

    fn eq_block(&mut self) -> Option<Vec<Equation>> {
        let mut out = Vec::new();
        while !self.at_block_end() && self.at_equation_start() {
            out.push(self.equation()?);
            self.expect(Sym::Semi)?;
        }
        Some(out)
    }

    pub(crate) fn for_indices(&mut self) -> Option<Vec<ForIndex>> {
        let mut out = Vec::new();
        loop {
            let name = self.ident()?;
            let range = if self.eat(Sym::KwIn) {
                Some(self.expression()?)
            } else {
                None
            };
            out.push(ForIndex { name, range });
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        Some(out)
    }

    // ------------------------------------------------------------ statements

    fn st_block(&mut self) -> Option<Vec<Statement>> {
        let mut out = Vec::new();
        while !self.at_block_end() && self.at_statement_start() {
            out.push(self.statement()?);
            self.expect(Sym::Semi)?;
        }
        Some(out)
    }

    pub(crate) fn statement(&mut self) -> Option<Statement> {
        let first = self.pos;
        let kind = if self.eat(Sym::KwIf) {
            self.if_statement_rest()?
        } else if self.eat(Sym::KwFor) {
            let indices = self.for_indices()?;
            self.expect(Sym::KwLoop)?;
            let body = self.st_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwFor)?;
            StatementKind::For { indices, body }
        } else if self.eat(Sym::KwWhile) {
            let condition = self.expression()?;
            self.expect(Sym::KwLoop)?;
            let body = self.st_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwWhile)?;
            StatementKind::While { condition, body }
        } else if self.eat(Sym::KwWhen) {
            self.when_statement_rest()?
        } else if self.eat(Sym::KwReturn) {
            StatementKind::Return
        } else if self.eat(Sym::KwBreak) {
            StatementKind::Break
        } else if self.at(Sym::LParen) {
            self.multi_assign(first)?
        } else {
            self.assign_or_call(first)?
        };
        let comment = self.comment()?;
        Some(Statement {
            kind,
            comment,
            span: self.span_from(first),
        })
    }

    /// `x := e`, `f(x)` or a bare reference (an error: a statement without effect).
    fn assign_or_call(&mut self, first: usize) -> Option<StatementKind> {
        let target = self.component_reference()?;
        let kind = if self.at(Sym::LParen) {
            let func = self.callee(&target);
            let args = self.call_args()?;
            StatementKind::Call(Expr {
                kind: ExprKind::Call { func, args },
                span: self.span_from(first),
            })
        } else if self.at(Sym::Equals) || self.at(Sym::Assign) {
            let op = self.toks[self.pos];
            self.pos += 1;
            if self.txt(&op) == "=" {
                self.diags.push(shared::equals_in_algorithm(Span::new(
                    self.file,
                    op.start(),
                    op.end(),
                )));
            }
            let value = self.expression()?;
            StatementKind::Assign { target, value }
        } else {
            self.diags
                .push(shared::statement_without_effect(target.span));
            let span = target.span;
            StatementKind::Call(Expr {
                kind: ExprKind::Ref(target),
                span,
            })
        };
        Some(kind)
    }

    /// `(a, , b) := f(x)`, from its opening parenthesis.
    fn multi_assign(&mut self, first: usize) -> Option<StatementKind> {
        self.pos += 1;
        let targets = self.output_list()?;
        self.expect(Sym::RParen)?;
        self.expect(Sym::Assign)?;
        let cref = self.component_reference()?;
        if !self.at(Sym::LParen) {
            return None;
        }
        // Arguments before the callee check: the order the pest builder reports in.
        let args = self.call_args()?;
        let func = self.callee(&cref);
        Some(StatementKind::MultiAssign {
            targets,
            value: Expr {
                kind: ExprKind::Call { func, args },
                span: self.span_from(first),
            },
        })
    }

    /// The rest of a `when` statement, its `when` eaten.
    fn when_statement_rest(&mut self) -> Option<StatementKind> {
        let mut branches = Vec::new();
        let c = self.expression()?;
        self.expect(Sym::KwThen)?;
        branches.push((c, self.st_block()?));
        while self.eat(Sym::KwElsewhen) {
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.st_block()?));
        }
        self.expect(Sym::KwEnd)?;
        self.expect(Sym::KwWhen)?;
        Some(StatementKind::When { branches })
    }

    /// The rest of an `if` statement, its `if` eaten.
    fn if_statement_rest(&mut self) -> Option<StatementKind> {
        let mut branches = Vec::new();
        let c = self.expression()?;
        self.expect(Sym::KwThen)?;
        branches.push((c, self.st_block()?));
        let mut otherwise = Vec::new();
        while self.eat(Sym::KwElseif) {
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.st_block()?));
        }
        if self.eat(Sym::KwElse) {
            otherwise = self.st_block()?;
        }
        self.expect(Sym::KwEnd)?;
        self.expect(Sym::KwIf)?;
        Some(StatementKind::If {
            branches,
            otherwise,
        })
    }
}
