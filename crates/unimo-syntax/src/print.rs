//! Prints AST fragments back as Modelica source (minimal parentheses, exact numbers),
//! so that printing and parsing again gives the same tree.

use crate::ast::*;
use std::fmt::Write;

/// Binding strength of an expression's top operator (higher binds tighter).
fn precedence(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::If { .. } => 0,
        ExprKind::Range { .. } => 1,
        ExprKind::Binary { op, .. } => binary_precedence(*op),
        ExprKind::Unary {
            op: UnaryOp::Not, ..
        } => 4,
        ExprKind::Unary { .. } => 6,
        // A negative literal (a folded constant) is a unary minus in the text: `a - (-1)`,
        // as Modelica's grammar has no `a - -1`.
        ExprKind::Real(v) if v.is_sign_negative() => 6,
        ExprKind::Integer(v) if *v < 0 => 6,
        _ => 10,
    }
}

fn binary_precedence(op: BinaryOp) -> u8 {
    use BinaryOp::*;
    match op {
        Or => 2,
        And => 3,
        Rel(_) => 5,
        Add | Sub | ElemAdd | ElemSub => 6,
        Mul | Div | ElemMul | ElemDiv => 7,
        Pow | ElemPow => 8,
    }
}

/// An expression as Modelica text.
pub fn expr(e: &Expr) -> String {
    let mut s = String::new();
    write_expr(&mut s, e);
    s
}

fn write_paren(out: &mut String, e: &Expr, paren: bool) {
    if paren {
        out.push('(');
        write_expr(out, e);
        out.push(')');
    } else {
        write_expr(out, e);
    }
}

/// Formats a Real so that it reads back as the same `f64` and as a Real (never as an
/// Integer literal).
pub fn real(v: f64) -> String {
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E', 'N', 'i']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// A string literal with Modelica escapes.
pub fn string_lit(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            '\u{7}' => out.push_str("\\a"),
            '\u{8}' => out.push_str("\\b"),
            '\u{c}' => out.push_str("\\f"),
            '\u{b}' => out.push_str("\\v"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn write_expr(out: &mut String, e: &Expr) {
    match &e.kind {
        ExprKind::Integer(v) => {
            let _ = write!(out, "{v}");
        }
        ExprKind::Real(v) => out.push_str(&real(*v)),
        ExprKind::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        ExprKind::String(s) => out.push_str(&string_lit(s)),
        ExprKind::Ref(r) => out.push_str(&cref(r)),
        ExprKind::Call { func, args } => {
            out.push_str(&func.to_dotted());
            out.push_str(&call_args(args));
        }
        ExprKind::Unary { op, operand } => write_unary(out, *op, operand),
        ExprKind::Binary { op, lhs, rhs } => write_binary(out, *op, lhs, rhs),
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (i, (c, v)) in branches.iter().enumerate() {
                out.push_str(if i == 0 { "if " } else { " elseif " });
                write_expr(out, c);
                out.push_str(" then ");
                write_expr(out, v);
            }
            out.push_str(" else ");
            write_expr(out, otherwise);
        }
        ExprKind::Range { start, step, stop } => {
            write_paren(out, start, precedence(start) <= 1);
            out.push(':');
            if let Some(s) = step {
                write_paren(out, s, precedence(s) <= 1);
                out.push(':');
            }
            write_paren(out, stop, precedence(stop) <= 1);
        }
        ExprKind::Array(items) => {
            out.push('{');
            list(out, items);
            out.push('}');
        }
        ExprKind::Comprehension { body, indices } => {
            out.push('{');
            write_expr(out, body);
            out.push_str(" for ");
            out.push_str(&for_indices(indices));
            out.push('}');
        }
        ExprKind::Matrix(rows) => {
            out.push('[');
            for (i, row) in rows.iter().enumerate() {
                if i > 0 {
                    out.push_str("; ");
                }
                list(out, row);
            }
            out.push(']');
        }
        ExprKind::Tuple(items) => write_tuple(out, items),
        ExprKind::End => out.push_str("end"),
        ExprKind::PartialApplication { func, args } => {
            let _ = write!(out, "function {}(", func.to_dotted());
            for (i, a) in args.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                let _ = write!(out, "{} = {}", a.name.text, expr(&a.value));
            }
            out.push(')');
        }
    }
}

/// `-x`, `not x`: the operand parenthesized when it binds more loosely.
fn write_unary(out: &mut String, op: UnaryOp, operand: &Expr) {
    out.push_str(op.symbol());
    if op == UnaryOp::Not {
        out.push(' ');
    }
    let p = precedence(operand);
    let paren = match op {
        UnaryOp::Not => p < 5,
        _ => p <= 6,
    };
    write_paren(out, operand, paren);
}

/// `a op b`: each side parenthesized when it binds more loosely (or equally, where the
/// operator does not associate that way).
fn write_binary(out: &mut String, op: BinaryOp, lhs: &Expr, rhs: &Expr) {
    let p = binary_precedence(op);
    let (lp, rp) = (precedence(lhs), precedence(rhs));
    let (lparen, rparen) = match p {
        // Non-associative: both sides parenthesized at equal strength.
        5 | 8 => (lp <= p, rp <= p),
        _ => (lp < p, rp <= p),
    };
    write_paren(out, lhs, lparen);
    let _ = write!(out, " {} ", op.symbol());
    write_paren(out, rhs, rparen);
}

/// `(a, , b)`: a tuple, empty slots left empty.
fn write_tuple(out: &mut String, items: &[Option<Expr>]) {
    out.push('(');
    for (i, it) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        if let Some(e) = it {
            write_expr(out, e);
        }
    }
    out.push(')');
}

