//! A hand-written scanner used around the pest parser: it finds lexical errors with
//! precise spans, measures nesting depth before pest recurses, and gives token
//! boundaries for error recovery and for naming the token an error was found at.

/// What kind of token a [`Token`] is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum TokenKind {
    Ident,
    QuotedIdent,
    Keyword,
    Number,
    String,
    /// Operators and punctuation.
    Punct,
}

/// What a keyword or punctuation token is, so parsers compare integers, not text.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
#[repr(u8)]
pub enum Sym {
    /// Names, numbers and strings.
    None,
    KwAlgorithm,
    KwAnd,
    KwAnnotation,
    KwBlock,
    KwBreak,
    KwClass,
    KwConnect,
    KwConnector,
    KwConstant,
    KwConstrainedby,
    KwDer,
    KwDiscrete,
    KwEach,
    KwElse,
    KwElseif,
    KwElsewhen,
    KwEncapsulated,
    KwEnd,
    KwEnumeration,
    KwEquation,
    KwExpandable,
    KwExtends,
    KwExternal,
    KwFalse,
    KwFinal,
    KwFlow,
    KwFor,
    KwFunction,
    KwIf,
    KwImport,
    KwImpure,
    KwIn,
    KwInitial,
    KwInner,
    KwInput,
    KwLoop,
    KwModel,
    KwNot,
    KwOperator,
    KwOr,
    KwOuter,
    KwOutput,
    KwPackage,
    KwParameter,
    KwPartial,
    KwProtected,
    KwPublic,
    KwPure,
    KwRecord,
    KwRedeclare,
    KwReplaceable,
    KwReturn,
    KwStream,
    KwThen,
    KwTrue,
    KwType,
    KwWhen,
    KwWhile,
    KwWithin,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// `;`
    Semi,
    /// `,`
    Comma,
    /// `.`
    Dot,
    /// `:`
    Colon,
    /// `=`
    Equals,
    /// `<`
    Lt,
    /// `>`
    Gt,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `^`
    Caret,
    /// `:=`
    Assign,
    /// `<=`
    Le,
    /// `>=`
    Ge,
    /// `==`
    EqEq,
    /// `<>`
    Ne,
    /// `.+`
    DotPlus,
    /// `.-`
    DotMinus,
    /// `.*`
    DotStar,
    /// `./`
    DotSlash,
    /// `.^`
    DotCaret,
}

/// The keyword a word is, if any.
pub fn keyword_sym(word: &str) -> Option<Sym> {
    Some(match word {
        "algorithm" => Sym::KwAlgorithm,
        "and" => Sym::KwAnd,
        "annotation" => Sym::KwAnnotation,
        "block" => Sym::KwBlock,
        "break" => Sym::KwBreak,
        "class" => Sym::KwClass,
        "connect" => Sym::KwConnect,
        "connector" => Sym::KwConnector,
        "constant" => Sym::KwConstant,
        "constrainedby" => Sym::KwConstrainedby,
        "der" => Sym::KwDer,
        "discrete" => Sym::KwDiscrete,
        "each" => Sym::KwEach,
        "else" => Sym::KwElse,
        "elseif" => Sym::KwElseif,
        "elsewhen" => Sym::KwElsewhen,
        "encapsulated" => Sym::KwEncapsulated,
        "end" => Sym::KwEnd,
        "enumeration" => Sym::KwEnumeration,
        "equation" => Sym::KwEquation,
        "expandable" => Sym::KwExpandable,
        "extends" => Sym::KwExtends,
        "external" => Sym::KwExternal,
        "false" => Sym::KwFalse,
        "final" => Sym::KwFinal,
        "flow" => Sym::KwFlow,
        "for" => Sym::KwFor,
        "function" => Sym::KwFunction,
        "if" => Sym::KwIf,
        "import" => Sym::KwImport,
        "impure" => Sym::KwImpure,
        "in" => Sym::KwIn,
        "initial" => Sym::KwInitial,
        "inner" => Sym::KwInner,
        "input" => Sym::KwInput,
        "loop" => Sym::KwLoop,
        "model" => Sym::KwModel,
        "not" => Sym::KwNot,
        "operator" => Sym::KwOperator,
        "or" => Sym::KwOr,
        "outer" => Sym::KwOuter,
        "output" => Sym::KwOutput,
        "package" => Sym::KwPackage,
        "parameter" => Sym::KwParameter,
        "partial" => Sym::KwPartial,
        "protected" => Sym::KwProtected,
        "public" => Sym::KwPublic,
        "pure" => Sym::KwPure,
        "record" => Sym::KwRecord,
        "redeclare" => Sym::KwRedeclare,
        "replaceable" => Sym::KwReplaceable,
        "return" => Sym::KwReturn,
        "stream" => Sym::KwStream,
        "then" => Sym::KwThen,
        "true" => Sym::KwTrue,
        "type" => Sym::KwType,
        "when" => Sym::KwWhen,
        "while" => Sym::KwWhile,
        "within" => Sym::KwWithin,
        _ => return None,
    })
}

