//! Instantiation and flattening: from parsed classes to one flat model.
//!
//! The class tree (typed `ClassId`s, lazy loading of library packages through a
//! [`SourceProvider`]), Modelica name lookup, the name-resolution check that
//! `unimo check` runs, and instantiation: modifiers merged outer-over-inner,
//! inheritance, `for` equations unrolled, structural parameters evaluated, connection
//! sets turned into equations, and the balance check.
//!
//! Invariants: no file system access of its own (files come through the provider), no
//! printing; every problem is a coded `E2xxx` diagnostic.

use crate::error::FlatCode;
pub mod balance;
mod check;
pub mod connect;
pub mod error;
pub mod eval;
mod expandable;
mod external;
pub mod flat;
pub mod functions;
pub mod instantiate;
mod interp;
pub mod lookup;
pub mod modif;
mod overconstrained;
pub mod provider;
pub(crate) mod records;
pub(crate) mod redeclare;
pub mod resolve;
mod semantic;
pub mod tree;
pub mod typecheck;
mod values;
pub mod verify;
pub mod visual;

pub use error::FlatError;
pub use flat::{FlatModel, FlatVar, FlatVisual, VarId};
pub use provider::{LibFile, LibLocation, MemoryProvider, SourceProvider};
pub use tree::{ClassId, ClassTree, LoadStats};
use unimo_source::Diagnostic;

/// Models with at least this many equations check sizes and types on a second thread
/// while the connection equations are generated (below it a thread costs more than it
/// saves).
const PARALLEL_FROM: usize = 20_000;

/// Whether `d`'s primary span overlaps the primary span of one of `earlier`.
fn overlaps_any(d: &Diagnostic, earlier: &[Diagnostic]) -> bool {
    let primary = |d: &Diagnostic| d.labels.iter().find(|l| l.primary).map(|l| l.span);
    let Some(s) = primary(d) else { return false };
    earlier.iter().filter_map(primary).any(|e| {
        e.file == s.file && e.start < s.end.max(s.start + 1) && s.start < e.end.max(e.start + 1)
    })
}

/// Instantiates `class` into a flat model, with connection equations. Returns the
/// model and the diagnostics (errors mean the model is not usable).
pub fn flatten(tree: &mut ClassTree<'_>, class: ClassId) -> (FlatModel, Vec<Diagnostic>) {
    flatten_with(tree, class, &[])
}

/// Like [`flatten`], with modifiers applied to the top-level class as if it were
/// instantiated as `class(name1 = value1, ...)`: each `(dotted name, value)` replaces
/// that element's binding (`body.m` modifies `m` of component `body`). Parameters
/// that set sizes or ranges take the new values like any modifier would.
pub fn flatten_with(
    tree: &mut ClassTree<'_>,
    class: ClassId,
    modifiers: &[(String, unimo_syntax::ast::Expr)],
) -> (FlatModel, Vec<Diagnostic>) {
    let mut diags = resolve::check_names(tree, class);
    diags.extend(check::check_file_siblings(tree, class));
    let mut inst = instantiate::Instantiator::new(tree);
    inst.top_modifiers = top_modifiers(class, modifiers);
    inst.run(class);
    let connects = std::mem::take(&mut inst.connects);
    let absent = std::mem::take(&mut inst.absent);
    let buses = std::mem::take(&mut inst.expandable);
    inst.collect_functions();
    let mut model = std::mem::take(&mut inst.model);
    let named = diags.len();
    for d in inst.diags.drain(..) {
        if !(d.code == FlatCode::UnknownName.into() && overlaps_any(&d, &diags[..named])) {
            diags.push(d);
        }
    }
    // A cycle that compile-time evaluation met is reported there already.
    if !diags
        .iter()
        .any(|d| d.code == FlatCode::CyclicBinding.into())
    {
        diags.extend(semantic::parameter_cycles(&model));
    }
    diags.extend(semantic::binding_variability(&model));
    diags.extend(check::flat_model(&model));
    // Connection equations and the size/type check of the equations so far are
    // independent: they run side by side. (Connected variables are checked against
    // each other in `connect`, so the generated equations need no type check.)
    let check_types = diags.is_empty();
    let check = |model: &FlatModel| {
        if check_types {
            typecheck::check(model)
        } else {
            Vec::new()
        }
    };
    let (conn_eqs, conn_diags, type_diags) = if model.equations.len() < PARALLEL_FROM {
        let (eqs, d) = connect::equations(&model, &connects, &absent);
        (eqs, d, check(&model))
    } else {
        std::thread::scope(|s| {
            let model = &model;
            let checker = std::thread::Builder::new()
                // As deep as the caller's expressions may nest (the CLI's stack).
                .stack_size(512 << 20)
                .spawn_scoped(s, move || check(model));
            let (eqs, d) = connect::equations(model, &connects, &absent);
            let types = match checker {
                Ok(handle) => handle
                    .join()
                    .unwrap_or_else(|p| std::panic::resume_unwind(p)),
                // No thread to be had: check here.
                Err(_) => check(model),
            };
            (eqs, d, types)
        })
    };
    let mut conn_eqs = conn_eqs;
    let called = inst.overconstrained(&mut model, &mut conn_eqs, (&connects, &absent));
    expandable::remove_unused_members(&mut model, &mut conn_eqs, &buses);
    model.equations.extend(conn_eqs);
    if !called.is_empty() {
        // The `equalityConstraint` functions of broken loops, and what they call.
        inst.model = model;
        inst.add_functions(called);
        model = std::mem::take(&mut inst.model);
    }
    let connect_failed = !conn_diags.is_empty();
    diags.extend(conn_diags);
    // Sizes and types, once the connections are sound.
    if !connect_failed {
        diags.extend(type_diags);
    }

    parameters_first(&mut model);
    functions::keep_called(&mut model);
    if !diags.iter().any(|d| d.is_error()) {
        diags.extend(check::unbound_parameters(&model));
    }
    if cfg!(debug_assertions) && !diags.iter().any(|d| d.is_error()) {
        if let Err(e) = verify::verify_flat(&model) {
            panic!("{e}");
        }
    }
    (model, diags)
}

