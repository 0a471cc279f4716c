//! Parameter sweeps: many runs of one model with different parameter values, on
//! threads (`unimo sweep`, and the Python package's `Model.sweep`). Each worker thread
//! parses the model once ([`api::with_session`]) and compiles it per point with the
//! point's values as modifiers; a point that fails keeps its error and the others go on.

use crate::api::{self, ApiError, Source};
use crate::error::CliError;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use unimo_runtime::sim::{Overrides, SimResult};
use unimo_solve::Method;

/// One point: parameter names and values as written in Modelica.
pub type Point = Vec<(String, String)>;

/// What every run of a sweep shares.
#[derive(Clone, Debug)]
pub struct SweepSettings {
    /// Variables whose final values are reported (all when empty); the model is
    /// pruned to them.
    pub outputs: Vec<String>,
    pub overrides: Overrides,
    pub method: Method,
    /// Worker threads (at least 1).
    pub jobs: usize,
    /// Keep each run's whole result (for summaries computed by the caller).
    pub keep_results: bool,
}

/// How one point ended.
#[derive(Debug, Default)]
pub struct PointOutcome {
    /// The final value of each selected output (with `time` first).
    pub values: Vec<(String, f64)>,
    pub error: Option<ApiError>,
    /// The run's result, when `keep_results` (also the rows before a failure).
    pub result: Option<SimResult>,
    /// Run statistics (empty when the point did not compile).
    pub stats: Vec<(&'static str, f64)>,
}

/// Runs every point on `settings.jobs` threads. `Err` when the model itself cannot be
/// read or flattened (no point could run).
pub fn run(
    source: &Source,
    points: &[Point],
    settings: &SweepSettings,
) -> Result<Vec<PointOutcome>, ApiError> {
    let next = AtomicUsize::new(0);
    let outcomes: Mutex<Vec<Option<PointOutcome>>> =
        Mutex::new((0..points.len()).map(|_| None).collect());
    let failure: Mutex<Option<ApiError>> = Mutex::new(None);
    let jobs = settings.jobs.clamp(1, points.len().max(1));
    std::thread::scope(|scope| {
        for k in 0..jobs {
            let worker = || {
                let session = api::with_session(source, |session| loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(point) = points.get(i) else { break };
                    let outcome = run_point(session, point, settings);
                    if let Ok(mut all) = outcomes.lock() {
                        all[i] = Some(outcome);
                    }
                });
                if let Err(e) = session {
                    if let Ok(mut f) = failure.lock() {
                        f.get_or_insert(e);
                    }
                }
            };
            std::thread::Builder::new()
                .name(format!("sweep-{k}"))
                .stack_size(api::STACK_SIZE)
                .spawn_scoped(scope, worker)
                .expect("cannot start a sweep thread");
        }
    });
    if let Some(e) = failure.into_inner().ok().flatten() {
        return Err(e);
    }
    let all = outcomes.into_inner().unwrap_or_default();
    Ok(all.into_iter().map(Option::unwrap_or_default).collect())
}

/// Compiles and runs one point.
fn run_point(session: &mut api::Session<'_>, point: &Point, s: &SweepSettings) -> PointOutcome {
    let compiled = match session.compile(point, &s.outputs) {
        Ok(c) => c,
        Err(e) => {
            return PointOutcome {
                error: Some(e),
                ..PointOutcome::default()
            }
        }
    };
    let (result, error) = match session.simulate(&compiled, &s.overrides, s.method) {
        Ok((r, e)) => (Some(r), e),
        Err(e) => (None, Some(e)),
    };
    let mut outcome = PointOutcome {
        error,
        ..PointOutcome::default()
    };
    if let Some(r) = &result {
        outcome.stats = compiled.stats(r);
        if outcome.error.is_none() {
            outcome.values = final_values(r, &s.outputs);
        }
    }
    if s.keep_results {
        outcome.result = result;
    }
    outcome
}

/// `time` and the selected outputs at the end of the run.
fn final_values(r: &SimResult, outputs: &[String]) -> Vec<(String, f64)> {
    let (Some(&t), Some(row)) = (r.times.last(), r.rows.last()) else {
        return Vec::new();
    };
    let cols = api::select_columns(&r.names, outputs).unwrap_or_default();
    std::iter::once(("time".to_owned(), t))
        .chain(cols.into_iter().map(|c| (r.names[c].clone(), row[c])))
        .collect()
}

/// The values of one `-p` setting: `name=a:b:n` (n points from a to b), `name=x,y,z`,
/// or `name=x`.
pub fn parse_setting(text: &str) -> Result<(String, Vec<String>), CliError> {
    let text_owned = || text.to_owned();
    let Some((name, spec)) = text.split_once('=') else {
        return Err(CliError::NotNameValues { text: text_owned() });
    };
    let (name, spec) = (name.trim().to_owned(), spec.trim());
    if name.is_empty() || spec.is_empty() {
        return Err(CliError::NoNameOrValues { text: text_owned() });
    }
    let parts: Vec<&str> = spec.split(':').collect();
    if parts.len() == 3 {
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| CliError::RangeEndNotNumber {
                    text: text_owned(),
                    value: s.to_owned(),
                })
        };
        let (a, b) = (number(parts[0])?, number(parts[1])?);
        let n: usize = parts[2]
            .trim()
            .parse()
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| CliError::RangeCountNotCount {
                text: text_owned(),
                value: parts[2].to_owned(),
            })?;
        let values = (0..n)
            .map(|k| match n {
                1 => a,
                _ if k == n - 1 => b,
                _ => a + (b - a) * k as f64 / (n - 1) as f64,
            })
            .map(|x| x.to_string())
            .collect();
        return Ok((name, values));
    }
    if parts.len() != 1 {
        return Err(CliError::NotARange { text: text_owned() });
    }
    Ok((name, spec.split(',').map(|v| v.trim().to_owned()).collect()))
}

