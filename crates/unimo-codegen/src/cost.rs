//! Where a compiled model's work goes: plan operations per evaluation, zero crossings
//! and states, attributed to the component instances of the model (`unimo simulate
//! --cost`), so that a user sees what a scene pays for.
//!
//! An explicit step's operations belong to the variables it assigns (the temporaries
//! before an assignment count for it); a Newton block's residual and Jacobian
//! operations are shared among its iteration variables' components. A zero crossing
//! belongs to the component of the first variable its relation names.
//!
//! With the time of each plan step measured during a run
//! (`unimo_runtime::sim::Simulator::profile`), each component also gets its measured share of the time spent
//! evaluating the plan: an explicit step's time split by its operations, a block's
//! (residuals, Jacobians and Newton's work) equally among its iteration variables.

use crate::model::{CompiledModel, CompiledStep};
use crate::tape::{Op, Reg};
use rustc_hash::FxHashMap as HashMap;

/// The cost of one component instance (or of the model's top level).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ComponentCost {
    /// The instance path (`ConstraintSurfaces`, `Ball[2]`), or `(top level)`.
    pub component: String,
    /// Plan operations per evaluation of the right-hand side (blocks' shares
    /// fractional).
    pub ops: f64,
    pub zero_crossings: usize,
    pub states: usize,
    /// Measured seconds of plan evaluation over the run (0 without a profile).
    pub seconds: f64,
}

/// The register an operation writes (the first, for `HeldBounds`).
fn destination(op: &Op) -> Reg {
    op.written()
        .next()
        .expect("every instruction writes a register")
}

/// The first `depth` parts of an instance path (`a.b[2].c` at depth 1: `a`, at depth 2:
/// `a.b[2]`); a name without a component is the top level. `der(x)` is `x`'s.
pub fn component_of(name: &str, depth: usize) -> String {
    let name = name.trim_start_matches("der(").trim_start_matches('\'');
    let mut end = 0;
    let mut parts = 0;
    let mut bracket = 0i32;
    for (k, c) in name.char_indices() {
        match c {
            '[' => bracket += 1,
            ']' => bracket -= 1,
            '.' if bracket == 0 => {
                parts += 1;
                end = k;
                if parts == depth {
                    break;
                }
            }
            _ => {}
        }
    }
    if parts == 0 {
        "(top level)".to_owned()
    } else {
        name[..end].to_owned()
    }
}

/// The first variable a relation's text names (`ConstraintSurfaces.relvtsqrt <= 0.001`;
/// function names, followed by `(`, are skipped).
fn first_name(text: &str) -> &str {
    let is_name = |c: char| c.is_alphanumeric() || matches!(c, '_' | '.' | '[' | ']' | '\'' | ',');
    let mut rest = text;
    loop {
        let Some(start) = rest.find(|c: char| c.is_alphabetic() || c == '_' || c == '\'') else {
            return "";
        };
        rest = &rest[start..];
        let end = rest.find(|c: char| !is_name(c)).unwrap_or(rest.len());
        let (name, after) = rest.split_at(end);
        if !after.trim_start().starts_with('(') {
            return name;
        }
        rest = after;
    }
}

/// The operations of one plan step per component: an explicit step's to the variables
/// it assigns (the temporaries before an assignment count for it), a block's shared
/// equally among its iteration variables' components.
fn step_shares(
    step: &CompiledStep,
    names: &HashMap<Reg, &str>,
    depth: usize,
    out: &mut Vec<(String, f64)>,
) {
    match step {
        CompiledStep::Explicit(tape) => {
            let mut pending = 0usize;
            let mut last = None;
            for op in &tape.ops {
                pending += 1;
                if let Some(n) = names.get(&destination(op)) {
                    let c = component_of(n, depth);
                    out.push((c.clone(), pending as f64));
                    last = Some(c);
                    pending = 0;
                }
            }
            if pending > 0 {
                let c = last.unwrap_or_else(|| "(top level)".to_owned());
                out.push((c, pending as f64));
            }
        }
        CompiledStep::Block(b) => {
            let total = (b.residual_tape.ops.len() + b.jacobian_tape.ops.len()) as f64;
            let share = total / b.names.len().max(1) as f64;
            for n in &b.names {
                out.push((component_of(n, depth), share));
            }
        }
    }
}

impl CompiledModel {
    /// Plan operations, zero crossings and states per component at `depth` levels of
    /// the instance tree, most expensive first.
    pub fn cost_by_component(&self, depth: usize) -> Vec<ComponentCost> {
        self.cost_by_component_timed(depth, &[])
    }

    /// [`Self::cost_by_component`] with the measured seconds of each plan step (as
    /// `unimo_runtime::sim::Simulator::profile` gives them) shared out among the components.
    pub fn cost_by_component_timed(
        &self,
        depth: usize,
        step_seconds: &[f64],
    ) -> Vec<ComponentCost> {
        let names: HashMap<Reg, &str> =
            self.outputs.iter().map(|(n, r)| (*r, n.as_str())).collect();
        let mut by: HashMap<String, ComponentCost> = HashMap::default();
        fn entry(by: &mut HashMap<String, ComponentCost>, c: String) -> &mut ComponentCost {
            by.entry(c).or_insert_with_key(|c| ComponentCost {
                component: c.clone(),
                ..ComponentCost::default()
            })
        }
        let mut shares: Vec<(String, f64)> = Vec::new();
        for (k, step) in self.steps.iter().enumerate() {
            shares.clear();
            step_shares(step, &names, depth, &mut shares);
            let ops: f64 = shares.iter().map(|(_, o)| o).sum();
            let seconds = step_seconds.get(k).copied().unwrap_or(0.0);
            for (c, o) in shares.drain(..) {
                let e = entry(&mut by, c);
                e.ops += o;
                if ops > 0.0 {
                    e.seconds += seconds * o / ops;
                }
            }
        }
        for text in &self.root_names {
            entry(&mut by, component_of(first_name(text), depth)).zero_crossings += 1;
        }
        for n in &self.state_names {
            entry(&mut by, component_of(n, depth)).states += 1;
        }
        let mut out: Vec<ComponentCost> = by.into_values().collect();
        out.sort_by(|a, b| {
            b.ops
                .total_cmp(&a.ops)
                .then(b.zero_crossings.cmp(&a.zero_crossings))
                .then(a.component.cmp(&b.component))
        });
        out
    }
}

#[cfg(test)]
mod tests {
    use super::{component_of, first_name};

    #[test]
    fn components_are_instance_path_prefixes() {
        assert_eq!(component_of("body.frame.r[1]", 1), "body");
        assert_eq!(component_of("body.frame.r[1]", 2), "body.frame");
        assert_eq!(component_of("Ball[2].v[1]", 1), "Ball[2]");
        assert_eq!(component_of("der(Ball[2].v[1])", 1), "Ball[2]");
        assert_eq!(component_of("x", 1), "(top level)");
        assert_eq!(component_of("a[1.5]", 1), "(top level)");
    }

    #[test]
    fn a_relation_is_named_by_its_first_variable() {
        assert_eq!(
            first_name("ConstraintSurfaces.relvtsqrt <= 0.001"),
            "ConstraintSurfaces.relvtsqrt"
        );
        assert_eq!(first_name("t >= 150"), "t");
        assert_eq!(first_name("abs(body.v) > 1e-3"), "body.v");
        assert_eq!(first_name("floor(time / 0.1) (its lower bound)"), "time");
    }
}
