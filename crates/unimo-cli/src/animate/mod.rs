//! `unimo animate` and `simulate --animate`: a self-contained HTML page (three.js)
//! that plays a result in 3D. The bodies are the model's components whose class
//! declares `annotation(__unimo_visual(...))` (docs/animation.md); their dimensions
//! come from the model, their positions and rotations from the result's columns.
//! Never prints: errors are coded `ApiError`s (`E0070`–`E0075`).

pub mod command;
mod page;
mod spec;
mod table;

pub use spec::{Body, Rotation, Series, Shape};
pub use table::ResultTable;

use crate::api::{self, ApiError};
use crate::error::CliError;
use std::collections::HashMap;
use std::path::PathBuf;
use unimo_flat::FlatModel;

/// How to draw: the clock column, the number of frames, the up axis, the title.
#[derive(Clone, Debug)]
pub struct AnimateOptions {
    /// The column that is the clock (`time`, or e.g. a physical time `t`).
    pub clock: String,
    /// Frames at most (rows are picked evenly in the clock when there are more).
    pub max_frames: usize,
    /// The world axis shown up (0 x, 1 y, 2 z); `None`: the first plane's normal,
    /// else z.
    pub up: Option<usize>,
    pub title: String,
}

impl Default for AnimateOptions {
    fn default() -> Self {
        AnimateOptions {
            clock: "time".into(),
            max_frames: 4000,
            up: None,
            title: "unimo".into(),
        }
    }
}

/// The page for a result table of a model: `constants` are the values of the model's
/// parameters and constants by scalar name (`body.dims[1]`).
pub fn page(
    flat: &FlatModel,
    constants: &HashMap<String, f64>,
    table: &ResultTable,
    options: &AnimateOptions,
) -> Result<String, ApiError> {
    if flat.visuals.is_empty() {
        return Err(CliError::NothingToDraw {
            model: flat.name.clone(),
        }
        .into());
    }
    let model = spec::ModelValues { flat, constants };
    let bodies = spec::bodies(&model, table)?;
    let clock = &options.clock;
    let column = table.column(clock).ok_or_else(|| CliError::NoClock {
        clock: clock.clone(),
    })?;
    let frames = page::frames(table, column, options.max_frames).map_err(|why| {
        let clock = clock.clone();
        CliError::BadClock { clock, why }
    })?;
    let up = options.up.unwrap_or_else(|| up_axis(&bodies, table));
    let o = page::PageOptions {
        title: &options.title,
        clock: &options.clock,
        up,
    };
    Ok(page::html(&bodies, table, &frames, &o))
}

/// The axis closest to the first plane's normal in the world (at the first row), else z.
fn up_axis(bodies: &[Body], table: &ResultTable) -> usize {
    let Some(plane) = bodies.iter().find(|b| b.shape == Shape::Plane) else {
        return 2;
    };
    let value = |s: &Series| match *s {
        Series::Column(c) => table.rows[0][c],
        Series::Constant(x) => x,
    };
    let n = plane.normal;
    let world = match &plane.rotation {
        Rotation::Matrix(m) => {
            let m: Vec<f64> = m.iter().map(value).collect();
            [0, 1, 2].map(|i| m[3 * i] * n[0] + m[3 * i + 1] * n[1] + m[3 * i + 2] * n[2])
        }
        Rotation::Quaternion(q) => {
            let q: Vec<f64> = q.iter().map(value).collect();
            let m = quaternion_matrix(&q);
            [0, 1, 2].map(|i| m[3 * i] * n[0] + m[3 * i + 1] * n[1] + m[3 * i + 2] * n[2])
        }
        Rotation::Identity => n,
    };
    (0..3)
        .max_by(|&a, &b| world[a].abs().total_cmp(&world[b].abs()))
        .unwrap_or(2)
}

/// The rotation matrix (row-major) of a quaternion (w, x, y, z), normalised first.
fn quaternion_matrix(q: &[f64]) -> [f64; 9] {
    let n = q
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    ]
}

/// The values of every parameter and constant of a compiled model after
/// initialization, by scalar name (`initial_values` of a run).
pub fn constants(dae: &unimo_dae::Dae, initial_values: &[f64]) -> HashMap<String, f64> {
    use unimo_dae::dae::ScalarKind;
    dae.ids()
        .filter(|&s| {
            matches!(
                dae.scalar(s).kind,
                ScalarKind::Parameter | ScalarKind::Constant
            )
        })
        .filter_map(|s| Some((dae.name(s), *initial_values.get(s.index())?)))
        .collect()
}

/// What `unimo animate` reads: the result file, the model (files, class name, library
/// folders, parameter values the run used).
pub struct AnimateSource {
    pub result: PathBuf,
    pub model: api::Source,
    pub params: Vec<(String, String)>,
}

/// Reads the result, compiles the model with the parameters it was run with (every
/// parameter kept tunable, so each has its value), initializes it for the values of
/// its parameters, and writes the page's HTML.
pub fn page_from_files(
    source: &AnimateSource,
    options: &AnimateOptions,
) -> Result<String, ApiError> {
    let table = ResultTable::read_csv(&source.result)?;
    let mut model = source.model.clone();
    model.fold = unimo_dae::FoldOptions {
        tunable_all: true,
        tunable: Vec::new(),
    };
    api::with_session(&model, |session| {
        let compiled = session.compile(&source.params, &[])?;
        let start = unimo_runtime::sim::SimOptions::resolve(
            &compiled.dae.experiment,
            &Default::default(),
            unimo_solve::Method::Auto,
            false,
        )
        .map(|o| o.start)
        .unwrap_or(0.0);
        let only_initialization = unimo_runtime::sim::Overrides {
            start: Some(start),
            stop: Some(start),
            ..Default::default()
        };
        let (result, failure) =
            compiled.simulate(&only_initialization, unimo_solve::Method::Auto)?;
        if result.initial_values.is_empty() {
            return Err(failure.unwrap_or_else(|| CliError::NotInitialized {}.into()));
        }
        let constants = constants(&compiled.dae, &result.initial_values);
        page(session.flat(), &constants, &table, options)
    })?
}
