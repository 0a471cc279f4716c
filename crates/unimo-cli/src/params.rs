//! Parameter overrides (`simulate -p NAME=VALUE`, `--override-file`) and the parameter
//! list (`--list-params`): each override is checked against the flat model (a known,
//! non-final parameter; a value of its type) and becomes a top-level modifier for
//! flattening again. Problems are coded `E00xx` diagnostics pointing into the command
//! line or the override file.

use crate::error::{CliError, Unsettable};
use std::path::{Path, PathBuf};
use unimo_flat::flat::{FlatModel, FlatType, FlatVar, Variability};
use unimo_source::{Diagnostic, FileId, SourceMap, Span};
use unimo_syntax::ast::{ComponentRef, Expr, ExprKind, Ident, RefPart};

/// One `name=value` as written, with the spans of its two sides.
struct Written {
    name: String,
    name_span: Span,
    value: String,
    value_span: Span,
}

/// Splits `text` (one override a line, `#` comments) of `file` into overrides.
fn split_lines(file: FileId, text: &str, diags: &mut Vec<Diagnostic>) -> Vec<Written> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let content = line.split('#').next().unwrap_or("").trim_end();
        let lead = content.len() - content.trim_start().len();
        let content = content.trim_start();
        if content.is_empty() {
            continue;
        }
        let at = |a: usize, b: usize| Span::new(file, start + lead + a, start + lead + b);
        let Some(eq) = content.find('=') else {
            let text = content.to_owned();
            diags.push(
                CliError::NotNameValue {
                    text,
                    span: at(0, content.len()),
                }
                .into(),
            );
            continue;
        };
        let (name, value) = (&content[..eq], &content[eq + 1..]);
        let name_trim = name.trim_end();
        let value_lead = value.len() - value.trim_start().len();
        out.push(Written {
            name: name_trim.to_owned(),
            name_span: at(0, name_trim.len()),
            value: value.trim().to_owned(),
            value_span: at(
                eq + 1 + value_lead,
                eq + 1 + value_lead + value.trim().len(),
            ),
        });
        if name_trim.is_empty() {
            diags.push(
                CliError::NoOverrideName {
                    span: at(0, eq + 1),
                }
                .into(),
            );
            out.pop();
        }
    }
    out
}

/// Reads the overrides: the `-p` flags (a source named `<command line>`, one a line)
/// and the `--override-file`, which may repeat (the flags win: they come last).
fn written(
    flags: &[String],
    file: Option<&Path>,
    map: &mut SourceMap,
    diags: &mut Vec<Diagnostic>,
) -> Result<Vec<Written>, Diagnostic> {
    let mut out = Vec::new();
    if let Some(path) = file {
        let text = crate::check::read(path).map_err(Diagnostic::from)?;
        let id = map.add(path.to_path_buf(), text.clone());
        out.extend(split_lines(id, &text, diags));
    }
    if !flags.is_empty() {
        let text: String = flags.iter().map(|f| format!("{f}\n")).collect();
        let id = map.add(PathBuf::from("<command line>"), text.clone());
        out.extend(split_lines(id, &text, diags));
    }
    Ok(out)
}

/// The parameter closest to `name` (for "did you mean").
fn closest(name: &str, flat: &FlatModel) -> Option<String> {
    let names = flat
        .vars
        .iter()
        .filter(|v| v.variability == Variability::Parameter)
        .map(|v| v.name.clone())
        .collect();
    unimo_flat::resolve::suggest(name, names)
}

fn literal(kind: ExprKind, span: Span) -> Expr {
    Expr { kind, span }
}

/// The value as an expression of the parameter's type, or the reason it is not one.
fn typed_value(var: &FlatVar, text: &str, span: Span) -> Result<Expr, String> {
    match &var.ty {
        FlatType::Real => match text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(literal(ExprKind::Real(x), span)),
            _ => Err(format!(
                "`{}` is a Real: `{text}` is not a finite number",
                var.name
            )),
        },
        FlatType::Integer => match text.parse::<i64>() {
            Ok(n) => Ok(literal(ExprKind::Integer(n), span)),
            _ => Err(format!(
                "`{}` is an Integer: `{text}` is not an integer",
                var.name
            )),
        },
        FlatType::Boolean => match text {
            "true" => Ok(literal(ExprKind::Bool(true), span)),
            "false" => Ok(literal(ExprKind::Bool(false), span)),
            _ => Err(format!(
                "`{}` is a Boolean: write `true` or `false`, not `{text}`",
                var.name
            )),
        },
        FlatType::String => Ok(literal(
            ExprKind::String(text.trim_matches('"').to_owned()),
            span,
        )),
        FlatType::Enumeration { name, literals } => {
            let last = text.rsplit('.').next().unwrap_or(text);
            if !literals.iter().any(|l| l == last) {
                return Err(format!(
                    "`{}` is of type {name}: `{text}` is not one of {}",
                    var.name,
                    literals.join(", ")
                ));
            }
            let parts = name
                .split('.')
                .chain(std::iter::once(last))
                .map(|p| RefPart {
                    name: Ident {
                        text: p.into(),
                        span,
                    },
                    subscripts: Vec::new(),
                })
                .collect();
            let r = ComponentRef {
                global: true,
                parts,
                span,
            };
            Ok(literal(ExprKind::Ref(r), span))
        }
        FlatType::ExternalObject { .. } => Err(format!("`{}` is an external object", var.name)),
    }
}

