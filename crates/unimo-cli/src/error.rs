//! The errors of the command line and the API (`E00xx`), one variant per situation,
//! written as a table with `unimo_source::coded_errors!` as the compiler's stages write
//! theirs: a variant's fields are what its message uses, its message is its
//! `#[error(...)]`, `code()` its [`CliCode`], and `From<CliError> for Diagnostic` adds the
//! labels of the variants that point into a file (parameter overrides point into the
//! override file or the `<command line>` source). The command line prints the others as
//! one line ([`CliError::line`]); the API turns every one into an
//! [`ApiError`](crate::api::ApiError) of the variant's [`ErrorKind`].

use crate::api::ErrorKind;
use crate::codes::CliCode;
use std::path::PathBuf;
use unimo_source::Span;

/// ` (did you mean `x`?)` after a message, or nothing.
fn one_suggestion(suggestion: &Option<String>) -> String {
    suggestion
        .as_ref()
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default()
}

/// ` (did you mean a, b?)` after a message, or nothing.
fn any_of(names: &[String]) -> String {
    if names.is_empty() {
        String::new()
    } else {
        format!(" (did you mean {}?)", names.join(", "))
    }
}

/// ` (similar: a, b)` after a message, or nothing.
fn similar_names(names: &[String]) -> String {
    if names.is_empty() {
        String::new()
    } else {
        format!(" (similar: {})", names.join(", "))
    }
}

/// What an override names that is not a setting (E0005).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Unsettable {
    #[default]
    Constant,
    Variable,
    Final,
}

impl Unsettable {
    /// The message after the name.
    fn message(self) -> &'static str {
        match self {
            Unsettable::Constant => "is a constant",
            Unsettable::Variable => "is a variable, not a parameter",
            Unsettable::Final => "is `final`: no modifier may change it (spec 7.2.6)",
        }
    }

    /// What to do instead.
    fn help(self) -> &'static str {
        match self {
            Unsettable::Constant => "only parameters can be overridden",
            Unsettable::Variable => "change its start value in the model instead",
            Unsettable::Final => "remove `final` in the model to make it a setting",
        }
    }
}

