//! Type and size checks of the flat model: references with more subscripts than their
//! variable has dimensions (`E2017`), and equations or bindings whose two sides have
//! certainly different sizes or types (`E2018`: `y = x` with `x[3]`, `b = 1.5` with a
//! Boolean `b`), and operators applied to variables of the wrong type (`E2020`: `der`
//! of an Integer, `edge` of a Real). Only shapes and types known for certain are
//! compared: a function call or an expression this check cannot size is left to the
//! back end.

use crate::error::FlatError;
use crate::eval::var_key_into;
use crate::flat::{FlatModel, FlatType};
use rustc_hash::FxHashMap as HashMap;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Ty {
    Number,
    Boolean,
    Text,
}

impl Ty {
    fn name(self) -> &'static str {
        match self {
            Ty::Number => "a number",
            Ty::Boolean => "a Boolean",
            Ty::Text => "a String",
        }
    }
}

struct Checker<'m> {
    all: &'m [crate::flat::FlatVar],
    /// Variable indices by name.
    vars: HashMap<&'m str, u32>,
    /// The variable found last: an equation's references are mostly to variables
    /// declared next to each other, so the neighbours are tried before the map (whose
    /// probes miss the cache in a large model).
    hint: std::cell::Cell<usize>,
    diags: Vec<Diagnostic>,
    /// A reused buffer for variable keys.
    buf: std::cell::RefCell<String>,
}

/// How many variables on each side of the last one found are tried first.
const NEAR: usize = 12;

fn ty_of(t: &FlatType) -> Ty {
    match t {
        FlatType::Boolean => Ty::Boolean,
        FlatType::String => Ty::Text,
        // Enumerations compare with each other like numbers here.
        // An external object's handle is an opaque value passed to its functions.
        FlatType::Real
        | FlatType::Integer
        | FlatType::Enumeration { .. }
        | FlatType::ExternalObject { .. } => Ty::Number,
    }
}

