//! `unimo bench`: error against run time for models x methods x tolerances, as a
//! table on stdout and a work-precision plot.

use crate::check::{render_stage, with_flat_model};
use crate::error::CliError;
use crate::simulate::{method, native_or_tape};
use crate::{BenchArgs, MethodArg, EXIT_MODEL_ERROR, EXIT_OK};
use std::collections::HashMap;
use std::time::Instant;
use unimo_codegen::model::CompiledModel;
use unimo_runtime::sim::{simulate, SimOptions, SimResult};

/// One measured configuration.
#[derive(Clone, Debug)]
pub struct Measurement {
    pub model: String,
    pub method: MethodArg,
    pub median_ms: f64,
    pub steps: u64,
    pub scd_end: f64,
    pub failed: Option<String>,
}

/// Reference values: per variable name, the values on the grid (by time) and at the end.
struct Reference {
    end: HashMap<String, f64>,
    grid: HashMap<u64, HashMap<String, f64>>,
}

fn key(t: f64) -> u64 {
    t.to_bits()
}

fn reference_from_result(r: &SimResult) -> Reference {
    let mut end = HashMap::new();
    let mut grid: HashMap<u64, HashMap<String, f64>> = HashMap::new();
    if let Some(last) = r.rows.last() {
        for (n, v) in r.names.iter().zip(last) {
            end.insert(n.clone(), *v);
        }
    }
    for (t, row) in r.times.iter().zip(&r.rows) {
        // At an event time two rows exist; the grid uses the first (left limit).
        grid.entry(key(*t))
            .or_insert_with(|| r.names.iter().cloned().zip(row.iter().copied()).collect());
    }
    Reference { end, grid }
}

fn reference_from_csv(path: &std::path::Path) -> Result<Reference, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let mut lines = text.lines();
    let header = csv_fields(lines.next().ok_or("the reference CSV is empty")?);
    let mut result = SimResult {
        names: header[1..].to_vec(),
        ..SimResult::default()
    };
    for (k, line) in lines.enumerate() {
        let vals: Result<Vec<f64>, _> = line.split(',').map(|s| s.trim().parse::<f64>()).collect();
        let vals = vals.map_err(|e| format!("reference line {}: {e}", k + 2))?;
        if vals.len() != header.len() {
            return Err(format!(
                "reference line {} has {} values, the header {}",
                k + 2,
                vals.len(),
                header.len()
            ));
        }
        result.times.push(vals[0]);
        result.rows.push(vals[1..].to_vec());
    }
    Ok(reference_from_result(&result))
}

/// The fields of one CSV line: commas inside double quotes belong to the field (a 2-D
/// array element is written `"u[1,2]"`), `""` inside quotes is one quote.
fn csv_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                fields.last_mut().expect("one field").push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => fields.push(String::new()),
            c => fields.last_mut().expect("one field").push(c),
        }
    }
    fields.into_iter().map(|f| f.trim().to_owned()).collect()
}

/// -log10 of the largest relative error of `values` against `reference` (matching
/// names; derivatives left out); absolute error where the reference is zero.
fn scd(names: &[String], values: &[f64], reference: &HashMap<String, f64>) -> f64 {
    let mut worst = 0.0f64;
    for (n, &v) in names.iter().zip(values) {
        if n.starts_with("der(") {
            continue;
        }
        let Some(&r) = reference.get(n) else { continue };
        let err = if r == 0.0 {
            v.abs()
        } else {
            ((v - r) / r).abs()
        };
        worst = worst.max(if err.is_nan() { f64::INFINITY } else { err });
    }
    if worst == 0.0 {
        16.0
    } else {
        -worst.log10()
    }
}

