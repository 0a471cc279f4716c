//! `unimo simulate`: compile, simulate, write CSV and statistics.

use crate::check::{render_stage, with_flat_model_overridden, ParameterOverrides};
use crate::error::CliError;
use crate::results::csv::CsvStream;
use crate::{
    EngineArg, MethodArg, ResultFormat, SimulateArgs, EXIT_MODEL_ERROR, EXIT_OK,
    EXIT_SIMULATION_FAILURE,
};
use std::io::Write;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use unimo_codegen::model::CompiledModel;
use unimo_dae::plan::Plan;
use unimo_dae::Dae;
use unimo_runtime::sim::{SimError, SimOptions, SimResult};
use unimo_solve::Method;
use unimo_source::SourceMap;

pub fn method(m: MethodArg) -> Method {
    match m {
        MethodArg::Auto => Method::Auto,
        MethodArg::Bdf => Method::Bdf,
        MethodArg::Radau5 => Method::Radau5,
        MethodArg::Dopri5 => Method::Dopri5,
    }
}

/// Columns selected by `--vars` (all when empty); Err names an unknown selector.
pub(crate) fn select(names: &[String], wanted: &[String]) -> Result<Vec<usize>, CliError> {
    if wanted.is_empty() {
        return Ok((0..names.len()).collect());
    }
    let mut out = Vec::new();
    for w in wanted {
        let w = w.trim();
        let hits: Vec<usize> = names
            .iter()
            .enumerate()
            .filter(|(_, n)| {
                *n == w
                    || n.strip_prefix(w)
                        .is_some_and(|rest| rest.starts_with('.') || rest.starts_with('['))
            })
            .map(|(k, _)| k)
            .collect();
        if hits.is_empty() {
            let mut similar: Vec<String> = names
                .iter()
                .filter(|n| n.contains(w) || w.contains(n.as_str()))
                .take(5)
                .cloned()
                .collect();
            similar.sort();
            let name = w.to_owned();
            return Err(CliError::UnknownVariable { name, similar });
        }
        out.extend(hits);
    }
    out.sort();
    out.dedup();
    Ok(out)
}

pub fn simulate(a: &SimulateArgs, color: bool) -> i32 {
    let started = Instant::now();
    let overrides = ParameterOverrides {
        flags: &a.params,
        file: a.override_file.as_deref(),
    };
    with_flat_model_overridden(
        &a.source.files,
        a.source.model.as_deref(),
        &a.source.libs,
        color,
        false,
        &overrides,
        &mut |flat, map, _| {
            if a.list_params {
                let (dae, _) = unimo_dae::lower_with(flat, &fold_options(a));
                let folded = dae
                    .folded_parameters
                    .iter()
                    .map(|&s| dae.scalar(s).name.clone())
                    .collect();
                print!("{}", crate::params::list(flat, &folded));
                return EXIT_OK;
            }
            simulate_flat(a, flat, map, color, started)
        },
    )
}

/// The parameters `--tunable` / `--tunable-all` keep out of folding.
fn fold_options(a: &SimulateArgs) -> unimo_dae::FoldOptions {
    unimo_dae::FoldOptions {
        tunable_all: a.tunable_all,
        tunable: a.tunable.clone(),
    }
}