unimo_source::coded_errors! {
    /// What the command line and the API refuse: files, the choice of the model, parameter
    /// overrides, options, outputs, and `animate`'s scene.
    pub enum CliError: CliCode {
        /// E0000: an error that came with no diagnostic (the API's fallback; a bug).
        #[error("unknown error")]
        Unknown {} = CliCode::Unknown,
        |d| d,
        /// E0001: a file that cannot be read.
        #[error("cannot read `{}`: {reason}", .path.display())]
        Unreadable { path: PathBuf, reason: String } = CliCode::Unreadable,
        |d| d,
        /// E0001: a folder `check` cannot list.
        #[error("cannot read folder `{}`: {reason}", .path.display())]
        UnreadableFolder { path: PathBuf, reason: String } = CliCode::Unreadable,
        |d| d,
        /// E0001: a path given to `check` that is neither a file nor a folder.
        #[error("no such file or folder: `{}`", .path.display())]
        NoSuchPath { path: PathBuf } = CliCode::Unreadable,
        |d| d,
        /// E0002: a file that is not UTF-8 text.
        #[error("`{}` is not UTF-8 text", .path.display())]
        NotUtf8 { path: PathBuf } = CliCode::BadFile,
        |d| d,
        /// E0008: `--model` (the API's `model`) names no class.
        #[error("no class `{name}` in the file or the library")]
        NoSuchClass { name: String } = CliCode::NoModel,
        |d| d,
        /// E0008: no `--model` and no non-partial model in the file.
        #[error("the file has no non-partial model; name one with --model")]
        NoModel {} = CliCode::NoModel,
        |d| d,
        /// E0008: no `--model` and several top models in the file.
        #[error("the file has several models ({}); choose one with --model", .names.join(", "))]
        SeveralModels { names: Vec<String> } = CliCode::NoModel,
        |d| d,
        /// E0003: an override of a name that is no variable of the model.
        #[error("no parameter `{name}` in `{model}`")]
        UnknownParameter { name: String, model: String, suggestion: Option<String>, span: Span } = CliCode::UnknownName,
        |d| {
            let d = d.at(span, "unknown name");
            match (name.split_once('['), suggestion) {
                (Some((base, _)), _) => d.with_help(format!(
                    "elements of arrays cannot be set one by one: set the whole array, `{base}={{...}}`"
                )),
                (None, Some(n)) => d.with_help(format!("did you mean `{n}`?")),
                (None, None) => d,
            }
        },
        /// E0003: an output (`--vars`, the API's `outputs`) that selects no variable.
        #[error("no variable `{name}` in the model{}", similar_names(.similar))]
        UnknownVariable { name: String, similar: Vec<String> } = CliCode::UnknownName,
        |d| d,
        /// E0004: an override whose value does not fit the parameter's type (`why`: what
        /// the type needs).
        #[error("{why}")]
        OverrideValue { why: String, span: Span, declared: Span } = CliCode::OverrideValue,
        |d| d.at(span, "wrong value").with_label(declared, "declared here"),
        /// E0005: an override of a constant, a variable or a `final` parameter.
        #[error("`{name}` {}", .why.message())]
        NotSettable { name: String, why: Unsettable, span: Span, declared: Span } = CliCode::NotSettable,
        |d| d
            .at(span, "cannot be changed")
            .with_label(declared, "declared here")
            .with_help(why.help()),
        /// E0006: an override (a `-p` flag or a line of the override file) without `=`.
        #[error("`{text}` is not `NAME=VALUE`")]
        NotNameValue { text: String, span: Span } = CliCode::NotNameValue,
        |d| d.at(span, "no `=`").with_help("write e.g. `-p k=0.8`"),
        /// E0006: an override without a name before its `=`.
        #[error("an override without a name")]
        NoOverrideName { span: Span } = CliCode::NotNameValue,
        |d| d.at(span, "name missing"),
        /// E0006: an `animate -p` flag without `=`.
        #[error("`-p {text}` is not NAME=VALUE")]
        NotNameValueFlag { text: String } = CliCode::NotNameValue,
        |d| d,
        /// E0006: a `sweep -p` setting without `=`.
        #[error("`{text}` is not NAME=VALUES (e.g. k=0.5:0.9:5 or f=0.05,0.1)")]
        NotNameValues { text: String } = CliCode::NotNameValue,
        |d| d,
        /// E0006: a `sweep -p` setting with an empty name or no values.
        #[error("`{text}`: a name and values are needed")]
        NoNameOrValues { text: String } = CliCode::NotNameValue,
        |d| d,
        /// E0006: an end of a `sweep -p` range that is not a number.
        #[error("`{text}`: `{value}` is not a number")]
        RangeEndNotNumber { text: String, value: String } = CliCode::NotNameValue,
        |d| d,
        /// E0006: the count of a `sweep -p` range that is not a positive integer.
        #[error("`{text}`: `{value}` is not a count of points")]
        RangeCountNotCount { text: String, value: String } = CliCode::NotNameValue,
        |d| d,
        /// E0006: a `sweep -p` range with other than three parts.
        #[error("`{text}`: a range is FROM:TO:N")]
        NotARange { text: String } = CliCode::NotNameValue,
        |d| d,
        /// E0007: simulation options the experiment's resolution refuses (`why`: which).
        #[error("{why}")]
        BadOptions { why: String } = CliCode::BadOptions,
        |d| d,
        /// E0007: a solver that is not `auto`, `bdf`, `radau5` or `dopri5`.
        #[error("unknown method `{name}`: auto, bdf, radau5 or dopri5")]
        UnknownMethod { name: String } = CliCode::BadOptions,
        |d| d,
        /// E0007: a `--output-tolerance` that is negative or not finite.
        #[error("the output tolerance must be 0 or positive")]
        BadOutputTolerance {} = CliCode::BadOptions,
        |d| d,
        /// E0007: `bench` tolerances or atol factor that are not positive.
        #[error("tolerances and the atol factor must be positive")]
        BadTolerances {} = CliCode::BadOptions,
        |d| d,
        /// E0009: an output file (results, table, plot, page) that cannot be written.
        #[error("cannot write {what}: {reason}")]
        CannotWrite { what: String, reason: String } = CliCode::CannotWrite,
        |d| d,
        /// E0010: `emit --stage ast` without a file.
        #[error("`emit --stage ast` prints the tree of a file: give the file")]
        AstNeedsFile {} = CliCode::NeedsFile,
        |d| d,
        /// E0011: `plot --range` without two numbers.
        #[error("--range takes two numbers: FROM,TO")]
        PlotRange {} = CliCode::CannotPlot,
        |d| d,
        /// E0011: `plot --size` without two positive numbers.
        #[error("--size takes two positive numbers: W,H")]
        PlotSize {} = CliCode::CannotPlot,
        |d| d,
        /// E0011: a CSV to plot without rows.
        #[error("{}: no rows to plot", .path.display())]
        NoRowsToPlot { path: PathBuf } = CliCode::CannotPlot,
        |d| d,
        /// E0011: nothing but the horizontal axis to plot.
        #[error("nothing to plot: give --vars")]
        NothingToPlot {} = CliCode::CannotPlot,
        |d| d,
        /// E0011: a column to plot that the CSV does not have.
        #[error("no column `{name}` in the CSV{}", any_of(.near))]
        NoColumn { name: String, near: Vec<String> } = CliCode::CannotPlot,
        |d| d,
        /// E0011: no finite point in the selected columns and range.
        #[error("no finite points in the selected columns and range")]
        NoFinitePoints {} = CliCode::CannotPlot,
        |d| d,
        /// E0012: `bench`'s reference run (tight Radau5) failed.
        #[error("the reference run failed: {why}")]
        ReferenceFailed { why: String } = CliCode::NoReference,
        |d| d,
        /// E0020: a `--tunable` name that covers no parameter.
        #[error("--tunable `{name}` names no parameter of the model{}", one_suggestion(.suggestion))]
        UnknownTunable { name: String, suggestion: Option<String> } = CliCode::UnknownTunable,
        |d| d,
        /// E0070: a result table (`animate`'s result, `plot`'s CSV, `bench --reference`)
        /// that cannot be read or is not a table (`why`: the file and what is wrong).
        #[error("{why}")]
        ResultTable { why: String } = CliCode::ResultTable,
        |d| d,
        /// E0071: a malformed `__unimo_visual` annotation of the instance `path`.
        #[error("`__unimo_visual` of `{path}` (class `{class}`): {what}")]
        MalformedVisual { path: String, class: String, what: String } = CliCode::MalformedVisual,
        |d| d,
        /// E0072: a name in a `__unimo_visual` annotation that is no variable of the
        /// instance.
        #[error("`__unimo_visual` of `{path}` (class `{class}`) names `{name}`, which is not a variable of the instance (or not a scalar where one is needed)")]
        VisualNotVariable { path: String, class: String, name: String } = CliCode::VisualNotVariable,
        |d| d,
        /// E0073: a variable the scene needs that is neither a column nor a parameter.
        #[error("`{name}` (drawing `{path}`) is not a column of the result and not a parameter of the model: simulate without `--vars`, or include it")]
        MissingColumn { name: String, path: String } = CliCode::MissingColumn,
        |d| d,
        /// E0074: a model without a component to draw.
        #[error("`{model}` has no component to draw: no class it instantiates declares `annotation(__unimo_visual(...))` (see docs/animation.md)")]
        NothingToDraw { model: String } = CliCode::NothingToDraw,
        |d| d,
        /// E0075: a result without the clock column.
        #[error("the result has no column `{clock}` for the clock")]
        NoClock { clock: String } = CliCode::BadClock,
        |d| d,
        /// E0075: a clock column that is not finite or goes backwards (`why`).
        #[error("clock `{clock}`: {why}")]
        BadClock { clock: String, why: String } = CliCode::BadClock,
        |d| d,
        /// E0076: a model that could not be initialized to know its parameter values.
        #[error("the model could not be initialized for its parameter values")]
        NotInitialized {} = CliCode::NotInitialized,
        |d| d,
    }
}