fn measure(
    m: &CompiledModel,
    o: &SimOptions,
    runs: usize,
    reference: &Reference,
) -> (f64, SimResult, f64, f64) {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..runs.max(1) {
        let t0 = Instant::now();
        let r = simulate(m, o);
        times.push(t0.elapsed().as_secs_f64() * 1e3);
        last = Some(r);
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let r = last.expect("at least one run");
    let end = r
        .rows
        .last()
        .map(|row| scd(&r.names, row, &reference.end))
        .unwrap_or(f64::NAN);
    let mut grid = f64::INFINITY;
    let mut seen = std::collections::HashSet::new();
    for (t, row) in r.times.iter().zip(&r.rows) {
        if !seen.insert(key(*t)) {
            continue;
        }
        if let Some(refrow) = reference.grid.get(&key(*t)) {
            grid = grid.min(scd(&r.names, row, refrow));
        }
    }
    (median, r, end, grid)
}

pub fn bench(a: &BenchArgs, color: bool) -> i32 {
    if a.tolerances.iter().any(|&t| !positive(t)) || !positive(a.atol_factor) {
        return CliError::BadTolerances {}.report();
    }
    let mut all = Vec::new();
    let mut code = EXIT_OK;
    println!(
        "{:<16} {:<7} {:>8} {:>8} {:>11} {:>7} {:>7} {:>7}",
        "model", "method", "rtol", "atol", "median_ms", "steps", "scd_end", "scd_grid"
    );
    for file in &a.files {
        let files = vec![file.clone()];
        let c = with_flat_model(
            &files,
            a.model.as_deref(),
            &a.libs,
            color,
            false,
            &mut |flat, map, _| bench_model(a, flat, map, color, &mut all),
        );
        code = code.max(c);
    }
    if let Some(path) = &a.plot {
        if let Err(e) = plot(path, &all) {
            let (what, reason) = ("the plot".to_owned(), e.to_string());
            return CliError::CannotWrite { what, reason }.report();
        }
        eprintln!("wrote {}", path.display());
    }
    code
}

/// Benchmarks one flat model with every method and tolerance, printing a table row
/// for each and adding it to `all`. Returns the exit code.
fn bench_model(
    a: &BenchArgs,
    flat: &unimo_flat::FlatModel,
    map: &unimo_source::SourceMap,
    color: bool,
    all: &mut Vec<Measurement>,
) -> i32 {
    let (dae, analysis) = match unimo_dae::analyze_model(flat) {
        Ok(x) => x,
        Err(d) => {
            render_stage(&d, map, color);
            return EXIT_MODEL_ERROR;
        }
    };
    let mut compiled = unimo_codegen::model::compile(&dae, &analysis.plan);
    // Native code is compiled once here, outside the timed runs, as the model's tapes are.
    native_or_tape(a.engine, &mut compiled);
    // The same resolution of the experiment's settings as `simulate`, with
    // the benchmark's tolerances and output points.
    let resolved = |m: MethodArg, rtol: f64, atol: f64| {
        let o = unimo_runtime::sim::Overrides {
            stop: a.stop_time,
            rtol: Some(rtol),
            atol: Some(atol),
            points: Some(a.points),
            ..Default::default()
        };
        // The grid alone: runs are compared row by row.
        SimOptions::resolve(&dae.experiment, &o, method(m), false).map(|o| SimOptions {
            output_rtol: 0.0,
            ..o
        })
    };
    // Tolerances are checked above: only the times can be wrong here.
    if let Err(why) = resolved(MethodArg::Bdf, 1e-6, 1e-8) {
        return CliError::BadOptions { why }.report();
    }
    let options = |m: MethodArg, rtol: f64, atol: f64| {
        resolved(m, rtol, atol).expect("times checked above, tolerances positive")
    };
    let reference = match reference_values(a, &compiled, &options) {
        Ok(r) => r,
        Err(e) => return e.report(),
    };
    for &m in &a.methods {
        for &rtol in &a.tolerances {
            let atol = rtol * a.atol_factor;
            let (median, r, end, grid) =
                measure(&compiled, &options(m, rtol, atol), a.runs, &reference);
            let meas = Measurement {
                model: dae.name.clone(),
                method: m,
                median_ms: median,
                steps: r.stats.solver.steps,
                scd_end: end,
                failed: r.error.as_ref().map(|e| e.message()),
            };
            print_row(&meas, rtol, atol, grid);
            if let Some(last) = r.rows.last() {
                for line in quantity_lines(&r.names, last, &reference.end, &a.quantities) {
                    println!("{line}");
                }
            }
            all.push(meas);
        }
    }
    EXIT_OK
}

/// The reference values: from `--reference`, or from a run with tolerances a thousand
/// times tighter than the tightest benchmarked.
fn reference_values(
    a: &BenchArgs,
    compiled: &CompiledModel,
    options: &dyn Fn(MethodArg, f64, f64) -> SimOptions,
) -> Result<Reference, CliError> {
    match &a.reference {
        Some(p) => reference_from_csv(p).map_err(|why| CliError::ResultTable { why }),
        None => {
            let tight =
                (a.tolerances.iter().copied().fold(f64::INFINITY, f64::min) * 1e-3).max(1e-14);
            let r = simulate(
                compiled,
                &options(MethodArg::Radau5, tight, tight * a.atol_factor),
            );
            if let Some(e) = &r.error {
                return Err(CliError::ReferenceFailed { why: e.message() });
            }
            Ok(reference_from_result(&r))
        }
    }
}

/// One line per requested quantity: its value at the end of a run, the reference's value
/// and the relative error (absolute where the reference is zero).
fn quantity_lines(
    names: &[String],
    last: &[f64],
    reference: &HashMap<String, f64>,
    quantities: &[String],
) -> Vec<String> {
    quantities
        .iter()
        .map(|q| {
            let value = names.iter().position(|n| n == q).map(|k| last[k]);
            match (value, reference.get(q)) {
                (Some(v), Some(&r)) => {
                    let err = if r == 0.0 {
                        v.abs()
                    } else {
                        ((v - r) / r).abs()
                    };
                    format!("  {q} = {v:.12} (reference {r:.12}, error {err:.1e})")
                }
                (Some(v), None) => format!("  {q} = {v:.12} (not in the reference)"),
                (None, _) => format!("  {q}: not an output of the model"),
            }
        })
        .collect()
}

/// One row of the table on stdout.
fn print_row(meas: &Measurement, rtol: f64, atol: f64, grid: f64) {
    println!(
        "{:<16} {:<7} {:>8.0e} {:>8.0e} {:>11.3} {:>7} {:>7.2} {:>7.2}{}",
        meas.model,
        format!("{:?}", meas.method).to_lowercase(),
        rtol,
        atol,
        meas.median_ms,
        meas.steps,
        meas.scd_end,
        grid,
        meas.failed
            .as_ref()
            .map(|f| format!("  FAILED: {f}"))
            .unwrap_or_default()
    );
}

fn plot(path: &std::path::Path, all: &[Measurement]) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let finite: Vec<&Measurement> = all
        .iter()
        .filter(|m| m.scd_end.is_finite() && m.median_ms > 0.0)
        .collect();
    let (mut tmin, mut tmax) = (f64::INFINITY, 0.0f64);
    let (mut smin, mut smax) = (f64::INFINITY, f64::NEG_INFINITY);
    for m in &finite {
        tmin = tmin.min(m.median_ms);
        tmax = tmax.max(m.median_ms);
        smin = smin.min(m.scd_end);
        smax = smax.max(m.scd_end);
    }
    if finite.is_empty() {
        tmin = 0.1;
        tmax = 1.0;
        smin = 0.0;
        smax = 1.0;
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Work-precision: scd at the end time against median run time",
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(
            (tmin * 0.8..tmax * 1.25).log_scale(),
            (smin - 0.5)..(smax + 0.5),
        )?;
    chart
        .configure_mesh()
        .x_desc("median run time [ms]")
        .y_desc("scd (significant correct digits)")
        .draw()?;
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for m in &finite {
        let label = format!("{} {}", m.model, format!("{:?}", m.method).to_lowercase());
        match series.iter_mut().find(|(l, _)| *l == label) {
            Some((_, pts)) => pts.push((m.median_ms, m.scd_end)),
            None => series.push((label, vec![(m.median_ms, m.scd_end)])),
        }
    }
    for (k, (label, pts)) in series.into_iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::LowerRight)
        .draw()?;
    root.present()?;
    Ok(())
}

