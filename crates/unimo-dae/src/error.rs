//! Errors of the lowering and structural stages (`E3xxx`), as data; the CLI renders.

use unimo_source::{Diagnostic, Span};

/// The optional parts of an error, boxed so that results stay small.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ErrorDetail {
    pub label: String,
    pub help: Option<String>,
    pub notes: Vec<String>,
}

/// A lowering or analysis error with its code.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{code}: {message}")]
pub struct DaeError {
    pub code: &'static str,
    pub message: Box<str>,
    pub span: Span,
    pub detail: Box<ErrorDetail>,
}

impl DaeError {
    pub fn new(code: &'static str, message: impl Into<String>, span: Span) -> DaeError {
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
        let mut d = Diagnostic::error(self.code, self.message.to_string()).at(self.span, label);
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
