//! Connection sets (Modelica spec 9.2): connected potential variables are equal, flow
//! variables sum to zero with inside connectors counted `+` and outside ones `-`, and an
//! unconnected flow variable is zero.

use crate::error::FlatError;
use crate::eval::var_key;
use crate::flat::FlatModel;
use crate::instantiate::Connect;
use rustc_hash::FxHashMap as HashMap;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::{
    BinaryOp, CallArgs, ComponentRef, Equation, EquationKind, Expr, ExprKind, Ident, Name, RefPart,
    Subscript,
};

/// A node of the connection graph: a primitive variable (or one element of an array
/// variable, `elem` its row-major offset; [`WHOLE`] for the whole variable) seen from
/// one side.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
struct Node {
    var: usize,
    elem: u32,
    outside: bool,
}

/// `Node::elem` of a whole variable.
const WHOLE: u32 = u32::MAX;

/// An element `x[2, 1]` of an array variable named in a `connect`: the variable's index
/// and the element's row-major offset. `None` unless `key` is a known array variable's
/// name followed by integer subscripts within its sizes.
fn element_of(
    model: &FlatModel,
    by_name: &HashMap<&str, usize>,
    key: &str,
) -> Option<(usize, u32)> {
    let body = key.strip_suffix(']')?;
    let open = body.rfind('[')?;
    let var = *by_name.get(&body[..open])?;
    let dims = &model.vars[var].dims;
    let subs: Vec<usize> = body[open + 1..]
        .split(',')
        .map(|t| t.trim().parse::<usize>().ok())
        .collect::<Option<_>>()?;
    if subs.len() != dims.len() || subs.iter().zip(dims).any(|(&i, &n)| i == 0 || i > n) {
        return None;
    }
    let offset = subs
        .iter()
        .zip(dims)
        .fold(0, |acc, (&i, &n)| acc * n + (i - 1));
    Some((var, u32::try_from(offset).ok()?))
}

/// A reference to a primitive: the variable, or its element at `elem`.
fn prim_ref(model: &FlatModel, var: usize, elem: u32, span: Span) -> Expr {
    let v = &model.vars[var];
    let mut e = var_ref(&v.name, span);
    if elem != WHOLE {
        let mut rest = elem as usize;
        let mut subs = vec![0usize; v.dims.len()];
        for (k, &n) in v.dims.iter().enumerate().rev() {
            subs[k] = rest % n + 1;
            rest /= n;
        }
        if let ExprKind::Ref(r) = &mut e.kind {
            r.parts[0].subscripts = subs
                .into_iter()
                .map(|i| {
                    unimo_syntax::ast::Subscript::Expr(Expr {
                        kind: ExprKind::Integer(i as i64),
                        span,
                    })
                })
                .collect();
        }
    }
    e
}

/// Whether the connector `key` is the instance `absent` or inside it (`a.V` is inside
/// `a`, but `a.V_internal` is not inside `a.V`).
fn inside(key: &str, absent: &str) -> bool {
    key.strip_prefix(absent)
        .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
}

/// Union-find's root of `x`, with path compression.
pub(crate) fn find(parent: &mut [usize], x: usize) -> usize {
    let mut r = x;
    while parent[r] != r {
        r = parent[r];
    }
    let mut c = x;
    while parent[c] != r {
        let next = parent[c];
        parent[c] = r;
        c = next;
    }
    r
}

/// `0.0` for a scalar, `zeros(n, m, ..)` for an array of dimensions `dims`.
fn zeros(dims: &[usize], span: Span) -> Expr {
    if dims.is_empty() {
        return Expr {
            kind: ExprKind::Real(0.0),
            span,
        };
    }
    let positional = dims
        .iter()
        .map(|&n| Expr {
            kind: ExprKind::Integer(n as i64),
            span,
        })
        .collect();
    Expr {
        kind: ExprKind::Call {
            func: Name {
                global: false,
                parts: vec![Ident {
                    text: "zeros".into(),
                    span,
                }],
                span,
            },
            args: Box::new(CallArgs {
                positional,
                named: Vec::new(),
                iterators: Vec::new(),
                span,
            }),
        },
        span,
    }
}

