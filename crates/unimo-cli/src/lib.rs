//! The `unimo` command line. The only crate that reads user files, renders diagnostics
//! and writes to the terminal; every other crate returns data.
//!
//! Exit codes, for the whole tool: 0 success, 1 errors in the model, 2 usage errors
//! (bad flags, missing files), 3 simulation failure.

pub mod animate;
pub mod api;
mod bench;
mod check;
pub mod codes;
pub mod error;
pub mod fmu;
mod numfmt;
mod params;
pub mod plot;
mod provider;
pub mod render;
pub mod results;
mod simulate;
mod stages;
pub mod sweep;

use clap::{Parser, Subcommand, ValueEnum};
use std::io::IsTerminal;
use std::path::PathBuf;

/// Exit code: everything went fine.
pub const EXIT_OK: i32 = 0;
/// Exit code: the model has errors.
pub const EXIT_MODEL_ERROR: i32 = 1;
/// Exit code: the command line was wrong (unknown flag, missing file).
pub const EXIT_USAGE: i32 = 2;
/// Exit code: an internal error (a bug in unimo; the panic message says where).
pub const EXIT_INTERNAL: i32 = 101;
/// Exit code: a simulation failed.
pub const EXIT_SIMULATION_FAILURE: i32 = 3;

#[derive(Parser, Debug)]
#[command(
    name = "unimo",
    version,
    about = "Acausal Modelica-subset compiler and hybrid DAE simulator",
    long_about = "unimo compiles models written in a subset of Modelica (see docs/language.md) \
                  and checks them.\n\nExit codes: 0 success, 1 model errors, 2 usage errors, \
                  3 simulation failure.",
    after_help = "Examples:\n  unimo check stdlib models     check every .mo file below two folders\n  \
                  unimo emit --stage ast models/BouncingBall.mo"
)]
struct Cli {
    /// When to colour diagnostics.
    #[arg(long, value_enum, default_value_t = ColorWhen::Auto, global = true)]
    color: ColorWhen,
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ColorWhen {
    Auto,
    Always,
    Never,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Check Modelica files: syntax, names, and the balance of every model.
    ///
    /// PATHs may be files or folders; folders are searched recursively for `*.mo`.
    /// Every top-level model that no other class of its file uses is flattened, its
    /// equations and unknowns counted, and it is analysed as for simulation (lowering,
    /// alias elimination, index reduction, BLT, tearing); `--stats` prints the counts
    /// after each step per model. Exits 0 when every file is clean, 1 when any has
    /// an error.
    Check {
        /// Files or folders to check.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
        /// Print counts after checking: files, classes, bytes, library files and
        /// classes loaded (the library is loaded lazily: only what the files use), time.
        #[arg(long)]
        stats: bool,
        /// Add a library folder (searched before MODELICAPATH, UNIMO_PATH and the bundled library).
        #[arg(long = "lib", value_name = "DIR")]
        libs: Vec<PathBuf>,
        /// Skip flattening and the balance check: syntax and names only.
        #[arg(long)]
        no_balance: bool,
        /// Skip the back end (lowering, alias elimination, index reduction, BLT):
        /// syntax, names, flattening and balance only.
        #[arg(long)]
        no_analysis: bool,
    },
    /// Instantiate a model and print it as flat Modelica.
    ///
    /// Variables get their full instance names (quoted when dotted), modifiers are
    /// merged, `for` equations unrolled and connections turned into equations. The
    /// output parses back with unimo.
    Flatten {
        #[command(flatten)]
        source: ModelArgs,
        /// Print equation and unknown counts to stderr.
        #[arg(long)]
        stats: bool,
    },
    /// Simulate a model and write its results as CSV.
    ///
    /// Compiles the model (flattening, lowering, alias elimination, index reduction,
    /// BLT, tearing), initializes it consistently and integrates it with one of
    /// unimo's solvers, handling events with Modelica semantics. Defaults for the time
    /// span, tolerance and output interval come from `annotation(experiment(...))`.
    ///
    /// The CSV has a header `time,<names>` and one row per output point, plus two rows
    /// (left and right limit) at every event. On a solver failure the exit code is 3 and
    /// the CSV keeps every row computed up to the failure. `--output x.mat` (or
    /// `--format mat`) writes the same rows as a MAT v4 file in the Dymola/OpenModelica
    /// layout, with the parameters, descriptions, units and aliases.
    ///
    /// Parameters: `-p e=0.5 -p h0=2`, or `--override-file FILE` with one `name=value` a
    /// line (`#` comments); `--list-params` prints them all. See docs/simulate.md.
    ///
    /// Example: `unimo simulate models/BouncingBall.mo -p e=0.5 -o ball.mat`.
    Simulate(SimulateArgs),
    /// Measure error against run time: every model x method x tolerance.
    ///
    /// Each configuration runs `--runs` times; the table gives the median wall time,
    /// the steps, and the error against a reference (the `--reference` CSV, or a very
    /// tight Radau5 run): scd = -log10(max relative error) over the variables at the
    /// end time, and the worst scd over the output grid. `--plot` writes a
    /// work-precision diagram (SVG).
    Bench(BenchArgs),
    /// Run a parameter sweep on threads and write one CSV row per point.
    ///
    /// Each `-p` gives a parameter's values: `k=0.5:0.9:5` (5 points from 0.5 to 0.9),
    /// `f=0.05,0.1` (a list) or `h0=2`; the sweep runs every combination. Each worker
    /// thread parses the model once and compiles it per point with the point's values
    /// as modifiers (as `simulate -p` does). A point that fails keeps its error code and
    /// message in its row while the others run. Columns: the parameters, `status`
    /// (`ok` or `failed`), `error_code`, `error_message`, then the final value of
    /// `time` and of every variable (or of `--vars`). Exits 3 when a point failed.
    ///
    /// Example: `unimo sweep models/BouncingBall.mo -p e=0.5:0.9:5 -p h0=1,2 --jobs 2 -o sweep.csv`.
    Sweep(SweepArgs),
    /// Plot columns of a result CSV as an SVG line chart.
    ///
    /// Each `--vars` column is a line against `--x` (default `time`); any column may
    /// be the horizontal axis, for phase plots (e.g. a contact point's x against its
    /// z). Long series are thinned to `--max-points` keeping each bucket's extremes,
    /// so event jumps and peaks stay visible.
    ///
    /// Example: `unimo plot result.csv --vars t --x time -o time.svg`.
    Plot(plot::PlotArgs),
    Animate(animate::command::AnimateArgs),
    /// Export a model as an FMU (FMI 2.0 or 3.0, Model Exchange or Co-Simulation).
    ///
    /// The FMU holds `modelDescription.xml` (every variable with causality,
    /// variability, initial, start, unit and description; derivatives, event
    /// indicators, model structure), the flat model in `resources/model.mo` and the
    /// shared library `binaries/<platform>/<id>.so`, which compiles the model at
    /// instantiation and runs it on unimo's runtime. The library is `libunimo_fmi.so`
    /// next to the `unimo` executable (or `UNIMO_FMI_LIBRARY`). See docs/fmi.md.
    ///
    /// Example: `unimo fmu models/BouncingBall.mo --fmi 2 --kind me -o BouncingBall.fmu`.
    Fmu(fmu::FmuArgs),
    /// Print an intermediate representation of a model.
    ///
    /// Stages in pipeline order: `ast` (syntax tree of the first file), `flat` (as
    /// `unimo flatten`), `dae` (scalarized hybrid DAE: variables by kind, equations,
    /// `when` clauses, zero crossings), `structure` (the causal plan: states, index
    /// reduction, dummy derivatives, blocks with their iteration variables).
    Emit {
        /// Which stage to print.
        #[arg(long, value_enum, default_value_t = Stage::Ast)]
        stage: Stage,
        #[command(flatten)]
        source: ModelArgs,
        /// Keep these parameters tunable (see `simulate --tunable`): the DAE, structure
        /// and tape name them instead of showing their folded values.
        #[arg(long, value_delimiter = ',', value_name = "P,Q.R")]
        tunable: Vec<String>,
        /// Keep every parameter tunable.
        #[arg(long, conflicts_with = "tunable")]
        tunable_all: bool,
    },
}

/// The model a command works on: its files, its name, the library folders (`flatten`,
/// `emit`, `simulate`, `sweep`, `fmu`).
#[derive(clap::Args, Debug, Clone)]
pub struct ModelArgs {
    /// The Modelica file with the model, then any other files it uses (none when
    /// --model names a class of a library: --lib, MODELICAPATH).
    #[arg(required_unless_present = "model", value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// The model (full dotted name); may be omitted when the file has one
    /// non-partial model (or one that no other model of the file uses).
    #[arg(long, value_name = "NAME")]
    pub model: Option<String>,
    /// Add a library folder (searched before MODELICAPATH, UNIMO_PATH and the bundled library).
    #[arg(long = "lib", value_name = "DIR")]
    pub libs: Vec<PathBuf>,
}

impl ModelArgs {
    /// The model as the API loads it (the files read from disk), with `fold`'s choice
    /// of tunable parameters.
    pub fn source(&self, fold: unimo_dae::FoldOptions) -> api::Source {
        api::Source {
            files: self.files.iter().map(|f| (f.clone(), None)).collect(),
            model: self.model.clone(),
            libs: self.libs.clone(),
            fold,
        }
    }
}

#[derive(clap::Args, Debug, Clone)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub source: ModelArgs,
    /// Start time [default: experiment StartTime, else 0].
    #[arg(long, value_name = "T0")]
    pub start: Option<f64>,
    /// Stop time [default: experiment StopTime, else 1].
    #[arg(long = "stop-time", value_name = "T")]
    pub stop_time: Option<f64>,
    /// Relative tolerance [default: experiment Tolerance, else 1e-6].
    #[arg(long, value_name = "RTOL")]
    pub tolerance: Option<f64>,
    /// Absolute tolerance, scaled per state by its `nominal` [default: RTOL / 100].
    #[arg(long, value_name = "ATOL")]
    pub atol: Option<f64>,
    /// Integration method: `auto` (the model's `experiment(__unimo_method = ...)`, else
    /// BDF), `bdf`, `radau5` (tight tolerances) or `dopri5` (explicit, non-stiff).
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    pub method: MethodArg,
    /// Output interval [default: experiment Interval, else (stop - start) / 500].
    #[arg(long, value_name = "DT", conflicts_with = "points")]
    pub interval: Option<f64>,
    /// Number of output intervals (instead of --interval).
    #[arg(long, value_name = "N")]
    pub points: Option<usize>,
    /// Also write a row after every internal solver step.
    #[arg(long)]
    pub every_step: bool,
    /// Rows between the grid's points: wherever a straight line between the written
    /// rows would miss a state by more than TOL times the state's largest magnitude so
    /// far, the solver step that keeps the line within it is written too, so plots and
    /// linear interpolation of the result follow the solution. 0: the grid and the
    /// events only.
    #[arg(long, value_name = "TOL", default_value_t = unimo_runtime::sim::OUTPUT_RTOL)]
    pub output_tolerance: f64,
    /// Write the results here instead of standard output.
    #[arg(long, short, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Result format: `csv`, or `mat` (MAT v4 in the Dymola/OpenModelica `dsres`
    /// layout, read by DyMat, scipy.io.loadmat, OMPlot). Default: `mat` when
    /// --output ends in `.mat`, else `csv`.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub format: Option<ResultFormat>,
    /// Only these variables (comma separated; `body` selects every `body.*` and
    /// `body[...]`). Variables nothing else needs are then left out of the computation.
    #[arg(long, value_name = "A,B.C", value_delimiter = ',')]
    pub vars: Vec<String>,
    /// Print run statistics as one JSON object to stderr.
    #[arg(long)]
    pub stats: bool,
    /// Keep these parameters tunable (comma separated; a record or array name covers
    /// its fields and elements). Every other parameter whose value is known is folded
    /// into the compiled model as a constant, with what it switches off: terms
    /// multiplied by zero, `if` branches that cannot be taken, relations that cannot
    /// change (no zero crossing). Parameters computed by initial equations
    /// (`fixed = false`) and those bound to a tunable one are never folded.
    #[arg(long, value_name = "P,Q.R", value_delimiter = ',')]
    pub tunable: Vec<String>,
    /// After the run, print where the work goes (stderr): per component instance, at
    /// DEPTH levels of the instance tree [default: 1], the plan operations per
    /// evaluation, the time spent evaluating them in this run (every plan step is timed)
    /// with their shares, the zero crossings and the states.
    #[arg(long, value_name = "DEPTH", num_args = 0..=1, default_missing_value = "1")]
    pub cost: Option<usize>,
    /// Keep every parameter tunable: fold only constants, parameters declared with
    /// `annotation(Evaluate = true)` and parameters bound to those alone.
    #[arg(long, conflicts_with = "tunable")]
    pub tunable_all: bool,
    /// Set a parameter: `-p e=0.5 -p h0=2` (repeatable). Values are checked against
    /// the declaration: a number for Real, an integer for Integer, `true`/`false` for
    /// Boolean, a literal's name for an enumeration. Unknown names, `final` parameters,
    /// constants and values of the wrong type are errors (exit code 2). The model is
    /// flattened again with the values as modifiers, so parameters that set array
    /// sizes or `for` ranges can be changed too.
    #[arg(short = 'p', long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Read parameter settings from a file: one `name=value` a line, `#` comments.
    /// `-p` flags are applied after it and win.
    #[arg(long, value_name = "FILE")]
    pub override_file: Option<PathBuf>,
    /// Print every parameter (value, unit, whether it can change without
    /// recompiling, description) instead of simulating; overrides are applied first.
    #[arg(long)]
    pub list_params: bool,
    /// How the compiled model is evaluated: `native` (the hot tapes compiled to machine
    /// code with Cranelift; the same results, bit for bit) or `tape` (the register-tape
    /// interpreter). A model above the native size threshold (120,000 instructions)
    /// runs on the tape either way; `--stats` says which engine ran.
    #[arg(long, value_enum, default_value_t = EngineArg::Native)]
    pub engine: EngineArg,
    /// Also write a 3D animation of the run as a self-contained HTML page (see
    /// `unimo animate` and docs/animation.md).
    #[arg(long, value_name = "FILE.html")]
    pub animate: Option<PathBuf>,
}

