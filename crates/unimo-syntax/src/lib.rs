//! The front end of unimo: Modelica-subset source text to an AST with spans.
//!
//! Invariants: parsing never panics and never stops at the first error — it returns the
//! tree it could build together with every diagnostic it found. This crate does no name
//! lookup, reads no files and prints nothing.

pub mod ast;
mod build;
pub mod dump;
pub mod error;
mod fast;
mod grammar;
pub mod lexer;
mod parse;
pub mod print;
mod shared;
mod validate;
pub mod visit;

pub use parse::{parse_expression, Parsed};
use unimo_source::FileId;

/// Parses and syntactically validates one file.
pub fn parse(file: FileId, text: &str) -> Parsed {
    let mut parsed = parse::parse(file, text);
    validate::validate(&parsed.ast, &mut parsed.diagnostics);
    parsed
}

/// The two parsers separately, for differential tests: the pest grammar alone, and the
/// hand-written fast path alone (`None` where it defers to pest). Both validated.
#[doc(hidden)]
pub mod differential {
    use super::*;

    pub fn pest_only(file: FileId, text: &str) -> Parsed {
        let mut parsed = parse::parse_with_pest(file, text);
        validate::validate(&parsed.ast, &mut parsed.diagnostics);
        parsed
    }

    pub fn fast_only_unvalidated(file: FileId, text: &str) -> Option<Parsed> {
        parse::parse_fast_only(file, text)
    }

    pub fn fast_only(file: FileId, text: &str) -> Option<Parsed> {
        let mut parsed = parse::parse_fast_only(file, text)?;
        validate::validate(&parsed.ast, &mut parsed.diagnostics);
        Some(parsed)
    }
}
