//! Compile-time evaluation of flat expressions: parameters and constants for array
//! sizes, `for` ranges, conditions of conditional components and structural `if`s.

use unimo_source::Span;
use unimo_syntax::ast::{BinaryOp, ComponentRef, Expr, ExprKind, Subscript, UnaryOp};

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Bool(bool),
    Str(String),
    /// An enumeration literal: its 1-based index and its full name.
    Enum(i64, String),
    Array(Vec<Value>),
    /// A record value: its class's full name and its fields in declaration order
    /// (a field that is a record is a `Record` itself).
    Record(String, Vec<(String, Value)>),
}

/// The evaluated arguments of a call of a user function or record constructor.
#[derive(Clone, Debug)]
pub struct Arguments {
    pub positional: Vec<Value>,
    pub named: Vec<(String, Value)>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum EvalError {
    /// The expression depends on something that is not a known constant or parameter.
    NotConstant { span: Span, what: String },
    /// A construct the evaluator does not handle (yet).
    Unsupported { span: Span, what: String },
    /// A parameter whose value depends on itself.
    Cycle { span: Span, name: String },
}

/// Values of variables, by flat name (the reference without its last subscripts).
pub trait Env {
    fn var(&mut self, key: &str, span: Span) -> Result<Value, EvalError>;

    /// The declared sizes of the variable `key` (`size(x, 2)` of a continuous `x` is
    /// known at compile time although its value is not); `None` when unknown.
    fn dims(&mut self, _key: &str) -> Option<Vec<usize>> {
        None
    }

    /// Calls the user function `name` (full name) on evaluated arguments.
    fn call(&mut self, name: &str, _args: Arguments, span: Span) -> Result<Value, EvalError> {
        Err(EvalError::NotConstant {
            span,
            what: format!("a call of `{name}`"),
        })
    }
}

impl Value {
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Int(i) => Some(*i as f64),
            Value::Real(r) => Some(*r),
            Value::Enum(i, _) => Some(*i as f64),
            _ => None,
        }
    }

    pub fn as_int(&self) -> Option<i64> {
        match self {
            Value::Int(i) | Value::Enum(i, _) => Some(*i),
            Value::Real(r) if r.fract() == 0.0 && r.abs() < 9.0e15 => Some(*r as i64),
            _ => None,
        }
    }

    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }

    /// Sizes along each dimension of a (rectangular) array value.
    pub fn dims(&self) -> Vec<usize> {
        match self {
            Value::Array(items) => {
                let mut d = vec![items.len()];
                if let Some(first) = items.first() {
                    d.extend(first.dims());
                }
                d
            }
            _ => Vec::new(),
        }
    }

    /// The value as a literal expression.
    pub fn to_expr(&self, span: Span) -> Expr {
        let kind = match self {
            Value::Int(i) => ExprKind::Integer(*i),
            Value::Real(r) => ExprKind::Real(*r),
            Value::Bool(b) => ExprKind::Bool(*b),
            Value::Str(s) => ExprKind::String(s.clone()),
            Value::Enum(_, name) => ExprKind::Ref(ComponentRef {
                global: false,
                parts: crate::flat::split_name(name)
                    .into_iter()
                    .map(|p| unimo_syntax::ast::RefPart {
                        name: unimo_syntax::ast::Ident {
                            text: p.into(),
                            span,
                        },
                        subscripts: Vec::new(),
                    })
                    .collect(),
                span,
            }),
            Value::Array(items) => ExprKind::Array(items.iter().map(|v| v.to_expr(span)).collect()),
            // The record constructor with every field named.
            Value::Record(class, fields) => ExprKind::Call {
                func: unimo_syntax::ast::Name {
                    global: true,
                    parts: crate::flat::split_name(class)
                        .into_iter()
                        .map(|p| unimo_syntax::ast::Ident {
                            text: p.into(),
                            span,
                        })
                        .collect(),
                    span,
                },
                args: Box::new(unimo_syntax::ast::CallArgs {
                    positional: Vec::new(),
                    named: fields
                        .iter()
                        .map(|(n, v)| unimo_syntax::ast::NamedArg {
                            name: unimo_syntax::ast::Ident {
                                text: n.as_str().into(),
                                span,
                            },
                            value: v.to_expr(span),
                        })
                        .collect(),
                    iterators: Vec::new(),
                    span,
                }),
            },
        };
        Expr { kind, span }
    }
}

