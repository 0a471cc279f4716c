//! `unimo._unimo`: the native half of the Python package. A thin layer over
//! `unimo_cli::api` and `unimo_cli::sweep`: it converts arguments, releases the GIL
//! around compiling and simulating, and turns coded errors into the exception classes
//! of `unimo.errors`. The Python half (`python/unimo/`) builds numpy arrays and pandas
//! tables from what this returns.

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::PathBuf;
use std::sync::Arc;
use unimo_cli::api::{self, ApiError, Compiled, ErrorKind, Source};
use unimo_cli::sweep::{run as run_sweep, SweepSettings};
use unimo_runtime::sim::{Overrides, SimResult};

/// Where the model comes from, as Python passes it: `(path, text or None)` per file,
/// the model's name, library folders, tunable parameters (`None`: fold every known
/// parameter; `["*"]`: keep every parameter tunable).
type SourceSpec = (
    Vec<(String, Option<String>)>,
    Option<String>,
    Vec<String>,
    Option<Vec<String>>,
);

fn source(spec: SourceSpec) -> Source {
    let (files, model, libs, tunable) = spec;
    let tunable = tunable.unwrap_or_default();
    let tunable_all = tunable.iter().any(|t| t == "*");
    Source {
        files: files
            .into_iter()
            .map(|(p, t)| (PathBuf::from(p), t))
            .collect(),
        model,
        libs: libs.into_iter().map(PathBuf::from).collect(),
        fold: unimo_dae::FoldOptions {
            tunable_all,
            tunable: if tunable_all { Vec::new() } else { tunable },
        },
    }
}

/// The exception of `unimo.errors` for an error's kind, carrying its code, message,
/// location and rendered text.
fn to_py_err(py: Python<'_>, e: &ApiError) -> PyErr {
    let class = match e.kind {
        ErrorKind::Model => "ModelError",
        ErrorKind::Usage => "UsageError",
        ErrorKind::Simulation => "SimulationError",
    };
    let made = py.import("unimo.errors").and_then(|m| {
        let args = (&e.code, &e.message, &e.location, &e.rendered);
        m.getattr(class)?.call1(args)
    });
    match made {
        Ok(exception) => PyErr::from_value(exception),
        Err(import_failed) => import_failed,
    }
}

/// The error as a tuple `(kind, code, message, location, rendered)` (sweep rows).
fn error_tuple(e: &ApiError) -> (&'static str, String, String, Option<String>, String) {
    let kind = match e.kind {
        ErrorKind::Model => "model",
        ErrorKind::Usage => "usage",
        ErrorKind::Simulation => "simulation",
    };
    (
        kind,
        e.code.clone(),
        e.message.clone(),
        e.location.clone(),
        e.rendered.clone(),
    )
}

/// Run settings as Python passes them.
#[derive(Clone, Debug, Default)]
struct RunSpec {
    overrides: Overrides,
    method: String,
}

fn run_spec(options: Option<&Bound<'_, PyDict>>) -> PyResult<RunSpec> {
    let mut spec = RunSpec {
        method: "auto".to_owned(),
        ..RunSpec::default()
    };
    let Some(o) = options else {
        return Ok(spec);
    };
    let float = |k: &str| -> PyResult<Option<f64>> {
        match o.get_item(k)? {
            Some(v) if !v.is_none() => Ok(Some(v.extract()?)),
            _ => Ok(None),
        }
    };
    spec.overrides.start = float("start_time")?;
    spec.overrides.stop = float("stop_time")?;
    spec.overrides.rtol = float("rtol")?;
    spec.overrides.atol = float("atol")?;
    spec.overrides.interval = float("interval")?;
    if let Some(v) = o.get_item("points")? {
        spec.overrides.points = v.extract()?;
    }
    if let Some(v) = o.get_item("method")? {
        if !v.is_none() {
            spec.method = v.extract()?;
        }
    }
    Ok(spec)
}

/// A compiled model: `unimo.Model` wraps it.
#[pyclass(module = "unimo._unimo", frozen)]
struct NativeModel {
    compiled: Arc<Compiled>,
    spec: SourceSpec,
}

/// Compiles a model with parameter values applied (`params`: `(name, Modelica text)`).
#[pyfunction]
fn compile(
    py: Python<'_>,
    spec: SourceSpec,
    params: Vec<(String, String)>,
) -> PyResult<NativeModel> {
    let src = source(spec.clone());
    let compiled = py.detach(|| compile_located(&src, &params));
    match compiled {
        Ok(c) => Ok(NativeModel {
            compiled: Arc::new(c),
            spec,
        }),
        Err(e) => Err(to_py_err(py, &e)),
    }
}

fn compile_located(src: &Source, params: &[(String, String)]) -> Result<Compiled, ApiError> {
    api::on_large_stack(|| {
        api::with_session(src, |s| {
            let mut c = s.compile(params, &[])?;
            s.locate(&mut c);
            Ok(c)
        })?
    })
}

