//! Checks on the flat model: a constant's binding reads no parameter (`E2019`, spec
//! 3.8.1: a constant expression holds constants and literals only).

use crate::eval::var_key;
use crate::flat::{for_each_value_ref, FlatModel, Variability};
use rustc_hash::FxHashMap as HashMap;
use unimo_source::Diagnostic;

/// `E2019` for every constant bound to an expression that reads a parameter.
pub(crate) fn constant_bindings(model: &FlatModel) -> Vec<Diagnostic> {
    let index: HashMap<&str, usize> = model
        .vars
        .iter()
        .enumerate()
        .map(|(k, v)| (v.name.as_str(), k))
        .collect();
    let mut diags = Vec::new();
    for v in &model.vars {
        if v.variability != Variability::Constant {
            continue;
        }
        let Some(b) = &v.binding else { continue };
        let mut culprit: Option<usize> = None;
        for_each_value_ref(b, &mut |r| {
            if culprit.is_none() {
                let key = var_key(r);
                culprit = index
                    .get(key.as_str())
                    .copied()
                    .filter(|&j| model.vars[j].variability == Variability::Parameter);
            }
        });
        if let Some(j) = culprit {
            let p = &model.vars[j];
            diags.push(
                Diagnostic::error(
                    "E2019",
                    format!(
                        "the binding of constant `{}` reads the parameter `{}`",
                        v.name, p.name
                    ),
                )
                .at(b.span, "not a constant expression")
                .with_label(p.origin, "declared a parameter here")
                .with_help(format!(
                    "declare `{}` a parameter, or bind it to constants only",
                    v.name
                ))
                .with_note("Modelica specification, section 3.8.1"),
            );
        }
    }
    diags
}
