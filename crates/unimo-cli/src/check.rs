//! `unimo check` and `unimo emit --stage ast`: read files, parse, report.

use crate::error::CliError;
use crate::provider::CliProvider;
use crate::render::emit_stderr;
use crate::{EXIT_MODEL_ERROR, EXIT_OK, EXIT_USAGE};
use std::path::{Path, PathBuf};
use std::time::Instant;
use unimo_flat::ClassTree;
use unimo_source::{Diagnostic, SourceMap};
use unimo_syntax::ast::{ClassBody, ElementKind, StoredDefinition};

/// The library class a file below one of the `--lib` folders defines
/// (`Lib/A/package.mo` is `A`'s package, `Lib/A/B.mo` is `A.B`), when the library
/// loads it.
fn library_class(
    tree: &mut ClassTree<'_>,
    libs: &[PathBuf],
    path: &Path,
) -> Option<unimo_flat::ClassId> {
    let canonical = path.canonicalize().ok()?;
    let rel = libs.iter().find_map(|root| {
        let root = root.canonicalize().ok()?;
        canonical.strip_prefix(root).ok().map(Path::to_path_buf)
    })?;
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .collect();
    let last = parts.pop()?;
    if last != "package.mo" {
        parts.push(last.strip_suffix(".mo")?.to_owned());
    }
    if parts.is_empty() {
        return None;
    }
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    tree.lookup_global(&refs)
}

