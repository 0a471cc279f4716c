//! Overconstrained connections (spec 9.4): the virtual connection graph of the
//! overdetermined records of connectors (nodes), `connect`s (optional edges) and
//! `Connections.branch` (required edges); its spanning tree, where a `connect` that
//! closes a loop gives `zeros(n) = R.equalityConstraint(a, b)` instead of the
//! equalities of its fields; the roots (`Connections.root`, else the
//! `potentialRoot` of lowest priority of each connected part); and the values of
//! `Connections.isRoot` and `Connections.rooted` in the equations, with those of
//! `cardinality(c)` (the number of `connect`s naming `c`, spec 3.7.2.3), whose `if`s
//! are then resolved.

use crate::connect::{find, var_ref};
use crate::eval::{self, Env, EvalError, Value};
use crate::flat::FlatModel;
use crate::instantiate::{Connect, Instantiator};
use crate::lookup::Found;
use rustc_hash::FxHashMap as HashMap;
use std::collections::VecDeque;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// The graph's nodes (record instances by key) and what the equations say of them.
#[derive(Default)]
struct Graph {
    index: HashMap<String, usize>,
    keys: Vec<String>,
    /// The record type of each node (full name).
    types: Vec<String>,
    required: Vec<(usize, usize)>,
    roots: Vec<usize>,
    /// Potential roots with their priority, in order of appearance.
    potential: Vec<(usize, i64)>,
}

impl Graph {
    fn node(&mut self, key: &str, ty: &str) -> usize {
        if let Some(&n) = self.index.get(key) {
            return n;
        }
        self.keys.push(key.to_owned());
        self.types.push(ty.to_owned());
        self.index.insert(key.to_owned(), self.keys.len() - 1);
        self.keys.len() - 1
    }
}

/// The `Connections` operator a call is (`rooted` also in its deprecated form).
fn operator(func: &Name) -> Option<&str> {
    match func.parts.as_slice() {
        [c, op] if c.text == "Connections" => Some(op.text.as_str()),
        [op] if op.text == "rooted" => Some("rooted"),
        _ => None,
    }
}

/// Record instances by key, with their type's full name.
type Instances<'m> = HashMap<&'m str, &'m str>;

/// The node key and record type of an argument: a record instance `a.R`, or the
/// printed form of one, `'R'('a.R.T', 'a.R.w')`.
fn argument_node(e: &Expr, types: &Instances) -> Option<(String, String)> {
    match &e.kind {
        ExprKind::Ref(r) => {
            let key = eval::var_key_parts(&r.parts);
            let ty = types.get(key.as_str())?;
            Some((key, ty.to_string()))
        }
        ExprKind::Call { func, args } => {
            let ExprKind::Ref(r) = &args.positional.first()?.kind else {
                return None;
            };
            let field = eval::var_key(r);
            let (key, _) = field.rsplit_once('.')?;
            Some((key.to_owned(), func.to_dotted()))
        }
        _ => None,
    }
}

/// Values of literal conditions only.
struct NoVariables;

impl Env for NoVariables {
    fn var(&mut self, key: &str, span: Span) -> Result<Value, EvalError> {
        Err(EvalError::NotConstant {
            span,
            what: key.to_owned(),
        })
    }
}