impl CliError {
    /// The class of the error, which gives the exit code: the malformed scene
    /// annotations are the model's errors, a model that cannot be initialized a
    /// simulation failure, everything else a usage error.
    pub fn kind(&self) -> ErrorKind {
        match self {
            CliError::MalformedVisual { .. } | CliError::VisualNotVariable { .. } => {
                ErrorKind::Model
            }
            CliError::NotInitialized {} => ErrorKind::Simulation,
            _ => ErrorKind::Usage,
        }
    }

    /// The error as the command line prints one that points into no file:
    /// `error[E0001]: cannot read ...`.
    pub fn line(&self) -> String {
        format!("error[{}]: {self}", self.code())
    }

    /// Prints [`line`](Self::line) to stderr; the exit code of the error's kind.
    pub fn report(&self) -> i32 {
        eprintln!("{}", self.line());
        self.kind().exit_code()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_has_a_variant_and_each_variant_its_code() {
        CliError::check_codes(CliCode::ALL);
    }

    #[test]
    fn an_error_without_a_file_is_one_line_with_its_code() {
        let e = CliError::Unreadable {
            path: "m.mo".into(),
            reason: "gone".into(),
        };
        assert_eq!(e.line(), "error[E0001]: cannot read `m.mo`: gone");
        assert_eq!(e.report(), crate::EXIT_USAGE);
        let e = CliError::UnknownTunable {
            name: "k".into(),
            suggestion: Some("kk".into()),
        };
        assert_eq!(
            e.line(),
            "error[E0020]: --tunable `k` names no parameter of the model (did you mean `kk`?)"
        );
    }
}