/// Canonical order: constants and parameters first, each group in declaration order
/// (so that flattening the printed model gives the same text); a stable partition that
/// moves the large variable records once instead of sorting them.
fn parameters_first(model: &mut FlatModel) {
    let is_fixed = |v: &FlatVar| {
        matches!(
            v.variability,
            flat::Variability::Constant | flat::Variability::Parameter
        )
    };
    let first_free = model.vars.iter().position(|v| !is_fixed(v));
    let partitioned = first_free.is_none_or(|k| !model.vars[k..].iter().any(is_fixed));
    if !partitioned {
        let n = model.vars.iter().filter(|v| is_fixed(v)).count();
        let mut fixed = Vec::with_capacity(model.vars.len());
        let mut rest = Vec::with_capacity(model.vars.len() - n);
        for v in std::mem::take(&mut model.vars) {
            if is_fixed(&v) {
                fixed.push(v);
            } else {
                rest.push(v);
            }
        }
        fixed.append(&mut rest);
        model.vars = fixed;
    }
}

/// The parts of a dotted name; a quoted identifier is one part, dots and all
/// (`'body.m'.start` is `'body.m'` and `start`, as in a flat model's text).
fn dotted_parts(name: &str) -> Vec<&str> {
    let (mut parts, mut start, mut quoted) = (Vec::new(), 0, false);
    for (k, c) in name.char_indices() {
        match c {
            '\'' => quoted = !quoted,
            '.' if !quoted => {
                parts.push(&name[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&name[start..]);
    parts
}

/// The modification `(a.b = v, ...)` of the top-level class.
fn top_modifiers(class: ClassId, modifiers: &[(String, unimo_syntax::ast::Expr)]) -> modif::Mod {
    let scope = modif::Scope {
        class,
        prefix: std::sync::Arc::from(Vec::new()),
    };
    let mut out = modif::Mod::default();
    for (name, value) in modifiers {
        let mut m = modif::Mod {
            binding: Some(modif::Bound {
                expr: value.clone(),
                scope: scope.clone(),
            }),
            ..modif::Mod::default()
        };
        for part in dotted_parts(name).into_iter().rev() {
            m = modif::Mod {
                children: vec![(part.into(), m)],
                ..modif::Mod::default()
            };
        }
        out = m.over_into(out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::dotted_parts;

    #[test]
    fn a_quoted_identifier_is_one_part_of_a_dotted_name() {
        assert_eq!(dotted_parts("body.m"), ["body", "m"]);
        assert_eq!(dotted_parts("'spring1.c'"), ["'spring1.c'"]);
        assert_eq!(dotted_parts("'mass1.s'.start"), ["'mass1.s'", "start"]);
    }
}
