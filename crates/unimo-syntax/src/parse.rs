//! The parse driver: a fast pest pass, and on failure a recovering loop that reports
//! every lexical and syntax error it can find with a coded diagnostic.
//!
//! Recovery keeps byte offsets intact: a broken statement is blanked out (replaced by
//! spaces, newlines kept) and the file is parsed again; a missing `;` is repaired by
//! turning the whitespace where it belongs into a `;`.

use crate::ast::{Expr, StoredDefinition};
use crate::build::Builder;
use crate::error::SyntaxError;
use crate::fast;
use crate::grammar::{describe, ModelicaParser, Rule};
use crate::lexer::{self, LexError, Scan, Token, TokenKind};
use pest::error::{ErrorVariant, InputLocation};
use pest::Parser;
use unimo_source::{Diagnostic, FileId, Span};

/// Most errors reported for one file before giving up.
const MAX_ERRORS: usize = 25;

/// A parsed file: the tree (possibly partial) and every diagnostic found.
#[derive(Debug)]
pub struct Parsed {
    pub ast: StoredDefinition,
    pub diagnostics: Vec<Diagnostic>,
}

impl Parsed {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(|d| d.is_error())
    }
}

/// Parses one file. Never panics; returns every error it can find.
pub fn parse(file: FileId, text: &str) -> Parsed {
    // The grammar is recursive; give it a roomy stack whatever thread calls us.
    stacker::maybe_grow(1 << 20, 64 << 20, || parse_inner(file, text, true))
}

/// Parses with the pest grammar only (no fast path): for differential tests.
pub fn parse_with_pest(file: FileId, text: &str) -> Parsed {
    stacker::maybe_grow(1 << 20, 64 << 20, || parse_inner(file, text, false))
}

/// The fast path alone: `None` where it defers to pest. For differential tests.
pub fn parse_fast_only(file: FileId, text: &str) -> Option<Parsed> {
    stacker::maybe_grow(1 << 20, 64 << 20, || {
        let scan = lexer::scan(text);
        if !scan.errors.is_empty() {
            return None;
        }
        let mut diagnostics = Vec::new();
        let ast = fast::parse_file(file, text, &scan.tokens, &mut diagnostics)?;
        Some(Parsed { ast, diagnostics })
    })
}

/// Parses a single expression (used by tests and by the flat-model reader).
pub fn parse_expression(file: FileId, text: &str) -> Result<Expr, Vec<Diagnostic>> {
    stacker::maybe_grow(1 << 20, 64 << 20, || {
        let scan = lexer::scan(text);
        if let Some(e) = scan.errors.first() {
            return Err(vec![lex_diagnostic(file, text, e)]);
        }
        let mut diags = Vec::new();
        match ModelicaParser::parse(Rule::expression_eof, text) {
            Ok(mut pairs) => {
                let top = pairs.next().and_then(|p| p.into_inner().next());
                let mut b = Builder {
                    file,
                    diags: &mut diags,
                    tokens: &scan.tokens,
                };
                let e = match top {
                    Some(p) => b.expression(p),
                    None => return Err(diags),
                };
                if diags.is_empty() {
                    Ok(e)
                } else {
                    Err(diags)
                }
            }
            Err(err) => Err(vec![syntax_diagnostic(file, text, &scan, &err).0]),
        }
    })
}

/// The tree of a file nothing could be built from: no classes, the whole text's span.
fn empty_tree(file: FileId, text: &str) -> StoredDefinition {
    StoredDefinition {
        within: None,
        classes: Vec::new(),
        span: Span::new(file, 0, text.len()),
    }
}

