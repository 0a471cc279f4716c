//! Errors of the lowering and structural stages (`E3xxx`), as data; the CLI renders.

use unimo_source::{Diagnostic, Span};

/// The optional parts of an error, boxed so that results stay small.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ErrorDetail {
    pub label: String,
    pub help: Option<String>,
    pub notes: Vec<String>,
}

/// The codes of the lowering and structural stages, one variant each; `docs/errors.md`
/// has a row per code (a test checks it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DaeCode {
    /// E3001: a construct the back end does not support yet.
    Unsupported,
    /// E3002: an index, size or range that must be known at compile time is not.
    NotKnownAtCompileTime,
    /// E3003: array sizes do not match, or a scalar was needed.
    SizeMismatch,
    /// E3004: a call of something that is not a known function.
    UnknownFunction,
    /// E3005: missing, surplus or unknown arguments of a call.
    WrongArguments,
    /// E3006: `reinit` of a variable that is not a state.
    ReinitOfNonState,
    /// E3007: inside `when`: a left side that is not a variable, or a nested `when`.
    InvalidInWhen,
    /// E3010: a reference to something the flat model has no scalar for.
    NoSuchScalar,
    /// E3011: branches of a non-parameter `if`-equation with different numbers of equations.
    UnequalIfBranches,
    /// E3012: a function output or local used before it is assigned.
    UnassignedLocal,
    /// E3013: an index out of bounds.
    IndexOutOfBounds,
    /// E3014: `pre`, `edge` or `change` of something that is not a variable.
    PreOfNonVariable,
    /// E3015: a `while` loop known at compile time that does not end.
    EndlessLoop,
    /// E3016: a function assigns a model variable.
    FunctionAssignsModel,
    /// E3017: `reinit` outside `when`.
    ReinitOutsideWhen,
    /// E3018: functions calling each other too deep while inlined.
    InliningTooDeep,
    /// E3019: wrong arguments of the collision built-ins.
    CollisionArguments,
    /// E3020: an external function unimo does not provide, or bad arguments of one it does.
    MissingExternal,
    /// E3021: a table given as an empty matrix.
    EmptyTable,
    /// E3022: the plan needs the derivative of a top-level input.
    DifferentiatedInput,
    /// W3001 (a warning): a call statement that is not executed, since the function
    /// reaches an external function unimo does not provide (writing a file, printing).
    CallNotExecuted,
    /// E3201: the model is structurally singular.
    StructurallySingular,
    /// E3202: index reduction must differentiate an equation that cannot be.
    CannotDifferentiate,
    /// E3203: index reduction would differentiate an equation too often.
    DifferentiationLimit,
    /// E3204: no dummy derivatives can be chosen at some level.
    NoDummyDerivatives,
    /// E3290: an internal consistency error of the structural algorithms (a bug).
    InternalStructure,
}