impl Checker<'_> {
    /// The index of the variable `r` names (subscripts of its last part ignored).
    fn var_index(&self, r: &ComponentRef) -> Option<usize> {
        let mut buf = self.buf.borrow_mut();
        var_key_into(&mut buf, &r.parts);
        self.vars.get(buf.as_str()).map(|&i| i as usize)
    }

    /// The dimensions and type of the variable `r` names.
    fn var(&self, r: &ComponentRef) -> Option<(&[usize], Ty)> {
        let mut buf = self.buf.borrow_mut();
        var_key_into(&mut buf, &r.parts);
        let key = buf.as_str();
        // From the last one found onwards first (references mostly go forwards),
        // then the ones before it.
        let hint = self.hint.get().min(self.all.len());
        let (lo, hi) = (hint.saturating_sub(NEAR), (hint + NEAR).min(self.all.len()));
        let i = match (hint..hi)
            .chain(lo..hint)
            .find(|&k| self.all[k].name == key)
        {
            Some(k) => k,
            None => *self.vars.get(key)? as usize,
        };
        self.hint.set(i);
        let v = &self.all[i];
        Some((v.dims.as_slice(), ty_of(&v.ty)))
    }

    /// The shape of a reference to a variable of dimensions `dims`, when certain.
    fn ref_shape(r: &ComponentRef, dims: &[usize]) -> Option<Vec<usize>> {
        let subs = r.parts.last().map_or(&[][..], |p| &p.subscripts[..]);
        if subs.len() > dims.len() {
            return None; // reported as E2017
        }
        let mut out = Vec::new();
        for (k, n) in dims.iter().enumerate() {
            match subs.get(k) {
                None | Some(Subscript::Colon(_)) => out.push(*n),
                Some(Subscript::Expr(x)) => match &x.kind {
                    ExprKind::Integer(_) => {}
                    ExprKind::Range {
                        start,
                        step: None,
                        stop,
                    } => match (&start.kind, &stop.kind) {
                        (ExprKind::Integer(a), ExprKind::Integer(b)) => {
                            out.push((b - a + 1).max(0) as usize)
                        }
                        _ => return None,
                    },
                    _ => return None,
                },
            }
        }
        Some(out)
    }

    /// The shape of `e` when it is certain.
    fn shape(&self, e: &Expr) -> Option<Vec<usize>> {
        self.info(e).0
    }

    /// The shape and the type of `e`, each when it is certain: one walk, one variable
    /// lookup per reference (the lookups are most of this check's cost).
    fn info(&self, e: &Expr) -> (Option<Vec<usize>>, Option<Ty>) {
        match &e.kind {
            ExprKind::Integer(_) | ExprKind::Real(_) => (Some(Vec::new()), Some(Ty::Number)),
            ExprKind::Bool(_) => (Some(Vec::new()), Some(Ty::Boolean)),
            ExprKind::String(_) => (Some(Vec::new()), Some(Ty::Text)),
            ExprKind::Ref(r) if !r.global => match self.var(r) {
                Some((dims, ty)) => (Self::ref_shape(r, dims), Some(ty)),
                None => (None, None),
            },
            ExprKind::Array(items) => {
                let Some((first, rest)) = items.split_first() else {
                    return (None, None);
                };
                let (s0, t0) = self.info(first);
                let (mut shape, mut ty) = (s0, t0);
                for i in rest {
                    let (s, t) = self.info(i);
                    if s != shape {
                        shape = None;
                    }
                    if t != ty {
                        ty = None;
                    }
                }
                let shape = shape.map(|first| {
                    let mut d = vec![items.len()];
                    d.extend(first);
                    d
                });
                (shape, ty)
            }
            ExprKind::Unary { op, operand } => {
                let (s, t) = self.info(operand);
                let t = match op {
                    UnaryOp::Not => Some(Ty::Boolean),
                    _ => t.filter(|t| *t == Ty::Number),
                };
                (s, t)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let ((sa, ta), (sb, tb)) = (self.info(lhs), self.info(rhs));
                let shape = match (sa, sb) {
                    (Some(a), Some(b)) => match op {
                        op if crate::lookup::is_elementwise(*op) => {
                            if a == b || b.is_empty() {
                                Some(a)
                            } else if a.is_empty() {
                                Some(b)
                            } else {
                                None
                            }
                        }
                        BinaryOp::Mul if a.is_empty() => Some(b),
                        BinaryOp::Mul | BinaryOp::Div if b.is_empty() => Some(a),
                        _ => None,
                    },
                    _ => None,
                };
                let ty = match op {
                    op if crate::lookup::is_boolean(*op) => Some(Ty::Boolean),
                    BinaryOp::Add => match (ta, tb) {
                        (Some(Ty::Text), Some(Ty::Text)) => Some(Ty::Text),
                        (Some(Ty::Number), Some(Ty::Number)) => Some(Ty::Number),
                        _ => None,
                    },
                    _ => (ta == Some(Ty::Number) && tb == Some(Ty::Number)).then_some(Ty::Number),
                };
                (shape, ty)
            }
            ExprKind::Call { func, args } => match crate::lookup::elementwise_arg(func, args) {
                Some(arg) => (self.info(arg).0, None),
                None => (None, None),
            },
            _ => (None, None),
        }
    }

    /// Operators applied to variables of the wrong type (spec 3.7): `der` of an
    /// Integer, Boolean, String or enumeration variable, `edge` of a variable that is
    /// not Boolean (`E2020`).
    fn operators(&mut self, e: &Expr) {
        let mut found: Vec<(String, String, &'static str, Span)> = Vec::new();
        crate::flat::for_each_call(e, &mut |_| {}, &mut |func, args| {
            let op = func.to_dotted();
            if !matches!(op.as_str(), "der" | "edge") {
                return;
            }
            let Some(Expr {
                kind: ExprKind::Ref(r),
                span,
            }) = args.positional.first()
            else {
                return;
            };
            let Some(i) = self.var_index(r) else { return };
            let ty = &self.all[i].ty;
            let bad = match (op.as_str(), ty) {
                ("der", FlatType::Real) => None,
                ("der", _) => Some("a Real variable"),
                ("edge", FlatType::Boolean) => None,
                ("edge", _) => Some("a Boolean variable"),
                _ => None,
            };
            if let Some(needs) = bad {
                found.push((op.clone(), crate::flat::type_name(ty), needs, *span));
            }
        });
        for (op, ty, needs, span) in found {
            self.diags.push(
                FlatError::OperatorType {
                    operator: op,
                    needs,
                    ty: ty.to_string(),
                    span,
                }
                .into(),
            );
        }
    }

    fn subscripts(&mut self, e: &Expr) {
        self.operators(e);
        let mut found = Vec::new();
        crate::flat::for_each_ref(e, &mut |r| {
            let n = r.parts.last().map_or(0, |p| p.subscripts.len());
            if r.global || n == 0 {
                return;
            }
            if let Some((dims, _)) = self.var(r) {
                if n > dims.len() {
                    found.push((crate::eval::var_key(r), n, dims.len(), r.span));
                }
            }
        });
        for (name, n, d, span) in found {
            self.diags.push(
                FlatError::TooManySubscripts {
                    name,
                    dims: d,
                    given: n,
                    span,
                }
                .into(),
            );
        }
    }

    fn sides(&mut self, lhs: &Expr, rhs: &Expr, span: Span) {
        self.subscripts(lhs);
        self.subscripts(rhs);
        let ((sa, ta), (sb, tb)) = (self.info(lhs), self.info(rhs));
        let differ = match (sa, sb, ta, tb) {
            (Some(a), Some(b), _, _) if a != b => Some(format!(
                "sizes: {} and {}",
                crate::flat::fmt_dims(&a),
                crate::flat::fmt_dims(&b)
            )),
            (_, _, Some(a), Some(b)) if a != b => {
                Some(format!("types: {} and {}", a.name(), b.name()))
            }
            _ => None,
        };
        if let Some(what) = differ {
            self.diags
                .push(FlatError::SidesDiffer { what, span }.into());
        }
    }

    fn equations(&mut self, eqs: &[Equation]) {
        for eq in eqs {
            match &eq.kind {
                EquationKind::Simple { lhs, rhs } => self.sides(lhs, rhs, eq.span),
                EquationKind::Call(c) => self.subscripts(c),
                EquationKind::Connect { .. } => {}
                EquationKind::If {
                    branches,
                    otherwise,
                } => {
                    for (c, body) in branches {
                        self.subscripts(c);
                        self.equations(body);
                    }
                    self.equations(otherwise);
                }
                EquationKind::When { branches } => {
                    for (c, body) in branches {
                        self.subscripts(c);
                        self.equations(body);
                    }
                }
                EquationKind::For { body, .. } => self.equations(body),
            }
        }
    }
}

