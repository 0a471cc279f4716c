//! Source files, byte spans and diagnostics: the vocabulary every unimo stage shares.
//!
//! Invariant: this crate never renders anything and never touches the terminal. A
//! [`Diagnostic`] is plain data (severity, code, message, labelled spans, notes); only
//! the CLI turns it into text.

mod coded;
#[doc(hidden)]
pub use coded::documented_code;
mod diagnostic;
mod source;

pub use diagnostic::{Code, Diagnostic, Label, Severity};
pub use source::{FileId, LineCol, SourceFile, SourceMap, Span};
