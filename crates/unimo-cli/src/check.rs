//! `unimo check` and `unimo emit --stage ast`: read files, parse, report.

use crate::render::emit_stderr;
use crate::{EXIT_MODEL_ERROR, EXIT_OK, EXIT_USAGE};
use std::path::{Path, PathBuf};
use std::time::Instant;
use unimo_source::{Diagnostic, SourceMap};
use unimo_syntax::ast::{ClassBody, ElementKind, StoredDefinition};

/// Collects `*.mo` files below each path (files are taken as given), sorted per folder.
fn collect(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out).map_err(|e| format!("cannot read folder `{}`: {e}", p.display()))?;
        } else if p.is_file() {
            out.push(p.clone());
        } else {
            return Err(format!("no such file or folder: `{}`", p.display()));
        }
    }
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            walk(&e, out)?;
        } else if e.extension().is_some_and(|x| x == "mo") {
            out.push(e);
        }
    }
    Ok(())
}

fn count_classes(def: &StoredDefinition) -> usize {
    fn rec(c: &unimo_syntax::ast::ClassDef) -> usize {
        1 + match &c.body {
            ClassBody::Long { composition, .. } => composition
                .elements
                .iter()
                .map(|e| match &e.kind {
                    ElementKind::Class(c) => rec(c),
                    _ => 0,
                })
                .sum(),
            _ => 0,
        }
    }
    def.classes.iter().map(rec).sum()
}

pub fn check(paths: &[PathBuf], stats: bool, color: bool) -> i32 {
    let started = Instant::now();
    let files = match collect(paths) {
        Ok(f) => f,
        Err(msg) => {
            eprintln!("error: {msg}");
            return EXIT_USAGE;
        }
    };
    let mut map = SourceMap::new();
    let mut n_errors = 0;
    let mut n_warnings = 0;
    let mut n_classes = 0;
    let mut bytes = 0;
    for path in &files {
        let text = match std::fs::read(path) {
            Ok(b) => match String::from_utf8(b) {
                Ok(t) => t,
                Err(_) => {
                    eprintln!("error[E0002]: `{}` is not UTF-8 text", path.display());
                    n_errors += 1;
                    continue;
                }
            },
            Err(e) => {
                eprintln!("error[E0001]: cannot read `{}`: {e}", path.display());
                n_errors += 1;
                continue;
            }
        };
        bytes += text.len();
        let id = map.add(path.clone(), text);
        let parsed = unimo_syntax::parse(id, map.get(id).text());
        n_classes += count_classes(&parsed.ast);
        report(
            &parsed.diagnostics,
            &map,
            color,
            &mut n_errors,
            &mut n_warnings,
        );
    }
    let elapsed = started.elapsed();
    if stats {
        eprintln!(
            "stats: files={} classes={} bytes={} time_ms={:.1}",
            files.len(),
            n_classes,
            bytes,
            elapsed.as_secs_f64() * 1e3
        );
    }
    let plural = |n: usize, w: &str| format!("{n} {w}{}", if n == 1 { "" } else { "s" });
    if n_errors > 0 {
        eprintln!(
            "checked {}: {}, {}",
            plural(files.len(), "file"),
            plural(n_errors, "error"),
            plural(n_warnings, "warning")
        );
        EXIT_MODEL_ERROR
    } else {
        eprintln!(
            "checked {}: no errors{}",
            plural(files.len(), "file"),
            if n_warnings > 0 {
                format!(", {}", plural(n_warnings, "warning"))
            } else {
                String::new()
            }
        );
        EXIT_OK
    }
}

fn report(
    diags: &[Diagnostic],
    map: &SourceMap,
    color: bool,
    errors: &mut usize,
    warnings: &mut usize,
) {
    emit_stderr(diags, map, color);
    for d in diags {
        if d.is_error() {
            *errors += 1;
        } else if d.severity == unimo_source::Severity::Warning {
            *warnings += 1;
        }
    }
}

pub fn emit_ast(file: &Path, color: bool) -> i32 {
    let text = match std::fs::read_to_string(file) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: cannot read `{}`: {e}", file.display());
            return EXIT_USAGE;
        }
    };
    let mut map = SourceMap::new();
    let id = map.add(file.to_path_buf(), text);
    let parsed = unimo_syntax::parse(id, map.get(id).text());
    print!("{}", unimo_syntax::dump::dump(&parsed.ast, map.get(id)));
    let (mut e, mut w) = (0, 0);
    report(&parsed.diagnostics, &map, color, &mut e, &mut w);
    if e > 0 {
        EXIT_MODEL_ERROR
    } else {
        EXIT_OK
    }
}
