//! The model an FMU carries: its flat Modelica text (`resources/model.mo`), compiled
//! the same way by `unimo fmu` (for the model description) and by the FMU's library
//! (at instantiation, and again with the parameter values the importer set), and the
//! table of its variables in value-reference order.

use crate::error::FmiError;
use std::collections::HashMap;
use unimo_codegen::model::CompiledModel;
use unimo_dae::dae::{ScalarKind, ScalarType};
use unimo_dae::expr::{Node, ScalarId};
use unimo_dae::Dae;
use unimo_flat::flat::FlatVar;
use unimo_flat::{ClassTree, FlatModel, MemoryProvider};
use unimo_syntax::ast::{Expr, ExprKind};

/// The FMI causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    /// A parameter the importer may set before initialization.
    Parameter,
    /// A parameter computed from others (or fixed at translation: not settable).
    CalculatedParameter,
    Input,
    Output,
    Local,
}

/// One variable of the FMU (a scalar of the DAE).
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    pub name: String,
    /// The DAE scalar, which is also its register.
    pub scalar: u32,
    pub ty: ScalarType,
    pub kind: ScalarKind,
    pub causality: Causality,
    pub description: String,
    pub unit: Option<String>,
    /// A derivative: the value reference of its state.
    pub derivative_of: Option<u32>,
    /// The value after initialization that the description gives as `start` (a
    /// parameter's, a constant's, an input's, a settable state's).
    pub start: Option<f64>,
    /// A scalar state whose start value is a literal with `fixed = true`: the importer
    /// may set it before the end of initialization (`initial = "exact"`).
    pub start_exact: bool,
}

/// A compiled model with its variable table.
pub struct Compiled {
    pub dae: Dae,
    pub model: CompiledModel,
    pub variables: Vec<Variable>,
    /// Value references of the states and of their derivatives, in the state order of
    /// the compiled model.
    pub states: Vec<(u32, u32)>,
}

/// The flat model text parsed and flattened, ready to compile with parameter values.
pub struct FlatSource {
    text: String,
    flat: FlatModel,
}

fn diagnostics_text(diags: &[unimo_source::Diagnostic]) -> String {
    diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{}: {}", d.code.0, d.message))
        .collect::<Vec<_>>()
        .join("; ")
}

/// Flattens the flat model `text` with the top-level `modifiers` (parameter values).
fn flatten(text: &str, modifiers: &[(String, Expr)]) -> Result<FlatModel, FmiError> {
    let provider = MemoryProvider::new().with_root(
        "<stdlib>",
        unimo_stdlib::FILES
            .iter()
            .map(|(p, t)| (p.to_string(), t.to_string())),
    );
    let mut tree = ClassTree::new(&provider);
    let id = tree.sources.add(
        std::path::PathBuf::from("resources/model.mo"),
        text.to_owned(),
    );
    let parsed = unimo_syntax::parse(id, tree.sources.get(id).text());
    if parsed.has_errors() {
        return Err(FmiError::Model(diagnostics_text(&parsed.diagnostics)));
    }
    let classes = tree.add_user_file(id, parsed.ast);
    let Some(&class) = classes.last() else {
        return Err(FmiError::Model("the model file has no class".into()));
    };
    let (flat, diags) = unimo_flat::flatten_with(&mut tree, class, modifiers);
    if diags.iter().any(|d| d.is_error()) {
        return Err(FmiError::Model(diagnostics_text(&diags)));
    }
    Ok(flat)
}

