//! The flat model's printer: flat Modelica that stands alone (the enumeration types,
//! records and functions it uses printed before the model) and parses back to the same
//! model; references printed as one quoted identifier.

use super::walk::rewrite_refs;
use super::{quote, FlatModel, FlatType, FlatVar, Variability};
use smol_str::SmolStr;
use std::fmt::Write;
use unimo_source::Span;
use unimo_syntax::ast::{
    Causality, ComponentRef, Equation, EquationKind, Expr, ExprKind, ForIndex, Ident, Name,
    RefPart, Statement, StatementKind,
};
use unimo_syntax::print;

/// A reference as one quoted identifier plus its last subscripts (for printing).
fn printable_ref(r: &ComponentRef) -> ComponentRef {
    let builtin_enum = r.parts.len() == 2
        && matches!(
            r.parts[0].name.text.as_str(),
            "StateSelect" | "AssertionLevel"
        );
    if builtin_enum
        || r.global
        || r.parts.len() <= 1
            && r.parts
                .first()
                .is_some_and(|p| quote(&p.name.text) == p.name.text)
    {
        return r.clone();
    }
    let key = crate::eval::var_key(r);
    let last_subs = r
        .parts
        .last()
        .map(|p| p.subscripts.clone())
        .unwrap_or_default();
    ComponentRef {
        global: false,
        parts: vec![RefPart {
            name: Ident {
                text: SmolStr::new(quote(&key)),
                span: r.span,
            },
            subscripts: last_subs
                .into_iter()
                .map(|s| match s {
                    unimo_syntax::ast::Subscript::Expr(e) => {
                        unimo_syntax::ast::Subscript::Expr(printable(&e))
                    }
                    c => c,
                })
                .collect(),
        }],
        span: r.span,
    }
}

/// An expression with every flat reference turned printable.
pub fn printable(e: &Expr) -> Expr {
    let mut e = e.clone();
    rewrite_refs(&mut e, &mut |r| *r = printable_ref(r));
    e
}

pub(crate) fn type_name(t: &FlatType) -> String {
    match t {
        FlatType::Real => "Real".into(),
        FlatType::Integer => "Integer".into(),
        FlatType::Boolean => "Boolean".into(),
        FlatType::String => "String".into(),
        // The predefined enumerations by their names.
        FlatType::Enumeration { name, .. } if name == "StateSelect" || name == "AssertionLevel" => {
            name.clone()
        }
        // Other enumerations are printed as types before the model.
        FlatType::Enumeration { name, .. } | FlatType::ExternalObject { name } => quote(name),
    }
}

impl FlatModel {
    /// Prints the model as flat Modelica that stands alone: the enumeration types,
    /// records and functions it uses first (named by their full quoted names, as
    /// `'Pkg.f'`), then the model; it parses back to the same model.
    pub fn to_modelica(&self) -> String {
        let p = Printer::new(self);
        let mut out = String::new();
        for (name, literals) in &self.enumerations {
            let _ = writeln!(
                out,
                "type {} = enumeration({});",
                quote(name),
                literals.join(", ")
            );
        }
        // The model and its functions first: they decide which records are printed
        // (those the text names).
        let mut body = String::new();
        // External object classes (spec 12.9.7), their constructors inside them.
        let mut objects: Vec<&str> = p.objects.iter().copied().collect();
        objects.sort_by_key(|n| quote(n));
        for name in objects {
            let class = quote(name);
            let _ = writeln!(body, "class {class}\n  extends ExternalObject;");
            let constructor = format!("{name}.constructor");
            if let Some(f) = self.functions.iter().find(|f| f.name == constructor) {
                p.function(&mut body, f, "constructor");
            }
            let _ = writeln!(body, "end {class};");
        }
        let mut functions: Vec<&crate::functions::FlatFunction> = self
            .functions
            .iter()
            .filter(|f| {
                p.functions.contains(f.name.as_str()) && p.constructor_of(&f.name).is_none()
            })
            .collect();
        functions.sort_by_key(|f| quote(&f.name));
        for f in functions {
            p.function(&mut body, f, &quote(&f.name));
        }
        let model = self.model_text(&p);
        let mut used: Vec<String> = p.used_records.borrow().iter().cloned().collect();
        let mut k = 0;
        while k < used.len() {
            if let Some(r) = p.records.get(used[k].as_str()) {
                for f in &r.fields {
                    if let Some(t) = &f.record {
                        if !used.contains(t) {
                            used.push(t.clone());
                        }
                    }
                }
            }
            k += 1;
        }
        let mut records: Vec<&crate::functions::FlatRecord> = self
            .records
            .iter()
            .filter(|r| used.contains(&r.name))
            .collect();
        records.sort_by_key(|r| quote(&r.name));
        for r in records {
            let name = quote(&r.name);
            let _ = writeln!(out, "record {name}");
            for f in &r.fields {
                let _ = writeln!(out, "  {};", p.func_var(f));
            }
            let _ = writeln!(out, "end {name};");
        }
        out.push_str(&body);
        out.push_str(&model);
        out
    }

