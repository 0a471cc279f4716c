//! Turns pest's parse tree into the [`crate::ast`] types, attaching a span to every node.
//!
//! The grammar guarantees the shape of each pair, so children are taken in order; a
//! shape this code does not expect is a bug in the grammar, reported as an internal
//! diagnostic rather than a panic.

use crate::ast::*;
use crate::error::SyntaxError;
use crate::grammar::Rule;
use crate::lexer::Token;
use pest::iterators::Pair;
use smol_str::SmolStr;
use unimo_source::{Diagnostic, FileId, Span};

mod class;
mod element;
mod equation;
mod expr;

/// Builds AST nodes for one file, collecting diagnostics found while building.
pub(crate) struct Builder<'d> {
    pub file: FileId,
    pub diags: &'d mut Vec<Diagnostic>,
    /// The scanner's tokens of the text being built, to make spans token-tight.
    pub tokens: &'d [Token],
}

fn is_token(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::kw_within
            | Rule::kw_if
            | Rule::kw_then
            | Rule::kw_else
            | Rule::kw_elseif
            | Rule::kw_for
            | Rule::kw_loop
            | Rule::kw_in
            | Rule::kw_when
            | Rule::kw_elsewhen
            | Rule::kw_while
            | Rule::kw_connect
            | Rule::kw_equation
            | Rule::kw_algorithm
            | Rule::kw_import
            | Rule::kw_extends
            | Rule::kw_constrainedby
            | Rule::kw_annotation
            | Rule::kw_enumeration
            | Rule::kw_return
            | Rule::kw_break
            | Rule::kw_public
            | Rule::kw_protected
            | Rule::kw_function
            | Rule::kw_end
            | Rule::semi
            | Rule::EOI
    )
}

/// The meaningful children of a pair (keyword and `;` tokens dropped).
fn kids(pair: Pair<'_, Rule>) -> impl Iterator<Item = Pair<'_, Rule>> {
    pair.into_inner().filter(|p| !is_token(p.as_rule()))
}

impl Builder<'_> {
    /// The pair's span without the whitespace and comments pest includes after its last
    /// token when it ends in an empty optional part: spans run from the first token's
    /// start to the last token's end.
    fn span(&self, pair: &Pair<'_, Rule>) -> Span {
        let s = pair.as_span();
        let end = s.end();
        let last = self.tokens.partition_point(|t| t.end() <= end);
        let tight = last
            .checked_sub(1)
            .map_or(s.start(), |i| self.tokens[i].end())
            .clamp(s.start(), end);
        Span::new(self.file, s.start(), tight)
    }

    fn internal(&mut self, pair: &Pair<'_, Rule>) {
        let span = self.span(pair);
        self.diags.push(
            SyntaxError::Internal {
                rule: format!("{:?}", pair.as_rule()),
                span,
            }
            .into(),
        );
    }

    pub fn stored_definition(&mut self, pair: Pair<'_, Rule>) -> StoredDefinition {
        let s = pair.as_span();
        let span = Span::new(self.file, s.start(), s.end());
        let mut within = None;
        let mut classes = Vec::new();
        for p in kids(pair) {
            match p.as_rule() {
                Rule::within_clause => {
                    within = Some(kids(p).next().map(|n| self.name(n)));
                }
                Rule::class_definition => classes.push(self.class_definition(p)),
                Rule::final_kw => {}
                _ => self.internal(&p),
            }
        }
        StoredDefinition {
            within,
            classes,
            span,
        }
    }

    fn ident(&self, pair: Pair<'_, Rule>) -> Ident {
        Ident {
            text: SmolStr::new(pair.as_str()),
            span: self.span(&pair),
        }
    }

    pub fn name(&self, pair: Pair<'_, Rule>) -> Name {
        let span = self.span(&pair);
        let mut global = false;
        let mut parts = Vec::new();
        let inner = if pair.as_rule() == Rule::type_specifier {
            pair.into_inner().next().map(|p| p.into_inner())
        } else {
            Some(pair.into_inner())
        };
        for p in inner.into_iter().flatten() {
            match p.as_rule() {
                Rule::global_dot => global = true,
                Rule::ident => parts.push(self.ident(p)),
                _ => {}
            }
        }
        Name {
            global,
            parts,
            span,
        }
    }
}

fn empty(span: Span) -> Expr {
    Expr {
        kind: ExprKind::Tuple(Vec::new()),
        span,
    }
}

/// `partial`, the refining prefixes and the kind of a `class_prefixes` pair.
fn class_prefixes(pair: Pair<'_, Rule>) -> ClassHead {
    let (mut partial, mut prefixes, mut kind) = (false, ClassPrefixes::default(), ClassKind::Class);
    for q in pair.into_inner() {
        match q.as_rule() {
            Rule::partial_kw => partial = true,
            Rule::expandable_kw => prefixes.expandable = true,
            Rule::operator_kw => prefixes.operator = true,
            Rule::purity_kw => {
                prefixes.purity = Some(if q.as_str() == "pure" {
                    Purity::Pure
                } else {
                    Purity::Impure
                })
            }
            Rule::class_kind => kind = class_kind(q.as_str()),
            _ => {}
        }
    }
    (partial, prefixes, kind)
}

fn class_kind(s: &str) -> ClassKind {
    match s {
        "model" => ClassKind::Model,
        "block" => ClassKind::Block,
        "connector" => ClassKind::Connector,
        "record" => ClassKind::Record,
        "package" => ClassKind::Package,
        "function" => ClassKind::Function,
        "type" => ClassKind::Type,
        "operator" => ClassKind::Operator,
        _ => ClassKind::Class,
    }
}

fn causality_of(s: &str) -> Causality {
    if s == "input" {
        Causality::Input
    } else {
        Causality::Output
    }
}

/// Resolves Modelica string escapes (the lexer has already rejected invalid ones).
pub fn unescape(s: &str) -> String {
    if !s.contains('\\') {
        return s.to_owned();
    }
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('a') => out.push('\u{7}'),
            Some('b') => out.push('\u{8}'),
            Some('f') => out.push('\u{c}'),
            Some('v') => out.push('\u{b}'),
            Some(other) => out.push(other),
            None => {}
        }
    }
    out
}
