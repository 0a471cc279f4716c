//! The user functions a flat model calls: their signatures and algorithm bodies with
//! names resolved (calls made global, package constants inlined), for the back end.

use crate::eval::{self, Value};
use crate::flat::FlatType;
use crate::instantiate::{Instantiator, Kind};
use crate::lookup::Found;
use crate::modif::Mod;
use crate::modif::Scope;
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;
use unimo_syntax::visit::{equation_exprs, statement_exprs, walk_expr, Walk};

/// A formal parameter or local variable of a function.
#[derive(Clone, Debug)]
pub struct FuncVar {
    pub name: String,
    /// The declared type as written (`Real`, `Integer`, `Boolean`, ...).
    pub type_name: String,
    /// Dimensions; `None` for `:` or a size not known at compile time.
    pub dims: Vec<Option<usize>>,
    /// The size expressions as written (in the function's scope: they may read its
    /// inputs, `output Real y[n]`), `None` for `:`; the back end evaluates them when
    /// it inlines a call.
    pub dim_exprs: Vec<Option<Expr>>,
    /// The default (inputs) or binding (outputs and locals).
    pub default: Option<Expr>,
    /// The type resolved through short class definitions: `Real`, `Integer`,
    /// `Boolean`, `String`, or the full name of an enumeration or record type.
    pub base: String,
    /// Set when the type is a record (its full name, as in [`FlatRecord`]).
    pub record: Option<String>,
}

/// A record type: its fields in constructor order (inherited ones first).
#[derive(Clone, Debug)]
pub struct FlatRecord {
    /// Full dotted name, as constructor calls in the flat model spell it.
    pub name: String,
    pub fields: Vec<FuncVar>,
    pub origin: Span,
}

/// A user function with an algorithm body.
#[derive(Clone, Debug)]
pub struct FlatFunction {
    /// Full dotted name, as calls in the flat model spell it.
    pub name: String,
    pub inputs: Vec<FuncVar>,
    pub outputs: Vec<FuncVar>,
    pub locals: Vec<FuncVar>,
    pub algorithm: Vec<Statement>,
    /// A function without a body (no algorithm, no output binding): the back end
    /// cannot inline it.
    pub external: bool,
    /// Its `external "C" y = f(a, b)` clause, when it has one: the back end calls its
    /// own implementation of `f` (see `unimo_dae::external`).
    pub external_call: Option<ExternalCall>,
    pub origin: Span,
}

/// A function's external clause, flattened: the language, the foreign function's
/// name, its arguments (expressions of the function's inputs and outputs, in the
/// function's scope) and the output it assigns.
#[derive(Clone, Debug)]
pub struct ExternalCall {
    pub language: String,
    pub function: String,
    pub args: Vec<Expr>,
    pub output: Option<String>,
}

/// Global names of user functions called in `e`, or passed as functional arguments
/// (`function f(a = 1)`), in subscripts and ranges too.
pub(crate) fn called_functions(e: &Expr, out: &mut Vec<String>) {
    walk_expr(e, &mut |x| {
        match &x.kind {
            ExprKind::Call { func, .. } if func.global => {
                out.push(func.to_dotted().trim_start_matches('.').to_owned())
            }
            ExprKind::PartialApplication { func, .. } if func.global => {
                out.push(func.to_dotted().trim_start_matches('.').to_owned())
            }
            _ => {}
        }
        Walk::Descend
    });
}

/// Global names of the user functions called in the statement `s` (nested statements
/// too).
pub fn statement_calls(s: &Statement, out: &mut Vec<String>) {
    statement_exprs(std::slice::from_ref(s), &mut |e| called_functions(e, out));
}

pub(crate) fn equation_calls(eq: &Equation, out: &mut Vec<String>) {
    equation_exprs(std::slice::from_ref(eq), &mut |e| called_functions(e, out));
}