/// The value of a parameter with these dimensions (none: a scalar): an array is written
/// whole, as nested braces (`{1, 2, 3}`, `{{1, 0}, {0, 1}}`), each element a value of
/// the element type.
fn array_value(var: &FlatVar, dims: &[usize], text: &str, span: Span) -> Result<Expr, String> {
    let Some((&n, inner)) = dims.split_first() else {
        return typed_value(var, text, span);
    };
    let shape = || {
        let d: Vec<String> = var.dims.iter().map(usize::to_string).collect();
        format!(
            "`{}` is an array of size [{}]: write all its elements in braces, e.g. `{}={{...}}`",
            var.name,
            d.join(", "),
            var.name
        )
    };
    let body = text
        .trim()
        .strip_prefix('{')
        .and_then(|t| t.strip_suffix('}'))
        .ok_or_else(shape)?;
    let items = split_top_level(body);
    if items.len() != n || items.iter().any(|i| i.trim().is_empty()) {
        return Err(format!(
            "{}: `{text}` has {} here, not {n}",
            shape(),
            match items.len() {
                1 => "1 element".to_owned(),
                k => format!("{k} elements"),
            }
        ));
    }
    let elements = items
        .iter()
        .map(|item| array_value(var, inner, item.trim(), span))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(literal(ExprKind::Array(elements), span))
}

/// `a, {b, c}, d` split at the commas outside braces.
fn split_top_level(text: &str) -> Vec<&str> {
    let (mut depth, mut start, mut out) = (0i32, 0, Vec::new());
    for (k, c) in text.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&text[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    out.push(&text[start..]);
    out
}

/// Checks one override against the flat model.
fn check(w: &Written, flat: &FlatModel) -> Result<(String, Expr), Diagnostic> {
    let Some(var) = flat.vars.iter().find(|v| v.name == w.name) else {
        return Err(CliError::UnknownParameter {
            name: w.name.clone(),
            model: flat.name.clone(),
            suggestion: closest(&w.name, flat),
            span: w.name_span,
        }
        .into());
    };
    let why = match var.variability {
        Variability::Parameter if var.is_final => Some(Unsettable::Final),
        Variability::Parameter => None,
        Variability::Constant => Some(Unsettable::Constant),
        _ => Some(Unsettable::Variable),
    };
    if let Some(why) = why {
        return Err(CliError::NotSettable {
            name: w.name.clone(),
            why,
            span: w.name_span,
            declared: var.origin,
        }
        .into());
    }
    let value = array_value(var, &var.dims, &w.value, w.value_span).map_err(|why| {
        CliError::OverrideValue {
            why,
            span: w.value_span,
            declared: var.origin,
        }
    })?;
    Ok((w.name.clone(), value))
}

/// The overrides as modifiers, or the diagnostics that refuse them (`E0001` when the
/// override file cannot be read).
pub fn overrides(
    flags: &[String],
    file: Option<&Path>,
    flat: &FlatModel,
    map: &mut SourceMap,
) -> Result<Vec<(String, Expr)>, Vec<Diagnostic>> {
    let mut diags = Vec::new();
    let list = written(flags, file, map, &mut diags).map_err(|d| vec![d])?;
    let mut out = Vec::new();
    for w in &list {
        match check(w, flat) {
            Ok(m) => out.push(m),
            Err(d) => diags.push(d),
        }
    }
    if diags.is_empty() {
        Ok(out)
    } else {
        Err(diags)
    }
}

/// Whether changing the parameter needs the model flattened again, and why.
pub fn structural_reason(var: &FlatVar, flat: &FlatModel) -> Option<&'static str> {
    if var.is_final {
        Some("final")
    } else if var.evaluate {
        Some("Evaluate=true")
    } else if flat.evaluated.binary_search(&var.name).is_ok() {
        Some("structural")
    } else {
        None
    }
}

/// The `--list-params` table: name, type, value (the binding as written, after the
/// overrides), unit, whether it can change without recompiling, description.
/// `folded`: the names of the parameters compiled as constants (`--tunable` keeps
/// others).
pub fn list(flat: &FlatModel, folded: &std::collections::HashSet<String>) -> String {
    let mut rows = vec![[
        "name".to_owned(),
        "type".to_owned(),
        "value".to_owned(),
        "unit".to_owned(),
        "change without recompiling".to_owned(),
        "description".to_owned(),
    ]];
    for v in flat
        .vars
        .iter()
        .filter(|v| v.variability == Variability::Parameter)
    {
        let attribute = |n: &str| v.attributes.iter().find(|(a, _)| a == n).map(|(_, e)| e);
        let value = v
            .binding
            .as_deref()
            .or_else(|| attribute("start"))
            .map_or("(none)".to_owned(), unimo_syntax::print::expr);
        let unit = match attribute("unit").map(|e| &e.kind) {
            Some(ExprKind::String(u)) => u.clone(),
            _ => String::new(),
        };
        let ty = match &v.ty {
            FlatType::Enumeration { name, .. } => name.clone(),
            t => format!("{t:?}"),
        };
        let ty = if v.dims.is_empty() {
            ty
        } else {
            format!("{ty}{:?}", v.dims)
        };
        let is_folded = || {
            let bare = v.name.trim_matches('\'');
            folded.contains(bare)
                || folded
                    .iter()
                    .any(|f| f.strip_prefix(bare).is_some_and(|r| r.starts_with('[')))
        };
        let changeable = match structural_reason(v, flat) {
            Some(why) => format!("no ({why})"),
            None if is_folded() => "no (folded: --tunable keeps it)".to_owned(),
            None => "yes".to_owned(),
        };
        let description = v.description.clone().unwrap_or_default();
        rows.push([v.name.clone(), ty, value, unit, changeable, description]);
    }
    let widths: Vec<usize> = (0..6)
        .map(|k| rows.iter().map(|r| r[k].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for r in &rows {
        let cells: Vec<String> = (0..6)
            .map(|k| format!("{:w$}", r[k], w = widths[k]))
            .collect();
        out.push_str(cells.join("  ").trim_end());
        out.push('\n');
    }
    out
}