/// The key of a flat reference: all parts with their subscripts, but the last part's.
pub fn var_key(r: &ComponentRef) -> String {
    var_key_parts(&r.parts)
}

/// [`var_key`] of a path given as its parts.
pub fn var_key_parts(parts: &[unimo_syntax::ast::RefPart]) -> String {
    let mut s = String::with_capacity(parts.len() * 8);
    var_key_into(&mut s, parts);
    s
}

/// [`var_key`] written into `s` (cleared first): no allocation once `s` has grown.
pub fn var_key_into(s: &mut String, parts: &[unimo_syntax::ast::RefPart]) {
    s.clear();
    for (i, p) in parts.iter().enumerate() {
        if i > 0 {
            s.push('.');
        }
        s.push_str(&p.name.text);
        if i + 1 < parts.len() && !p.subscripts.is_empty() {
            s.push_str(&unimo_syntax::print::subscripts(&p.subscripts));
        }
    }
}

fn unsupported(e: &Expr, what: &str) -> EvalError {
    EvalError::Unsupported {
        span: e.span,
        what: what.to_owned(),
    }
}

fn num(e: &Expr, v: &Value) -> Result<f64, EvalError> {
    v.as_f64()
        .ok_or_else(|| unsupported(e, "a number is needed here"))
}

/// Evaluates `e`; `iterators` are the values of enclosing `for` indices.
pub fn eval(
    e: &Expr,
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    match &e.kind {
        ExprKind::Integer(i) => Ok(Value::Int(*i)),
        ExprKind::Real(r) => Ok(Value::Real(*r)),
        ExprKind::Bool(b) => Ok(Value::Bool(*b)),
        ExprKind::String(s) => Ok(Value::Str(s.clone())),
        ExprKind::Ref(r) => reference(e, r, env, iterators),
        ExprKind::Unary { op, operand } => {
            let v = eval(operand, env, iterators)?;
            match op {
                UnaryOp::Not => Ok(Value::Bool(
                    !v.as_bool()
                        .ok_or_else(|| unsupported(e, "`not` needs a Boolean"))?,
                )),
                UnaryOp::Plus => Ok(v),
                UnaryOp::Neg => map_num(e, &v, &|x| -x),
            }
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let a = eval(lhs, env, iterators)?;
            let b = eval(rhs, env, iterators)?;
            binary(e, *op, &a, &b)
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                let cv = eval(c, env, iterators)?;
                if cv
                    .as_bool()
                    .ok_or_else(|| unsupported(c, "a condition must be Boolean"))?
                {
                    return eval(v, env, iterators);
                }
            }
            eval(otherwise, env, iterators)
        }
        ExprKind::Range { start, step, stop } => {
            let a = eval(start, env, iterators)?;
            let b = eval(stop, env, iterators)?;
            let s = match step {
                Some(s) => Some(eval(s, env, iterators)?),
                None => None,
            };
            range(e, &a, s.as_ref(), &b)
        }
        ExprKind::Array(items) => Ok(Value::Array(
            items
                .iter()
                .map(|i| eval(i, env, iterators))
                .collect::<Result<_, _>>()?,
        )),
        ExprKind::Matrix(rows) => matrix(e, rows, env, iterators),
        ExprKind::Comprehension { body, indices } => comprehension(body, indices, env, iterators),
        ExprKind::Call { func, args } => call(e, func, args, env, iterators),
        _ => Err(unsupported(e, "this expression")),
    }
}

/// The value of a reference `e`: a `for` index's or a variable's, subscripted.
fn reference(
    e: &Expr,
    r: &ComponentRef,
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    if r.parts.len() == 1 {
        let n = r.parts[0].name.text.as_str();
        if let Some((_, v)) = iterators.iter().rev().find(|(k, _)| k == n) {
            let v = v.clone();
            return index(e, v, &r.parts[0].subscripts, env, iterators);
        }
        if n == "time" {
            return Err(EvalError::NotConstant {
                span: e.span,
                what: "time".into(),
            });
        }
    }
    let v = env.var(&var_key(r), e.span)?;
    let subs = &r
        .parts
        .last()
        .map(|p| p.subscripts.clone())
        .unwrap_or_default();
    index(e, v, subs, env, iterators)
}