/// A reference to the flat variable `name`.
pub(crate) fn var_ref(name: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Ref(ComponentRef {
            global: false,
            parts: vec![RefPart {
                name: Ident {
                    text: name.into(),
                    span,
                },
                subscripts: Vec::new(),
            }],
            span,
        }),
        span,
    }
}

/// A connector instance's primitive variables: (suffix after the instance's name, var
/// index).
type Members<'n> = Vec<(&'n str, usize)>;

/// The primitive variables inside each connector instance in `keys`: (suffix, var
/// index), sorted by suffix, at the slot the returned map gives each key. A variable belongs to every instance its name is
/// inside of (`a.p[1].v` to `a.p[1]`, `a.p` and `a`): one hash probe per boundary of
/// its name, for the instances a `connect` names only; a prefix the previous variable
/// shared (`s1.a` of `s1.a.s` and `s1.a.f`) is not probed again.
fn members<'n>(
    vars: &'n [crate::flat::FlatVar],
    keys: &'n [(String, String)],
) -> (HashMap<&'n str, usize>, Vec<Members<'n>>) {
    let mut slot: HashMap<&str, usize> = HashMap::default();
    for (ka, kb) in keys {
        for k in [ka, kb] {
            let n = slot.len();
            slot.entry(k.as_str()).or_insert(n);
        }
    }
    let mut lists: Vec<Members> = vec![Vec::new(); slot.len()];
    // Per boundary depth: the previous variable's prefix there and its slot.
    let mut last: Vec<(&str, Option<usize>)> = Vec::new();
    for (i, v) in vars.iter().enumerate() {
        let name = v.name.as_str();
        let boundaries = name
            .bytes()
            .enumerate()
            .filter(|(_, b)| *b == b'.' || *b == b'[')
            .map(|(k, _)| k)
            .chain(std::iter::once(name.len()));
        for (depth, k) in boundaries.enumerate() {
            let prefix = &name[..k];
            let found = match last.get(depth) {
                Some(&(p, found)) if p == prefix => found,
                _ => {
                    let found = slot.get(prefix).copied();
                    if depth < last.len() {
                        last[depth] = (prefix, found);
                    } else {
                        last.push((prefix, found));
                    }
                    found
                }
            };
            if let Some(s) = found {
                lists[s].push((&name[k..], i));
            }
        }
    }
    for list in &mut lists {
        list.sort_unstable_by(|a, b| a.0.cmp(b.0));
    }
    (slot, lists)
}

/// Adds the connection equations to `model`; returns diagnostics for mismatches.
pub fn generate(model: &mut FlatModel, connects: &[Connect], absent: &[String]) -> Vec<Diagnostic> {
    let (eqs, diags) = equations(model, connects, absent);
    model.equations.extend(eqs);
    diags
}

