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

pub mod balance;
pub mod connect;
pub mod error;
pub mod eval;
pub mod flat;
pub mod functions;
pub mod instantiate;
mod interp;
pub mod lookup;
pub mod modif;
pub mod provider;
pub(crate) mod records;
pub(crate) mod redeclare;
pub mod resolve;
pub mod tree;
pub mod typecheck;

pub use error::FlatError;
pub use flat::{FlatModel, FlatVar, VarId};
pub use provider::{LibFile, LibLocation, MemoryProvider, SourceProvider};
pub use tree::{ClassId, ClassTree, LoadStats};
use unimo_source::Diagnostic;

/// Instantiates `class` into a flat model, with connection equations. Returns the
/// model and the diagnostics (errors mean the model is not usable).
pub fn flatten(tree: &mut ClassTree<'_>, class: ClassId) -> (FlatModel, Vec<Diagnostic>) {
    let mut diags = resolve::check_names(tree, class);
    let mut inst = instantiate::Instantiator::new(tree);
    inst.run(class);
    let connects = std::mem::take(&mut inst.connects);
    let absent = std::mem::take(&mut inst.absent);
    inst.collect_functions();
    let mut model = std::mem::take(&mut inst.model);
    diags.append(&mut inst.diags);
    diags.extend(connect::generate(&mut model, &connects, &absent));
    // Sizes and types, once the model is whole.
    if diags.is_empty() {
        diags.extend(typecheck::check(&model));
    }
    // Canonical order: constants and parameters first, each group in declaration order
    // (so that flattening the printed model gives the same text).
    // (a stable partition: moving the large variable records once, not sorting them)
    let (mut fixed, rest): (Vec<FlatVar>, Vec<FlatVar>) =
        std::mem::take(&mut model.vars).into_iter().partition(|v| {
            matches!(
                v.variability,
                flat::Variability::Constant | flat::Variability::Parameter
            )
        });
    fixed.extend(rest);
    model.vars = fixed;
    (model, diags)
}