fn punct_sym(text: &str) -> Sym {
    match text {
        "(" => Sym::LParen,
        ")" => Sym::RParen,
        "[" => Sym::LBracket,
        "]" => Sym::RBracket,
        "{" => Sym::LBrace,
        "}" => Sym::RBrace,
        ";" => Sym::Semi,
        "," => Sym::Comma,
        "." => Sym::Dot,
        ":" => Sym::Colon,
        "=" => Sym::Equals,
        "<" => Sym::Lt,
        ">" => Sym::Gt,
        "+" => Sym::Plus,
        "-" => Sym::Minus,
        "*" => Sym::Star,
        "/" => Sym::Slash,
        "^" => Sym::Caret,
        ":=" => Sym::Assign,
        "<=" => Sym::Le,
        ">=" => Sym::Ge,
        "==" => Sym::EqEq,
        "<>" => Sym::Ne,
        ".+" => Sym::DotPlus,
        ".-" => Sym::DotMinus,
        ".*" => Sym::DotStar,
        "./" => Sym::DotSlash,
        ".^" => Sym::DotCaret,
        _ => Sym::None,
    }
}

/// A token: 12 bytes (files are limited to 4 GiB, as spans are).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Token {
    pub kind: TokenKind,
    pub sym: Sym,
    lo: u32,
    hi: u32,
}

impl Token {
    fn new(kind: TokenKind, sym: Sym, start: usize, end: usize) -> Token {
        Token {
            kind,
            sym,
            lo: start as u32,
            hi: end as u32,
        }
    }

    /// Byte offset of the first byte.
    pub fn start(&self) -> usize {
        self.lo as usize
    }

    /// Byte offset just past the last byte.
    pub fn end(&self) -> usize {
        self.hi as usize
    }
}

/// A lexical error, with the byte range it covers.
#[derive(Clone, PartialEq, Eq, Debug)]
pub enum LexError {
    UnexpectedChar { start: usize, end: usize, ch: char },
    UnterminatedString { start: usize },
    UnterminatedComment { start: usize },
    UnterminatedQuotedIdent { start: usize },
    BadEscape { start: usize, end: usize },
    MalformedNumber { start: usize, end: usize },
    TooDeep { start: usize, depth: usize },
}

/// Result of scanning a whole file.
#[derive(Debug, Default)]
pub struct Scan {
    pub tokens: Vec<Token>,
    pub errors: Vec<LexError>,
    /// Deepest bracket/`if` nesting seen, and where it was first reached.
    pub max_depth: usize,
}

/// Reserved words of Modelica (spec 2.3.3) plus the builtin-call names `der`,
/// `initial` and `pure`, which the grammar treats as keywords too.
pub const KEYWORDS: &[&str] = &[
    "algorithm",
    "and",
    "annotation",
    "block",
    "break",
    "class",
    "connect",
    "connector",
    "constant",
    "constrainedby",
    "der",
    "discrete",
    "each",
    "else",
    "elseif",
    "elsewhen",
    "encapsulated",
    "end",
    "enumeration",
    "equation",
    "expandable",
    "extends",
    "external",
    "false",
    "final",
    "flow",
    "for",
    "function",
    "if",
    "import",
    "impure",
    "in",
    "initial",
    "inner",
    "input",
    "loop",
    "model",
    "not",
    "operator",
    "or",
    "outer",
    "output",
    "package",
    "parameter",
    "partial",
    "protected",
    "public",
    "pure",
    "record",
    "redeclare",
    "replaceable",
    "return",
    "stream",
    "then",
    "true",
    "type",
    "when",
    "while",
    "within",
];