/// The connection equations of `model` (not added to it), and diagnostics for
/// mismatches. Connected variables have the same flow prefix, size and type, so the
/// equations are well-typed by construction.
pub fn equations(
    model: &FlatModel,
    connects: &[Connect],
    absent: &[String],
) -> (Vec<Equation>, Vec<Diagnostic>) {
    let expanded;
    let connects = match expand_component_arrays(model, connects) {
        Some(c) => {
            expanded = c;
            expanded.as_slice()
        }
        None => connects,
    };
    let mut diags = Vec::new();
    let mut graph = ConnectionSets::new(model.vars.len());
    let keys: Vec<(String, String)> = connects
        .iter()
        .map(|c| (var_key_full(&c.a), var_key_full(&c.b)))
        .collect();
    let (slot, lists) = members(&model.vars, &keys);
    // Connected elements of array variables (`connect(a.y, sum.u[2])`): such a
    // variable is connected element by element everywhere.
    let has_members = |k: &str| slot.get(k).is_some_and(|&s| !lists[s].is_empty());
    let unmatched = keys
        .iter()
        .flat_map(|(a, b)| [a, b])
        .any(|k| !has_members(k));
    let by_name = if unmatched {
        array_vars_by_name(model)
    } else {
        HashMap::default()
    };
    let element = |k: &str| -> Option<(usize, u32)> {
        if has_members(k) {
            None
        } else {
            element_of(model, &by_name, k)
        }
    };
    let mut split = vec![false; if unmatched { model.vars.len() } else { 0 }];
    for (ka, kb) in &keys {
        for (v, _) in [element(ka), element(kb)].into_iter().flatten() {
            split[v] = true;
        }
    }
    let element_members: Vec<(Members, Members)> = keys
        .iter()
        .map(|(ka, kb)| {
            let one = |k: &str| element(k).map(|(v, _)| vec![("", v)]).unwrap_or_default();
            (one(ka), one(kb))
        })
        .collect();
    let none = Vec::new();
    for (k, (c, (ka, kb))) in connects.iter().zip(&keys).enumerate() {
        // A connection to an absent conditional component is dropped (spec 4.4.5).
        if absent.iter().any(|a| inside(ka, a) || inside(kb, a)) {
            continue;
        }
        let (ea, eb) = (element(ka), element(kb));
        let ma = match (ea, slot.get(ka.as_str())) {
            (Some(_), _) => &element_members[k].0,
            (None, Some(&s)) => &lists[s],
            (None, None) => &none,
        };
        let mb = match (eb, slot.get(kb.as_str())) {
            (Some(_), _) => &element_members[k].1,
            (None, Some(&s)) => &lists[s],
            (None, None) => &none,
        };
        if ma.is_empty() || mb.is_empty() {
            let which = if ma.is_empty() { ka } else { kb };
            diags.push(
                FlatError::NotAConnectorInstance {
                    name: which.to_string(),
                    span: c.span,
                }
                .into(),
            );
            continue;
        }
        if let Some(d) = members_mismatch(c, (ka, kb), ma, mb) {
            diags.push(d);
            continue;
        }
        let sides = ConnectedSides {
            ea,
            eb,
            split: &split,
        };
        connect_members(model, c, &sides, ma, mb, &mut graph, &mut diags);
    }
    let mut new_eqs = Vec::new();
    for set in &graph.sets() {
        set_equations(model, &graph, set, &mut new_eqs);
    }
    unconnected_flow_equations(model, &graph.nodes, &mut new_eqs);
    (new_eqs, diags)
}

/// The array variables of `model` by name.
fn array_vars_by_name(model: &FlatModel) -> HashMap<&str, usize> {
    model
        .vars
        .iter()
        .enumerate()
        .filter(|(_, v)| !v.dims.is_empty())
        .map(|(i, v)| (v.name.as_str(), i))
        .collect()
}

/// The nodes of the connections (whole variables or elements, from either side) in a
/// union-find, with the first `connect` that named each node.
struct ConnectionSets {
    nodes: Vec<Node>,
    parent: Vec<usize>,
    /// The first `connect` that named each node, by node.
    spans: Vec<Option<Span>>,
    /// Node of (variable, outside) at `2 * var + outside`; `usize::MAX`: none yet.
    index: Vec<usize>,
    /// Elements of array variables by (variable, element, outside).
    element_index: HashMap<(usize, u32, bool), usize>,
}

impl ConnectionSets {
    fn new(n_vars: usize) -> Self {
        ConnectionSets {
            nodes: Vec::new(),
            parent: Vec::new(),
            spans: Vec::new(),
            index: vec![usize::MAX; 2 * n_vars],
            element_index: HashMap::default(),
        }
    }