    fn model_text(&self, p: &Printer<'_>) -> String {
        let mut out = String::new();
        let name = quote(&self.name);
        let _ = writeln!(out, "class {name}");
        for v in &self.vars {
            out.push_str("  ");
            out.push_str(&p.var_decl(v));
            out.push_str(";\n");
        }
        let sections = [
            ("initial equation", &self.initial_equations),
            ("equation", &self.equations),
        ];
        for (head, eqs) in sections {
            if !eqs.is_empty() {
                let _ = writeln!(out, "{head}");
                for e in eqs {
                    p.equation(&mut out, e, 1);
                }
            }
        }
        for (head, algs) in [
            ("initial algorithm", &self.initial_algorithms),
            ("algorithm", &self.algorithms),
        ] {
            for stmts in algs {
                let _ = writeln!(out, "{head}");
                for s in stmts {
                    p.statement(&mut out, s, 1);
                }
            }
        }
        if let Some(x) = &self.experiment {
            let _ = writeln!(
                out,
                "  annotation(experiment{});",
                print::class_modification(x)
            );
        }
        let _ = writeln!(out, "end {name};");
        out
    }
}

/// One quoted identifier for a full class name.
fn class_ident(name: &str, span: Span) -> Ident {
    Ident {
        text: SmolStr::new(quote(name.trim_start_matches('.'))),
        span,
    }
}

/// Prints a flat model's parts so that the text stands alone: calls of the model's
/// functions and record constructors and its enumeration literals name the
/// definitions printed before the model, and a whole record is written as its
/// constructor applied to its fields.
struct Printer<'a> {
    /// The functions printed: those with a body and those with an external clause.
    functions: std::collections::HashSet<&'a str>,
    /// External object classes, by full name (the types of the model's handles).
    objects: std::collections::HashSet<&'a str>,
    records: std::collections::HashMap<&'a str, &'a crate::functions::FlatRecord>,
    instances: std::collections::HashMap<&'a str, &'a str>,
    enumerations: std::collections::HashSet<&'a str>,
    /// Variable names; only filled when a record instance or an enumeration literal
    /// could be mistaken for one (the only questions it answers).
    variables: rustc_hash::FxHashSet<&'a str>,
    /// Records named by the printed text (their definitions are printed).
    used_records: std::cell::RefCell<std::collections::BTreeSet<String>>,
}

