//! Lowering: the flat model's variables become scalars, its (array) expressions become
//! scalar expressions in the arena (arrays are scalarized here), user functions are
//! inlined, and `der`, `pre`, `edge`, `change` and the other operators get their
//! meaning.

use crate::dae::*;
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprArena, ExprId, Fn1, Fn2, Node, RelOp, ScalarId};
use crate::tensor::{self, Tensor};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use unimo_flat::flat::{FlatType, FlatVar, Variability};
use unimo_flat::functions::FlatFunction;
use unimo_flat::FlatModel;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// How deep user functions may call each other while being inlined.
pub(crate) const MAX_INLINE_DEPTH_PUB: usize = 32;

/// A name bound during lowering: a `for` iterator or a function's local.
#[derive(Clone, Debug)]
pub(crate) struct Local {
    pub name: String,
    pub value: Option<Tensor>,
    /// The record type of a function's record input, output or local: its value is
    /// the fields side by side (see `records.rs`).
    pub record: Option<String>,
    /// The value of a String input (`getInstanceName()`, a literal): Strings have no
    /// numeric value; only the functions unimo provides read them (a hash).
    pub text: Option<String>,
}

pub struct Lowerer<'m> {
    pub(crate) model: &'m FlatModel,
    pub(crate) dae: Dae,
    /// Flat variable name -> (first scalar, dims).
    pub(crate) vars: HashMap<String, (ScalarId, Vec<usize>)>,
    pub(crate) functions: HashMap<&'m str, &'m FlatFunction>,
    pub(crate) locals: Vec<Local>,
    /// Values of model variables assigned so far in the algorithm being lowered.
    pub(crate) assigned: Option<HashMap<ScalarId, ExprId>>,
    pub(crate) inline_depth: usize,
    /// Size of the dimension an `end` in a subscript refers to.
    pub(crate) end_stack: Vec<usize>,
    /// Actions collected while lowering the body of a `when`.
    pub(crate) when_actions: Option<Vec<(WhenAction, Span)>>,
    /// Values of parameters evaluated at compile time (NaN: not evaluable).
    pub(crate) parameter_values: HashMap<ScalarId, f64>,
    /// Parameters fixed at translation (see `fold.rs`): equations read their values
    /// as constants.
    pub(crate) evaluated: HashMap<ScalarId, ExprId>,
    pub(crate) errors: Vec<DaeError>,
    /// Conditional `return`/`break` exits of the algorithm being executed.
    pub(crate) exits: Vec<crate::algo::Exit>,
}

/// Parameter values for [`ExprArena::eval`].
struct ParameterEnv<'a>(&'a HashMap<ScalarId, f64>);

impl crate::expr::EvalEnv for ParameterEnv<'_> {
    fn value(&self, s: ScalarId) -> f64 {
        self.0.get(&s).copied().unwrap_or(f64::NAN)
    }
}

pub(crate) fn unsupported(what: impl Into<String>, span: Span) -> DaeError {
    DaeError::new("E3001", format!("not supported yet: {}", what.into()), span)
}

