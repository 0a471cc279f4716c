//! Redeclared classes (spec 7.3): `redeclare model Sensor = OffsetSensor(offset = 0.05)`
//! in a component modifier, in an `extends` modifier, or as an element of a class
//! body changes what the replaceable class name means inside one instance. The
//! instantiator keeps, per instance, the class each redeclared name stands for, and
//! resolves component types, function calls and package constants through it.

use crate::error::FlatError;
use crate::eval;
use crate::instantiate::{instance_key, Instantiator};
use crate::lookup::Found;
use crate::modif::{Mod, Scope};
use crate::tree::ClassId;
use smol_str::SmolStr;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// Notes the class redeclarations that apply inside the instance at `prefix`:
    /// the instance's modifier first (it wins), then the class's own `redeclare`
    /// elements; `extends` modifiers are noted when their base is instantiated.
    pub(crate) fn register_class_redeclares(
        &mut self,
        class: ClassId,
        composition: &Composition,
        prefix: &[RefPart],
        m: &Mod,
    ) {
        let any = m.children.iter().any(|(_, c)| c.class_redeclare.is_some())
            || composition
                .elements
                .iter()
                .any(|e| e.redeclare && matches!(e.kind, ElementKind::Class(_)));
        if !any {
            return;
        }
        let key = instance_key(prefix);
        for (name, child) in &m.children {
            let Some((def, scope)) = &child.class_redeclare else {
                continue;
            };
            if self.class_element_replaceable(class, name, 0) == Some(false) {
                self.not_replaceable(name, def.name.span);
            }
            let k = (key.clone(), name.clone());
            if self.class_redeclares.contains_key(&k) {
                continue;
            }
            let id = self.tree.add_detached(scope.class, def.clone());
            self.class_redeclares.insert(k, id);
            self.detached_scopes.insert(id, scope.clone());
        }
        for e in &composition.elements {
            let (true, ElementKind::Class(cd)) = (e.redeclare, &e.kind) else {
                continue;
            };
            let inherited = self
                .tree
                .bases(class)
                .into_iter()
                .find_map(|b| self.class_element_replaceable(b, &cd.name.text, 0));
            match inherited {
                Some(false) => self.not_replaceable(&cd.name.text, cd.name.span),
                None => self.diags.push(
                    FlatError::RedeclareWithoutBase {
                        name: cd.name.text.to_string(),
                        span: cd.name.span,
                    }
                    .into(),
                ),
                Some(true) => {}
            }
            let k = (key.clone(), cd.name.text.clone());
            if self.class_redeclares.contains_key(&k) {
                continue;
            }
            if let Some(id) = self.tree.child_class(class, &cd.name.text) {
                self.class_redeclares.insert(k, id);
            }
        }
    }

    /// The class a replaceable class name stands for inside the instance of `scope`.
    pub(crate) fn redeclared(&self, scope: &Scope, name: &str) -> Option<ClassId> {
        if self.class_redeclares.is_empty() {
            return None;
        }
        let key = instance_key(&scope.prefix);
        self.class_redeclares
            .get(&(key, SmolStr::new(name)))
            .copied()
    }

    /// Looks up a class path from `scope`, through the instance's redeclared classes.
    pub(crate) fn lookup_class_path(&mut self, scope: &Scope, parts: &[&str]) -> Option<Found> {
        let (first, rest) = parts.split_first()?;
        // Only a name that means a class here can be redeclared (not a component).
        if let Some(rc) = self.redeclared(scope, first) {
            if let Some(Found::Class(_)) = self.tree.lookup_simple(Some(scope.class), first, false)
            {
                let mut found = Found::Class(rc);
                for p in rest {
                    found = match found {
                        Found::Class(c) => match self.tree.member_class(c, p) {
                            Some(m) => Found::Class(m),
                            None if self.tree.has_component(c, p) => Found::Component(c),
                            None => return None,
                        },
                        other => return Some(other),
                    };
                }
                return Some(found);
            }
        }
        self.lookup_cached(scope.class, parts)
    }

    /// `lookup_dotted(Some(class), parts, false)`, cached: the same type names are
    /// looked up from the same classes many times (a model of 10^5 components).
    pub(crate) fn lookup_cached(&mut self, class: ClassId, parts: &[&str]) -> Option<Found> {
        let name = match parts {
            [one] => SmolStr::new(one),
            _ => SmolStr::new(parts.join(".")),
        };
        let key = (class, name);
        if let Some(f) = self.type_cache.get(&key) {
            return *f;
        }
        let found = self.tree.lookup_dotted(Some(class), parts, false);
        self.type_cache.insert(key, found);
        found
    }

    /// A class written in a modifier has no global name: the class it names instead
    /// (`redeclare function f = g` is `g`), for a call's global name.
    pub(crate) fn real_class(&mut self, mut c: ClassId) -> ClassId {
        for _ in 0..32 {
            let entry = self.tree.get(c);
            let detached = self.class_redeclares.values().any(|&v| v == c);
            let short = matches!(
                &entry.def.body,
                ClassBody::Short {
                    modification: None,
                    ..
                }
            );
            if !(detached && short) {
                return c;
            }
            match self.tree.bases(c).first() {
                Some(&b) => c = b,
                None => return c,
            }
        }
        c
    }

    /// `Medium.cp` where `Medium` is redeclared in this instance: the constant's value.
    pub(crate) fn redeclared_constant(
        &mut self,
        r: &ComponentRef,
        scope: &Scope,
        locals: &[String],
    ) -> Option<Expr> {
        if r.global || r.parts.len() < 2 || self.class_redeclares.is_empty() {
            return None;
        }
        let first = r.parts[0].name.text.as_str();
        if locals.iter().any(|l| l == first) || self.redeclared(scope, first).is_none() {
            return None;
        }
        if r.parts.iter().any(|p| !p.subscripts.is_empty()) {
            return None;
        }
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        let (last, owner_path) = names.split_last()?;
        let Some(Found::Class(owner)) = self.lookup_class_path(scope, owner_path) else {
            return None;
        };
        let (binding, bscope) = self.class_constant(owner, last, 0)?;
        let flat = self.flat_expr(&binding, &bscope);
        let v = eval::eval(&flat, self, &mut Vec::new()).ok()?;
        Some(v.to_expr(r.span))
    }

    /// Whether the class element `name` of `class` (or of a base) is `replaceable`;
    /// `None` when there is no such class element.
    fn class_element_replaceable(
        &mut self,
        class: ClassId,
        name: &str,
        depth: usize,
    ) -> Option<bool> {
        if depth > 32 {
            return None;
        }
        let def = self.tree.get(class).def.clone();
        if let ClassBody::Long { composition, .. } = &def.body {
            for e in &composition.elements {
                if let ElementKind::Class(cd) = &e.kind {
                    if cd.name.text == name {
                        return Some(e.replaceable || e.redeclare);
                    }
                }
            }
        }
        for b in self.tree.bases(class) {
            if let Some(r) = self.class_element_replaceable(b, name, depth + 1) {
                return Some(r);
            }
        }
        None
    }

    fn not_replaceable(&mut self, name: &str, span: Span) {
        self.diags.push(
            FlatError::NotReplaceable {
                name: name.to_owned(),
                span,
            }
            .into(),
        );
    }

    /// A modifier of element `d`: a redeclaration needs a `replaceable` element
    /// (`E2015`), a `final` element takes no modifier (`E2016`).
    pub(crate) fn check_element_modifier(&mut self, e: &Element, d: &ComponentDecl, m: &Mod) {
        if let Some((name, _)) = &m.redeclare {
            if !e.replaceable && !e.redeclare {
                self.not_replaceable(&d.name.text, name.span);
            }
        }
        if e.is_final && (m.binding.is_some() || !m.children.is_empty()) {
            let span = m.binding.as_ref().map_or(d.name.span, |b| b.expr.span);
            self.diags.push(
                FlatError::FinalModified {
                    name: d.name.text.to_string(),
                    span,
                    declared: d.name.span,
                }
                .into(),
            );
        }
    }
}

