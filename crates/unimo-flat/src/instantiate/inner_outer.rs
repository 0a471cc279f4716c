//! `outer` components (spec 5.4): each stands for the nearest `inner` component of the
//! same name in an enclosing instance, whose type must be a subtype of the outer's
//! (`E2035`). Without one, an inner of the outer's class is added at the top of the
//! model with a warning (`W2002`) when that class is not partial and every outer of
//! that name without inner has the same class; otherwise `E2013`.

use super::{instance_key, part, Instantiator};
use crate::error::FlatError;
use crate::lookup::Found;
use crate::modif::{Mod, Scope};
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// The type an `inner` component `d` of clause `cc` in instance `scope` has, noted
    /// for the check of the `outer` components that will refer to it.
    pub(super) fn note_inner_type(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        d: &ComponentDecl,
        m: &Mod,
        path: &[RefPart],
    ) {
        // A redeclared inner has another type than written: not checked.
        let redeclared = m.child(&d.name.text).is_some_and(|c| c.redeclare.is_some());
        let parts: Vec<&str> = cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
        let found = if redeclared {
            None
        } else {
            self.lookup_class_path(scope, &parts)
        };
        self.inner_types.insert(instance_key(path), found);
    }

    /// An `outer` component: no variables of its own; its references go to the nearest
    /// `inner` component of the same name in an enclosing instance (spec 5.4).
    pub(super) fn outer_component(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        d: &ComponentDecl,
    ) {
        let name = d.name.text.as_str();
        // Inners declared in this very instance do not count: they are siblings.
        let own = scope.prefix.len();
        let found = self
            .inners
            .iter()
            .rev()
            .find(|(n, path)| n == name && path.len() <= own)
            .map(|(_, p)| p.clone());
        let mut key_path = scope.prefix.to_vec();
        key_path.push(part(name, d.name.span));
        let key = instance_key(&key_path);
        let parts: Vec<&str> = cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
        let outer_type = self.lookup_class_path(scope, &parts);
        match found {
            Some(inner) => {
                let inner_type = self
                    .inner_types
                    .get(&instance_key(&inner))
                    .copied()
                    .flatten();
                if let (Some(i), Some(o)) = (inner_type, outer_type) {
                    self.check_inner_subtype(i, o, &inner, d);
                }
                self.outer_alias.insert(key, inner);
            }
            None => match self.default_inner(scope, cc, d, outer_type) {
                Ok(path) => {
                    self.outer_alias.insert(key, path);
                }
                Err(why) => self.report(FlatError::MissingInner {
                    name: name.to_string(),
                    why,
                    span: d.name.span,
                }),
            },
        }
    }

    /// `E2035` when the inner's type `inner` lacks an element of the outer's `outer`.
    fn check_inner_subtype(
        &mut self,
        inner: Found,
        outer: Found,
        path: &[RefPart],
        d: &ComponentDecl,
    ) {
        let why = match (inner, outer) {
            (Found::Builtin(i), Found::Builtin(o)) if i != o => format!("`{i}` is not `{o}`"),
            (Found::Class(i), Found::Class(o)) if i != o => {
                let missing: Vec<String> = self
                    .record_fields(o)
                    .into_iter()
                    .filter(|f| !self.tree.has_component(i, &f.name))
                    .map(|f| format!("`{}`", f.name))
                    .collect();
                if missing.is_empty() {
                    return;
                }
                format!(
                    "`{}` lacks {} of `{}`",
                    self.tree.full_name(i),
                    missing.join(", "),
                    self.tree.full_name(o)
                )
            }
            _ => return,
        };
        let inner_span = path.last().map_or(d.name.span, |p| p.name.span);
        self.report(FlatError::InnerOuterMismatch {
            name: d.name.text.to_string(),
            why: why.to_string(),
            span: d.name.span,
            inner: inner_span,
        });
    }

    /// The inner component created at the top of the model for an `outer` without
    /// one (`W2002`), or why none can be.
    fn default_inner(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        d: &ComponentDecl,
        outer_type: Option<Found>,
    ) -> Result<Vec<RefPart>, String> {
        let name = d.name.text.as_str();
        let ty = outer_type.ok_or_else(|| "its type is unknown".to_owned())?;
        if let Some((_, t, path)) = self.default_inners.iter().find(|(n, _, _)| n == name) {
            return if *t == ty {
                Ok(path.clone())
            } else {
                Err("other `outer` declarations of that name have another class".to_owned())
            };
        }
        // An element of that name at the top (not this outer itself) leaves no room.
        if let Some(&top) = self.ancestors.first() {
            if !scope.prefix.is_empty() && self.tree.has_component(top, name) {
                return Err(format!(
                    "the model has an element `{name}` that is not `inner`"
                ));
            }
        }
        if let Found::Class(c) = ty {
            if self.tree.get(c).def.partial {
                return Err(format!("`{}` is partial", self.tree.full_name(c)));
            }
        }
        let path = vec![part(name, d.name.span)];
        self.default_inners
            .push((d.name.text.clone(), ty, path.clone()));
        let type_name = match ty {
            Found::Class(c) => self.tree.full_name(c),
            Found::Builtin(b) => b.to_owned(),
            Found::Component(_) => return Err("its type is not a class".to_owned()),
        };
        self.report(FlatError::DefaultInner {
            name: name.to_string(),
            type_name: type_name.to_string(),
            span: d.name.span,
        });
        // Instantiated at the top (the type name looked up where the outer is
        // declared), outside the duplicate check of the instance being built.
        let top = Scope {
            class: scope.class,
            prefix: std::sync::Arc::from([]),
        };
        let d_top = ComponentDecl {
            modification: None,
            ..d.clone()
        };
        let causality = self.inherited_causality.take();
        self.declared.push(None);
        self.element_final = false;
        self.component(&top, "", cc, &d_top, &Mod::default(), None, false);
        self.declared.pop();
        self.inherited_causality = causality;
        Ok(path)
    }
}
