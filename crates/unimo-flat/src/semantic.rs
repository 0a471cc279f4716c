//! Semantic checks on the flat model that need the whole of it: parameters and
//! constants whose bindings depend on each other in a cycle (spec 4.4.4: a binding may
//! not depend on itself, directly or through other bindings), and bindings of higher
//! variability than their variable (spec 3.8: a parameter's binding reads parameters
//! and constants only, never `time` or a time-varying variable).

use crate::error::FlatError;
use crate::eval::var_key;
use crate::flat::{for_each_ref, for_each_value_ref, FlatModel, Variability};
use rustc_hash::FxHashMap as HashMap;
use unimo_source::Diagnostic;

/// `E2008` for every cycle among the bindings of parameters and constants, once per
/// cycle, at the binding of its first member, naming the whole cycle.
pub(crate) fn parameter_cycles(model: &FlatModel) -> Vec<Diagnostic> {
    let index: HashMap<&str, usize> = model
        .vars
        .iter()
        .enumerate()
        .filter(|(_, v)| {
            matches!(
                v.variability,
                Variability::Parameter | Variability::Constant
            )
        })
        .map(|(k, v)| (v.name.as_str(), k))
        .collect();
    // Edges: a parameter's binding -> the parameters it reads.
    let mut edges: Vec<Vec<usize>> = vec![Vec::new(); model.vars.len()];
    for (k, v) in model.vars.iter().enumerate() {
        if !index.contains_key(v.name.as_str()) {
            continue;
        }
        let Some(b) = &v.binding else { continue };
        let mut out = Vec::new();
        for_each_ref(b, &mut |r| {
            let key = var_key(r);
            if let Some(&j) = index.get(key.as_str()) {
                out.push(j);
            }
        });
        out.sort_unstable();
        out.dedup();
        edges[k] = out;
    }
    let mut diags = Vec::new();
    for cycle in cycles(&edges) {
        let first = &model.vars[cycle[0]];
        let mut names: Vec<&str> = cycle.iter().map(|&k| model.vars[k].name.as_str()).collect();
        names.push(first.name.as_str());
        let span = first.binding.as_ref().map_or(first.origin, |b| b.span);
        diags.push(
            if cycle.len() == 1 {
                FlatError::SelfDependentBinding {
                    name: first.name.clone(),
                    span,
                }
            } else {
                FlatError::BindingCycle {
                    names: names.iter().map(|n| n.to_string()).collect(),
                    span,
                }
            }
            .into(),
        );
    }
    diags
}

/// `E2019` for a parameter or constant whose binding reads `time` or a variable that
/// is not a parameter or constant.
pub(crate) fn binding_variability(model: &FlatModel) -> Vec<Diagnostic> {
    let index = model.var_positions();
    let mut diags = Vec::new();
    for v in &model.vars {
        if !matches!(
            v.variability,
            Variability::Parameter | Variability::Constant
        ) {
            continue;
        }
        let Some(b) = &v.binding else { continue };
        let mut culprit: Option<String> = None;
        for_each_value_ref(b, &mut |r| {
            if culprit.is_some() {
                return;
            }
            let key = var_key(r);
            match index.get(key.as_str()) {
                Some(&j) => {
                    let w = &model.vars[j];
                    if matches!(
                        w.variability,
                        Variability::Discrete | Variability::Continuous
                    ) {
                        culprit = Some(format!("`{}`, a variable that varies in time", w.name));
                    }
                }
                None if key == "time" && !r.global => {
                    culprit = Some("`time`".to_owned());
                }
                None => {}
            }
        });
        if let Some(c) = culprit {
            let kind = if v.variability == Variability::Constant {
                "constant"
            } else {
                "parameter"
            };
            diags.push(
                FlatError::BindingVaries {
                    kind,
                    name: v.name.clone(),
                    reads: c.to_string(),
                    span: b.span,
                }
                .into(),
            );
        }
    }
    diags
}

/// The strongly connected components with a cycle (more than one node, or a node with
/// an edge to itself), each in the order of its nodes' indices (iterative Tarjan).
fn cycles(edges: &[Vec<usize>]) -> Vec<Vec<usize>> {
    const UNSEEN: usize = usize::MAX;
    let n = edges.len();
    let (mut index, mut low) = (vec![UNSEEN; n], vec![0; n]);
    let mut on_stack = vec![false; n];
    let (mut stack, mut out) = (Vec::new(), Vec::new());
    let mut next = 0;
    for root in 0..n {
        if index[root] != UNSEEN || edges[root].is_empty() {
            continue;
        }
        let mut call: Vec<(usize, usize)> = vec![(root, 0)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (v, ref mut i)) = call.last_mut() {
            if let Some(&w) = edges[v].get(*i) {
                *i += 1;
                if index[w] == UNSEEN {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    call.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            call.pop();
            if let Some(&(parent, _)) = call.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    comp.push(w);
                    if w == v {
                        break;
                    }
                }
                if comp.len() > 1 || edges[v].contains(&v) {
                    comp.sort_unstable();
                    out.push(comp);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::cycles;

    #[test]
    fn finds_cycles_and_self_loops_only() {
        // 0 -> 1 -> 0 (cycle), 2 -> 2 (self), 3 -> 0 (reaches a cycle, not in one).
        let edges = vec![vec![1], vec![0], vec![2], vec![0], vec![]];
        assert_eq!(cycles(&edges), vec![vec![0, 1], vec![2]]);
    }
}