/// Analyses, compiles and simulates a flat model, then writes the results and reports
/// how the run ended. Returns the exit code.
fn simulate_flat(
    a: &SimulateArgs,
    flat: &unimo_flat::FlatModel,
    map: &SourceMap,
    color: bool,
    started: Instant,
) -> i32 {
    let load = ms_since(started);
    let parse = crate::check::parse_seconds() * 1e3;
    let mut phases = Phases {
        parse,
        flatten: load - parse,
        ..Phases::default()
    };
    let fold = fold_options(a);
    if let Err(unknown) = check_tunable(flat, &fold) {
        return report_all(&unknown);
    }
    let mut seconds = [0.0; 2];
    let (dae, analysis) = match unimo_dae::analyze_model_timed(flat, &fold, &mut seconds) {
        Ok(x) => x,
        Err(diags) => {
            render_stage(&diags, map, color);
            return EXIT_MODEL_ERROR;
        }
    };
    render_stage(&dae.warnings, map, color);
    // Select the outputs first: with --vars, what they do not need is left out.
    let (output_ids, cols) = match output_columns(&dae, &a.vars) {
        Ok(x) => x,
        Err(e) => return e.report(),
    };
    let mut plan = analysis.plan.clone();
    if !a.vars.is_empty() {
        let wanted: Vec<_> = cols.iter().map(|&c| output_ids[c]).collect();
        unimo_dae::prune::prune(&dae, &mut plan, &wanted);
    }
    phases.lower = seconds[0] * 1e3;
    // The structure phase also holds selecting the outputs and pruning.
    phases.structure = ms_since(started) - load - phases.lower;
    let compile_started = Instant::now();
    let mut compiled = unimo_codegen::model::compile(&dae, &plan);
    phases.compile = ms_since(compile_started);
    let native_started = Instant::now();
    let native = native_or_tape(a.engine, &mut compiled);
    phases.native = ms_since(native_started);
    let options = match sim_options(a, &dae) {
        Ok(o) => o,
        Err(e) => return e.report(),
    };
    let start = options.start;
    let sim_started = Instant::now();
    // --stats splits the run's time into evaluation and linear algebra.
    unimo_solve::set_fine_timing(a.stats);
    // --cost times every plan step of the run.
    let profile = a.cost.map(|_| Arc::new(Mutex::new(Vec::new())));
    let mut csv = csv_stream(a, &compiled, &cols);
    // The rows stay in memory only for what reads them after the run (--animate).
    let sink = csv
        .as_mut()
        .map(|stream| (stream.sink(&cols), a.animate.is_some()));
    let result = run(&compiled, &options, sim_started, profile.clone(), sink);
    let simulate_ms = ms_since(sim_started);
    (phases.simulate, phases.run) = (simulate_ms, result.phase_times.clone());
    let write_started = Instant::now();
    let ids = (&output_ids[..], &cols[..]);
    let span = (start, options.stop);
    if let Err(e) = finish_results(a, (flat, &dae), &result, csv, ids, span) {
        let (what, reason) = ("the results".to_owned(), e.to_string());
        return CliError::CannotWrite { what, reason }.report();
    }
    phases.write = ms_since(write_started);
    if let Some(page) = &a.animate {
        let code = crate::animate::command::after_run(page, flat, &dae, &result, &cols);
        if code != EXIT_OK {
            return code;
        }
    }
    // Before the `--stats` line, which scripts read as the last line of a run that ends well.
    stiffness_note(&result);
    if a.stats {
        print_stats(
            options.method,
            &compiled,
            &plan,
            &result,
            &phases,
            native.as_ref(),
        );
    }
    if let Some(depth) = a.cost {
        eprint!(
            "{}",
            cost_table(&compiled, depth.max(1), &result, simulate_ms, profile)
        );
    }
    how_it_ended(&dae, map, &result, start)
}

/// The CSV writer, started before the run when the result is a CSV: it writes on a
/// second thread while the run goes on.
fn csv_stream(a: &SimulateArgs, compiled: &CompiledModel, cols: &[usize]) -> Option<CsvStream> {
    let names: Vec<String> = compiled.outputs.iter().map(|(n, _)| n.clone()).collect();
    (result_format(a) == ResultFormat::Csv)
        .then(|| CsvStream::start(a.output.as_deref(), names, cols.to_vec()))
}

/// Completes the result file: waits for the CSV writer, or writes the MAT file.
fn finish_results(
    a: &SimulateArgs,
    (flat, dae): (&unimo_flat::FlatModel, &Dae),
    result: &SimResult,
    csv: Option<CsvStream>,
    ids: (&[unimo_dae::expr::ScalarId], &[usize]),
    span: (f64, f64),
) -> std::io::Result<()> {
    match csv {
        Some(stream) => stream.finish(),
        None => write_mat(a, flat, dae, result, ids, span),
    }
}