/// `[a, b; c, d]`: each row concatenated along columns, the rows along rows; a scalar
/// is a 1x1 matrix and a vector a column (spec 10.4.2).
fn matrix(
    e: &Expr,
    rows: &[Vec<Expr>],
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    let mut out: Vec<Vec<Value>> = Vec::new();
    for r in rows {
        let mut block: Vec<Vec<Value>> = Vec::new();
        for item in r {
            let m = as_matrix(eval(item, env, iterators)?);
            if block.is_empty() {
                block = m;
            } else if block.len() == m.len() {
                for (row, more) in block.iter_mut().zip(m) {
                    row.extend(more);
                }
            } else {
                return Err(unsupported(
                    item,
                    "a matrix row of parts with different numbers of rows",
                ));
            }
        }
        if let (Some(first), Some(new)) = (out.first(), block.first()) {
            if first.len() != new.len() {
                return Err(unsupported(e, "matrix rows of different lengths"));
            }
        }
        out.extend(block);
    }
    Ok(Value::Array(out.into_iter().map(Value::Array).collect()))
}

/// `size(a, k)` (or `size(a)` without `k`) of an array of sizes `d`.
fn size_of(e: &Expr, d: Vec<usize>, k: Option<&Value>) -> Result<Value, EvalError> {
    match k {
        Some(k) => {
            let k = k
                .as_int()
                .ok_or_else(|| unsupported(e, "size(a, k) needs an Integer k"))?;
            d.get((k - 1).max(0) as usize)
                .map(|n| Value::Int(*n as i64))
                .ok_or_else(|| unsupported(e, "size of a missing dimension"))
        }
        None => Ok(Value::Array(
            d.into_iter().map(|n| Value::Int(n as i64)).collect(),
        )),
    }
}

/// A value as the rows of a matrix: a scalar is 1x1, a vector a column.
fn as_matrix(v: Value) -> Vec<Vec<Value>> {
    match v {
        Value::Array(items)
            if items.iter().all(|i| matches!(i, Value::Array(_))) && !items.is_empty() =>
        {
            items
                .into_iter()
                .map(|r| match r {
                    Value::Array(r) => r,
                    other => vec![other],
                })
                .collect()
        }
        Value::Array(items) => items.into_iter().map(|x| vec![x]).collect(),
        other => vec![vec![other]],
    }
}

fn comprehension(
    body: &Expr,
    indices: &[unimo_syntax::ast::ForIndex],
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    let Some((first, rest)) = indices.split_first() else {
        return eval(body, env, iterators);
    };
    let range = match &first.range {
        Some(r) => eval(r, env, iterators)?,
        None => return Err(unsupported(body, "an iterator without a range")),
    };
    let Value::Array(items) = range else {
        return Err(unsupported(body, "an iterator range must be an array"));
    };
    let mut out = Vec::with_capacity(items.len());
    for v in items {
        iterators.push((first.name.text.to_string(), v));
        let r = comprehension(body, rest, env, iterators);
        iterators.pop();
        out.push(r?);
    }
    Ok(Value::Array(out))
}

fn index(
    e: &Expr,
    mut v: Value,
    subs: &[Subscript],
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    for (k, s) in subs.iter().enumerate() {
        match s {
            Subscript::Colon(_) => {
                if k + 1 != subs.len() {
                    return Err(unsupported(e, "a slice before another subscript"));
                }
            }
            Subscript::Expr(ix) => {
                let i = eval(ix, env, iterators)?
                    .as_int()
                    .ok_or_else(|| unsupported(ix, "an array index must be an Integer"))?;
                let Value::Array(items) = v else {
                    return Err(unsupported(e, "a subscript on a scalar"));
                };
                v = items
                    .get((i - 1).max(0) as usize)
                    .filter(|_| i >= 1)
                    .cloned()
                    .ok_or_else(|| {
                        unsupported(
                            ix,
                            &format!("index {i} is out of bounds 1..{}", items.len()),
                        )
                    })?;
            }
        }
    }
    Ok(v)
}

fn map_num(e: &Expr, v: &Value, f: &dyn Fn(f64) -> f64) -> Result<Value, EvalError> {
    match v {
        Value::Int(i) => {
            let r = f(*i as f64);
            Ok(if r.fract() == 0.0 && r.abs() < 9.0e15 {
                Value::Int(r as i64)
            } else {
                Value::Real(r)
            })
        }
        Value::Real(r) => Ok(Value::Real(f(*r))),
        Value::Array(items) => Ok(Value::Array(
            items
                .iter()
                .map(|i| map_num(e, i, f))
                .collect::<Result<_, _>>()?,
        )),
        _ => Err(unsupported(e, "a number is needed here")),
    }
}