impl<'a> Printer<'a> {
    fn new(m: &'a FlatModel) -> Printer<'a> {
        Printer {
            functions: m
                .functions
                .iter()
                .filter(|f| !f.external || f.external_call.is_some())
                .map(|f| f.name.as_str())
                .collect(),
            objects: m
                .vars
                .iter()
                .filter_map(|v| match &v.ty {
                    FlatType::ExternalObject { name } => Some(name.as_str()),
                    _ => None,
                })
                .collect(),
            records: m.records.iter().map(|r| (r.name.as_str(), r)).collect(),
            instances: m
                .record_instances
                .iter()
                .map(|(k, r)| (k.as_str(), r.as_str()))
                .collect(),
            enumerations: m.enumerations.iter().map(|(n, _)| n.as_str()).collect(),
            variables: if m.record_instances.is_empty() && m.enumerations.is_empty() {
                Default::default()
            } else {
                m.vars.iter().map(|v| v.name.as_str()).collect()
            },
            used_records: Default::default(),
        }
    }

    /// Calls and enumeration literals renamed to the printed definitions; with
    /// `model`, whole records written as constructor calls.
    fn standalone(&self, e: &mut Expr, model: bool) {
        e.for_each_child_mut(&mut |c| self.standalone(c, model));
        match &mut e.kind {
            ExprKind::Call { func, .. } if func.global => {
                let name = func
                    .parts
                    .iter()
                    .map(|p| p.text.as_str())
                    .collect::<Vec<_>>()
                    .join(".");
                if self.records.contains_key(name.as_str()) {
                    self.used_records.borrow_mut().insert(name.clone());
                }
                if let Some(class) = self.constructor_of(&name) {
                    // The class's name calls its constructor.
                    *func = Name {
                        global: false,
                        parts: vec![class_ident(class, func.span)],
                        span: func.span,
                    };
                } else if self.functions.contains(name.as_str())
                    || self.records.contains_key(name.as_str())
                {
                    *func = Name {
                        global: false,
                        parts: vec![class_ident(&name, func.span)],
                        span: func.span,
                    };
                }
            }
            ExprKind::Ref(r) if r.parts.len() >= 2 && self.is_literal(r) => {
                let ty = type_part(r);
                let literal = r.parts[r.parts.len() - 1].clone();
                r.global = true;
                r.parts = vec![
                    RefPart {
                        name: class_ident(&ty, r.span),
                        subscripts: Vec::new(),
                    },
                    literal,
                ];
            }
            ExprKind::Ref(r) if model && !r.global && !self.instances.is_empty() => {
                let mut key = crate::eval::var_key(r);
                if self.variables.contains(key.as_str()) {
                    return;
                }
                if let Some(last) = r.parts.last() {
                    key.push_str(&print::subscripts(&last.subscripts));
                }
                if let Some(c) = self.record_value(&key, e.span) {
                    *e = c;
                }
            }
            _ => {}
        }
    }

    /// The external object class whose constructor `function` is.
    fn constructor_of(&self, function: &str) -> Option<&'a str> {
        let class = function.strip_suffix(".constructor")?;
        self.objects.get(class).copied()
    }

    /// Whether `r` names a literal of one of the model's enumeration types.
    fn is_literal(&self, r: &ComponentRef) -> bool {
        if self.enumerations.is_empty() {
            return false;
        }
        self.enumerations.contains(type_part(r).as_str())
            && (r.global || !self.variables.contains(crate::eval::var_key(r).as_str()))
    }

    /// The record instance at `key` as a constructor call of its fields.
    fn record_value(&self, key: &str, span: Span) -> Option<Expr> {
        let ty = self.instances.get(key)?;
        let rec = self.records.get(ty)?;
        self.used_records.borrow_mut().insert(ty.to_string());
        let positional = rec
            .fields
            .iter()
            .map(|f| {
                let path = format!("{key}.{}", f.name);
                match f.record.as_ref().filter(|_| f.dims.is_empty()) {
                    Some(_) => self.record_value(&path, span),
                    None => None,
                }
                .unwrap_or(Expr {
                    kind: ExprKind::Ref(ComponentRef {
                        global: false,
                        parts: vec![RefPart {
                            name: Ident {
                                text: SmolStr::new(quote(&path)),
                                span,
                            },
                            subscripts: Vec::new(),
                        }],
                        span,
                    }),
                    span,
                })
            })
            .collect();
        Some(Expr {
            kind: ExprKind::Call {
                func: Name {
                    global: false,
                    parts: vec![class_ident(ty, span)],
                    span,
                },
                args: Box::new(unimo_syntax::ast::CallArgs {
                    positional,
                    named: Vec::new(),
                    iterators: Vec::new(),
                    span,
                }),
            },
            span,
        })
    }

    /// A model expression as text.
    fn expr(&self, e: &Expr) -> String {
        let mut e = e.clone();
        self.standalone(&mut e, true);
        rewrite_refs(&mut e, &mut |r| *r = printable_ref(r));
        print::expr(&e)
    }

    /// A function body's expression as text (its names are local, not flat).
    fn local_expr(&self, e: &Expr) -> String {
        let mut e = e.clone();
        self.standalone(&mut e, false);
        print::expr(&e)
    }

