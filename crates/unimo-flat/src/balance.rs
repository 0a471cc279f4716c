//! The balance check (Modelica spec 4.7): as many scalar equations as scalar unknowns.
//! Unknowns are continuous and discrete variables other than top-level inputs;
//! equations are counted by the size of their left side, `if`-equations by one branch,
//! `when`-equations by their body, algorithms by the variables they assign.

use crate::error::FlatError;
use crate::eval::var_key;
use crate::flat::{FlatModel, Variability};
use rustc_hash::FxHashMap as HashMap;
use std::collections::BTreeSet;
use unimo_source::Diagnostic;
use unimo_syntax::ast::*;

/// Counts of one model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Balance {
    pub equations: usize,
    pub unknowns: usize,
}

struct Shapes<'m> {
    /// Dimensions of the array variables; a name not here is a scalar (or a record).
    dims: HashMap<&'m str, &'m [usize]>,
    /// Scalar sizes of the record instances (`z` of `z.re`, `z.im`).
    record_sizes: HashMap<&'m str, usize>,
    /// A reused buffer for variable keys.
    buf: std::cell::RefCell<String>,
    /// Record types by full name: a constructor call has the size of its fields.
    records: HashMap<&'m str, &'m crate::functions::FlatRecord>,
    /// Bindings of the Integer parameters and constants (slice bounds `a[2:na]`).
    integers: HashMap<&'m str, &'m Expr>,
    /// Dimensions of the references through arrays of components (`port.T` of the
    /// variables `port[1].T` ... `port[3].T` is a 3-vector): see [`through_arrays`].
    through: HashMap<String, Vec<usize>>,
}