impl Instantiator<'_, '_> {
    /// Whether class `class` is declared `replaceable` in its parent, with its
    /// constraining clause (cached: asked for every component of that type).
    fn class_element(&mut self, class: ClassId) -> Option<(bool, Option<ConstrainingClause>)> {
        if let Some(c) = self.constraint_cache.get(&class) {
            return c.clone();
        }
        let info = (|| {
            let parent = self.tree.get(class).parent?;
            let name = self.tree.get(class).name.clone();
            let def = self.tree.get(parent).def.clone();
            let ClassBody::Long { composition, .. } = &def.body else {
                return None;
            };
            composition
                .elements
                .iter()
                .find(|e| matches!(&e.kind, ElementKind::Class(cd) if cd.name.text == name))
                .map(|e| (e.replaceable, e.constrainedby.clone()))
        })();
        self.constraint_cache.insert(class, info.clone());
        info
    }

    /// For a component whose type name `parts` resolved to `found` from `scope`: the
    /// modifiers of the replaceable class's constraining clause, and, when the class
    /// was redeclared in this instance, a check that the new class has every element
    /// of the constraining one (`E2015`).
    pub(crate) fn class_constraint(
        &mut self,
        scope: &Scope,
        parts: &[&str],
        found: ClassId,
        span: Span,
    ) -> Option<Mod> {
        if parts.len() != 1 {
            return None;
        }
        // The class as declared (not redeclared) tells the constraint.
        let original = match self.lookup_cached(scope.class, parts) {
            Some(Found::Class(c)) => c,
            _ => return None,
        };
        let (replaceable, constrainedby) = self.class_element(original)?;
        if !replaceable {
            return None;
        }
        let parent = self.tree.get(original).parent?;
        let decl_scope = Scope {
            class: parent,
            prefix: std::sync::Arc::from([]),
        };
        if found != original {
            let constraint = match &constrainedby {
                Some(c) => {
                    let names: Vec<&str> = c.base.parts.iter().map(|p| p.text.as_str()).collect();
                    match self.tree.lookup_dotted(Some(parent), &names, false) {
                        Some(Found::Class(k)) => k,
                        _ => original,
                    }
                }
                None => original,
            };
            // Point at the redeclaration when it is a class written in a modifier.
            let at = if self.class_redeclares.values().any(|&v| v == found) {
                self.tree.get(found).def.name.span
            } else {
                span
            };
            self.check_fits(found, constraint, parts[0], at);
        }
        let cm = constrainedby.as_ref()?.modification.as_ref()?;
        Some(Mod::from_class_mod(cm, &decl_scope))
    }

    /// A component redeclared with type `new`: it must have every element of the type
    /// it replaces (or of that declaration's constraining class).
    pub(crate) fn check_plug_compatible(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        name: &str,
        new: ClassId,
        span: Span,
    ) {
        let parts: Vec<&str> = cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
        if let Some(Found::Class(old)) = self.tree.lookup_dotted(Some(scope.class), &parts, false) {
            self.check_fits(new, old, name, span);
        }
    }

    fn check_fits(&mut self, new: ClassId, constraint: ClassId, what: &str, span: Span) {
        let missing: Vec<String> = self
            .record_fields(constraint)
            .into_iter()
            .filter(|f| !self.tree.has_component(new, &f.name))
            .map(|f| f.name.to_string())
            .collect();
        if !missing.is_empty() {
            let _ = new;
            let cname = self.tree.full_name(constraint);
            self.diags.push(
                FlatError::RedeclaredClassLacks {
                    name: what.to_string(),
                    missing: missing.iter().map(|m| m.to_string()).collect(),
                    constraint: cname,
                    span,
                }
                .into(),
            );
        }
    }
}