/// Native code for the compiled model, or `None` with a note when it cannot be had
/// (the tape computes the same results).
pub(crate) fn native_or_tape(
    engine: EngineArg,
    compiled: &mut CompiledModel,
) -> Option<unimo_codegen::NativeStats> {
    native_code(engine, compiled).unwrap_or_else(|msg| {
        eprintln!("note: {msg}; running on the tape");
        None
    })
}

/// Says when the explicit method found the problem stiff ([`SimResult::stiff_since`]).
fn stiffness_note(result: &SimResult) {
    if let Some(t) = result.stiff_since {
        eprintln!(
            "note: the problem looks stiff from t = {t}: the explicit method's step size \
             is limited there by its stability, not by the tolerance (Hairer's test); an \
             implicit method (`--method radau5` or `bdf`) may take fewer steps"
        );
    }
}

/// Reports a `terminate()` and a failure; the exit code of the run.
fn how_it_ended(dae: &Dae, map: &SourceMap, result: &SimResult, start: f64) -> i32 {
    if let Some(msg) = &result.terminated {
        eprintln!(
            "note: terminate() at t = {}: {msg}",
            result.times.last().copied().unwrap_or(start)
        );
    }
    match &result.error {
        Some(e) => {
            report_failure(dae, map, e, result, start);
            EXIT_SIMULATION_FAILURE
        }
        None => EXIT_OK,
    }
}

/// The scalars written (all but parameters and constants) and the columns of them
/// that `--vars` selects; Err names an unknown selector.
fn output_columns(
    dae: &Dae,
    vars: &[String],
) -> Result<(Vec<unimo_dae::expr::ScalarId>, Vec<usize>), CliError> {
    let output_ids: Vec<unimo_dae::expr::ScalarId> = dae
        .ids()
        .filter(|&s| {
            !matches!(
                dae.scalar(s).kind,
                unimo_dae::dae::ScalarKind::Parameter | unimo_dae::dae::ScalarKind::Constant
            )
        })
        .collect();
    let all_names: Vec<String> = output_ids.iter().map(|&s| dae.name(s)).collect();
    let cols = select(&all_names, vars)?;
    Ok((output_ids, cols))
}

/// The experiment's settings with the command line's overrides.
fn sim_options(a: &SimulateArgs, dae: &Dae) -> Result<SimOptions, CliError> {
    let overrides = unimo_runtime::sim::Overrides {
        start: a.start,
        stop: a.stop_time,
        rtol: a.tolerance,
        atol: a.atol,
        interval: a.interval,
        points: a.points,
    };
    if !(a.output_tolerance >= 0.0 && a.output_tolerance.is_finite()) {
        return Err(CliError::BadOutputTolerance {});
    }
    let resolved = SimOptions::resolve(&dae.experiment, &overrides, method(a.method), a.every_step);
    resolved
        .map(|o| SimOptions {
            output_rtol: a.output_tolerance,
            ..o
        })
        .map_err(|why| CliError::BadOptions { why })
}

/// Runs the simulation; a progress bar on stderr for runs longer than a moment, when
/// it is a terminal (never in pipes, files or CI logs).
fn run(
    compiled: &CompiledModel,
    options: &SimOptions,
    sim_started: Instant,
    profile: Option<Arc<Mutex<Vec<Duration>>>>,
    row_sink: Option<(unimo_runtime::sim::RowSink<'_>, bool)>,
) -> SimResult {
    let (start, stop) = (options.start, options.stop);
    let bar = if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        let bar = indicatif::ProgressBar::new(1000);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} simulating [{bar:40}] t = {msg} ({elapsed})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
        Some(bar)
    } else {
        None
    };
    let shown_after = std::time::Duration::from_millis(500);
    let mut report = |t: f64| {
        if let Some(bar) = &bar {
            if bar.is_hidden() && sim_started.elapsed() > shown_after {
                bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            }
            bar.set_position((((t - start) / (stop - start)) * 1000.0) as u64);
            bar.set_message(format!("{t:.6e}"));
        }
    };
    let mut simulator = unimo_runtime::sim::Simulator::new(compiled);
    if let Some(sink) = profile {
        simulator = simulator.profile(sink);
    }
    if let Some((sink, keep_rows)) = row_sink {
        simulator = if keep_rows {
            simulator.on_row(sink)
        } else {
            simulator.on_row_only(sink)
        };
    }
    let result = simulator.run_with_progress(options, &mut report);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    result
}

