//! The name-resolution check: every type name, base class, import, function name and
//! the first part of every component reference in a class must denote something.

use crate::error::FlatError;
use crate::lookup::Found;
use crate::tree::{ClassId, ClassTree};
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

/// Checks the names used in `class` and in its nested classes, then the semantic rules
/// of the specification on them (`crate::check`); returns diagnostics.
pub fn check_names(tree: &mut ClassTree<'_>, class: ClassId) -> Vec<Diagnostic> {
    let mut c = Checker {
        tree,
        out: Vec::new(),
        iterators: Vec::new(),
        suppress_refs: false,
    };
    c.class(class);
    let mut out = c.out;
    out.extend(crate::check::check_class(tree, class));
    out
}

/// The E2001 diagnostic for `name`, unknown in `scope`, with a suggestion of a close name
/// (the same message the name check gives).
pub(crate) fn unknown_name(
    tree: &mut ClassTree<'_>,
    scope: ClassId,
    name: &Name,
    what: &'static str,
) -> Diagnostic {
    let mut c = Checker {
        tree,
        out: Vec::new(),
        iterators: Vec::new(),
        suppress_refs: false,
    };
    c.unknown(scope, name, name.span, what);
    c.out.pop().expect("`unknown` reports one diagnostic")
}

struct Checker<'t, 'p> {
    tree: &'t mut ClassTree<'p>,
    out: Vec<Diagnostic>,
    /// `for` iterator names in scope.
    iterators: Vec<String>,
    /// A base class of the current class is unknown: its inherited names would all be
    /// reported again, so references are not checked.
    suppress_refs: bool,
}

/// The closest candidate to `name` (Damerau–Levenshtein, at most a third of its length),
/// preferring a candidate of the same length on ties.
pub fn suggest(name: &str, candidates: Vec<String>) -> Option<String> {
    if name.chars().count() <= 1 {
        return None;
    }
    let limit = (name.len() / 3).max(1);
    candidates
        .into_iter()
        .filter(|c| c != name)
        .map(|c| {
            let d = strsim::damerau_levenshtein(name, &c);
            (d, c.len().abs_diff(name.len()), c)
        })
        .filter(|(d, _, _)| *d <= limit)
        .min()
        .map(|(_, _, c)| c)
}

impl Checker<'_, '_> {
    /// Reports `name` as unknown, pointing at its first part that does not resolve and
    /// suggesting a close name from where that part was searched.
    fn unknown(&mut self, scope: ClassId, name: &Name, span: Span, what: &'static str) {
        if self.suppress_refs && what == "name" {
            return;
        }
        let parts: Vec<&str> = name.parts.iter().map(|p| p.text.as_str()).collect();
        // The longest prefix that resolves to a class: the failing part is a member of it.
        let start = if name.global { None } else { Some(scope) };
        let mut owner = None;
        let mut failing = 0;
        for k in 1..parts.len() {
            match self.tree.lookup_dotted(start, &parts[..k], false) {
                Some(Found::Class(c)) => {
                    owner = Some(c);
                    failing = k;
                }
                _ => break,
            }
        }
        let mut candidates = match owner {
            Some(c) => self.tree.child_names(c),
            None => {
                let mut v = self.tree.visible_names(start);
                if what == "function" {
                    v.extend(unimo_builtins::function_names().map(str::to_string));
                }
                v
            }
        };
        if owner.is_none() {
            candidates.extend(self.iterators.iter().cloned());
        }
        let suggestion = parts
            .get(failing)
            .and_then(|p| suggest(p, candidates))
            .map(|s| {
                let mut full: Vec<&str> = parts[..failing].to_vec();
                full.push(&s);
                full.join(".")
            });
        let encapsulated_hint = owner.is_none()
            && failing == 0
            && self.tree.is_inside_encapsulated(scope)
            && self.tree.lookup_dotted(None, &parts, false).is_some();
        let span = name.parts.get(failing).map_or(span, |p| {
            p.span.to(name.parts.last().map_or(p.span, |l| l.span))
        });
        self.out.push(
            FlatError::UnknownName {
                name: name.to_dotted(),
                what,
                span,
                suggestion,
                encapsulated: encapsulated_hint,
            }
            .into(),
        );
    }

    fn class(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        match &def.body {
            ClassBody::Der { base, .. } => {
                let scope = self.tree.get(id).parent;
                let refs: Vec<&str> = base.parts.iter().map(|p| p.text.as_str()).collect();
                if self.tree.lookup_dotted(scope, &refs, false).is_none() {
                    self.unknown(scope.unwrap_or(id), base, base.span, "function");
                }
            }
            ClassBody::Short {
                base, modification, ..
            } => {
                let scope = self.tree.get(id).parent;
                let refs: Vec<&str> = base.parts.iter().map(|p| p.text.as_str()).collect();
                if self.tree.lookup_dotted(scope, &refs, false).is_none() {
                    self.unknown(scope.unwrap_or(id), base, base.span, "class");
                }
                if let Some(m) = modification {
                    self.class_mod(id, m);
                }
            }
            ClassBody::Enumeration { .. } => {}
            ClassBody::Long { composition, .. } => {
                let outer = self.suppress_refs;
                for e in &composition.elements {
                    self.element(id, e);
                }
                for s in &composition.sections {
                    match s {
                        Section::Equation(es) => {
                            for eq in &es.equations {
                                self.equation(id, eq);
                            }
                        }
                        Section::Algorithm(al) => {
                            for st in &al.statements {
                                self.statement(id, st);
                            }
                        }
                    }
                }
                self.suppress_refs = outer;
            }
        }
    }

