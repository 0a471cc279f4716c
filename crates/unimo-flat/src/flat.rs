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
    RefPart, Statement, StatementKind,
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
    pub binding: Option<Expr>,
    /// `start`, `fixed`, `nominal`, `min`, `max`, `unit`, `stateSelect`, ... in order
    /// of first appearance.
    pub attributes: Vec<(SmolStr, Expr)>,
    /// `each` applied to an attribute of an array variable.
    pub each_attributes: Vec<SmolStr>,
    pub description: Option<String>,
    /// Declared in the top-level class (its inputs are known from outside).
    pub top_level: bool,
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

fn type_name(t: &FlatType) -> String {
    match t {
        FlatType::Real => "Real".into(),
        FlatType::Integer => "Integer".into(),
        FlatType::Boolean => "Boolean".into(),
        FlatType::String => "String".into(),
        // Enumerations are referred to by their global name (they live in the model's
        // files or the library, like the functions the equations call).
        FlatType::Enumeration { name, .. } if name == "StateSelect" || name == "AssertionLevel" => {
            name.clone()
        }
        FlatType::Enumeration { name, .. } => format!(
            ".{}",
            name.split('.').map(quote).collect::<Vec<_>>().join(".")
        ),
    }
}

impl FlatModel {
    /// Prints the model as flat Modelica (parses back to the same model).
    pub fn to_modelica(&self) -> String {
        let mut out = String::new();
        let name = quote(&self.name);
        let _ = writeln!(out, "class {name}");
        for v in &self.vars {
            out.push_str("  ");
            out.push_str(&self.var_decl(v));
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
                    write_equation(&mut out, e, 1);
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
                    write_statement(&mut out, s, 1);
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
                    format!("{each}{n} = {}", print::expr(&printable(e)))
                })
                .collect();
            let _ = write!(s, "({})", attrs.join(", "));
        }
        if let Some(b) = &v.binding {
            let _ = write!(s, " = {}", print::expr(&printable(b)));
        }
        if let Some(d) = &v.description {
            s.push(' ');
            s.push_str(&print::string_lit(d));
        }
        s
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

fn indent(out: &mut String, depth: usize) {
    for _ in 0..depth {
        out.push_str("  ");
    }
}

/// `if c then ... elseif ... else ... end if;` (or `when`/`elsewhen`), each body
/// written by `item` one level deeper.
#[allow(clippy::too_many_arguments)]
fn write_branches<T>(
    out: &mut String,
    depth: usize,
    (first, next, end): (&str, &str, &str),
    branches: &[(Expr, Vec<T>)],
    otherwise: &[T],
    item: fn(&mut String, &T, usize),
) {
    for (i, (c, body)) in branches.iter().enumerate() {
        if i > 0 {
            indent(out, depth);
        }
        let kw = if i == 0 { first } else { next };
        let _ = writeln!(out, "{kw} {} then", print::expr(&printable(c)));
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

fn write_equation(out: &mut String, e: &Equation, depth: usize) {
    indent(out, depth);
    match &e.kind {
        EquationKind::Simple { lhs, rhs } => {
            let _ = writeln!(
                out,
                "{} = {};",
                print::expr(&printable(lhs)),
                print::expr(&printable(rhs))
            );
        }
        EquationKind::Call(c) => {
            let _ = writeln!(out, "{};", print::expr(&printable(c)));
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
        } => write_branches(
            out,
            depth,
            ("if", "elseif", "end if"),
            branches,
            otherwise,
            write_equation,
        ),
        EquationKind::For { indices, body } => {
            let _ = writeln!(out, "for {} loop", print::for_indices(indices));
            for b in body {
                write_equation(out, b, depth + 1);
            }
            indent(out, depth);
            out.push_str("end for;\n");
        }
        EquationKind::When { branches } => write_branches(
            out,
            depth,
            ("when", "elsewhen", "end when"),
            branches,
            &[],
            write_equation,
        ),
    }
}

fn write_statement(out: &mut String, s: &Statement, depth: usize) {
    indent(out, depth);
    match &s.kind {
        StatementKind::Assign { target, value } => {
            let _ = writeln!(
                out,
                "{} := {};",
                print::cref(&printable_ref(target)),
                print::expr(&printable(value))
            );
        }
        StatementKind::MultiAssign { targets, value } => {
            let t: Vec<String> = targets
                .iter()
                .map(|t| {
                    t.as_ref()
                        .map(|e| print::expr(&printable(e)))
                        .unwrap_or_default()
                })
                .collect();
            let _ = writeln!(
                out,
                "({}) := {};",
                t.join(", "),
                print::expr(&printable(value))
            );
        }
        StatementKind::Call(e) => {
            let _ = writeln!(out, "{};", print::expr(&printable(e)));
        }
        StatementKind::If {
            branches,
            otherwise,
        } => write_branches(
            out,
            depth,
            ("if", "elseif", "end if"),
            branches,
            otherwise,
            write_statement,
        ),
        StatementKind::For { indices, body } => {
            let _ = writeln!(out, "for {} loop", print::for_indices(indices));
            for b in body {
                write_statement(out, b, depth + 1);
            }
            indent(out, depth);
            out.push_str("end for;\n");
        }
        StatementKind::While { condition, body } => {
            let _ = writeln!(out, "while {} loop", print::expr(&printable(condition)));
            for b in body {
                write_statement(out, b, depth + 1);
            }
            indent(out, depth);
            out.push_str("end while;\n");
        }
        StatementKind::When { branches } => write_branches(
            out,
            depth,
            ("when", "elsewhen", "end when"),
            branches,
            &[],
            write_statement,
        ),
        StatementKind::Return => out.push_str("return;\n"),
        StatementKind::Break => out.push_str("break;\n"),
    }
}
