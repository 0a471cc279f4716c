//! Visibility (spec 4.1, 5.3): protected elements referenced through dot notation
//! from outside (`E2022`) or modified (`E2023`); `each` on a modifier of something
//! that is not an array (`E2024`, spec 7.2.5).

use super::elements::{
    base_of, component_type, declares_protected_class, find_component, is_array, is_within, Base,
    ComponentInfo,
};
use super::walk::{composition_exprs, for_each_equation};
use super::Ctx;
use crate::error::FlatError;
use crate::flat::for_each_call;
use crate::lookup::Found;
use crate::tree::ClassId;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

fn protected_access(name: &str, span: Span, declared: Span) -> Diagnostic {
    FlatError::ProtectedAccess {
        name: name.to_owned(),
        span,
        declared,
    }
    .into()
}

impl Ctx<'_, '_> {
    /// `E2022` for every dotted reference or class name of `id` through a protected element.
    pub(super) fn visibility(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let mut refs: Vec<ComponentRef> = Vec::new();
        let mut functions: Vec<Name> = Vec::new();
        composition_exprs(composition, &mut |e| {
            for_each_call(
                e,
                &mut |r| {
                    if r.parts.len() > 1 {
                        refs.push(r.clone());
                    }
                },
                &mut |f, _| {
                    if f.parts.len() > 1 && !f.global {
                        functions.push(f.clone());
                    }
                },
            )
        });
        for s in &composition.sections {
            let Section::Equation(es) = s else { continue };
            for_each_equation(&es.equations, &mut |eq| {
                if let EquationKind::Connect { a, b } = &eq.kind {
                    refs.extend([a, b].into_iter().filter(|r| r.parts.len() > 1).cloned());
                }
            });
        }
        for r in &refs {
            self.reference(id, r);
        }
        for f in &functions {
            self.class_path(Some(id), id, &f.parts);
        }
        for e in &composition.elements {
            match &e.kind {
                ElementKind::Component(cc) => self.class_path(Some(id), id, &cc.type_name.parts),
                ElementKind::Extends(x) => self.class_path(Some(id), id, &x.base.parts),
                ElementKind::Import(imp) => {
                    let name = match &imp.kind {
                        ImportKind::Qualified(n) | ImportKind::Unqualified(n) => n,
                        ImportKind::Renamed { name, .. } | ImportKind::Multiple { name, .. } => {
                            name
                        }
                    };
                    self.class_path(None, id, &name.parts);
                }
                ElementKind::Class(_) => {}
            }
        }
    }

    /// A reference `a.b.c` of class `id`: through components, or through classes.
    fn reference(&mut self, id: ClassId, r: &ComponentRef) {
        let first = &r.parts[0].name.text;
        let Some(mut cur) = find_component(self.tree, id, first) else {
            if !r.global {
                let idents: Vec<Ident> = r.parts.iter().map(|p| p.name.clone()).collect();
                self.class_path(Some(id), id, &idents);
            }
            return;
        };
        for p in &r.parts[1..] {
            let Some(Found::Class(c)) = component_type(self.tree, &cur) else {
                return;
            };
            let Some(next) = find_component(self.tree, c, &p.name.text) else {
                return;
            };
            if next.protected {
                self.out
                    .push(protected_access(&p.name.text, p.name.span, next.name_span));
                return;
            }
            cur = next;
        }
    }

    /// A dotted class name (or a reference starting with one) used in class `from`,
    /// looked up from `scope`: a protected member of a class `from` is not inside.
    fn class_path(&mut self, scope: Option<ClassId>, from: ClassId, parts: &[Ident]) {
        if parts.len() < 2 {
            return;
        }
        let Some(Found::Class(mut c)) = self.tree.lookup_simple(scope, &parts[0].text, false)
        else {
            return;
        };
        for p in &parts[1..] {
            if let Some(span) = declares_protected_class(self.tree, c, &p.text) {
                if !is_within(self.tree, from, c) {
                    self.out.push(protected_access(&p.text, p.span, span));
                }
                return;
            }
            if let Some(m) = self.tree.member_class(c, &p.text) {
                c = m;
                continue;
            }
            if let Some(info) = find_component(self.tree, c, &p.text) {
                if info.protected && !is_within(self.tree, from, info.owner) {
                    self.out
                        .push(protected_access(&p.text, p.span, info.name_span));
                }
            }
            return;
        }
    }