/// A finite number above zero.
pub fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_report_their_error_against_the_reference() {
        let names = vec!["Impacts".to_owned(), "tFirstRolling".to_owned()];
        let reference: HashMap<String, f64> = [
            ("Impacts".to_owned(), 2168.0),
            ("tFirstRolling".to_owned(), 0.0),
        ]
        .into();
        let asked = ["Impacts", "tFirstRolling", "Energy"].map(str::to_owned);
        let lines = quantity_lines(&names, &[2200.0, 0.5], &reference, &asked);
        assert_eq!(
            lines,
            vec![
                "  Impacts = 2200.000000000000 (reference 2168.000000000000, error 1.5e-2)",
                "  tFirstRolling = 0.500000000000 (reference 0.000000000000, error 5.0e-1)",
                "  Energy: not an output of the model",
            ]
        );
    }

    #[test]
    fn quoted_fields_keep_their_commas() {
        assert_eq!(
            csv_fields(r#"time,"u[1,2]", y ,"a""b""#),
            vec!["time", "u[1,2]", "y", r#"a"b"#]
        );
    }

    #[test]
    fn a_reference_with_two_dimensional_names_is_read_by_name() {
        let path = std::env::temp_dir().join(format!("unimo-bench-ref-{}.csv", std::process::id()));
        std::fs::write(&path, "time,\"u[1,1]\",\"u[1,2]\"\n2,0.5,0.25\n").unwrap();
        let reference = reference_from_csv(&path);
        std::fs::remove_file(&path).unwrap();
        let reference = reference.unwrap();
        assert_eq!(reference.end.get("u[1,2]"), Some(&0.25));
        let names = vec!["u[1,1]".to_owned(), "u[1,2]".to_owned()];
        // u[1,2] is off by 1e-3 relative: 3 correct digits
        let digits = scd(&names, &[0.5, 0.25 * (1.0 + 1e-3)], &reference.end);
        assert!((digits - 3.0).abs() < 1e-9, "{digits}");
    }
}
