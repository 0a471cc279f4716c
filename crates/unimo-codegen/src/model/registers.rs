//! Who reads each register: the model's instructions (in every tape, hot or cold) and
//! the runtime itself (states, derivatives, outputs, residuals, root operands, `when`
//! conditions and actions, Jacobian entries, the collision world's and the tables'
//! arguments). A temporary that only instructions of one native function read need not
//! be stored to the register file (`native::translate`).

use super::{Action, CompiledModel, CompiledStep};
use crate::tape::{Op, Reg, Tape};

/// Whether running `op` does nothing but write its result registers (no event state,
/// sample, table, FFT or held rounding).
fn pure(op: &Op) -> bool {
    !matches!(
        op,
        Op::RelEvent(..) | Op::Sample(..) | Op::Ext(..) | Op::Held(..) | Op::HeldBounds(..)
    )
}

/// Every tape of a compiled model, as `&` or `&mut` references (one list for both).
macro_rules! every_tape {
    ($m:expr, $($r:tt)+) => {{
        let m = $m;
        let mut out = vec![
            $($r)+ m.parameters,
            $($r)+ m.starts,
            $($r)+ m.roots_tape,
            $($r)+ m.when_tape,
            $($r)+ m.assert_tape,
            $($r)+ m.alias_tape,
            $($r)+ m.dependent_parameters,
            $($r)+ m.initial_tape,
            $($r)+ m.fixed_constraints_tape,
            $($r)+ m.objects_tape,
        ];
        for step in $($r)+ m.steps {
            match step {
                CompiledStep::Explicit(t) => out.push(t),
                CompiledStep::Block(b) => {
                    out.push($($r)+ b.residual_tape);
                    out.push($($r)+ b.jacobian_tape);
                }
            }
        }
        if let Some((t, _)) = $($r)+ m.jacobian {
            out.push(t);
        }
        for s in $($r)+ m.state_sets {
            out.push($($r)+ s.jacobian_tape);
        }
        if let Some(c) = $($r)+ m.collision {
            out.push($($r)+ c.inputs);
        }
        out
    }};
}

impl CompiledModel {
    /// Every tape of the model, hot and cold: every instruction that may read a register.
    pub fn all_tapes(&self) -> Vec<&Tape> {
        every_tape!(self, &)
    }

    /// [`CompiledModel::all_tapes`], to change them.
    fn all_tapes_mut(&mut self) -> Vec<&mut Tape> {
        every_tape!(self, &mut)
    }

    /// Removes every instruction whose results no one reads: a pure instruction (no
    /// event state, sample, table or held rounding) writing private temporaries
    /// ([`RegisterUse::is_private`]) that no instruction reads, until none is left
    /// (removing one may leave its operands unread). Returns how many were removed.
    pub fn remove_dead_instructions(&mut self) -> usize {
        let mut registers = RegisterUse::of(self);
        let mut removed = 0;
        loop {
            let mut changed = false;
            for tape in self.all_tapes_mut() {
                // Backwards, so that an operand freed by a later instruction is seen.
                let mut keep = vec![true; tape.ops.len()];
                for (k, op) in tape.ops.iter().enumerate().rev() {
                    if pure(op) && op.written().all(|r| registers.is_unread(r)) {
                        keep[k] = false;
                        for r in op.read() {
                            registers.reads[r as usize] -= 1;
                        }
                    }
                }
                let before = tape.ops.len();
                let mut flags = keep.into_iter();
                tape.ops.retain(|_| flags.next().unwrap_or(true));
                if tape.ops.len() < before {
                    removed += before - tape.ops.len();
                    changed = true;
                }
            }
            if !changed {
                return removed;
            }
        }
    }

    /// The registers the runtime reads or writes itself, not through an instruction
    /// (with repetitions). Every register below the first temporary (scalars, `pre`
    /// values, time and the flags) counts as read by the runtime, whether listed here
    /// or not.
    pub fn registers_outside_tapes(&self) -> Vec<Reg> {
        let mut out: Vec<Reg> = Vec::new();
        out.extend(self.constants.iter().map(|&(r, _)| r));
        for step in &self.steps {
            if let CompiledStep::Block(b) = step {
                out.extend(&b.iteration);
                out.extend(&b.residuals);
                out.extend(&b.jacobian);
            }
        }
        out.extend(self.roots.iter().flat_map(|&(a, b)| [a, b]));
        out.extend(self.samples.iter().flat_map(|&(a, b)| [a, b]));
        for w in &self.whens {
            for (conditions, actions) in &w.branches {
                out.extend(conditions);
                for a in actions {
                    match *a {
                        Action::Assign { target, value } | Action::Reinit { target, value } => {
                            out.extend([target, value])
                        }
                        Action::Assert { condition, .. } => out.push(condition),
                        Action::Terminate(_) => {}
                    }
                }
            }
        }
        out.extend(&self.conditions);
        out.extend(self.assertions.iter().map(|a| a.0));
        out.extend(&self.states);
        out.extend(&self.derivatives);
        out.extend(&self.discretes);
        out.extend(self.outputs.iter().map(|o| o.1));
        out.extend(self.definitions.keys());
        if let Some((_, entries)) = &self.jacobian {
            out.extend(entries.iter().map(|e| e.2));
        }
        out.extend(self.free_parameters.iter().map(|p| p.0));
        out.extend(&self.initial_residuals);
        for c in &self.fixed_constraints {
            out.extend([c.lhs, c.rhs]);
            out.extend(c.variables.iter().map(|v| v.1));
        }
        out.extend(self.initial_assigned.iter().map(|a| a.0));
        out.extend(&self.initial_pre_assigned);
        for s in &self.objects {
            out.extend(&s.table);
            out.extend(&s.columns);
            out.extend(s.settings);
        }
        for s in &self.state_sets {
            out.extend(&s.candidates);
            out.extend(&s.selectors);
            out.extend(&s.jacobian);
        }
        if let Some(c) = &self.collision {
            for b in &c.bodies {
                out.extend(b.args.to_flat());
                out.extend(b.outputs);
                out.extend(b.velocity_states.iter().flatten());
            }
            out.extend(c.world_args.to_flat());
            out.extend(c.gaps);
        }
        out
    }
}

