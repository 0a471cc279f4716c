//! The structural sparsity pattern of `d der(x) / dx` read off the compiled plan, for
//! models without a symbolic Jacobian (plans with Newton blocks): each register's set of
//! the states it depends on, propagated through the plan's instructions in order; a
//! block's unknowns depend on everything its residuals read. The solvers then take
//! finite differences by groups of structurally orthogonal columns (column colouring)
//! and factor with the sparse LU above `unimo_solve::SPARSE_AUTO_THRESHOLD` states.
//!
//! Cost: linear in the plan's instructions times the sets' sizes; the propagation gives
//! up (the solvers stay dense) once the sets hold more than [`MAX_ENTRIES`] entries in
//! all, which only a nearly dense Jacobian reaches.

use unimo_codegen::model::{CompiledModel, CompiledStep};
use unimo_codegen::tape::{Reg, Tape};
use unimo_solve::SparsityPattern;

/// Total size of the dependency sets above which the pattern is not worth having.
const MAX_ENTRIES: usize = 50_000_000;

/// Each register's states (sorted indices), and the total size of the sets.
struct Dependencies {
    sets: Vec<Vec<u32>>,
    entries: usize,
    scratch: Vec<u32>,
}

impl Dependencies {
    /// `regs` now depends on the union of `reads`' states.
    fn assign(&mut self, written: impl Iterator<Item = Reg>, reads: &[Reg]) {
        self.scratch.clear();
        for &r in reads {
            self.scratch.extend_from_slice(&self.sets[r as usize]);
        }
        if reads.len() > 1 {
            self.scratch.sort_unstable();
            self.scratch.dedup();
        }
        for w in written {
            let set = &mut self.sets[w as usize];
            self.entries = self.entries.saturating_sub(set.len()) + self.scratch.len();
            set.clear();
            set.extend_from_slice(&self.scratch);
        }
    }

    fn run(&mut self, tape: &Tape) {
        for op in &tape.ops {
            self.assign(op.written(), &op.read());
        }
    }

    fn too_big(&self) -> bool {
        self.entries > MAX_ENTRIES
    }
}

/// The pattern of `d der(x) / dx`, or `None` when the model has no states, has dynamic
/// state sets (its states change during the run), a collision world (computed outside
/// the tapes) or the pattern is nearly dense.
pub(super) fn structural_pattern(m: &CompiledModel) -> Option<SparsityPattern> {
    let n = m.states.len();
    if n == 0 || !m.state_sets.is_empty() || m.collision.is_some() {
        return None;
    }
    let mut deps = Dependencies {
        sets: vec![Vec::new(); m.n_registers],
        entries: 0,
        scratch: Vec::new(),
    };
    for (k, &reg) in m.states.iter().enumerate() {
        deps.sets[reg as usize] = vec![k as u32];
    }
    for step in &m.steps {
        match step {
            CompiledStep::Explicit(tape) => deps.run(tape),
            CompiledStep::Block(block) => {
                for &r in &block.iteration {
                    deps.assign(std::iter::once(r), &[]);
                }
                deps.run(&block.residual_tape);
                let reads = block.residuals.clone();
                deps.assign(block.iteration.iter().copied(), &reads);
                // The inner assignments again, now that the unknowns have their sets.
                deps.run(&block.residual_tape);
            }
        }
        if deps.too_big() {
            return None;
        }
    }
    let entries = m
        .derivatives
        .iter()
        .enumerate()
        .flat_map(|(row, &reg)| {
            deps.sets[reg as usize]
                .iter()
                .map(move |&column| (row, column as usize))
        })
        .collect::<Vec<_>>();
    SparsityPattern::from_entries(n, entries).ok()
}