fn list(out: &mut String, items: &[Expr]) {
    for (i, e) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        write_expr(out, e);
    }
}

/// `(a, b = 1)` or `(x[i] for i in 1:n)`.
pub fn call_args(args: &CallArgs) -> String {
    let mut out = String::from("(");
    list(&mut out, &args.positional);
    if !args.iterators.is_empty() {
        out.push_str(" for ");
        out.push_str(&for_indices(&args.iterators));
    }
    for (i, a) in args.named.iter().enumerate() {
        if i > 0 || !args.positional.is_empty() {
            out.push_str(", ");
        }
        let _ = write!(out, "{} = {}", a.name.text, expr(&a.value));
    }
    out.push(')');
    out
}

pub fn for_indices(indices: &[ForIndex]) -> String {
    let mut out = String::new();
    for (i, idx) in indices.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&idx.name.text);
        if let Some(r) = &idx.range {
            out.push_str(" in ");
            write_expr(&mut out, r);
        }
    }
    out
}

pub fn subscripts(subs: &[Subscript]) -> String {
    if subs.is_empty() {
        return String::new();
    }
    let mut out = String::from("[");
    for (i, s) in subs.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        match s {
            Subscript::Colon(_) => out.push(':'),
            Subscript::Expr(e) => write_expr(&mut out, e),
        }
    }
    out.push(']');
    out
}

pub fn cref(r: &ComponentRef) -> String {
    let mut out = String::new();
    if r.global {
        out.push('.');
    }
    for (i, p) in r.parts.iter().enumerate() {
        if i > 0 {
            out.push('.');
        }
        out.push_str(&p.name.text);
        out.push_str(&subscripts(&p.subscripts));
    }
    out
}

/// `(a = 1, redeclare B b)`.
pub fn class_modification(m: &ClassModification) -> String {
    let mut out = String::from("(");
    for (i, a) in m.args.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&argument(a));
    }
    out.push(')');
    out
}

pub fn modification(m: &Modification) -> String {
    let mut out = String::new();
    if let Some(cm) = &m.class_mod {
        out.push_str(&class_modification(cm));
    }
    if let Some(b) = &m.binding {
        out.push_str(if m.assign { " := " } else { " = " });
        out.push_str(&expr(b));
    }
    out
}

fn argument(a: &Argument) -> String {
    let mut out = String::new();
    match a {
        Argument::Modify {
            each,
            is_final,
            name,
            modification: m,
            description,
            ..
        } => {
            if *each {
                out.push_str("each ");
            }
            if *is_final {
                out.push_str("final ");
            }
            out.push_str(&name.to_dotted());
            if let Some(m) = m {
                out.push_str(&modification(m));
            }
            if let Some(d) = description {
                out.push(' ');
                out.push_str(&string_lit(d));
            }
        }
        Argument::Redeclare {
            redeclare,
            each,
            is_final,
            replaceable,
            element,
            constrainedby,
            ..
        } => {
            for (flag, word) in [
                (*redeclare, "redeclare "),
                (*each, "each "),
                (*is_final, "final "),
                (*replaceable, "replaceable "),
            ] {
                if flag {
                    out.push_str(word);
                }
            }
            match element {
                RedeclaredElement::Component(cc) => out.push_str(&component_clause(cc)),
                RedeclaredElement::Class(cd) => out.push_str(&short_class(cd)),
            }
            if let Some(c) = constrainedby {
                out.push_str(" constrainedby ");
                out.push_str(&c.base.to_dotted());
                if let Some(m) = &c.modification {
                    out.push_str(&class_modification(m));
                }
            }
        }
    }
    out
}

