//! A stable, indented text dump of the AST for snapshot tests and `unimo emit --stage ast`.
//! Classes, elements, equations and statements carry their `@line:col`; expressions are
//! printed as Modelica text.

use crate::ast::*;
use crate::print;
use std::fmt::Write;
use unimo_source::{SourceFile, Span};

/// Dumps a parsed file.
pub fn dump(def: &StoredDefinition, source: &SourceFile) -> String {
    let mut d = Dumper {
        out: String::new(),
        source,
    };
    if let Some(w) = &def.within {
        let name = w.as_ref().map(Name::to_dotted).unwrap_or_default();
        let _ = writeln!(d.out, "within {name}");
    }
    for c in &def.classes {
        d.class(c, 0);
    }
    d.out
}

struct Dumper<'s> {
    out: String,
    source: &'s SourceFile,
}

impl Dumper<'_> {
    fn at(&self, span: Span) -> String {
        format!("@{}", self.source.line_col(span.start as usize))
    }

    fn line(&mut self, depth: usize, text: &str, span: Option<Span>) {
        for _ in 0..depth {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        if let Some(s) = span {
            self.out.push_str("  ");
            self.out.push_str(&self.at(s));
        }
        self.out.push('\n');
    }

    fn class(&mut self, c: &ClassDef, depth: usize) {
        let mut head = String::new();
        if c.encapsulated {
            head.push_str("encapsulated ");
        }
        if c.partial {
            head.push_str("partial ");
        }
        head.push_str(&c.prefixes.keywords());
        let _ = write!(head, "{} ", c.kind.keyword());
        match &c.body {
            ClassBody::Long {
                description,
                composition,
                extends,
                ..
            } => {
                if let Some(ext) = extends {
                    head.push_str("extends ");
                    head.push_str(&c.name.text);
                    if let Some(m) = &ext.modification {
                        head.push_str(&print::class_modification(m));
                    }
                } else {
                    head.push_str(&c.name.text);
                }
                if let Some(d) = description {
                    head.push(' ');
                    head.push_str(&print::string_lit(d));
                }
                self.line(depth, &head, Some(c.span));
                self.composition(composition, depth + 1);
            }
            _ => {
                let text = print::short_class(c);
                self.line(depth, &text, Some(c.span));
            }
        }
    }

    fn composition(&mut self, comp: &Composition, depth: usize) {
        for e in &comp.elements {
            self.element(e, depth);
        }
        for s in &comp.sections {
            match s {
                Section::Equation(es) => {
                    let head = if es.initial {
                        "initial equation"
                    } else {
                        "equation"
                    };
                    self.line(depth, head, Some(es.span));
                    for eq in &es.equations {
                        self.equation(eq, depth + 1);
                    }
                }
                Section::Algorithm(al) => {
                    let head = if al.initial {
                        "initial algorithm"
                    } else {
                        "algorithm"
                    };
                    self.line(depth, head, Some(al.span));
                    for st in &al.statements {
                        self.statement(st, depth + 1);
                    }
                }
            }
        }
        if let Some(ext) = &comp.external {
            let text = print::external_clause(ext);
            self.line(depth, &text, Some(ext.span));
        }
        if let Some(a) = &comp.annotation {
            let text = format!("annotation{}", print::class_modification(a));
            self.line(depth, &text, None);
        }
    }

    fn element(&mut self, e: &Element, depth: usize) {
        let mut prefix = String::new();
        if e.visibility == Visibility::Protected {
            prefix.push_str("protected ");
        }
        for (flag, word) in [
            (e.redeclare, "redeclare "),
            (e.is_final, "final "),
            (e.inner, "inner "),
            (e.outer, "outer "),
            (e.replaceable, "replaceable "),
        ] {
            if flag {
                prefix.push_str(word);
            }
        }
        let constrained = e.constrainedby.as_ref().map(|c| {
            let m = c
                .modification
                .as_ref()
                .map(print::class_modification)
                .unwrap_or_default();
            format!(" constrainedby {}{m}", c.base.to_dotted())
        });
        match &e.kind {
            ElementKind::Import(i) => {
                let text = match &i.kind {
                    ImportKind::Qualified(n) => format!("import {}", n.to_dotted()),
                    ImportKind::Renamed { alias, name } => {
                        format!("import {} = {}", alias.text, name.to_dotted())
                    }
                    ImportKind::Unqualified(n) => format!("import {}.*", n.to_dotted()),
                    ImportKind::Multiple { name, items } => {
                        let items: Vec<&str> = items.iter().map(|i| i.text.as_str()).collect();
                        format!("import {}.{{{}}}", name.to_dotted(), items.join(", "))
                    }
                };
                self.line(depth, &format!("{prefix}{text}"), Some(e.span));
            }
            ElementKind::Extends(x) => {
                let m = x
                    .modification
                    .as_ref()
                    .map(print::class_modification)
                    .unwrap_or_default();
                let text = format!("{prefix}extends {}{m}", x.base.to_dotted());
                self.line(depth, &text, Some(e.span));
            }
            ElementKind::Class(c) => {
                if !prefix.is_empty() {
                    self.line(depth, prefix.trim_end(), None);
                }
                self.class(c, depth);
                if let Some(c) = constrained {
                    self.line(depth + 1, c.trim_start(), None);
                }
            }
            ElementKind::Component(cc) => {
                let text = format!(
                    "{prefix}{}{}",
                    print::component_clause(cc),
                    constrained.unwrap_or_default()
                );
                self.line(depth, &text, Some(e.span));
            }
        }
    }

    fn equation(&mut self, eq: &Equation, depth: usize) {
        let c = print::comment(&eq.comment);
        match &eq.kind {
            EquationKind::Simple { lhs, rhs } => {
                let text = format!("{} = {}{c}", print::expr(lhs), print::expr(rhs));
                self.line(depth, &text, Some(eq.span));
            }
            EquationKind::Call(e) => {
                let text = format!("{}{c}", print::expr(e));
                self.line(depth, &text, Some(eq.span));
            }
            EquationKind::Connect { a, b } => {
                let text = format!("connect({}, {}){c}", print::cref(a), print::cref(b));
                self.line(depth, &text, Some(eq.span));
            }
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (i, (cond, body)) in branches.iter().enumerate() {
                    let kw = if i == 0 { "if" } else { "elseif" };
                    let span = (i == 0).then_some(eq.span);
                    self.line(depth, &format!("{kw} {} then", print::expr(cond)), span);
                    for e in body {
                        self.equation(e, depth + 1);
                    }
                }
                if !otherwise.is_empty() {
                    self.line(depth, "else", None);
                    for e in otherwise {
                        self.equation(e, depth + 1);
                    }
                }
                self.line(depth, "end if", None);
            }
            EquationKind::For { indices, body } => {
                let head = format!("for {} loop", print::for_indices(indices));
                self.line(depth, &head, Some(eq.span));
                for e in body {
                    self.equation(e, depth + 1);
                }
                self.line(depth, "end for", None);
            }
            EquationKind::When { branches } => {
                for (i, (cond, body)) in branches.iter().enumerate() {
                    let kw = if i == 0 { "when" } else { "elsewhen" };
                    let span = (i == 0).then_some(eq.span);
                    self.line(depth, &format!("{kw} {} then", print::expr(cond)), span);
                    for e in body {
                        self.equation(e, depth + 1);
                    }
                }
                self.line(depth, "end when", None);
            }
        }
    }

    fn statement(&mut self, st: &Statement, depth: usize) {
        match &st.kind {
            StatementKind::Assign { target, value } => {
                let text = format!("{} := {}", print::cref(target), print::expr(value));
                self.line(depth, &text, Some(st.span));
            }
            StatementKind::MultiAssign { targets, value } => {
                let t: Vec<String> = targets
                    .iter()
                    .map(|t| t.as_ref().map(print::expr).unwrap_or_default())
                    .collect();
                let text = format!("({}) := {}", t.join(", "), print::expr(value));
                self.line(depth, &text, Some(st.span));
            }
            StatementKind::Call(e) => {
                let text = print::expr(e);
                self.line(depth, &text, Some(st.span));
            }
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (i, (cond, body)) in branches.iter().enumerate() {
                    let kw = if i == 0 { "if" } else { "elseif" };
                    let span = (i == 0).then_some(st.span);
                    self.line(depth, &format!("{kw} {} then", print::expr(cond)), span);
                    for s in body {
                        self.statement(s, depth + 1);
                    }
                }
                if !otherwise.is_empty() {
                    self.line(depth, "else", None);
                    for s in otherwise {
                        self.statement(s, depth + 1);
                    }
                }
                self.line(depth, "end if", None);
            }
            StatementKind::For { indices, body } => {
                let head = format!("for {} loop", print::for_indices(indices));
                self.line(depth, &head, Some(st.span));
                for s in body {
                    self.statement(s, depth + 1);
                }
                self.line(depth, "end for", None);
            }
            StatementKind::While { condition, body } => {
                let head = format!("while {} loop", print::expr(condition));
                self.line(depth, &head, Some(st.span));
                for s in body {
                    self.statement(s, depth + 1);
                }
                self.line(depth, "end while", None);
            }
            StatementKind::When { branches } => {
                for (i, (cond, body)) in branches.iter().enumerate() {
                    let kw = if i == 0 { "when" } else { "elsewhen" };
                    let span = (i == 0).then_some(st.span);
                    self.line(depth, &format!("{kw} {} then", print::expr(cond)), span);
                    for s in body {
                        self.statement(s, depth + 1);
                    }
                }
                self.line(depth, "end when", None);
            }
            StatementKind::Return => self.line(depth, "return", Some(st.span)),
            StatementKind::Break => self.line(depth, "break", Some(st.span)),
        }
    }
}