    /// The number of node `n`, added when new.
    fn node(&mut self, n: Node) -> usize {
        let slot = if n.elem == WHOLE {
            &mut self.index[2 * n.var + usize::from(n.outside)]
        } else {
            self.element_index
                .entry((n.var, n.elem, n.outside))
                .or_insert(usize::MAX)
        };
        if *slot == usize::MAX {
            self.nodes.push(n);
            self.parent.push(self.parent.len());
            *slot = self.parent.len() - 1;
        }
        *slot
    }

    /// Puts `a` and `b` in one set; `span` is the `connect` that names them.
    fn connect(&mut self, a: Node, b: Node, span: Span) {
        let na = self.node(a);
        let nb = self.node(b);
        let (ra, rb) = (find(&mut self.parent, na), find(&mut self.parent, nb));
        if ra != rb {
            self.parent[ra] = rb;
        }
        if self.spans.len() < self.nodes.len() {
            self.spans.resize(self.nodes.len(), None);
        }
        self.spans[na].get_or_insert(span);
    }

    /// The nodes grouped by set, in order of first appearance.
    fn sets(&mut self) -> Vec<Vec<usize>> {
        let mut sets: Vec<Vec<usize>> = Vec::new();
        let mut set_of_root: Vec<usize> = vec![usize::MAX; self.nodes.len()];
        for n in 0..self.nodes.len() {
            let r = find(&mut self.parent, n);
            if set_of_root[r] == usize::MAX {
                sets.push(Vec::new());
                set_of_root[r] = sets.len() - 1;
            }
            sets[set_of_root[r]].push(n);
        }
        sets
    }
}

/// `E2006` when the two sides of a `connect` do not have the same variables.
fn members_mismatch(
    c: &Connect,
    (ka, kb): (&str, &str),
    ma: &Members,
    mb: &Members,
) -> Option<Diagnostic> {
    let same = ma.len() == mb.len() && ma.iter().zip(mb).all(|(a, b)| a.0 == b.0);
    if same {
        return None;
    }
    let sa: Vec<&str> = ma.iter().map(|(s, _)| *s).collect();
    let sb: Vec<&str> = mb.iter().map(|(s, _)| *s).collect();
    let missing: Vec<&str> = sa
        .iter()
        .filter(|s| !sb.contains(s))
        .chain(sb.iter().filter(|s| !sa.contains(s)))
        .copied()
        .collect();
    Some(
        FlatError::ConnectorsDiffer {
            a: ka.to_string(),
            b: kb.to_string(),
            one_sided: missing.iter().map(|m| m.to_string()).collect(),
            span: c.span,
        }
        .into(),
    )
}

/// What one `connect` names on each side: the array element, if it names one, and which
/// array variables are connected element by element.
struct ConnectedSides<'s> {
    ea: Option<(usize, u32)>,
    eb: Option<(usize, u32)>,
    split: &'s [bool],
}