/// Checks the flat model's equations and bindings (`E2017`, `E2018`).
pub fn check(model: &FlatModel) -> Vec<Diagnostic> {
    let mut c = Checker {
        all: &model.vars,
        vars: {
            let mut m = HashMap::with_capacity_and_hasher(model.vars.len(), Default::default());
            m.extend(
                model
                    .vars
                    .iter()
                    .enumerate()
                    .map(|(i, v)| (v.name.as_str(), i as u32)),
            );
            m
        },
        hint: std::cell::Cell::new(0),
        diags: Vec::new(),
        buf: Default::default(),
    };
    c.equations(&model.equations);
    c.equations(&model.initial_equations);
    for v in &model.vars {
        let Some(b) = &v.binding else {
            continue;
        };
        let lhs = Expr {
            kind: ExprKind::Ref(ComponentRef {
                global: false,
                parts: vec![RefPart {
                    name: Ident {
                        text: v.name.as_str().into(),
                        span: v.origin,
                    },
                    subscripts: Vec::new(),
                }],
                span: v.origin,
            }),
            span: v.origin,
        };
        // A scalar binding of an array variable applies to every element.
        if !v.dims.is_empty() && c.shape(b).is_some_and(|s| s.is_empty()) {
            continue;
        }
        c.sides(&lhs, b, b.span);
    }
    c.diags
}