impl Shapes<'_> {
    /// The value of an Integer expression of literals, Integer parameters and `size`
    /// of arrays (`size(a, 1) - 1`), where the structure fixes it.
    fn int_value(&self, e: &Expr, depth: u32) -> Option<i64> {
        if depth > 16 {
            return None;
        }
        match &e.kind {
            ExprKind::Integer(n) => Some(*n),
            ExprKind::Ref(r) if r.parts.iter().all(|p| p.subscripts.is_empty()) => {
                let b = self.integers.get(var_key(r).as_str())?;
                self.int_value(b, depth + 1)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (
                    self.int_value(lhs, depth + 1)?,
                    self.int_value(rhs, depth + 1)?,
                );
                match op {
                    BinaryOp::Add => a.checked_add(b),
                    BinaryOp::Sub => a.checked_sub(b),
                    BinaryOp::Mul => a.checked_mul(b),
                    _ => None,
                }
            }
            ExprKind::Call { func, args } if args.positional.len() == 2 => {
                let name = func.to_dotted();
                let (x, y) = (&args.positional[0], &args.positional[1]);
                match name.as_str() {
                    "size" => {
                        let ExprKind::Ref(r) = &x.kind else {
                            return None;
                        };
                        let k = self.int_value(y, depth + 1)?;
                        let d = self.dims.get(var_key(r).as_str())?;
                        d.get(usize::try_from(k - 1).ok()?).map(|&n| n as i64)
                    }
                    "max" => Some(
                        self.int_value(x, depth + 1)?
                            .max(self.int_value(y, depth + 1)?),
                    ),
                    "min" => Some(
                        self.int_value(x, depth + 1)?
                            .min(self.int_value(y, depth + 1)?),
                    ),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    fn of(&self, e: &Expr) -> Vec<usize> {
        match &e.kind {
            ExprKind::Ref(r) => self.of_ref(r),
            ExprKind::Call { func, args } => self.of_call(func, args),
            ExprKind::Unary { operand, .. } => self.of(operand),
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.of(lhs), self.of(rhs));
                match op {
                    BinaryOp::Mul => match (a.len(), b.len()) {
                        (0, _) => b,
                        (_, 0) => a,
                        (1, 1) => Vec::new(),
                        (2, 1) => vec![a[0]],
                        (1, 2) => vec![b[1]],
                        _ => vec![a[0], b[b.len() - 1]],
                    },
                    BinaryOp::Div => a,
                    op if crate::lookup::is_boolean(*op) => Vec::new(),
                    _ => {
                        if a.len() >= b.len() {
                            a
                        } else {
                            b
                        }
                    }
                }
            }
            ExprKind::Array(items) => {
                let mut d = vec![items.len()];
                if let Some(f) = items.first() {
                    d.extend(self.of(f));
                }
                d
            }
            // `[a, b; c, d]`: each element is promoted to a matrix (a scalar 1 x 1, a
            // vector n x 1), a row concatenates along columns, the rows along rows
            // (spec 10.4.2): `[u1; u2; u3]` of scalars is 3 x 1, of 2-vectors 6 x 1.
            ExprKind::Matrix(rows) => {
                let as_matrix = |d: Vec<usize>| match d.len() {
                    0 => (1, 1),
                    1 => (d[0], 1),
                    _ => (d[0], d[1..].iter().product()),
                };
                let mut height = 0;
                let mut width = 0;
                for (k, row) in rows.iter().enumerate() {
                    let shapes: Vec<(usize, usize)> =
                        row.iter().map(|x| as_matrix(self.of(x))).collect();
                    height += shapes.first().map_or(0, |s| s.0);
                    if k == 0 {
                        width = shapes.iter().map(|s| s.1).sum();
                    }
                }
                vec![height, width]
            }
            ExprKind::If { branches, .. } => branches
                .first()
                .map(|(_, v)| self.of(v))
                .unwrap_or_default(),
            _ => Vec::new(),
        }
    }

    /// The dimensions of a call: a record constructor's arguments side by side, or a
    /// built-in's result.
    fn of_call(&self, func: &Name, args: &CallArgs) -> Vec<usize> {
        let name = func.to_dotted();
        if self.records.contains_key(name.trim_start_matches('.')) {
            // A record constructor: its arguments side by side.
            let n: usize = args
                .positional
                .iter()
                .chain(args.named.iter().map(|a| &a.value))
                .map(|a| sat_product(&self.of(a)))
                .sum();
            return vec![n];
        }
        let arg = |k: usize| {
            args.positional
                .get(k)
                .map(|a| self.of(a))
                .unwrap_or_default()
        };
        match name.as_str() {
            f if unimo_builtins::is_elementwise(f) => arg(0),
            "smooth" => arg(1),
            "cross" => vec![3],
            "collisionBody" => vec![6],
            "collisionGaps" => vec![2],
            "transpose" => {
                let mut d = arg(0);
                d.reverse();
                d
            }
            "zeros" | "ones" | "fill" => {
                let skip = usize::from(name == "fill");
                args.positional
                    .iter()
                    .skip(skip)
                    .filter_map(|a| match a.kind {
                        ExprKind::Integer(n) => Some(n.max(0) as usize),
                        _ => None,
                    })
                    .collect()
            }
            "identity" => match args.positional.first().map(|a| &a.kind) {
                Some(ExprKind::Integer(n)) => vec![*n as usize; 2],
                _ => Vec::new(),
            },
            _ => Vec::new(),
        }
    }

    /// The dimensions of a reference: a variable's, less its scalar subscripts; a record
    /// instance counts as a vector of its scalars.
    fn of_ref(&self, r: &ComponentRef) -> Vec<usize> {
        let d = {
            let mut buf = self.buf.borrow_mut();
            crate::eval::var_key_into(&mut buf, &r.parts);
            self.dims.get(buf.as_str()).copied()
        };
        let Some(d) = d else {
            if let Some(d) = self.through_array(r) {
                return d;
            }
            if self.record_sizes.is_empty() {
                return Vec::new();
            }
            let key = var_key(r);
            // A record: as many scalars as its variables.
            let mut instance = key;
            if let Some(last) = r.parts.last() {
                instance.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
            }
            return match self.record_sizes.get(instance.as_str()) {
                Some(&n) if n > 0 => vec![n],
                _ => Vec::new(),
            };
        };
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.as_slice())
            .unwrap_or(&[]);
        let mut out = Vec::new();
        for (k, n) in d.iter().enumerate() {
            match subs.get(k) {
                None | Some(Subscript::Colon(_)) => out.push(*n),
                Some(Subscript::Expr(x)) => {
                    if let ExprKind::Range {
                        start,
                        step: None,
                        stop,
                    } = &x.kind
                    {
                        if let (Some(a), Some(b)) =
                            (self.int_value(start, 0), self.int_value(stop, 0))
                        {
                            out.push((b - a + 1).max(0) as usize);
                        }
                    }
                }
            }
        }
        out
    }

    /// The dimensions of a reference without subscripts through arrays of components.
    fn through_array(&self, r: &ComponentRef) -> Option<Vec<usize>> {
        if self.through.is_empty() || r.parts.iter().any(|p| !p.subscripts.is_empty()) {
            return None;
        }
        self.through.get(var_key(r).as_str()).cloned()
    }

    fn size(&self, e: &Expr) -> usize {
        sat_product(&self.of(e))
    }

    fn count(&self, eqs: &[Equation]) -> usize {
        eqs.iter()
            .map(|e| self.count_one(e))
            .fold(0, usize::saturating_add)
    }

    fn count_one(&self, e: &Equation) -> usize {
        match &e.kind {
            // The left side decides; the right side when the left is a plain scalar
            // expression whose shape is unknown here (`zeros(3) = v` has its own shape).
            // `(a, b) = f(x)`: one equation per scalar of each target (an empty slot
            // `(a, , c)` discards that output).
            EquationKind::Simple {
                lhs:
                    Expr {
                        kind: ExprKind::Tuple(targets),
                        ..
                    },
                ..
            } => targets
                .iter()
                .flatten()
                .map(|t| self.size(t))
                .fold(0, usize::saturating_add),
            EquationKind::Simple { lhs, rhs } => {
                let l = self.of(lhs);
                if l.is_empty() && !is_scalar_for_sure(lhs) {
                    self.size(rhs)
                } else {
                    sat_product(&l)
                }
            }
            // assert, terminate and reinit are not equations for counting.
            EquationKind::Call(_) | EquationKind::Connect { .. } => 0,
            EquationKind::If {
                branches,
                otherwise,
            } => branches
                .first()
                .map(|(_, b)| self.count(b))
                .unwrap_or_else(|| self.count(otherwise)),
            EquationKind::For { body, .. } => self.count(body),
            EquationKind::When { branches } => {
                branches.first().map(|(_, b)| self.count(b)).unwrap_or(0)
            }
        }
    }
}