/// Every combination of the settings' values (the first setting varies slowest).
pub fn grid(settings: &[(String, Vec<String>)]) -> Vec<Point> {
    let mut points: Vec<Point> = vec![Vec::new()];
    for (name, values) in settings {
        points = points
            .iter()
            .flat_map(|p| {
                values.iter().map(move |v| {
                    let mut q = p.clone();
                    q.push((name.clone(), v.clone()));
                    q
                })
            })
            .collect();
    }
    points
}

/// `unimo sweep`: runs the grid of the `-p` settings and writes one CSV row per point.
pub fn command(a: &crate::SweepArgs) -> i32 {
    let mut settings = Vec::new();
    for p in &a.params {
        match parse_setting(p) {
            Ok(s) => settings.push(s),
            Err(e) => return e.report(),
        }
    }
    let points = grid(&settings);
    let source = a.source.source(unimo_dae::FoldOptions {
        tunable_all: false,
        tunable: a.tunable.clone(),
    });
    let jobs = a
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let sweep = SweepSettings {
        outputs: a.vars.clone(),
        overrides: Overrides {
            stop: a.stop_time,
            rtol: a.tolerance,
            ..Overrides::default()
        },
        method: crate::simulate::method(a.method),
        jobs,
        keep_results: false,
    };
    let started = std::time::Instant::now();
    let outcomes = match run(&source, &points, &sweep) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{}", e.rendered);
            return match e.kind {
                api::ErrorKind::Model => crate::EXIT_MODEL_ERROR,
                _ => crate::EXIT_USAGE,
            };
        }
    };
    let seconds = started.elapsed().as_secs_f64();
    let names: Vec<&str> = settings.iter().map(|(n, _)| n.as_str()).collect();
    let table = csv_table(&names, &points, &outcomes);
    let written = match &a.output {
        Some(path) => std::fs::write(path, table),
        None => std::io::Write::write_all(&mut std::io::stdout(), table.as_bytes()),
    };
    if let Err(e) = written {
        let (what, reason) = ("the table".to_owned(), e.to_string());
        return CliError::CannotWrite { what, reason }.report();
    }
    let failed = outcomes.iter().filter(|o| o.error.is_some()).count();
    eprintln!(
        "{} points, {failed} failed, {jobs} jobs, {seconds:.2} s, {:.1} runs/s",
        points.len(),
        points.len() as f64 / seconds.max(1e-9)
    );
    if failed > 0 {
        crate::EXIT_SIMULATION_FAILURE
    } else {
        crate::EXIT_OK
    }
}

/// The sweep's table: the parameters, `status`, `error_code`, `error_message`, then the
/// final values (the union of every point's columns, in order of appearance).
fn csv_table(params: &[&str], points: &[Point], outcomes: &[PointOutcome]) -> String {
    let mut columns: Vec<&str> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for o in outcomes {
        for (n, _) in &o.values {
            if seen.insert(n.as_str()) {
                columns.push(n);
            }
        }
    }
    let quote = |s: &str| {
        if s.contains([',', '"', '\n']) {
            format!("\"{}\"", s.replace('"', "\"\"").replace('\n', " "))
        } else {
            s.to_owned()
        }
    };
    let header: Vec<String> = params
        .iter()
        .copied()
        .chain(["status", "error_code", "error_message"])
        .chain(columns.iter().copied())
        .map(quote)
        .collect();
    let mut out = header.join(",") + "\n";
    for (point, o) in points.iter().zip(outcomes) {
        let mut cells: Vec<String> = point.iter().map(|(_, v)| quote(v)).collect();
        match &o.error {
            Some(e) => cells.extend(["failed".to_owned(), e.code.clone(), quote(&e.message)]),
            None => cells.extend(["ok".to_owned(), String::new(), String::new()]),
        }
        for c in &columns {
            let v = o.values.iter().find(|(n, _)| n == c);
            cells.push(v.map_or(String::new(), |(_, x)| format!("{x:e}")));
        }
        out += &(cells.join(",") + "\n");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_lists_and_grids() {
        let (n, v) = parse_setting("k=0.5:0.9:5").unwrap();
        assert_eq!(n, "k");
        assert_eq!(v, ["0.5", "0.6", "0.7", "0.8", "0.9"]);
        let (_, v) = parse_setting("f=0.05,0.1").unwrap();
        assert_eq!(v, ["0.05", "0.1"]);
        assert!(parse_setting("k=1:2").is_err());
        assert!(parse_setting("k=1:2:0").is_err());
        let g = grid(&[
            ("a".into(), vec!["1".into(), "2".into()]),
            ("b".into(), vec!["x".into(), "y".into(), "z".into()]),
        ]);
        assert_eq!(g.len(), 6);
        assert_eq!(
            g[1],
            [
                ("a".to_owned(), "1".to_owned()),
                ("b".to_owned(), "y".to_owned())
            ]
        );
    }
}