fn binary(e: &Expr, op: BinaryOp, a: &Value, b: &Value) -> Result<Value, EvalError> {
    use BinaryOp::*;
    // Element-wise over arrays (and scalar with array).
    match (a, b) {
        (Value::Array(x), Value::Array(y))
            if matches!(
                op,
                Add | Sub | ElemAdd | ElemSub | ElemMul | ElemDiv | ElemPow
            ) =>
        {
            if x.len() != y.len() {
                return Err(unsupported(e, "arrays of different sizes"));
            }
            return Ok(Value::Array(
                x.iter()
                    .zip(y)
                    .map(|(p, q)| binary(e, op, p, q))
                    .collect::<Result<_, _>>()?,
            ));
        }
        (Value::Array(x), Value::Array(y)) if op == Mul => {
            if x.iter().chain(y).any(|v| matches!(v, Value::Array(_))) {
                return matrix_product(e, a, b);
            }
            if x.len() != y.len() {
                return Err(unsupported(
                    e,
                    "a scalar product of vectors of different sizes",
                ));
            }
            let mut acc = 0.0;
            for (p, q) in x.iter().zip(y) {
                acc += num(e, p)? * num(e, q)?;
            }
            return Ok(Value::Real(acc));
        }
        (Value::Array(x), s) if !matches!(s, Value::Array(_)) => {
            return Ok(Value::Array(
                x.iter()
                    .map(|p| binary(e, op, p, s))
                    .collect::<Result<_, _>>()?,
            ));
        }
        (s, Value::Array(y))
            if !matches!(s, Value::Array(_))
                && matches!(op, Mul | ElemMul | Add | Sub | ElemAdd | ElemSub) =>
        {
            return Ok(Value::Array(
                y.iter()
                    .map(|q| binary(e, op, s, q))
                    .collect::<Result<_, _>>()?,
            ));
        }
        _ => {}
    }
    match op {
        And | Or => {
            let (x, y) = (a.as_bool(), b.as_bool());
            match (x, y) {
                (Some(x), Some(y)) => Ok(Value::Bool(if op == And { x && y } else { x || y })),
                _ => Err(unsupported(e, "`and`/`or` need Booleans")),
            }
        }
        Rel(relation) => {
            let ord = match (a, b) {
                (Value::Str(x), Value::Str(y)) => x.cmp(y) as i32 as f64,
                (Value::Bool(x), Value::Bool(y)) => (*x as i32 - *y as i32) as f64,
                _ => num(e, a)? - num(e, b)?,
            };
            Ok(Value::Bool(relation.apply(ord, 0.0)))
        }
        Add | ElemAdd if matches!((a, b), (Value::Str(_), Value::Str(_))) => match (a, b) {
            (Value::Str(x), Value::Str(y)) => Ok(Value::Str(format!("{x}{y}"))),
            _ => unreachable!(),
        },
        _ => {
            let ints = matches!((a, b), (Value::Int(_), Value::Int(_)));
            let (x, y) = (num(e, a)?, num(e, b)?);
            let r = match op {
                Add | ElemAdd => x + y,
                Sub | ElemSub => x - y,
                Mul | ElemMul => x * y,
                Div | ElemDiv => return Ok(Value::Real(x / y)),
                _ => return Ok(Value::Real(x.powf(y))),
            };
            Ok(if ints {
                Value::Int(r as i64)
            } else {
                Value::Real(r)
            })
        }
    }
}