impl FlatSource {
    pub fn new(text: &str) -> Result<FlatSource, FmiError> {
        Ok(FlatSource {
            text: text.to_owned(),
            flat: flatten(text, &[])?,
        })
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    pub fn flat(&self) -> &FlatModel {
        &self.flat
    }

    /// Compiles the model, with `values` (by variable name) for the settable
    /// parameters given and `starts` for the settable states' start values, as
    /// top-level modifiers (`k = v`, `'a.x'.start = v`: what `simulate -p` does).
    pub fn compile(
        &self,
        values: &[(String, ScalarType, f64)],
        starts: &[(String, f64)],
    ) -> Result<Compiled, FmiError> {
        let flat_overridden;
        let flat = if values.is_empty() && starts.is_empty() {
            &self.flat
        } else {
            let modifiers: Vec<(String, Expr)> = values
                .iter()
                .map(|(name, ty, v)| (quoted(name), literal(*ty, *v)))
                .chain(starts.iter().map(|(name, v)| {
                    (
                        format!("{}.start", quoted(name)),
                        literal(ScalarType::Real, *v),
                    )
                }))
                .collect();
            flat_overridden = flatten(&self.text, &modifiers)?;
            &flat_overridden
        };
        let fold = unimo_dae::FoldOptions::default();
        let (dae, analysis) = unimo_dae::analyze_model_with(flat, &fold)
            .map_err(|d| FmiError::Model(diagnostics_text(&d)))?;
        let model = unimo_codegen::model::compile(&dae, &analysis.plan);
        let variables = variables(&dae, flat, &model);
        let states = states(&model, &variables)?;
        Ok(Compiled {
            dae,
            model,
            variables,
            states,
        })
    }
}

/// A flat variable's name as the flat text declares it (quoted when dotted).
fn quoted(name: &str) -> String {
    if name.contains('.') && !name.starts_with('\'') {
        format!("'{name}'")
    } else {
        name.to_owned()
    }
}

fn literal(ty: ScalarType, v: f64) -> Expr {
    let kind = match ty {
        ScalarType::Boolean => ExprKind::Bool(v != 0.0),
        ScalarType::Integer | ScalarType::Enumeration(_) => ExprKind::Integer(v as i64),
        ScalarType::Real => ExprKind::Real(v),
    };
    Expr {
        kind,
        span: unimo_source::Span::default(),
    }
}

/// Whether a parameter may be set from outside: a scalar declared with a literal
/// value (or none), not `final`, not `Evaluate = true`, not structural.
fn settable(dae: &Dae, s: ScalarId, flat: &FlatModel, by_name: &HashMap<String, usize>) -> bool {
    let scalar = dae.scalar(s);
    let Some(&k) = by_name.get(flat_name(&plain(&scalar.name))) else {
        return false;
    };
    let var = &flat.vars[k];
    let literal_binding = scalar
        .binding
        .is_none_or(|b| matches!(dae.arena.node(b), Node::Const(_)));
    var.dims.is_empty()
        && !var.is_final
        && !var.evaluate
        && scalar.fixed != Some(false)
        && literal_binding
        && flat.evaluated.binary_search(&var.name).is_err()
}

/// Whether a state's start value may be set through the FMU: a scalar, not `final`,
/// `fixed = true`, its start a literal (one computed from parameters follows them).
fn start_settable(dae: &Dae, s: ScalarId, var: Option<&FlatVar>) -> bool {
    let scalar = dae.scalar(s);
    var.is_some_and(|v| v.dims.is_empty() && !v.is_final)
        && scalar.fixed == Some(true)
        && scalar
            .start
            .is_some_and(|e| matches!(dae.arena.node(e), Node::Const(_)))
}

/// The variable table: every scalar of the DAE, by scalar id.
pub fn variables(dae: &Dae, flat: &FlatModel, model: &CompiledModel) -> Vec<Variable> {
    let by_name: HashMap<String, usize> = flat
        .vars
        .iter()
        .enumerate()
        .map(|(k, v)| (plain(&v.name), k))
        .collect();
    let units = units(flat);
    let free: Vec<u32> = model.free_parameters.iter().map(|(r, _)| *r).collect();
    dae.ids()
        .map(|s| {
            let scalar = dae.scalar(s);
            let name = plain(&scalar.name);
            let flat_var = by_name.get(flat_name(&name)).map(|&k| &flat.vars[k]);
            let output = flat_var.is_some_and(|v| {
                v.top_level && v.causality == Some(unimo_syntax::ast::Causality::Output)
            });
            let causality = match scalar.kind {
                ScalarKind::Parameter if free.contains(&s.0) => Causality::CalculatedParameter,
                ScalarKind::Parameter if settable(dae, s, flat, &by_name) => Causality::Parameter,
                ScalarKind::Parameter => Causality::CalculatedParameter,
                _ if scalar.input => Causality::Input,
                ScalarKind::Constant => Causality::Local,
                _ if output => Causality::Output,
                _ => Causality::Local,
            };
            Variable {
                name: plain(&dae.name(s)),
                scalar: s.0,
                ty: scalar.ty,
                kind: scalar.kind,
                causality,
                description: scalar.description.clone().unwrap_or_default(),
                unit: units.get(flat_name(&name)).cloned(),
                derivative_of: scalar.derivative_of.map(|d| d.0),
                start: None,
                start_exact: model.states.contains(&s.0) && start_settable(dae, s, flat_var),
            }
        })
        .collect()
}

/// A name as `unimo simulate` writes it: the flat text's quotes (`'a.b'`) removed.
pub fn plain(name: &str) -> String {
    name.replace('\'', "")
}

/// `a.b[2]` belongs to the flat variable `a.b`.
fn flat_name(scalar: &str) -> &str {
    match scalar.strip_suffix(']').and_then(|s| s.rfind('[')) {
        Some(k) => &scalar[..k],
        None => scalar,
    }
}

fn units(flat: &FlatModel) -> HashMap<String, String> {
    flat.vars
        .iter()
        .filter_map(|v| {
            v.attributes.iter().find_map(|(n, e)| match &e.kind {
                ExprKind::String(u) if n == "unit" && !u.is_empty() => {
                    Some((plain(&v.name), u.clone()))
                }
                _ => None,
            })
        })
        .collect()
}

/// The states and their derivatives as value references (each must be a scalar).
fn states(model: &CompiledModel, variables: &[Variable]) -> Result<Vec<(u32, u32)>, FmiError> {
    let n = variables.len() as u32;
    model
        .states
        .iter()
        .zip(&model.derivatives)
        .zip(&model.state_names)
        .map(|((&x, &dx), name)| {
            if x < n && dx < n {
                Ok((x, dx))
            } else {
                Err(FmiError::Unsupported(format!(
                    "the state `{name}` or its derivative is not a variable of the model"
                )))
            }
        })
        .collect()
}
