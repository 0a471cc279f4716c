//! The compiled model's verifier: the invariants the tapes' evaluation relies on
//! without checking them per instruction. Run after every compilation in debug and
//! test builds (`model::compile`), and by `verify_compiled` on demand.
//!
//! Invariants checked:
//! 1. every register an instruction reads or writes lies in the register file;
//! 2. no instruction writes `time`, `initial()` or `terminal()`, nor a `pre(...)`
//!    register except the initial equations' tape (`initial equation pre(y) = y0`)
//!    (the simulator alone sets them);
//! 3. relation, held-rounding and sample indices lie within the event state's arrays;
//! 4. a temporary register is read only after an instruction of the same tape, or of
//!    a tape that always runs before it (the parameter tapes for every other tape, the
//!    plan's earlier steps for a later step), the constants or the collision world
//!    (its outputs, written before the plan) wrote it;
//! 5. the model's per-state, per-block and per-root lists have matching lengths
//!    (states and derivatives, a block's residuals and iteration variables, its
//!    Jacobian `n x n`, each state set's Jacobian `rows x candidates`).

use crate::model::{CompiledModel, CompiledStep};
use crate::tape::{Op, Reg, Tape};

/// A broken invariant: which tape or list, and what.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("compiled model: {place}: {message}")]
pub struct VerifyError {
    pub place: String,
    pub message: String,
}

/// The registers an instruction reads and the ones it writes (the tape's own lists).
fn operands(op: &Op) -> (Vec<Reg>, Vec<Reg>) {
    (op.read(), op.written().collect())
}

struct Checker<'a> {
    m: &'a CompiledModel,
    /// The tape being checked may set `pre` values.
    writes_pre: bool,
    /// Temporaries written so far on the current path (constants first).
    written: Vec<bool>,
}

impl Checker<'_> {
    fn fail(place: &str, message: String) -> Result<(), VerifyError> {
        Err(VerifyError {
            place: place.to_string(),
            message,
        })
    }

    fn tape(&mut self, place: &str, t: &Tape) -> Result<(), VerifyError> {
        let l = &self.m.layout;
        let n = self.m.n_registers as Reg;
        for (i, op) in t.ops.iter().enumerate() {
            let at = format!("{place}, instruction {i}");
            let (reads, writes) = operands(op);
            for &r in reads.iter().chain(&writes) {
                if r >= n {
                    return Self::fail(&at, format!("register {r} outside the file of {n}"));
                }
            }
            for &r in &reads {
                if r >= l.temp_base && !self.written[r as usize] {
                    return Self::fail(
                        &at,
                        format!("temporary t{} read before written", r - l.temp_base),
                    );
                }
            }
            for &w in &writes {
                let special = ((l.pre_base..l.pre_base + l.n_scalars).contains(&w)
                    && !self.writes_pre)
                    || w == l.time
                    || w == l.initial
                    || w == l.terminal;
                if special {
                    return Self::fail(&at, format!("writes the simulator's register {w}"));
                }
                self.written[w as usize] = true;
            }
            let (index, count, what) = match *op {
                Op::RelEvent(.., k) => (k, self.m.root_ops.len(), "relation"),
                Op::Held(.., k) | Op::HeldBounds(.., k) => (k, self.m.n_held, "held rounding"),
                Op::Sample(_, k) => (k, self.m.samples.len(), "sample"),
                _ => continue,
            };
            if index as usize >= count {
                return Self::fail(&at, format!("{what} {index} of {count}"));
            }
        }
        Ok(())
    }

    /// Checks `t` starting from the temporaries written before it, without letting its
    /// writes count for the tapes checked after it.
    fn branch(&mut self, place: &str, t: &Tape) -> Result<(), VerifyError> {
        let saved = self.written.clone();
        let r = self.tape(place, t);
        self.written = saved;
        r
    }
}

fn lengths(m: &CompiledModel) -> Result<(), VerifyError> {
    let fail = |place: &str, message: String| {
        Err(VerifyError {
            place: place.into(),
            message,
        })
    };
    let s = m.states.len();
    if m.derivatives.len() != s || m.nominals.len() != s || m.fixed.len() != s {
        return fail(
            "states",
            format!(
                "{s} states, {} derivatives, {} nominals, {} fixed flags",
                m.derivatives.len(),
                m.nominals.len(),
                m.fixed.len()
            ),
        );
    }
    for (k, step) in m.steps.iter().enumerate() {
        if let CompiledStep::Block(b) = step {
            let n = b.iteration.len();
            if b.residuals.len() != n || b.jacobian.len() != n * n || b.names.len() != n {
                return fail(
                    &format!("step {k}"),
                    format!(
                        "{n} iteration variables, {} residuals, {} Jacobian entries, {} names",
                        b.residuals.len(),
                        b.jacobian.len(),
                        b.names.len()
                    ),
                );
            }
        }
    }
    for (k, set) in m.state_sets.iter().enumerate() {
        if set.jacobian.len() != set.rows * set.candidates.len() {
            return fail(
                &format!("state set {k}"),
                format!(
                    "{} Jacobian entries for {} rows and {} candidates",
                    set.jacobian.len(),
                    set.rows,
                    set.candidates.len()
                ),
            );
        }
    }
    if m.roots.len() < m.root_ops.len() || m.root_names.len() != m.roots.len() {
        return fail(
            "zero crossings",
            format!(
                "{} roots, {} relations, {} names",
                m.roots.len(),
                m.root_ops.len(),
                m.root_names.len()
            ),
        );
    }
    Ok(())
}

