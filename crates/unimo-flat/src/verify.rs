//! The flat model's verifier: the invariants lowering relies on. `flatten` runs it in
//! debug and test builds on every model it returns without errors.
//!
//! Invariants checked:
//! 1. variable names are unique and non-empty;
//! 2. the canonical order: constants and parameters before every other variable;
//! 3. functions and records are sorted by name, each name once;
//! 4. every record instance names a record type of `records`, and each of that
//!    record's fields is a variable `instance.field` (an array field's elements
//!    `instance.field[...]` count, an empty array field has none) or a nested record
//!    instance.

use crate::flat::{FlatModel, Variability};
use rustc_hash::FxHashSet as HashSet;

/// A broken invariant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("flat model `{model}`: {message}")]
pub struct VerifyError {
    pub model: String,
    pub message: String,
}

/// Checks the invariants in the module docs.
pub fn verify_flat(m: &FlatModel) -> Result<(), VerifyError> {
    let fail = |message: String| {
        Err(VerifyError {
            model: m.name.clone(),
            message,
        })
    };
    let mut names: HashSet<&str> = HashSet::default();
    names.reserve(m.vars.len());
    let mut seen_free = false;
    for v in &m.vars {
        if v.name.is_empty() {
            return fail("a variable without a name".into());
        }
        if !names.insert(&v.name) {
            return fail(format!("variable `{}` declared twice", v.name));
        }
        let fixed = matches!(
            v.variability,
            Variability::Constant | Variability::Parameter
        );
        if fixed && seen_free {
            return fail(format!(
                "parameter `{}` after a non-parameter variable (canonical order)",
                v.name
            ));
        }
        seen_free |= !fixed;
    }
    for (what, list) in [
        (
            "function",
            m.functions
                .iter()
                .map(|f| f.name.as_str())
                .collect::<Vec<_>>(),
        ),
        (
            "record",
            m.records.iter().map(|r| r.name.as_str()).collect(),
        ),
    ] {
        if let Some(w) = list.windows(2).find(|w| w[0] >= w[1]) {
            return fail(format!(
                "{what}s not sorted by name: `{}` before `{}`",
                w[0], w[1]
            ));
        }
    }
    let instances: HashSet<&str> = m.record_instances.iter().map(|(p, _)| p.as_str()).collect();
    // `a.b[2].c[1]` is an element of the arrays `a.b` and `a.b[2].c`.
    let mut array_bases: HashSet<&str> = HashSet::default();
    for n in names.iter().chain(&instances) {
        for (k, _) in n.match_indices('[') {
            array_bases.insert(&n[..k]);
        }
    }
    for (path, ty) in &m.record_instances {
        let Some(record) = m.records.iter().find(|r| &r.name == ty) else {
            return fail(format!(
                "record instance `{path}` of unknown record type `{ty}`"
            ));
        };
        for f in &record.fields {
            let full = format!("{path}.{}", f.name);
            let empty = f.dims.contains(&Some(0));
            let present = empty
                || names.contains(full.as_str())
                || instances.contains(full.as_str())
                || array_bases.contains(full.as_str());
            if !present {
                return fail(format!(
                    "record instance `{path}` has no variable for its field `{}`",
                    f.name
                ));
            }
        }
    }
    Ok(())
}
