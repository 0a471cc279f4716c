//! Syntactic rules the grammar cannot express: matching `end` names, where `when`,
//! `reinit`, `der`, `return` and `break` may stand, builtin operator arity, and
//! duplicates within one declaration.

use crate::ast::*;
use crate::error::SyntaxError;
use std::collections::HashMap;
use unimo_source::{Diagnostic, Span};

/// Checks a parsed file, appending diagnostics.
pub fn validate(def: &StoredDefinition, diags: &mut Vec<Diagnostic>) {
    let mut v = Validator { diags };
    v.classes(&def.classes);
}

struct Validator<'d> {
    diags: &'d mut Vec<Diagnostic>,
}

/// Where an equation or statement stands.
#[derive(Clone, Copy, Default)]
struct Ctx {
    in_when: bool,
    in_initial: bool,
    in_function: bool,
    in_loop: bool,
}

/// Operators with a fixed number of arguments (min, max).
fn operator_arity(name: &str) -> Option<(usize, usize)> {
    Some(match name {
        "der" | "pre" | "edge" | "change" | "noEvent" => (1, 1),
        "reinit" | "smooth" => (2, 2),
        // `sample(start, interval)`, and the clocked `sample(u)` / `sample(u, clock)`.
        "sample" => (1, 2),
        "initial" | "terminal" => (0, 0),
        "assert" => (2, 3),
        "terminate" => (1, 1),
        _ => return None,
    })
}

fn simple_name(func: &Name) -> Option<&str> {
    if func.global || func.parts.len() != 1 {
        return None;
    }
    Some(func.parts[0].text.as_str())
}

