//! Helpers shared by the end-to-end tests: expected-diagnostics manifests and the
//! `CODE @line:col` list of rendered diagnostics.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::PathBuf;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
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

/// Simulates `m` from 0 to `stop` at `rtol` (atol = rtol / 100, the command line's
/// default) with output every `interval`; panics with the error message on failure.
pub fn run_ok(
    m: &unimo_cli::LoadedModel,
    method: unimo_solve::Method,
    rtol: f64,
    stop: f64,
    interval: f64,
) -> unimo_runtime::sim::SimResult {
    let o = unimo_runtime::sim::SimOptions {
        start: 0.0,
        stop,
        rtol,
        atol: rtol / 100.0,
        method,
        interval,
        every_step: false,
    };
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