impl<'m> Lowerer<'m> {
    pub fn new(model: &'m FlatModel) -> Lowerer<'m> {
        Lowerer {
            model,
            dae: Dae {
                name: model.name.clone(),
                enumerations: model.enumerations.clone(),
                ..Dae::default()
            },
            vars: HashMap::default(),
            functions: model
                .functions
                .iter()
                .map(|f| (f.name.as_str(), f))
                .collect(),
            locals: Vec::new(),
            assigned: None,
            inline_depth: 0,
            end_stack: Vec::new(),
            when_actions: None,
            parameter_values: HashMap::default(),
            evaluated: HashMap::default(),
            errors: Vec::new(),
            exits: Vec::new(),
        }
    }

    /// The value of `e` when it is known at compile time: a constant, or an expression
    /// of parameters and constants whose bindings can be evaluated (structural
    /// parameters: sizes, ranges, indices, conditions of `if`-equations).
    /// The branch of an `if`-expression to lower alone: `Some` when its conditions
    /// are parameters known at compile time and lowering every branch fails (different
    /// sizes, or a value the back end does not have).
    fn structural_if<'e>(
        &mut self,
        branches: &'e [(Expr, Expr)],
        otherwise: &'e Expr,
    ) -> DaeResult<Option<&'e Expr>> {
        // Conditions known at compile time (parameters only, as for `if`-equations in
        // flattening): the branch taken, so that what the other branches hold never
        // reaches the structure (`y1 = if use_pder then der(y) else 0` with `use_pder`
        // false has no `der(y)`).
        for (c, v) in branches {
            let c = self.scalar(c)?;
            match self.const_value(c) {
                Some(x) if x != 0.0 => return Ok(Some(v)),
                Some(_) => continue,
                None => return Ok(None),
            }
        }
        Ok(Some(otherwise))
    }

    pub(crate) fn const_value(&mut self, e: ExprId) -> Option<f64> {
        if let Some(c) = self.dae.arena.as_const(e) {
            return Some(c);
        }
        if !self.parameters_only(e) {
            return None;
        }
        for s in self.dae.arena.vars(e) {
            self.parameter_value(s, 0)?;
        }
        let values = &self.parameter_values;
        let env = ParameterEnv(values);
        let v = self.dae.arena.eval(e, &env);
        v.is_finite().then_some(v)
    }

    /// A model variable in an expression: its value where it is fixed at translation.
    pub(crate) fn var_value(&mut self, s: ScalarId) -> ExprId {
        match self.evaluated.get(&s) {
            Some(&c) => c,
            None => self.dae.arena.var(s),
        }
    }

    /// Whether every leaf of `e` is a constant or a parameter (no time, `pre`, ...).
    fn parameters_only(&self, e: ExprId) -> bool {
        let mut stack = vec![e];
        let mut seen = HashSet::default();
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            match self.dae.arena.node(x) {
                Node::Const(_) => {}
                Node::Var(s) => {
                    if !matches!(
                        self.dae.scalar(s).kind,
                        ScalarKind::Parameter | ScalarKind::Constant
                    ) {
                        return false;
                    }
                }
                Node::Time
                | Node::Pre(_)
                | Node::Initial
                | Node::Terminal
                | Node::Sample(..)
                | Node::External(..) => return false,
                _ => stack.extend(self.dae.arena.children(x)),
            }
        }
        true
    }

    pub(crate) fn parameter_value(&mut self, s: ScalarId, depth: u32) -> Option<f64> {
        if let Some(v) = self.parameter_values.get(&s) {
            return v.is_finite().then_some(*v);
        }
        let sc = self.dae.scalar(s);
        let binding = if sc.fixed == Some(false) {
            None
        } else {
            sc.binding.or(sc.start)
        };
        let value = match binding {
            Some(b) if depth < 64 && self.parameters_only(b) => {
                let mut ok = true;
                for d in self.dae.arena.vars(b) {
                    ok &= self.parameter_value(d, depth + 1).is_some();
                }
                if ok {
                    self.dae
                        .arena
                        .eval(b, &ParameterEnv(&self.parameter_values))
                } else {
                    f64::NAN
                }
            }
            _ => f64::NAN,
        };
        self.parameter_values.insert(s, value);
        value.is_finite().then_some(value)
    }

    pub(crate) fn a(&mut self) -> &mut ExprArena {
        &mut self.dae.arena
    }

    // ------------------------------------------------------------ variables

    /// Creates the scalars of every flat variable (attributes come later, when all
    /// names are known).
    pub(crate) fn declare_vars(&mut self) {
        for v in &self.model.vars {
            let ty = match &v.ty {
                FlatType::Real => ScalarType::Real,
                FlatType::Integer => ScalarType::Integer,
                FlatType::Boolean => ScalarType::Boolean,
                FlatType::String => continue,
                // A handle: the index of its object in `Dae::external_objects`.
                FlatType::ExternalObject { .. } => ScalarType::Integer,
                FlatType::Enumeration { name, .. } => {
                    let k = self
                        .dae
                        .enumerations
                        .iter()
                        .position(|(n, _)| n == name)
                        .unwrap_or(0);
                    ScalarType::Enumeration(k as u32)
                }
            };
            let kind = match v.variability {
                Variability::Constant => ScalarKind::Constant,
                Variability::Parameter => ScalarKind::Parameter,
                Variability::Discrete => ScalarKind::Discrete,
                Variability::Continuous if ty == ScalarType::Real => ScalarKind::Continuous,
                Variability::Continuous => ScalarKind::Discrete,
            };
            let first = ScalarId(self.dae.scalars.len() as u32);
            // A flat model read back names its variables `'body.r'`: results use the
            // name inside the quotes, as for the original model.
            let display = match v.name.strip_prefix('\'').and_then(|n| n.strip_suffix('\'')) {
                Some(inner) if !inner.is_empty() => inner.replace("\\'", "'"),
                _ => v.name.clone(),
            };
            for idx in index_tuples(&v.dims) {
                let name = if idx.is_empty() {
                    display.clone()
                } else {
                    format!(
                        "{}[{}]",
                        display,
                        idx.iter()
                            .map(|i| i.to_string())
                            .collect::<Vec<_>>()
                            .join(",")
                    )
                };
                let mut s = Scalar::new(name, kind, ty, v.origin);
                s.description = v.description.clone();
                s.input = v.top_level
                    && v.causality == Some(Causality::Input)
                    && kind != ScalarKind::Parameter;
                self.dae.add_scalar(s);
            }
            self.vars.insert(v.name.clone(), (first, v.dims.clone()));
        }
    }

    /// Lowers bindings and attributes; bindings of non-parameters become equations.
    pub(crate) fn var_attributes(&mut self) {
        // A parameter binding that needs another parameter's value declared further
        // down (`x_start[nx] = zeros(nx)` before `nx = size(a, 1) - 1`) is tried again
        // once the others are known.
        let mut deferred = Vec::new();
        for v in &self.model.vars {
            let Some(&(first, ref dims)) = self.vars.get(&v.name) else {
                continue;
            };
            let dims = dims.clone();
            let n = dims.iter().product::<usize>();
            if let Err(e) = self.var_binding(v, first, &dims) {
                let parameter = matches!(
                    v.variability,
                    Variability::Parameter | Variability::Constant
                );
                if parameter && e.code == "E3002" {
                    deferred.push((v, first, dims.clone(), e));
                } else {
                    self.errors.push(e);
                }
            }
            self.attributes_of(v, first, &dims, n);
        }
        while !deferred.is_empty() {
            self.parameter_values.retain(|_, x| x.is_finite());
            let before = deferred.len();
            let mut still = Vec::new();
            for (v, first, dims, _) in deferred {
                if let Err(e) = self.var_binding(v, first, &dims) {
                    still.push((v, first, dims, e));
                }
            }
            deferred = still;
            if deferred.len() == before {
                self.errors.extend(deferred.drain(..).map(|(.., e)| e));
            }
        }
    }

    /// A variable's binding: a parameter's value, or an equation.
    fn var_binding(&mut self, v: &FlatVar, first: ScalarId, dims: &[usize]) -> DaeResult<()> {
        if let Some(b) = &v.binding {
            let t = self.expr(b).and_then(|t| broadcast(t, dims, b.span))?;
            let parameter = matches!(
                v.variability,
                Variability::Parameter | Variability::Constant
            );
            for (k, &e) in t.data.iter().enumerate() {
                let s = ScalarId(first.0 + k as u32);
                if parameter {
                    self.dae.scalars[s.index()].binding = Some(e);
                } else {
                    let lhs = self.dae.arena.var(s);
                    self.dae.equations.push(crate::dae::Equation {
                        lhs,
                        rhs: e,
                        origin: b.span,
                        derivative_of: None,
                    });
                }
            }
        }
        Ok(())
    }

    /// A variable's attributes (`start`, `fixed`, `nominal`, ...).
    fn attributes_of(&mut self, v: &FlatVar, first: ScalarId, dims: &[usize], n: usize) {
        {
            for (name, value) in &v.attributes {
                let which = name.as_str();
                if !matches!(
                    which,
                    "start" | "fixed" | "nominal" | "min" | "max" | "stateSelect"
                ) {
                    continue;
                }
                let t = match self
                    .expr(value)
                    .and_then(|t| broadcast(t, dims, value.span))
                {
                    Ok(t) => t,
                    Err(e) => {
                        self.errors.push(e);
                        continue;
                    }
                };
                for k in 0..n {
                    let e = t.data[k];
                    let c = self.const_value(e);
                    let s = &mut self.dae.scalars[first.index() + k];
                    match which {
                        "start" => s.start = Some(e),
                        "nominal" => s.nominal = Some(e),
                        "min" => s.min = Some(e),
                        "max" => s.max = Some(e),
                        "fixed" => s.fixed = c.map(|x| x != 0.0),
                        _ => {
                            s.state_select = match c.map(|x| x as i64) {
                                Some(1) => StateSelect::Never,
                                Some(2) => StateSelect::Avoid,
                                Some(4) => StateSelect::Prefer,
                                Some(5) => StateSelect::Always,
                                _ => StateSelect::Default,
                            }
                        }
                    }
                }
            }
        }
    }

    // ------------------------------------------------------------ references

    fn local(&self, name: &str) -> Option<&Local> {
        self.locals.iter().rev().find(|l| l.name == name)
    }

    /// The value of a reference.
    pub(crate) fn reference(&mut self, r: &ComponentRef) -> DaeResult<Tensor> {
        if r.global {
            return self.global_ref(r);
        }
        if r.parts.len() == 1 {
            let name = r.parts[0].name.text.as_str();
            if name == "time" {
                let t = self.a().time();
                return Ok(Tensor::scalar(t));
            }
            if let Some(l) = self.local(name) {
                if l.record.is_some() && !r.parts[0].subscripts.is_empty() {
                    return Err(unsupported("subscripts on a record", r.span));
                }
                let Some(v) = l.value.clone() else {
                    return Err(DaeError::new(
                        "E3012",
                        format!("`{name}` is used before it is assigned"),
                        r.span,
                    ));
                };
                return self.subscript(v, &r.parts[0].subscripts, r.span);
            }
        }
        // A field of a function's record variable (`a.re`).
        if r.parts.len() > 1 && !r.global {
            if let Some(l) = self.local(r.parts[0].name.text.as_str()) {
                if let (Some(ty), Some(v)) = (l.record.clone(), l.value.clone()) {
                    return self.record_field(ty, v, &r.parts[1..], r.span);
                }
            }
        }
        // Subscripts of an inner part (`p[i].x` in a loop) must be known here: they
        // select the component, hence the variable.
        let folded;
        let r = if r.parts[..r.parts.len().saturating_sub(1)]
            .iter()
            .any(|p| !p.subscripts.is_empty())
        {
            let mut c = r.clone();
            let n = c.parts.len();
            for part in &mut c.parts[..n - 1] {
                for sub in &mut part.subscripts {
                    if let Subscript::Expr(e) = sub {
                        if matches!(e.kind, ExprKind::Integer(_)) {
                            continue;
                        }
                        let k = self.constant_int(e)?;
                        *e = Expr {
                            kind: ExprKind::Integer(k),
                            span: e.span,
                        };
                    }
                }
            }
            folded = c;
            &folded
        } else {
            r
        };
        let key = unimo_flat::eval::var_key(r);
        let builtin_enum = r.parts.len() == 2
            && matches!(
                r.parts[0].name.text.as_str(),
                "StateSelect" | "AssertionLevel"
            );
        if builtin_enum && !self.vars.contains_key(&key) {
            return self.global_ref(r);
        }
        let Some((first, dims)) = self.vars.get(&key).cloned() else {
            // A whole record instance (`z`, `c[2]`).
            let mut instance = key.clone();
            if let Some(last) = r.parts.last() {
                instance.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
            }
            if let Some(t) = self.record_instance(&instance, r.span)? {
                return Ok(t);
            }
            return Err(DaeError::new(
                "E3010",
                format!("`{key}` is not a variable of the flat model"),
                r.span,
            )
            .help("string variables are not lowered"));
        };
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        // One element picked by constant indices: no need to build the whole array.
        if !subs.is_empty() && subs.len() == dims.len() {
            if let Some(k) = self.constant_position(&dims, &subs)? {
                let s = ScalarId(first.0 + k as u32);
                let e = match self.assigned.as_ref().and_then(|m| m.get(&s)) {
                    Some(&e) => e,
                    None => self.var_value(s),
                };
                return Ok(Tensor::scalar(e));
            }
        }
        let n: usize = dims.iter().product();
        let data = (0..n)
            .map(|k| {
                let s = ScalarId(first.0 + k as u32);
                match self.assigned.as_ref().and_then(|m| m.get(&s)) {
                    Some(&e) => e,
                    None => self.var_value(s),
                }
            })
            .collect();
        let t = Tensor { dims, data };
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        self.subscript(t, &subs, r.span)
    }

    /// The row-major position selected by scalar constant subscripts, if they are.
    fn constant_position(
        &mut self,
        dims: &[usize],
        subs: &[Subscript],
    ) -> DaeResult<Option<usize>> {
        let mut pos = 0usize;
        for (d, s) in dims.iter().zip(subs) {
            let Subscript::Expr(e) = s else {
                return Ok(None);
            };
            self.end_stack.push(*d);
            let t = self.expr(e);
            self.end_stack.pop();
            let t = t?;
            if !t.is_scalar() {
                return Ok(None);
            }
            let Some(k) = self.const_value(t.data[0]) else {
                return Ok(None);
            };
            let k = k as i64;
            if k < 1 || k as usize > *d {
                return Err(DaeError::new(
                    "E3013",
                    format!("index {k} is out of bounds 1..{d}"),
                    e.span,
                ));
            }
            pos = pos * d + (k as usize - 1);
        }
        Ok(Some(pos))
    }

    fn global_ref(&mut self, r: &ComponentRef) -> DaeResult<Tensor> {
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        if let Some((literal, ty)) = names.split_last() {
            let ty = ty.join(".");
            let lits: Option<Vec<String>> = match ty.as_str() {
                "StateSelect" => Some(
                    ["never", "avoid", "default", "prefer", "always"]
                        .map(String::from)
                        .to_vec(),
                ),
                "AssertionLevel" => Some(["error", "warning"].map(String::from).to_vec()),
                _ => self
                    .dae
                    .enumerations
                    .iter()
                    .find(|(n, _)| *n == ty)
                    .map(|(_, l)| l.clone()),
            };
            if let Some(k) = lits.and_then(|l| l.iter().position(|x| x == literal)) {
                let c = self.a().constant(k as f64 + 1.0);
                return Ok(Tensor::scalar(c));
            }
        }
        Err(DaeError::new(
            "E3010",
            format!(
                "`{}` is not a variable or enumeration literal",
                names.join(".")
            ),
            r.span,
        ))
    }

    /// Applies subscripts: scalar indices drop a dimension, `:` and vectors keep it.
    pub(crate) fn subscript(
        &mut self,
        t: Tensor,
        subs: &[Subscript],
        span: Span,
    ) -> DaeResult<Tensor> {
        if subs.is_empty() {
            return Ok(t);
        }
        if subs.len() > t.dims.len() {
            return Err(DaeError::new(
                "E3003",
                format!(
                    "{} subscripts on an array of size {}",
                    subs.len(),
                    tensor::fmt_dims(&t.dims)
                ),
                span,
            ));
        }
        let first_dim = t.dims[0];
        let rows = t.rows();
        let rest = &subs[1..];
        match &subs[0] {
            Subscript::Colon(_) => {
                let items = rows
                    .into_iter()
                    .map(|r| self.subscript(r, rest, span))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)
            }
            Subscript::Expr(e) => {
                self.end_stack.push(first_dim);
                let idx = self.expr(e);
                self.end_stack.pop();
                let idx = idx?;
                if idx.is_scalar() {
                    let row = self.pick(&rows, idx.data[0], first_dim, e.span)?;
                    self.subscript(row, rest, span)
                } else {
                    let mut items = Vec::new();
                    for &i in &idx.data {
                        let row = self.pick(&rows, i, first_dim, e.span)?;
                        items.push(self.subscript(row, rest, span)?);
                    }
                    Tensor::stack(items, span)
                }
            }
        }
    }

    /// Row `i` (1-based) of `rows`; a non-constant index picks with an `if` chain.
    fn pick(&mut self, rows: &[Tensor], i: ExprId, n: usize, span: Span) -> DaeResult<Tensor> {
        if let Some(k) = self.const_value(i) {
            let k = k as i64;
            if k < 1 || k as usize > n {
                return Err(DaeError::new(
                    "E3013",
                    format!("index {k} is out of bounds 1..{n}"),
                    span,
                ));
            }
            return Ok(rows[k as usize - 1].clone());
        }
        // x[i] with a discrete i: if i == 1 then x[1] elseif ... else x[n].
        let mut acc = rows[n - 1].clone();
        for k in (0..n - 1).rev() {
            let kc = self.a().constant(k as f64 + 1.0);
            let c = self.a().rel(RelOp::Eq, i, kc);
            let data = rows[k]
                .data
                .iter()
                .zip(&acc.data)
                .map(|(&x, &y)| self.dae.arena.if_(c, x, y))
                .collect();
            acc = Tensor {
                dims: acc.dims.clone(),
                data,
            };
        }
        Ok(acc)
    }

    // ------------------------------------------------------------ expressions

    pub(crate) fn scalar(&mut self, e: &Expr) -> DaeResult<ExprId> {
        self.expr(e)?.as_scalar(e.span)
    }

    /// A compile-time integer.
    pub(crate) fn constant_int(&mut self, e: &Expr) -> DaeResult<i64> {
        let x = self.scalar(e)?;
        match self.const_value(x) {
            Some(v) if v == v.trunc() => Ok(v as i64),
            _ => Err(
                DaeError::new("E3002", "a constant integer is needed here", e.span)
                    .help("sizes, indices and ranges must be known at compile time"),
            ),
        }
    }

    pub(crate) fn expr(&mut self, e: &Expr) -> DaeResult<Tensor> {
        let span = e.span;
        match &e.kind {
            ExprKind::Integer(i) => Ok(Tensor::scalar(self.a().constant(*i as f64))),
            ExprKind::Real(x) => Ok(Tensor::scalar(self.a().constant(*x))),
            ExprKind::Bool(b) => Ok(Tensor::scalar(self.a().boolean(*b))),
            ExprKind::String(_) => Err(unsupported("a String value in an expression", span)),
            ExprKind::Ref(r) => self.reference(r),
            ExprKind::End => match self.end_stack.last() {
                Some(&n) => Ok(Tensor::scalar(self.a().constant(n as f64))),
                None => Err(DaeError::new("E3003", "`end` outside a subscript", span)),
            },
            ExprKind::Call { func, args } => self.call(func, args, span),
            ExprKind::Unary { op, operand } => {
                let x = self.expr(operand)?;
                Ok(match op {
                    UnaryOp::Neg => x.map(|v| self.dae.arena.neg(v)),
                    UnaryOp::Plus => x,
                    UnaryOp::Not => x.map(|v| self.dae.arena.not(v)),
                })
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.expr(lhs)?;
                let b = self.expr(rhs)?;
                self.binary(*op, &a, &b, span)
            }
            ExprKind::If {
                branches,
                otherwise,
            } => {
                // A branch whose condition is known at compile time (parameters only):
                // the branch taken (branches of different sizes, values the back end does
                // not have such as Strings, and a `der` in a branch not taken never reach
                // the structure).
                if let Some(e) = self.structural_if(branches, otherwise)? {
                    return self.expr(e);
                }
                let mut acc = self.expr(otherwise)?;
                for (c, v) in branches.iter().rev() {
                    let c = self.scalar(c)?;
                    let v = self.expr(v)?;
                    if v.dims != acc.dims {
                        return Err(tensor::size_error(&v.dims, &acc.dims, span));
                    }
                    let data = v
                        .data
                        .iter()
                        .zip(&acc.data)
                        .map(|(&x, &y)| self.dae.arena.if_(c, x, y))
                        .collect();
                    acc = Tensor { dims: v.dims, data };
                }
                Ok(acc)
            }
            ExprKind::Range { start, step, stop } => {
                let values = self.range_values(start, step.as_deref(), stop)?;
                let data = values.into_iter().map(|x| self.a().constant(x)).collect();
                Ok(Tensor::vector(data))
            }
            ExprKind::Array(items) => {
                let items = items
                    .iter()
                    .map(|x| self.expr(x))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)
            }
            ExprKind::Matrix(rows) => {
                let mut row_tensors = Vec::new();
                for row in rows {
                    let items = row
                        .iter()
                        .map(|x| self.expr(x).map(as_matrix))
                        .collect::<DaeResult<Vec<_>>>()?;
                    row_tensors.push(tensor::concatenate(&items, 1, span)?);
                }
                tensor::concatenate(&row_tensors, 0, span)
            }
            ExprKind::Comprehension { body, indices } => {
                let items = self.comprehension(body, indices)?;
                Tensor::stack(items, span)
            }
            ExprKind::Tuple(items) if items.len() == 1 && items[0].is_some() => {
                self.expr(items[0].as_ref().expect("checked"))
            }
            ExprKind::Tuple(_) => Err(unsupported("a tuple outside a multiple assignment", span)),
            ExprKind::PartialApplication { .. } => Err(unsupported("functional arguments", span)),
        }
    }

    pub(crate) fn range_values(
        &mut self,
        start: &Expr,
        step: Option<&Expr>,
        stop: &Expr,
    ) -> DaeResult<Vec<f64>> {
        let c = |me: &mut Self, e: &Expr| -> DaeResult<f64> {
            let x = me.scalar(e)?;
            me.const_value(x).ok_or_else(|| {
                DaeError::new(
                    "E3002",
                    "a range bound must be known at compile time",
                    e.span,
                )
            })
        };
        let a = c(self, start)?;
        let h = match step {
            Some(s) => c(self, s)?,
            None => 1.0,
        };
        let b = c(self, stop)?;
        if h == 0.0 {
            return Err(DaeError::new("E3003", "a range step of zero", start.span));
        }
        let n = ((b - a) / h + 1e-10).floor();
        if n < 0.0 {
            return Ok(Vec::new());
        }
        if n > 1e7 {
            return Err(DaeError::new(
                "E3003",
                "a range with more than 1e7 elements",
                start.span,
            ));
        }
        Ok((0..=n as usize).map(|k| a + k as f64 * h).collect())
    }

    /// Evaluates `body` once per combination of the iterators (last one fastest).
    pub(crate) fn comprehension(
        &mut self,
        body: &Expr,
        indices: &[ForIndex],
    ) -> DaeResult<Vec<Tensor>> {
        let Some((first, rest)) = indices.split_first() else {
            return Ok(vec![self.expr(body)?]);
        };
        let values = self.iterator_values(first)?;
        let mut out = Vec::new();
        for v in values {
            self.locals.push(Local {
                name: first.name.text.to_string(),
                value: Some(v),
                record: None,
                text: None,
            });
            let r = self.comprehension(body, rest);
            self.locals.pop();
            out.extend(r?);
        }
        Ok(out)
    }

    pub(crate) fn iterator_values(&mut self, index: &ForIndex) -> DaeResult<Vec<Tensor>> {
        let Some(range) = &index.range else {
            return Err(unsupported(
                "a `for` iterator without a range",
                index.name.span,
            ));
        };
        let t = self.expr(range)?;
        Ok(t.rows())
    }

    pub(crate) fn binary(
        &mut self,
        op: BinaryOp,
        a: &Tensor,
        b: &Tensor,
        span: Span,
    ) -> DaeResult<Tensor> {
        let ar = &mut self.dae.arena;
        use BinaryOp::*;
        match op {
            Add | Sub if !a.is_scalar() || !b.is_scalar() => {
                let f = if op == Add {
                    ExprArena::add
                } else {
                    ExprArena::sub
                };
                tensor::elementwise(ar, a, b, false, span, f)
            }
            Add | ElemAdd => tensor::elementwise(ar, a, b, true, span, ExprArena::add),
            Sub | ElemSub => tensor::elementwise(ar, a, b, true, span, ExprArena::sub),
            Mul => tensor::multiply(ar, a, b, span),
            ElemMul => tensor::elementwise(ar, a, b, true, span, ExprArena::mul),
            Div | ElemDiv => {
                if op == Div && !b.is_scalar() {
                    return Err(DaeError::new("E3003", "division by an array", span));
                }
                tensor::elementwise(ar, a, b, true, span, ExprArena::div)
            }
            Pow | ElemPow => {
                if op == Pow && (!a.is_scalar() || !b.is_scalar()) {
                    return Err(unsupported("matrix powers", span));
                }
                tensor::elementwise(ar, a, b, true, span, ExprArena::pow)
            }
            And => tensor::elementwise(ar, a, b, true, span, ExprArena::and),
            Or => tensor::elementwise(ar, a, b, true, span, ExprArena::or),
            Lt | Le | Gt | Ge | Eq | Ne => {
                let rel = match op {
                    Lt => RelOp::Lt,
                    Le => RelOp::Le,
                    Gt => RelOp::Gt,
                    Ge => RelOp::Ge,
                    Eq => RelOp::Eq,
                    _ => RelOp::Ne,
                };
                let x = a.as_scalar(span)?;
                let y = b.as_scalar(span)?;
                Ok(Tensor::scalar(ar.rel(rel, x, y)))
            }
        }
    }

    /// The time derivative of a lowered expression: a continuous variable's derivative
    /// is its derivative scalar (made on demand); parameters and discrete variables
    /// have none.
    pub(crate) fn time_derivative(&mut self, e: ExprId) -> ExprId {
        crate::analysis::time_derivative(&mut self.dae, e)
    }

    // ------------------------------------------------------------ calls

    fn call(&mut self, func: &Name, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let name = func.to_dotted().trim_start_matches('.').to_owned();
        if func.global {
            if let Some(f) = self.functions.get(name.as_str()).copied() {
                let mut outs = self.inline_call(f, args, span)?;
                return Ok(outs.swap_remove(0));
            }
            if let Some(t) = self.constructor(&name, args, span)? {
                return Ok(t);
            }
            // Builtin functions reached by a global name (`Modelica.Math.sin` style
            // wrappers are user functions; these are enumerations' `Integer` etc.).
            let last = func
                .parts
                .last()
                .map(|p| p.text.to_string())
                .unwrap_or_default();
            return self.builtin(&last, args, span).and_then(|r| {
                r.ok_or_else(|| {
                    DaeError::new("E3004", format!("`{name}` is not a known function"), span)
                })
            });
        }
        if unimo_builtins::is_unsupported(&name) {
            return Err(unsupported(
                format!(
                    "the built-in `{name}` (stream connectors, clocked and synchronous features, \
                     state machines and overconstrained connections are not implemented)"
                ),
                span,
            ));
        }
        match self.builtin(&name, args, span)? {
            Some(t) => Ok(t),
            None => Err(DaeError::new(
                "E3004",
                format!("`{name}` is not a known function"),
                span,
            )),
        }
    }

    fn positional(&mut self, args: &CallArgs, k: usize, span: Span) -> DaeResult<Tensor> {
        match args.positional.get(k) {
            Some(e) => self.expr(e),
            None => Err(DaeError::new(
                "E3005",
                format!("argument {} is missing", k + 1),
                span,
            )),
        }
    }

    /// Builtin operators and functions; `Ok(None)` when `name` is not one.
    fn builtin(&mut self, name: &str, args: &CallArgs, span: Span) -> DaeResult<Option<Tensor>> {
        if !args.iterators.is_empty() {
            return self.reduction(name, args, span).map(Some);
        }
        let nargs = args.positional.len();
        if let Some(f) = Fn1::from_name(name) {
            let x = self.positional(args, 0, span)?;
            return Ok(Some(x.map(|v| self.dae.arena.fn1(f, v))));
        }
        // A two-argument compiled form: `atan2`, `div`, `mod`, `rem`, and `min`/`max`
        // of two arguments (one argument is their reduction).
        let fn2 = Fn2::from_name(name)
            .filter(|f| nargs == 2 || unimo_builtins::Arity::Fixed(2) == f.entry().arity);
        if let Some(f) = fn2 {
            let a = self.positional(args, 0, span)?;
            let b = self.positional(args, 1, span)?;
            let ar = &mut self.dae.arena;
            let t = tensor::elementwise(ar, &a, &b, true, span, |x, p, q| x.fn2(f, p, q))?;
            return Ok(Some(t));
        }
        let t = match name {
            "der" => {
                let x = self.positional(args, 0, span)?;
                x.map(|v| self.time_derivative(v))
            }
            "pre" => {
                let x = self.positional(args, 0, span)?;
                let mut data = Vec::new();
                for &v in &x.data {
                    match self.dae.arena.node(v) {
                        Node::Var(s) => data.push(self.dae.arena.pre(s)),
                        Node::Const(_) => data.push(v),
                        _ => return Err(DaeError::new("E3014", "`pre` needs a variable", span)),
                    }
                }
                Tensor { dims: x.dims, data }
            }
            "edge" | "change" => {
                let x = self.positional(args, 0, span)?;
                let mut data = Vec::new();
                for &v in &x.data {
                    let Node::Var(s) = self.dae.arena.node(v) else {
                        return Err(DaeError::new(
                            "E3014",
                            format!("`{name}` needs a variable"),
                            span,
                        ));
                    };
                    let p = self.dae.arena.pre(s);
                    data.push(if name == "edge" {
                        let np = self.dae.arena.not(p);
                        self.dae.arena.and(v, np)
                    } else {
                        self.dae.arena.rel(RelOp::Ne, v, p)
                    });
                }
                Tensor { dims: x.dims, data }
            }
            "initial" => Tensor::scalar(self.a().initial()),
            "collisionBody" => {
                // Every argument, flattened in order; the runtime reads them by position
                // (see `unimo_runtime::collision`).
                let mut flat = Vec::new();
                for e in &args.positional {
                    flat.extend(self.expr(e)?.data);
                }
                let Some(named) = crate::dae::CollisionBodyArgs::from_flat(&flat) else {
                    return Err(DaeError::new(
                        "E3019",
                        format!(
                            "`collisionBody` takes {} scalar arguments, got {}; use \
                             `Unimo.Collision.CollisionBody` instead of calling it directly",
                            crate::dae::COLLISION_BODY_ARGS,
                            flat.len()
                        ),
                        span,
                    ));
                };
                // The codes of the shape and the damping law (the library passes its
                // enumerations; a direct call may pass anything).
                use crate::collision_args::{LawCode, ShapeCode};
                let shape_ok = |x: f64| ShapeCode::from_value(x).is_some();
                let law_ok = |x: f64| LawCode::from_value(x).is_some();
                let checks = [
                    (
                        named.shape,
                        "shape",
                        ShapeCode::ALL.len(),
                        &shape_ok as &dyn Fn(f64) -> bool,
                    ),
                    (named.law, "damping law", LawCode::ALL.len(), &law_ok),
                ];
                for (arg, what, count, valid) in checks {
                    if let Some(code) = self.const_value(arg) {
                        if !valid(code) {
                            return Err(DaeError::new(
                                "E3019",
                                format!(
                                    "`collisionBody`: {code} is not a {what} code (1..{count}); \
                                     use `Unimo.Collision.CollisionBody`, whose enumerations \
                                     give valid codes"
                                ),
                                span,
                            ));
                        }
                    }
                }
                let site = self.dae.collision.len() as u32;
                self.dae
                    .collision
                    .push(crate::dae::CollisionBody { args: named, span });
                let data = (0..6).map(|k| self.dae.arena.external(site, k)).collect();
                Tensor {
                    dims: vec![6],
                    data,
                }
            }
            "collisionGaps" => {
                let mut flat = Vec::new();
                for e in &args.positional {
                    flat.extend(self.expr(e)?.data);
                }
                let named = crate::dae::CollisionWorldArgs::from_flat(&flat);
                let Some(named) = named.filter(|_| self.dae.collision_world.is_none()) else {
                    return Err(DaeError::new(
                        "E3019",
                        format!(
                            "`collisionGaps` takes {} scalar arguments and appears once per model; \
                             use one `Unimo.Collision.CollisionWorld`",
                            crate::dae::COLLISION_WORLD_ARGS
                        ),
                        span,
                    ));
                };
                self.dae.collision_world = Some(crate::dae::CollisionWorld { args: named, span });
                let g = crate::dae::COLLISION_GAPS_SITE;
                let data = (0..2).map(|k| self.dae.arena.external(g, k)).collect();
                Tensor {
                    dims: vec![2],
                    data,
                }
            }
            "terminal" => {
                self.dae.uses_terminal = true;
                Tensor::scalar(self.a().terminal())
            }
            "noEvent" => {
                let x = self.positional(args, 0, span)?;
                x.map(|v| self.dae.arena.no_event(v))
            }
            "smooth" => self.positional(args, 1, span)?,
            "homotopy" => match args.named.iter().find(|a| a.name.text == "actual") {
                Some(a) => self.expr(&a.value)?,
                None => self.positional(args, 0, span)?,
            },
            "sample" => {
                let a = self.positional(args, 0, span)?.as_scalar(span)?;
                let b = self.positional(args, 1, span)?.as_scalar(span)?;
                Tensor::scalar(self.a().sample(a, b))
            }
            "semiLinear" => {
                let x = self.positional(args, 0, span)?.as_scalar(span)?;
                let p = self.positional(args, 1, span)?.as_scalar(span)?;
                let n = self.positional(args, 2, span)?.as_scalar(span)?;
                let ar = self.a();
                let zero = ar.zero();
                let c = ar.rel(RelOp::Ge, x, zero);
                let px = ar.mul(p, x);
                let nx = ar.mul(n, x);
                Tensor::scalar(ar.if_(c, px, nx))
            }
            "Integer" | "Real" | "integer_of_enum" => self.positional(args, 0, span)?,
            "abs_" => return Ok(None),
            _ => return self.array_builtin(name, args, span),
        };
        Ok(Some(t))
    }

    /// `sum(e for i in r)` and friends.
    fn reduction(&mut self, name: &str, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let body = args
            .positional
            .first()
            .ok_or_else(|| DaeError::new("E3005", "a reduction needs an expression", span))?;
        let items = self.comprehension(body, &args.iterators)?;
        let stacked = Tensor::stack(items, span)?;
        match name {
            "sum" | "product" | "min" | "max" => self.reduce(name, &stacked, span),
            "array" => Ok(stacked),
            _ => Err(unsupported(format!("`{name}(... for ...)`"), span)),
        }
    }

    fn reduce(&mut self, name: &str, t: &Tensor, span: Span) -> DaeResult<Tensor> {
        let ar = &mut self.dae.arena;
        let r = match name {
            "sum" => t.data.iter().fold(ar.zero(), |acc, &x| ar.add(acc, x)),
            "product" => t.data.iter().fold(ar.one(), |acc, &x| ar.mul(acc, x)),
            "min" | "max" => {
                let f = Fn2::from_name(name).expect("min and max have a compiled form");
                let Some((&first, rest)) = t.data.split_first() else {
                    return Err(DaeError::new(
                        "E3003",
                        format!("`{name}` of an empty array"),
                        span,
                    ));
                };
                rest.iter().fold(first, |acc, &x| ar.fn2(f, acc, x))
            }
            _ => unreachable!("reduce is called for sum, product, min and max"),
        };
        Ok(Tensor::scalar(r))
    }

    fn dims_args(&mut self, args: &CallArgs, from: usize) -> DaeResult<Vec<usize>> {
        let mut dims = Vec::new();
        for e in &args.positional[from.min(args.positional.len())..] {
            let n = self.constant_int(e)?;
            dims.push(n.max(0) as usize);
        }
        Ok(dims)
    }

    fn array_builtin(
        &mut self,
        name: &str,
        args: &CallArgs,
        span: Span,
    ) -> DaeResult<Option<Tensor>> {
        let t = match name {
            "sum" | "product" | "min" | "max" => {
                let x = self.positional(args, 0, span)?;
                self.reduce(name, &x, span)?
            }
            "size" => {
                let x = self.positional(args, 0, span)?;
                if args.positional.len() > 1 {
                    let k = self.constant_int(&args.positional[1])?;
                    let n = x
                        .dims
                        .get((k - 1).max(0) as usize)
                        .copied()
                        .ok_or_else(|| {
                            DaeError::new("E3003", format!("dimension {k} does not exist"), span)
                        })?;
                    Tensor::scalar(self.a().constant(n as f64))
                } else {
                    let data = x
                        .dims
                        .iter()
                        .map(|&n| self.dae.arena.constant(n as f64))
                        .collect();
                    Tensor::vector(data)
                }
            }
            "ndims" => {
                let x = self.positional(args, 0, span)?;
                Tensor::scalar(self.a().constant(x.dims.len() as f64))
            }
            "transpose" => {
                let x = self.positional(args, 0, span)?;
                tensor::transpose(&x, span)?
            }
            "zeros" | "ones" => {
                let dims = self.dims_args(args, 0)?;
                let v = self.a().constant(if name == "ones" { 1.0 } else { 0.0 });
                Tensor {
                    data: vec![v; dims.iter().product()],
                    dims,
                }
            }
            "fill" => {
                let x = self.positional(args, 0, span)?;
                let dims = self.dims_args(args, 1)?;
                let n: usize = dims.iter().product();
                let mut all = dims.clone();
                all.extend(&x.dims);
                let data = (0..n).flat_map(|_| x.data.iter().copied()).collect();
                Tensor { dims: all, data }
            }
            "identity" => {
                let n = self.constant_int(&args.positional[0])?.max(0) as usize;
                let (z, o) = (self.a().zero(), self.a().one());
                let data = (0..n * n)
                    .map(|k| if k / n == k % n { o } else { z })
                    .collect();
                Tensor {
                    dims: vec![n, n],
                    data,
                }
            }
            "diagonal" => {
                let x = self.positional(args, 0, span)?;
                let n = x.data.len();
                let z = self.a().zero();
                let data = (0..n * n)
                    .map(|k| if k / n == k % n { x.data[k / n] } else { z })
                    .collect();
                Tensor {
                    dims: vec![n, n],
                    data,
                }
            }
            "cross" => {
                let x = self.positional(args, 0, span)?;
                let y = self.positional(args, 1, span)?;
                if x.dims != [3] || y.dims != [3] {
                    return Err(tensor::size_error(&x.dims, &y.dims, span));
                }
                let ar = self.a();
                let c = |ar: &mut ExprArena, i: usize, j: usize| {
                    let p = ar.mul(x.data[i], y.data[j]);
                    let q = ar.mul(x.data[j], y.data[i]);
                    ar.sub(p, q)
                };
                let data = vec![c(ar, 1, 2), c(ar, 2, 0), c(ar, 0, 1)];
                Tensor::vector(data)
            }
            "skew" => {
                let x = self.positional(args, 0, span)?;
                if x.dims != [3] {
                    return Err(tensor::size_error(&x.dims, &[3], span));
                }
                let ar = self.a();
                let z = ar.zero();
                let n = |ar: &mut ExprArena, k: usize| ar.neg(x.data[k]);
                let data = vec![
                    z,
                    n(ar, 2),
                    x.data[1],
                    x.data[2],
                    z,
                    n(ar, 0),
                    n(ar, 1),
                    x.data[0],
                    z,
                ];
                Tensor {
                    dims: vec![3, 3],
                    data,
                }
            }
            "outerProduct" => {
                let x = self.positional(args, 0, span)?;
                let y = self.positional(args, 1, span)?;
                let mut data = Vec::new();
                for &a in &x.data {
                    for &b in &y.data {
                        data.push(self.dae.arena.mul(a, b));
                    }
                }
                Tensor {
                    dims: vec![x.data.len(), y.data.len()],
                    data,
                }
            }
            "linspace" => {
                let a = self.positional(args, 0, span)?.as_scalar(span)?;
                let b = self.positional(args, 1, span)?.as_scalar(span)?;
                let n = self.constant_int(&args.positional[2])?.max(0) as usize;
                let mut data = Vec::new();
                for k in 0..n {
                    let f = if n > 1 {
                        k as f64 / (n - 1) as f64
                    } else {
                        0.0
                    };
                    let ar = self.a();
                    let fc = ar.constant(f);
                    let d = ar.sub(b, a);
                    let m = ar.mul(fc, d);
                    data.push(ar.add(a, m));
                }
                Tensor::vector(data)
            }
            "scalar" => {
                let x = self.positional(args, 0, span)?;
                Tensor::scalar(x.as_scalar(span)?)
            }
            // `array(a, b, c)` is `{a, b, c}` (spec 10.4).
            "array" => {
                let items = args
                    .positional
                    .iter()
                    .map(|a| self.expr(a))
                    .collect::<DaeResult<Vec<_>>>()?;
                Tensor::stack(items, span)?
            }
            "vector" => {
                let x = self.positional(args, 0, span)?;
                Tensor::vector(x.data)
            }
            "matrix" => {
                let x = self.positional(args, 0, span)?;
                as_matrix(x)
            }
            "cat" => {
                let k = self.constant_int(&args.positional[0])?;
                let items = args.positional[1..]
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<DaeResult<Vec<_>>>()?;
                tensor::concatenate(&items, (k - 1).max(0) as usize, span)?
            }
            "String" => return Err(unsupported("`String` outside an assert message", span)),
            "delay" | "spatialDistribution" | "cardinality" | "getInstanceName" => {
                return Err(unsupported(format!("`{name}`"), span))
            }
            _ => return Ok(None),
        };
        Ok(Some(t))
    }
}

