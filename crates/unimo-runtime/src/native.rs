//! The hook for native code: a tape may carry machine code compiled from its
//! instructions (`unimo-codegen`), which [`crate::tape::Tape::run`] calls instead of
//! interpreting. The runtime never generates code itself; it only calls what it is
//! given, after checking that the code was compiled from the tape as it is and that the
//! register file and relation state are as large as the code assumes.

use std::any::Any;
use std::sync::Arc;

use crate::tape::{EventState, Op};

/// The signature of a compiled tape (or of one part of a long one): the register file
/// (pointer and length), the event state, the relation values (read between events)
/// and whether the call is in event mode (1) or not (0).
pub type NativeFn = unsafe extern "C" fn(
    registers: *mut f64,
    n_registers: usize,
    events: *mut EventState,
    relations: *const f64,
    event_mode: u32,
);

/// Machine code for one tape.
#[derive(Clone)]
pub struct NativeTape {
    /// Entry points, called in order (a long tape is split into several functions).
    pub functions: Vec<NativeFn>,
    /// The number of instructions the code was compiled from: a tape whose instruction
    /// list changed afterwards is interpreted.
    pub n_ops: usize,
    /// The code reads and writes registers below this index.
    pub min_registers: usize,
    /// The code reads relation values below this index.
    pub min_relations: usize,
    /// Keeps the code's memory alive as long as a tape refers to it.
    pub owner: Arc<dyn Any + Send + Sync>,
}

impl std::fmt::Debug for NativeTape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NativeTape")
            .field("functions", &self.functions.len())
            .field("n_ops", &self.n_ops)
            .finish()
    }
}

impl NativeTape {
    /// Whether the code may run on this register file and event state.
    #[inline]
    pub fn fits(&self, n_ops: usize, registers: &[f64], ev: &EventState) -> bool {
        self.n_ops == n_ops
            && registers.len() >= self.min_registers
            && ev.relations.len() >= self.min_relations
    }

    /// Runs the code. The caller has checked [`NativeTape::fits`].
    #[inline]
    pub fn call(&self, registers: &mut [f64], ev: &mut EventState) {
        let relations = ev.relations.as_ptr();
        let event_mode = u32::from(ev.event_mode);
        let (regs, n) = (registers.as_mut_ptr(), registers.len());
        let events: *mut EventState = ev;
        for f in &self.functions {
            // SAFETY: `unimo-codegen` compiled `f` from this tape's instructions (the
            // count is checked by `fits`); it reads and writes registers below
            // `min_registers <= n` and relation values below `min_relations <=
            // relations.len()` (also checked), and passes `events` only to the
            // runtime's own `extern "C"` functions (`execute_shim`), which do not
            // resize the relation vector, so `relations` stays valid during the call.
            // The code memory is alive: `owner` holds it.
            unsafe { f(regs, n, events, relations, event_mode) };
        }
    }
}

/// The signature of a compiled right-hand side: [`NativeFn`]'s arguments, then the
/// time, the states (`n_states` values) and where the derivatives go (`n_states`).
pub type NativeRhsFn = unsafe extern "C" fn(
    registers: *mut f64,
    n_registers: usize,
    events: *mut EventState,
    relations: *const f64,
    event_mode: u32,
    time: f64,
    states: *const f64,
    derivatives: *mut f64,
);

/// Machine code for a whole right-hand side evaluation of a plan that is one explicit
/// step: it writes the time and the states into the register file, runs the step and
/// copies the derivatives out, in one call (the per-call bookkeeping of the tape path
/// costs as much as a small model's arithmetic).
#[derive(Clone)]
pub struct NativeRhs {
    pub function: NativeRhsFn,
    /// The number of instructions of the plan's one step the code was compiled from.
    pub n_ops: usize,
    /// The number of states (and derivatives) the code reads (writes).
    pub n_states: usize,
    /// As for [`NativeTape`].
    pub min_registers: usize,
    pub min_relations: usize,
    pub owner: Arc<dyn Any + Send + Sync>,
}

impl std::fmt::Debug for NativeRhs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NativeRhs")
            .field("n_ops", &self.n_ops)
            .field("n_states", &self.n_states)
            .finish()
    }
}

impl NativeRhs {
    /// Whether the code may run: compiled from a plan of one explicit step with `n_ops`
    /// instructions and `n_states` states, on a register file and event state as large
    /// as it assumes.
    #[inline]
    pub fn fits(
        &self,
        plan_ops: Option<usize>,
        n_states: usize,
        registers: &[f64],
        ev: &EventState,
    ) -> bool {
        plan_ops == Some(self.n_ops)
            && n_states == self.n_states
            && registers.len() >= self.min_registers
            && ev.relations.len() >= self.min_relations
    }

    /// Evaluates the right-hand side. The caller has checked [`NativeRhs::fits`], and
    /// `x` and `out` hold `n_states` values each.
    #[inline]
    pub fn call(
        &self,
        t: f64,
        x: &[f64],
        out: &mut [f64],
        registers: &mut [f64],
        ev: &mut EventState,
    ) {
        assert!(x.len() == self.n_states && out.len() == self.n_states);
        let relations = ev.relations.as_ptr();
        let event_mode = u32::from(ev.event_mode);
        let (regs, n) = (registers.as_mut_ptr(), registers.len());
        let events: *mut EventState = ev;
        // SAFETY: as in `NativeTape::call` (the caller checked `fits`); besides the
        // register file the code reads `n_states` values at `x` and writes `n_states`
        // at `out`, both checked above.
        unsafe {
            (self.function)(
                regs,
                n,
                events,
                relations,
                event_mode,
                t,
                x.as_ptr(),
                out.as_mut_ptr(),
            )
        };
    }
}

/// Executes one instruction with the interpreter's semantics: what native code calls
/// for the instructions it does not translate itself (event-mode relations, samples,
/// tables, held roundings).
///
/// # Safety
/// `op` points to a live instruction, `registers` to `n_registers` valid `f64`s and
/// `events` to a live event state, none of them borrowed elsewhere during the call.
pub unsafe extern "C" fn execute_shim(
    op: *const Op,
    registers: *mut f64,
    n_registers: usize,
    events: *mut EventState,
) {
    // SAFETY: guaranteed by the caller (see above).
    let (op, r, ev) = unsafe {
        (
            *op,
            std::slice::from_raw_parts_mut(registers, n_registers),
            &mut *events,
        )
    };
    crate::tape::execute(op, r, ev);
}