/// Drops the functions and records the final model no longer calls or uses (those
/// called only in branches that flattening removed after collecting them, such as the
/// `isRoot` branches of overconstrained connectors), so that the printed model reads
/// back to the same text.
pub(crate) fn keep_called(model: &mut crate::flat::FlatModel) {
    let mut pending = Vec::new();
    for eq in model.equations.iter().chain(&model.initial_equations) {
        equation_calls(eq, &mut pending);
    }
    for s in model
        .algorithms
        .iter()
        .chain(&model.initial_algorithms)
        .flatten()
    {
        statement_calls(s, &mut pending);
    }
    for v in &model.vars {
        for e in v
            .binding
            .iter()
            .map(|b| &**b)
            .chain(v.attributes.iter().map(|(_, a)| a))
        {
            called_functions(e, &mut pending);
        }
    }
    let mut used: std::collections::HashSet<String> = std::collections::HashSet::new();
    while let Some(name) = pending.pop() {
        if !used.insert(name.clone()) {
            continue;
        }
        if let Some(f) = model.functions.iter().find(|f| f.name == name) {
            for s in &f.algorithm {
                statement_calls(s, &mut pending);
            }
            for v in f.inputs.iter().chain(&f.outputs).chain(&f.locals) {
                if let Some(d) = &v.default {
                    called_functions(d, &mut pending);
                }
                for d in v.dim_exprs.iter().flatten() {
                    called_functions(d, &mut pending);
                }
            }
            if let Some(x) = &f.external_call {
                for a in &x.args {
                    called_functions(a, &mut pending);
                }
            }
        }
    }
    model.functions.retain(|f| used.contains(&f.name));
}

impl Instantiator<'_, '_> {
    /// Collects every user function the model calls (transitively) into the model.
    pub(crate) fn collect_functions(&mut self) {
        let mut pending = Vec::new();
        for eq in self
            .model
            .equations
            .iter()
            .chain(&self.model.initial_equations)
        {
            equation_calls(eq, &mut pending);
        }
        for s in self
            .model
            .algorithms
            .iter()
            .chain(&self.model.initial_algorithms)
            .flatten()
        {
            statement_calls(s, &mut pending);
        }
        for v in &self.model.vars {
            if let Some(b) = &v.binding {
                called_functions(b, &mut pending);
            }
        }
        self.add_functions(pending);
    }

    /// Adds the functions named in `pending` (full names), the functions they call and
    /// the records they use, to those the model has already.
    pub(crate) fn add_functions(&mut self, mut pending: Vec<String>) {
        let mut done: Vec<String> = self
            .model
            .functions
            .iter()
            .map(|f| f.name.clone())
            .collect();
        while let Some(name) = pending.pop() {
            if done.contains(&name) {
                continue;
            }
            done.push(name.clone());
            let parts: Vec<&str> = crate::flat::split_name(&name);
            let Some(Found::Class(c)) = self.tree.lookup_dotted(None, &parts, false) else {
                continue;
            };
            if self.is_record(c) {
                self.note_record(c);
                continue;
            }
            if self.tree.get(c).def.kind != ClassKind::Function {
                continue;
            }
            if let Some(f) = self.flat_function(c, &name) {
                for s in &f.algorithm {
                    statement_calls(s, &mut pending);
                }
                for v in f.inputs.iter().chain(&f.outputs).chain(&f.locals) {
                    if let Some(d) = &v.default {
                        called_functions(d, &mut pending);
                    }
                }
                self.model.functions.push(f);
            }
        }
        self.model.functions.sort_by(|a, b| a.name.cmp(&b.name));
        // The record types used, with the records their fields use.
        let mut k = 0;
        while k < self.records_used.len() {
            let c = self.records_used[k];
            k += 1;
            let r = self.flat_record(c);
            for f in &r.fields {
                if let Some(d) = &f.default {
                    let mut calls = Vec::new();
                    called_functions(d, &mut calls);
                    for name in calls {
                        let parts = crate::flat::split_name(&name);
                        if let Some(Found::Class(rc)) = self.tree.lookup_dotted(None, &parts, false)
                        {
                            if self.is_record(rc) {
                                self.note_record(rc);
                            }
                        }
                    }
                }
            }
            if !self.model.records.iter().any(|x| x.name == r.name) {
                self.model.records.push(r);
            }
        }
        self.model.records.sort_by(|a, b| a.name.cmp(&b.name));
    }