/// The vector and matrix built-ins (`transpose`, `outerProduct`, `skew`, `cross`, `identity`,
/// spec 10.3.6); `None` when `name` is none of them.
fn matrix_builtin(e: &Expr, name: &str, vals: &[Value]) -> Result<Option<Value>, EvalError> {
    let arg = |k: usize| {
        vals.get(k)
            .ok_or_else(|| unsupported(e, "missing argument"))
    };
    let v = match name {
        "transpose" => transpose(e, arg(0)?),
        "outerProduct" => {
            let (x, y) = (arg(0)?, arg(1)?);
            let column = Value::Array(vec![x.clone()]);
            matrix_product(e, &transpose(e, &column)?, &Value::Array(vec![y.clone()]))
        }
        "skew" => {
            let c = |k: usize| match arg(0)? {
                Value::Array(items) if items.len() == 3 => num(e, &items[k]),
                _ => Err(unsupported(e, "skew() needs a 3-vector")),
            };
            let (x, y, z) = (c(0)?, c(1)?, c(2)?);
            let row = |a: f64, b: f64, c: f64| {
                Value::Array(vec![Value::Real(a), Value::Real(b), Value::Real(c)])
            };
            Ok(Value::Array(vec![
                row(0.0, -z, y),
                row(z, 0.0, -x),
                row(-y, x, 0.0),
            ]))
        }
        "cross" => {
            let (x, y) = (arg(0)?, arg(1)?);
            let c = |v: &Value, k: usize| match v {
                Value::Array(items) if items.len() == 3 => num(e, &items[k]),
                _ => Err(unsupported(e, "cross() needs two 3-vectors")),
            };
            Ok(Value::Array(vec![
                Value::Real(c(x, 1)? * c(y, 2)? - c(x, 2)? * c(y, 1)?),
                Value::Real(c(x, 2)? * c(y, 0)? - c(x, 0)? * c(y, 2)?),
                Value::Real(c(x, 0)? * c(y, 1)? - c(x, 1)? * c(y, 0)?),
            ]))
        }
        "identity"
            if arg(0)?
                .as_int()
                .is_some_and(|n| n.saturating_mul(n) > MAX_ELEMENTS) =>
        {
            Err(unsupported(e, "an array of more than 10^7 elements"))
        }
        "identity" => {
            let n = arg(0)?
                .as_int()
                .ok_or_else(|| unsupported(e, "identity(n) needs an Integer"))?
                .max(0);
            Ok(Value::Array(
                (0..n)
                    .map(|i| Value::Array((0..n).map(|j| Value::Int((i == j) as i64)).collect()))
                    .collect(),
            ))
        }
        _ => return Ok(None),
    };
    v.map(Some)
}

/// `transpose(m)` of a matrix (of any element values).
fn transpose(e: &Expr, m: &Value) -> Result<Value, EvalError> {
    let Value::Array(rows) = m else {
        return Err(unsupported(e, "transpose() needs a matrix"));
    };
    let rows: Vec<&Vec<Value>> = rows
        .iter()
        .map(|r| match r {
            Value::Array(c) => Ok(c),
            _ => Err(unsupported(e, "transpose() needs a matrix")),
        })
        .collect::<Result<_, _>>()?;
    let cols = rows.first().map_or(0, |r| r.len());
    if rows.iter().any(|r| r.len() != cols) {
        return Err(unsupported(e, "transpose() of a ragged array"));
    }
    Ok(Value::Array(
        (0..cols)
            .map(|j| Value::Array(rows.iter().map(|r| r[j].clone()).collect()))
            .collect(),
    ))
}

/// `a * b` with a matrix operand: matrix times matrix, matrix times vector, vector
/// times matrix (spec 10.6.4).
fn matrix_product(e: &Expr, a: &Value, b: &Value) -> Result<Value, EvalError> {
    let rows = |v: &Value| -> Result<Vec<Vec<f64>>, EvalError> {
        let Value::Array(items) = v else {
            return Err(unsupported(e, "a matrix is needed here"));
        };
        items
            .iter()
            .map(|r| match r {
                Value::Array(c) => c.iter().map(|x| num(e, x)).collect(),
                x => Ok(vec![num(e, x)?]),
            })
            .collect()
    };
    let (ma, mb) = (rows(a)?, rows(b)?);
    let a_is_vector = a.dims().len() == 1;
    let b_is_vector = b.dims().len() == 1;
    // A vector on the left is a row, on the right a column.
    let left: Vec<Vec<f64>> = if a_is_vector {
        vec![ma.iter().map(|r| r[0]).collect()]
    } else {
        ma
    };
    let right = mb;
    let inner = right.len();
    if left.iter().any(|r| r.len() != inner) {
        return Err(unsupported(e, "a matrix product of mismatched sizes"));
    }
    let cols = right.first().map_or(0, |r| r.len());
    let product: Vec<Vec<Value>> = left
        .iter()
        .map(|r| {
            (0..cols)
                .map(|j| Value::Real((0..inner).map(|k| r[k] * right[k][j]).sum()))
                .collect()
        })
        .collect();
    Ok(match (a_is_vector, b_is_vector) {
        (true, _) => Value::Array(product.into_iter().next().unwrap_or_default()),
        (false, true) => Value::Array(product.into_iter().map(|mut r| r.remove(0)).collect()),
        (false, false) => Value::Array(product.into_iter().map(Value::Array).collect()),
    })
}