pub fn is_keyword(word: &str) -> bool {
    keyword_sym(word).is_some()
}

/// Nesting beyond this is refused before parsing (the parser is recursive).
pub const MAX_DEPTH: usize = 200;

/// Operators in one statement beyond this are refused (the tree they build is as deep).
pub const MAX_OPERATORS: usize = 20_000;

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}

fn is_ident_char(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// The scanner's running measures of nesting, checked against the depth limits.
#[derive(Default)]
struct Nesting {
    depth: usize,
    ifs_since_semi: usize,
    too_deep_reported: bool,
    // Unary operators in a row (`- - - x`) nest like brackets; an operand ends the run.
    unary_run: usize,
    after_operand: bool,
    // Binary operators in one statement build one deep tree.
    ops_in_statement: usize,
}

impl Nesting {
    /// A string, quoted identifier or number: an operand.
    fn operand(&mut self) {
        self.unary_run = 0;
        self.after_operand = true;
    }

    /// A keyword or identifier.
    fn word(&mut self, word: &str, kind: TokenKind) {
        if word == "if" {
            self.ifs_since_semi += 1;
        }
        match word {
            "not" => self.unary_run += 1,
            "and" | "or" => {
                self.ops_in_statement += 1;
                self.after_operand = false;
            }
            _ => {
                self.unary_run = 0;
                self.after_operand =
                    kind == TokenKind::Ident || matches!(word, "end" | "true" | "false");
            }
        }
    }

    /// A punctuation token of `len` bytes starting with `b`.
    fn punct(&mut self, b: u8, len: usize) {
        match b {
            b'(' | b'[' | b'{' => self.depth += 1,
            b')' | b']' | b'}' => self.depth = self.depth.saturating_sub(1),
            b';' => {
                self.ifs_since_semi = 0;
                self.ops_in_statement = 0;
            }
            _ => {}
        }
        if matches!(b, b'-' | b'+') && len == 1 && !self.after_operand {
            self.unary_run += 1;
        } else if matches!(b, b')' | b']' | b'}') {
            self.unary_run = 0;
        } else if !matches!(b, b'(' | b'[' | b'{' | b';' | b',') {
            self.ops_in_statement += 1;
        }
        self.after_operand = matches!(b, b')' | b']' | b'}');
    }

    /// Records the deepest nesting so far and reports the first excess, at `start`.
    fn check(&mut self, start: usize, out: &mut Scan) {
        if self.ops_in_statement > MAX_OPERATORS && !self.too_deep_reported {
            self.too_deep_reported = true;
            out.errors.push(LexError::TooDeep {
                start,
                depth: self.ops_in_statement,
            });
        }
        let d = self.depth + self.ifs_since_semi + self.unary_run;
        if d > out.max_depth {
            out.max_depth = d;
            if d > MAX_DEPTH && !self.too_deep_reported {
                self.too_deep_reported = true;
                out.errors.push(LexError::TooDeep { start, depth: d });
            }
        }
    }
}

/// Scans `text` into tokens, collecting every lexical error.
pub fn scan(text: &str) -> Scan {
    let bytes = text.as_bytes();
    // About one token per five bytes of typical Modelica: reserve once, not by doubling.
    let mut out = Scan {
        tokens: Vec::with_capacity(text.len() / 5 + 16),
        ..Scan::default()
    };
    let mut nest = Nesting::default();
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        let start = i;
        match b {
            b' ' | b'\t' | b'\r' | b'\n' => {
                i += 1;
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i = skip_block_comment(text, i, &mut out);
                continue;
            }
            b'"' | b'\'' => {
                nest.operand();
                i = quoted_token(bytes, i, &mut out);
                continue;
            }
            _ if is_ident_start(b) => {
                i = word_token(text, i, &mut out, &mut nest);
            }
            _ if b.is_ascii_digit()
                || (b == b'.' && bytes.get(i + 1).is_some_and(|c| c.is_ascii_digit())) =>
            {
                nest.operand();
                i = number_token(bytes, i, &mut out);
            }
            _ => {
                let len = punct_len(bytes, i);
                if len == 0 {
                    i = unexpected_char(text, i, &mut out);
                    continue;
                }
                nest.punct(b, len);
                out.tokens.push(Token::new(
                    TokenKind::Punct,
                    punct_sym(&text[start..i + len]),
                    start,
                    i + len,
                ));
                i += len;
            }
        }
        nest.check(start, &mut out);
    }
    out
}

