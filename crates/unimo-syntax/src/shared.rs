//! Tree-building steps both parsers share (the pest builder and the fast path), so that
//! they build the same nodes and report the same diagnostics.

use crate::ast::{ComponentRef, ExprKind, Name};
use unimo_source::{Diagnostic, Span};

/// A number literal's value; reports `E1007` when it is out of range.
pub(crate) fn number(text: &str, span: Span, diags: &mut Vec<Diagnostic>) -> ExprKind {
    if text.contains(['.', 'e', 'E']) {
        let v: f64 = text.parse().unwrap_or(f64::NAN);
        if !v.is_finite() {
            diags.push(
                Diagnostic::error("E1007", "real literal is out of range")
                    .at(span, "larger than the largest finite Real (about 1.8e308)"),
            );
        }
        return ExprKind::Real(v);
    }
    match text.parse::<i64>() {
        Ok(v) => ExprKind::Integer(v),
        Err(_) => {
            diags.push(
                Diagnostic::error("E1007", "integer literal is too large")
                    .at(span, "does not fit in a 64-bit Integer")
                    .with_help("write it as a Real, e.g. `1e20`"),
            );
            ExprKind::Integer(0)
        }
    }
}

/// The name of a called function; reports `E1218` when it has subscripts.
pub(crate) fn callee(cref: &ComponentRef, diags: &mut Vec<Diagnostic>) -> Name {
    match cref.as_name() {
        Some(n) => n,
        None => {
            diags.push(
                Diagnostic::error("E1218", "a function name cannot have subscripts")
                    .at(cref.span, "subscripted name called as a function"),
            );
            Name {
                global: cref.global,
                parts: cref.parts.iter().map(|p| p.name.clone()).collect(),
                span: cref.span,
            }
        }
    }
}

/// `E1215`: `:=` written in an equation section.
pub(crate) fn assign_in_equation(op: Span) -> Diagnostic {
    Diagnostic::error("E1215", "`:=` in an equation section")
        .at(op, "assignment is only allowed in algorithm sections")
        .with_help("write an equation with `=`, or move it into an `algorithm` section")
}

/// `E1216`: `=` written in an algorithm section.
pub(crate) fn equals_in_algorithm(op: Span) -> Diagnostic {
    Diagnostic::error("E1216", "`=` in an algorithm section")
        .at(op, "statements assign with `:=`")
        .with_help("write `:=`, or move the equation into an `equation` section")
}

/// `E1217`: a statement that is only a reference.
pub(crate) fn statement_without_effect(target: Span) -> Diagnostic {
    Diagnostic::error("E1217", "a statement must assign or call")
        .at(target, "this reference alone does nothing")
        .with_help("write `x := expr;` or call a function `f(x);`")
}