/// How the registers of a model are used: how many instructions read and write each
/// one, and which ones the runtime reads itself.
#[derive(Clone, Debug)]
pub struct RegisterUse {
    reads: Vec<u32>,
    writes: Vec<u32>,
    outside: Vec<bool>,
    temp_base: Reg,
}

impl RegisterUse {
    /// The use of every register of `m`.
    pub fn of(m: &CompiledModel) -> RegisterUse {
        let n = m.n_registers;
        let mut u = RegisterUse {
            reads: vec![0; n],
            writes: vec![0; n],
            outside: vec![false; n],
            temp_base: m.layout.temp_base,
        };
        let grow = |u: &mut RegisterUse, r: Reg| {
            let need = r as usize + 1;
            if u.reads.len() < need {
                u.reads.resize(need, 0);
                u.writes.resize(need, 0);
                u.outside.resize(need, false);
            }
        };
        for t in m.all_tapes() {
            for op in &t.ops {
                for r in op.read() {
                    grow(&mut u, r);
                    u.reads[r as usize] += 1;
                }
                for r in op.written() {
                    grow(&mut u, r);
                    u.writes[r as usize] += 1;
                }
            }
        }
        for r in m.registers_outside_tapes() {
            grow(&mut u, r);
            u.outside[r as usize] = true;
        }
        u
    }

    /// Instructions of the model that read `r`.
    pub fn reads(&self, r: Reg) -> u32 {
        self.reads.get(r as usize).copied().unwrap_or(0)
    }

    /// Whether `r` is private and no instruction reads it.
    fn is_unread(&self, r: Reg) -> bool {
        self.is_private(r) && self.reads(r) == 0
    }

    /// Whether `r` is a temporary that exactly one instruction writes and that the
    /// runtime never reads: its value matters only to the instructions reading it.
    pub fn is_private(&self, r: Reg) -> bool {
        let k = r as usize;
        r >= self.temp_base && k < self.writes.len() && self.writes[k] == 1 && !self.outside[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::CompiledBlock;
    use crate::tape::Layout;
    use unimo_dae::expr::RelOp;

    /// A block whose residual tape computes two values no one reads (one feeding the
    /// other), a residual the runtime reads, a Jacobian entry, zero-crossing operands
    /// and a relation with events nobody reads (it still decides the relation state).
    #[test]
    fn only_instructions_no_one_reads_are_removed() {
        let layout = Layout::new(2);
        let t = layout.temp_base;
        let (x, y) = (0, 1);
        let mut m = CompiledModel {
            layout,
            n_registers: (t + 10) as usize,
            ..CompiledModel::default()
        };
        m.steps = vec![CompiledStep::Block(CompiledBlock {
            iteration: vec![y],
            residual_tape: Tape::new(vec![
                Op::Mul(t, x, x),
                Op::Add(t + 1, x, x),
                Op::Mul(t + 2, t + 1, x),
                Op::Sub(t + 3, t, y),
            ]),
            residuals: vec![t + 3],
            jacobian_tape: Tape::new(vec![Op::Neg(t + 4, x)]),
            jacobian: vec![t + 4],
            linear: false,
            relations: vec![],
            names: vec!["y".into()],
        })];
        m.roots_tape = Tape::new(vec![
            Op::Add(t + 5, x, y),
            Op::Mul(t + 6, t + 5, t + 5),
            Op::RelEvent(RelOp::Gt, t + 7, x, y, 0),
        ]);
        m.roots = vec![(t + 5, x)];
        assert_eq!(m.remove_dead_instructions(), 3);
        let CompiledStep::Block(b) = &m.steps[0] else {
            unreachable!()
        };
        assert_eq!(
            b.residual_tape.ops,
            [Op::Mul(t, x, x), Op::Sub(t + 3, t, y)]
        );
        assert_eq!(b.jacobian_tape.ops.len(), 1);
        assert_eq!(
            m.roots_tape.ops,
            [
                Op::Add(t + 5, x, y),
                Op::RelEvent(RelOp::Gt, t + 7, x, y, 0)
            ]
        );
        assert_eq!(m.remove_dead_instructions(), 0);
    }
}
