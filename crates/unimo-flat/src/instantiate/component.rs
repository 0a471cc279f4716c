//! Instantiation of one component declaration: its type resolved, its modifiers
//! merged, array components expanded, and the variables of predefined types created.

use super::class_body::Body;
use super::{
    annotation_is_true, duplicate, index_tuples, instance_key, int_expr, part, Instantiator, Kind,
    ATTRIBUTES,
};
use crate::error::FlatError;
use crate::eval::{self, EvalError, Value};
use crate::flat::{FlatType, FlatVar, Variability};
use crate::lookup::Found;
use crate::modif::{Bound, Mod, Scope};
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn component(
        &mut self,
        scope: &Scope,
        prefix_key: &str,
        cc: &ComponentClause,
        d: &ComponentDecl,
        m: &Mod,
        inherited: Option<Variability>,
        top: bool,
    ) {
        let name = d.name.text.as_str();
        if !self.first_declaration(scope, d) {
            return;
        }
        let decl_mod = d
            .modification
            .as_ref()
            .map(|dm| Mod::from_modification(dm, scope))
            .unwrap_or_default();
        let mut merged = match m.child(name) {
            Some(outer) => outer.clone().over_into(decl_mod),
            None => decl_mod,
        };
        // The full name (`s1.a.f`): the instance's key and the element's name.
        let key = if prefix_key.is_empty() {
            name.to_owned()
        } else {
            let mut k = String::with_capacity(prefix_key.len() + 1 + name.len());
            k.push_str(prefix_key);
            k.push('.');
            k.push_str(name);
            k
        };
        if !self.is_present(scope, d) {
            self.absent.push(key);
            return;
        }
        let found = self.clause_type(scope, cc, d, &mut merged);
        let Some(found) = found else {
            // The name check covers the flattened class and its nested classes; a type
            // unknown in a class used from elsewhere (a record, a library model) is
            // reported here (`flatten` drops the repeat of one already reported).
            let d = crate::resolve::unknown_name(self.tree, scope.class, &cc.type_name, "type");
            self.diags.push(d);
            return;
        };
        let Some((kind, merged, short_dims)) = self.resolve_type_dims(found, merged) else {
            return;
        };
        let type_causality = self.type_causality.take();
        let variability = match cc.prefix.variability {
            Some(unimo_syntax::ast::Variability::Constant) => Some(Variability::Constant),
            Some(unimo_syntax::ast::Variability::Parameter) => Some(Variability::Parameter),
            Some(unimo_syntax::ast::Variability::Discrete) => Some(Variability::Discrete),
            None => inherited,
        };
        let dims = self.component_dims(scope, cc, d, &merged, &short_dims);
        let count = dims
            .iter()
            .try_fold(1usize, |acc, &n| acc.checked_mul(n))
            .unwrap_or(usize::MAX);
        if !self.spend(count, d.span) {
            return;
        }
        // `connector RealInput = input Real`: the type's prefix, under the clause's own.
        let saved = self.inherited_causality;
        self.inherited_causality = type_causality.or(saved);
        match kind {
            Kind::Builtin(ty) => {
                let var = self.builtin_var(key, ty, &merged, cc, d, variability, dims, top);
                self.model.vars.push(var);
            }
            Kind::Class(c) => {
                let declaration = (scope, cc, d);
                self.structured_component(c, key, merged, dims, declaration, variability, top);
            }
        }
        self.inherited_causality = saved;
    }

    /// A component of a class type: a record's binding split into field bindings or
    /// kept as a record equation, its causality passed down, its class body instantiated
    /// once or per element of an array.
    #[allow(clippy::too_many_arguments)]
    fn structured_component(
        &mut self,
        c: ClassId,
        key: String,
        merged: Mod,
        dims: Vec<usize>,
        (scope, cc, d): (&Scope, &ComponentClause, &ComponentDecl),
        variability: Option<Variability>,
        top: bool,
    ) {
        let name = d.name.text.as_str();
        if self.partial_instance(c, &key, d) {
            return;
        }
        let mut path = Vec::with_capacity(scope.prefix.len() + 1);
        path.extend_from_slice(&scope.prefix);
        path.push(part(name, d.name.span));
        let record = self.is_record(c);
        // A record binding is split into field bindings where it can be
        // (per element of an array of records).
        let merged = if record && dims.is_empty() {
            self.note_record_instance(&key, c);
            self.split_record_binding(c, merged)
        } else {
            merged
        };
        // An array of records is bound element by element when its binding
        // can be taken apart (an array of constructor calls, a record array).
        let per_element = record
            && !dims.is_empty()
            && merged.binding.as_ref().is_some_and(|b| {
                let first = vec![1; dims.len()];
                self.pick_element(&b.expr, &b.scope, &first).is_some()
            });
        // A binding of a structured component left whole is a record equation.
        if !per_element {
            self.record_binding_equation(&merged, &path, variability, &key, d.span);
        }
        // `input`/`output` on a structured component applies to its variables;
        // those of the top-level model's connectors are the model's interface.
        let saved = self.inherited_causality;
        self.inherited_causality = cc.prefix.causality.or(saved);
        if self.tree.get(c).def.prefixes.expandable {
            self.expandable.push(key.clone());
        }
        let connector = self.tree.get(c).def.kind == ClassKind::Connector;
        if connector {
            self.connector_keys.insert(key.clone());
        }
        let top = top && connector;
        if dims.is_empty() {
            if !record {
                self.note_visual(c, super::instance_key(&path));
            }
            self.class_body(Body::new(c, &path, &merged, variability, top));
        } else {
            let elements = (record, per_element);
            self.structured_elements(c, &path, &merged, &dims, elements, variability, top, d.span);
        }
        self.inherited_causality = saved;
    }

    /// An instance of a partial class (spec 4.7; an `outer` component is not
    /// instantiated here, it refers to its inner): `E2009`, and `true`.
    fn partial_instance(&mut self, c: ClassId, key: &str, d: &ComponentDecl) -> bool {
        if !self.tree.get(c).def.partial {
            return false;
        }
        let class_name = self.tree.full_name(c);
        self.diags.push(
            FlatError::PartialComponent {
                name: key.to_string(),
                class: class_name,
                span: d.name.span,
                declared: self.tree.get(c).def.name.span,
            }
            .into(),
        );
        true
    }

    /// The elements of an array of structured components, each with its part of the
    /// modifiers (a record element with its part of the binding).
    #[allow(clippy::too_many_arguments)]
    fn structured_elements(
        &mut self,
        c: ClassId,
        path: &[RefPart],
        merged: &Mod,
        dims: &[usize],
        (record, per_element): (bool, bool),
        variability: Option<Variability>,
        top: bool,
        span: Span,
    ) {
        for t in index_tuples(dims) {
            let mut p = path.to_vec();
            if let Some(last) = p.last_mut() {
                last.subscripts = t
                    .iter()
                    .map(|i| Subscript::Expr(int_expr(*i, span)))
                    .collect();
            }
            // A modifier without `each` gives element t its part of the
            // array value (spec 7.2.5).
            let mut element = self.element_mod(merged, &t);
            if record {
                let key = instance_key(&p);
                self.note_record_instance(&key, c);
                element.binding = if per_element {
                    merged.binding.as_ref().and_then(|b| {
                        let e = self.pick_element(&b.expr, &b.scope, &t)?;
                        Some(Bound {
                            expr: e,
                            scope: b.scope.clone(),
                        })
                    })
                } else {
                    None
                };
                element = self.split_record_binding(c, element);
                self.record_binding_equation(&element, &p, variability, &key, span);
            } else {
                self.note_visual(c, instance_key(&p));
            }
            self.class_body(Body::new(c, &p, &element, variability, top));
        }
    }

    /// Whether `d` is the first declaration of its name in the class being instantiated
    /// (a second one is `E2005`, reported here; the same declaration met again through
    /// a second inheritance path is no second one).
    fn first_declaration(&mut self, scope: &Scope, d: &ComponentDecl) -> bool {
        let name = d.name.text.as_str();
        let Some(level) = self.declared.last_mut() else {
            return false;
        };
        if let Some(seen) = level {
            if let Some(first) = seen.get(name).copied() {
                if first == d.name.span {
                    // The same declaration inherited along two paths (a base extended
                    // twice, as the MSL's `Visualizers.Advanced.Shape` does): one
                    // element (spec 7.1.4: identical inherited elements are one). The
                    // class keeps this check on its later instances (it is not
                    // "duplicate-free"): without it they would create the element twice.
                    if let Some(f) = self.duplicate_found.last_mut() {
                        *f = true;
                    }
                    return false;
                }
                let owner = if scope.prefix.is_empty() {
                    self.model.name.clone()
                } else {
                    instance_key(&scope.prefix)
                };
                self.diags.push(duplicate(name, &owner, d.name.span, first));
                if let Some(f) = self.duplicate_found.last_mut() {
                    *f = true;
                }
                return false;
            }
            seen.insert(d.name.text.clone(), d.name.span);
        }
        true
    }

    /// Whether a component is present: not a conditional one whose condition is false.
    fn is_present(&mut self, scope: &Scope, d: &ComponentDecl) -> bool {
        let Some(cond) = &d.condition else {
            return true;
        };
        let flat = self.expr(cond, scope, &mut Vec::new(), &mut Vec::new());
        match eval::eval(&flat, self, &mut Vec::new()) {
            Ok(Value::Bool(false)) => return false,
            Ok(Value::Bool(true)) => {}
            Ok(_) => self.report(FlatError::ConditionNotBoolean { span: cond.span }),
            Err(e) => self.eval_error(e, "condition of a conditional component"),
        }
        true
    }

    /// The class or type of a component clause: its redeclared class (checked to fit),
    /// or the clause's type with a replaceable class's constraining modifiers merged into
    /// `merged`.
    fn clause_type(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        d: &ComponentDecl,
        merged: &mut Mod,
    ) -> Option<Found> {
        let name = d.name.text.as_str();
        match &merged.redeclare {
            Some((n, s)) => {
                let parts: Vec<&str> = n.parts.iter().map(|p| p.text.as_str()).collect();
                let found = self.tree.lookup_dotted(Some(s.class), &parts, false);
                if let Some(Found::Class(new)) = found {
                    self.check_plug_compatible(scope, cc, name, new, n.span);
                }
                found
            }
            None => {
                // Without class redeclarations a clause's type depends on its class
                // only: cached by (class, clause).
                let key = (scope.class, &cc.type_name as *const Name as usize);
                let cacheable = self.class_redeclares.is_empty();
                match self.clause_types.get(&key) {
                    Some(&(found, true)) if cacheable => found,
                    _ => {
                        let parts: Vec<&str> =
                            cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
                        let found = self.lookup_class_path(scope, &parts);
                        // A replaceable class's constraining modifiers (and, when it
                        // was redeclared, a check that the new class fits).
                        let mut unconstrained = true;
                        if let Some(Found::Class(c)) = found {
                            if let Some(cmod) = self.class_constraint(scope, &parts, c, d.span) {
                                *merged = std::mem::take(merged).over_into(cmod);
                                unconstrained = false;
                            }
                        }
                        if cacheable {
                            self.clause_types.insert(key, (found, unconstrained));
                        }
                        found
                    }
                }
            }
        }
    }

    /// A component's dimensions: the name's, the clause's, then those of short class
    /// definitions of its type; `[:]` sized by the binding.
    fn component_dims(
        &mut self,
        scope: &Scope,
        cc: &ComponentClause,
        d: &ComponentDecl,
        merged: &Mod,
        short_dims: &[(Subscript, Scope)],
    ) -> Vec<usize> {
        let mut dims = Vec::new();
        // `Real[3] x[2]` is `Real x[2, 3]` (spec 10.1): the name's dimensions come first.
        for s in d.dims.iter().chain(&cc.type_dims) {
            match s {
                Subscript::Expr(e) => {
                    if let Some(n) = self.dimension(e, scope) {
                        dims.push(n);
                    }
                }
                Subscript::Colon(span) => {
                    // `[:]`: the size comes from the binding.
                    // Its value when it is constant; else its shape, which a binding
                    // of variables (`reset = {b1.on, b2.on}`) has too.
                    let mut refused = None;
                    let size = merged.binding.clone().and_then(|b| {
                        let flat = self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new());
                        match eval::eval(&flat, self, &mut Vec::new()) {
                            Ok(v) => Some(v.dims()),
                            Err(e) => {
                                if let EvalError::Unsupported { what, .. } = e {
                                    refused = Some(what);
                                }
                                self.shape_of(&flat)
                            }
                        }
                    });
                    match size {
                        Some(vd) if vd.len() > dims.len() => dims.push(vd[dims.len()]),
                        _ => {
                            self.report(FlatError::ColonSizeUnknown {
                                span: *span,
                                refused: refused.map(|what| what.to_string()),
                            });
                        }
                    }
                }
            }
        }
        for (sub, dim_scope) in short_dims {
            if let Subscript::Expr(e) = sub {
                if let Some(n) = self.dimension(e, dim_scope) {
                    dims.push(n);
                }
            }
        }
        dims
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn builtin_var(
        &mut self,
        name: String,
        ty: FlatType,
        m: &Mod,
        cc: &ComponentClause,
        d: &ComponentDecl,
        variability: Option<Variability>,
        dims: Vec<usize>,
        top: bool,
    ) -> FlatVar {
        let mut attributes = Vec::new();
        let mut each_attributes = Vec::new();
        for (attr, am) in &m.children {
            if !ATTRIBUTES.contains(&attr.as_str()) {
                let span = am.binding.as_ref().map_or(d.span, |b| b.expr.span);
                self.diags.push(
                    FlatError::NotAnAttribute {
                        attribute: attr.to_string(),
                        name: name.to_string(),
                        attributes: ATTRIBUTES,
                        span,
                    }
                    .into(),
                );
                continue;
            }
            if let Some(b) = &am.binding {
                attributes.push((
                    attr.clone(),
                    self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new()),
                ));
                if am.each {
                    each_attributes.push(attr.clone());
                }
            }
        }
        let binding = m
            .binding
            .as_ref()
            .map(|b: &Bound| self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new()));
        let discrete_type = matches!(
            ty,
            FlatType::Integer | FlatType::Boolean | FlatType::String | FlatType::Enumeration { .. }
        );
        let variability = match variability {
            Some(v) => v,
            None if discrete_type => Variability::Discrete,
            None => Variability::Continuous,
        };
        FlatVar {
            name,
            ty,
            variability,
            causality: cc.prefix.causality.or(self.inherited_causality),
            flow: cc.prefix.connection == Some(Connection::Flow),
            dims,
            binding: binding.map(Box::new),
            attributes,
            each_attributes,
            description: d.comment.description.clone(),
            top_level: top,
            evaluate: annotation_is_true(d.comment.annotation.as_ref(), "Evaluate"),
            is_final: std::mem::take(&mut self.element_final) || m.is_final,
            origin: d.span,
        }
    }
}