    /// A function's or record's variable: dimensions evaluated where they are known,
    /// the type resolved (records noted for the model).
    fn func_var(
        &mut self,
        cc: &ComponentClause,
        d: &ComponentDecl,
        scope: &Scope,
        local_names: &mut Vec<String>,
    ) -> FuncVar {
        let parts: Vec<&str> = cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
        let start = if cc.type_name.global {
            None
        } else {
            Some(scope.class)
        };
        let (mut base, mut record, mut short_dims) = (cc.type_name.to_dotted(), None, Vec::new());
        if let Some(found) = self.tree.lookup_dotted(start, &parts, false) {
            if let Some((kind, _, sd)) = self.resolve_type_dims(found, Mod::default()) {
                short_dims = sd;
                match kind {
                    Kind::Builtin(FlatType::Enumeration { name, .. }) => base = name,
                    Kind::Builtin(t) => base = crate::flat::type_name(&t),
                    Kind::Class(c) => {
                        base = self.tree.full_name(c);
                        if self.is_record(c) {
                            self.note_record(c);
                            record = Some(base.clone());
                        }
                    }
                }
            }
        }
        let mut dim_exprs: Vec<Option<Expr>> = Vec::new();
        let mut dims: Vec<Option<usize>> = d
            .dims
            .iter()
            .chain(&cc.type_dims)
            .map(|s| match s {
                Subscript::Colon(_) => {
                    dim_exprs.push(None);
                    None
                }
                Subscript::Expr(x) => {
                    let x = self.function_expr(x, scope, local_names);
                    let n = match eval::eval(&x, self, &mut Vec::new()) {
                        Ok(Value::Int(n)) if n >= 0 => Some(n as usize),
                        _ => None,
                    };
                    dim_exprs.push(Some(x));
                    n
                }
            })
            .collect();
        for (s, sc) in &short_dims {
            dims.push(match s {
                Subscript::Colon(_) => {
                    dim_exprs.push(None);
                    None
                }
                Subscript::Expr(x) => {
                    let x = self.function_expr(x, sc, &mut Vec::new());
                    let n = match eval::eval(&x, self, &mut Vec::new()) {
                        Ok(Value::Int(n)) if n >= 0 => Some(n as usize),
                        _ => None,
                    };
                    dim_exprs.push(Some(x));
                    n
                }
            });
        }
        let default = d
            .modification
            .as_ref()
            .and_then(|m| m.binding.as_ref())
            .map(|b| self.function_expr(b, scope, local_names));
        FuncVar {
            name: d.name.text.to_string(),
            type_name: cc.type_name.to_dotted(),
            dims,
            dim_exprs,
            default,
            base,
            record,
        }
    }

    /// A record type's fields, inherited ones first.
    fn flat_record(&mut self, class: ClassId) -> FlatRecord {
        let mut classes = Vec::new();
        self.record_classes(class, &mut classes, 0);
        let mut fields = Vec::new();
        for c in classes {
            let def = self.tree.get(c).def.clone();
            let ClassBody::Long { composition, .. } = &def.body else {
                continue;
            };
            let scope = Scope {
                class: c,
                prefix: std::sync::Arc::from([]),
            };
            let mut names: Vec<String> = composition
                .elements
                .iter()
                .filter_map(|e| match &e.kind {
                    ElementKind::Component(cc) => Some(cc),
                    _ => None,
                })
                .flat_map(|cc| cc.components.iter().map(|d| d.name.text.to_string()))
                .collect();
            for e in &composition.elements {
                if let ElementKind::Component(cc) = &e.kind {
                    for d in &cc.components {
                        let v = self.func_var(cc, d, &scope, &mut names);
                        fields.push(v);
                    }
                }
            }
            // `extends Base(field = value)` changes an inherited field's default.
            for e in &composition.elements {
                let ElementKind::Extends(x) = &e.kind else {
                    continue;
                };
                for arg in x.modification.iter().flat_map(|m| &m.args) {
                    let Argument::Modify {
                        name,
                        modification: Some(m),
                        ..
                    } = arg
                    else {
                        continue;
                    };
                    let (Some(b), [field]) = (&m.binding, name.parts.as_slice()) else {
                        continue;
                    };
                    let value = self.function_expr(b, &scope, &mut names);
                    if let Some(f) = fields.iter_mut().find(|f| f.name == field.text.as_str()) {
                        f.default = Some(value);
                    }
                }
            }
        }
        FlatRecord {
            name: self.tree.full_name(class),
            fields,
            origin: self.tree.get(class).def.name.span,
        }
    }