impl Validator<'_> {
    fn push(&mut self, e: SyntaxError) {
        self.diags.push(e.into());
    }

    fn classes<'c>(&mut self, classes: impl IntoIterator<Item = &'c ClassDef>) {
        let mut seen: HashMap<&str, Span> = HashMap::new();
        for c in classes {
            if let Some(first) = seen.get(c.name.text.as_str()) {
                self.push(SyntaxError::DuplicateClass {
                    name: c.name.text.to_string(),
                    span: c.name.span,
                    first: *first,
                });
            } else {
                seen.insert(&c.name.text, c.name.span);
            }
            self.class(c);
        }
    }

    /// `expandable` refines only `connector`; `operator` only `record` and `function`;
    /// `pure`/`impure` only `function` (spec A.2.2, class-prefixes).
    fn class_prefixes(&mut self, c: &ClassDef) {
        let p = c.prefixes;
        let misplaced = [
            (
                p.expandable && c.kind != ClassKind::Connector,
                "expandable",
                "connector",
            ),
            (
                p.operator && !matches!(c.kind, ClassKind::Record | ClassKind::Function),
                "operator",
                "record` or `function",
            ),
            (
                p.purity.is_some() && c.kind != ClassKind::Function,
                "pure`/`impure",
                "function",
            ),
        ];
        for (bad, word, allowed) in misplaced {
            if bad {
                self.push(SyntaxError::MisplacedClassPrefix {
                    word,
                    keyword: c.kind.keyword(),
                    allowed,
                    span: c.name.span,
                });
            }
        }
    }

    fn class(&mut self, c: &ClassDef) {
        self.class_prefixes(c);
        match &c.body {
            ClassBody::Der { comment, .. } => self.comment(comment),
            ClassBody::Long {
                composition,
                end_name,
                ..
            } => {
                if end_name.text != c.name.text && !end_name.text.is_empty() {
                    self.push(SyntaxError::EndNameMismatch {
                        end_name: end_name.text.to_string(),
                        keyword: c.kind.keyword(),
                        name: c.name.text.to_string(),
                        span: end_name.span,
                        opened: c.name.span,
                    });
                }
                self.composition(c, composition);
            }
            ClassBody::Short {
                modification,
                comment,
                dims,
                ..
            } => {
                for d in dims {
                    self.subscript(d, Ctx::default());
                }
                if let Some(m) = modification {
                    self.class_modification(m);
                }
                self.comment(comment);
            }
            ClassBody::Enumeration { literals, .. } => {
                let mut seen: HashMap<&str, Span> = HashMap::new();
                for l in literals {
                    if let Some(first) = seen.get(l.name.text.as_str()) {
                        self.push(SyntaxError::DuplicateLiteral {
                            name: l.name.text.to_string(),
                            span: l.name.span,
                            first: *first,
                        });
                    } else {
                        seen.insert(&l.name.text, l.name.span);
                    }
                }
            }
        }
    }

    fn composition(&mut self, c: &ClassDef, comp: &Composition) {
        for e in &comp.elements {
            match &e.kind {
                ElementKind::Class(_) => {}
                ElementKind::Component(cc) => self.component_clause(cc),
                ElementKind::Extends(ext) => {
                    if let Some(m) = &ext.modification {
                        self.class_modification(m);
                    }
                }
                ElementKind::Import(_) => {}
            }
            if let Some(cb) = &e.constrainedby {
                if let Some(m) = &cb.modification {
                    self.class_modification(m);
                }
            }
        }
        self.classes(comp.elements.iter().filter_map(|e| match &e.kind {
            ElementKind::Class(cd) => Some(cd.as_ref()),
            _ => None,
        }));
        if let Some(ext) = &comp.external {
            self.external(c, ext);
        }
        for s in &comp.sections {
            self.section(c, s);
        }
    }

    /// An `external` clause: allowed in functions only; its arguments checked.
    fn external(&mut self, c: &ClassDef, ext: &External) {
        if c.kind != ClassKind::Function {
            self.push(SyntaxError::ExternalNotInFunction {
                keyword: c.kind.keyword(),
                name: c.name.text.to_string(),
                span: ext.span,
                class: c.name.span,
            });
        }
        if let Some(call) = &ext.call {
            for a in &call.args {
                self.expr(a, Ctx::default());
            }
        }
    }

    /// An equation or algorithm section: allowed in some kinds of class only; its
    /// equations or statements checked.
    fn section(&mut self, c: &ClassDef, s: &Section) {
        let in_function = c.kind == ClassKind::Function;
        match s {
            Section::Equation(es) => {
                if !c.kind.may_have_equations() {
                    self.push(SyntaxError::EquationsNotAllowed {
                        keyword: c.kind.keyword(),
                        name: c.name.text.to_string(),
                        in_function,
                        span: es.span,
                        class: c.name.span,
                    });
                }
                let ctx = Ctx {
                    in_initial: es.initial,
                    in_function,
                    ..Ctx::default()
                };
                for eq in &es.equations {
                    self.equation(eq, ctx);
                }
            }
            Section::Algorithm(al) => {
                if !c.kind.may_have_algorithms() {
                    self.push(SyntaxError::AlgorithmNotAllowed {
                        keyword: c.kind.keyword(),
                        name: c.name.text.to_string(),
                        span: al.span,
                        class: c.name.span,
                    });
                }
                let ctx = Ctx {
                    in_initial: al.initial,
                    in_function,
                    ..Ctx::default()
                };
                for st in &al.statements {
                    self.statement(st, ctx);
                }
            }
        }
    }

    fn component_clause(&mut self, cc: &ComponentClause) {
        for d in &cc.type_dims {
            self.subscript(d, Ctx::default());
        }
        for decl in &cc.components {
            for d in &decl.dims {
                self.subscript(d, Ctx::default());
            }
            if let Some(m) = &decl.modification {
                self.modification(m);
            }
            if let Some(cond) = &decl.condition {
                self.expr(cond, Ctx::default());
            }
            self.comment(&decl.comment);
        }
    }

    /// Annotations are free-form (vendor annotations, `choices(choice = 1, choice = 2)`):
    /// they are parsed but not validated.
    fn comment(&mut self, _c: &Comment) {}

    fn modification(&mut self, m: &Modification) {
        if let Some(cm) = &m.class_mod {
            self.class_modification(cm);
        }
        if let Some(b) = &m.binding {
            self.expr(b, Ctx::default());
        }
    }

    fn class_modification(&mut self, cm: &ClassModification) {
        let mut seen: HashMap<String, Span> = HashMap::new();
        for a in &cm.args {
            match a {
                Argument::Modify {
                    name,
                    modification,
                    span,
                    ..
                } => {
                    let key = name.to_dotted();
                    // `a(x = 1)` and `a(y = 2)` written as `a.x = 1, a.y = 2` are fine; the
                    // same full name twice is not (spec 7.2.4).
                    if let Some(first) = seen.get(&key) {
                        if modification.as_ref().is_some_and(|m| m.binding.is_some()) {
                            self.push(SyntaxError::DuplicateModification {
                                name: key.clone(),
                                span: *span,
                                first: *first,
                            });
                        }
                    } else if modification.as_ref().is_some_and(|m| m.binding.is_some()) {
                        seen.insert(key, *span);
                    }
                    if let Some(m) = modification {
                        self.modification(m);
                    }
                }
                Argument::Redeclare { element, .. } => match element {
                    RedeclaredElement::Component(cc) => self.component_clause(cc),
                    RedeclaredElement::Class(cd) => self.class(cd),
                },
            }
        }
    }

    fn equation(&mut self, eq: &Equation, ctx: Ctx) {
        match &eq.kind {
            EquationKind::Simple { lhs, rhs } => {
                match &lhs.kind {
                    // `(a, b) = f(x)` is a valid equation.
                    ExprKind::Tuple(items) if !items.is_empty() => {
                        for i in items.iter().flatten() {
                            self.expr(i, ctx);
                        }
                    }
                    _ => self.expr(lhs, ctx),
                }
                self.expr(rhs, ctx);
            }
            EquationKind::Call(e) => {
                if !matches!(e.kind, ExprKind::Call { .. }) {
                    if !matches!(&e.kind, ExprKind::Tuple(v) if v.is_empty()) {
                        self.push(SyntaxError::EquationWithoutEquals { span: e.span });
                    }
                    return;
                }
                self.call_statement(e, ctx);
            }
            EquationKind::Connect { a, b } => {
                for r in [a, b] {
                    self.cref(r, ctx);
                }
            }
            EquationKind::If {
                branches,
                otherwise,
            } => {
                for (c, body) in branches {
                    self.expr(c, ctx);
                    for e in body {
                        self.equation(e, ctx);
                    }
                }
                for e in otherwise {
                    self.equation(e, ctx);
                }
            }
            EquationKind::For { indices, body } => {
                self.indices(indices, ctx);
                for e in body {
                    self.equation(e, ctx);
                }
            }
            EquationKind::When { branches } => {
                if self.when_allowed(eq.span, ctx) {
                    let inner = Ctx {
                        in_when: true,
                        ..ctx
                    };
                    for (c, body) in branches {
                        self.expr(c, ctx);
                        for e in body {
                            self.equation(e, inner);
                        }
                    }
                }
            }
        }
    }

    /// Reports a `when` where none may stand; returns whether its body should be checked.
    fn when_allowed(&mut self, span: Span, ctx: Ctx) -> bool {
        let when_span = Span::new(span.file, span.start as usize, span.start as usize + 4);
        if ctx.in_when {
            self.push(SyntaxError::NestedWhen { span: when_span });
            return false;
        }
        if ctx.in_function {
            self.push(SyntaxError::WhenInFunction { span: when_span });
            return false;
        }
        if ctx.in_initial {
            self.push(SyntaxError::WhenInInitial { span: when_span });
            return false;
        }
        true
    }

    /// A call standing alone as an equation or statement (`reinit`, `assert`, ...).
    fn call_statement(&mut self, e: &Expr, ctx: Ctx) {
        if let ExprKind::Call { func, args } = &e.kind {
            if simple_name(func) == Some("reinit") {
                if !ctx.in_when {
                    self.push(SyntaxError::ReinitOutsideWhen { span: func.span });
                }
                if let Some(first) = args.positional.first() {
                    if !matches!(first.kind, ExprKind::Ref(_)) {
                        self.push(SyntaxError::ReinitOfNonVariable { span: first.span });
                    }
                }
            }
        }
        self.expr(e, ctx);
    }

    fn statement(&mut self, st: &Statement, ctx: Ctx) {
        match &st.kind {
            StatementKind::Assign { target, value } => {
                self.cref(target, ctx);
                self.expr(value, ctx);
            }
            StatementKind::MultiAssign { targets, value } => {
                for t in targets.iter().flatten() {
                    if !matches!(t.kind, ExprKind::Ref(_)) {
                        self.push(SyntaxError::NonVariableTarget { span: t.span });
                    }
                }
                self.expr(value, ctx);
            }
            StatementKind::Call(e) => {
                if matches!(e.kind, ExprKind::Call { .. }) {
                    self.call_statement(e, ctx);
                }
            }
            StatementKind::If {
                branches,
                otherwise,
            } => {
                for (c, body) in branches {
                    self.expr(c, ctx);
                    for s in body {
                        self.statement(s, ctx);
                    }
                }
                for s in otherwise {
                    self.statement(s, ctx);
                }
            }
            StatementKind::For { indices, body } => {
                self.indices(indices, ctx);
                let inner = Ctx {
                    in_loop: true,
                    ..ctx
                };
                for s in body {
                    self.statement(s, inner);
                }
            }
            StatementKind::While { condition, body } => {
                self.expr(condition, ctx);
                let inner = Ctx {
                    in_loop: true,
                    ..ctx
                };
                for s in body {
                    self.statement(s, inner);
                }
            }
            StatementKind::When { branches } => {
                if self.when_allowed(st.span, ctx) {
                    let inner = Ctx {
                        in_when: true,
                        in_loop: false,
                        ..ctx
                    };
                    for (c, body) in branches {
                        self.expr(c, ctx);
                        for s in body {
                            self.statement(s, inner);
                        }
                    }
                }
            }
            StatementKind::Return => {
                if !ctx.in_function {
                    self.push(SyntaxError::ReturnOutsideFunction { span: st.span });
                }
            }
            StatementKind::Break => {
                if !ctx.in_loop {
                    self.push(SyntaxError::BreakOutsideLoop { span: st.span });
                }
            }
        }
    }

    fn indices(&mut self, indices: &[ForIndex], ctx: Ctx) {
        for i in indices {
            if let Some(r) = &i.range {
                self.expr(r, ctx);
            }
        }
    }

    fn cref(&mut self, r: &ComponentRef, ctx: Ctx) {
        for p in &r.parts {
            for s in &p.subscripts {
                self.subscript(s, ctx);
            }
        }
    }

    fn subscript(&mut self, s: &Subscript, ctx: Ctx) {
        if let Subscript::Expr(e) = s {
            if matches!(e.kind, ExprKind::End) {
                return;
            }
            self.expr_in(e, ctx, true);
        }
    }

    fn expr(&mut self, e: &Expr, ctx: Ctx) {
        self.expr_in(e, ctx, false);
    }

    fn expr_in(&mut self, e: &Expr, ctx: Ctx, in_subscript: bool) {
        match &e.kind {
            ExprKind::Integer(_) | ExprKind::Real(_) | ExprKind::Bool(_) | ExprKind::String(_) => {}
            ExprKind::End => {
                if !in_subscript {
                    self.push(SyntaxError::EndOutsideSubscript { span: e.span });
                }
            }
            ExprKind::Ref(r) => self.cref(r, ctx),
            ExprKind::Call { func, args } => self.call(func, args, ctx, in_subscript),
            ExprKind::Unary { operand, .. } => self.expr_in(operand, ctx, in_subscript),
            ExprKind::Binary { op, lhs, rhs } => {
                self.chained(*op, lhs, rhs);
                self.expr_in(lhs, ctx, in_subscript);
                self.expr_in(rhs, ctx, in_subscript);
            }
            ExprKind::If {
                branches,
                otherwise,
            } => {
                for (c, v) in branches {
                    self.expr_in(c, ctx, in_subscript);
                    self.expr_in(v, ctx, in_subscript);
                }
                self.expr_in(otherwise, ctx, in_subscript);
            }
            ExprKind::Range { start, step, stop } => {
                self.expr_in(start, ctx, in_subscript);
                if let Some(s) = step {
                    self.expr_in(s, ctx, in_subscript);
                }
                self.expr_in(stop, ctx, in_subscript);
            }
            ExprKind::Array(items) => {
                for i in items {
                    self.expr_in(i, ctx, in_subscript);
                }
            }
            ExprKind::Comprehension { body, indices } => {
                self.indices(indices, ctx);
                self.expr_in(body, ctx, in_subscript);
            }
            ExprKind::Matrix(rows) => {
                for i in rows.iter().flatten() {
                    self.expr_in(i, ctx, in_subscript);
                }
            }
            ExprKind::Tuple(items) => {
                self.push(if items.is_empty() {
                    SyntaxError::EmptyParentheses { span: e.span }
                } else {
                    SyntaxError::TupleAsValue { span: e.span }
                });
            }
            ExprKind::PartialApplication { args, .. } => {
                for a in args {
                    self.expr(&a.value, ctx);
                }
            }
        }
    }

    /// `a < b < c` and `a ^ b ^ c` are not Modelica (both operators are non-associative).
    fn chained(&mut self, op: BinaryOp, lhs: &Expr, rhs: &Expr) {
        use BinaryOp::*;
        let relational = |o: BinaryOp| matches!(o, Rel(_));
        let power = |o: BinaryOp| matches!(o, Pow | ElemPow);
        for (side, sub) in [(false, lhs), (true, rhs)] {
            // The parser keeps explicit parentheses in the span only; a parenthesized
            // operand has a span wider than its operator's operands, so skip those.
            if let ExprKind::Binary {
                op: inner,
                lhs: il,
                rhs: ir,
            } = &sub.kind
            {
                let parenthesized = sub.span != il.span.to(ir.span);
                if parenthesized {
                    continue;
                }
                if relational(op) && relational(*inner) {
                    self.push(SyntaxError::ChainedComparison {
                        span: lhs.span.to(rhs.span),
                    });
                    return;
                }
                if power(op) && power(*inner) && side {
                    self.push(SyntaxError::ChainedPower {
                        span: lhs.span.to(rhs.span),
                    });
                    return;
                }
            }
        }
    }

    fn call(&mut self, func: &Name, args: &CallArgs, ctx: Ctx, in_subscript: bool) {
        if let Some(name) = simple_name(func) {
            if let Some((lo, hi)) = operator_arity(name) {
                let n = args.positional.len() + args.named.len();
                if n < lo || n > hi {
                    self.push(SyntaxError::OperatorArity {
                        name: name.to_string(),
                        min: lo,
                        max: hi,
                        found: n,
                        span: args.span,
                    });
                }
            }
            let event_op = matches!(
                name,
                "der" | "pre" | "edge" | "change" | "reinit" | "initial" | "terminal" | "sample"
            );
            if ctx.in_function && event_op {
                self.push(SyntaxError::EventOperatorInFunction {
                    name: name.to_string(),
                    span: func.span,
                });
            }
            match name {
                "der" => {
                    if let Some(a) = args.positional.first() {
                        if matches!(
                            a.kind,
                            ExprKind::Integer(_)
                                | ExprKind::Real(_)
                                | ExprKind::Bool(_)
                                | ExprKind::String(_)
                        ) {
                            self.push(SyntaxError::DerOfLiteral { span: a.span });
                        }
                    }
                }
                "pre" | "edge" | "change" => {
                    if let Some(a) = args.positional.first() {
                        if !matches!(a.kind, ExprKind::Ref(_)) {
                            self.push(SyntaxError::PreOfNonVariable {
                                name: name.to_string(),
                                span: a.span,
                            });
                        }
                    }
                }
                _ => {}
            }
        }
        for a in &args.positional {
            self.expr_in(a, ctx, in_subscript);
        }
        for a in &args.named {
            self.expr_in(&a.value, ctx, in_subscript);
        }
        self.indices(&args.iterators, ctx);
    }
}