/// Skips the `/* ... */` comment starting at `i`; returns where scanning resumes.
fn skip_block_comment(text: &str, i: usize, out: &mut Scan) -> usize {
    match text[i + 2..].find("*/") {
        Some(k) => i + 2 + k + 2,
        None => {
            out.errors.push(LexError::UnterminatedComment { start: i });
            text.len()
        }
    }
}

/// The string or quoted identifier starting at `start` (its quote); returns its end.
fn quoted_token(bytes: &[u8], start: usize, out: &mut Scan) -> usize {
    let b = bytes[start];
    let (end, ok, escapes) = scan_quoted(bytes, start, b);
    for (s, e) in escapes {
        out.errors.push(LexError::BadEscape { start: s, end: e });
    }
    if !ok {
        out.errors.push(if b == b'"' {
            LexError::UnterminatedString { start }
        } else {
            LexError::UnterminatedQuotedIdent { start }
        });
    }
    let kind = if b == b'"' {
        TokenKind::String
    } else {
        TokenKind::QuotedIdent
    };
    out.tokens.push(Token::new(kind, Sym::None, start, end));
    end
}

/// The keyword or identifier starting at `start`; returns its end.
fn word_token(text: &str, start: usize, out: &mut Scan, nest: &mut Nesting) -> usize {
    let bytes = text.as_bytes();
    let mut i = start;
    while i < bytes.len() && is_ident_char(bytes[i]) {
        i += 1;
    }
    let word = &text[start..i];
    // Every keyword is 2 to 13 lower-case letters: most names fail cheaply.
    let sym = if (2..=13).contains(&word.len()) && bytes[start].is_ascii_lowercase() {
        keyword_sym(word)
    } else {
        None
    };
    let (kind, sym) = match sym {
        Some(k) => (TokenKind::Keyword, k),
        None => (TokenKind::Ident, Sym::None),
    };
    nest.word(word, kind);
    out.tokens.push(Token::new(kind, sym, start, i));
    i
}

/// The number starting at `start`; returns its end.
fn number_token(bytes: &[u8], start: usize, out: &mut Scan) -> usize {
    let (end, ok) = scan_number(bytes, start);
    if !ok {
        out.errors.push(LexError::MalformedNumber { start, end });
    }
    out.tokens
        .push(Token::new(TokenKind::Number, Sym::None, start, end));
    end
}

/// A character no token starts with, at `start`; returns where scanning resumes.
fn unexpected_char(text: &str, start: usize, out: &mut Scan) -> usize {
    let ch = text[start..].chars().next().unwrap_or('\u{FFFD}');
    let end = start + ch.len_utf8();
    // A byte-order mark is harmless whitespace.
    if ch != '\u{FEFF}' {
        out.errors.push(LexError::UnexpectedChar { start, end, ch });
    }
    end
}

/// Scans a string or quoted identifier starting at `i` (the quote). Returns the end,
/// whether it was terminated, and the ranges of invalid escapes.
fn scan_quoted(bytes: &[u8], mut i: usize, quote: u8) -> (usize, bool, Vec<(usize, usize)>) {
    let mut bad = Vec::new();
    i += 1;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' => {
                let valid = matches!(
                    bytes.get(i + 1),
                    Some(
                        b'\''
                            | b'"'
                            | b'?'
                            | b'\\'
                            | b'a'
                            | b'b'
                            | b'f'
                            | b'n'
                            | b'r'
                            | b't'
                            | b'v'
                    )
                );
                if !valid && i + 1 < bytes.len() {
                    // Cover the whole (possibly multi-byte) escaped character.
                    let mut e = i + 2;
                    while e < bytes.len() && (bytes[e] & 0xC0) == 0x80 {
                        e += 1;
                    }
                    bad.push((i, e));
                }
                i += 2;
            }
            c if c == quote => return (i + 1, true, bad),
            // A quoted identifier ends at the line; a string may span lines.
            b'\n' if quote == b'\'' => return (i, false, bad),
            _ => i += 1,
        }
    }
    (bytes.len().min(i), false, bad)
}

