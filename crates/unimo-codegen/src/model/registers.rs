//! Who reads each register: the model's instructions (in every tape, hot or cold) and
//! the runtime itself (states, derivatives, outputs, residuals, root operands, `when`
//! conditions and actions, Jacobian entries, the collision world's and the tables'
//! arguments). A temporary that only instructions of one native function read need not
//! be stored to the register file (`native::translate`).

use super::{Action, CompiledModel, CompiledStep};
use crate::tape::{Reg, Tape};

impl CompiledModel {
    /// Every tape of the model, hot and cold: every instruction that may read a register.
    pub fn all_tapes(&self) -> Vec<&Tape> {
        let mut out = vec![
            &self.parameters,
            &self.starts,
            &self.roots_tape,
            &self.when_tape,
            &self.assert_tape,
            &self.alias_tape,
            &self.dependent_parameters,
            &self.initial_tape,
            &self.fixed_constraints_tape,
            &self.objects_tape,
            &self.delay_tape,
        ];
        for step in &self.steps {
            match step {
                CompiledStep::Explicit(t) => out.push(t),
                CompiledStep::Block(b) => out.extend([&b.residual_tape, &b.jacobian_tape]),
            }
        }
        if let Some((t, _)) = &self.jacobian {
            out.push(t);
        }
        out.extend(self.state_sets.iter().map(|s| &s.jacobian_tape));
        if let Some(c) = &self.collision {
            out.push(&c.inputs);
        }
        out
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
        out.extend(&self.delay_inputs);
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

    /// Whether `r` is a temporary that exactly one instruction writes and that the
    /// runtime never reads: its value matters only to the instructions reading it.
    pub fn is_private(&self, r: Reg) -> bool {
        let k = r as usize;
        r >= self.temp_base && k < self.writes.len() && self.writes[k] == 1 && !self.outside[k]
    }
}
