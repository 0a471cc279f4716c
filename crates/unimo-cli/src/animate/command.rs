//! The command line of the animation: `unimo animate` and `simulate --animate`
//! (arguments, the page written to its file, errors printed with exit codes).

use super::{AnimateOptions, AnimateSource, ResultTable};
use crate::api::ApiError;
use crate::error::CliError;
use crate::EXIT_OK;
use std::path::{Path, PathBuf};

/// Write a 3D animation of a result as one self-contained HTML page (three.js).
///
/// The bodies are the model's components whose class declares
/// `annotation(__unimo_visual(...))`: the bundled libraries' collision bodies
/// (`Unimo.Collision`) and paper A's bodies and planes (`UnilateralMBS`); your own
/// classes can declare it too (docs/animation.md). Dimensions come from the model
/// (compiled with the parameter values `-p` gives, as the run was), positions and
/// rotations from the result's columns. Open the page in a browser: play, pause,
/// scrub, speed; drag to turn the view, wheel to zoom.
#[derive(clap::Args, Debug, Clone)]
pub struct AnimateArgs {
    /// The result, a CSV as `unimo simulate` writes it.
    #[arg(value_name = "RESULT.csv")]
    pub result: PathBuf,
    /// The model's file (then any other files it uses).
    #[arg(long = "model", value_name = "MODEL.mo", required = true)]
    pub files: Vec<PathBuf>,
    /// The model's full name, when the file has several.
    #[arg(long = "class", value_name = "NAME")]
    pub class: Option<String>,
    /// Add a library folder (searched before MODELICAPATH, UNIMO_PATH and the bundled library).
    #[arg(long = "lib", value_name = "DIR")]
    pub libs: Vec<PathBuf>,
    /// A parameter value the run used (as `simulate -p`); repeat for several.
    #[arg(short = 'p', long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// The page to write.
    #[arg(long, short, value_name = "FILE", default_value = "scene.html")]
    pub output: PathBuf,
    /// The column used as the clock (e.g. a physical time `t` when `time` is a
    /// regularised time).
    #[arg(long, value_name = "NAME", default_value = "time")]
    pub clock: String,
    /// Frames at most: with more rows, the last row at or before each of N evenly
    /// spaced clock values.
    #[arg(long, value_name = "N", default_value_t = 4000)]
    pub max_frames: usize,
    /// The world axis drawn up [default: the first plane's normal, else z].
    #[arg(long, value_enum)]
    pub up: Option<Axis>,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl AnimateArgs {
    fn options(&self) -> AnimateOptions {
        let name = self.files.first().map_or("model".into(), |f| {
            f.file_stem()
                .map_or("model".into(), |s| s.to_string_lossy().into_owned())
        });
        AnimateOptions {
            clock: self.clock.clone(),
            max_frames: self.max_frames,
            up: self.up.map(|a| a as usize),
            title: self.class.clone().unwrap_or(name),
        }
    }
}

/// `unimo animate`.
pub fn command(a: &AnimateArgs) -> i32 {
    let mut params = Vec::new();
    for p in &a.params {
        match p.split_once('=') {
            Some((n, v)) => params.push((n.trim().to_owned(), v.trim().to_owned())),
            None => return CliError::NotNameValueFlag { text: p.clone() }.report(),
        }
    }
    let source = AnimateSource {
        result: a.result.clone(),
        model: crate::api::Source {
            files: a.files.iter().map(|f| (f.clone(), None)).collect(),
            model: a.class.clone(),
            libs: a.libs.clone(),
            fold: Default::default(),
        },
        params,
    };
    let page = crate::api::on_large_stack(|| super::page_from_files(&source, &a.options()));
    finish(page, &a.output)
}

/// Writes the page, or prints the error; the exit code.
fn finish(page: Result<String, ApiError>, output: &Path) -> i32 {
    match page {
        Ok(html) => match std::fs::write(output, html) {
            Ok(()) => {
                eprintln!("wrote {}", output.display());
                EXIT_OK
            }
            Err(e) => CliError::CannotWrite {
                what: format!("`{}`", output.display()),
                reason: e.to_string(),
            }
            .report(),
        },
        Err(e) => {
            eprintln!("{}", e.rendered);
            e.kind.exit_code()
        }
    }
}

/// `simulate --animate FILE`: the page of the run just made (the written columns).
pub fn after_run(
    output: &Path,
    flat: &unimo_flat::FlatModel,
    dae: &unimo_dae::Dae,
    result: &unimo_runtime::sim::SimResult,
    cols: &[usize],
) -> i32 {
    let mut names = vec!["time".to_owned()];
    names.extend(cols.iter().map(|&c| result.names[c].clone()));
    let rows = result
        .times
        .iter()
        .zip(&result.rows)
        .map(|(t, row)| {
            std::iter::once(*t)
                .chain(cols.iter().map(|&c| row[c]))
                .collect()
        })
        .collect();
    let table = ResultTable::new(names, rows);
    let constants = super::constants(dae, &result.initial_values);
    let options = AnimateOptions {
        title: flat.name.clone(),
        ..Default::default()
    };
    finish(super::page(flat, &constants, &table, &options), output)
}