#[derive(clap::Args, Debug, Clone)]
pub struct BenchArgs {
    /// Model files (each must hold one model, or use --model for all).
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// The model name, when the files hold several.
    #[arg(long, value_name = "NAME")]
    pub model: Option<String>,
    /// Add a library folder.
    #[arg(long = "lib", value_name = "DIR")]
    pub libs: Vec<PathBuf>,
    /// Methods to compare, comma-separated (`--methods bdf,radau5`).
    #[arg(long, value_name = "M,...", value_enum, value_delimiter = ',', default_values_t = [MethodArg::Bdf, MethodArg::Radau5])]
    pub methods: Vec<MethodArg>,
    /// Relative tolerances, comma-separated (`--tolerances 1e-4,1e-6`).
    #[arg(long, value_name = "RTOL,...", value_delimiter = ',', default_values_t = [1e-4, 1e-6, 1e-8, 1e-10])]
    pub tolerances: Vec<f64>,
    /// Absolute tolerance as a multiple of the relative one.
    #[arg(long, value_name = "F", default_value_t = 1e-2)]
    pub atol_factor: f64,
    /// Reference results (CSV as written by `simulate`); columns are matched by name.
    #[arg(long, value_name = "CSV")]
    pub reference: Option<PathBuf>,
    /// Runs per configuration (the median is reported).
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Output intervals for the grid error.
    #[arg(long, default_value_t = 100)]
    pub points: usize,
    /// Stop time [default: the model's experiment StopTime].
    #[arg(long = "stop-time", value_name = "T")]
    pub stop_time: Option<f64>,
    /// Write a work-precision plot (SVG) here.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Variables whose values at the end each run reports with their relative error
    /// against the reference, below its row (counters such as `Impacts`, event times
    /// such as `tFirstRolling`).
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    pub quantities: Vec<String>,
    /// How the compiled model is evaluated, as `simulate --engine`: `native` (machine code,
    /// compiled once before the timed runs) or `tape` (the interpreter).
    #[arg(long, value_enum, default_value_t = EngineArg::Native)]
    pub engine: EngineArg,
}

