//! Redeclarations as written (spec 7.3): a `final` element is not redeclared
//! (`E2016`), and a redeclared component keeps the dimensions of the one it replaces
//! (`E2015` when their number or literal sizes differ). Whether the element is
//! `replaceable` and whether the new type fits are checked at instantiation.

use super::elements::{component_class, find_component, ComponentInfo};
use super::Ctx;
use crate::error::FlatError;
use crate::lookup::Found;
use crate::tree::ClassId;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

/// The literal size of a dimension (`3`), when it is one.
fn literal_size(s: &Subscript) -> Option<i64> {
    match s {
        Subscript::Expr(Expr {
            kind: ExprKind::Integer(n),
            ..
        }) => Some(*n),
        _ => None,
    }
}

/// How two dimension lists certainly differ: in number, or in a literal size.
fn dims_differ(old: &[Subscript], new: &[Subscript]) -> Option<String> {
    if old.len() != new.len() {
        return Some(format!(
            "{} dimension(s) instead of {}",
            new.len(),
            old.len()
        ));
    }
    old.iter().zip(new).enumerate().find_map(|(k, (o, n))| {
        match (literal_size(o), literal_size(n)) {
            (Some(a), Some(b)) if a != b => {
                Some(format!("size {b} instead of {a} in dimension {}", k + 1))
            }
            _ => None,
        }
    })
}

/// The class element `name` of `class` or of a base, as declared.
fn class_element(
    tree: &mut crate::tree::ClassTree<'_>,
    class: ClassId,
    name: &str,
    depth: usize,
) -> Option<(bool, Span)> {
    if depth > 32 {
        return None;
    }
    let def = tree.get(class).def.clone();
    if let ClassBody::Long { composition, .. } = &def.body {
        for e in &composition.elements {
            if let ElementKind::Class(cd) = &e.kind {
                if cd.name.text == name {
                    return Some((e.is_final, cd.name.span));
                }
            }
        }
    }
    for b in tree.bases(class) {
        if b != class {
            if let Some(found) = class_element(tree, b, name, depth + 1) {
                return Some(found);
            }
        }
    }
    None
}

fn final_redeclared(name: &str, at: Span, declared: Span) -> Diagnostic {
    FlatError::FinalRedeclared {
        name: name.to_owned(),
        span: at,
        declared,
    }
    .into()
}

impl Ctx<'_, '_> {
    /// `E2016`/`E2015` for the redeclarations in the modifiers of class `id`'s
    /// components and `extends` clauses, and for its `redeclare` elements.
    pub(super) fn redeclarations(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        for e in &composition.elements {
            match &e.kind {
                ElementKind::Component(cc) => {
                    for d in &cc.components {
                        let Some(cm) = d.modification.as_ref().and_then(|m| m.class_mod.as_ref())
                        else {
                            continue;
                        };
                        let info = ComponentInfo::new(id, e, cc, d);
                        if let Some(c) = component_class(self.tree, &info) {
                            self.redeclare_args(c, cm, 0);
                        }
                    }
                    if e.redeclare {
                        for d in &cc.components {
                            self.redeclared_element(id, cc, d);
                        }
                    }
                }
                ElementKind::Extends(x) => {
                    let Some(cm) = &x.modification else { continue };
                    let parts: Vec<&str> = x.base.parts.iter().map(|p| p.text.as_str()).collect();
                    if let Some(Found::Class(b)) = self.tree.lookup_dotted(Some(id), &parts, true) {
                        if b != id {
                            self.redeclare_args(b, cm, 0);
                        }
                    }
                }
                _ => {}
            }
        }
    }

    /// `redeclare T x` as an element of `id`: the inherited `x` it replaces.
    fn redeclared_element(&mut self, id: ClassId, cc: &ComponentClause, d: &ComponentDecl) {
        for b in self.tree.bases(id) {
            if b == id {
                continue;
            }
            if let Some(old) = find_component(self.tree, b, &d.name.text) {
                self.check_component_redeclare(&old, cc, d);
                return;
            }
        }
    }

    /// The redeclarations of modification `cm` of an instance of `class`, nested ones
    /// included (`p(q(redeclare T x))`).
    fn redeclare_args(&mut self, class: ClassId, cm: &ClassModification, depth: usize) {
        if depth > 8 {
            return;
        }
        for a in &cm.args {
            match a {
                Argument::Modify {
                    name,
                    modification: Some(m),
                    ..
                } if name.parts.len() == 1 => {
                    let Some(inner) = &m.class_mod else { continue };
                    let Some(info) = find_component(self.tree, class, &name.parts[0].text) else {
                        continue;
                    };
                    if let Some(c) = component_class(self.tree, &info) {
                        self.redeclare_args(c, inner, depth + 1);
                    }
                }
                Argument::Redeclare {
                    redeclare: true,
                    element,
                    ..
                } => match element {
                    RedeclaredElement::Component(cc) => {
                        for d in &cc.components {
                            if let Some(old) = find_component(self.tree, class, &d.name.text) {
                                self.check_component_redeclare(&old, cc, d);
                            }
                        }
                    }
                    RedeclaredElement::Class(cd) => {
                        if let Some((true, declared)) =
                            class_element(self.tree, class, &cd.name.text, 0)
                        {
                            self.out
                                .push(final_redeclared(&cd.name.text, cd.name.span, declared));
                        }
                    }
                },
                _ => {}
            }
        }
    }

    /// A component `old` redeclared as declaration `d` of clause `cc`.
    fn check_component_redeclare(
        &mut self,
        old: &ComponentInfo,
        cc: &ComponentClause,
        d: &ComponentDecl,
    ) {
        if old.is_final {
            self.out
                .push(final_redeclared(&d.name.text, d.name.span, old.name_span));
            return;
        }
        let new: Vec<Subscript> = d.dims.iter().chain(&cc.type_dims).cloned().collect();
        // `redeclare T x` without dimensions keeps the old ones only when T is the
        // element type: a type that is itself an array is left to instantiation.
        if new.is_empty() {
            return;
        }
        if let Some(how) = dims_differ(&old.dims, &new) {
            self.out.push(
                FlatError::RedeclaredDimensions {
                    name: d.name.text.to_string(),
                    how,
                    span: d.name.span,
                    declared: old.name_span,
                }
                .into(),
            );
        }
    }
}
