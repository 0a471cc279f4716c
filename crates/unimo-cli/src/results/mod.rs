//! Result files of `unimo simulate`: the variables a run writes (trajectories,
//! aliases, time-invariant values, with descriptions and units) and their CSV and
//! MAT v4 writers.

pub mod csv;
pub mod mat;

use std::collections::HashMap;
use unimo_dae::dae::ScalarKind;
use unimo_dae::expr::{Node, ScalarId};
use unimo_dae::Dae;
use unimo_syntax::ast::ExprKind;

/// Where a variable's values are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Storage {
    /// Column `c` of the run's rows.
    Column(usize),
    /// The same values as variable `target` (an index into the list), negated or not.
    Alias { target: usize, negated: bool },
    /// One value for the whole run (a parameter or constant).
    Constant(f64),
}

/// One variable of a result file.
#[derive(Clone, Debug, PartialEq)]
pub struct ResultVariable {
    pub name: String,
    /// The declaration's description, then ` [unit]` when it has one (as
    /// OpenModelica writes it).
    pub description: String,
    pub storage: Storage,
}

/// The `unit` attribute of every variable of the flat model that has one, by name.
pub fn units(flat: &unimo_flat::FlatModel) -> HashMap<String, String> {
    flat.vars
        .iter()
        .filter_map(|v| {
            v.attributes.iter().find_map(|(n, e)| match &e.kind {
                ExprKind::String(u) if n == "unit" && !u.is_empty() => {
                    Some((v.name.clone(), u.clone()))
                }
                _ => None,
            })
        })
        .collect()
}

/// `a.b[2]` belongs to the flat variable `a.b`.
fn flat_name(scalar: &str) -> &str {
    match scalar.strip_suffix(']').and_then(|s| s.rfind('[')) {
        Some(k) => &scalar[..k],
        None => scalar,
    }
}

fn description(dae: &Dae, s: ScalarId, units: &HashMap<String, String>) -> String {
    let scalar = dae.scalar(s);
    let mut text = scalar.description.clone().unwrap_or_default();
    if let Some(unit) = units.get(flat_name(&scalar.name)) {
        text.push_str(&format!(" [{unit}]"));
    }
    text
}

/// The variables of a MAT result: the parameters and constants with their values
/// after initialization (`values`, by scalar id; those `keep` accepts), then the
/// output columns `cols` of `output_ids`. An output that alias elimination replaced by
/// `b` or `-b` of another written variable is stored as that alias.
pub fn variables(
    dae: &Dae,
    units: &HashMap<String, String>,
    values: &[f64],
    (output_ids, cols): (&[ScalarId], &[usize]),
    keep: &dyn Fn(&str) -> bool,
) -> Vec<ResultVariable> {
    let mut out = Vec::new();
    let mut index: HashMap<ScalarId, usize> = HashMap::new();
    for s in dae.ids() {
        let scalar = dae.scalar(s);
        let time_invariant = matches!(scalar.kind, ScalarKind::Parameter | ScalarKind::Constant);
        if !time_invariant || !keep(&scalar.name) {
            continue;
        }
        let value = values.get(s.0 as usize).copied().unwrap_or(f64::NAN);
        index.insert(s, out.len());
        out.push(ResultVariable {
            name: dae.name(s),
            description: description(dae, s, units),
            storage: Storage::Constant(value),
        });
    }
    let first_output = out.len();
    for &c in cols {
        index.insert(output_ids[c], out.len());
        out.push(ResultVariable {
            name: dae.name(output_ids[c]),
            description: description(dae, output_ids[c], units),
            storage: Storage::Column(c),
        });
    }
    for variable in &mut out[first_output..] {
        let Storage::Column(c) = variable.storage else {
            continue;
        };
        let Some(alias) = dae.scalar(output_ids[c]).alias else {
            continue;
        };
        let (negated, of) = match dae.arena.node(alias) {
            Node::Neg(x) => (true, x),
            _ => (false, alias),
        };
        if let Node::Var(target) = dae.arena.node(of) {
            if let Some(&target) = index.get(&target) {
                variable.storage = Storage::Alias { target, negated };
            }
        }
    }
    out
}