#[derive(clap::Args, Debug, Clone)]
pub struct SweepArgs {
    #[command(flatten)]
    pub source: ModelArgs,
    /// A parameter's values: `k=0.5:0.9:5` (n points from a to b), `f=0.05,0.1`, `h0=2`.
    #[arg(short = 'p', long = "param", value_name = "NAME=VALUES")]
    pub params: Vec<String>,
    /// Worker threads [default: every core].
    #[arg(long, short = 'j', value_name = "N")]
    pub jobs: Option<usize>,
    /// Write the table here instead of standard output.
    #[arg(long, short, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Report only these variables' final values (comma separated, as `simulate --vars`).
    #[arg(long, value_name = "A,B.C", value_delimiter = ',')]
    pub vars: Vec<String>,
    /// Stop time [default: experiment StopTime].
    #[arg(long = "stop-time", value_name = "T")]
    pub stop_time: Option<f64>,
    /// Relative tolerance [default: experiment Tolerance, else 1e-6].
    #[arg(long, value_name = "RTOL")]
    pub tolerance: Option<f64>,
    /// Integration method.
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    pub method: MethodArg,
    /// Keep these parameters tunable (see `simulate --tunable`).
    #[arg(long, value_name = "P,Q.R", value_delimiter = ',')]
    pub tunable: Vec<String>,
}