impl Instantiator<'_, '_> {
    /// Applies spec 9.4 to `model` and its connection equations `conn_eqs` (not yet
    /// in it); returns the `equalityConstraint` functions the loops call.
    pub(crate) fn overconstrained(
        &mut self,
        model: &mut FlatModel,
        conn_eqs: &mut Vec<Equation>,
        (connects, absent): (&[Connect], &[String]),
    ) -> Vec<String> {
        let mut graph = Graph::default();
        let mut operators = false;
        let records = std::mem::take(&mut model.record_instances);
        let types: Instances = records
            .iter()
            .map(|(k, t)| (k.as_str(), t.as_str()))
            .collect();
        for eq in model.equations.iter().chain(&model.initial_equations) {
            note_operators(eq, &types, &mut graph, &mut operators);
        }
        if !operators {
            model.record_instances = records;
            return Vec::new();
        }
        let edge_of_eq = self.optional_edges(conn_eqs, &types, &mut graph);
        let n = graph.keys.len();
        let mut parent: Vec<usize> = (0..n).collect();
        let mut tree: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(a, b) in &graph.required {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            parent[ra] = rb;
            tree[a].push(b);
            tree[b].push(a);
        }
        // Each optional edge in order: in the tree, or a loop to break.
        let mut decided: HashMap<(usize, usize), bool> = HashMap::default();
        let mut broken = Vec::new();
        for &(a, b) in edge_of_eq.iter().flatten() {
            let pair = (a.min(b), a.max(b));
            if decided.contains_key(&pair) || a == b {
                continue;
            }
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            let in_tree = ra != rb;
            if in_tree {
                parent[ra] = rb;
                tree[a].push(b);
                tree[b].push(a);
            } else {
                broken.push((a, b));
            }
            decided.insert(pair, in_tree);
        }
        let mut k = 0;
        conn_eqs.retain(|_| {
            let keep = edge_of_eq[k]
                .is_none_or(|(a, b)| decided.get(&(a.min(b), a.max(b))).copied().unwrap_or(true));
            k += 1;
            keep
        });
        let mut called = Vec::new();
        for edge in broken {
            if let Some((eq, f)) = self.loop_equation(&graph, edge) {
                conn_eqs.push(eq);
                called.push(f);
            }
        }
        called.sort();
        called.dedup();
        let depth = root_depths(&graph, &mut parent, &tree);
        let branches = graph.required.clone();
        let cardinality = connection_counts(connects, absent);
        let values = |key: &str, op: &str| -> Option<Value> {
            if op == "cardinality" {
                return Some(Value::Int(cardinality.get(key).copied().unwrap_or(0)));
            }
            let node = *graph.index.get(key)?;
            match op {
                "isRoot" => Some(Value::Bool(depth[node] == Some(0))),
                "rooted" => {
                    let other = branches.iter().find_map(|&(a, b)| {
                        (a == node).then_some(b).or((b == node).then_some(a))
                    })?;
                    Some(Value::Bool(depth[node]? < depth[other]?))
                }
                _ => None,
            }
        };
        self.resolve_operators(model, &types, &values);
        drop(types);
        model.record_instances = records;
        called
    }

    /// `model`'s equations with `isRoot`/`rooted` replaced by `values` and the `if`s
    /// they decide resolved; the conditions are evaluated as instantiation does
    /// (parameters included), so that an `elseif` a resolved `isRoot` leaves is decided
    /// as it would be in the printed model (which reads back to the same text).
    fn resolve_operators(
        &mut self,
        model: &mut FlatModel,
        types: &Instances,
        values: &dyn Fn(&str, &str) -> Option<Value>,
    ) {
        std::mem::swap(&mut self.model, model);
        for initial in [false, true] {
            let eqs = if initial {
                &mut self.model.initial_equations
            } else {
                &mut self.model.equations
            };
            let old = std::mem::take(eqs);
            let new = resolve_equations(old, types, values, self);
            if initial {
                self.model.initial_equations = new;
            } else {
                self.model.equations = new;
            }
        }
        std::mem::swap(&mut self.model, model);
    }

    /// The optional edge each connection equation belongs to: an equation between
    /// fields of two overdetermined record instances.
    fn optional_edges(
        &mut self,
        conn_eqs: &[Equation],
        types: &Instances,
        graph: &mut Graph,
    ) -> Vec<Option<(usize, usize)>> {
        let mut overdetermined: HashMap<String, bool> = HashMap::default();
        let mut edge_of_eq: Vec<Option<(usize, usize)>> = Vec::with_capacity(conn_eqs.len());
        for eq in conn_eqs.iter() {
            let edge = match &eq.kind {
                EquationKind::Simple { lhs, rhs } => {
                    let mut side = |e: &Expr| -> Option<usize> {
                        let ExprKind::Ref(r) = &e.kind else {
                            return None;
                        };
                        let field = eval::var_key(r);
                        let (key, _) = field.rsplit_once('.')?;
                        let ty = *types.get(key)?;
                        let od = *overdetermined
                            .entry(ty.to_owned())
                            .or_insert_with(|| self.declares_equality_constraint(ty));
                        od.then(|| graph.node(key, ty))
                    };
                    side(lhs).zip(side(rhs))
                }
                _ => None,
            };
            edge_of_eq.push(edge);
        }
        edge_of_eq
    }

    /// Whether record type `ty` (full name) declares `equalityConstraint`.
    fn declares_equality_constraint(&mut self, ty: &str) -> bool {
        let parts = crate::flat::split_name(ty);
        match self.tree.lookup_dotted(None, &parts, false) {
            Some(Found::Class(c)) => self.tree.member_class(c, "equalityConstraint").is_some(),
            _ => false,
        }
    }

