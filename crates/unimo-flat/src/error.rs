//! The coded errors of the instantiation stage (`E2xxx`), turned into diagnostics.

use unimo_source::{Diagnostic, Span};

/// Errors found while looking up names and instantiating classes.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlatError {
    /// E2001: a name that denotes nothing in its scope.
    #[error("unknown {what} `{name}`")]
    UnknownName {
        name: String,
        /// What kind of thing was expected: "type", "base class", "function", ...
        what: &'static str,
        span: Span,
        suggestion: Option<String>,
        /// The name exists globally but the scope is encapsulated.
        encapsulated: bool,
    },
}

impl FlatError {
    pub fn code(&self) -> &'static str {
        match self {
            FlatError::UnknownName { .. } => "E2001",
        }
    }
}

impl From<FlatError> for Diagnostic {
    fn from(e: FlatError) -> Diagnostic {
        let message = e.to_string();
        let code = e.code();
        match e {
            FlatError::UnknownName {
                span,
                suggestion,
                encapsulated,
                name,
                ..
            } => {
                let d = Diagnostic::error(code, message).at(span, "not found in this scope");
                let d = match (suggestion, encapsulated) {
                    (_, true) => d.with_help(format!(
                        "the enclosing class is `encapsulated`: global names are hidden; add `import {name};`"
                    )),
                    (Some(s), false) => d.with_help(format!("did you mean `{s}`?")),
                    (None, false) => d,
                };
                d.with_note(
                    "names are searched in the class (with inherited elements), its imports, \
                     the enclosing classes and the library (Modelica spec 5.3)",
                )
            }
        }
    }
}
