//! The library API behind the Python package and `unimo sweep`: compile a model with
//! parameter values, run it, and get numbers and coded errors back (never printing).
//!
//! A parameter value is applied the way `simulate -p` applies it: checked against the
//! flat model and made a top-level modifier, and the model flattened and compiled
//! again. A [`Session`] keeps the parsed files and the loaded library between
//! compilations, so a sweep parses once per worker and recompiles per point.

use crate::error::CliError;
use crate::provider::CliProvider;
use std::collections::HashMap;
use std::path::PathBuf;
use unimo_codegen::model::CompiledModel;
use unimo_dae::plan::Plan;
use unimo_dae::Dae;
use unimo_flat::{ClassId, ClassTree, FlatModel};
use unimo_runtime::sim::{Overrides, SimError, SimOptions, SimResult};
use unimo_solve::Method;
use unimo_source::{Diagnostic, SourceMap};

/// What went wrong, in the command line's exit-code classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// The model has errors (exit code 1).
    Model,
    /// A request was wrong: unknown parameter, bad value, missing file (exit code 2).
    Usage,
    /// The simulation failed (exit code 3).
    Simulation,
}

impl ErrorKind {
    /// The command line's exit code for an error of this kind.
    pub fn exit_code(self) -> i32 {
        match self {
            ErrorKind::Model => crate::EXIT_MODEL_ERROR,
            ErrorKind::Usage => crate::EXIT_USAGE,
            ErrorKind::Simulation => crate::EXIT_SIMULATION_FAILURE,
        }
    }
}

/// A coded error: the first error diagnostic's code, message and `file:line:col`,
/// and every diagnostic rendered as plain text.
#[derive(Clone, Debug, PartialEq)]
pub struct ApiError {
    pub kind: ErrorKind,
    pub code: String,
    pub message: String,
    pub location: Option<String>,
    /// Every diagnostic rendered (source line and caret), for display.
    pub rendered: String,
}

impl ApiError {
    fn plain(kind: ErrorKind, code: &str, message: impl Into<String>) -> ApiError {
        let message = message.into();
        ApiError {
            kind,
            code: code.to_owned(),
            rendered: format!("error[{code}]: {message}"),
            message,
            location: None,
        }
    }

    fn from_diagnostics(kind: ErrorKind, diags: &[Diagnostic], map: &SourceMap) -> ApiError {
        let first = diags.iter().find(|d| d.is_error()).or(diags.first());
        let rendered = diags
            .iter()
            .filter(|d| d.is_error())
            .map(|d| crate::render::render_plain(d, map))
            .collect::<Vec<_>>()
            .join("\n");
        match first {
            Some(d) => ApiError {
                kind,
                code: d.code.0.to_owned(),
                message: d.message.clone(),
                location: d.primary_span().map(|s| map.location(s)),
                rendered,
            },
            None => ApiError {
                kind,
                ..ApiError::from(CliError::Unknown {})
            },
        }
    }
}

/// A command-line error as the API reports it: its kind, code, message and line.
impl From<CliError> for ApiError {
    fn from(e: CliError) -> ApiError {
        ApiError {
            kind: e.kind(),
            code: e.code().as_str().to_owned(),
            message: e.to_string(),
            location: None,
            rendered: e.line(),
        }
    }
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.location {
            Some(at) => write!(f, "error[{}]: {} ({at})", self.code, self.message),
            None => write!(f, "error[{}]: {}", self.code, self.message),
        }
    }
}

/// Where a model comes from: its files (with their text when the caller already read
/// it, e.g. shipped to a cluster worker), the model's name, library folders and the
/// parameters kept tunable.
#[derive(Clone, Debug, Default)]
pub struct Source {
    pub files: Vec<(PathBuf, Option<String>)>,
    pub model: Option<String>,
    pub libs: Vec<PathBuf>,
    pub fold: unimo_dae::FoldOptions,
}

/// A model ready to run, with what the results need: output names and units.
pub struct Compiled {
    pub dae: Dae,
    pub plan: Plan,
    pub model: CompiledModel,
    /// Units by flat variable name (`a.b`, for scalars `a.b[2]` too).
    pub units: HashMap<String, String>,
    /// Each DAE equation's `file:line:col`, when asked for ([`Session::locate`]).
    pub equation_locations: Vec<String>,
}

impl Compiled {
    /// The unit of an output column (its flat variable's), or "".
    pub fn unit(&self, name: &str) -> &str {
        let flat = name.split('[').next().unwrap_or(name);
        self.units
            .get(name)
            .or_else(|| self.units.get(flat))
            .map_or("", |u| u.as_str())
    }

