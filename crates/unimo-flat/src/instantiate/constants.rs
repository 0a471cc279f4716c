//! Compile-time values: package and class constants inlined as literals, and the
//! variables the constant evaluator reads (`Env`).

use super::{Instantiator, MAX_DEPTH};
use crate::eval::{self, Arguments, Env, EvalError, Value};
use crate::flat::Variability;
use crate::lookup::Found;
use crate::modif::Scope;
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// The value of a package constant (`Modelica.Constants.pi`), as a literal.
    pub(super) fn package_constant(&mut self, r: &ComponentRef) -> Option<Expr> {
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        let (last, owner_path) = names.split_last()?;
        let Some(Found::Class(owner)) = self.tree.lookup_dotted(None, owner_path, false) else {
            return None;
        };
        let (binding, scope) = self.class_constant(owner, last, 0)?;
        let flat = self.expr(&binding, &scope, &mut Vec::new(), &mut Vec::new());
        let v = eval::eval(&flat, self, &mut Vec::new()).ok()?;
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        if subs.is_empty() {
            Some(v.to_expr(r.span))
        } else {
            None
        }
    }

    /// The value of constant `name` of class `owner`: declared there, or inherited,
    /// with the modifiers of short class definitions and `extends` clauses on the way
    /// (`package Water extends PartialMedium(cp = 4184)`, `package M = Water`).
    pub(crate) fn class_constant(
        &mut self,
        owner: ClassId,
        name: &str,
        depth: usize,
    ) -> Option<(Expr, Scope)> {
        if depth > MAX_DEPTH {
            return None;
        }
        let def = self.tree.get(owner).def.clone();
        let here = Scope {
            class: owner,
            prefix: std::sync::Arc::from([]),
        };
        let modified = |cm: &Option<ClassModification>| -> Option<Expr> {
            cm.iter().flat_map(|m| &m.args).find_map(|a| match a {
                Argument::Modify {
                    name: n,
                    modification: Some(m),
                    ..
                } if n.parts.len() == 1 && n.parts[0].text == name => m.binding.clone(),
                _ => None,
            })
        };
        match &def.body {
            ClassBody::Short { modification, .. } => {
                // The modifier of a short class is written in its enclosing scope.
                if let Some(b) = modified(modification) {
                    let scope = Scope {
                        class: self.tree.get(owner).parent.unwrap_or(owner),
                        prefix: std::sync::Arc::from([]),
                    };
                    return Some((b, scope));
                }
                let base = self.tree.bases(owner).first().copied()?;
                self.class_constant(base, name, depth + 1)
            }
            ClassBody::Long {
                composition,
                extends: class_extends,
                ..
            } => {
                for e in &composition.elements {
                    if let ElementKind::Component(cc) = &e.kind {
                        if let Some(d) = cc.components.iter().find(|d| d.name.text == name) {
                            if cc.prefix.variability
                                != Some(unimo_syntax::ast::Variability::Constant)
                            {
                                return None;
                            }
                            let b = d.modification.as_ref()?.binding.clone()?;
                            return Some((b, here));
                        }
                    }
                }
                // The bases in `bases` order: a class extension's original first.
                let extends: Vec<Option<ClassModification>> = class_extends
                    .iter()
                    .map(|x| x.modification.clone())
                    .chain(composition.elements.iter().filter_map(|e| match &e.kind {
                        ElementKind::Extends(x) => Some(x.modification.clone()),
                        _ => None,
                    }))
                    .collect();
                let bases = self.tree.bases(owner);
                for (base, m) in bases.into_iter().zip(extends) {
                    if !self.tree.has_component(base, name) {
                        continue;
                    }
                    if let Some(b) = modified(&m) {
                        return Some((b, here));
                    }
                    return self.class_constant(base, name, depth + 1);
                }
                None
            }
            ClassBody::Enumeration { .. } | ClassBody::Der { .. } => None,
        }
    }
}

impl Env for Instantiator<'_, '_> {
    fn dims(&mut self, key: &str) -> Option<Vec<usize>> {
        let id = self.var_id(key)?;
        Some(self.model.vars[id.0 as usize].dims.clone())
    }

    fn call(&mut self, name: &str, args: Arguments, span: Span) -> Result<Value, EvalError> {
        self.call_function(name, args, span)
    }

    fn var(&mut self, key: &str, span: Span) -> Result<Value, EvalError> {
        if let Some(v) = self.values.get(key) {
            return Ok(v.clone());
        }
        let Some(id) = self.var_id(key) else {
            if let Some(v) = self.enum_literal(key) {
                return Ok(v);
            }
            if let Some(r) = self.record_instance_value(key, span) {
                return r;
            }
            if let Some(r) = self.pending_own_value(key, span) {
                return r;
            }
            return Err(EvalError::NotConstant {
                span,
                what: format!("`{key}`"),
            });
        };
        let var = self.model.vars[id.0 as usize].clone();
        if !matches!(
            var.variability,
            Variability::Parameter | Variability::Constant
        ) {
            return Err(EvalError::NotConstant {
                span,
                what: format!("the variable `{key}`"),
            });
        }
        // The specification's rule, as in lowering (`unimo_dae::params`): a parameter
        // with `fixed = false` is computed by initial equations; its start value is a
        // guess, not a value the model can be translated with.
        if var.variability == Variability::Parameter && self.fixed_false(&var) {
            return Err(EvalError::NotConstant {
                span,
                what: format!("`{key}`, a parameter computed at initialization (fixed = false)"),
            });
        }
        let expr = var
            .binding
            .as_deref()
            .cloned()
            .or_else(|| {
                var.attributes
                    .iter()
                    .find(|(n, _)| n == "start")
                    .map(|(_, e)| e.clone())
            })
            .ok_or_else(|| EvalError::NotConstant {
                span,
                what: format!("`{key}`, a parameter without a value"),
            })?;
        if !self.evaluating.insert(key.to_owned()) {
            return Err(EvalError::Cycle {
                span,
                name: key.to_owned(),
            });
        }
        let r = eval::eval(&expr, self, &mut Vec::new());
        self.evaluating.remove(key);
        let v = r?;
        self.values.insert(key.to_owned(), v.clone());
        Ok(v)
    }
}

impl Instantiator<'_, '_> {
    /// The value of the record instance `key` (its fields' values), `None` when `key`
    /// is no record instance.
    fn record_instance_value(&mut self, key: &str, span: Span) -> Option<Result<Value, EvalError>> {
        let (_, class_name) = self
            .model
            .record_instances
            .iter()
            .find(|(k, _)| k == key)?
            .clone();
        let parts = crate::flat::split_name(&class_name);
        let Some(Found::Class(class)) = self.tree.lookup_dotted(None, &parts, false) else {
            return None;
        };
        let mut fields = Vec::new();
        for f in self.record_fields(class) {
            match self.var(&format!("{key}.{}", f.name), span) {
                Ok(v) => fields.push((f.name.to_string(), v)),
                Err(e) => return Some(Err(e)),
            }
        }
        Some(Ok(Value::Record(class_name, fields)))
    }

    /// Whether a variable's `fixed` attribute is the literal or evaluated `false`.
    fn fixed_false(&mut self, var: &crate::flat::FlatVar) -> bool {
        let Some((_, e)) = var.attributes.iter().find(|(n, _)| n == "fixed") else {
            return false;
        };
        matches!(eval::eval(e, self, &mut Vec::new()), Ok(Value::Bool(false)))
    }
}
