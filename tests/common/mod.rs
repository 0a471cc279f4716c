//! Helpers shared by the end-to-end tests: expected-diagnostics manifests and the
//! `CODE @line:col` list of rendered diagnostics.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::{Command, Output};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs the `unimo` binary with `args` then `--color never`, in the repository.
pub fn unimo(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(args)
        .args(["--color", "never"])
        .current_dir(root())
        .output()
        .unwrap()
}

/// Asserts that a finished command exited with 0, showing its stderr when not.
pub fn assert_success(out: &Output) {
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The exit code, stdout and stderr of a finished command.
pub fn code_and_text(out: Output) -> (Option<i32>, String, String) {
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `name` in this test process's own folder `unimo-<suite>-<pid>` of the system's
/// temporary folder (made when missing).
pub fn temp(suite: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("unimo-{suite}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The `.mo` files of the repository folder `dir`, sorted, as absolute paths.
pub fn mo_files(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mo"))
        .collect();
    v.sort();
    v
}

/// Loads and compiles a model of the repository (`model`: its name when the file holds
/// several); panics with the diagnostics otherwise.
pub fn load(file: &str, model: Option<&str>) -> unimo_cli::LoadedModel {
    unimo_cli::load_model(&[root().join(file)], model).unwrap_or_else(|e| panic!("{file}:\n{e}"))
}

/// `file: CODE @l:c, CODE @l:c` lines of a manifest (lines starting with `#` skipped).
pub fn manifest(rel: &str) -> BTreeMap<String, Vec<String>> {
    std::fs::read_to_string(root().join(rel))
        .unwrap_or_else(|e| panic!("{rel}: {e}"))
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let (f, codes) = l.split_once(':').expect("`file: CODE @l:c, ...`");
            (
                f.trim().to_owned(),
                codes.split(',').map(|c| c.trim().to_owned()).collect(),
            )
        })
        .collect()
}

/// `CODE @line:col` of every error rendered in `stderr` (the header line, then the
/// `┌─ file:line:col` line).
pub fn rendered_codes(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .collect::<Vec<_>>()
        .windows(2)
        .filter_map(|w| {
            let code = w[0].strip_prefix("error[")?.split(']').next()?;
            let loc: Vec<&str> = w[1].rsplit(':').take(2).collect();
            Some(format!("{code} @{}:{}", loc[1], loc[0]))
        })
        .collect()
}

/// The options of a simulation from `start` to `stop` at `rtol` (atol = rtol / 100,
/// the command line's default) with output every `interval`.
pub fn sim_options(
    method: unimo_solve::Method,
    rtol: f64,
    start: f64,
    stop: f64,
    interval: f64,
) -> unimo_runtime::sim::SimOptions {
    unimo_runtime::sim::SimOptions {
        start,
        stop,
        rtol,
        atol: rtol / 100.0,
        method,
        interval,
        every_step: false,
        output_rtol: 0.0,
    }
}

/// Simulates `m` from 0 to `stop` at `rtol` (atol = rtol / 100, the command line's
/// default) with output every `interval`; panics with the error message on failure.
pub fn run_ok(
    m: &unimo_cli::LoadedModel,
    method: unimo_solve::Method,
    rtol: f64,
    stop: f64,
    interval: f64,
) -> unimo_runtime::sim::SimResult {
    let o = sim_options(method, rtol, 0.0, stop, interval);
    let r = unimo_runtime::sim::simulate(&m.compiled, &o);
    assert!(
        r.error.is_none(),
        "{:?}",
        r.error.as_ref().map(|e| e.message())
    );
    r
}

/// The values of output `name` over the rows of `r`; panics when there is no such output.
pub fn column(r: &unimo_runtime::sim::SimResult, name: &str) -> Vec<f64> {
    let k = r
        .names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no {name}"));
    r.rows.iter().map(|row| row[k]).collect()
}