/// Collects `*.mo` files below each path (files are taken as given), sorted per folder.
fn collect(paths: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out).map_err(|e| CliError::UnreadableFolder {
                path: p.clone(),
                reason: e.to_string(),
            })?;
        } else if p.is_file() {
            out.push(p.clone());
        } else {
            return Err(CliError::NoSuchPath { path: p.clone() });
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

/// What reading and parsing the files of `check` gave.
#[derive(Default)]
struct Parsed {
    diags: Vec<Diagnostic>,
    n_classes: usize,
    bytes: usize,
    read_errors: usize,
    /// The files that parse, with their syntax trees.
    files: Vec<(unimo_source::FileId, StoredDefinition, PathBuf)>,
}

/// The text of a file for `check`; None (after the error) when it cannot be read.
fn read_text(path: &Path) -> Option<String> {
    let text = std::fs::read(path)
        .map_err(|e| CliError::Unreadable {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })
        .and_then(|b| {
            String::from_utf8(b).map_err(|_| CliError::NotUtf8 {
                path: path.to_path_buf(),
            })
        });
    match text {
        Ok(t) => Some(t),
        Err(e) => {
            e.report();
            None
        }
    }
}

/// Reads and parses every file into the tree's sources.
fn parse_files(tree: &mut ClassTree<'_>, files: &[PathBuf]) -> Parsed {
    let mut out = Parsed::default();
    for path in files {
        let Some(text) = read_text(path) else {
            out.read_errors += 1;
            continue;
        };
        out.bytes += text.len();
        let id = tree.sources.add(path.clone(), text);
        let parsed = unimo_syntax::parse(id, tree.sources.get(id).text());
        out.n_classes += count_classes(&parsed.ast);
        let clean = !parsed.has_errors();
        out.diags.extend(parsed.diagnostics);
        // Names are checked only in files that parse: a broken file would only add
        // follow-on errors.
        if clean {
            out.files.push((id, parsed.ast, path.clone()));
        }
    }
    out
}

/// Adds the parsed files to the tree; returns their classes.
fn add_files(
    tree: &mut ClassTree<'_>,
    libs: &[PathBuf],
    mut parsed_files: Vec<(unimo_source::FileId, StoredDefinition, PathBuf)>,
) -> Vec<unimo_flat::ClassId> {
    let mut user_classes = Vec::new();
    // Enclosing packages before their members: a file `within A.B;` needs `A.B`.
    parsed_files.sort_by_key(|(_, ast, _)| match &ast.within {
        Some(Some(n)) => n.parts.len(),
        _ => 0,
    });
    for (id, ast, path) in parsed_files {
        // A file of a library given with --lib is checked as that library's class, so
        // that it sees its package's other files (a `package.mo` its siblings).
        if let Some(c) = library_class(tree, libs, &path) {
            user_classes.push(c);
            continue;
        }
        user_classes.extend(tree.add_user_file(id, ast));
    }
    user_classes
}

/// The analysis statistics of one model: its name, the counts and the time taken.
type ModelStats = (String, unimo_dae::plan::PlanStats, std::time::Duration);

/// Flattens every top model of `user_classes` and checks its balance (and, with
/// `analysis`, analyses it), adding the diagnostics to `diags`. Returns the number of
/// models flattened.
fn check_models(
    tree: &mut ClassTree<'_>,
    user_classes: &[unimo_flat::ClassId],
    (stats, analysis): (bool, bool),
    diags: &mut Vec<Diagnostic>,
    model_stats: &mut Vec<ModelStats>,
) -> usize {
    let mut flattened = 0;
    // Every top model of a file that holds models (not a package): flatten it and
    // check its balance.
    for c in top_models(tree, user_classes) {
        let (flat, mut fd) = unimo_flat::flatten(tree, c);
        // `check` already ran the name check on every class.
        fd.retain(|d| d.code.0 != "E2001");
        if !fd.iter().any(|d| d.is_error()) {
            let span = tree.get(c).def.name.span;
            fd.extend(unimo_flat::balance::check(&flat, span));
        }
        if analysis && !fd.iter().any(|d| d.is_error()) {
            let t0 = Instant::now();
            match unimo_dae::analyze_model(&flat) {
                Ok((dae, analysis)) => {
                    if stats {
                        let mut plan = analysis.plan.clone();
                        unimo_dae::prune::prune(&dae, &mut plan, &[]);
                        model_stats.push((flat.name.clone(), plan.stats, t0.elapsed()));
                    }
                }
                Err(d) => fd.extend(d),
            }
        }
        diags.extend(fd);
        flattened += 1;
    }
    flattened
}

pub fn check(
    paths: &[PathBuf],
    libs: &[PathBuf],
    stats: bool,
    balance: bool,
    analysis: bool,
    color: bool,
) -> i32 {
    let started = Instant::now();
    let files = match collect(paths) {
        Ok(f) => f,
        Err(e) => return e.report(),
    };
    let provider = CliProvider::new(libs);
    let mut tree = ClassTree::new(&provider);
    let parsed = parse_files(&mut tree, &files);
    let mut diags = parsed.diags;
    let user_classes = add_files(&mut tree, libs, parsed.files);
    let mut flattened = 0;
    let mut model_stats = Vec::new();
    for c in &user_classes {
        diags.extend(unimo_flat::resolve::check_names(&mut tree, *c));
    }
    if balance && !diags.iter().any(|d| d.is_error()) {
        flattened = check_models(
            &mut tree,
            &user_classes,
            (stats, analysis),
            &mut diags,
            &mut model_stats,
        );
    }
    diags.append(&mut tree.diagnostics);
    let (mut n_errors, mut n_warnings) = (parsed.read_errors, 0);
    report(&diags, &tree.sources, color, &mut n_errors, &mut n_warnings);
    let elapsed = started.elapsed();
    if stats {
        let s = tree.stats;
        eprintln!(
            "stats: files={} classes={} bytes={} models_flattened={} library_files_loaded={} library_bytes_loaded={} classes_in_tree={} time_ms={:.1}",
            files.len(),
            parsed.n_classes,
            parsed.bytes,
            flattened,
            s.library_files,
            s.library_bytes,
            s.classes,
            elapsed.as_secs_f64() * 1e3
        );
    }
    print_model_stats(&model_stats);
    summary(files.len(), n_errors, n_warnings)
}

/// The `--stats` line of each analysed model.
fn print_model_stats(model_stats: &[ModelStats]) {
    for (name, p, time) in model_stats {
        eprintln!(
            "stats: model={name} flat_scalars={} aliases_removed={} constants_removed={} equations={} differentiated={} states={} dummy_derivatives={} state_sets={} algebraic={} blocks={} torn_blocks={} largest_block={} zero_crossings={} pruned={} analysis_ms={:.2}",
            p.flat_scalars,
            p.aliases_removed,
            p.constants_removed,
            p.equations,
            p.differentiated_equations,
            p.states,
            p.dummy_derivatives,
            p.state_sets,
            p.algebraic,
            p.blocks,
            p.torn_blocks,
            p.largest_block,
            p.zero_crossings,
            p.pruned_equations,
            time.as_secs_f64() * 1e3
        );
    }
}

/// The closing line of `check`; returns the exit code.
fn summary(n_files: usize, n_errors: usize, n_warnings: usize) -> i32 {
    let plural = |n: usize, w: &str| format!("{n} {w}{}", if n == 1 { "" } else { "s" });
    if n_errors > 0 {
        eprintln!(
            "checked {}: {}, {}",
            plural(n_files, "file"),
            plural(n_errors, "error"),
            plural(n_warnings, "warning")
        );
        EXIT_MODEL_ERROR
    } else {
        eprintln!(
            "checked {}: no errors{}",
            plural(n_files, "file"),
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
    let text = match read(file) {
        Ok(t) => t,
        Err(e) => return e.report(),
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

/// The models `check` flattens: in files without a `within` clause, the non-partial
/// models and blocks at the top level that no other class of the same file uses.
fn top_models(tree: &ClassTree<'_>, classes: &[unimo_flat::ClassId]) -> Vec<unimo_flat::ClassId> {
    use unimo_syntax::ast::ClassKind;
    let mut out = Vec::new();
    for &c in classes {
        let entry = tree.get(c);
        let d = &entry.def;
        if entry.parent.is_some()
            || d.partial
            || !matches!(d.kind, ClassKind::Model | ClassKind::Block)
        {
            continue;
        }
        let used = classes
            .iter()
            .filter(|&&o| o != c && tree.get(o).file == entry.file)
            .any(|&o| uses_of(&tree.get(o).def).iter().any(|u| *u == entry.name));
        if !used {
            out.push(c);
        }
    }
    out
}

/// Last parts of the type names a class uses for its components and bases.
fn uses_of(def: &unimo_syntax::ast::ClassDef) -> Vec<String> {
    use unimo_syntax::ast::{ClassBody, ElementKind};
    let composition = match &def.body {
        ClassBody::Long { composition, .. } => composition,
        // `model B = A(...)` uses `A`; `type D = der(f, x)` uses `f`.
        ClassBody::Short { base, .. } | ClassBody::Der { base, .. } => {
            return base
                .parts
                .last()
                .map(|p| p.text.to_string())
                .into_iter()
                .collect()
        }
        ClassBody::Enumeration { .. } => return Vec::new(),
    };
    composition
        .elements
        .iter()
        .filter_map(|e| match &e.kind {
            ElementKind::Component(cc) => cc.type_name.parts.last().map(|p| p.text.to_string()),
            ElementKind::Extends(x) => x.base.parts.last().map(|p| p.text.to_string()),
            _ => None,
        })
        .collect()
}

/// Picks the model to flatten: `--model`, or the one non-partial model of the file.
/// Picks the model to compile (see [`pick_model`]).
pub fn pick(
    tree: &mut ClassTree<'_>,
    classes: &[unimo_flat::ClassId],
    wanted: Option<&str>,
) -> Result<unimo_flat::ClassId, CliError> {
    pick_model(tree, classes, wanted)
}

/// The text of a file given on the command line (`E0001` when it cannot be read).
pub fn read(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|e| CliError::Unreadable {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

fn pick_model(
    tree: &mut ClassTree<'_>,
    classes: &[unimo_flat::ClassId],
    wanted: Option<&str>,
) -> Result<unimo_flat::ClassId, CliError> {
    use unimo_syntax::ast::ClassKind;
    if let Some(w) = wanted {
        for &c in classes {
            if tree.full_name(c) == w || tree.get(c).name == w {
                return Ok(c);
            }
        }
        let parts: Vec<&str> = w.split('.').collect();
        return tree
            .lookup_global(&parts)
            .ok_or_else(|| CliError::NoSuchClass { name: w.to_owned() });
    }
    let candidates: Vec<_> = classes
        .iter()
        .copied()
        .filter(|&c| {
            let d = &tree.get(c).def;
            !d.partial
                && matches!(
                    d.kind,
                    ClassKind::Model | ClassKind::Block | ClassKind::Class
                )
        })
        .collect();
    // Several models: the top one is the model no other model of the file uses as a
    // component type or base class.
    let used: Vec<String> = candidates
        .iter()
        .flat_map(|&c| uses_of(&tree.get(c).def))
        .collect();
    let tops: Vec<_> = candidates
        .iter()
        .copied()
        .filter(|&c| !used.iter().any(|u| *u == tree.get(c).name))
        .collect();
    if let [one] = tops.as_slice() {
        return Ok(*one);
    }
    match candidates.as_slice() {
        [one] => Ok(*one),
        [] => {
            // One partial model and nothing else: take it, so that instantiation can
            // say why it cannot be simulated.
            let partial: Vec<_> = classes
                .iter()
                .copied()
                .filter(|&c| {
                    matches!(
                        tree.get(c).def.kind,
                        ClassKind::Model | ClassKind::Block | ClassKind::Class
                    )
                })
                .collect();
            match partial.as_slice() {
                [one] => Ok(*one),
                _ => Err(CliError::NoModel {}),
            }
        }
        many => Err(CliError::SeveralModels {
            names: many.iter().map(|c| tree.full_name(*c)).collect(),
        }),
    }
}

/// Parses `files`, picks the model, flattens it and checks its balance, rendering the
/// diagnostics; then hands the flat model to `then`. Returns the exit code.
pub fn with_flat_model(
    files: &[PathBuf],
    model: Option<&str>,
    libs: &[PathBuf],
    color: bool,
    print_unbalanced: bool,
    then: &mut dyn FnMut(&unimo_flat::FlatModel, &SourceMap, bool) -> i32,
) -> i32 {
    let none = ParameterOverrides::default();
    with_flat_model_overridden(files, model, libs, color, print_unbalanced, &none, then)
}

/// Parameter overrides from the command line: `-p NAME=VALUE` flags and a file.
#[derive(Default)]
pub struct ParameterOverrides<'a> {
    pub flags: &'a [String],
    pub file: Option<&'a std::path::Path>,
}

thread_local! {
    /// Seconds spent parsing the files given on the command line (`--stats`).
    static PARSE_SECONDS: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

/// Seconds this thread has spent parsing command-line files in
/// [`with_flat_model_overridden`] (library files are parsed as flattening reads them).
pub fn parse_seconds() -> f64 {
    PARSE_SECONDS.with(std::cell::Cell::get)
}

/// Like [`with_flat_model`], with parameter overrides: they are checked against the
/// model (coded `E00xx` errors, exit code 2) and the model flattened again with them
/// as top-level modifiers.
pub fn with_flat_model_overridden(
    files: &[PathBuf],
    model: Option<&str>,
    libs: &[PathBuf],
    color: bool,
    print_unbalanced: bool,
    overrides: &ParameterOverrides<'_>,
    then: &mut dyn FnMut(&unimo_flat::FlatModel, &SourceMap, bool) -> i32,
) -> i32 {
    let provider = CliProvider::new(libs);
    let mut tree = ClassTree::new(&provider);
    let mut first_classes = None;
    for file in files {
        let text = match read(file) {
            Ok(t) => t,
            Err(e) => return e.report(),
        };
        let id = tree.sources.add(file.to_path_buf(), text);
        let started = Instant::now();
        let parsed = unimo_syntax::parse(id, tree.sources.get(id).text());
        PARSE_SECONDS.with(|c| c.set(c.get() + started.elapsed().as_secs_f64()));
        if parsed.has_errors() {
            let (mut e, mut w) = (0, 0);
            report(&parsed.diagnostics, &tree.sources, color, &mut e, &mut w);
            return EXIT_MODEL_ERROR;
        }
        let classes = tree.add_user_file(id, parsed.ast);
        first_classes.get_or_insert(classes);
    }
    let classes = first_classes.unwrap_or_default();
    let class = match pick_model(&mut tree, &classes, model) {
        Ok(c) => c,
        Err(e) => return e.report(),
    };
    let (mut flat, mut diags) = unimo_flat::flatten(&mut tree, class);
    let overridden = !overrides.flags.is_empty() || overrides.file.is_some();
    if overridden && !diags.iter().any(|d| d.is_error()) {
        let (o, file) = (overrides.flags, overrides.file);
        match crate::params::overrides(o, file, &flat, &mut tree.sources) {
            Ok(modifiers) => (flat, diags) = unimo_flat::flatten_with(&mut tree, class, &modifiers),
            Err(refused) => {
                let (mut e, mut w) = (0, 0);
                report(&refused, &tree.sources, color, &mut e, &mut w);
                return EXIT_USAGE;
            }
        }
    }
    let has_errors = diags.iter().any(|d| d.is_error());
    let mut unbalanced = false;
    if !has_errors {
        let span = tree.get(class).def.name.span;
        if let Some(d) = unimo_flat::balance::check(&flat, span) {
            diags.push(d);
            unbalanced = true;
        }
    }
    diags.append(&mut tree.diagnostics);
    let (mut e, mut w) = (0, 0);
    report(&diags, &tree.sources, color, &mut e, &mut w);
    if e > 0 && !(unbalanced && print_unbalanced) {
        return EXIT_MODEL_ERROR;
    }
    let code = then(&flat, &tree.sources, e > 0);
    if e > 0 {
        EXIT_MODEL_ERROR
    } else {
        code
    }
}

/// Renders diagnostics of a later stage; true when there were errors.
pub fn render_stage(diags: &[Diagnostic], map: &SourceMap, color: bool) -> bool {
    let (mut e, mut w) = (0, 0);
    report(diags, map, color, &mut e, &mut w);
    e > 0
}

pub fn flatten(
    files: &[PathBuf],
    model: Option<&str>,
    libs: &[PathBuf],
    stats: bool,
    color: bool,
) -> i32 {
    let started = Instant::now();
    // An unbalanced model is still printed: reading it is how one finds the surplus or
    // missing equation. The exit code says it is not usable.
    with_flat_model(files, model, libs, color, true, &mut |flat, _, _| {
        print!("{}", flat.to_modelica());
        if stats {
            let b = unimo_flat::balance::count(flat);
            eprintln!(
                "stats: variables={} scalars={} equations={} unknowns={} time_ms={:.1}",
                flat.vars.len(),
                flat.vars.iter().map(|v| v.size()).sum::<usize>(),
                b.equations,
                b.unknowns,
                started.elapsed().as_secs_f64() * 1e3
            );
        }
        EXIT_OK
    })
}
