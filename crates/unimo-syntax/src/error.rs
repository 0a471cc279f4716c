//! The coded errors of the syntax stage (`E1xxx`): lexical, syntax and syntactic-rule
//! errors, one `SyntaxError` variant per situation, turned into diagnostics.

use unimo_source::{Code, Span};

/// The codes of the syntax stage, one variant each; `docs/errors.md` has a row per code
/// (a test checks it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SyntaxCode {
    /// E1001: a character that is not part of Modelica.
    UnexpectedChar,
    /// E1002: a string literal never closed.
    UnterminatedString,
    /// E1003: a block comment never closed.
    UnterminatedComment,
    /// E1004: a malformed number.
    MalformedNumber,
    /// E1005: an invalid escape in a string.
    BadEscape,
    /// E1006: a quoted identifier not closed on its line.
    UnterminatedQuotedIdent,
    /// E1007: a literal out of range.
    LiteralOutOfRange,
    /// E1008: nesting too deep, or too many operators in one statement.
    TooDeep,
    /// E1100: a generic syntax error: what was expected and what was found.
    Unexpected,
    /// E1101: a missing `;` at the end of a line.
    MissingSemicolon,
    /// E1102: the file ends inside a class.
    UnclosedClass,
    /// E1103: a reserved word used as a name.
    ReservedWord,
    /// E1104: a bracket opened and never closed.
    UnclosedBracket,
    /// E1105: too many errors in one file.
    TooManyErrors,
    /// E1201: `end Name;` does not match the class name.
    EndNameMismatch,
    /// E1202: `when` nested inside another `when`.
    NestedWhen,
    /// E1203: `der` of a literal.
    DerOfLiteral,
    /// E1204: `reinit` outside `when`.
    ReinitOutsideWhen,
    /// E1205: the first argument of `reinit` is not a variable.
    ReinitOfNonVariable,
    /// E1206: `when` in an initial section.
    WhenInInitial,
    /// E1207: `when` inside a function.
    WhenInFunction,
    /// E1208: `return` outside a function.
    ReturnOutsideFunction,
    /// E1209: `break` outside a loop.
    BreakOutsideLoop,
    /// E1210: an event or time operator used in a function.
    EventOperatorInFunction,
    /// E1211: a builtin operator with the wrong number of arguments.
    OperatorArity,
    /// E1212: the argument of `pre`, `edge` or `change` is not a variable.
    PreOfNonVariable,
    /// E1213: two classes with the same name in one scope.
    DuplicateClass,
    /// E1214: an enumeration literal twice.
    DuplicateLiteral,
    /// E1215: `:=` in an equation section.
    AssignInEquation,
    /// E1216: `=` in an algorithm section.
    EqualsInAlgorithm,
    /// E1217: a statement that neither assigns nor calls.
    StatementWithoutEffect,
    /// E1218: a subscripted name called as a function.
    SubscriptedCallee,
    /// E1219: an equation without `=`.
    EquationWithoutEquals,
    /// E1220: a target of `(a, b) := f(x)` that is not a variable.
    NonVariableTarget,
    /// E1221: equations in a class that cannot have them.
    EquationsNotAllowed,
    /// E1222: an algorithm section in a class that cannot have one.
    AlgorithmNotAllowed,
    /// E1223: a class prefix that does not refine this kind of class.
    MisplacedClassPrefix,
    /// E1224: `end` outside an array subscript.
    EndOutsideSubscript,
    /// E1225: a parenthesized list or `()` used as a value.
    TupleAsValue,
    /// E1226: an `external` clause in a class that is not a function.
    ExternalNotInFunction,
    /// E1230: chained comparison.
    ChainedComparison,
    /// E1231: chained `^`.
    ChainedPower,
    /// E1242: the same element modified twice in one modification.
    DuplicateModification,
    /// E1999: an internal error (the parse tree had an unexpected shape).
    Internal,
}