/// The product of sizes, saturating (sizes come from user input).
fn sat_product(d: &[usize]) -> usize {
    d.iter().fold(1usize, |acc, &n| acc.saturating_mul(n))
}

/// Continuous and discrete variables other than top-level inputs.
fn is_unknown(v: &crate::flat::FlatVar) -> bool {
    matches!(
        v.variability,
        Variability::Continuous | Variability::Discrete
    ) && !(v.top_level && v.causality == Some(Causality::Input))
}

/// A left side whose shape is certainly scalar (a literal or a scalar reference).
fn is_scalar_for_sure(e: &Expr) -> bool {
    matches!(
        e.kind,
        ExprKind::Integer(_)
            | ExprKind::Real(_)
            | ExprKind::Bool(_)
            | ExprKind::String(_)
            | ExprKind::Ref(_)
    )
}

fn assigned(stmts: &[Statement], out: &mut BTreeSet<String>) {
    for s in stmts {
        match &s.kind {
            StatementKind::Assign { target, .. } => {
                out.insert(var_key(target));
            }
            StatementKind::MultiAssign { targets, .. } => {
                for t in targets.iter().flatten() {
                    if let ExprKind::Ref(r) = &t.kind {
                        out.insert(var_key(r));
                    }
                }
            }
            StatementKind::If {
                branches,
                otherwise,
            } => {
                branches.iter().for_each(|(_, b)| assigned(b, out));
                assigned(otherwise, out);
            }
            StatementKind::For { body, .. } | StatementKind::While { body, .. } => {
                assigned(body, out)
            }
            StatementKind::When { branches } => branches.iter().for_each(|(_, b)| assigned(b, out)),
            _ => {}
        }
    }
}

/// The references through arrays of components, with their dimensions: the variable
/// `a.port[2].T` (of `Real T[2]`) makes `a.port.T` have the dimensions of `port`
/// (largest index seen) followed by those of `T` (spec 10.6.9: `port.T` is the array
/// of the elements' `T`).
fn through_arrays(model: &FlatModel) -> HashMap<String, Vec<usize>> {
    let mut out: HashMap<String, Vec<usize>> = HashMap::default();
    for v in &model.vars {
        let parts = crate::flat::split_name(&v.name);
        let Some((_, init)) = parts.split_last() else {
            continue;
        };
        if !init.iter().any(|p| p.ends_with(']')) {
            continue;
        }
        let mut key = String::with_capacity(v.name.len());
        let mut dims = Vec::new();
        let mut ok = true;
        for (k, p) in parts.iter().enumerate() {
            if k > 0 {
                key.push('.');
            }
            match p
                .find('[')
                .filter(|_| p.ends_with(']') && k + 1 < parts.len())
            {
                Some(i) => {
                    key.push_str(&p[..i]);
                    for x in p[i + 1..p.len() - 1].split(',') {
                        match x.trim().parse::<usize>() {
                            Ok(n) => dims.push(n),
                            Err(_) => ok = false,
                        }
                    }
                }
                None => key.push_str(p),
            }
        }
        if !ok {
            continue;
        }
        dims.extend_from_slice(&v.dims);
        let e = out.entry(key).or_insert_with(|| vec![0; dims.len()]);
        if e.len() == dims.len() {
            for (a, b) in e.iter_mut().zip(&dims) {
                *a = (*a).max(*b);
            }
        }
    }
    out
}

