//! The codes of the command line and the API's usage errors (`E00xx`), one variant each
//! (the errors themselves: `error.rs`); `docs/errors.md` has a row per code (a test
//! checks it).

use unimo_source::Code;

/// A code of the command line or the API (files, options, overrides, `animate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CliCode {
    /// E0000: an error that came with no diagnostic (a bug).
    Unknown,
    /// E0001: a file could not be read.
    Unreadable,
    /// E0002: a file is not UTF-8 text.
    BadFile,
    /// E0003: a parameter override or output name that names nothing in the model.
    UnknownName,
    /// E0004: an override's value does not fit the parameter's type.
    OverrideValue,
    /// E0005: an override of something that cannot be set.
    NotSettable,
    /// E0006: an override that is not `NAME=VALUE`.
    NotNameValue,
    /// E0007: the simulation options cannot be used (an unknown method, a stop before
    /// the start, a non-positive interval or tolerance).
    BadOptions,
    /// E0008: no model can be chosen: `--model` names no class, or the file has no
    /// model or several.
    NoModel,
    /// E0009: an output file cannot be written.
    CannotWrite,
    /// E0010: a command given without what it needs (`emit --stage ast` without a file).
    NeedsFile,
    /// E0011: `plot`: the options or the columns cannot be plotted.
    CannotPlot,
    /// E0012: `bench`: the reference run failed.
    NoReference,
    /// E0020: `--tunable NAME` names no parameter.
    UnknownTunable,
    /// E0070: `animate`: the result file is unusable.
    ResultTable,
    /// E0071: `animate`: a `__unimo_visual` annotation is malformed.
    MalformedVisual,
    /// E0072: `animate`: a name in a `__unimo_visual` annotation is not a variable.
    VisualNotVariable,
    /// E0073: `animate`: a variable the scene needs is not in the result.
    MissingColumn,
    /// E0074: `animate`: the model has nothing to draw.
    NothingToDraw,
    /// E0075: `animate`: the clock column is missing, not finite or goes backwards.
    BadClock,
    /// E0076: `animate`: the model could not be initialized.
    NotInitialized,
}

impl CliCode {
    /// Every code of the command line.
    pub const ALL: &'static [CliCode] = &[
        CliCode::Unknown,
        CliCode::Unreadable,
        CliCode::BadFile,
        CliCode::UnknownName,
        CliCode::OverrideValue,
        CliCode::NotSettable,
        CliCode::NotNameValue,
        CliCode::BadOptions,
        CliCode::NoModel,
        CliCode::CannotWrite,
        CliCode::NeedsFile,
        CliCode::CannotPlot,
        CliCode::NoReference,
        CliCode::UnknownTunable,
        CliCode::ResultTable,
        CliCode::MalformedVisual,
        CliCode::VisualNotVariable,
        CliCode::MissingColumn,
        CliCode::NothingToDraw,
        CliCode::BadClock,
        CliCode::NotInitialized,
    ];

    /// Whether the code is a warning: none of the command line's is.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }

    /// The code as printed (`E0003`).
    pub fn as_str(self) -> &'static str {
        match self {
            CliCode::Unknown => "E0000",
            CliCode::Unreadable => "E0001",
            CliCode::BadFile => "E0002",
            CliCode::UnknownName => "E0003",
            CliCode::OverrideValue => "E0004",
            CliCode::NotSettable => "E0005",
            CliCode::NotNameValue => "E0006",
            CliCode::BadOptions => "E0007",
            CliCode::NoModel => "E0008",
            CliCode::CannotWrite => "E0009",
            CliCode::NeedsFile => "E0010",
            CliCode::CannotPlot => "E0011",
            CliCode::NoReference => "E0012",
            CliCode::UnknownTunable => "E0020",
            CliCode::ResultTable => "E0070",
            CliCode::MalformedVisual => "E0071",
            CliCode::VisualNotVariable => "E0072",
            CliCode::MissingColumn => "E0073",
            CliCode::NothingToDraw => "E0074",
            CliCode::BadClock => "E0075",
            CliCode::NotInitialized => "E0076",
        }
    }
}

impl From<CliCode> for Code {
    fn from(c: CliCode) -> Code {
        Code(c.as_str())
    }
}

impl std::fmt::Display for CliCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}