fn range(e: &Expr, a: &Value, step: Option<&Value>, b: &Value) -> Result<Value, EvalError> {
    if let (Some(x), Some(y), None | Some(Value::Int(_))) = (a.as_int(), b.as_int(), step) {
        if matches!(a, Value::Int(_) | Value::Enum(..))
            && matches!(b, Value::Int(_) | Value::Enum(..))
        {
            let s = step.and_then(Value::as_int).unwrap_or(1);
            if s == 0 {
                return Err(unsupported(e, "a range with step 0"));
            }
            let n = if (s > 0 && y < x) || (s < 0 && y > x) {
                0
            } else {
                (y - x) / s + 1
            };
            if n > MAX_ELEMENTS {
                return Err(unsupported(e, "a range of more than 10^7 elements"));
            }
            return Ok(Value::Array(
                (0..n).map(|k| Value::Int(x + k * s)).collect(),
            ));
        }
    }
    let (x, y) = (num(e, a)?, num(e, b)?);
    let s = match step {
        Some(s) => num(e, s)?,
        None => 1.0,
    };
    if s == 0.0 {
        return Err(unsupported(e, "a range with step 0"));
    }
    let n = ((y - x) / s + 1e-10).floor() as i64 + 1;
    if n > MAX_ELEMENTS {
        return Err(unsupported(e, "a range of more than 10^7 elements"));
    }
    Ok(Value::Array(
        (0..n.max(0))
            .map(|k| Value::Real(x + k as f64 * s))
            .collect(),
    ))
}

fn flatten_values(v: &Value, out: &mut Vec<Value>) {
    match v {
        Value::Array(items) => items.iter().for_each(|i| flatten_values(i, out)),
        other => out.push(other.clone()),
    }
}

fn call(
    e: &Expr,
    func: &unimo_syntax::ast::Name,
    args: &unimo_syntax::ast::CallArgs,
    env: &mut dyn Env,
    iterators: &mut Vec<(String, Value)>,
) -> Result<Value, EvalError> {
    let name = func.to_dotted();
    // `size(x, k)` of a variable: its declared sizes, whatever its variability.
    if let ("size", Some(ExprKind::Ref(r))) =
        (name.as_str(), args.positional.first().map(|a| &a.kind))
    {
        let whole = r.parts.last().is_some_and(|p| p.subscripts.is_empty());
        if let (true, Some(d)) = (whole, env.dims(&var_key(r))) {
            let k = match args.positional.get(1) {
                Some(k) => Some(eval(k, env, iterators)?),
                None => None,
            };
            return size_of(e, d, k.as_ref());
        }
    }
    if !args.iterators.is_empty() {
        // Reductions: sum(e for i in r) and friends.
        let body = args
            .positional
            .first()
            .ok_or_else(|| unsupported(e, "an empty reduction"))?;
        let v = comprehension(body, &args.iterators, env, iterators)?;
        return reduce(e, &name, &v);
    }
    let vals: Vec<Value> = args
        .positional
        .iter()
        .map(|a| eval(a, env, iterators))
        .collect::<Result<_, _>>()?;
    let arg = |k: usize| {
        vals.get(k)
            .ok_or_else(|| unsupported(e, "missing argument"))
    };
    if let Some(v) = scalar_builtin(e, &name, &vals)? {
        return Ok(v);
    }
    if let Some(v) = matrix_builtin(e, &name, &vals)? {
        return Ok(v);
    }
    match name.as_str() {
        "Integer" => {
            Ok(Value::Int(arg(0)?.as_int().ok_or_else(|| {
                unsupported(e, "Integer() of a non-enumeration")
            })?))
        }
        "min" | "max" | "sum" | "product" => reduce(e, &name, arg(0)?),
        "size" => size_of(e, arg(0)?.dims(), vals.get(1)),
        "zeros" | "ones" => {
            let fill_with = if name == "zeros" {
                Value::Int(0)
            } else {
                Value::Int(1)
            };
            filled(e, fill_with, &vals)
        }
        "fill" => filled(e, arg(0)?.clone(), &vals[1..]),
        // `array(a, b, c)` is `{a, b, c}` (spec 10.4).
        "array" => Ok(Value::Array(vals.clone())),
        "noEvent" | "smooth" => vals
            .last()
            .cloned()
            .ok_or_else(|| unsupported(e, "missing argument")),
        _ if func.global => {
            let named = args
                .named
                .iter()
                .map(|a| Ok((a.name.text.to_string(), eval(&a.value, env, iterators)?)))
                .collect::<Result<Vec<_>, EvalError>>()?;
            let args = Arguments {
                positional: vals,
                named,
            };
            env.call(name.trim_start_matches('.'), args, e.span)
        }
        _ => Err(EvalError::NotConstant {
            span: e.span,
            what: format!("a call of `{name}`"),
        }),
    }
}