fn parse_inner(file: FileId, text: &str, try_fast: bool) -> Parsed {
    let empty = empty_tree(file, text);
    let mut diagnostics = Vec::new();

    // Fast path: most files are fine. Depth is checked first: the parser recurses.
    let scan = lexer::scan(text);
    if let Some(e) = scan
        .errors
        .iter()
        .find(|e| matches!(e, LexError::TooDeep { .. }))
    {
        diagnostics.push(lex_diagnostic(file, text, e));
        return Parsed {
            ast: empty,
            diagnostics,
        };
    }
    if scan.errors.is_empty() && try_fast {
        if let Some(ast) = fast::parse_file(file, text, &scan.tokens, &mut diagnostics) {
            return Parsed { ast, diagnostics };
        }
        // The fast path declined: pest decides, and reports.
        diagnostics.clear();
    }
    if scan.errors.is_empty() {
        if let Ok(mut pairs) = ModelicaParser::parse(Rule::stored_definition, text) {
            let ast = match pairs.next() {
                Some(p) => Builder {
                    file,
                    diags: &mut diagnostics,
                    tokens: &scan.tokens,
                }
                .stored_definition(p),
                None => empty,
            };
            return Parsed { ast, diagnostics };
        }
    }

    recover(file, text, scan, diagnostics)
}

/// The slow path: recover. Error detail is switched on for good (never off again, so
/// that concurrent parses give the same messages).
fn recover(file: FileId, text: &str, scan: Scan, mut diagnostics: Vec<Diagnostic>) -> Parsed {
    pest::set_error_detail(true);
    let Some(masked) = blank_lex_errors(file, text, scan, &mut diagnostics) else {
        return Parsed {
            ast: empty_tree(file, text),
            diagnostics,
        };
    };
    repair_syntax_errors(file, text, masked, diagnostics)
}

/// Reports each lexical error and blanks it out with the rest of its statement; returns
/// the blanked text, or `None` when there are too many errors or one runs to the end.
fn blank_lex_errors(
    file: FileId,
    text: &str,
    scan: Scan,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<Vec<u8>> {
    let mut masked = text.as_bytes().to_vec();
    let mut scan = scan;
    // 1. Lexical errors, each blanked out with the rest of its statement.
    let mut guard = 0;
    while let Some(err) = scan.errors.first().cloned() {
        diagnostics.push(lex_diagnostic(file, text, &err));
        let (start, end) = lex_region(&masked, &scan.tokens, &err);
        blank(&mut masked, start, end);
        guard += 1;
        // Blanked to the end (an unclosed comment): anything further would be a
        // consequence of this error, not a new one.
        if guard >= MAX_ERRORS || end >= masked.len() {
            return None;
        }
        scan = lexer::scan(as_str(&masked));
        scan.errors
            .retain(|e| !matches!(e, LexError::TooDeep { .. }));
    }
    Some(masked)
}

/// Reports each syntax error and repairs or blanks it out, until the file parses.
fn repair_syntax_errors(
    file: FileId,
    text: &str,
    mut masked: Vec<u8>,
    mut diagnostics: Vec<Diagnostic>,
) -> Parsed {
    let empty = empty_tree(file, text);
    let mut last_region: Option<(usize, usize)> = None;
    loop {
        let current = as_str(&masked).to_owned();
        match ModelicaParser::parse(Rule::stored_definition, &current) {
            Ok(mut pairs) => {
                let tokens = lexer::scan(&current).tokens;
                let ast = match pairs.next() {
                    Some(p) => Builder {
                        file,
                        diags: &mut diagnostics,
                        tokens: &tokens,
                    }
                    .stored_definition(p),
                    None => empty,
                };
                return Parsed { ast, diagnostics };
            }
            Err(err) => {
                let scan = lexer::scan(&current);
                let (diag, fix) = syntax_diagnostic(file, &current, &scan, &err);
                // An error whose statement starts where the last blanked region ended is
                // a follow-on of that repair, not a new mistake.
                // (A dangling `end`/`else` right after it is the tail of the blanked block.)
                let cascade = matches!(fix, Fix::Blank(s, _) if last_region.is_some_and(|(_, le)| {
                    s <= le
                        || (masked[le..s.min(masked.len())].iter().all(u8::is_ascii_whitespace)
                            && starts_block_tail(&current[s.min(current.len())..]))
                }));
                let fix = match (fix, cascade, last_region) {
                    (Fix::Blank(_, e), true, Some((ls, _))) => {
                        // Follow-on error of the last repair: widen it to whole statements.
                        Fix::Blank(statement_start(&scan.tokens, &current, ls, true), e)
                    }
                    (f, _, _) => {
                        diagnostics.push(diag);
                        f
                    }
                };
                if diagnostics.len() >= MAX_ERRORS {
                    diagnostics.push(
                        SyntaxError::TooManyErrors {
                            limit: MAX_ERRORS,
                            span: Span::point(file, err_pos(&err).min(text.len())),
                        }
                        .into(),
                    );
                    return Parsed {
                        ast: empty,
                        diagnostics,
                    };
                }
                match fix {
                    Fix::InsertSemicolon(at) => {
                        masked[at] = b';';
                        last_region = None;
                    }
                    Fix::Blank(s, e) => {
                        let before: usize = masked[s..e]
                            .iter()
                            .filter(|b| !b.is_ascii_whitespace())
                            .count();
                        if before == 0 {
                            return Parsed {
                                ast: empty,
                                diagnostics,
                            };
                        }
                        blank(&mut masked, s, e);
                        last_region = Some((s, e));
                    }
                }
            }
        }
    }
}

fn starts_block_tail(rest: &str) -> bool {
    let word: String = rest
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    matches!(word.as_str(), "end" | "else" | "elseif" | "elsewhen")
}

fn as_str(bytes: &[u8]) -> &str {
    // Blanking only ever writes ASCII over whole characters, so this never fails; fall
    // back to an empty text rather than panic if it somehow did.
    std::str::from_utf8(bytes).unwrap_or("")
}

/// Replaces `[start, end)` by spaces, keeping newlines (and so every line:col).
fn blank(bytes: &mut [u8], start: usize, end: usize) {
    let end = end.min(bytes.len());
    // Never cut a UTF-8 character in half: widen to character boundaries.
    let mut s = start.min(end);
    while s > 0 && (bytes[s] & 0xC0) == 0x80 {
        s -= 1;
    }
    let mut e = end;
    while e < bytes.len() && (bytes[e] & 0xC0) == 0x80 {
        e += 1;
    }
    for b in &mut bytes[s..e] {
        if *b != b'\n' {
            *b = b' ';
        }
    }
}

/// How the driver continues after an error.
enum Fix {
    InsertSemicolon(usize),
    Blank(usize, usize),
}

fn token_text<'t>(text: &'t str, t: &Token) -> &'t str {
    &text[t.start()..t.end()]
}