/// The format of `simulate`'s result file.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ResultFormat {
    /// Comma-separated text, a header `time,<names>`.
    Csv,
    /// MAT v4, the result format of Dymola and OpenModelica.
    Mat,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum EngineArg {
    /// The register-tape interpreter.
    Tape,
    /// Machine code compiled with Cranelift (`unimo-codegen`).
    Native,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum MethodArg {
    Auto,
    Bdf,
    Radau5,
    Dopri5,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
enum Stage {
    /// The syntax tree, one node a line with its line:col.
    Ast,
    /// The flat model as flat Modelica.
    Flat,
    /// The hybrid DAE after lowering.
    Dae,
    /// The structural analysis and causal plan.
    Structure,
    /// The compiled model: every tape the simulator runs, one instruction a line.
    Tape,
}

/// Runs the command line and returns the process exit code.
///
/// The work runs on a thread with a large stack: the compiler's passes are recursive
/// over expression trees, and generated models can nest deeply.
pub fn run() -> i32 {
    std::thread::Builder::new()
        .name("unimo".into())
        .stack_size(512 << 20)
        .spawn(run_on_this_thread)
        .map(|h| h.join().unwrap_or(EXIT_INTERNAL))
        .unwrap_or_else(|_| run_on_this_thread())
}

fn run_on_this_thread() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
        }
    };
    let color = match cli.color {
        ColorWhen::Always => true,
        ColorWhen::Never => false,
        ColorWhen::Auto => std::io::stderr().is_terminal(),
    };
    match cli.command {
        Command::Check {
            paths,
            stats,
            libs,
            no_balance,
            no_analysis,
        } => check::check(&paths, &libs, stats, !no_balance, !no_analysis, color),
        Command::Flatten { source: m, stats } => {
            check::flatten(&m.files, m.model.as_deref(), &m.libs, stats, color)
        }
        Command::Simulate(args) => simulate::simulate(&args, color),
        Command::Bench(args) => bench::bench(&args, color),
        Command::Sweep(args) => sweep::command(&args),
        Command::Plot(args) => plot::plot(&args),
        Command::Animate(args) => animate::command::command(&args),
        Command::Fmu(args) => fmu::command(&args),
        Command::Emit {
            stage,
            source: m,
            tunable,
            tunable_all,
        } => match stage {
            Stage::Ast => match m.files.first() {
                Some(file) => check::emit_ast(file, color),
                None => error::CliError::AstNeedsFile {}.report(),
            },
            Stage::Flat => check::flatten(&m.files, m.model.as_deref(), &m.libs, false, color),
            Stage::Dae | Stage::Structure | Stage::Tape => {
                let fold = unimo_dae::FoldOptions {
                    tunable_all,
                    tunable,
                };
                let back = match stage {
                    Stage::Dae => stages::BackStage::Dae,
                    Stage::Structure => stages::BackStage::Structure,
                    _ => stages::BackStage::Tape,
                };
                stages::emit(back, &m.files, m.model.as_deref(), &m.libs, &fold, color)
            }
        },
    }
}

