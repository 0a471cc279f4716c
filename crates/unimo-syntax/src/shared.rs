//! Tree-building steps both parsers share (the pest builder and the fast path), so that
//! they build the same nodes and report the same diagnostics.

use crate::ast::{ComponentRef, ExprKind, Name};
use crate::error::SyntaxError;
use unimo_source::{Diagnostic, Span};

/// A number literal's value; reports `E1007` when it is out of range.
pub(crate) fn number(text: &str, span: Span, diags: &mut Vec<Diagnostic>) -> ExprKind {
    if text.contains(['.', 'e', 'E']) {
        let v: f64 = text.parse().unwrap_or(f64::NAN);
        if !v.is_finite() {
            diags.push(SyntaxError::RealOutOfRange { span }.into());
        }
        return ExprKind::Real(v);
    }
    match text.parse::<i64>() {
        Ok(v) => ExprKind::Integer(v),
        Err(_) => {
            diags.push(SyntaxError::IntegerTooLarge { span }.into());
            ExprKind::Integer(0)
        }
    }
}

/// The name of a called function; reports `E1218` when it has subscripts.
pub(crate) fn callee(cref: &ComponentRef, diags: &mut Vec<Diagnostic>) -> Name {
    match cref.as_name() {
        Some(n) => n,
        None => {
            diags.push(SyntaxError::SubscriptedCallee { span: cref.span }.into());
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
    SyntaxError::AssignInEquation { span: op }.into()
}

/// `E1216`: `=` written in an algorithm section.
pub(crate) fn equals_in_algorithm(op: Span) -> Diagnostic {
    SyntaxError::EqualsInAlgorithm { span: op }.into()
}

/// `E1217`: a statement that is only a reference.
pub(crate) fn statement_without_effect(target: Span) -> Diagnostic {
    SyntaxError::StatementWithoutEffect { span: target }.into()
}
