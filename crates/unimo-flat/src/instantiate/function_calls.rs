//! Calls of functions that are not plain class paths: a function class element named
//! through a component (`world.gravityAcceleration(r)`, spec 5.3.2: the function of
//! the component's instance, after its redeclarations and through `outer`), and a short
//! function class with a modification (`function f = g(k = 2)`, spec 12.1.2: the
//! modifiers are default values of `g`'s inputs). Both become a call of the long
//! function with the modifiers as named arguments, flattened where they were written
//! (a component's modifiers read the component's parameters: `world.g`).

use super::{instance_key, instance_key_no_subs, Instantiator};
use crate::lookup::Found;
use crate::modif::Scope;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

/// Short classes followed from a call's function to its long definition.
const MAX_CHAIN: usize = 16;

impl Instantiator<'_, '_> {
    /// The long function a call of `func` in `scope` calls and the named arguments the
    /// modifiers of the short classes on the way give it, flattened; `None` when
    /// `func` is a plain function name (a class path without modifiers).
    pub(super) fn modified_function(
        &mut self,
        func: &Name,
        scope: &Scope,
    ) -> Option<(ClassId, Vec<NamedArg>)> {
        let (class, decl_scope) = match self.function_of_component(func, scope) {
            Some(found) => found,
            None => {
                let parts: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
                if func.global {
                    return None;
                }
                let Some(Found::Class(c)) = self.lookup_class_path(scope, &parts) else {
                    return None;
                };
                if !self.is_short_function(c) {
                    return None;
                }
                let decl = self.declaring_scope(c, scope, parts.len() == 1);
                (c, decl)
            }
        };
        let (long, args) = self.modifier_arguments(class, decl_scope);
        Some((long, args))
    }

    /// `a.b.f` where `a` is a component of `scope`: the class `f` denotes in the
    /// instance `a.b` (its redeclaration there, or its declaration in the instance's
    /// class), and the scope its modifiers were written in.
    fn function_of_component(&mut self, func: &Name, scope: &Scope) -> Option<(ClassId, Scope)> {
        if func.global || func.parts.len() < 2 {
            return None;
        }
        let first = func.parts[0].text.as_str();
        if !self.tree.has_component(scope.class, first) {
            return None;
        }
        let (last, path) = func.parts.split_last()?;
        let mut cur = scope.clone();
        for p in path {
            let info = crate::check::find_component(self.tree, cur.class, &p.text)?;
            let mut prefix = cur.prefix.to_vec();
            prefix.push(super::part(&p.text, p.span));
            let mut class = match crate::check::component_type(self.tree, &info)? {
                Found::Class(c) => c,
                _ => return None,
            };
            // An `outer` component stands for its `inner` (spec 5.4).
            if let Some(inner) = self.outer_alias.get(&instance_key_no_subs(&prefix)) {
                prefix = inner.clone();
                if let Some(Some(Found::Class(c))) = self.inner_types.get(&instance_key(&prefix)) {
                    class = *c;
                }
            }
            cur = Scope {
                class,
                prefix: prefix.into(),
            };
        }
        let name = last.text.as_str();
        if let Some(c) = self.redeclared(&cur, name) {
            let decl = self
                .detached_scopes
                .get(&c)
                .cloned()
                .unwrap_or_else(|| self.declaring_scope(c, &cur, true));
            return Some((c, decl));
        }
        let c = self.tree.member_class(cur.class, name)?;
        if self.tree.get(c).def.kind != ClassKind::Function {
            return None;
        }
        let decl = self.declaring_scope(c, &cur, true);
        Some((c, decl))
    }

    /// The scope the modifiers of class `c`, found from `scope`, were written in: the
    /// scope's instance when `c` is a member of its class (`local`: found by a simple
    /// name there), a redeclaration's own scope, else `c`'s enclosing class with no
    /// instance (a package's function).
    fn declaring_scope(&mut self, c: ClassId, scope: &Scope, local: bool) -> Scope {
        if let Some(s) = self.detached_scopes.get(&c) {
            return s.clone();
        }
        let parent = self.tree.get(c).parent.unwrap_or(scope.class);
        let name = self.tree.get(c).name.clone();
        let member = local && self.tree.member_class(scope.class, &name) == Some(c);
        Scope {
            class: parent,
            prefix: if member {
                scope.prefix.clone()
            } else {
                std::sync::Arc::from([])
            },
        }
    }

    /// Whether `c` is a short function class (`function f = g(k = 2)`, `function f = g`).
    fn is_short_function(&mut self, c: ClassId) -> bool {
        let def = self.tree.get(c).def.clone();
        def.kind == ClassKind::Function && matches!(&def.body, ClassBody::Short { .. })
    }

    /// From function class `c` (modifiers written in `scope`) to its long definition:
    /// the long class and the modifiers' bindings as named arguments, the nearest
    /// modifier of an input winning.
    fn modifier_arguments(&mut self, mut c: ClassId, mut scope: Scope) -> (ClassId, Vec<NamedArg>) {
        let mut args: Vec<NamedArg> = Vec::new();
        for _ in 0..MAX_CHAIN {
            let def = self.tree.get(c).def.clone();
            let ClassBody::Short { modification, .. } = &def.body else {
                break;
            };
            for arg in modification.iter().flat_map(|m| &m.args) {
                let Argument::Modify {
                    name,
                    modification:
                        Some(Modification {
                            binding: Some(e), ..
                        }),
                    ..
                } = arg
                else {
                    continue;
                };
                let [input] = name.parts.as_slice() else {
                    continue;
                };
                if args.iter().any(|a| a.name.text == input.text) {
                    continue;
                }
                let value = self.flat_expr(e, &scope);
                args.push(NamedArg {
                    name: input.clone(),
                    value,
                });
            }
            // The base is looked up where the short class was written, through that
            // instance's redeclarations (`redeclare function colorMap = colorMap` names
            // the enclosing instance's `colorMap`).
            let ClassBody::Short { base, .. } = &def.body else {
                break;
            };
            let parts: Vec<&str> = base.parts.iter().map(|p| p.text.as_str()).collect();
            let found = if base.global {
                self.tree.lookup_dotted(None, &parts, false)
            } else {
                self.lookup_class_path(&scope, &parts)
            };
            let Some(Found::Class(base)) = found.filter(|f| *f != Found::Class(c)) else {
                break;
            };
            // The base's own modifiers were written where the base is declared: its
            // redeclaration's scope, the same instance when it is a member of the
            // instance's class, else its package.
            scope = self.declaring_scope(base, &scope, parts.len() == 1);
            c = base;
        }
        (c, args)
    }

    /// The names of the inputs of function `c`, in declaration order (bases first).
    pub(super) fn function_inputs(&mut self, c: ClassId) -> Vec<String> {
        let mut classes = Vec::new();
        self.record_classes(c, &mut classes, 0);
        let mut out: Vec<String> = Vec::new();
        for k in classes {
            let def = self.tree.get(k).def.clone();
            for (_, cc) in def.component_clauses() {
                if cc.prefix.causality != Some(Causality::Input) {
                    continue;
                }
                for d in &cc.components {
                    let n = d.name.text.to_string();
                    if !out.contains(&n) {
                        out.push(n);
                    }
                }
            }
        }
        out
    }
}
