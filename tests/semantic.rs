//! Semantic checks of the specification (issue #16): every file of `tests/semantic/err`
//! makes `unimo check` exit 1 with exactly the diagnostics its first line lists
//! (`// expect: CODE @line:col, ...`), rendered diagnostics snapshot-tested; every file
//! of `tests/semantic/ok` (legal models at the edge of each rule) checks cleanly.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn check(path: &Path) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["check", "--color", "never"])
        .arg(path)
        .current_dir(common::root())
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn files(dir: &str) -> Vec<PathBuf> {
    let relative = |p: PathBuf| p.strip_prefix(common::root()).unwrap().to_path_buf();
    common::mo_files(dir).into_iter().map(relative).collect()
}

/// The `CODE @line:col` list of a file's first line, sorted.
/// `unimo flatten` of one file.
fn flatten(path: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["flatten", "--color", "never"])
        .arg(path)
        .current_dir(common::root())
        .output()
        .unwrap()
}

fn expected(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(common::root().join(path)).unwrap();
    let first = text.lines().next().unwrap_or_default();
    let list = first
        .strip_prefix("// expect: ")
        .unwrap_or_else(|| panic!("{}: no `// expect:` line", path.display()));
    let mut v: Vec<String> = list.split(',').map(|c| c.trim().to_owned()).collect();
    v.sort();
    v
}

#[test]
fn invalid_models_are_rejected_where_the_rule_is_broken() {
    let err = files("tests/semantic/err");
    assert!(err.len() >= 150, "{} invalid models", err.len());
    let mut failures = Vec::new();
    for f in &err {
        let want = expected(f);
        let (code, stderr) = check(f);
        let mut got = common::rendered_codes(&stderr);
        got.sort();
        if code != Some(1) || got != want {
            failures.push(format!(
                "{}: want {want:?}, got {got:?} (exit {code:?})\n{stderr}",
                f.display()
            ));
            continue;
        }
        let name = f.file_stem().unwrap().to_string_lossy().to_string();
        insta::assert_snapshot!(format!("semantic_err_{name}"), stderr);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn legal_models_at_the_edge_of_each_rule_check_cleanly() {
    let ok = files("tests/semantic/ok");
    assert!(ok.len() >= 50, "{} valid models", ok.len());
    let failures: Vec<String> = ok
        .iter()
        .filter_map(|f| {
            let (code, stderr) = check(f);
            (code != Some(0) || !stderr.contains("no errors"))
                .then(|| format!("{}: exit {code:?}\n{stderr}", f.display()))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `flatten` (and so `simulate`) checks the other classes of the model's file too: a
/// function beside the model that assigns its input is refused there as well.
#[test]
fn flattening_checks_the_other_classes_of_the_file() {
    let f = Path::new("tests/semantic/err/assign_function_input_of_used_function.mo");
    let out = flatten(f);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(common::rendered_codes(&stderr), expected(f), "{stderr}");
}

/// `W2001`: a parameter with neither a value nor a start value is a warning (spec 8.6
/// lets it take its type's default); the check still succeeds. Parameters computed by
/// initial equations (`fixed = false`) or with a start value are not reported.
#[test]
fn a_parameter_without_any_value_is_a_warning() {
    let (code, stderr) = check(Path::new("tests/semantic/warn/unbound_parameter.mo"));
    assert_eq!(code, Some(0), "{stderr}");
    let at: Vec<&str> = stderr
        .lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix("┌─ tests/semantic/warn/unbound_parameter.mo:")
        })
        .collect();
    assert_eq!(at, ["2:18", "5:21"], "{stderr}");
    assert_eq!(stderr.matches("warning[W2001]").count(), 2, "{stderr}");
    assert!(stderr.contains("no errors, 2 warnings"), "{stderr}");
}

/// `W2002`: an `outer` component without `inner` whose class is not partial gets an
/// inner of that class at the top of the model, with a warning (spec 5.4); both outers
/// refer to the one created inner.
#[test]
fn a_missing_inner_is_created_by_default_with_a_warning() {
    let f = Path::new("tests/semantic/warn/default_inner.mo");
    let (code, stderr) = check(f);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stderr.matches("warning[W2002]").count(), 1, "{stderr}");
    assert!(stderr.contains("default_inner.mo:5:15"), "{stderr}");
    assert!(stderr.contains("no errors, 1 warning"), "{stderr}");
    let out = flatten(f);
    let flat = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{flat}");
    assert!(flat.contains("parameter Real 'world.g' = 9.81;"), "{flat}");
    assert_eq!(flat.matches("'world.g'").count(), 3, "{flat}");
}