/// A built-in with a scalar evaluation in `unimo_builtins::BUILTINS` (`sin`, `floor`,
/// `div`, `min(x, y)`, ...), evaluated by the table's function: continuous maths element
/// by element (a whole result of an Integer argument stays Integer), roundings of
/// scalars with the table's result type, `min`/`max` of two values picking the
/// operand the table's function gives. `None` when `name` is no such call.
fn scalar_builtin(e: &Expr, name: &str, vals: &[Value]) -> Result<Option<Value>, EvalError> {
    use unimo_builtins::{Eval, Kind};
    let Some(b) = unimo_builtins::find(name) else {
        return Ok(None);
    };
    let arg = |k: usize| {
        vals.get(k)
            .ok_or_else(|| unsupported(e, "missing argument"))
    };
    let typed = |r: f64, all_integer: bool| match b.integer_result(r, all_integer) {
        None => Ok(Value::Real(r)),
        Some(Ok(i)) => Ok(Value::Int(i)),
        Some(Err(())) => Err(unsupported(
            e,
            &format!("an Integer result of `{name}` that is no Integer ({r})"),
        )),
    };
    let value = match b.eval {
        Eval::None => return Ok(None),
        Eval::Unary(f) if b.kind == Kind::Math => map_num(e, arg(0)?, &f)?,
        Eval::Unary(f) => typed(f(num(e, arg(0)?)?), false)?,
        // `min(a)`, `max(a)`: the reductions.
        Eval::Binary(_) if b.kind == Kind::Reduction && vals.len() != 2 => return Ok(None),
        Eval::Binary(f) if b.kind == Kind::Reduction => {
            let (x, y) = (arg(0)?, arg(1)?);
            let r = f(num(e, x)?, num(e, y)?);
            // The operand itself, so that its type (Integer, enumeration) is kept.
            if r.to_bits() == num(e, x)?.to_bits() || r == num(e, x)? {
                x.clone()
            } else {
                y.clone()
            }
        }
        Eval::Binary(f) => {
            let (x, y) = (arg(0)?, arg(1)?);
            let ints = matches!((x, y), (Value::Int(_), Value::Int(_)));
            typed(f(num(e, x)?, num(e, y)?), ints)?
        }
    };
    Ok(Some(value))
}

/// Largest array a compile-time evaluation may build.
const MAX_ELEMENTS: i64 = 10_000_000;

fn filled(e: &Expr, v: Value, dims: &[Value]) -> Result<Value, EvalError> {
    let total = dims
        .iter()
        .map(|d| d.as_int().unwrap_or(0).max(0))
        .try_fold(1i64, |acc, n| acc.checked_mul(n))
        .unwrap_or(i64::MAX);
    if total > MAX_ELEMENTS {
        return Err(unsupported(e, "an array of more than 10^7 elements"));
    }
    let Some((first, rest)) = dims.split_first() else {
        return Ok(v);
    };
    let n = first
        .as_int()
        .ok_or_else(|| unsupported(e, "a dimension must be an Integer"))?
        .max(0);
    let inner = filled(e, v, rest)?;
    Ok(Value::Array(vec![inner; n as usize]))
}

fn reduce(e: &Expr, name: &str, v: &Value) -> Result<Value, EvalError> {
    let mut items = Vec::new();
    flatten_values(v, &mut items);
    let all_int = items.iter().all(|i| matches!(i, Value::Int(_)));
    let nums: Vec<f64> = items.iter().map(|i| num(e, i)).collect::<Result<_, _>>()?;
    let r = match name {
        "sum" => nums.iter().sum(),
        "product" => nums.iter().product(),
        "min" => nums.iter().cloned().fold(f64::INFINITY, f64::min),
        _ => nums.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
    };
    Ok(if all_int && r.is_finite() {
        Value::Int(r as i64)
    } else {
        Value::Real(r)
    })
}