/// Counts the scalar equations and unknowns of `model`.
pub fn count(model: &FlatModel) -> Balance {
    let mut record_sizes: HashMap<&str, usize> = HashMap::default();
    if !model.record_instances.is_empty() {
        for (k, _) in &model.record_instances {
            record_sizes.insert(k.as_str(), 0);
        }
        // Each variable counts for every record instance its name is inside of.
        for v in &model.vars {
            for (i, c) in v.name.char_indices() {
                if c == '.' {
                    if let Some(n) = record_sizes.get_mut(&v.name[..i]) {
                        *n += v.size();
                    }
                }
            }
        }
    }
    let shapes = Shapes {
        // Scalars are left out: most models are mostly scalars, and a small map is
        // looked up in cache.
        dims: model
            .vars
            .iter()
            .filter(|v| !v.dims.is_empty())
            .map(|v| (v.name.as_str(), v.dims.as_slice()))
            .collect(),
        record_sizes,
        buf: Default::default(),
        records: model.records.iter().map(|r| (r.name.as_str(), r)).collect(),
        integers: model
            .vars
            .iter()
            .filter(|v| {
                v.ty == crate::flat::FlatType::Integer
                    && v.dims.is_empty()
                    && matches!(
                        v.variability,
                        crate::flat::Variability::Parameter | crate::flat::Variability::Constant
                    )
            })
            .filter_map(|v| Some((v.name.as_str(), v.binding.as_deref()?)))
            .collect(),
        through: through_arrays(model),
    };
    let unknowns = model
        .vars
        .iter()
        .filter(|v| is_unknown(v))
        .map(|v| v.size())
        .sum();
    // A declaration equation of a variable (`Real s = f(x)`) is an equation too.
    let bindings: usize = model
        .vars
        .iter()
        .filter(|v| {
            v.binding.is_some()
                && matches!(
                    v.variability,
                    Variability::Continuous | Variability::Discrete
                )
        })
        .map(|v| v.size())
        .sum();
    let mut equations = shapes.count(&model.equations).saturating_add(bindings);
    for alg in &model.algorithms {
        let mut names = BTreeSet::new();
        assigned(alg, &mut names);
        let assigned_size = names
            .iter()
            .map(|n| shapes.dims.get(n.as_str()).map_or(1, |d| sat_product(d)))
            .fold(0, usize::saturating_add);
        equations = equations.saturating_add(assigned_size);
    }
    Balance {
        equations,
        unknowns,
    }
}

/// `E2010` when the counts differ, naming the unknowns no equation mentions.
pub fn check(model: &FlatModel, span: unimo_source::Span) -> Option<Diagnostic> {
    let b = count(model);
    if b.equations == b.unknowns {
        return None;
    }
    let mut mentioned = BTreeSet::new();
    let mut note = |e: &Expr| {
        crate::flat::for_each_ref(e, &mut |r| {
            mentioned.insert(var_key(r));
        });
    };
    crate::flat::for_each_equation_expr(&model.equations, &mut note);
    let mut assigned_names = BTreeSet::new();
    for alg in &model.algorithms {
        assigned(alg, &mut assigned_names);
    }
    let orphans: Vec<&str> = model
        .vars
        .iter()
        .filter(|v| is_unknown(v))
        .filter(|v| {
            v.binding.is_none() && !mentioned.contains(&v.name) && !assigned_names.contains(&v.name)
        })
        .map(|v| v.name.as_str())
        .collect();
    let (more, what) = if b.equations < b.unknowns {
        (b.unknowns - b.equations, "too few equations")
    } else {
        (b.equations - b.unknowns, "too many equations")
    };
    Some(
        FlatError::Unbalanced {
            model: model.name.clone(),
            equations: b.equations,
            unknowns: b.unknowns,
            what,
            off: more,
            orphans: orphans.iter().map(|o| o.to_string()).collect(),
            span,
        }
        .into(),
    )
}
