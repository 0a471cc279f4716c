//! A hand-written recursive-descent parser over the scanner's tokens: the fast path.
//!
//! The pest grammar (`modelica.pest`) is the grammar of record. This parser accepts a
//! subset of what it accepts — every valid file in practice — and builds exactly the
//! same tree (spans and diagnostics included) about twenty times faster. Whenever it
//! meets anything it is not sure of, it gives up (`None`) and the pest parser, with its
//! error recovery and messages, takes over. Differential tests (`tests/fast_path.rs`
//! and the fuzz target) check that both parsers agree wherever the fast one answers.

use crate::ast::*;
use crate::build::unescape;
use crate::lexer::{Sym, Token, TokenKind};
use smol_str::SmolStr;
use unimo_source::{Diagnostic, FileId, Span};

mod class;
mod element;
mod equation;
mod expr;

/// Parses a whole file; `None` means "ask pest".
pub(crate) fn parse_file(
    file: FileId,
    text: &str,
    tokens: &[Token],
    diags: &mut Vec<Diagnostic>,
) -> Option<StoredDefinition> {
    let mut p = P {
        file,
        text,
        toks: tokens,
        pos: 0,
        diags,
    };
    let mut within = None;
    if p.at(Sym::KwWithin) {
        p.pos += 1;
        let name = if p.at(Sym::Semi) {
            None
        } else {
            Some(p.name()?)
        };
        p.expect(Sym::Semi)?;
        within = Some(name);
    }
    let mut classes = Vec::new();
    while p.pos < p.toks.len() {
        if p.at(Sym::KwFinal) {
            p.pos += 1;
        }
        classes.push(p.class_definition()?);
        p.expect(Sym::Semi)?;
    }
    Some(StoredDefinition {
        within,
        classes,
        span: Span::new(file, 0, text.len()),
    })
}

struct P<'a, 'd> {
    file: FileId,
    text: &'a str,
    toks: &'a [Token],
    pos: usize,
    diags: &'d mut Vec<Diagnostic>,
}

/// A keyword that names a kind of class (`operator` included).
fn is_kind_keyword(sym: Sym) -> bool {
    matches!(
        sym,
        Sym::KwClass
            | Sym::KwModel
            | Sym::KwRecord
            | Sym::KwBlock
            | Sym::KwConnector
            | Sym::KwType
            | Sym::KwPackage
            | Sym::KwFunction
            | Sym::KwOperator
    )
}

/// A keyword that can start a class definition's prefixes and kind.
fn is_class_kind(sym: Sym) -> bool {
    is_kind_keyword(sym) || matches!(sym, Sym::KwExpandable | Sym::KwPure | Sym::KwImpure)
}

impl<'a> P<'a, '_> {
    // ------------------------------------------------------------ tokens

    fn tok(&self, at: usize) -> Option<&'a Token> {
        self.toks.get(at)
    }

    fn txt(&self, t: &Token) -> &'a str {
        &self.text[t.start()..t.end()]
    }

    fn sym_at(&self, at: usize, sym: Sym) -> bool {
        self.toks.get(at).is_some_and(|t| t.sym == sym)
    }

    /// What `parse` reads when the next token is `sym` (`Some(None)` otherwise); `None`
    /// when it fails.
    fn parse_if<T>(
        &mut self,
        sym: Sym,
        parse: impl FnOnce(&mut Self) -> Option<T>,
    ) -> Option<Option<T>> {
        if self.at(sym) {
            parse(self).map(Some)
        } else {
            Some(None)
        }
    }

    fn at(&self, sym: Sym) -> bool {
        self.sym_at(self.pos, sym)
    }

    fn sym(&self) -> Sym {
        self.toks.get(self.pos).map_or(Sym::None, |t| t.sym)
    }

    fn eat(&mut self, sym: Sym) -> bool {
        let hit = self.at(sym);
        self.pos += hit as usize;
        hit
    }

    fn expect(&mut self, sym: Sym) -> Option<()> {
        self.eat(sym).then_some(())
    }

    fn at_ident(&self) -> bool {
        self.tok(self.pos)
            .is_some_and(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent))
    }

    /// Span from token `first` to the last consumed token.
    fn span_from(&self, first: usize) -> Span {
        let start = self.toks[first].start();
        let end = self.toks[self.pos.max(first + 1) - 1].end();
        Span::new(self.file, start, end.max(start))
    }

    fn ident(&mut self) -> Option<Ident> {
        if !self.at_ident() {
            return None;
        }
        let t = &self.toks[self.pos];
        self.pos += 1;
        Some(Ident {
            text: SmolStr::new(self.txt(t)),
            span: Span::new(self.file, t.start(), t.end()),
        })
    }

    /// `name` in pest is compound-atomic: no whitespace around its dots.
    fn name(&mut self) -> Option<Name> {
        let first = self.pos;
        let mut global = false;
        if self.at(Sym::Dot)
            && self
                .tok(self.pos + 1)
                .is_some_and(|n| n.start() == self.toks[self.pos].end())
        {
            global = true;
            self.pos += 1;
        }
        let mut parts = vec![self.ident()?];
        while let (Some(dot), Some(next)) = (self.tok(self.pos), self.tok(self.pos + 1)) {
            let adjacent =
                dot.start() == self.toks[self.pos - 1].end() && next.start() == dot.end();
            if adjacent
                && self.sym_at(self.pos, Sym::Dot)
                && matches!(next.kind, TokenKind::Ident | TokenKind::QuotedIdent)
            {
                self.pos += 1;
                parts.push(self.ident()?);
            } else {
                break;
            }
        }
        Some(Name {
            global,
            parts,
            span: self.span_from(first),
        })
    }

    fn string_value(&self, t: &Token) -> String {
        let raw = self.txt(t);
        unescape(&raw[1..raw.len().saturating_sub(1).max(1)])
    }

    fn description(&mut self) -> Option<String> {
        let mut out: Option<String> = None;
        if self
            .tok(self.pos)
            .is_some_and(|t| t.kind == TokenKind::String)
        {
            loop {
                let t = &self.toks[self.pos];
                self.pos += 1;
                out.get_or_insert_with(String::new)
                    .push_str(&self.string_value(t));
                let more = self.at(Sym::Plus)
                    && self
                        .tok(self.pos + 1)
                        .is_some_and(|n| n.kind == TokenKind::String);
                if !more {
                    break;
                }
                self.pos += 1;
            }
        }
        out
    }

    fn comment(&mut self) -> Option<Comment> {
        let description = self.description();
        let annotation = self.parse_if(Sym::KwAnnotation, Self::annotation)?;
        Some(Comment {
            description,
            annotation,
        })
    }

    fn annotation(&mut self) -> Option<ClassModification> {
        self.expect(Sym::KwAnnotation)?;
        self.class_modification()
    }
}