/// A model compiled for simulation, for tests and benchmarks that drive the library
/// directly: the DAE, its causal plan and the compiled tapes.
pub struct LoadedModel {
    pub dae: unimo_dae::Dae,
    pub analysis: unimo_dae::analysis::Analysis,
    pub compiled: unimo_codegen::model::CompiledModel,
}

/// Reads, flattens, lowers, analyses and compiles a model; errors come back as the
/// plain-text diagnostics.
pub fn load_model(files: &[PathBuf], model: Option<&str>) -> Result<LoadedModel, String> {
    load_model_with(files, model, &unimo_dae::FoldOptions::default())
}

/// [`load_model`] with a choice of the parameters kept tunable (the others are folded).
pub fn load_model_with(
    files: &[PathBuf],
    model: Option<&str>,
    fold: &unimo_dae::FoldOptions,
) -> Result<LoadedModel, String> {
    let provider = provider::CliProvider::new(&[]);
    let mut tree = unimo_flat::ClassTree::new(&provider);
    let mut first = None;
    for f in files {
        let text = std::fs::read_to_string(f).map_err(|e| format!("{}: {e}", f.display()))?;
        let id = tree.sources.add(f.clone(), text);
        let parsed = unimo_syntax::parse(id, tree.sources.get(id).text());
        if parsed.has_errors() {
            return Err(render_all(&parsed.diagnostics, &tree.sources));
        }
        let classes = tree.add_user_file(id, parsed.ast);
        first.get_or_insert(classes);
    }
    let classes = first.unwrap_or_default();
    let class = check::pick(&mut tree, &classes, model).map_err(|e| e.line())?;
    let (flat, diags) = unimo_flat::flatten(&mut tree, class);
    if diags.iter().any(|d| d.is_error()) {
        return Err(render_all(&diags, &tree.sources));
    }
    let (dae, analysis) =
        unimo_dae::analyze_model_with(&flat, fold).map_err(|d| render_all(&d, &tree.sources))?;
    let compiled = unimo_codegen::model::compile(&dae, &analysis.plan);
    Ok(LoadedModel {
        dae,
        analysis,
        compiled,
    })
}

fn render_all(diags: &[unimo_source::Diagnostic], map: &unimo_source::SourceMap) -> String {
    diags
        .iter()
        .map(|d| render::render_plain(d, map))
        .collect::<Vec<_>>()
        .join("\n")
}
