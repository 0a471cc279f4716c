//! Expressions flattened: references made absolute (`cref`), calls and array
//! constructors resolved, reductions unrolled; expressions and statements of function
//! bodies, whose locals stay local.

use super::{instance_key_no_subs, instance_name, int_expr, part, Instantiator};
use crate::eval::{self, Value};
use crate::lookup::{is_builtin_function, Found};
use crate::modif::Scope;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// A reference made absolute: the instance prefix added to a component of the
    /// scope; `for` indices replaced by their value; package constants inlined.
    pub(super) fn cref(
        &mut self,
        r: &ComponentRef,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> ComponentRef {
        let Some(first) = r.parts.first().map(|p| p.name.text.clone()) else {
            return r.clone();
        };
        let plain = r.global || first == "time" || locals.iter().any(|l| *l == first);
        let component = !plain && self.tree.has_component(scope.class, &first);
        // A component reference gets the instance prefix (unless it goes through an
        // `outer`, below): the prefix is written first, then the parts as written.
        let direct = component && self.outer_alias.is_empty();
        let mut parts: Vec<RefPart> =
            Vec::with_capacity(if direct { scope.prefix.len() } else { 0 } + r.parts.len());
        if direct {
            parts.extend_from_slice(&scope.prefix);
        }
        for p in &r.parts {
            let mut subscripts = p.subscripts.clone();
            for s in &mut subscripts {
                if let Subscript::Expr(e) = s {
                    *e = self.expr(e, scope, iters, locals);
                    // Constant subscripts are folded (`x[i + 1]` in an unrolled loop is
                    // `x[3]`), so that every reference to an element looks the same.
                    if !matches!(e.kind, ExprKind::Integer(_) | ExprKind::End) && locals.is_empty()
                    {
                        if let Ok(Value::Int(k)) = eval::eval(e, self, &mut Vec::new()) {
                            *e = int_expr(k, e.span);
                        }
                    }
                }
            }
            parts.push(RefPart {
                name: p.name.clone(),
                subscripts,
            });
        }
        let r = ComponentRef {
            global: r.global,
            parts,
            span: r.span,
        };
        if plain || direct {
            return r;
        }
        if component {
            return self.through_outer(r, scope);
        }
        // A class path: an enumeration literal or a package constant, made global.
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        let owner = match self.tree.lookup_simple(Some(scope.class), &first, false) {
            Some(Found::Class(c)) => Some(c),
            Some(Found::Component(c)) => Some(c),
            _ => None,
        };
        if let Some(owner) = owner {
            let full = match self.tree.lookup_dotted(Some(scope.class), &names, false) {
                Some(Found::Component(c)) => {
                    let mut n = self.tree.full_name(c);
                    n.push('.');
                    n.push_str(names.last().copied().unwrap_or(""));
                    n
                }
                Some(Found::Class(c)) => self.tree.full_name(c),
                _ => {
                    let _ = owner;
                    return r;
                }
            };
            let mut parts: Vec<RefPart> = crate::flat::split_name(&full)
                .into_iter()
                .map(|p| part(p, r.span))
                .collect();
            if let (Some(last), Some(orig)) = (parts.last_mut(), r.parts.last()) {
                last.subscripts = orig.subscripts.clone();
            }
            return ComponentRef {
                global: true,
                parts,
                span: r.span,
            };
        }
        r
    }

    /// A reference whose first part is an `outer` component, sent to its `inner` (or
    /// prefixed like any component when the instance has no `inner` for it).
    fn through_outer(&self, r: ComponentRef, scope: &Scope) -> ComponentRef {
        let mut head = scope.prefix.to_vec();
        head.push(r.parts[0].clone());
        let parts = match self.outer_alias.get(&instance_key_no_subs(&head)) {
            Some(inner) => {
                let mut p = inner.clone();
                if let Some(last) = p.last_mut() {
                    if !r.parts[0].subscripts.is_empty() {
                        last.subscripts = r.parts[0].subscripts.clone();
                    }
                }
                p.extend(r.parts.into_iter().skip(1));
                p
            }
            None => {
                head.extend(r.parts.into_iter().skip(1));
                head
            }
        };
        ComponentRef {
            global: false,
            parts,
            span: r.span,
        }
    }

    /// `e` flattened in `scope`, outside any loop.
    pub(crate) fn flat_expr(&mut self, e: &Expr, scope: &Scope) -> Expr {
        self.expr(e, scope, &mut Vec::new(), &mut Vec::new())
    }

    pub(crate) fn expr(
        &mut self,
        e: &Expr,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Expr {
        let span = e.span;
        let kind = match &e.kind {
            ExprKind::Ref(r) => {
                if r.parts.len() == 1 && !r.global {
                    let n = r.parts[0].name.text.as_str();
                    if !locals.iter().any(|l| l == n) {
                        if let Some((_, v)) = iters.iter().rev().find(|(k, _)| k == n) {
                            return v.to_expr(span);
                        }
                    }
                }
                if let Some(v) = self.redeclared_constant(r, scope, locals) {
                    return v;
                }
                let fr = self.cref(r, scope, iters, locals);
                if fr.global {
                    if let Some(v) = self.package_constant(&fr) {
                        return v;
                    }
                }
                ExprKind::Ref(fr)
            }
            ExprKind::Call { func, args } => {
                return self.call_expr((func, args), span, scope, iters, locals)
            }
            ExprKind::Comprehension { body, indices } => {
                self.comprehension_expr((body, indices), scope, iters, locals)
            }
            ExprKind::Unary { op, operand } => ExprKind::Unary {
                op: *op,
                operand: Box::new(self.expr(operand, scope, iters, locals)),
            },
            ExprKind::Binary { op, lhs, rhs } => ExprKind::Binary {
                op: *op,
                lhs: Box::new(self.expr(lhs, scope, iters, locals)),
                rhs: Box::new(self.expr(rhs, scope, iters, locals)),
            },
            ExprKind::If {
                branches,
                otherwise,
            } => ExprKind::If {
                branches: branches
                    .iter()
                    .map(|(c, v)| {
                        (
                            self.expr(c, scope, iters, locals),
                            self.expr(v, scope, iters, locals),
                        )
                    })
                    .collect(),
                otherwise: Box::new(self.expr(otherwise, scope, iters, locals)),
            },
            ExprKind::Range { start, step, stop } => ExprKind::Range {
                start: Box::new(self.expr(start, scope, iters, locals)),
                step: step
                    .as_ref()
                    .map(|s| Box::new(self.expr(s, scope, iters, locals))),
                stop: Box::new(self.expr(stop, scope, iters, locals)),
            },
            ExprKind::Array(items) => ExprKind::Array(
                items
                    .iter()
                    .map(|i| self.expr(i, scope, iters, locals))
                    .collect(),
            ),
            ExprKind::Matrix(rows) => ExprKind::Matrix(
                rows.iter()
                    .map(|r| {
                        r.iter()
                            .map(|i| self.expr(i, scope, iters, locals))
                            .collect()
                    })
                    .collect(),
            ),
            ExprKind::Tuple(items) => ExprKind::Tuple(
                items
                    .iter()
                    .map(|i| i.as_ref().map(|e| self.expr(e, scope, iters, locals)))
                    .collect(),
            ),
            other => other.clone(),
        };
        Expr { kind, span }
    }

    /// A comprehension flattened: written out as an array when its body selects
    /// components by the iterator, else with its body and ranges flattened.
    fn comprehension_expr(
        &mut self,
        (body, indices): (&Expr, &[ForIndex]),
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> ExprKind {
        if let Some(items) = self.unroll(body, indices, scope, iters, locals) {
            return ExprKind::Array(items);
        }
        let indices = self.indices(indices, scope, iters, locals);
        let n = indices.len();
        locals.extend(indices.iter().map(|i| i.name.text.to_string()));
        let body = Box::new(self.expr(body, scope, iters, locals));
        locals.truncate(locals.len() - n);
        ExprKind::Comprehension { body, indices }
    }

    /// A call flattened: its function named by its full name (a built-in's alias, an
    /// external object's constructor), a reduction over component array elements
    /// written out, its arguments flattened; `getInstanceName()` replaced by its text.
    fn call_expr(
        &mut self,
        (func, args): (&Name, &CallArgs),
        span: Span,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Expr {
        let simple = func.parts.len() == 1;
        if simple && func.parts[0].text == "getInstanceName" && args.positional.is_empty() {
            return instance_name(&self.model.name, &scope.prefix, span);
        }
        let modified = if simple && is_builtin_function(&func.parts[0].text) {
            None
        } else {
            self.modified_function(func, scope)
        };
        let func = match &modified {
            Some((c, _)) => self.class_call_name(*c, func.span),
            None => self.call_name(func, scope),
        };
        // A reduction over component array elements (`sum(c[i].f for i in
        // 1:n)`) is written out: `sum({c[1].f, c[2].f, ...})`.
        if let (Some(body), true) = (args.positional.first(), args.positional.len() == 1) {
            if let Some(items) = self.unroll(body, &args.iterators, scope, iters, locals) {
                return Expr {
                    kind: ExprKind::Call {
                        func,
                        args: Box::new(CallArgs {
                            positional: vec![Expr {
                                kind: ExprKind::Array(items),
                                span,
                            }],
                            named: Vec::new(),
                            iterators: Vec::new(),
                            span: args.span,
                        }),
                    },
                    span,
                };
            }
        }
        let n = args.iterators.len();
        let iterators = self.indices(&args.iterators, scope, iters, locals);
        locals.extend(iterators.iter().map(|i| i.name.text.to_string()));
        let positional = args
            .positional
            .iter()
            .map(|a| self.expr(a, scope, iters, locals))
            .collect();
        let mut named: Vec<NamedArg> = args
            .named
            .iter()
            .map(|a| NamedArg {
                name: a.name.clone(),
                value: self.expr(&a.value, scope, iters, locals),
            })
            .collect();
        locals.truncate(locals.len() - n);
        // The modifiers of a short function class give the inputs the call leaves out.
        if let Some((c, defaults)) = modified {
            let inputs = self.function_inputs(c);
            let n_pos = args.positional.len();
            for d in defaults {
                let by_position = inputs.iter().position(|i| *i == d.name.text.as_str());
                let given = named.iter().any(|a| a.name.text == d.name.text)
                    || by_position.is_some_and(|k| k < n_pos);
                if !given {
                    named.push(d);
                }
            }
        }
        Expr {
            kind: ExprKind::Call {
                func,
                args: Box::new(CallArgs {
                    positional,
                    named,
                    iterators,
                    span: args.span,
                }),
            },
            span,
        }
    }

    /// The name a call's function is flattened to: a built-in stays as written (without
    /// a leading dot), a class gets its full name.
    fn call_name(&mut self, func: &Name, scope: &Scope) -> Name {
        // `.asin(u)` names the built-in from the global scope.
        let simple = func.parts.len() == 1;
        if simple && is_builtin_function(&func.parts[0].text) {
            Name {
                global: false,
                ..func.clone()
            }
        } else {
            let parts: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
            let found = if func.global {
                self.tree.lookup_dotted(None, &parts, false)
            } else {
                self.lookup_class_path(scope, &parts)
            };
            match found {
                Some(Found::Class(c)) => self.class_call_name(c, func.span),
                _ => func.clone(),
            }
        }
    }

    /// The name a call of function class `c` is flattened to: its full name, a
    /// built-in's alias, or an external object's constructor.
    fn class_call_name(&mut self, c: crate::tree::ClassId, span: Span) -> Name {
        let c = self.real_class(c);
        let def = self.tree.get(c).def.clone();
        let builtin = crate::external::builtin_alias(&def);
        let full = match builtin {
            Some(b) => b.to_owned(),
            // `Table(...)` of an external object class calls its constructor.
            None if crate::external::is_external_object(&def) => {
                format!("{}.constructor", self.tree.full_name(c))
            }
            None => self.tree.full_name(c),
        };
        Name {
            global: builtin.is_none(),
            ..crate::overconstrained::dotted_name(&full, span)
        }
    }

    /// The elements of a one-iterator comprehension whose body selects components by
    /// the iterator (`{coil[i].r[3] for i in 1:n}`), when its range is known: a flat
    /// model has `coil[1].r`, not `coil[i].r`.
    pub(super) fn unroll(
        &mut self,
        body: &Expr,
        indices: &[ForIndex],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Option<Vec<Expr>> {
        let [index] = indices else {
            return None;
        };
        let name = index.name.text.as_str();
        let mut selects = false;
        crate::flat::for_each_ref(body, &mut |r| {
            let n = r.parts.len();
            for p in &r.parts[..n.saturating_sub(1)] {
                for sub in &p.subscripts {
                    if let Subscript::Expr(e) = sub {
                        let mut uses = false;
                        crate::flat::for_each_ref(e, &mut |x| {
                            uses |= x.parts.len() == 1 && x.parts[0].name.text == name;
                        });
                        selects |= uses;
                    }
                }
            }
        });
        if !selects {
            return None;
        }
        let range = self.expr(index.range.as_ref()?, scope, iters, locals);
        let Ok(Value::Array(values)) = eval::eval(&range, self, iters) else {
            return None;
        };
        let mut items = Vec::with_capacity(values.len());
        for v in values {
            iters.push((name.to_owned(), v));
            items.push(self.expr(body, scope, iters, locals));
            iters.pop();
        }
        Some(items)
    }

    /// `for` indices with their ranges made absolute (the names stay local).
    pub(super) fn indices(
        &mut self,
        indices: &[ForIndex],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Vec<ForIndex> {
        indices
            .iter()
            .map(|i| ForIndex {
                name: i.name.clone(),
                range: i.range.as_ref().map(|r| {
                    let flat = self.expr(r, scope, iters, locals);
                    // A range of a function's inputs or locals stays as written.
                    let mut local = false;
                    crate::flat::for_each_ref(&flat, &mut |r| {
                        local |= !r.global
                            && r.parts
                                .first()
                                .is_some_and(|p| locals.iter().any(|l| *l == p.name.text))
                    });
                    if local {
                        return flat;
                    }
                    // A range of parameters is decided here, so that the flat text
                    // names no structural parameter (they are folded away).
                    match eval::eval(&flat, self, iters) {
                        Ok(v @ Value::Array(_)) => v.to_expr(r.span),
                        _ => flat,
                    }
                }),
            })
            .collect()
    }

    /// An expression of a function body, with names resolved in the function's scope.
    pub(crate) fn expr_in_function(&mut self, e: &Expr, scope: &Scope) -> Expr {
        self.expr(e, scope, &mut Vec::new(), &mut Vec::new())
    }

    /// An expression of a function body, its formal parameters and locals kept local.
    pub(crate) fn function_expr(
        &mut self,
        e: &Expr,
        scope: &Scope,
        locals: &mut Vec<String>,
    ) -> Expr {
        self.expr(e, scope, &mut Vec::new(), locals)
    }

    /// A statement of a function body, its formal parameters and locals kept local.
    pub(crate) fn function_statement(
        &mut self,
        st: &Statement,
        scope: &Scope,
        locals: &mut Vec<String>,
    ) -> Statement {
        self.statement(st, scope, locals)
    }
}