    fn var_decl(&self, v: &FlatVar) -> String {
        let mut s = String::new();
        match v.variability {
            Variability::Constant => s.push_str("constant "),
            Variability::Parameter => s.push_str("parameter "),
            Variability::Discrete => s.push_str("discrete "),
            Variability::Continuous => {}
        }
        // `flow` has done its work (the connection equations are written out), and
        // only top-level inputs and outputs keep their causality: printed otherwise, a
        // re-read would change the model.
        match v.causality {
            Some(Causality::Input) if v.top_level => s.push_str("input "),
            Some(Causality::Output) if v.top_level => s.push_str("output "),
            _ => {}
        }
        s.push_str(&type_name(&v.ty));
        s.push(' ');
        s.push_str(&quote(&v.name));
        if !v.dims.is_empty() {
            let d: Vec<String> = v.dims.iter().map(|n| n.to_string()).collect();
            let _ = write!(s, "[{}]", d.join(", "));
        }
        if !v.attributes.is_empty() {
            let attrs: Vec<String> = v
                .attributes
                .iter()
                .map(|(n, e)| {
                    let each = if v.each_attributes.contains(n) {
                        "each "
                    } else {
                        ""
                    };
                    format!("{each}{n} = {}", self.expr(e))
                })
                .collect();
            let _ = write!(s, "({})", attrs.join(", "));
        }
        if let Some(b) = &v.binding {
            let _ = write!(s, " = {}", self.expr(b));
        }
        if let Some(d) = &v.description {
            s.push(' ');
            s.push_str(&print::string_lit(d));
        }
        s
    }

    /// `input Real x[3] = ...` of a function or record.
    fn func_var(&self, v: &crate::functions::FuncVar) -> String {
        if let Some(r) = &v.record {
            self.used_records.borrow_mut().insert(r.clone());
        }
        let mut s = quote(&v.base);
        s.push(' ');
        s.push_str(&quote(&v.name));
        if !v.dims.is_empty() {
            // A size known only when the function is called (`output Integer
            // state[nState]`, `nState` an input) keeps its expression.
            let d: Vec<String> = v
                .dims
                .iter()
                .enumerate()
                .map(|(k, n)| match (n, v.dim_exprs.get(k)) {
                    (Some(n), _) => n.to_string(),
                    (None, Some(Some(e))) => self.local_expr(e),
                    (None, _) => ":".to_owned(),
                })
                .collect();
            let _ = write!(s, "[{}]", d.join(", "));
        }
        if let Some(d) = &v.default {
            let _ = write!(s, " = {}", self.local_expr(d));
        }
        s
    }

    /// A function named `name` (its full quoted name, or `constructor` inside its
    /// external object class); an external function with its external clause.
    fn function(&self, out: &mut String, f: &crate::functions::FlatFunction, name: &str) {
        let _ = writeln!(out, "function {name}");
        for v in &f.inputs {
            let _ = writeln!(out, "  input {};", self.func_var(v));
        }
        for v in &f.outputs {
            let _ = writeln!(out, "  output {};", self.func_var(v));
        }
        if !f.locals.is_empty() {
            out.push_str("protected\n");
            for v in &f.locals {
                let _ = writeln!(out, "  {};", self.func_var(v));
            }
        }
        if !f.algorithm.is_empty() {
            out.push_str("algorithm\n");
            for s in &f.algorithm {
                self.statement_in(out, s, 1, false);
            }
        }
        if let Some(ext) = f.external_call.as_ref().filter(|_| f.external) {
            let args: Vec<String> = ext.args.iter().map(|a| self.local_expr(a)).collect();
            let output = ext
                .output
                .as_ref()
                .map(|o| format!("{o} = "))
                .unwrap_or_default();
            let _ = writeln!(
                out,
                "external {} {output}{}({});",
                print::string_lit(&ext.language),
                ext.function,
                args.join(", ")
            );
        }
        let _ = writeln!(out, "end {name};");
    }

    /// `if c then ... elseif ... else ... end if;` (or `when`/`elsewhen`), each body
    /// written by `item` one level deeper.
    #[allow(clippy::too_many_arguments)]
    fn branches<T>(
        &self,
        out: &mut String,
        depth: usize,
        (first, next, end): (&str, &str, &str),
        branches: &[(Expr, Vec<T>)],
        otherwise: &[T],
        model: bool,
        item: &dyn Fn(&mut String, &T, usize),
    ) {
        for (i, (c, body)) in branches.iter().enumerate() {
            if i > 0 {
                indent(out, depth);
            }
            let kw = if i == 0 { first } else { next };
            let c = if model {
                self.expr(c)
            } else {
                self.local_expr(c)
            };
            let _ = writeln!(out, "{kw} {c} then");
            for b in body {
                item(out, b, depth + 1);
            }
        }
        if !otherwise.is_empty() {
            indent(out, depth);
            out.push_str("else\n");
            for b in otherwise {
                item(out, b, depth + 1);
            }
        }
        indent(out, depth);
        let _ = writeln!(out, "{end};");
    }