    /// `zeros(n) = R.equalityConstraint(R(a fields), R(b fields))` for the broken
    /// edge `(a, b)`, and the function's name.
    fn loop_equation(
        &mut self,
        graph: &Graph,
        (a, b): (usize, usize),
    ) -> Option<(Equation, String)> {
        let ty = &graph.types[a];
        let parts = crate::flat::split_name(ty);
        let Some(Found::Class(c)) = self.tree.lookup_dotted(None, &parts, false) else {
            return None;
        };
        let fc = self.tree.member_class(c, "equalityConstraint")?;
        let name = format!("{ty}.equalityConstraint");
        let f = self.flat_function(fc, &name)?;
        let size = f.outputs.first()?.dims.first().copied().flatten()?;
        let span = Span::default();
        let value = |key: &str| var_ref(key, span);
        let rhs = Expr {
            kind: ExprKind::Call {
                func: dotted_name(&name, span),
                args: Box::new(CallArgs {
                    positional: vec![value(&graph.keys[a]), value(&graph.keys[b])],
                    named: Vec::new(),
                    iterators: Vec::new(),
                    span,
                }),
            },
            span,
        };
        let lhs = Value::Array(vec![Value::Real(0.0); size]).to_expr(span);
        let eq = Equation {
            kind: EquationKind::Simple { lhs, rhs },
            comment: Comment::default(),
            span,
        };
        Some((eq, name))
    }
}

/// A function's full name, as flattened calls spell it.
pub(crate) fn dotted_name(name: &str, span: Span) -> Name {
    Name {
        global: true,
        parts: crate::flat::split_name(name)
            .into_iter()
            .map(|p| Ident {
                text: p.into(),
                span,
            })
            .collect(),
        span,
    }
}

/// The key of a connector reference with all its subscripts (`a.p[2]`).
fn key_with_subscripts(r: &ComponentRef) -> String {
    let mut s = eval::var_key(r);
    if let Some(last) = r.parts.last() {
        s.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
    }
    s
}

/// How many `connect`s name each connector (spec 3.7.2.3, `cardinality`), those to
/// absent conditional components left out.
fn connection_counts(connects: &[Connect], absent: &[String]) -> HashMap<String, i64> {
    let inside = |k: &str| {
        absent.iter().any(|a| {
            k == a
                || k.strip_prefix(a.as_str())
                    .is_some_and(|r| r.starts_with(['.', '[']))
        })
    };
    let mut out: HashMap<String, i64> = HashMap::default();
    for c in connects {
        let (a, b) = (key_with_subscripts(&c.a), key_with_subscripts(&c.b));
        if inside(&a) || inside(&b) {
            continue;
        }
        *out.entry(a).or_default() += 1;
        *out.entry(b).or_default() += 1;
    }
    out
}

/// Notes the roots, potential roots and branches the equations declare (also inside
/// `if`s); `operators` is set when any `Connections` operator occurs.
fn note_operators(eq: &Equation, types: &Instances, graph: &mut Graph, operators: &mut bool) {
    match &eq.kind {
        EquationKind::Call(e) => note_calls(e, types, graph, operators),
        EquationKind::Simple { lhs, rhs } => {
            note_calls(lhs, types, graph, operators);
            note_calls(rhs, types, graph, operators);
        }
        EquationKind::If {
            branches,
            otherwise,
        } => {
            for (c, body) in branches {
                note_calls(c, types, graph, operators);
                for e in body {
                    note_operators(e, types, graph, operators);
                }
            }
            for e in otherwise {
                note_operators(e, types, graph, operators);
            }
        }
        EquationKind::For { body, .. } => {
            for e in body {
                note_operators(e, types, graph, operators);
            }
        }
        _ => {}
    }
}

/// Notes the `Connections` operators called in `e`.
fn note_calls(e: &Expr, types: &Instances, graph: &mut Graph, operators: &mut bool) {
    crate::flat::for_each_call(e, &mut |_| {}, &mut |func, args| {
        let Some(op) = operator(func) else {
            return;
        };
        *operators = true;
        let mut nodes = args
            .positional
            .iter()
            .filter_map(|a| argument_node(a, types));
        let Some((key, ty)) = nodes.next() else {
            return;
        };
        let a = graph.node(&key, &ty);
        match op {
            "root" => graph.roots.push(a),
            "potentialRoot" => {
                let priority = args
                    .positional
                    .get(1)
                    .or(args.named.first().map(|n| &n.value))
                    .and_then(|p| eval::eval(p, &mut NoVariables, &mut Vec::new()).ok())
                    .and_then(|v| v.as_int())
                    .unwrap_or(0);
                graph.potential.push((a, priority));
            }
            "branch" => {
                if let Some((key, ty)) = nodes.next() {
                    let b = graph.node(&key, &ty);
                    graph.required.push((a, b));
                }
            }
            _ => {}
        }
    });
}

