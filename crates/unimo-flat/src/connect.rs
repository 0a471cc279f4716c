//! Connection sets (Modelica spec 9.2): connected potential variables are equal, flow
//! variables sum to zero with inside connectors counted `+` and outside ones `-`, and an
//! unconnected flow variable is zero.

use crate::eval::var_key;
use crate::flat::FlatModel;
use crate::instantiate::Connect;
use rustc_hash::FxHashMap as HashMap;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::{
    BinaryOp, ComponentRef, Equation, EquationKind, Expr, ExprKind, Ident, RefPart,
};

/// A node of the connection graph: a primitive variable seen from one side.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
struct Node {
    var: usize,
    outside: bool,
}

fn find(parent: &mut [usize], x: usize) -> usize {
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

fn var_ref(name: &str, span: Span) -> Expr {
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
    let mut diags = Vec::new();
    let mut nodes: Vec<Node> = Vec::new();
    // Node of (variable, outside) at `2 * var + outside`; `usize::MAX`: none yet.
    let mut index: Vec<usize> = vec![usize::MAX; 2 * model.vars.len()];
    let mut parent: Vec<usize> = Vec::new();
    let mut node = |n: Node, nodes: &mut Vec<Node>, parent: &mut Vec<usize>| -> usize {
        let slot = &mut index[2 * n.var + usize::from(n.outside)];
        if *slot == usize::MAX {
            nodes.push(n);
            parent.push(parent.len());
            *slot = parent.len() - 1;
        }
        *slot
    };
    // The first `connect` that named each node, by node.
    let mut spans: Vec<Option<Span>> = Vec::new();
    let keys: Vec<(String, String)> = connects
        .iter()
        .map(|c| (var_key_full(&c.a), var_key_full(&c.b)))
        .collect();
    let (slot, lists) = members(&model.vars, &keys);
    let none = Vec::new();
    for (c, (ka, kb)) in connects.iter().zip(&keys) {
        // A connection to an absent conditional component is dropped (spec 4.4.5).
        if absent
            .iter()
            .any(|a| ka.starts_with(a.as_str()) || kb.starts_with(a.as_str()))
        {
            continue;
        }
        let ma = slot.get(ka.as_str()).map_or(&none, |&s| &lists[s]);
        let mb = slot.get(kb.as_str()).map_or(&none, |&s| &lists[s]);
        if ma.is_empty() || mb.is_empty() {
            let which = if ma.is_empty() { ka } else { kb };
            diags.push(
                Diagnostic::error("E2006", format!("`{which}` is not a connector instance"))
                    .at(c.span, "in this connect"),
            );
            continue;
        }
        let same = ma.len() == mb.len() && ma.iter().zip(mb).all(|(a, b)| a.0 == b.0);
        if !same {
            let sa: Vec<&str> = ma.iter().map(|(s, _)| *s).collect();
            let sb: Vec<&str> = mb.iter().map(|(s, _)| *s).collect();
            let missing: Vec<&str> = sa
                .iter()
                .filter(|s| !sb.contains(s))
                .chain(sb.iter().filter(|s| !sa.contains(s)))
                .copied()
                .collect();
            diags.push(
                Diagnostic::error(
                    "E2006",
                    format!("connectors `{ka}` and `{kb}` do not match"),
                )
                .at(c.span, "in this connect")
                .with_note(format!(
                    "variables on one side only: {}",
                    missing.join(", ")
                )),
            );
            continue;
        }
        for ((_, va), (_, vb)) in ma.iter().zip(mb) {
            let (xa, xb) = (&model.vars[*va], &model.vars[*vb]);
            // Parameters and constants of connectors (a signal port's size `n`) are not
            // connected (spec 9.3).
            let fixed = |v: &crate::flat::FlatVar| {
                matches!(
                    v.variability,
                    crate::flat::Variability::Parameter | crate::flat::Variability::Constant
                )
            };
            if fixed(xa) || fixed(xb) {
                continue;
            }
            if xa.flow != xb.flow || xa.dims != xb.dims || !same_kind(&xa.ty, &xb.ty) {
                diags.push(
                    Diagnostic::error(
                        "E2006",
                        format!("`{}` and `{}` cannot be connected", xa.name, xb.name),
                    )
                    .at(c.span, "in this connect")
                    .with_note(mismatch(xa, xb)),
                );
                continue;
            }
            let both_outputs = xa.causality == Some(unimo_syntax::ast::Causality::Output)
                && xb.causality == Some(unimo_syntax::ast::Causality::Output)
                && !c.a_outside
                && !c.b_outside;
            if both_outputs {
                diags.push(
                    Diagnostic::error(
                        "E2007",
                        format!("two outputs connected: `{}` and `{}`", xa.name, xb.name),
                    )
                    .at(c.span, "in this connect")
                    .with_help(
                        "an output may drive several inputs, but two outputs cannot be connected",
                    ),
                );
                continue;
            }
            let na = node(
                Node {
                    var: *va,
                    outside: c.a_outside,
                },
                &mut nodes,
                &mut parent,
            );
            let nb = node(
                Node {
                    var: *vb,
                    outside: c.b_outside,
                },
                &mut nodes,
                &mut parent,
            );
            let (ra, rb) = (find(&mut parent, na), find(&mut parent, nb));
            if ra != rb {
                parent[ra] = rb;
            }
            if spans.len() < nodes.len() {
                spans.resize(nodes.len(), None);
            }
            spans[na].get_or_insert(c.span);
        }
    }
    // Group the nodes by set, in order of first appearance.
    let mut sets: Vec<Vec<usize>> = Vec::new();
    let mut set_of_root: Vec<usize> = vec![usize::MAX; nodes.len()];
    for n in 0..nodes.len() {
        let r = find(&mut parent, n);
        if set_of_root[r] == usize::MAX {
            sets.push(Vec::new());
            set_of_root[r] = sets.len() - 1;
        }
        sets[set_of_root[r]].push(n);
    }
    let mut connected_inside = vec![false; model.vars.len()];
    for n in &nodes {
        if !n.outside {
            connected_inside[n.var] = true;
        }
    }
    let mut new_eqs = Vec::new();
    for set in &sets {
        let span = set
            .iter()
            .find_map(|&n| spans.get(n).copied().flatten())
            .unwrap_or_default();
        let first = &nodes[set[0]];
        if model.vars[first.var].flow {
            // Sum of inside minus outside flows is zero.
            let mut sum: Option<Expr> = None;
            for &n in set {
                let v = var_ref(&model.vars[nodes[n].var].name, span);
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
            if let Some(sum) = sum {
                new_eqs.push(eq(
                    sum,
                    Expr {
                        kind: ExprKind::Real(0.0),
                        span,
                    },
                    span,
                ));
            }
        } else {
            let mut seen = vec![first.var];
            for &n in &set[1..] {
                let v = nodes[n].var;
                if seen.contains(&v) {
                    continue;
                }
                seen.push(v);
                new_eqs.push(eq(
                    var_ref(&model.vars[first.var].name, span),
                    var_ref(&model.vars[v].name, span),
                    span,
                ));
            }
        }
    }
    for (i, v) in model.vars.iter().enumerate() {
        if v.flow && !connected_inside[i] {
            new_eqs.push(eq(
                var_ref(&v.name, v.origin),
                Expr {
                    kind: ExprKind::Real(0.0),
                    span: v.origin,
                },
                v.origin,
            ));
        }
    }
    (new_eqs, diags)
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