    fn element(&mut self, id: ClassId, e: &Element) {
        match &e.kind {
            ElementKind::Import(imp) => {
                let name = match &imp.kind {
                    ImportKind::Qualified(n) | ImportKind::Unqualified(n) => n,
                    ImportKind::Renamed { name, .. } => name,
                    ImportKind::Multiple { name, .. } => name,
                };
                let refs: Vec<&str> = name.parts.iter().map(|p| p.text.as_str()).collect();
                if self.tree.lookup_dotted(None, &refs, false).is_none() {
                    self.unknown(id, name, name.span, "imported package or class");
                }
            }
            ElementKind::Extends(x) => {
                let refs: Vec<&str> = x.base.parts.iter().map(|p| p.text.as_str()).collect();
                if !matches!(
                    self.tree.lookup_dotted(Some(id), &refs, true),
                    Some(Found::Class(_) | Found::Builtin(_))
                ) {
                    self.unknown(id, &x.base, x.base.span, "base class");
                    self.suppress_refs = true;
                }
                if let Some(m) = &x.modification {
                    self.class_mod(id, m);
                }
            }
            ElementKind::Class(c) => {
                if let Some(child) = self.tree.child_class(id, &c.name.text) {
                    // Checked in its own scope (its `end` and body belong to it).
                    if self.tree.get(child).def.span == c.span {
                        self.class(child);
                    }
                }
            }
            ElementKind::Component(cc) => {
                let refs: Vec<&str> = cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
                if !matches!(
                    self.tree.lookup_dotted(Some(id), &refs, false),
                    Some(Found::Class(_) | Found::Builtin(_))
                ) {
                    self.unknown(id, &cc.type_name, cc.type_name.span, "type");
                }
                for s in &cc.type_dims {
                    self.subscript(id, s);
                }
                for d in &cc.components {
                    for s in &d.dims {
                        self.subscript(id, s);
                    }
                    if let Some(m) = &d.modification {
                        self.modification(id, m);
                    }
                    if let Some(c) = &d.condition {
                        self.expr(id, c);
                    }
                }
            }
        }
        if let Some(cb) = &e.constrainedby {
            let refs: Vec<&str> = cb.base.parts.iter().map(|p| p.text.as_str()).collect();
            if self.tree.lookup_dotted(Some(id), &refs, false).is_none() {
                self.unknown(id, &cb.base, cb.base.span, "constraining class");
            }
        }
    }

    /// Modifier values are expressions of the scope that writes them; the modified
    /// names themselves belong to the modified class and are checked when instantiating.
    fn modification(&mut self, id: ClassId, m: &Modification) {
        if let Some(cm) = &m.class_mod {
            self.class_mod(id, cm);
        }
        if let Some(b) = &m.binding {
            self.expr(id, b);
        }
    }

    fn class_mod(&mut self, id: ClassId, cm: &ClassModification) {
        for a in &cm.args {
            match a {
                Argument::Modify {
                    modification: Some(m),
                    ..
                } => self.modification(id, m),
                Argument::Modify { .. } => {}
                Argument::Redeclare { element, .. } => match element {
                    RedeclaredElement::Component(cc) => {
                        let refs: Vec<&str> =
                            cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
                        if self.tree.lookup_dotted(Some(id), &refs, false).is_none() {
                            self.unknown(id, &cc.type_name, cc.type_name.span, "type");
                        }
                    }
                    RedeclaredElement::Class(c) => {
                        if let ClassBody::Short { base, .. } = &c.body {
                            let refs: Vec<&str> =
                                base.parts.iter().map(|p| p.text.as_str()).collect();
                            if self.tree.lookup_dotted(Some(id), &refs, false).is_none() {
                                self.unknown(id, base, base.span, "class");
                            }
                        }
                    }
                },
            }
        }
    }