    fn equation(&self, out: &mut String, e: &Equation, depth: usize) {
        indent(out, depth);
        let item = |o: &mut String, e: &Equation, d: usize| self.equation(o, e, d);
        match &e.kind {
            EquationKind::Simple { lhs, rhs } => {
                let _ = writeln!(out, "{} = {};", self.expr(lhs), self.expr(rhs));
            }
            EquationKind::Call(c) => {
                let _ = writeln!(out, "{};", self.expr(c));
            }
            EquationKind::Connect { a, b } => {
                let _ = writeln!(
                    out,
                    "connect({}, {});",
                    print::cref(&printable_ref(a)),
                    print::cref(&printable_ref(b))
                );
            }
            EquationKind::If {
                branches,
                otherwise,
            } => self.branches(out, depth, IF, branches, otherwise, true, &item),
            EquationKind::For { indices, body } => for_loop(out, depth, indices, body, &item),
            EquationKind::When { branches } => {
                self.branches(out, depth, WHEN, branches, &[], true, &item)
            }
        }
    }

    fn statement(&self, out: &mut String, s: &Statement, depth: usize) {
        self.statement_in(out, s, depth, true);
    }

    /// A statement of the model's algorithm (`model`) or of a function body.
    fn statement_in(&self, out: &mut String, s: &Statement, depth: usize, model: bool) {
        indent(out, depth);
        let expr = |e: &Expr| {
            if model {
                self.expr(e)
            } else {
                self.local_expr(e)
            }
        };
        let target = |r: &ComponentRef| {
            if model {
                print::cref(&printable_ref(r))
            } else {
                print::cref(r)
            }
        };
        let item = |o: &mut String, s: &Statement, d: usize| self.statement_in(o, s, d, model);
        match &s.kind {
            StatementKind::Assign { target: t, value } => {
                let _ = writeln!(out, "{} := {};", target(t), expr(value));
            }
            StatementKind::MultiAssign { targets, value } => {
                let t: Vec<String> = targets
                    .iter()
                    .map(|t| t.as_ref().map(&expr).unwrap_or_default())
                    .collect();
                let _ = writeln!(out, "({}) := {};", t.join(", "), expr(value));
            }
            StatementKind::Call(e) => {
                let _ = writeln!(out, "{};", expr(e));
            }
            StatementKind::If {
                branches,
                otherwise,
            } => self.branches(out, depth, IF, branches, otherwise, model, &item),
            StatementKind::For { indices, body } => for_loop(out, depth, indices, body, &item),
            StatementKind::While { condition, body } => {
                let head = format!("while {} loop", expr(condition));
                block(out, depth, &head, body, "end while", &item);
            }
            StatementKind::When { branches } => {
                self.branches(out, depth, WHEN, branches, &[], model, &item)
            }
            StatementKind::Return => out.push_str("return;\n"),
            StatementKind::Break => out.push_str("break;\n"),
        }
    }
}

/// The keywords of an `if` equation or statement: first branch, next ones, end.
const IF: (&str, &str, &str) = ("if", "elseif", "end if");
/// The keywords of a `when` equation or statement.
const WHEN: (&str, &str, &str) = ("when", "elsewhen", "end when");

/// A loop (already indented): `head`, the `body` items one level deeper, `end;`.
fn block<T>(
    out: &mut String,
    depth: usize,
    head: &str,
    body: &[T],
    end: &str,
    item: &dyn Fn(&mut String, &T, usize),
) {
    let _ = writeln!(out, "{head}");
    for b in body {
        item(out, b, depth + 1);
    }
    indent(out, depth);
    let _ = writeln!(out, "{end};");
}

/// The dotted name of every part of `r` but the last: the type of `E.a` when `r`
/// names an enumeration literal.
fn type_part(r: &ComponentRef) -> String {
    let n = r.parts.len();
    r.parts[..n - 1]
        .iter()
        .map(|p| p.name.text.as_str())
        .collect::<Vec<_>>()
        .join(".")
}

/// A `for` loop over `indices` (already indented).
fn for_loop<T>(
    out: &mut String,
    depth: usize,
    indices: &[ForIndex],
    body: &[T],
    item: &dyn Fn(&mut String, &T, usize),
) {
    let head = format!("for {} loop", print::for_indices(indices));
    block(out, depth, &head, body, "end for", item);
}

fn indent(out: &mut String, depth: usize) {
    for _ in 0..depth {
        out.push_str("  ");
    }
}