impl SyntaxCode {
    /// Every code of the stage.
    pub const ALL: &'static [SyntaxCode] = &[
        SyntaxCode::UnexpectedChar,
        SyntaxCode::UnterminatedString,
        SyntaxCode::UnterminatedComment,
        SyntaxCode::MalformedNumber,
        SyntaxCode::BadEscape,
        SyntaxCode::UnterminatedQuotedIdent,
        SyntaxCode::LiteralOutOfRange,
        SyntaxCode::TooDeep,
        SyntaxCode::Unexpected,
        SyntaxCode::MissingSemicolon,
        SyntaxCode::UnclosedClass,
        SyntaxCode::ReservedWord,
        SyntaxCode::UnclosedBracket,
        SyntaxCode::TooManyErrors,
        SyntaxCode::EndNameMismatch,
        SyntaxCode::NestedWhen,
        SyntaxCode::DerOfLiteral,
        SyntaxCode::ReinitOutsideWhen,
        SyntaxCode::ReinitOfNonVariable,
        SyntaxCode::WhenInInitial,
        SyntaxCode::WhenInFunction,
        SyntaxCode::ReturnOutsideFunction,
        SyntaxCode::BreakOutsideLoop,
        SyntaxCode::EventOperatorInFunction,
        SyntaxCode::OperatorArity,
        SyntaxCode::PreOfNonVariable,
        SyntaxCode::DuplicateClass,
        SyntaxCode::DuplicateLiteral,
        SyntaxCode::AssignInEquation,
        SyntaxCode::EqualsInAlgorithm,
        SyntaxCode::StatementWithoutEffect,
        SyntaxCode::SubscriptedCallee,
        SyntaxCode::EquationWithoutEquals,
        SyntaxCode::NonVariableTarget,
        SyntaxCode::EquationsNotAllowed,
        SyntaxCode::AlgorithmNotAllowed,
        SyntaxCode::MisplacedClassPrefix,
        SyntaxCode::EndOutsideSubscript,
        SyntaxCode::TupleAsValue,
        SyntaxCode::ExternalNotInFunction,
        SyntaxCode::ChainedComparison,
        SyntaxCode::ChainedPower,
        SyntaxCode::DuplicateModification,
        SyntaxCode::Internal,
    ];

    /// Whether the code is a warning; the syntax stage has none.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }

    /// The code as printed (`E1101`).
    pub fn as_str(self) -> &'static str {
        match self {
            SyntaxCode::UnexpectedChar => "E1001",
            SyntaxCode::UnterminatedString => "E1002",
            SyntaxCode::UnterminatedComment => "E1003",
            SyntaxCode::MalformedNumber => "E1004",
            SyntaxCode::BadEscape => "E1005",
            SyntaxCode::UnterminatedQuotedIdent => "E1006",
            SyntaxCode::LiteralOutOfRange => "E1007",
            SyntaxCode::TooDeep => "E1008",
            SyntaxCode::Unexpected => "E1100",
            SyntaxCode::MissingSemicolon => "E1101",
            SyntaxCode::UnclosedClass => "E1102",
            SyntaxCode::ReservedWord => "E1103",
            SyntaxCode::UnclosedBracket => "E1104",
            SyntaxCode::TooManyErrors => "E1105",
            SyntaxCode::EndNameMismatch => "E1201",
            SyntaxCode::NestedWhen => "E1202",
            SyntaxCode::DerOfLiteral => "E1203",
            SyntaxCode::ReinitOutsideWhen => "E1204",
            SyntaxCode::ReinitOfNonVariable => "E1205",
            SyntaxCode::WhenInInitial => "E1206",
            SyntaxCode::WhenInFunction => "E1207",
            SyntaxCode::ReturnOutsideFunction => "E1208",
            SyntaxCode::BreakOutsideLoop => "E1209",
            SyntaxCode::EventOperatorInFunction => "E1210",
            SyntaxCode::OperatorArity => "E1211",
            SyntaxCode::PreOfNonVariable => "E1212",
            SyntaxCode::DuplicateClass => "E1213",
            SyntaxCode::DuplicateLiteral => "E1214",
            SyntaxCode::AssignInEquation => "E1215",
            SyntaxCode::EqualsInAlgorithm => "E1216",
            SyntaxCode::StatementWithoutEffect => "E1217",
            SyntaxCode::SubscriptedCallee => "E1218",
            SyntaxCode::EquationWithoutEquals => "E1219",
            SyntaxCode::NonVariableTarget => "E1220",
            SyntaxCode::EquationsNotAllowed => "E1221",
            SyntaxCode::AlgorithmNotAllowed => "E1222",
            SyntaxCode::MisplacedClassPrefix => "E1223",
            SyntaxCode::EndOutsideSubscript => "E1224",
            SyntaxCode::TupleAsValue => "E1225",
            SyntaxCode::ExternalNotInFunction => "E1226",
            SyntaxCode::ChainedComparison => "E1230",
            SyntaxCode::ChainedPower => "E1231",
            SyntaxCode::DuplicateModification => "E1242",
            SyntaxCode::Internal => "E1999",
        }
    }
}