/// Connects the variables `ma` and `mb` of the two sides of `c` pairwise (they have the
/// same names), skipping parameters and constants; mismatched pairs are diagnosed.
fn connect_members(
    model: &FlatModel,
    c: &Connect,
    sides: &ConnectedSides<'_>,
    ma: &Members,
    mb: &Members,
    graph: &mut ConnectionSets,
    diags: &mut Vec<Diagnostic>,
) {
    let (ea, eb) = (sides.ea, sides.eb);
    let is_split = |v: usize| sides.split.get(v).copied().unwrap_or(false);
    for ((_, va), (_, vb)) in ma.iter().zip(mb) {
        let (xa, xb) = (&model.vars[*va], &model.vars[*vb]);
        // Parameters and constants of connectors (a signal port's size `n`) are not
        // connected (spec 9.3).
        if is_fixed(xa) || is_fixed(xb) {
            continue;
        }
        // The shape connected on each side: an element is a scalar.
        let (da, db): (&[usize], &[usize]) = (
            if ea.is_some() { &[] } else { &xa.dims },
            if eb.is_some() { &[] } else { &xb.dims },
        );
        if let Some(d) = pair_mismatch(c, xa, xb, da == db) {
            diags.push(d);
            continue;
        }
        // Pairs of primitives: whole variables, one element each, or a split array
        // variable element by element.
        let n_elems: usize = da.iter().product();
        let pairs: Vec<(u32, u32)> = match (ea, eb) {
            (Some((_, a)), Some((_, b))) => vec![(a, b)],
            (Some((_, a)), None) => vec![(a, WHOLE)],
            (None, Some((_, b))) => vec![(WHOLE, b)],
            (None, None) if !da.is_empty() && (is_split(*va) || is_split(*vb)) => {
                (0..n_elems as u32).map(|i| (i, i)).collect()
            }
            (None, None) => vec![(WHOLE, WHOLE)],
        };
        for (ia, ib) in pairs {
            let a = Node {
                var: *va,
                elem: ia,
                outside: c.a_outside,
            };
            let b = Node {
                var: *vb,
                elem: ib,
                outside: c.b_outside,
            };
            graph.connect(a, b, c.span);
        }
    }
}

/// Whether `v` is a parameter or a constant.
fn is_fixed(v: &crate::flat::FlatVar) -> bool {
    matches!(
        v.variability,
        crate::flat::Variability::Parameter | crate::flat::Variability::Constant
    )
}

/// `E2006` when `xa` and `xb` differ in flow prefix, shape (`same_shape`) or type;
/// `E2007` when both are outputs connected from inside.
fn pair_mismatch(
    c: &Connect,
    xa: &crate::flat::FlatVar,
    xb: &crate::flat::FlatVar,
    same_shape: bool,
) -> Option<Diagnostic> {
    if xa.flow != xb.flow || !same_shape || !same_kind(&xa.ty, &xb.ty) {
        return Some(
            FlatError::CannotConnect {
                a: xa.name.clone(),
                b: xb.name.clone(),
                why: mismatch(xa, xb),
                span: c.span,
            }
            .into(),
        );
    }
    let both_outputs = xa.causality == Some(unimo_syntax::ast::Causality::Output)
        && xb.causality == Some(unimo_syntax::ast::Causality::Output)
        && !c.a_outside
        && !c.b_outside;
    if both_outputs {
        return Some(
            FlatError::OutputsConnected {
                a: xa.name.clone(),
                b: xb.name.clone(),
                span: c.span,
            }
            .into(),
        );
    }
    None
}

/// The equations of one connection set: the flows sum to zero (inside minus outside),
/// the other variables are equal.
fn set_equations(
    model: &FlatModel,
    graph: &ConnectionSets,
    set: &[usize],
    out: &mut Vec<Equation>,
) {
    let nodes = &graph.nodes;
    let span = set
        .iter()
        .find_map(|&n| graph.spans.get(n).copied().flatten())
        .unwrap_or_default();
    let first = &nodes[set[0]];
    if model.vars[first.var].flow {
        if let Some(sum) = flow_sum(model, nodes, set, span) {
            // Whole array flows (`i_[2]` of a space phasor) sum to an array of zeros.
            let dims: &[usize] = if first.elem == WHOLE {
                &model.vars[first.var].dims
            } else {
                &[]
            };
            out.push(eq(sum, zeros(dims, span), span));
        }
    } else {
        let mut seen = vec![(first.var, first.elem)];
        for &n in &set[1..] {
            let v = (nodes[n].var, nodes[n].elem);
            if seen.contains(&v) {
                continue;
            }
            seen.push(v);
            out.push(eq(
                prim_ref(model, first.var, first.elem, span),
                prim_ref(model, v.0, v.1, span),
                span,
            ));
        }
    }
}