/// The result format: `--format`, else from the output file's extension (`.mat`),
/// else CSV.
pub fn result_format(a: &SimulateArgs) -> ResultFormat {
    a.format.unwrap_or_else(|| {
        let mat = a
            .output
            .as_deref()
            .and_then(|p| p.extension())
            .is_some_and(|e| e.eq_ignore_ascii_case("mat"));
        if mat {
            ResultFormat::Mat
        } else {
            ResultFormat::Csv
        }
    })
}

/// Writes a MAT v4 result file (`--format mat`): the selected outputs, aliases as
/// such, and the parameters (with `--vars`, those the selectors name).
fn write_mat(
    a: &SimulateArgs,
    flat: &unimo_flat::FlatModel,
    dae: &Dae,
    result: &SimResult,
    ids: (&[unimo_dae::expr::ScalarId], &[usize]),
    span: (f64, f64),
) -> std::io::Result<()> {
    let Some(path) = a.output.as_deref() else {
        return Err(std::io::Error::other(
            "a MAT file is binary: give the file with --output",
        ));
    };
    let units = crate::results::units(flat);
    let keep = |name: &str| a.vars.is_empty() || select(&[name.to_owned()], &a.vars).is_ok();
    let vars = crate::results::variables(dae, &units, &result.initial_values, ids, &keep);
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    crate::results::mat::write(&mut f, &vars, &result.times, &result.rows, span)?;
    f.flush()
}

/// `E0020` for each `--tunable` name that covers no parameter of the model, with the
/// closest parameter name.
pub(crate) fn check_tunable(
    flat: &unimo_flat::FlatModel,
    fold: &unimo_dae::FoldOptions,
) -> Result<(), Vec<CliError>> {
    let unknown = unimo_dae::fold::unknown_tunable(flat, fold);
    if unknown.is_empty() {
        return Ok(());
    }
    let names: Vec<String> = flat
        .vars
        .iter()
        .filter(|v| v.variability == unimo_flat::flat::Variability::Parameter)
        .map(|v| v.name.trim_matches('\'').to_string())
        .collect();
    Err(unknown
        .iter()
        .map(|n| CliError::UnknownTunable {
            name: n.to_string(),
            suggestion: unimo_flat::resolve::suggest(n, names.clone()),
        })
        .collect())
}

/// Prints every error of `errors`; the exit code of the first.
pub(crate) fn report_all(errors: &[CliError]) -> i32 {
    errors
        .iter()
        .map(CliError::report)
        .reduce(|first, _| first)
        .unwrap_or(EXIT_OK)
}