fn is_punct(text: &str, t: &Token, p: &str) -> bool {
    t.kind == TokenKind::Punct && token_text(text, t) == p
}

/// Start of the statement containing `pos`: after the last `;` (or, unless `only_semi`,
/// after a keyword that opens a list) before it.
fn statement_start(tokens: &[Token], text: &str, pos: usize, only_semi: bool) -> usize {
    let mut start = 0;
    for (i, t) in tokens.iter().enumerate() {
        if t.start() >= pos {
            break;
        }
        let opens = is_punct(text, t, ";")
            || (!only_semi
                && t.kind == TokenKind::Keyword
                && matches!(
                    token_text(text, t),
                    "equation" | "algorithm" | "public" | "protected" | "then" | "loop" | "else"
                ));
        if opens {
            start = tokens.get(i + 1).map_or(t.end(), |n| n.start().min(pos));
        }
    }
    start
}

/// End of the statement containing `pos`: just past the next `;`, or the end of text.
fn statement_end(tokens: &[Token], text: &str, pos: usize) -> usize {
    tokens
        .iter()
        .find(|t| t.start() >= pos && is_punct(text, t, ";"))
        .map_or(text.len(), |t| t.end())
}

fn lex_region(bytes: &[u8], tokens: &[Token], err: &LexError) -> (usize, usize) {
    let text = as_str(bytes);
    let (start, end) = lex_span(err);
    let line_start = text[..start.min(text.len())]
        .rfind('\n')
        .map_or(0, |k| k + 1);
    let line_end = text[end.min(text.len())..]
        .find('\n')
        .map_or(text.len(), |k| end + k);
    match err {
        LexError::UnterminatedComment { .. } => (start, text.len()),
        LexError::UnterminatedString { .. } | LexError::UnterminatedQuotedIdent { .. } => {
            // Everything after the quote is string: blank its statement up to the line end.
            (
                statement_start(tokens, text, start, false).max(line_start),
                line_end,
            )
        }
        _ => {
            let s = statement_start(tokens, text, start, false).max(line_start);
            let e = statement_end(tokens, text, end);
            (s, e.max(end))
        }
    }
}