    /// `E2023`/`E2024` in the modifiers of the components `id` declares.
    pub(super) fn modifications(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        for (e, cc) in def.component_clauses() {
            for d in &cc.components {
                let Some(cm) = d.modification.as_ref().and_then(|m| m.class_mod.as_ref()) else {
                    continue;
                };
                let info = ComponentInfo::new(id, e, cc, d);
                let array = is_array(self.tree, &info);
                let target = component_type(self.tree, &info);
                self.class_mod(cm, target, array);
            }
        }
    }

    /// The arguments of a modification of an element of type `target`; `array`: an
    /// enclosing element is an array.
    fn class_mod(&mut self, cm: &ClassModification, target: Option<Found>, array: bool) {
        for a in &cm.args {
            let Argument::Modify {
                each,
                name,
                modification,
                span,
                ..
            } = a
            else {
                continue;
            };
            let mut t = target;
            let mut any_array = array;
            let mut resolved = true;
            for p in &name.parts {
                match t {
                    Some(Found::Class(c)) => {
                        match find_component(self.tree, c, &p.text) {
                            Some(info) => {
                                if info.protected {
                                    self.out.push(
                                        FlatError::ProtectedModified {
                                            name: p.text.to_string(),
                                            span: p.span,
                                            declared: info.name_span,
                                        }
                                        .into(),
                                    );
                                }
                                any_array |= is_array(self.tree, &info);
                                t = component_type(self.tree, &info);
                            }
                            // An attribute of a type derived from a predefined one.
                            None if base_of(self.tree, Found::Class(c))
                                .is_some_and(|b| b != Base::Other) =>
                            {
                                if let Some(base) = base_of(self.tree, Found::Class(c)) {
                                    self.attribute(base, p);
                                }
                                t = None
                            }
                            None => {
                                resolved = false;
                                t = None;
                            }
                        }
                    }
                    // An attribute of a predefined type.
                    Some(Found::Builtin(b)) => {
                        if let Some(base) = base_of(self.tree, Found::Builtin(b)) {
                            self.attribute(base, p);
                        }
                        t = None
                    }
                    _ => resolved = false,
                }
            }
            if *each && resolved && !any_array {
                self.out.push(
                    FlatError::EachOnScalar {
                        name: name.to_dotted(),
                        span: *span,
                    }
                    .into(),
                );
            }
            if let Some(cm) = modification.as_ref().and_then(|m| m.class_mod.as_ref()) {
                self.class_mod(cm, t, any_array);
            }
        }
    }

    /// `E2004`: an attribute of the predefined types that `base` does not have
    /// (`Integer(unit = "m")`; names no predefined type has are reported when
    /// instantiating).
    fn attribute(&mut self, base: Base, attr: &Ident) {
        const ALL: &[&str] = &[
            "quantity",
            "unit",
            "displayUnit",
            "min",
            "max",
            "start",
            "fixed",
            "nominal",
            "unbounded",
            "stateSelect",
        ];
        let allowed: &[&str] = match base {
            Base::Real | Base::Other => return,
            Base::Integer | Base::Enumeration => &["quantity", "min", "max", "start", "fixed"],
            Base::Boolean | Base::String => &["quantity", "start", "fixed"],
        };
        let a = attr.text.as_str();
        if !ALL.contains(&a) || allowed.contains(&a) {
            return;
        }
        self.out.push(
            FlatError::NotAttributeOfType {
                attribute: a.to_owned(),
                base: base.name(),
                allowed,
                span: attr.span,
            }
            .into(),
        );
    }
}