/// The `--cost` table: per component instance, plan operations per evaluation (and
/// their share), zero crossings and states.
fn cost_table(
    m: &CompiledModel,
    depth: usize,
    r: &SimResult,
    simulate_ms: f64,
    profile: Option<Arc<Mutex<Vec<Duration>>>>,
) -> String {
    use std::fmt::Write as _;
    let step_seconds: Vec<f64> = profile
        .and_then(|p| {
            p.lock()
                .ok()
                .map(|v| v.iter().map(Duration::as_secs_f64).collect())
        })
        .unwrap_or_default();
    let rows = m.cost_by_component_timed(depth, &step_seconds);
    let total: f64 = rows.iter().map(|c| c.ops).sum();
    let seconds: f64 = rows.iter().map(|c| c.seconds).sum();
    let width = rows
        .iter()
        .map(|c| c.component.len())
        .chain([9])
        .max()
        .unwrap_or(9);
    let mut out = format!(
        "cost by component (instance depth {depth}):\n{:width$}  {:>8}  {:>6}  {:>9}  {:>6}  {:>14}  {:>6}\n",
        "component", "ops", "share", "time ms", "share", "zero crossings", "states"
    );
    let pct = |x: f64, of: f64| if of > 0.0 { 100.0 * x / of } else { 0.0 };
    for c in &rows {
        let _ = writeln!(
            out,
            "{:width$}  {:>8.1}  {:>5.1}%  {:>9.3}  {:>5.1}%  {:>14}  {:>6}",
            c.component,
            c.ops,
            pct(c.ops, total),
            c.seconds * 1e3,
            pct(c.seconds, seconds),
            c.zero_crossings,
            c.states
        );
    }
    let crossings: usize = rows.iter().map(|c| c.zero_crossings).sum();
    let states: usize = rows.iter().map(|c| c.states).sum();
    let _ = writeln!(
        out,
        "{:width$}  {:>8.1}  {:>5.1}%  {:>9.3}  {:>5.1}%  {:>14}  {:>6}",
        "total",
        total,
        100.0,
        seconds * 1e3,
        100.0,
        crossings,
        states
    );
    let _ = writeln!(
        out,
        "ops: plan operations per evaluation of the model; time: measured in each plan \
         step over this run ({} evaluations; {:.1} of the run's {:.1} ms went to \
         evaluating the plan, the rest to the solver, zero crossings, events and output), \
         an explicit step's time split by its operations, a block's equally among its \
         iteration variables",
        r.stats.rhs_evaluations,
        seconds * 1e3,
        simulate_ms
    );
    out
}

/// With `--engine native`, compiles the model's hot tapes to machine code (a model
/// above the size threshold keeps the tape: the statistics say so). Err: why the
/// native code generator failed (nothing is attached then).
fn native_code(
    engine: EngineArg,
    compiled: &mut CompiledModel,
) -> Result<Option<unimo_codegen::NativeStats>, String> {
    match engine {
        EngineArg::Tape => Ok(None),
        EngineArg::Native => unimo_codegen::compile_model(
            compiled,
            &unimo_codegen::NativeOptions::default(),
            unimo_runtime::native::execute_shim,
        )
        .map(Some)
        .map_err(|e| e.to_string()),
    }
}

/// The engine's part of the `--stats` line.
fn engine_stats(native: Option<&unimo_codegen::NativeStats>) -> String {
    match native {
        None => "\"engine\":\"tape\"".to_owned(),
        Some(n) => format!(
            "\"engine\":\"{}\",\"native\":{{\"tapes\":{},\"functions\":{},\"ops\":{},\"interpreted_ops\":{},\"code_bytes\":{},\"compile_ms\":{:.3},\"above_threshold\":{}}}",
            if n.above_threshold { "tape" } else { "native" },
            n.tapes,
            n.functions,
            n.native_ops,
            n.interpreted_ops,
            n.code_bytes,
            n.compile_ms,
            n.above_threshold
        ),
    }
}

/// Wall time of each phase of one run, in milliseconds: parsing the command-line
/// files, flattening (name lookup, with the library files the model reads), lowering
/// with alias elimination, the structural analysis, compiling the tapes, compiling them
/// to machine code, simulating (and inside it, in `run`, initialization, integration
/// with its evaluation and linear-algebra shares, events and the rows kept), writing
/// the result file.
#[derive(Clone, Debug, Default)]
struct Phases {
    parse: f64,
    flatten: f64,
    lower: f64,
    structure: f64,
    compile: f64,
    native: f64,
    simulate: f64,
    run: unimo_runtime::sim::RunTimes,
    write: f64,
}

impl Phases {
    /// Everything before the simulation.
    fn before_run(&self) -> f64 {
        self.parse + self.flatten + self.lower + self.structure + self.compile + self.native
    }

    fn json(&self) -> String {
        let r = &self.run;
        let ms = |seconds: f64| seconds * 1e3;
        format!(
            "{{\"parse\":{:.3},\"flatten\":{:.3},\"lower\":{:.3},\"structure\":{:.3},\"compile\":{:.3},\"native\":{:.3},\"simulate\":{:.3},\"initialize\":{:.3},\"integrate\":{:.3},\"evaluation\":{:.3},\"linear_algebra\":{:.3},\"events\":{:.3},\"output\":{:.3},\"write\":{:.3}}}",
            self.parse,
            self.flatten,
            self.lower,
            self.structure,
            self.compile,
            self.native,
            self.simulate,
            ms(r.initialize),
            ms(r.integrate),
            ms(r.evaluation),
            ms(r.linear_algebra),
            ms(r.events),
            ms(r.output),
            self.write
        )
    }
}

fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The `--stats` line: one JSON object on stderr. `compile_ms` is everything before
/// the simulation (load, analysis, tapes and native code), `phases_ms` each phase.
fn print_stats(
    method: Method,
    compiled: &CompiledModel,
    plan: &Plan,
    result: &SimResult,
    phases: &Phases,
    native: Option<&unimo_codegen::NativeStats>,
) {
    let compile_ms = phases.before_run();
    let simulate_ms = phases.simulate;
    let s = &result.stats;
    let collision = match &s.collision {
        Some(c) => format!(
            ",\"collision\":{{\"bodies\":{},\"evaluations\":{},\"broadphase_tests\":{},\"narrowphase_pairs\":{},\"impulses\":{},\"contact_changes\":{}}}",
            compiled.collision.as_ref().map_or(0, |c| c.bodies.len()),
            c.evaluations,
            c.broadphase_tests,
            c.narrowphase_pairs,
            c.impulses,
            c.contact_changes
        ),
        None => String::new(),
    };
    let projection = match &s.projection {
        Some(p) => format!(
            ",\"projection\":{{\"projections\":{},\"evaluations\":{},\"jacobians\":{}}}",
            p.projections, p.evaluations, p.jacobians
        ),
        None => String::new(),
    };
    eprintln!(
        "{{\"method\":\"{}\",\"states\":{},\"steps\":{},\"rejected\":{},\"rhs\":{},\"jacobians\":{},\"lu\":{},\"newton\":{},\"events\":{},\"event_iterations\":{},\"plan_evaluations\":{},\"state_selections\":{},\"pruned_equations\":{},\"parameters_folded\":{},\"plan_ops\":{},\"zero_crossings\":{},\"jacobian_nonzeros\":{},\"sparse_lu\":{},\"linear_solver\":{},\"compile_ms\":{:.3},\"simulate_ms\":{:.3},\"phases_ms\":{},{}{}{}}}",
        format!("{method:?}").to_lowercase(),
        compiled.states.len(),
        s.solver.steps,
        s.solver.rejected_steps,
        s.solver.rhs_evals,
        s.solver.jacobian_evals,
        s.solver.lu_factorizations,
        s.solver.newton_iterations,
        s.events,
        s.event_iterations,
        s.rhs_evaluations,
        s.state_selections,
        plan.stats.pruned_equations,
        plan.stats.parameters_folded,
        compiled.plan_ops(),
        compiled.roots.len(),
        s.jacobian_nonzeros
            .map_or_else(|| "null".to_string(), |n| n.to_string()),
        s.sparse_lu,
        s.linear_solver
            .map_or_else(|| "null".to_string(), |k| format!("\"{}\"", k.name())),
        compile_ms,
        simulate_ms,
        phases.json(),
        engine_stats(native),
        collision,
        projection
    );
}

/// Reports a failed run: the error, the equation that went non-finite and the rows
/// that were kept.
fn report_failure(dae: &Dae, map: &SourceMap, e: &SimError, result: &SimResult, start: f64) {
    eprintln!("error[{}]: {}", e.code(), e.message());
    if let SimError::NonFinite {
        equation: Some(eq), ..
    } = e
    {
        let equation = &dae.equations[eq.index()];
        let mut text = String::new();
        let name = |s| dae.name(s);
        let _ = dae.arena.write(equation.lhs, &name, &mut text);
        text.push_str(" = ");
        let _ = dae.arena.write(equation.rhs, &name, &mut text);
        eprintln!(
            "note: equation #{} is `{text}` ({})",
            eq.0,
            map.location(equation.origin)
        );
    }
    eprintln!(
        "note: {} rows up to t = {} were kept",
        result.times.len(),
        result.times.last().copied().unwrap_or(start)
    );
}