    /// An external clause in terms of the function's inputs and outputs; without an
    /// explicit call, the function's own name with its inputs then outputs.
    fn external_call(
        &mut self,
        ext: &External,
        def: &ClassDef,
        scope: &Scope,
        local_names: &mut Vec<String>,
    ) -> ExternalCall {
        let language = ext.language.clone().unwrap_or_else(|| "C".to_owned());
        match &ext.call {
            Some(call) => ExternalCall {
                language,
                function: call.function.text.to_string(),
                args: call
                    .args
                    .iter()
                    .map(|a| self.function_expr(a, scope, local_names))
                    .collect(),
                output: call.output.as_ref().map(|o| o.to_dotted()),
            },
            None => ExternalCall {
                language,
                function: def.name.text.to_string(),
                args: Vec::new(),
                output: None,
            },
        }
    }

    /// `class` and its bases, bases first.
    pub(crate) fn record_classes(&mut self, class: ClassId, out: &mut Vec<ClassId>, depth: usize) {
        if depth > 32 {
            return;
        }
        for b in self.tree.bases(class) {
            self.record_classes(b, out, depth + 1);
        }
        out.push(class);
    }

    pub(crate) fn flat_function(&mut self, class: ClassId, name: &str) -> Option<FlatFunction> {
        let def = self.tree.get(class).def.clone();
        if !matches!(def.body, ClassBody::Long { .. }) {
            return None;
        }
        let mut f = FlatFunction {
            name: name.to_owned(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            locals: Vec::new(),
            algorithm: Vec::new(),
            external: false,
            external_call: None,
            origin: def.name.span,
        };
        // The function and the classes it extends (`function quantile extends
        // partialQuantile`: the inputs and outputs declared there), bases first; an
        // element declared again further down replaces the inherited one.
        let mut classes = Vec::new();
        self.record_classes(class, &mut classes, 0);
        let compositions: Vec<(ClassId, std::sync::Arc<ClassDef>)> = classes
            .iter()
            .map(|&c| (c, self.tree.get(c).def.clone()))
            .collect();
        let mut local_names: Vec<String> = Vec::new();
        for (_, d) in &compositions {
            for (_, cc) in d.component_clauses() {
                local_names.extend(cc.components.iter().map(|d| d.name.text.to_string()));
            }
        }
        let mut has_sections = false;
        for (c, d) in &compositions {
            let ClassBody::Long { composition, .. } = &d.body else {
                continue;
            };
            let scope = Scope {
                class: *c,
                prefix: std::sync::Arc::from([]),
            };
            for e in &composition.elements {
                let ElementKind::Component(cc) = &e.kind else {
                    continue;
                };
                for d in &cc.components {
                    let var = self.func_var(cc, d, &scope, &mut local_names);
                    for list in [&mut f.inputs, &mut f.outputs, &mut f.locals] {
                        list.retain(|v| v.name != var.name);
                    }
                    match cc.prefix.causality {
                        Some(Causality::Input) => f.inputs.push(var),
                        Some(Causality::Output) => f.outputs.push(var),
                        None => f.locals.push(var),
                    }
                }
            }
            has_sections |= !composition.sections.is_empty();
            if let Some(ext) = &composition.external {
                f.external_call = Some(self.external_call(ext, d, &scope, &mut local_names));
            }
            for s in &composition.sections {
                if let Section::Algorithm(a) = s {
                    for st in &a.statements {
                        let st = self.function_statement(st, &scope, &mut local_names);
                        f.algorithm.push(st);
                    }
                }
            }
        }
        let composition_sections_empty = !has_sections;
        // No body: no algorithm and no output computed by its binding.
        f.external = composition_sections_empty
            && f.algorithm.is_empty()
            && f.outputs.iter().all(|o| o.default.is_none());
        Some(f)
    }
}
