//! Expressions: precedence climbing over binary operators, prefixes, primaries, component
//! references, subscripts and call arguments.

use super::P;
use crate::ast::*;
use crate::lexer::{Sym, Token, TokenKind};
use crate::shared;
use smol_str::SmolStr;
use unimo_source::Span;

impl<'a> P<'a, '_> {
    // ------------------------------------------------------------ expressions

    pub(crate) fn expression(&mut self) -> Option<Expr> {
        if self.at(Sym::KwIf) {
            let first = self.pos;
            self.pos += 1;
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.expression()?));
            while self.eat(Sym::KwElseif) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.expression()?));
            }
            self.expect(Sym::KwElse)?;
            let otherwise = self.expression()?;
            return Some(Expr {
                kind: ExprKind::If {
                    branches,
                    otherwise: Box::new(otherwise),
                },
                span: self.span_from(first),
            });
        }
        self.simple_expression()
    }

    pub(crate) fn simple_expression(&mut self) -> Option<Expr> {
        let first = self.pos;
        let start = self.operand_expr()?;
        if !self.at(Sym::Colon) {
            return Some(start);
        }
        self.pos += 1;
        let second = self.operand_expr()?;
        if !self.at(Sym::Colon) {
            return Some(Expr {
                kind: ExprKind::Range {
                    start: Box::new(start),
                    step: None,
                    stop: Box::new(second),
                },
                span: self.span_from(first),
            });
        }
        self.pos += 1;
        let third = self.operand_expr()?;
        Some(Expr {
            kind: ExprKind::Range {
                start: Box::new(start),
                step: Some(Box::new(second)),
                stop: Box::new(third),
            },
            span: self.span_from(first),
        })
    }

    /// The binary operator at the cursor and its binding power (pest's Pratt levels).
    fn infix(&self) -> Option<(BinaryOp, u32)> {
        Some(match self.sym() {
            Sym::KwOr => (BinaryOp::Or, 10),
            Sym::KwAnd => (BinaryOp::And, 20),
            Sym::Lt => (BinaryOp::Rel(RelOp::Lt), 40),
            Sym::Le => (BinaryOp::Rel(RelOp::Le), 40),
            Sym::Gt => (BinaryOp::Rel(RelOp::Gt), 40),
            Sym::Ge => (BinaryOp::Rel(RelOp::Ge), 40),
            Sym::EqEq => (BinaryOp::Rel(RelOp::Eq), 40),
            Sym::Ne => (BinaryOp::Rel(RelOp::Ne), 40),
            Sym::Plus => (BinaryOp::Add, 50),
            Sym::Minus => (BinaryOp::Sub, 50),
            Sym::DotPlus => (BinaryOp::ElemAdd, 50),
            Sym::DotMinus => (BinaryOp::ElemSub, 50),
            Sym::Star => (BinaryOp::Mul, 70),
            Sym::Slash => (BinaryOp::Div, 70),
            Sym::DotStar => (BinaryOp::ElemMul, 70),
            Sym::DotSlash => (BinaryOp::ElemDiv, 70),
            Sym::Caret => (BinaryOp::Pow, 80),
            Sym::DotCaret => (BinaryOp::ElemPow, 80),
            _ => return None,
        })
    }

    fn operand_expr(&mut self) -> Option<Expr> {
        self.pratt(0)
    }

    /// Precedence climbing with the same levels and associativity as the pest Pratt
    /// parser in `build.rs` (so both build identical trees).
    fn pratt(&mut self, min_bp: u32) -> Option<Expr> {
        let mut lhs = self.prefix()?;
        while let Some((op, bp)) = self.infix() {
            if bp <= min_bp {
                break;
            }
            self.pos += 1;
            let right_assoc = matches!(op, BinaryOp::Pow | BinaryOp::ElemPow);
            let rhs = self.pratt(if right_assoc { bp - 1 } else { bp })?;
            let span = lhs.span.to(rhs.span);
            lhs = Expr {
                kind: ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            };
        }
        Some(lhs)
    }

    pub(crate) fn prefix(&mut self) -> Option<Expr> {
        let t = *self.tok(self.pos)?;
        let op = match t.sym {
            Sym::KwNot => Some((UnaryOp::Not, 30)),
            Sym::Minus => Some((UnaryOp::Neg, 60)),
            Sym::Plus => Some((UnaryOp::Plus, 60)),
            _ => None,
        };
        match op {
            Some((op, bp)) => {
                self.pos += 1;
                // As pest's Pratt parser: the operand binds one level below the operator.
                let operand = self.pratt(bp - 1)?;
                let span = Span::new(self.file, t.start(), t.end()).to(operand.span);
                Some(Expr {
                    kind: ExprKind::Unary {
                        op,
                        operand: Box::new(operand),
                    },
                    span,
                })
            }
            None => self.primary(),
        }
    }

    fn primary(&mut self) -> Option<Expr> {
        let first = self.pos;
        let t = *self.tok(self.pos)?;
        let kind = match t.kind {
            TokenKind::Number => {
                self.pos += 1;
                let span = self.span_from(first);
                shared::number(self.txt(&t), span, self.diags)
            }
            TokenKind::String => {
                self.pos += 1;
                ExprKind::String(self.string_value(&t))
            }
            TokenKind::Keyword => self.keyword_primary(t, first)?,
            TokenKind::Ident | TokenKind::QuotedIdent => self.ref_or_call()?,
            TokenKind::Punct => match t.sym {
                Sym::Dot => self.ref_or_call()?,
                Sym::LParen => {
                    self.pos += 1;
                    let mut items = self.output_list()?;
                    self.expect(Sym::RParen)?;
                    let span = self.span_from(first);
                    if items.len() == 1 && items[0].is_some() {
                        let mut e = items.pop().flatten()?;
                        e.span = span;
                        return Some(e);
                    }
                    ExprKind::Tuple(items)
                }
                Sym::LBrace => self.array_constructor()?,
                Sym::LBracket => self.matrix_constructor()?,
                _ => return None,
            },
        };
        Some(Expr {
            kind,
            span: self.span_from(first),
        })
    }

    /// `true`, `false`, `end`, or a call of `der`, `initial` or `pure`; `None` for any other
    /// keyword.
    fn keyword_primary(&mut self, t: Token, first: usize) -> Option<ExprKind> {
        let kind = match self.txt(&t) {
            // Rare here; text comparison is fine.
            "true" => {
                self.pos += 1;
                ExprKind::Bool(true)
            }
            "false" => {
                self.pos += 1;
                ExprKind::Bool(false)
            }
            "end" => {
                self.pos += 1;
                ExprKind::End
            }
            w @ ("der" | "initial" | "pure") => {
                if !self.sym_at(self.pos + 1, Sym::LParen) {
                    return None;
                }
                self.pos += 1;
                let args = self.call_args()?;
                let span = self.span_from(first);
                ExprKind::Call {
                    func: Name {
                        global: false,
                        parts: vec![Ident {
                            text: SmolStr::new(w),
                            span: Span::new(self.file, t.start(), t.end()),
                        }],
                        span,
                    },
                    args,
                }
            }
            _ => return None,
        };
        Some(kind)
    }

    /// `{a, b, c}` or `{e for i in r}`, from its opening brace.
    fn array_constructor(&mut self) -> Option<ExprKind> {
        self.pos += 1;
        let head = self.expression()?;
        let kind = if self.at(Sym::KwFor) {
            self.pos += 1;
            let indices = self.for_indices()?;
            ExprKind::Comprehension {
                body: Box::new(head),
                indices,
            }
        } else {
            let mut items = vec![head];
            while self.eat(Sym::Comma) {
                items.push(self.expression()?);
            }
            ExprKind::Array(items)
        };
        self.expect(Sym::RBrace)?;
        Some(kind)
    }

    /// `[a, b; c, d]`, from its opening bracket.
    fn matrix_constructor(&mut self) -> Option<ExprKind> {
        self.pos += 1;
        let mut rows = Vec::new();
        loop {
            let mut row = vec![self.expression()?];
            while self.eat(Sym::Comma) {
                row.push(self.expression()?);
            }
            rows.push(row);
            if !self.eat(Sym::Semi) {
                break;
            }
        }
        self.expect(Sym::RBracket)?;
        Some(ExprKind::Matrix(rows))
    }

    fn ref_or_call(&mut self) -> Option<ExprKind> {
        let cref = self.component_reference()?;
        if self.at(Sym::LParen) {
            let func = self.callee(&cref);
            let args = self.call_args()?;
            Some(ExprKind::Call { func, args })
        } else {
            Some(ExprKind::Ref(cref))
        }
    }

    pub(crate) fn callee(&mut self, cref: &ComponentRef) -> Name {
        shared::callee(cref, self.diags)
    }

    /// `expression? ("," expression?)*` as in `(a, , b)`.
    pub(crate) fn output_list(&mut self) -> Option<Vec<Option<Expr>>> {
        let mut items = vec![None];
        loop {
            if self.at_expression_start() {
                let e = self.expression()?;
                if let Some(last) = items.last_mut() {
                    *last = Some(e);
                }
            }
            if self.eat(Sym::Comma) {
                items.push(None);
            } else {
                break;
            }
        }
        if items.len() == 1 && items[0].is_none() {
            items.clear();
        }
        Some(items)
    }

    pub(crate) fn component_reference(&mut self) -> Option<ComponentRef> {
        let first = self.pos;
        let global = self.eat(Sym::Dot);
        let mut parts = Vec::new();
        loop {
            let name = self.ident()?;
            let subscripts = if self.at(Sym::LBracket) {
                self.array_subscripts()?
            } else {
                Vec::new()
            };
            parts.push(RefPart { name, subscripts });
            let more = self.at(Sym::Dot)
                && self
                    .tok(self.pos + 1)
                    .is_some_and(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent));
            if !more {
                break;
            }
            self.pos += 1;
        }
        Some(ComponentRef {
            global,
            parts,
            span: self.span_from(first),
        })
    }

    pub(crate) fn array_subscripts(&mut self) -> Option<Vec<Subscript>> {
        self.expect(Sym::LBracket)?;
        let mut out = Vec::new();
        loop {
            if self.at(Sym::Colon) {
                let t = self.toks[self.pos];
                self.pos += 1;
                out.push(Subscript::Colon(Span::new(self.file, t.start(), t.end())));
            } else {
                out.push(Subscript::Expr(self.expression()?));
            }
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        self.expect(Sym::RBracket)?;
        Some(out)
    }

    pub(crate) fn call_args(&mut self) -> Option<Box<CallArgs>> {
        let first = self.pos;
        self.expect(Sym::LParen)?;
        let mut args = CallArgs::default();
        if !self.at(Sym::RParen) {
            loop {
                if self.at_ident() && self.sym_at(self.pos + 1, Sym::Equals) {
                    args.named = self.named_args()?;
                    break;
                }
                args.positional.push(self.function_argument()?);
                if self.at(Sym::KwFor) {
                    self.pos += 1;
                    args.iterators = self.for_indices()?;
                    break;
                }
                if !self.eat(Sym::Comma) {
                    break;
                }
            }
        }
        self.expect(Sym::RParen)?;
        args.span = self.span_from(first);
        Some(Box::new(args))
    }

    fn named_args(&mut self) -> Option<Vec<NamedArg>> {
        let mut out = Vec::new();
        loop {
            let name = self.ident()?;
            self.expect(Sym::Equals)?;
            let value = self.function_argument()?;
            out.push(NamedArg { name, value });
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        Some(out)
    }

    fn function_argument(&mut self) -> Option<Expr> {
        if !self.at(Sym::KwFunction) {
            return self.expression();
        }
        let first = self.pos;
        self.pos += 1;
        let func = self.name()?;
        self.expect(Sym::LParen)?;
        let args = if self.at(Sym::RParen) {
            Vec::new()
        } else {
            self.named_args()?
        };
        self.expect(Sym::RParen)?;
        Some(Expr {
            kind: ExprKind::PartialApplication {
                func: Box::new(func),
                args,
            },
            span: self.span_from(first),
        })
    }
}
