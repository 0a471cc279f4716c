//! The `unimo` command line. The only crate that reads user files, renders diagnostics
//! and writes to the terminal; every other crate returns data.
//!
//! Exit codes, for the whole tool: 0 success, 1 errors in the model, 2 usage errors
//! (bad flags, missing files), 3 simulation failure.

mod check;
mod provider;
pub mod render;

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
    /// Every top-level model that no other class of its file uses is flattened and its
    /// equations and unknowns counted. Exits 0 when every file is clean, 1 when any has
    /// an error.
    Check {
        /// Files or folders to check.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
        /// Print counts after checking: files, classes, bytes, library files and
        /// classes loaded (the library is loaded lazily: only what the files use), time.
        #[arg(long)]
        stats: bool,
        /// Add a library folder (searched before UNIMO_PATH and the bundled library).
        #[arg(long = "lib", value_name = "DIR")]
        libs: Vec<PathBuf>,
        /// Skip flattening and the balance check: syntax and names only.
        #[arg(long)]
        no_balance: bool,
    },
    /// Instantiate a model and print it as flat Modelica.
    ///
    /// Variables get their full instance names (quoted when dotted), modifiers are
    /// merged, `for` equations unrolled and connections turned into equations. The
    /// output parses back with unimo.
    Flatten {
        /// The Modelica file with the model, then any other files it uses.
        #[arg(required = true, value_name = "FILE")]
        files: Vec<PathBuf>,
        /// The model to flatten (full dotted name); may be omitted when the file has
        /// exactly one non-partial model.
        #[arg(long, value_name = "NAME")]
        model: Option<String>,
        /// Add a library folder (searched before UNIMO_PATH and the bundled library).
        #[arg(long = "lib", value_name = "DIR")]
        libs: Vec<PathBuf>,
        /// Print equation and unknown counts to stderr.
        #[arg(long)]
        stats: bool,
    },
    /// Print an intermediate representation of a file.
    Emit {
        /// Which stage to print.
        #[arg(long, value_enum, default_value_t = Stage::Ast)]
        stage: Stage,
        /// The Modelica file.
        #[arg(value_name = "FILE")]
        file: PathBuf,
    },
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Stage {
    /// The syntax tree, one node a line with its line:col.
    Ast,
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
        } => check::check(&paths, &libs, stats, !no_balance, color),
        Command::Flatten {
            files,
            model,
            libs,
            stats,
        } => check::flatten(&files, model.as_deref(), &libs, stats, color),
        Command::Emit { stage, file } => match stage {
            Stage::Ast => check::emit_ast(&file, color),
        },
    }
}