/// Scans a number starting at `i`; returns its end and whether it is well formed.
fn scan_number(bytes: &[u8], mut i: usize) -> (usize, bool) {
    let digits = |i: &mut usize| {
        let s = *i;
        while *i < bytes.len() && bytes[*i].is_ascii_digit() {
            *i += 1;
        }
        *i - s
    };
    let mut ok = true;
    let int_digits = digits(&mut i);
    if i < bytes.len() && bytes[i] == b'.' {
        i += 1;
        let frac = digits(&mut i);
        if int_digits == 0 && frac == 0 {
            ok = false;
        }
    }
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        i += 1;
        if i < bytes.len() && (bytes[i] == b'+' || bytes[i] == b'-') {
            i += 1;
        }
        if digits(&mut i) == 0 {
            ok = false;
        }
    }
    // A number glued to letters (`12abc`, `1.5x`) is one malformed token.
    while i < bytes.len()
        && (is_ident_char(bytes[i])
            || (bytes[i] == b'.' && bytes.get(i + 1).is_some_and(|c| c.is_ascii_digit())))
    {
        ok = false;
        i += 1;
    }
    (i, ok)
}

/// Length of the operator or punctuation at `i`, 0 if none.
fn punct_len(bytes: &[u8], i: usize) -> usize {
    let two = |a: u8, b: u8| bytes[i] == a && bytes.get(i + 1) == Some(&b);
    if two(b':', b'=')
        || two(b'<', b'=')
        || two(b'>', b'=')
        || two(b'=', b'=')
        || two(b'<', b'>')
        || two(b'.', b'+')
        || two(b'.', b'-')
        || two(b'.', b'*')
        || two(b'.', b'/')
        || two(b'.', b'^')
    {
        return 2;
    }
    match bytes[i] {
        b'(' | b')' | b'[' | b']' | b'{' | b'}' | b';' | b',' | b'.' | b':' | b'=' | b'<'
        | b'>' | b'+' | b'-' | b'*' | b'/' | b'^' => 1,
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_sorted_for_binary_search() {
        let mut sorted = KEYWORDS.to_vec();
        sorted.sort_unstable();
        assert_eq!(sorted, KEYWORDS);
    }

    #[test]
    fn finds_lexical_errors() {
        let s = scan("x = \"abc");
        assert_eq!(s.errors, vec![LexError::UnterminatedString { start: 4 }]);
        let s = scan("/* open");
        assert_eq!(s.errors, vec![LexError::UnterminatedComment { start: 0 }]);
        let s = scan("x = 1e+;");
        assert_eq!(
            s.errors,
            vec![LexError::MalformedNumber { start: 4, end: 7 }]
        );
        let s = scan("x = 12abc;");
        assert_eq!(
            s.errors,
            vec![LexError::MalformedNumber { start: 4, end: 9 }]
        );
        let s = scan("x = \"a\\qb\";");
        assert_eq!(s.errors, vec![LexError::BadEscape { start: 6, end: 8 }]);
        let s = scan("x = 1 # 2;");
        assert_eq!(
            s.errors,
            vec![LexError::UnexpectedChar {
                start: 6,
                end: 7,
                ch: '#'
            }]
        );
    }

    #[test]
    fn numbers_and_element_wise_operators() {
        let s = scan("a = 2.*b + .5 + 1.e3 + 3.;");
        assert!(s.errors.is_empty(), "{:?}", s.errors);
        let texts: Vec<_> = s
            .tokens
            .iter()
            .map(|t| &"a = 2.*b + .5 + 1.e3 + 3.;"[t.start()..t.end()])
            .collect();
        assert_eq!(
            texts,
            ["a", "=", "2.", "*", "b", "+", ".5", "+", "1.e3", "+", "3.", ";"]
        );
    }

    #[test]
    fn depth_is_measured() {
        let deep = "(".repeat(300);
        let s = scan(&deep);
        assert!(s
            .errors
            .iter()
            .any(|e| matches!(e, LexError::TooDeep { .. })));
    }
}