fn lex_span(err: &LexError) -> (usize, usize) {
    match *err {
        LexError::UnexpectedChar { start, end, .. }
        | LexError::BadEscape { start, end }
        | LexError::MalformedNumber { start, end } => (start, end),
        LexError::UnterminatedString { start }
        | LexError::UnterminatedComment { start }
        | LexError::UnterminatedQuotedIdent { start } => (start, start + 1),
        LexError::TooDeep { start, .. } => (start, start + 1),
    }
}

pub(crate) fn lex_diagnostic(file: FileId, text: &str, err: &LexError) -> Diagnostic {
    lex_error(file, text, err).into()
}

/// The syntax error of a lexical error in `text`.
fn lex_error(file: FileId, text: &str, err: &LexError) -> SyntaxError {
    let (start, end) = lex_span(err);
    let span = Span::new(file, start.min(text.len()), end.min(text.len()));
    let lexeme = || text[start..end.min(text.len())].to_string();
    match *err {
        LexError::UnexpectedChar { ch, .. } => SyntaxError::UnexpectedChar { ch, span },
        LexError::UnterminatedString { .. } => SyntaxError::UnterminatedString { span },
        LexError::UnterminatedComment { .. } => SyntaxError::UnterminatedComment {
            span: Span::new(file, start, (start + 2).min(text.len())),
        },
        LexError::MalformedNumber { .. } => SyntaxError::MalformedNumber {
            text: lexeme(),
            span,
        },
        LexError::BadEscape { .. } => SyntaxError::BadEscape {
            text: lexeme(),
            span,
        },
        LexError::UnterminatedQuotedIdent { .. } => SyntaxError::UnterminatedQuotedIdent { span },
        LexError::TooDeep { depth, .. } if depth > lexer::MAX_OPERATORS => {
            SyntaxError::TooManyOperators {
                limit: lexer::MAX_OPERATORS,
                span,
            }
        }
        LexError::TooDeep { depth, .. } => SyntaxError::TooDeep {
            depth,
            limit: lexer::MAX_DEPTH,
            span,
        },
    }
}

fn err_pos(err: &pest::error::Error<Rule>) -> usize {
    match err.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    }
}

/// Turns a pest error into a diagnostic and the repair that lets parsing continue.
fn syntax_diagnostic(
    file: FileId,
    text: &str,
    scan: &Scan,
    err: &pest::error::Error<Rule>,
) -> (Diagnostic, Fix) {
    let pos = match err.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    }
    .min(text.len());
    let expected = expected_set(err);
    let tokens = &scan.tokens;
    let found_idx = tokens.partition_point(|t| t.start() < pos);
    let found = tokens.get(found_idx).filter(|t| t.start() == pos);
    let prev = found_idx.checked_sub(1).map(|i| &tokens[i]);
    let found_desc = match found {
        Some(t) => format!("`{}`", token_text(text, t)),
        None if text[pos..].trim().is_empty() => "end of file".to_owned(),
        None => format!("`{}`", text[pos..].chars().next().unwrap_or(' ')),
    };
    let site = ErrorSite {
        file,
        text,
        tokens,
        pos,
        found,
        found_desc,
        here: Span::new(file, pos, found.map_or(pos, |t| t.end())),
        expected,
    };

    if let Some(fixed) = site.missing_semicolon(prev) {
        return fixed;
    }
    let blank = Fix::Blank(
        statement_start(tokens, text, pos, false),
        statement_end(tokens, text, pos),
    );
    let d = site
        .unclosed_class_at_eof()
        .or_else(|| site.reserved_word())
        .or_else(|| site.unclosed_bracket())
        .unwrap_or_else(|| site.unexpected());
    (d, blank)
}

/// Where pest stopped, with what it found there and what it expected: the facts each
/// kind of syntax error is recognized by.
struct ErrorSite<'t> {
    file: FileId,
    text: &'t str,
    tokens: &'t [Token],
    pos: usize,
    found: Option<&'t Token>,
    found_desc: String,
    here: Span,
    expected: Vec<String>,
}