/// The sum of a set's flows, inside ones added and outside ones subtracted.
fn flow_sum(model: &FlatModel, nodes: &[Node], set: &[usize], span: Span) -> Option<Expr> {
    let mut sum: Option<Expr> = None;
    for &n in set {
        let v = prim_ref(model, nodes[n].var, nodes[n].elem, span);
        sum = Some(match (sum, nodes[n].outside) {
            (None, false) => v,
            (None, true) => Expr {
                kind: ExprKind::Unary {
                    op: unimo_syntax::ast::UnaryOp::Neg,
                    operand: Box::new(v),
                },
                span,
            },
            (Some(acc), outside) => Expr {
                kind: ExprKind::Binary {
                    op: if outside {
                        BinaryOp::Sub
                    } else {
                        BinaryOp::Add
                    },
                    lhs: Box::new(acc),
                    rhs: Box::new(v),
                },
                span,
            },
        });
    }
    sum
}

/// `f = 0` for every flow variable (or element) that no connection reaches from inside.
fn unconnected_flow_equations(model: &FlatModel, nodes: &[Node], out: &mut Vec<Equation>) {
    let mut connected_inside = vec![false; model.vars.len()];
    let mut elements_inside: HashMap<usize, Vec<u32>> = HashMap::default();
    for n in nodes {
        if !n.outside {
            if n.elem == WHOLE {
                connected_inside[n.var] = true;
            } else {
                elements_inside.entry(n.var).or_default().push(n.elem);
            }
        }
    }
    for (i, v) in model.vars.iter().enumerate() {
        if let (true, false, Some(done)) = (v.flow, connected_inside[i], elements_inside.get(&i)) {
            // Some elements connected: the others are zero one by one.
            let n: usize = v.dims.iter().product();
            for k in (0..n as u32).filter(|k| !done.contains(k)) {
                out.push(eq(
                    prim_ref(model, i, k, v.origin),
                    Expr {
                        kind: ExprKind::Real(0.0),
                        span: v.origin,
                    },
                    v.origin,
                ));
            }
            continue;
        }
        if v.flow && !connected_inside[i] {
            out.push(eq(
                var_ref(&v.name, v.origin),
                zeros(&v.dims, v.origin),
                v.origin,
            ));
        }
    }
}

/// What differs between two variables that cannot be connected.
fn mismatch(a: &crate::flat::FlatVar, b: &crate::flat::FlatVar) -> String {
    let flow = |v: &crate::flat::FlatVar| {
        if v.flow {
            "a flow variable"
        } else {
            "not a flow variable"
        }
    };
    if a.flow != b.flow {
        format!(
            "`{}` is {}, `{}` is {}: a flow variable connects only to a flow variable",
            a.name,
            flow(a),
            b.name,
            flow(b)
        )
    } else if a.dims != b.dims {
        format!(
            "sizes differ: {} and {}",
            crate::flat::fmt_dims(&a.dims),
            crate::flat::fmt_dims(&b.dims)
        )
    } else {
        format!(
            "types differ: {} and {}",
            crate::flat::type_name(&a.ty),
            crate::flat::type_name(&b.ty)
        )
    }
}

/// Whether two connected variables have compatible types: numbers with numbers
/// (`Real` and `Integer`), Booleans with Booleans, Strings with Strings, an enumeration
/// with the same enumeration.
fn same_kind(a: &crate::flat::FlatType, b: &crate::flat::FlatType) -> bool {
    use crate::flat::FlatType as T;
    match (a, b) {
        (T::Real | T::Integer, T::Real | T::Integer) => true,
        (T::Boolean, T::Boolean) | (T::String, T::String) => true,
        (T::Enumeration { name: x, .. }, T::Enumeration { name: y, .. }) => x == y,
        _ => false,
    }
}

