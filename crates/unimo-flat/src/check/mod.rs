//! Semantic checks of the Modelica specification on classes as written (class
//! restrictions, prefixes, visibility, `each`, connections, algorithms, purity) and on
//! the flat model (variability of constants' bindings): each a coded `E2xxx`.
//!
//! The class checks run with the name check (`resolve::check_names`) on a class and
//! its nested classes; they look names up in the class tree and skip whatever does not
//! resolve (the name check reports it). The flat checks run after instantiation.

mod access;
mod algorithms;
mod connects;
mod elements;
mod flat;
mod restrictions;
mod walk;

pub(crate) use flat::{constant_bindings, pre_of_continuous};

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

/// The class tree and the diagnostics found so far.
pub(crate) struct Ctx<'t, 'p> {
    pub tree: &'t mut ClassTree<'p>,
    pub out: Vec<Diagnostic>,
}

impl Ctx<'_, '_> {
    /// Every class check on one class (not its nested classes).
    fn class(&mut self, id: ClassId) {
        self.restrictions(id);
        self.prefixes(id);
        self.visibility(id);
        self.modifications(id);
        self.connections(id);
        self.algorithms(id);
        self.purity(id);
    }
}