    fn equation(&mut self, id: ClassId, eq: &Equation) {
        match &eq.kind {
            EquationKind::Simple { lhs, rhs } => {
                self.expr(id, lhs);
                self.expr(id, rhs);
            }
            EquationKind::Call(e) => self.expr(id, e),
            EquationKind::Connect { a, b } => {
                self.cref(id, a);
                self.cref(id, b);
            }
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (c, body) in branches {
                    self.expr(id, c);
                    for e in body {
                        self.equation(id, e);
                    }
                }
                for e in otherwise {
                    self.equation(id, e);
                }
            }
            EquationKind::For { indices, body } => {
                let n = self.push_indices(id, indices);
                for e in body {
                    self.equation(id, e);
                }
                self.iterators.truncate(self.iterators.len() - n);
            }
            EquationKind::When { branches } => {
                for (c, body) in branches {
                    self.expr(id, c);
                    for e in body {
                        self.equation(id, e);
                    }
                }
            }
        }
    }

    fn statement(&mut self, id: ClassId, st: &Statement) {
        match &st.kind {
            StatementKind::Assign { target, value } => {
                self.cref(id, target);
                self.expr(id, value);
            }
            StatementKind::MultiAssign { targets, value } => {
                for t in targets.iter().flatten() {
                    self.expr(id, t);
                }
                self.expr(id, value);
            }
            StatementKind::Call(e) => self.expr(id, e),
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (c, body) in branches {
                    self.expr(id, c);
                    for s in body {
                        self.statement(id, s);
                    }
                }
                for s in otherwise {
                    self.statement(id, s);
                }
            }
            StatementKind::For { indices, body } => {
                let n = self.push_indices(id, indices);
                for s in body {
                    self.statement(id, s);
                }
                self.iterators.truncate(self.iterators.len() - n);
            }
            StatementKind::While { condition, body } => {
                self.expr(id, condition);
                for s in body {
                    self.statement(id, s);
                }
            }
            StatementKind::When { branches } => {
                for (c, body) in branches {
                    self.expr(id, c);
                    for s in body {
                        self.statement(id, s);
                    }
                }
            }
            StatementKind::Return | StatementKind::Break => {}
        }
    }

    /// Checks the ranges, then brings the iterators into scope; returns how many.
    fn push_indices(&mut self, id: ClassId, indices: &[ForIndex]) -> usize {
        for i in indices {
            if let Some(r) = &i.range {
                self.expr(id, r);
            }
        }
        self.iterators
            .extend(indices.iter().map(|i| i.name.text.to_string()));
        indices.len()
    }

    fn subscript(&mut self, id: ClassId, s: &Subscript) {
        if let Subscript::Expr(e) = s {
            self.expr(id, e);
        }
    }

    fn cref(&mut self, id: ClassId, r: &ComponentRef) {
        for p in &r.parts {
            for s in &p.subscripts {
                self.subscript(id, s);
            }
        }
        let Some(first) = r.parts.first() else { return };
        let name = first.name.text.as_str();
        if r.global {
            let refs: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
            if self.tree.lookup_dotted(None, &refs, false).is_none() {
                let n = Name {
                    global: true,
                    parts: r.parts.iter().map(|p| p.name.clone()).collect(),
                    span: r.span,
                };
                self.unknown(id, &n, r.span, "name");
            }
            return;
        }
        if name == "time" || self.iterators.iter().any(|i| i == name) {
            return;
        }
        match self.tree.lookup_simple(Some(id), name, false) {
            None => {
                let n = Name {
                    global: false,
                    parts: vec![first.name.clone()],
                    span: first.name.span,
                };
                self.unknown(id, &n, first.name.span, "name");
            }
            // A path through packages (`Modelica.Constants.pi`, `State.Flight`): every
            // part must exist. Members of components are checked when instantiating.
            Some(Found::Class(_)) if r.parts.len() > 1 => {
                let refs: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
                if self.tree.lookup_dotted(Some(id), &refs, false).is_none() {
                    let n = Name {
                        global: false,
                        parts: r.parts.iter().map(|p| p.name.clone()).collect(),
                        span: r.span,
                    };
                    self.unknown(id, &n, r.span, "name");
                }
            }
            Some(_) => {}
        }
    }

    fn expr(&mut self, id: ClassId, e: &Expr) {
        match &e.kind {
            ExprKind::Ref(r) => self.cref(id, r),
            ExprKind::Call { func, args } => {
                // `.asin(u)` names the built-in from the global scope.
                let simple = func.parts.len() == 1;
                let builtin = (simple && crate::lookup::is_builtin_function(&func.parts[0].text))
                    || (!func.global && crate::lookup::is_unsupported_builtin(&func.to_dotted()));
                if !builtin {
                    let refs: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
                    let scope = if func.global { None } else { Some(id) };
                    if self.tree.lookup_dotted(scope, &refs, false).is_none() {
                        self.unknown(id, func, func.span, "function");
                    }
                }
                let n = self.push_indices(id, &args.iterators);
                for a in &args.positional {
                    self.expr(id, a);
                }
                for a in &args.named {
                    self.expr(id, &a.value);
                }
                self.iterators.truncate(self.iterators.len() - n);
            }
            ExprKind::Comprehension { body, indices } => {
                let n = self.push_indices(id, indices);
                self.expr(id, body);
                self.iterators.truncate(self.iterators.len() - n);
            }
            ExprKind::PartialApplication { func, args } => {
                let refs: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
                if self.tree.lookup_dotted(Some(id), &refs, false).is_none() {
                    self.unknown(id, func, func.span, "function");
                }
                for a in args {
                    self.expr(id, &a.value);
                }
            }
            _ => e.for_each_child(&mut |c| self.expr(id, c)),
        }
    }
}