/// `connect(c.p, plug.pin)` where `c` is an array of components: the connector array
/// `c.p` has `c`'s dimension (spec 9.1.3), so the connect is one per element,
/// `connect(c[i].p, plug.pin[i])`. None when no side needs it (the common case: a
/// side whose name some variable starts with is left alone).
fn expand_component_arrays(model: &FlatModel, connects: &[Connect]) -> Option<Vec<Connect>> {
    let mut names: Vec<&str> = model.vars.iter().map(|v| v.name.as_str()).collect();
    names.sort_unstable();
    let has_members = |k: &str| {
        let from = names.partition_point(|n| *n < k);
        names[from..]
            .iter()
            .take_while(|n| n.starts_with(k))
            .any(|n| matches!(n.as_bytes().get(k.len()), None | Some(b'.') | Some(b'[')))
    };
    let unmatched =
        |c: &Connect| !has_members(&var_key_full(&c.a)) || !has_members(&var_key_full(&c.b));
    if !connects.iter().any(unmatched) {
        return None;
    }
    // Highest index of every array prefix: `c[3].p.v` counts 3 for `c`.
    let mut sizes: HashMap<String, usize> = HashMap::default();
    for n in &names {
        for (at, _) in n.match_indices('[') {
            let rest = &n[at + 1..];
            let Some(close) = rest.find(']') else {
                continue;
            };
            if let Ok(i) = rest[..close].parse::<usize>() {
                let e = sizes.entry(n[..at].to_owned()).or_insert(0);
                *e = (*e).max(i);
            }
        }
    }
    // An array of primitive connectors (`RealOutput i[3]`) is one variable with dims.
    for v in &model.vars {
        if let Some(&n) = v.dims.first() {
            let e = sizes.entry(v.name.clone()).or_insert(0);
            *e = (*e).max(n);
        }
    }
    let index = |i: usize, span: Span| {
        Subscript::Expr(Expr {
            kind: ExprKind::Integer(i as i64),
            span,
        })
    };
    // The elements of a side: over the first part, from the left, that names an array
    // of components without a subscript; else over its last part when that is an
    // array of connectors.
    let elements = |r: &ComponentRef, component: bool| -> Option<Vec<ComponentRef>> {
        let mut prefix = String::new();
        for (j, p) in r.parts.iter().enumerate() {
            if j > 0 {
                prefix.push('.');
            }
            prefix.push_str(&p.name.text);
            let last = j + 1 == r.parts.len();
            if p.subscripts.is_empty() && (component != last) {
                if let Some(&n) = sizes.get(&prefix) {
                    return Some(
                        (1..=n)
                            .map(|i| {
                                let mut e = r.clone();
                                e.parts[j].subscripts.push(index(i, r.span));
                                e
                            })
                            .collect(),
                    );
                }
            }
            if !p.subscripts.is_empty() {
                prefix.push_str(&unimo_syntax::print::subscripts(&p.subscripts));
            }
        }
        None
    };
    let mut out = Vec::with_capacity(connects.len());
    for c in connects {
        let (ka, kb) = (var_key_full(&c.a), var_key_full(&c.b));
        let (ma, mb) = (has_members(&ka), has_members(&kb));
        if ma && mb {
            out.push(c.clone());
            continue;
        }
        let side = |r: &ComponentRef, members: bool| {
            if members {
                elements(r, false)
            } else {
                elements(r, true)
            }
        };
        match (side(&c.a, ma), side(&c.b, mb)) {
            (Some(ea), Some(eb)) if ea.len() == eb.len() => {
                for (a, b) in ea.into_iter().zip(eb) {
                    out.push(Connect { a, b, ..c.clone() });
                }
            }
            _ => out.push(c.clone()),
        }
    }
    Some(out)
}

fn var_key_full(r: &ComponentRef) -> String {
    let mut s = var_key(r);
    if let Some(last) = r.parts.last() {
        s.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
    }
    s
}

fn eq(lhs: Expr, rhs: Expr, span: Span) -> Equation {
    Equation {
        kind: EquationKind::Simple { lhs, rhs },
        comment: Default::default(),
        span,
    }
}