impl ErrorSite<'_> {
    fn has(&self, s: &str) -> bool {
        self.expected.iter().any(|e| e == s)
    }

    /// Missing `;` at the end of a line (after `prev`): repaired by inserting one.
    fn missing_semicolon(&self, prev: Option<&Token>) -> Option<(Diagnostic, Fix)> {
        let text = self.text;
        if !self.has("`;`") {
            return None;
        }
        let prev = prev?;
        let later_line = self
            .found
            .is_none_or(|t| text[prev.end()..t.start()].contains('\n'));
        let ends_with_space = text
            .as_bytes()
            .get(prev.end())
            .is_some_and(|b| b.is_ascii_whitespace());
        if later_line && ends_with_space && !is_punct(text, prev, ";") {
            let at = Span::point(self.file, prev.end());
            let d = SyntaxError::MissingSemicolon {
                found: self.found_desc.clone(),
                span: at,
                next: self.here,
            }
            .into();
            return Some((d, Fix::InsertSemicolon(prev.end())));
        }
        None
    }

    /// The file ended inside a class.
    fn unclosed_class_at_eof(&self) -> Option<Diagnostic> {
        let (file, text) = (self.file, self.text);
        if self.found.is_some() || !text[self.pos..].trim().is_empty() {
            return None;
        }
        let (name, span) = unclosed_class(self.tokens, text)?;
        Some(
            SyntaxError::UnclosedClass {
                name: name.to_string(),
                span: Span::point(file, text.len()),
                opened: Span::new(file, span.0, span.1),
            }
            .into(),
        )
    }

    /// A reserved word where a name belongs.
    fn reserved_word(&self) -> Option<Diagnostic> {
        let t = self.found?;
        if t.kind == TokenKind::Keyword
            && self.has("identifier")
            && !matches!(token_text(self.text, t), "end" | "equation" | "algorithm")
        {
            let word = token_text(self.text, t).to_string();
            return Some(
                SyntaxError::ReservedWord {
                    word,
                    span: self.here,
                }
                .into(),
            );
        }
        None
    }

    /// An opening bracket never closed before the statement ended.
    fn unclosed_bracket(&self) -> Option<Diagnostic> {
        let text = self.text;
        let closers: Vec<&str> = ["`)`", "`]`", "`}`"]
            .into_iter()
            .filter(|c| self.has(c))
            .collect();
        if closers.is_empty()
            || !self
                .found
                .is_none_or(|t| is_punct(text, t, ";") || t.kind == TokenKind::Keyword)
        {
            return None;
        }
        let (open, span) = unclosed_bracket(self.tokens, text, self.pos)?;
        let close = match open {
            "(" => ")",
            "[" => "]",
            _ => "}",
        };
        Some(
            SyntaxError::UnclosedBracket {
                open: open.to_string(),
                close,
                found: self.found_desc.clone(),
                span: self.here,
                opened: Span::new(self.file, span.0, span.1),
            }
            .into(),
        )
    }

    /// Any other error: what was expected and what was found.
    fn unexpected(&self) -> Diagnostic {
        let expected = if self.expected.is_empty() {
            String::new()
        } else {
            join_expected(&self.expected)
        };
        SyntaxError::Unexpected {
            expected,
            found: self.found_desc.clone(),
            when: self
                .found
                .is_some_and(|t| token_text(self.text, t) == "when"),
            span: self.here,
        }
        .into()
    }
}