/// The distance of each node from the root of its connected part in the spanning
/// tree (`None`: a part without a root). The root is the part's `Connections.root`,
/// else its potential root of lowest priority (the first of equal ones).
fn root_depths(graph: &Graph, parent: &mut [usize], tree: &[Vec<usize>]) -> Vec<Option<usize>> {
    let n = graph.keys.len();
    let mut chosen: HashMap<usize, (usize, i64, bool)> = HashMap::default();
    for &r in &graph.roots {
        chosen.entry(find(parent, r)).or_insert((r, i64::MIN, true));
    }
    for &(p, priority) in &graph.potential {
        let part = find(parent, p);
        match chosen.get(&part) {
            Some(&(_, best, _)) if best <= priority => {}
            _ => {
                chosen.insert(part, (p, priority, false));
            }
        }
    }
    let mut depth = vec![None; n];
    let mut queue = VecDeque::new();
    for &(root, _, _) in chosen.values() {
        depth[root] = Some(0);
        queue.push_back(root);
    }
    while let Some(x) = queue.pop_front() {
        let d = depth[x].unwrap_or(0);
        for &y in &tree[x] {
            if depth[y].is_none() {
                depth[y] = Some(d + 1);
                queue.push_back(y);
            }
        }
    }
    depth
}

/// The equations without the `Connections` operators that state the graph, with
/// `isRoot` and `rooted` replaced by their values and the `if`s they decide resolved.
fn resolve_equations(
    eqs: Vec<Equation>,
    types: &Instances,
    values: &dyn Fn(&str, &str) -> Option<Value>,
    env: &mut dyn Env,
) -> Vec<Equation> {
    let mut out = Vec::with_capacity(eqs.len());
    for mut eq in eqs {
        match &mut eq.kind {
            EquationKind::Call(Expr {
                kind: ExprKind::Call { func, .. },
                ..
            }) if matches!(operator(func), Some("root" | "potentialRoot" | "branch")) => continue,
            EquationKind::If {
                branches,
                otherwise,
            } => {
                let mut kept = Vec::new();
                let (mut chosen, mut last) = (None, None);
                for (mut c, body) in std::mem::take(branches) {
                    replace_values(&mut c, types, values);
                    let body = resolve_equations(body, types, values, env);
                    match eval::eval(&c, env, &mut Vec::new()) {
                        Ok(Value::Bool(false)) => {}
                        // Always taken: the rest is never reached.
                        Ok(Value::Bool(true)) if kept.is_empty() => {
                            chosen = Some(body);
                            break;
                        }
                        Ok(Value::Bool(true)) => {
                            last = Some(body);
                            break;
                        }
                        _ => kept.push((c, body)),
                    }
                }
                let rest = match last {
                    Some(body) => body,
                    None => resolve_equations(std::mem::take(otherwise), types, values, env),
                };
                match (chosen, kept.is_empty()) {
                    (Some(body), _) => out.extend(body),
                    (None, true) => out.extend(rest),
                    (None, false) => {
                        *branches = kept;
                        *otherwise = rest;
                        out.push(eq);
                    }
                }
                continue;
            }
            EquationKind::Simple { lhs, rhs } => {
                replace_values(lhs, types, values);
                replace_values(rhs, types, values);
            }
            EquationKind::Call(e) => replace_values(e, types, values),
            EquationKind::For { body, .. } => {
                *body = resolve_equations(std::mem::take(body), types, values, env);
            }
            _ => {}
        }
        out.push(eq);
    }
    out
}

/// `e` with `Connections.isRoot(x)` and `rooted(x)` replaced by their values.
fn replace_values(e: &mut Expr, types: &Instances, values: &dyn Fn(&str, &str) -> Option<Value>) {
    if let ExprKind::Call { func, args } = &e.kind {
        if let (
            true,
            [Expr {
                kind: ExprKind::Ref(r),
                ..
            }],
        ) = (
            func.to_dotted() == "cardinality",
            args.positional.as_slice(),
        ) {
            if let Some(v) = values(&key_with_subscripts(r), "cardinality") {
                *e = v.to_expr(e.span);
                return;
            }
        }
        if let Some(op @ ("isRoot" | "rooted")) = operator(func) {
            let value = args
                .positional
                .first()
                .and_then(|a| argument_node(a, types))
                .and_then(|(key, _)| values(&key, op));
            if let Some(v) = value {
                *e = v.to_expr(e.span);
                return;
            }
        }
    }
    e.for_each_child_mut(&mut |c| replace_values(c, types, values));
}