#[pymethods]
impl NativeModel {
    /// Runs the compiled model (no recompiling). Returns the result as a dict; a failed
    /// run has `error` set and keeps the rows computed before the failure.
    #[pyo3(signature = (options=None, outputs=Vec::new()))]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        options: Option<&Bound<'py, PyDict>>,
        outputs: Vec<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let spec = run_spec(options)?;
        let method = api::method(&spec.method).map_err(|e| to_py_err(py, &e))?;
        let compiled = Arc::clone(&self.compiled);
        let run =
            py.detach(move || api::on_large_stack(|| compiled.simulate(&spec.overrides, method)));
        let (result, error) = run.map_err(|e| to_py_err(py, &e))?;
        let cols = api::select_columns(&result.names, &outputs).map_err(|e| to_py_err(py, &e))?;
        let out = result_dict(py, &self.compiled, &result, &cols)?;
        out.set_item("stats", stats_dict(py, &self.compiled.stats(&result))?)?;
        out.set_item("error", error.as_ref().map(error_tuple))?;
        Ok(out)
    }

    /// The names of the result columns (every variable but parameters and constants).
    fn names(&self) -> Vec<String> {
        self.compiled
            .model
            .outputs
            .iter()
            .map(|(n, _)| n.clone())
            .collect()
    }

    /// `(name, unit)` of every result column (`""` when none is declared).
    fn units(&self) -> Vec<(String, String)> {
        let c = &self.compiled;
        c.model
            .outputs
            .iter()
            .map(|(n, _)| (n.clone(), c.unit(n).to_owned()))
            .collect()
    }

    /// Where the model came from, to compile it again elsewhere (a Dask worker).
    fn source_spec(&self) -> SourceSpec {
        self.spec.clone()
    }
}

/// `{names, units, time, data, ncols}`: `time` and `data` (row-major, the selected
/// columns) as native-endian float64 bytes for `numpy.frombuffer`.
fn result_dict<'py>(
    py: Python<'py>,
    compiled: &Compiled,
    r: &SimResult,
    cols: &[usize],
) -> PyResult<Bound<'py, PyDict>> {
    let d = bare_result_dict(py, r, cols)?;
    let units: Vec<&str> = cols.iter().map(|&c| compiled.unit(&r.names[c])).collect();
    d.set_item("units", units)?;
    Ok(d)
}

fn stats_dict<'py>(py: Python<'py>, stats: &[(&str, f64)]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, value) in stats {
        if value.fract() == 0.0 && value.abs() < 9e15 {
            d.set_item(*name, *value as i64)?;
        } else {
            d.set_item(*name, *value)?;
        }
    }
    Ok(d)
}

/// Runs a sweep on `jobs` threads (GIL released): one dict per point with `values`
/// (final values, `(name, value)` pairs), `error` (a tuple or None), `stats`, and with
/// `keep_results` the point's `result` dict.
#[pyfunction]
#[pyo3(signature = (spec, points, outputs=Vec::new(), jobs=1, keep_results=false, options=None))]
fn sweep<'py>(
    py: Python<'py>,
    spec: SourceSpec,
    points: Vec<Vec<(String, String)>>,
    outputs: Vec<String>,
    jobs: usize,
    keep_results: bool,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    let run = run_spec(options)?;
    let method = api::method(&run.method).map_err(|e| to_py_err(py, &e))?;
    let settings = SweepSettings {
        outputs,
        overrides: run.overrides,
        method,
        jobs,
        keep_results,
    };
    let src = source(spec);
    let outcomes = py
        .detach(|| run_sweep(&src, &points, &settings))
        .map_err(|e| to_py_err(py, &e))?;
    let list = PyList::empty(py);
    for o in &outcomes {
        let d = PyDict::new(py);
        d.set_item("values", &o.values)?;
        d.set_item("error", o.error.as_ref().map(error_tuple))?;
        d.set_item("stats", stats_dict(py, &o.stats)?)?;
        if let Some(r) = &o.result {
            let cols: Vec<usize> = (0..r.names.len()).collect();
            d.set_item("result", bare_result_dict(py, r, &cols)?)?;
        }
        list.append(d)?;
    }
    Ok(list)
}

/// The selected columns of a result, without units (sweep results).
fn bare_result_dict<'py>(
    py: Python<'py>,
    r: &SimResult,
    cols: &[usize],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let time: Vec<u8> = r.times.iter().flat_map(|t| t.to_ne_bytes()).collect();
    let mut data = Vec::with_capacity(r.rows.len() * cols.len() * 8);
    for row in &r.rows {
        for &c in cols {
            data.extend_from_slice(&row[c].to_ne_bytes());
        }
    }
    let names: Vec<&str> = cols.iter().map(|&c| r.names[c].as_str()).collect();
    d.set_item("names", names)?;
    d.set_item("units", PyList::empty(py))?;
    d.set_item("time", PyBytes::new(py, &time))?;
    d.set_item("data", PyBytes::new(py, &data))?;
    d.set_item("ncols", cols.len())?;
    Ok(d)
}

/// The native module.
#[pymodule]
fn _unimo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeModel>()?;
    m.add_function(wrap_pyfunction!(compile, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