    /// Runs the model: the result (the rows computed so far when the run failed) and
    /// the run's error. `Err` when the options are wrong (nothing ran).
    pub fn simulate(
        &self,
        overrides: &Overrides,
        method: Method,
    ) -> Result<(SimResult, Option<ApiError>), ApiError> {
        // The grid alone: a sweep's runs share their time points.
        let options = SimOptions::resolve(&self.dae.experiment, overrides, method, false)
            .map(|o| SimOptions {
                output_rtol: 0.0,
                ..o
            })
            .map_err(|why| CliError::BadOptions { why })?;
        let result = unimo_runtime::sim::simulate(&self.model, &options);
        let error = result.error.as_ref().map(|e| self.simulation_error(e));
        Ok((result, error))
    }

    fn simulation_error(&self, e: &SimError) -> ApiError {
        let mut error = ApiError::plain(ErrorKind::Simulation, e.code(), e.message());
        if let SimError::NonFinite {
            equation: Some(eq), ..
        } = e
        {
            error.location = self.equation_locations.get(eq.index()).cloned();
        }
        error
    }

    /// Run statistics as (name, value) pairs, as `simulate --stats` prints them.
    pub fn stats(&self, result: &SimResult) -> Vec<(&'static str, f64)> {
        let s = &result.stats;
        vec![
            ("states", self.model.states.len() as f64),
            ("steps", s.solver.steps as f64),
            ("rejected", s.solver.rejected_steps as f64),
            ("rhs", s.solver.rhs_evals as f64),
            ("jacobians", s.solver.jacobian_evals as f64),
            ("lu", s.solver.lu_factorizations as f64),
            ("newton", s.solver.newton_iterations as f64),
            ("events", s.events as f64),
            ("event_iterations", s.event_iterations as f64),
            ("plan_evaluations", s.rhs_evaluations as f64),
            ("state_selections", s.state_selections as f64),
            (
                "parameters_folded",
                self.plan.stats.parameters_folded as f64,
            ),
            ("zero_crossings", self.model.roots.len() as f64),
        ]
    }
}

/// The parsed files and loaded library of one model, flattened again per set of
/// parameter values.
pub struct Session<'p> {
    tree: ClassTree<'p>,
    class: ClassId,
    base: FlatModel,
    fold: unimo_dae::FoldOptions,
}