/// Checks the invariants in the module docs.
pub fn verify_compiled(m: &CompiledModel) -> Result<(), VerifyError> {
    lengths(m)?;
    let mut c = Checker {
        m,
        writes_pre: false,
        written: vec![false; m.n_registers],
    };
    for &(r, _) in &m.constants {
        if r as usize >= m.n_registers {
            return Checker::fail("constants", format!("register {r} outside the file"));
        }
        c.written[r as usize] = true;
    }
    // Parameters (and the objects' arguments) run first; every other tape after them.
    c.tape("objects", &m.objects_tape)?;
    c.tape("parameters", &m.parameters)?;
    c.tape("dependent parameters", &m.dependent_parameters)?;
    c.branch("start values", &m.starts)?;
    c.branch("fixed constraints", &m.fixed_constraints_tape)?;
    if let Some(cm) = &m.collision {
        c.tape("collision inputs", &cm.inputs)?;
        // The world writes its bodies' forces and torques and its gaps before the plan.
        for &r in cm.bodies.iter().flat_map(|b| &b.outputs).chain(&cm.gaps) {
            if r as usize >= m.n_registers {
                return Checker::fail(
                    "collision outputs",
                    format!("register {r} outside the file"),
                );
            }
            c.written[r as usize] = true;
        }
    }
    // The plan in order: a step may read what earlier steps computed.
    for (k, step) in m.steps.iter().enumerate() {
        match step {
            CompiledStep::Explicit(t) => c.tape(&format!("step {k}"), t)?,
            CompiledStep::Block(b) => {
                c.tape(&format!("step {k} residuals"), &b.residual_tape)?;
                c.branch(&format!("step {k} jacobian"), &b.jacobian_tape)?;
            }
        }
    }
    // Tapes run after a pass of the plan.
    for (place, t) in [
        ("zero crossings", &m.roots_tape),
        ("when conditions", &m.when_tape),
        ("initial equations", &m.initial_tape),
        ("assertions", &m.assert_tape),
        ("invariants", &m.invariant_tape),
        ("aliases", &m.alias_tape),
        ("delay inputs", &m.delay_tape),
    ] {
        c.writes_pre = place == "initial equations";
        c.branch(place, t)?;
    }
    c.writes_pre = false;
    if let Some((t, _)) = &m.jacobian {
        c.branch("symbolic jacobian", t)?;
    }
    for (k, set) in m.state_sets.iter().enumerate() {
        c.branch(&format!("state set {k}"), &set.jacobian_tape)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tape::Layout;

    fn model(ops: Vec<Op>) -> CompiledModel {
        let mut m = CompiledModel {
            layout: Layout::new(2),
            n_registers: 10,
            ..CompiledModel::default()
        };
        m.steps.push(CompiledStep::Explicit(Tape::new(ops)));
        m
    }

    #[test]
    fn a_well_formed_tape_passes() {
        let l = Layout::new(2);
        let t = l.temp_base;
        let m = model(vec![
            Op::Const(t, 2.0),
            Op::Mul(t + 1, t, l.time),
            Op::Copy(1, t + 1),
        ]);
        assert_eq!(verify_compiled(&m), Ok(()));
    }

    #[test]
    fn broken_tapes_are_named() {
        let l = Layout::new(2);
        let t = l.temp_base;
        let cases = [
            (vec![Op::Copy(1, t)], "read before written"),
            (vec![Op::Const(99, 1.0)], "outside the file"),
            (vec![Op::Const(l.pre_base, 1.0)], "simulator's register"),
            (vec![Op::Const(l.time, 1.0)], "simulator's register"),
            (vec![Op::Sample(t, 0)], "sample 0 of 0"),
            (
                vec![Op::RelEvent(unimo_dae::expr::RelOp::Lt, t, 0, 1, 3)],
                "relation 3 of 0",
            ),
        ];
        for (ops, needle) in cases {
            let e = verify_compiled(&model(ops)).unwrap_err();
            assert!(e.to_string().contains(needle), "{e}");
            assert!(e.place.starts_with("step 0"), "{e}");
        }
    }

    #[test]
    fn a_tape_reads_what_an_earlier_step_wrote_but_not_a_jacobian_tape() {
        let l = Layout::new(2);
        let t = l.temp_base;
        let mut m = model(vec![Op::Const(t, 1.0)]);
        m.steps
            .push(CompiledStep::Explicit(Tape::new(vec![Op::Copy(0, t)])));
        assert_eq!(verify_compiled(&m), Ok(()));
        // A temporary only the zero-crossing tape writes is not there for the whens.
        m.roots_tape.ops.push(Op::Const(t + 1, 0.0));
        m.when_tape.ops.push(Op::Copy(1, t + 1));
        let e = verify_compiled(&m).unwrap_err();
        assert_eq!(e.place, "when conditions, instruction 0");
    }
}
