//! Semantic checks of the Modelica specification on classes as written (class
//! restrictions, prefixes, visibility, `each`, connections, algorithms, purity) and on
//! the flat model (variability of constants' bindings): each a coded `E2xxx`.
//!
//! The class checks run with the name check (`resolve::check_names`) on a class and
//! its nested classes; they look names up in the class tree and skip whatever does not
//! resolve (the name check reports it). The flat checks run after instantiation.

mod access;
mod algorithms;
mod connectors;
mod connects;
mod discrete;
mod elements;
mod flat;
mod overconstrained;
mod predefined;
mod redeclares;
mod restrictions;
mod walk;

pub(crate) use elements::{component_type, find_component};

use crate::tree::{ClassId, ClassTree};
use unimo_source::Diagnostic;
use unimo_syntax::ast::{ClassBody, ElementKind};

/// The semantic diagnostics of `class` and of the classes nested in it.
pub(crate) fn check_class(tree: &mut ClassTree<'_>, class: ClassId) -> Vec<Diagnostic> {
    let mut ctx = Ctx {
        tree,
        out: Vec::new(),
    };
    let mut pending = vec![class];
    let mut seen = 0usize;
    while let Some(id) = pending.pop() {
        seen += 1;
        if seen > 100_000 {
            break;
        }
        ctx.class(id);
        let def = ctx.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            continue;
        };
        for e in &composition.elements {
            if let ElementKind::Class(c) = &e.kind {
                if let Some(child) = ctx.tree.child_class(id, &c.name.text) {
                    if ctx.tree.get(child).def.span == c.span {
                        pending.push(child);
                    }
                }
            }
        }
    }
    ctx.out
}

/// The semantic diagnostics of the other top-level classes of the user file that
/// declares `class` (the functions and classes a model's file holds beside it; the
/// name check covers `class` and what encloses it).
pub(crate) fn check_file_siblings(tree: &mut ClassTree<'_>, class: ClassId) -> Vec<Diagnostic> {
    let file = tree.get(class).file;
    let mut out = Vec::new();
    for c in tree.user_top_classes_in(file) {
        if !elements::is_within(tree, class, c) {
            out.extend(check_class(tree, c));
        }
    }
    out
}

/// The semantic diagnostics of a flat model: constants bound to parameters (`E2019`),
/// `pre` of continuous-time variables outside `when` (`E2032`), discrete-time variables
/// given continuous-time values (`E2033`).
pub(crate) fn flat_model(model: &crate::FlatModel) -> Vec<Diagnostic> {
    let mut out = flat::constant_bindings(model);
    out.extend(flat::pre_of_continuous(model));
    out.extend(discrete::discrete_equations(model));
    out
}

/// `W2001` for parameters without any value; run on a model without errors (an error
/// in a binding leaves its fields unbound, which is no news to the modeller).
pub(crate) fn unbound_parameters(model: &crate::FlatModel) -> Vec<Diagnostic> {
    flat::unbound_parameters(model)
}

/// The class tree and the diagnostics found so far.
pub(crate) struct Ctx<'t, 'p> {
    pub tree: &'t mut ClassTree<'p>,
    pub out: Vec<Diagnostic>,
}

impl Ctx<'_, '_> {
    fn report(&mut self, e: crate::error::FlatError) {
        self.out.push(e.into());
    }

    /// Every class check on one class (not its nested classes).
    fn class(&mut self, id: ClassId) {
        self.restrictions(id);
        self.prefixes(id);
        self.visibility(id);
        self.modifications(id);
        self.redeclarations(id);
        self.connections(id);
        self.stream_connector(id);
        self.connector_balance(id);
        self.constant_connectors(id);
        self.overconstrained(id);
        self.predefined_members(id);
        self.algorithms(id);
        self.purity(id);
    }
}