/// Reads and parses the model's files, picks the model and flattens it once (its
/// errors are returned here), then hands the session to `then`.
pub fn with_session<R>(
    source: &Source,
    then: impl FnOnce(&mut Session<'_>) -> R,
) -> Result<R, ApiError> {
    let provider = CliProvider::new(&source.libs);
    let mut tree = ClassTree::new(&provider);
    let mut first = None;
    for (path, text) in &source.files {
        let text = match text {
            Some(t) => t.clone(),
            None => std::fs::read_to_string(path).map_err(|e| CliError::Unreadable {
                path: path.clone(),
                reason: e.to_string(),
            })?,
        };
        let id = tree.sources.add(path.clone(), text);
        let parsed = unimo_syntax::parse(id, tree.sources.get(id).text());
        if parsed.has_errors() {
            let kind = ErrorKind::Model;
            return Err(ApiError::from_diagnostics(
                kind,
                &parsed.diagnostics,
                &tree.sources,
            ));
        }
        let classes = tree.add_user_file(id, parsed.ast);
        first.get_or_insert(classes);
    }
    let classes = first.unwrap_or_default();
    let class = crate::check::pick(&mut tree, &classes, source.model.as_deref())?;
    let (base, diags) = unimo_flat::flatten(&mut tree, class);
    let mut session = Session {
        tree,
        class,
        base,
        fold: source.fold.clone(),
    };
    session.check(diags)?;
    // The first name that covers no parameter (the command line lists them all).
    crate::simulate::check_tunable(&session.base, &session.fold)
        .map_err(|unknown| unknown.into_iter().next().unwrap_or(CliError::Unknown {}))?;
    Ok(then(&mut session))
}

impl Session<'_> {
    /// Errors of flattening, or an unbalanced model, as an error.
    fn check(&mut self, mut diags: Vec<Diagnostic>) -> Result<(), ApiError> {
        if !diags.iter().any(|d| d.is_error()) {
            let span = self.tree.get(self.class).def.name.span;
            diags.extend(unimo_flat::balance::check(&self.base, span));
        }
        diags.append(&mut self.tree.diagnostics);
        if diags.iter().any(|d| d.is_error()) {
            let e = ApiError::from_diagnostics(ErrorKind::Model, &diags, &self.tree.sources);
            return Err(e);
        }
        Ok(())
    }

    /// The flat model without overrides.
    pub fn flat(&self) -> &FlatModel {
        &self.base
    }

    /// Compiles the model with these parameter values (`name`, value as written in
    /// Modelica: `0.5`, `true`, an enumeration literal), pruned to `outputs` when some
    /// are given.
    pub fn compile(
        &mut self,
        params: &[(String, String)],
        outputs: &[String],
    ) -> Result<Compiled, ApiError> {
        let flat_overridden;
        let flat = if params.is_empty() {
            &self.base
        } else {
            let flags: Vec<String> = params.iter().map(|(n, v)| format!("{n}={v}")).collect();
            let modifiers =
                crate::params::overrides(&flags, None, &self.base, &mut self.tree.sources)
                    .map_err(|d| {
                        ApiError::from_diagnostics(ErrorKind::Usage, &d, &self.tree.sources)
                    })?;
            let (flat, diags) = unimo_flat::flatten_with(&mut self.tree, self.class, &modifiers);
            let errors: Vec<Diagnostic> = diags.into_iter().filter(|d| d.is_error()).collect();
            if !errors.is_empty() {
                let map = &self.tree.sources;
                return Err(ApiError::from_diagnostics(ErrorKind::Model, &errors, map));
            }
            flat_overridden = flat;
            &flat_overridden
        };
        let (dae, analysis) = unimo_dae::analyze_model_with(flat, &self.fold)
            .map_err(|d| ApiError::from_diagnostics(ErrorKind::Model, &d, &self.tree.sources))?;
        let mut plan = analysis.plan;
        if !outputs.is_empty() {
            let wanted = output_ids(&dae, outputs)?;
            unimo_dae::prune::prune(&dae, &mut plan, &wanted);
        }
        let model = unimo_codegen::model::compile(&dae, &plan);
        Ok(Compiled {
            units: crate::results::units(flat),
            dae,
            plan,
            model,
            equation_locations: Vec::new(),
        })
    }

    /// Fills `compiled.equation_locations` (for errors naming an equation).
    pub fn locate(&self, compiled: &mut Compiled) {
        compiled.equation_locations = compiled
            .dae
            .equations
            .iter()
            .map(|e| self.tree.sources.location(e.origin))
            .collect();
    }

    /// Runs `compiled` (made by this session), errors located in its files.
    pub fn simulate(
        &self,
        compiled: &Compiled,
        overrides: &Overrides,
        method: Method,
    ) -> Result<(SimResult, Option<ApiError>), ApiError> {
        let (result, mut error) = compiled.simulate(overrides, method)?;
        if let (Some(e), Some(SimError::NonFinite { equation, .. })) = (&mut error, &result.error) {
            if let (None, Some(eq)) = (&e.location, equation) {
                let origin = compiled.dae.equations[eq.index()].origin;
                e.location = Some(self.tree.sources.location(origin));
            }
        }
        Ok((result, error))
    }
}

/// The scalars `outputs` select (a name, or a prefix followed by `.` or `[`).
fn output_ids(dae: &Dae, outputs: &[String]) -> Result<Vec<unimo_dae::expr::ScalarId>, ApiError> {
    let ids: Vec<_> = dae.ids().collect();
    let names: Vec<String> = ids.iter().map(|&s| dae.name(s)).collect();
    let cols = crate::simulate::select(&names, &without_time(outputs))?;
    Ok(cols.into_iter().map(|c| ids[c]).collect())
}

/// The columns of `names` that `outputs` select (all when empty; `time` is always
/// there and selects nothing more).
pub fn select_columns(names: &[String], outputs: &[String]) -> Result<Vec<usize>, ApiError> {
    if !outputs.is_empty() && outputs.iter().all(|o| o == "time") {
        return Ok(Vec::new());
    }
    Ok(crate::simulate::select(names, &without_time(outputs))?)
}

fn without_time(outputs: &[String]) -> Vec<String> {
    outputs.iter().filter(|o| *o != "time").cloned().collect()
}

/// The solver named as on the command line (`auto`, `bdf`, `radau5`, `dopri5`).
pub fn method(name: &str) -> Result<Method, ApiError> {
    match name {
        "auto" => Ok(Method::Auto),
        "bdf" => Ok(Method::Bdf),
        "radau5" => Ok(Method::Radau5),
        "dopri5" => Ok(Method::Dopri5),
        _ => Err(CliError::UnknownMethod {
            name: name.to_owned(),
        }
        .into()),
    }
}

/// Runs `work` on a thread with a large stack (the compiler's passes recurse over
/// expression trees), as the command line does.
pub fn on_large_stack<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("unimo".into())
            .stack_size(STACK_SIZE)
            .spawn_scoped(scope, work)
            .expect("cannot start a thread")
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// The stack of every thread that compiles.
pub const STACK_SIZE: usize = 256 << 20;