/// A tensor as a matrix: scalars become 1x1, vectors columns.
fn as_matrix(t: Tensor) -> Tensor {
    match t.dims.len() {
        0 => Tensor {
            dims: vec![1, 1],
            data: t.data,
        },
        1 => Tensor {
            dims: vec![t.dims[0], 1],
            data: t.data,
        },
        _ => t,
    }
}

/// `t` as an array of size `dims`: a scalar is repeated (`each`, or a scalar
/// attribute of an array).
pub(crate) fn broadcast(t: Tensor, dims: &[usize], span: Span) -> DaeResult<Tensor> {
    if t.dims == dims {
        return Ok(t);
    }
    let n: usize = dims.iter().product();
    if t.data.len() == 1 {
        return Ok(Tensor {
            dims: dims.to_vec(),
            data: vec![t.data[0]; n],
        });
    }
    if t.data.len() == n {
        return Ok(Tensor {
            dims: dims.to_vec(),
            data: t.data,
        });
    }
    Err(tensor::size_error(dims, &t.dims, span))
}

/// Every index tuple of an array of size `dims` in row-major order (1-based).
pub(crate) fn index_tuples(dims: &[usize]) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    for &d in dims {
        out = out
            .into_iter()
            .flat_map(|t| {
                (1..=d).map(move |i| {
                    let mut t = t.clone();
                    t.push(i);
                    t
                })
            })
            .collect();
    }
    out
}
