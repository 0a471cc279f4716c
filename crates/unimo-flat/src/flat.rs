//! The flat model: variables with full names, equations and algorithms with full
//! references, and its printer (flat Modelica that unimo parses back).
//!
//! Naming: a variable's name is its instance path (`body.r`, `pins[2].v`); array
//! variables keep their dimensions (`Real 'body.r'[3]`) and array equations stay array
//! equations — scalarization is the lowering stage's job. When printed, a dotted or
//! subscripted path becomes one quoted identifier (`'body.r'`), which is standard
//! Modelica and reads back as the same name.

use smol_str::SmolStr;
use std::fmt::Write;
use unimo_source::Span;
use unimo_syntax::ast::{
    Causality, ClassModification, ComponentRef, Equation, EquationKind, Expr, ExprKind, Ident,
    Name, RefPart, Statement, StatementKind,
};
use unimo_syntax::print;

/// Index of a variable in [`FlatModel::vars`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct VarId(pub u32);

#[derive(Clone, Debug, PartialEq)]
pub enum FlatType {
    Real,
    Integer,
    Boolean,
    String,
    /// An enumeration type: its full class name and literals.
    Enumeration {
        name: String,
        literals: Vec<String>,
    },
    /// An external object class (`extends ExternalObject`): its full name. Values are
    /// handles its `constructor` function makes.
    ExternalObject {
        name: String,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Variability {
    Constant,
    Parameter,
    Discrete,
    Continuous,
}

#[derive(Clone, Debug)]
pub struct FlatVar {
    /// The instance path (`body.r`, `pins[2].v`).
    pub name: String,
    pub ty: FlatType,
    pub variability: Variability,
    pub causality: Option<Causality>,
    pub flow: bool,
    /// Evaluated array dimensions (empty: scalar).
    pub dims: Vec<usize>,
    pub binding: Option<Box<Expr>>,
    /// `start`, `fixed`, `nominal`, `min`, `max`, `unit`, `stateSelect`, ... in order
    /// of first appearance.
    pub attributes: Vec<(SmolStr, Expr)>,
    /// `each` applied to an attribute of an array variable.
    pub each_attributes: Vec<SmolStr>,
    pub description: Option<String>,
    /// Declared in the top-level class (its inputs are known from outside).
    pub top_level: bool,
    /// A parameter declared with `annotation(Evaluate = true)`: its value is fixed at
    /// translation (a capacitance of 0 removes the capacitor's derivative).
    pub evaluate: bool,
    /// Declared `final`, or given a value by a `final` modifier: no modifier may
    /// change it (spec 7.2.6).
    pub is_final: bool,
    pub origin: Span,
}

impl FlatVar {
    /// Number of scalars.
    pub fn size(&self) -> usize {
        self.dims
            .iter()
            .fold(1usize, |acc, &n| acc.saturating_mul(n))
    }
}

/// The whole model after instantiation.
#[derive(Clone, Debug, Default)]
pub struct FlatModel {
    /// Full name of the instantiated class.
    pub name: String,
    pub vars: Vec<FlatVar>,
    pub equations: Vec<Equation>,
    pub initial_equations: Vec<Equation>,
    pub algorithms: Vec<Vec<Statement>>,
    pub initial_algorithms: Vec<Vec<Statement>>,
    /// `annotation(experiment(...))` of the class, as written.
    pub experiment: Option<ClassModification>,
    /// Enumeration types used by variables, by full name.
    pub enumerations: Vec<(String, Vec<String>)>,
    /// The user functions called (transitively), sorted by name.
    pub functions: Vec<crate::functions::FlatFunction>,
    /// The record types the model uses (components, constructors, function
    /// arguments), sorted by name.
    pub records: Vec<crate::functions::FlatRecord>,
    /// Every record instance by path (`z`, `body.frame`, `c[2]`) with its record type's
    /// full name; its fields are variables named `path.field`.
    pub record_instances: Vec<(String, String)>,
    /// Parameters and constants whose values instantiation evaluated (array sizes,
    /// `for` ranges, conditions of conditional components and structural `if`s, folded
    /// subscripts, and what those depend on), sorted: changing one changes the
    /// model's structure, so it needs flattening again.
    pub evaluated: Vec<String>,
}

/// Array dimensions as text: `scalar` or `[3, 2]`.
pub fn fmt_dims(d: &[usize]) -> String {
    if d.is_empty() {
        "scalar".into()
    } else {
        let parts: Vec<String> = d.iter().map(|x| x.to_string()).collect();
        format!("[{}]", parts.join(", "))
    }
}

/// Splits a dotted name at the dots outside quoted identifiers
/// (`'Pkg.f'.x` is `'Pkg.f'` and `x`).
pub fn split_name(name: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut quoted = false;
    let bytes = name.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if quoted => i += 1,
            b'\'' => quoted = !quoted,
            b'.' if !quoted => {
                out.push(&name[start..i]);
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    out.push(&name[start..]);
    out
}

/// A flat reference: the instance path as reference parts.
pub fn path_ref(parts: Vec<RefPart>, span: Span) -> ComponentRef {
    ComponentRef {
        global: false,
        parts,
        span,
    }
}

/// `name` quoted when it is not a plain identifier.
pub fn quote(name: &str) -> String {
    let plain = name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !unimo_syntax::lexer::is_keyword(name);
    if plain || (name.starts_with('\'') && name.ends_with('\'') && name.len() > 1) {
        name.to_owned()
    } else {
        format!("'{}'", name.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

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

/// Calls `note` with every expression of `eqs` (conditions included, nested equations
/// too; the references of `connect` are not expressions).
pub fn for_each_equation_expr(eqs: &[Equation], note: &mut dyn FnMut(&Expr)) {
    for e in eqs {
        match &e.kind {
            EquationKind::Simple { lhs, rhs } => {
                note(lhs);
                note(rhs);
            }
            EquationKind::Call(c) => note(c),
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (c, b) in branches {
                    note(c);
                    for_each_equation_expr(b, note);
                }
                for_each_equation_expr(otherwise, note);
            }
            EquationKind::When { branches } => {
                for (c, b) in branches {
                    note(c);
                    for_each_equation_expr(b, note);
                }
            }
            EquationKind::For { body, .. } => for_each_equation_expr(body, note),
            EquationKind::Connect { .. } => {}
        }
    }
}

/// Calls `f` with every component reference in `e` (not function names), subscripts
/// of references included.
pub fn for_each_ref(e: &Expr, f: &mut dyn FnMut(&ComponentRef)) {
    refs(e, f, false, &mut |_, _| {});
}

/// Calls `on_call` with the function name and arguments of every call in `e` (outer
/// calls first), and `f` with every component reference.
pub fn for_each_call(
    e: &Expr,
    f: &mut dyn FnMut(&ComponentRef),
    on_call: &mut dyn FnMut(&Name, &unimo_syntax::ast::CallArgs),
) {
    refs(e, f, false, on_call);
}

/// [`for_each_ref`] without the arguments of `size`, `ndims`, `cardinality` and
/// `isPresent`, which read a variable's structure, not its value.
pub fn for_each_value_ref(e: &Expr, f: &mut dyn FnMut(&ComponentRef)) {
    refs(e, f, true, &mut |_, _| {});
}

fn refs(
    e: &Expr,
    f: &mut dyn FnMut(&ComponentRef),
    values_only: bool,
    on_call: &mut dyn FnMut(&Name, &unimo_syntax::ast::CallArgs),
) {
    match &e.kind {
        ExprKind::Ref(r) => {
            for p in &r.parts {
                for s in &p.subscripts {
                    if let unimo_syntax::ast::Subscript::Expr(x) = s {
                        refs(x, f, values_only, on_call);
                    }
                }
            }
            f(r);
        }
        ExprKind::Call { func, args } => {
            on_call(func, args);
            // `size(x, 1)` reads x's shape, not its value.
            if values_only
                && matches!(
                    func.to_dotted().as_str(),
                    "size" | "ndims" | "cardinality" | "isPresent"
                )
            {
                return;
            }
            for a in &args.positional {
                refs(a, f, values_only, on_call);
            }
            for a in &args.named {
                refs(&a.value, f, values_only, on_call);
            }
            for i in &args.iterators {
                if let Some(r) = &i.range {
                    refs(r, f, values_only, on_call);
                }
            }
        }
        ExprKind::Unary { operand, .. } => refs(operand, f, values_only, on_call),
        ExprKind::Binary { lhs, rhs, .. } => {
            refs(lhs, f, values_only, on_call);
            refs(rhs, f, values_only, on_call);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                refs(c, f, values_only, on_call);
                refs(v, f, values_only, on_call);
            }
            refs(otherwise, f, values_only, on_call);
        }
        ExprKind::Range { start, step, stop } => {
            refs(start, f, values_only, on_call);
            if let Some(s) = step {
                refs(s, f, values_only, on_call);
            }
            refs(stop, f, values_only, on_call);
        }
        ExprKind::Array(items) => items.iter().for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Matrix(rows) => rows
            .iter()
            .flatten()
            .for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Tuple(items) => items
            .iter()
            .flatten()
            .for_each(|i| refs(i, f, values_only, on_call)),
        ExprKind::Comprehension { body, indices } => {
            for i in indices {
                if let Some(r) = &i.range {
                    refs(r, f, values_only, on_call);
                }
            }
            refs(body, f, values_only, on_call);
        }
        ExprKind::PartialApplication { args, .. } => {
            for a in args {
                refs(&a.value, f, values_only, on_call);
            }
        }
        ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
    }
}

/// Applies `f` to every component reference in `e` (not to function names).
pub fn rewrite_refs(e: &mut Expr, f: &mut dyn FnMut(&mut ComponentRef)) {
    match &mut e.kind {
        ExprKind::Ref(r) => {
            for p in &mut r.parts {
                for s in &mut p.subscripts {
                    if let unimo_syntax::ast::Subscript::Expr(x) = s {
                        rewrite_refs(x, f);
                    }
                }
            }
            f(r);
        }
        ExprKind::Call { args, .. } => {
            for a in &mut args.positional {
                rewrite_refs(a, f);
            }
            for a in &mut args.named {
                rewrite_refs(&mut a.value, f);
            }
            for i in &mut args.iterators {
                if let Some(r) = &mut i.range {
                    rewrite_refs(r, f);
                }
            }
        }
        ExprKind::Unary { operand, .. } => rewrite_refs(operand, f),
        ExprKind::Binary { lhs, rhs, .. } => {
            rewrite_refs(lhs, f);
            rewrite_refs(rhs, f);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                rewrite_refs(c, f);
                rewrite_refs(v, f);
            }
            rewrite_refs(otherwise, f);
        }
        ExprKind::Range { start, step, stop } => {
            rewrite_refs(start, f);
            if let Some(s) = step {
                rewrite_refs(s, f);
            }
            rewrite_refs(stop, f);
        }
        ExprKind::Array(items) => items.iter_mut().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Matrix(rows) => rows.iter_mut().flatten().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Tuple(items) => items.iter_mut().flatten().for_each(|i| rewrite_refs(i, f)),
        ExprKind::Comprehension { body, indices } => {
            for i in indices.iter_mut() {
                if let Some(r) = &mut i.range {
                    rewrite_refs(r, f);
                }
            }
            rewrite_refs(body, f);
        }
        ExprKind::PartialApplication { args, .. } => {
            for a in args {
                rewrite_refs(&mut a.value, f);
            }
        }
        ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
    }
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
        let mut functions: Vec<&crate::functions::FlatFunction> =
            self.functions.iter().filter(|f| !f.external).collect();
        functions.sort_by_key(|f| quote(&f.name));
        for f in functions {
            p.function(&mut body, f);
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

    /// Number of scalar variables by variability.
    pub fn count(&self, var: Variability) -> usize {
        self.vars
            .iter()
            .filter(|v| v.variability == var)
            .map(FlatVar::size)
            .sum()
    }
}

/// Children of an expression, mutably (subscripts of references excluded).
fn for_each_child(e: &mut Expr, f: &mut dyn FnMut(&mut Expr)) {
    match &mut e.kind {
        ExprKind::Call { args, .. } => {
            args.positional.iter_mut().for_each(&mut *f);
            args.named.iter_mut().for_each(|a| f(&mut a.value));
            for i in &mut args.iterators {
                if let Some(r) = &mut i.range {
                    f(r);
                }
            }
        }
        ExprKind::Unary { operand, .. } => f(operand),
        ExprKind::Binary { lhs, rhs, .. } => {
            f(lhs);
            f(rhs);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                f(c);
                f(v);
            }
            f(otherwise);
        }
        ExprKind::Range { start, step, stop } => {
            f(start);
            if let Some(s) = step {
                f(s);
            }
            f(stop);
        }
        ExprKind::Array(items) => items.iter_mut().for_each(f),
        ExprKind::Matrix(rows) => rows.iter_mut().flatten().for_each(f),
        ExprKind::Tuple(items) => items.iter_mut().flatten().for_each(f),
        ExprKind::Comprehension { body, indices } => {
            for i in indices.iter_mut() {
                if let Some(r) = &mut i.range {
                    f(r);
                }
            }
            f(body);
        }
        ExprKind::PartialApplication { args, .. } => {
            args.iter_mut().for_each(|a| f(&mut a.value));
        }
        ExprKind::Ref(_)
        | ExprKind::Integer(_)
        | ExprKind::Real(_)
        | ExprKind::Bool(_)
        | ExprKind::String(_)
        | ExprKind::End => {}
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
    functions: std::collections::HashSet<&'a str>,
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
                .filter(|f| !f.external)
                .map(|f| f.name.as_str())
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
        for_each_child(e, &mut |c| self.standalone(c, model));
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
                if self.functions.contains(name.as_str())
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
                let n = r.parts.len();
                let ty = r.parts[..n - 1]
                    .iter()
                    .map(|p| p.name.text.as_str())
                    .collect::<Vec<_>>()
                    .join(".");
                if self.enumerations.contains(ty.as_str()) {
                    let literal = r.parts[n - 1].clone();
                    r.global = true;
                    r.parts = vec![
                        RefPart {
                            name: class_ident(&ty, r.span),
                            subscripts: Vec::new(),
                        },
                        literal,
                    ];
                }
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

    /// Whether `r` names a literal of one of the model's enumeration types.
    fn is_literal(&self, r: &ComponentRef) -> bool {
        if self.enumerations.is_empty() {
            return false;
        }
        let n = r.parts.len();
        let ty = r.parts[..n - 1]
            .iter()
            .map(|p| p.name.text.as_str())
            .collect::<Vec<_>>()
            .join(".");
        self.enumerations.contains(ty.as_str())
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
            let d: Vec<String> = v
                .dims
                .iter()
                .map(|n| n.map_or(":".to_owned(), |n| n.to_string()))
                .collect();
            let _ = write!(s, "[{}]", d.join(", "));
        }
        if let Some(d) = &v.default {
            let _ = write!(s, " = {}", self.local_expr(d));
        }
        s
    }

    fn function(&self, out: &mut String, f: &crate::functions::FlatFunction) {
        let name = quote(&f.name);
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
            } => self.branches(
                out,
                depth,
                ("if", "elseif", "end if"),
                branches,
                otherwise,
                true,
                &item,
            ),
            EquationKind::For { indices, body } => {
                let _ = writeln!(out, "for {} loop", print::for_indices(indices));
                for b in body {
                    self.equation(out, b, depth + 1);
                }
                indent(out, depth);
                out.push_str("end for;\n");
            }
            EquationKind::When { branches } => self.branches(
                out,
                depth,
                ("when", "elsewhen", "end when"),
                branches,
                &[],
                true,
                &item,
            ),
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
            } => self.branches(
                out,
                depth,
                ("if", "elseif", "end if"),
                branches,
                otherwise,
                model,
                &item,
            ),
            StatementKind::For { indices, body } => {
                let _ = writeln!(out, "for {} loop", print::for_indices(indices));
                for b in body {
                    self.statement_in(out, b, depth + 1, model);
                }
                indent(out, depth);
                out.push_str("end for;\n");
            }
            StatementKind::While { condition, body } => {
                let _ = writeln!(out, "while {} loop", expr(condition));
                for b in body {
                    self.statement_in(out, b, depth + 1, model);
                }
                indent(out, depth);
                out.push_str("end while;\n");
            }
            StatementKind::When { branches } => self.branches(
                out,
                depth,
                ("when", "elsewhen", "end when"),
                branches,
                &[],
                model,
                &item,
            ),
            StatementKind::Return => out.push_str("return;\n"),
            StatementKind::Break => out.push_str("break;\n"),
        }
    }
}

fn indent(out: &mut String, depth: usize) {
    for _ in 0..depth {
        out.push_str("  ");
    }
}