impl DaeCode {
    /// Every code of the stage.
    pub const ALL: &'static [DaeCode] = &[
        DaeCode::Unsupported,
        DaeCode::NotKnownAtCompileTime,
        DaeCode::SizeMismatch,
        DaeCode::UnknownFunction,
        DaeCode::WrongArguments,
        DaeCode::ReinitOfNonState,
        DaeCode::InvalidInWhen,
        DaeCode::NoSuchScalar,
        DaeCode::UnequalIfBranches,
        DaeCode::UnassignedLocal,
        DaeCode::IndexOutOfBounds,
        DaeCode::PreOfNonVariable,
        DaeCode::EndlessLoop,
        DaeCode::FunctionAssignsModel,
        DaeCode::ReinitOutsideWhen,
        DaeCode::InliningTooDeep,
        DaeCode::CollisionArguments,
        DaeCode::MissingExternal,
        DaeCode::EmptyTable,
        DaeCode::DifferentiatedInput,
        DaeCode::CallNotExecuted,
        DaeCode::StructurallySingular,
        DaeCode::CannotDifferentiate,
        DaeCode::DifferentiationLimit,
        DaeCode::NoDummyDerivatives,
        DaeCode::InternalStructure,
    ];

    /// Whether the code is a warning (`W3xxx`): reported, and the model goes on.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }

    /// The code as printed (`E3001`).
    pub fn as_str(self) -> &'static str {
        match self {
            DaeCode::Unsupported => "E3001",
            DaeCode::NotKnownAtCompileTime => "E3002",
            DaeCode::SizeMismatch => "E3003",
            DaeCode::UnknownFunction => "E3004",
            DaeCode::WrongArguments => "E3005",
            DaeCode::ReinitOfNonState => "E3006",
            DaeCode::InvalidInWhen => "E3007",
            DaeCode::NoSuchScalar => "E3010",
            DaeCode::UnequalIfBranches => "E3011",
            DaeCode::UnassignedLocal => "E3012",
            DaeCode::IndexOutOfBounds => "E3013",
            DaeCode::PreOfNonVariable => "E3014",
            DaeCode::EndlessLoop => "E3015",
            DaeCode::FunctionAssignsModel => "E3016",
            DaeCode::ReinitOutsideWhen => "E3017",
            DaeCode::InliningTooDeep => "E3018",
            DaeCode::CollisionArguments => "E3019",
            DaeCode::MissingExternal => "E3020",
            DaeCode::EmptyTable => "E3021",
            DaeCode::DifferentiatedInput => "E3022",
            DaeCode::CallNotExecuted => "W3001",
            DaeCode::StructurallySingular => "E3201",
            DaeCode::CannotDifferentiate => "E3202",
            DaeCode::DifferentiationLimit => "E3203",
            DaeCode::NoDummyDerivatives => "E3204",
            DaeCode::InternalStructure => "E3290",
        }
    }
}

impl std::fmt::Display for DaeCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A lowering or analysis error with its code.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{code}: {message}")]
pub struct DaeError {
    pub code: DaeCode,
    pub message: Box<str>,
    pub span: Span,
    pub detail: Box<ErrorDetail>,
}

impl DaeError {
    pub fn new(code: DaeCode, message: impl Into<String>, span: Span) -> DaeError {
        DaeError {
            code,
            message: message.into().into_boxed_str(),
            span,
            detail: Box::default(),
        }
    }

    pub fn label(mut self, label: impl Into<String>) -> DaeError {
        self.detail.label = label.into();
        self
    }

    pub fn help(mut self, help: impl Into<String>) -> DaeError {
        self.detail.help = Some(help.into());
        self
    }

    pub fn note(mut self, note: impl Into<String>) -> DaeError {
        self.detail.notes.push(note.into());
        self
    }

    pub fn notes(&self) -> &[String] {
        &self.detail.notes
    }

    pub fn to_diagnostic(&self) -> Diagnostic {
        let label = if self.detail.label.is_empty() {
            "here"
        } else {
            &self.detail.label
        };
        let mut d = if self.code.is_warning() {
            Diagnostic::warning(self.code.as_str(), self.message.to_string())
        } else {
            Diagnostic::error(self.code.as_str(), self.message.to_string())
        }
        .at(self.span, label);
        for n in &self.detail.notes {
            d = d.with_note(n.clone());
        }
        if let Some(h) = &self.detail.help {
            d = d.with_help(h.clone());
        }
        d
    }
}

pub type DaeResult<T> = Result<T, DaeError>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_diagnostic_carries_the_code_label_and_notes() {
        let e = DaeError::new(DaeCode::SizeMismatch, "sizes differ", Span::default())
            .label("this side")
            .note("a note")
            .help("a help");
        let d = e.to_diagnostic();
        assert_eq!(d.code.0, "E3003");
        assert_eq!(d.notes, ["a note"]);
        assert_eq!(d.help.as_deref(), Some("a help"));
        assert_eq!(e.to_string(), "E3003: sizes differ");
    }
}