impl From<SyntaxCode> for Code {
    fn from(c: SyntaxCode) -> Code {
        Code(c.as_str())
    }
}

impl std::fmt::Display for SyntaxCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// `expected X, found Y` or, when nothing is expected, `unexpected Y`.
fn expected_found(expected: &str, found: &str) -> String {
    if expected.is_empty() {
        format!("unexpected {found}")
    } else {
        format!("expected {expected}, found {found}")
    }
}

/// The note appended to `E1100` when the unexpected token is a `when`.
fn when_note(when: &bool) -> &'static str {
    if *when {
        " (a `when` is not allowed here)"
    } else {
        ""
    }
}

/// An operator's argument count: `1`, or `1 to 2`.
fn arity(min: &usize, max: &usize) -> String {
    if min == max {
        format!("{min}")
    } else {
        format!("{min} to {max}")
    }
}

/// `s` unless at most one argument is allowed.
fn arguments_plural(max: &usize) -> &'static str {
    if *max == 1 {
        ""
    } else {
        "s"
    }
}

/// The help of a character that is not Modelica, when one fits.
fn char_help(ch: char) -> Option<&'static str> {
    match ch {
        '#' | '%' | '$' | '@' | '!' | '&' | '|' | '?' | '~' | '`' => {
            Some("comments start with `//` or `/*`; logical operators are `and`, `or`, `not`")
        }
        '\u{2013}' | '\u{2212}' => Some("this is a typographic dash; use `-`"),
        '\u{201c}' | '\u{201d}' => Some("this is a typographic quote; use `\"`"),
        _ => None,
    }
}