/// The expected rules and tokens of a pest error as readable, ordered, deduplicated names.
fn expected_set(err: &pest::error::Error<Rule>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut push = |s: String| {
        if !out.contains(&s) {
            out.push(s);
        }
    };
    if let ErrorVariant::ParsingError { positives, .. } = &err.variant {
        for r in positives {
            if let Some(d) = describe(*r) {
                push(d.to_owned());
            }
        }
    }
    if let Some(attempts) = err.parse_attempts() {
        for t in attempts.expected_tokens() {
            {
                let token = t.to_string();
                let ok_punct = matches!(
                    token.as_str(),
                    "(" | ")" | "[" | "]" | "{" | "}" | "," | ";" | "=" | ":=" | ":" | "."
                );
                let ok_word = token.len() >= 2 && token.chars().all(|c| c.is_ascii_lowercase());
                if ok_punct || ok_word {
                    push(format!("`{token}`"));
                }
            }
        }
    }
    // Tokens that merely start an expression or a class add noise next to those words.
    let has_expression = out.iter().any(|e| e == "expression");
    let has_class = out.iter().any(|e| e == "class definition");
    let has_operator = out.iter().any(|e| e == "operator");
    if has_operator {
        out.retain(|e| e != "`and`" && e != "`or`");
    }
    if has_expression {
        let starts = [
            "`end`",
            "`(`",
            "`.`",
            "`[`",
            "`{`",
            "`der`",
            "`initial`",
            "`pure`",
            "`not`",
            "`true`",
            "`false`",
            "`if`",
            "`function`",
            "`-`",
            "`+`",
            "string",
            "number",
            "identifier",
            "component reference",
        ];
        out.retain(|e| !starts.contains(&e.as_str()));
    }
    if has_class {
        let starts = [
            "`block`",
            "`class`",
            "`connector`",
            "`encapsulated`",
            "`final`",
            "`function`",
            "`model`",
            "`package`",
            "`partial`",
            "`record`",
            "`expandable`",
            "`pure`",
            "`impure`",
            "`operator`",
            "`type`",
        ];
        out.retain(|e| !starts.contains(&e.as_str()));
    }
    // Most useful first.
    let rank = |s: &str| match s {
        "`;`" => 0,
        "`)`" | "`]`" | "`}`" | "`then`" | "`loop`" | "`in`" => 1,
        "`=`" | "`:=`" => 2,
        "identifier" | "expression" | "equation" | "statement" | "declaration" => 3,
        "`end`" => 4,
        "operator" => 6,
        _ => 5,
    };
    out.sort_by_key(|s| rank(s));
    out
}

fn join_expected(items: &[String]) -> String {
    const SHOWN: usize = 6;
    let shown: Vec<&str> = items.iter().take(SHOWN).map(String::as_str).collect();
    let mut s = match shown.len() {
        1 => shown[0].to_owned(),
        n => format!("{} or {}", shown[..n - 1].join(", "), shown[n - 1]),
    };
    if items.len() > SHOWN {
        s.push_str(", ...");
    }
    s
}

/// The innermost class whose `end` was never reached: its name and header span.
fn unclosed_class(tokens: &[Token], text: &str) -> Option<(String, (usize, usize))> {
    let mut stack: Vec<(String, (usize, usize))> = Vec::new();
    let word = |i: usize| tokens.get(i).map(|t| token_text(text, t));
    for i in 0..tokens.len() {
        let w = token_text(text, &tokens[i]);
        let class_kw = matches!(
            w,
            "model" | "block" | "connector" | "record" | "package" | "function" | "type" | "class"
        );
        if class_kw && tokens[i].kind == TokenKind::Keyword {
            if let Some(n) = tokens
                .get(i + 1)
                .filter(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent))
            {
                if word(i + 2) != Some("=") {
                    stack.push((token_text(text, n).to_owned(), (tokens[i].start(), n.end())));
                }
            }
        } else if w == "end"
            && tokens[i].kind == TokenKind::Keyword
            && tokens
                .get(i + 1)
                .is_some_and(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent))
        {
            stack.pop();
        }
    }
    stack.pop()
}

/// The innermost bracket still open at `pos`.
fn unclosed_bracket<'t>(
    tokens: &[Token],
    text: &'t str,
    pos: usize,
) -> Option<(&'t str, (usize, usize))> {
    let mut stack: Vec<(&str, (usize, usize))> = Vec::new();
    for t in tokens.iter().take_while(|t| t.start() < pos) {
        match token_text(text, t) {
            s @ ("(" | "[" | "{") if t.kind == TokenKind::Punct => {
                stack.push((s, (t.start(), t.end())))
            }
            ")" | "]" | "}" if t.kind == TokenKind::Punct => {
                stack.pop();
            }
            ";" if t.kind == TokenKind::Punct => stack.clear(),
            _ => {}
        }
    }
    stack.pop()
}