pub fn type_prefix(p: &TypePrefix) -> String {
    let mut out = String::new();
    match p.connection {
        Some(Connection::Flow) => out.push_str("flow "),
        Some(Connection::Stream) => out.push_str("stream "),
        None => {}
    }
    match p.variability {
        Some(Variability::Discrete) => out.push_str("discrete "),
        Some(Variability::Parameter) => out.push_str("parameter "),
        Some(Variability::Constant) => out.push_str("constant "),
        None => {}
    }
    match p.causality {
        Some(Causality::Input) => out.push_str("input "),
        Some(Causality::Output) => out.push_str("output "),
        None => {}
    }
    out
}

/// `parameter Real[3] x(start = 1) = y "doc"`, without the `;`.
pub fn component_clause(cc: &ComponentClause) -> String {
    let mut out = type_prefix(&cc.prefix);
    out.push_str(&cc.type_name.to_dotted());
    out.push_str(&subscripts(&cc.type_dims));
    for (i, d) in cc.components.iter().enumerate() {
        out.push_str(if i == 0 { " " } else { ", " });
        out.push_str(&d.name.text);
        out.push_str(&subscripts(&d.dims));
        if let Some(m) = &d.modification {
            out.push_str(&modification(m));
        }
        if let Some(c) = &d.condition {
            out.push_str(" if ");
            out.push_str(&expr(c));
        }
        out.push_str(&comment(&d.comment));
    }
    out
}

/// ` "doc" annotation(...)` (with a leading space), or nothing.
pub fn comment(c: &Comment) -> String {
    let mut out = String::new();
    if let Some(d) = &c.description {
        out.push(' ');
        out.push_str(&string_lit(d));
    }
    if let Some(a) = &c.annotation {
        out.push_str(" annotation");
        out.push_str(&class_modification(a));
    }
    out
}

/// A function's external clause, with its `;`.
pub fn external_clause(ext: &External) -> String {
    let mut out = String::from("external");
    if let Some(lang) = &ext.language {
        out.push(' ');
        out.push_str(&string_lit(lang));
    }
    if let Some(call) = &ext.call {
        out.push(' ');
        if let Some(target) = &call.output {
            out.push_str(&cref(target));
            out.push_str(" = ");
        }
        out.push_str(&call.function.text);
        out.push('(');
        for (i, a) in call.args.iter().enumerate() {
            if i > 0 {
                out.push_str(", ");
            }
            out.push_str(&expr(a));
        }
        out.push(')');
    }
    if let Some(a) = &ext.annotation {
        out.push_str(" annotation");
        out.push_str(&class_modification(a));
    }
    out.push(';');
    out
}

/// A short class, enumeration or derivative definition, without the `;`.
pub fn short_class(cd: &ClassDef) -> String {
    let mut out = String::new();
    if cd.partial {
        out.push_str("partial ");
    }
    out.push_str(&cd.prefixes.keywords());
    let _ = write!(out, "{} {} = ", cd.kind.keyword(), cd.name.text);
    match &cd.body {
        ClassBody::Der {
            base,
            with_respect_to,
            comment: c,
        } => {
            out.push_str("der(");
            out.push_str(&base.to_dotted());
            for v in with_respect_to {
                out.push_str(", ");
                out.push_str(&v.text);
            }
            out.push(')');
            out.push_str(&comment(c));
        }
        ClassBody::Short {
            causality,
            base,
            dims,
            modification,
            comment: c,
        } => {
            match causality {
                Some(Causality::Input) => out.push_str("input "),
                Some(Causality::Output) => out.push_str("output "),
                None => {}
            }
            out.push_str(&base.to_dotted());
            out.push_str(&subscripts(dims));
            if let Some(m) = modification {
                out.push_str(&class_modification(m));
            }
            out.push_str(&comment(c));
        }
        ClassBody::Enumeration {
            literals,
            open,
            comment: c,
        } => {
            out.push_str("enumeration(");
            if *open {
                out.push(':');
            }
            for (i, l) in literals.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                out.push_str(&l.name.text);
                out.push_str(&comment(&l.comment));
            }
            out.push(')');
            out.push_str(&comment(c));
        }
        ClassBody::Long { .. } => out.push_str("..."),
    }
    out
}