unimo_source::coded_errors! {
    /// Errors found while scanning, parsing and checking the syntactic rules of one file,
    /// one variant per situation with the names and spans its message uses; each turns
    /// into the diagnostic with its code, labels, help and notes
    /// (`From<SyntaxError> for Diagnostic`).
    pub enum SyntaxError: SyntaxCode {
        /// E1001: a character that is not part of Modelica's syntax.
        #[error("unexpected character `{}`", .ch.escape_debug())]
        UnexpectedChar { ch: char, span: Span } = SyntaxCode::UnexpectedChar,
        |d| {
            let d = d.at(span, "not part of Modelica's syntax");
            match char_help(ch) {
                Some(help) => d.with_help(help),
                None => d,
            }
        },
        /// E1002: a string literal never closed.
        #[error("unterminated string literal")]
        UnterminatedString { span: Span } = SyntaxCode::UnterminatedString,
        |d| d
            .at(span, "this string is never closed")
            .with_help("add the closing `\"`; a `\"` inside a string is written `\\\"`"),
        /// E1003: a block comment never closed (`span`: its `/*`).
        #[error("unterminated block comment")]
        UnterminatedComment { span: Span } = SyntaxCode::UnterminatedComment,
        |d| d.at(span, "this comment is never closed").with_help("close it with `*/`"),
        /// E1004: a malformed number (`text`).
        #[error("malformed number `{text}`")]
        MalformedNumber { text: String, span: Span } = SyntaxCode::MalformedNumber,
        |d| d
            .at(span, "not a valid number")
            .with_help("numbers look like `12`, `1.5`, `.5`, `2.`, `1e-3` or `6.02E23`; a name cannot start with a digit"),
        /// E1005: an invalid escape (`text`) in a string.
        #[error("invalid escape `{text}` in string")]
        BadEscape { text: String, span: Span } = SyntaxCode::BadEscape,
        |d| d
            .at(span, "unknown escape sequence")
            .with_help("valid escapes are \\' \\\" \\? \\\\ \\a \\b \\f \\n \\r \\t \\v"),
        /// E1006: a quoted identifier not closed on its line.
        #[error("unterminated quoted identifier")]
        UnterminatedQuotedIdent { span: Span } = SyntaxCode::UnterminatedQuotedIdent,
        |d| d
            .at(span, "this `'` is never closed on its line")
            .with_help("quoted identifiers look like `'my name'`"),
        /// E1007: a Real literal beyond the largest finite Real.
        #[error("real literal is out of range")]
        RealOutOfRange { span: Span } = SyntaxCode::LiteralOutOfRange,
        |d| d.at(span, "larger than the largest finite Real (about 1.8e308)"),
        /// E1007: an Integer literal beyond 64 bits.
        #[error("integer literal is too large")]
        IntegerTooLarge { span: Span } = SyntaxCode::LiteralOutOfRange,
        |d| d
            .at(span, "does not fit in a 64-bit Integer")
            .with_help("write it as a Real, e.g. `1e20`"),
        /// E1008: more than `limit` operators in one statement.
        #[error("expression too long (more than {limit} operators in one statement)")]
        TooManyOperators { limit: usize, span: Span } = SyntaxCode::TooDeep,
        |d| d
            .at(span, "the limit is exceeded here")
            .with_help("split it with intermediate variables, or use `sum(...)` over an array"),
        /// E1008: brackets or `if`-expressions nested `depth` deep, beyond `limit`.
        #[error("nesting is too deep ({depth} levels; at most {limit} are supported)")]
        TooDeep { depth: usize, limit: usize, span: Span } = SyntaxCode::TooDeep,
        |d| d.at(span, "nesting exceeds the limit here"),
        /// E1100: what was expected (`", "`-joined, empty if nothing) and what was found.
        #[error("{}{}", expected_found(.expected, .found), when_note(.when))]
        Unexpected { expected: String, found: String, when: bool, span: Span } = SyntaxCode::Unexpected,
        |d| d.at(span, "unexpected here"),
        /// E1101: a missing `;` at the end of a line (`span`: where it belongs).
        #[error("expected `;`, found {found}")]
        MissingSemicolon { found: String, span: Span, next: Span } = SyntaxCode::MissingSemicolon,
        |d| d.at(span, "add `;` here").with_label(next, "the next item starts here"),
        /// E1102: the file ends inside class `name`.
        #[error("unexpected end of file: class `{name}` is not closed")]
        UnclosedClass { name: String, span: Span, opened: Span } = SyntaxCode::UnclosedClass,
        |d| d
            .at(span, format!("expected `end {name};` before the end of the file"))
            .with_label(opened, "class opened here"),
        /// E1103: a reserved word used as a name.
        #[error("`{word}` is a reserved word and cannot be used as a name")]
        ReservedWord { word: String, span: Span } = SyntaxCode::ReservedWord,
        |d| d
            .at(span, "reserved word")
            .with_help(format!("rename it, or quote it as `'{word}'`")),
        /// E1104: a bracket `open` never closed by `close` before the statement ended.
        #[error("unclosed `{open}`: expected `{close}`, found {found}")]
        UnclosedBracket { open: String, close: &'static str, found: String, span: Span, opened: Span } = SyntaxCode::UnclosedBracket,
        |d| d
            .at(span, format!("expected `{close}` before this"))
            .with_label(opened, "opened here"),
        /// E1105: parsing stopped after `limit` errors.
        #[error("too many errors; stopped after {limit}")]
        TooManyErrors { limit: usize, span: Span } = SyntaxCode::TooManyErrors,
        |d| d.at(span, "parsing stopped here"),
        /// E1201: `end end_name;` does not match `keyword name`.
        #[error("`end {end_name}` does not match `{keyword} {name}`")]
        EndNameMismatch { end_name: String, keyword: &'static str, name: String, span: Span, opened: Span } = SyntaxCode::EndNameMismatch,
        |d| d
            .at(span, format!("expected `{name}`"))
            .with_label(opened, "class opened here"),
        /// E1202: `when` nested inside another `when`.
        #[error("`when` nested inside another `when`")]
        NestedWhen { span: Span } = SyntaxCode::NestedWhen,
        |d| d
            .at(span, "nested `when`")
            .with_help("combine the conditions, or use `elsewhen` (Modelica spec 8.3.5)"),
        /// E1203: `der` of a literal.
        #[error("`der` of a literal")]
        DerOfLiteral { span: Span } = SyntaxCode::DerOfLiteral,
        |d| d
            .at(span, "a constant has no time derivative to take")
            .with_help("the derivative of a constant is 0; write `0`"),
        /// E1204: `reinit` outside `when`.
        #[error("`reinit` outside a `when`")]
        ReinitOutsideWhen { span: Span } = SyntaxCode::ReinitOutsideWhen,
        |d| d
            .at(span, "reinit is only allowed in the body of a `when`")
            .with_help("wrap it: `when condition then reinit(x, value); end when;`"),
        /// E1205: the first argument of `reinit` is not a variable.
        #[error("the first argument of `reinit` must be a variable")]
        ReinitOfNonVariable { span: Span } = SyntaxCode::ReinitOfNonVariable,
        |d| d
            .at(span, "not a variable reference")
            .with_help("write `reinit(x, expr)` where `x` is a state"),
        /// E1206: `when` in an initial section.
        #[error("`when` in an initial section")]
        WhenInInitial { span: Span } = SyntaxCode::WhenInInitial,
        |d| d
            .at(span, "not allowed during initialization")
            .with_help("use `when initial() then ... end when;` in a normal section, or write the initial equation directly"),
        /// E1207: `when` inside a function.
        #[error("`when` inside a function")]
        WhenInFunction { span: Span } = SyntaxCode::WhenInFunction,
        |d| d
            .at(span, "not allowed in a function")
            .with_help("functions have no events; use `if`"),
        /// E1208: `return` outside a function.
        #[error("`return` outside a function")]
        ReturnOutsideFunction { span: Span } = SyntaxCode::ReturnOutsideFunction,
        |d| d
            .at(span, "only functions can return")
            .with_help("in a model's algorithm, use `if` to skip statements"),
        /// E1209: `break` outside a loop.
        #[error("`break` outside a loop")]
        BreakOutsideLoop { span: Span } = SyntaxCode::BreakOutsideLoop,
        |d| d.at(span, "not inside `for` or `while`"),
        /// E1210: the event or time operator `name` used in a function.
        #[error("`{name}` cannot be used in a function")]
        EventOperatorInFunction { name: String, span: Span } = SyntaxCode::EventOperatorInFunction,
        |d| d
            .at(span, "functions have no time, states or events")
            .with_help("compute the value in the model and pass it as an input"),
        /// E1211: operator `name` called with `found` arguments, not `min` to `max`.
        #[error("`{name}` takes {} argument{}, found {found}", arity(.min, .max), arguments_plural(.max))]
        OperatorArity { name: String, min: usize, max: usize, found: usize, span: Span } = SyntaxCode::OperatorArity,
        |d| d.at(span, "wrong number of arguments"),
        /// E1212: the argument of `pre`, `edge` or `change` (`name`) is not a variable.
        #[error("the argument of `{name}` must be a variable")]
        PreOfNonVariable { name: String, span: Span } = SyntaxCode::PreOfNonVariable,
        |d| d
            .at(span, "not a variable reference")
            .with_help(format!("introduce a variable `v = ...;` and write `{name}(v)`")),
        /// E1213: two classes named `name` in one scope.
        #[error("class `{name}` is defined twice")]
        DuplicateClass { name: String, span: Span, first: Span } = SyntaxCode::DuplicateClass,
        |d| d.at(span, "second definition").with_label(first, "first defined here"),
        /// E1214: an enumeration literal twice.
        #[error("enumeration literal `{name}` appears twice")]
        DuplicateLiteral { name: String, span: Span, first: Span } = SyntaxCode::DuplicateLiteral,
        |d| d.at(span, "duplicate literal").with_label(first, "first here"),
        /// E1215: `:=` in an equation section.
        #[error("`:=` in an equation section")]
        AssignInEquation { span: Span } = SyntaxCode::AssignInEquation,
        |d| d
            .at(span, "assignment is only allowed in algorithm sections")
            .with_help("write an equation with `=`, or move it into an `algorithm` section"),
        /// E1216: `=` in an algorithm section.
        #[error("`=` in an algorithm section")]
        EqualsInAlgorithm { span: Span } = SyntaxCode::EqualsInAlgorithm,
        |d| d
            .at(span, "statements assign with `:=`")
            .with_help("write `:=`, or move the equation into an `equation` section"),
        /// E1217: a statement that is only a reference.
        #[error("a statement must assign or call")]
        StatementWithoutEffect { span: Span } = SyntaxCode::StatementWithoutEffect,
        |d| d
            .at(span, "this reference alone does nothing")
            .with_help("write `x := expr;` or call a function `f(x);`"),
        /// E1218: a subscripted name called as a function.
        #[error("a function name cannot have subscripts")]
        SubscriptedCallee { span: Span } = SyntaxCode::SubscriptedCallee,
        |d| d.at(span, "subscripted name called as a function"),
        /// E1219: an equation that is neither `lhs = rhs` nor a call.
        #[error("an equation needs `=`")]
        EquationWithoutEquals { span: Span } = SyntaxCode::EquationWithoutEquals,
        |d| d
            .at(span, "this expression is not an equation")
            .with_help("write `lhs = rhs;`; only function calls such as `assert(...)` stand alone"),
        /// E1220: a target of `(a, b) := f(x)` that is not a variable.
        #[error("the targets of `(...) :=` must be variables")]
        NonVariableTarget { span: Span } = SyntaxCode::NonVariableTarget,
        |d| d.at(span, "not a variable reference"),
        /// E1221: equations in class `name` of kind `keyword` (`in_function`: a function).
        #[error("a {keyword} cannot have equations")]
        EquationsNotAllowed { keyword: &'static str, name: String, in_function: bool, span: Span, class: Span } = SyntaxCode::EquationsNotAllowed,
        |d| d
            .at(span, "equation section not allowed here")
            .with_label(class, format!("in {keyword} `{name}`"))
            .with_help(if in_function {
                "functions compute their outputs in an `algorithm` section with `:=`"
            } else {
                "equations belong in a `model` or `block`"
            }),
        /// E1222: an algorithm section in class `name` of kind `keyword`.
        #[error("a {keyword} cannot have algorithm sections")]
        AlgorithmNotAllowed { keyword: &'static str, name: String, span: Span, class: Span } = SyntaxCode::AlgorithmNotAllowed,
        |d| d
            .at(span, "algorithm section not allowed here")
            .with_label(class, format!("in {keyword} `{name}`")),
        /// E1223: the class prefix `word` on a `keyword`; it refines only `allowed`.
        #[error("`{word}` cannot prefix a {keyword}")]
        MisplacedClassPrefix { word: &'static str, keyword: &'static str, allowed: &'static str, span: Span } = SyntaxCode::MisplacedClassPrefix,
        |d| d
            .at(span, format!("declared as {keyword} here"))
            .with_help(format!("`{word}` refines only `{allowed}`")),
        /// E1224: `end` outside an array subscript.
        #[error("`end` used outside an array subscript")]
        EndOutsideSubscript { span: Span } = SyntaxCode::EndOutsideSubscript,
        |d| d.at(span, "`end` only means the last index inside `[...]`"),
        /// E1225: `()` used as a value.
        #[error("empty parentheses `()` are not an expression")]
        EmptyParentheses { span: Span } = SyntaxCode::TupleAsValue,
        |d| d.at(span, "only allowed as the left side of `(a, b) := f(x)`"),
        /// E1225: a parenthesized list `(a, b)` used as a value.
        #[error("a parenthesized list `(a, b)` is not an expression")]
        TupleAsValue { span: Span } = SyntaxCode::TupleAsValue,
        |d| d.at(span, "only allowed as the left side of `(a, b) := f(x)`"),
        /// E1226: an `external` clause in class `name` of kind `keyword`.
        #[error("a {keyword} cannot have an `external` clause")]
        ExternalNotInFunction { keyword: &'static str, name: String, span: Span, class: Span } = SyntaxCode::ExternalNotInFunction,
        |d| d
            .at(span, "external clause not allowed here")
            .with_label(class, format!("in {keyword} `{name}`"))
            .with_help("only functions are implemented externally"),
        /// E1230: chained comparison.
        #[error("comparison operators cannot be chained")]
        ChainedComparison { span: Span } = SyntaxCode::ChainedComparison,
        |d| d.at(span, "chained comparison").with_help("write `a < b and b < c`"),
        /// E1231: chained `^`.
        #[error("`^` is not associative in Modelica")]
        ChainedPower { span: Span } = SyntaxCode::ChainedPower,
        |d| d
            .at(span, "`a ^ b ^ c` is ambiguous")
            .with_help("add parentheses: `a ^ (b ^ c)` or `(a ^ b) ^ c`"),
        /// E1242: the element `name` modified twice in one modification.
        #[error("`{name}` is modified twice in one modification")]
        DuplicateModification { name: String, span: Span, first: Span } = SyntaxCode::DuplicateModification,
        |d| d.at(span, "second modification").with_label(first, "first here"),
        /// E1999: a parse-tree node (`rule`) the tree builder does not expect (a bug).
        #[error("internal error: unexpected `{rule}` in the parse tree")]
        Internal { rule: String, span: Span } = SyntaxCode::Internal,
        |d| d
            .at(span, "here")
            .with_note("this is a bug in unimo; please report it with this file"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_has_a_variant_and_each_variant_its_documented_code() {
        SyntaxError::check_variants(SyntaxCode::ALL);
    }

    #[test]
    fn the_syntax_stage_has_no_warnings() {
        for e in SyntaxError::samples() {
            assert!(unimo_source::Diagnostic::from(e).is_error());
        }
    }

    #[test]
    fn codes_are_unique_and_in_the_stage_range() {
        let mut seen = std::collections::HashSet::new();
        for code in SyntaxCode::ALL {
            assert!(seen.insert(code.as_str()), "{code} twice");
            assert!(code.as_str().starts_with("E1"), "{code} outside E1xxx");
        }
    }

    #[test]
    fn messages_with_conditional_parts() {
        let span = Span::default();
        let e = SyntaxError::Unexpected {
            expected: "`;`".into(),
            found: "`when`".into(),
            when: true,
            span,
        };
        assert_eq!(
            e.to_string(),
            "expected `;`, found `when` (a `when` is not allowed here)"
        );
        let e = SyntaxError::Unexpected {
            expected: String::new(),
            found: "end of file".into(),
            when: false,
            span,
        };
        assert_eq!(e.to_string(), "unexpected end of file");
        let arity = |min, max, found| {
            SyntaxError::OperatorArity {
                name: "f".into(),
                min,
                max,
                found,
                span,
            }
            .to_string()
        };
        assert_eq!(arity(1, 1, 2), "`f` takes 1 argument, found 2");
        assert_eq!(arity(1, 2, 3), "`f` takes 1 to 2 arguments, found 3");
        assert_eq!(arity(0, 0, 1), "`f` takes 0 arguments, found 1");
    }
}
