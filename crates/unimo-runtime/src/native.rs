//! Calling native code: a tape may carry machine code compiled from its instructions
//! (`unimo-codegen`), which [`crate::exec::Run::run`] calls instead of interpreting.
//! The runtime never generates code itself; it only calls what it is given, after
//! checking that the code was compiled from the tape as it is and that the register
//! file and relation state are as large as the code assumes. It also supplies the
//! one-instruction interpreter the code calls back ([`execute_shim`]).

use crate::exec::EventState;
use unimo_codegen::native::{Events, NativeRhs, NativeTape};
use unimo_codegen::tape::Op;

/// The event state as the opaque pointer native code passes on.
fn events_ptr(ev: &mut EventState) -> *mut Events {
    let p: *mut EventState = ev;
    p.cast()
}

/// Calling a tape's code.
pub trait TapeCall {
    /// Whether the code may run on this register file and event state, for a tape of
    /// `n_ops` instructions.
    fn fits(&self, n_ops: usize, registers: &[f64], ev: &EventState) -> bool;
    /// Runs the code. The caller has checked [`TapeCall::fits`].
    fn call(&self, registers: &mut [f64], ev: &mut EventState);
}

impl TapeCall for NativeTape {
    #[inline]
    fn fits(&self, n_ops: usize, registers: &[f64], ev: &EventState) -> bool {
        self.n_ops == n_ops
            && registers.len() >= self.min_registers
            && ev.relations.len() >= self.min_relations
    }

    #[inline]
    fn call(&self, registers: &mut [f64], ev: &mut EventState) {
        call_tape(self, registers, ev)
    }
}

fn call_tape(native: &NativeTape, registers: &mut [f64], ev: &mut EventState) {
    let relations = ev.relations.as_ptr();
    let event_mode = u32::from(ev.event_mode);
    let (regs, n) = (registers.as_mut_ptr(), registers.len());
    let events = events_ptr(ev);
    for f in &native.functions {
        // SAFETY: `unimo-codegen` compiled `f` from this tape's instructions (the
        // count is checked by `fits`); it reads and writes registers below
        // `min_registers <= n` and relation values below `min_relations <=
        // relations.len()` (also checked), and passes `events` only to
        // [`execute_shim`], which does not resize the relation vector, so `relations`
        // stays valid during the call. The code memory is alive: `owner` holds it.
        unsafe { f(regs, n, events, relations, event_mode) };
    }
}

/// Whether a whole right-hand side's code may run: compiled from a plan of one
/// explicit step with `plan_ops` instructions and `n_states` states, on a register file
/// and event state as large as it assumes.
#[inline]
pub fn rhs_fits(
    native: &NativeRhs,
    plan_ops: Option<usize>,
    n_states: usize,
    registers: &[f64],
    ev: &EventState,
) -> bool {
    plan_ops == Some(native.n_ops)
        && n_states == native.n_states
        && registers.len() >= native.min_registers
        && ev.relations.len() >= native.min_relations
}

/// Evaluates the right-hand side. The caller has checked [`rhs_fits`], and `x` and
/// `out` hold `n_states` values each.
#[inline]
pub fn call_rhs(
    native: &NativeRhs,
    t: f64,
    x: &[f64],
    out: &mut [f64],
    registers: &mut [f64],
    ev: &mut EventState,
) {
    assert!(x.len() == native.n_states && out.len() == native.n_states);
    let relations = ev.relations.as_ptr();
    let event_mode = u32::from(ev.event_mode);
    let (regs, n) = (registers.as_mut_ptr(), registers.len());
    let events = events_ptr(ev);
    // SAFETY: as in `call_tape` (the caller checked `rhs_fits`); besides the register
    // file the code reads `n_states` values at `x` and writes `n_states` at `out`, both
    // checked above.
    unsafe {
        (native.function)(
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

/// Executes one instruction with the interpreter's semantics: what native code calls
/// for the instructions it does not translate itself (event-mode relations, samples,
/// tables, held roundings). Pass it to `unimo_codegen::compile_model`.
///
/// # Safety
/// `op` points to a live instruction, `registers` to `n_registers` valid `f64`s and
/// `events` to a live [`EventState`] (cast), none of them borrowed elsewhere during the
/// call.
pub unsafe extern "C" fn execute_shim(
    op: *const Op,
    registers: *mut f64,
    n_registers: usize,
    events: *mut Events,
) {
    // SAFETY: guaranteed by the caller (see above).
    let (op, r, ev) = unsafe {
        (
            *op,
            std::slice::from_raw_parts_mut(registers, n_registers),
            &mut *events.cast::<EventState>(),
        )
    };
    crate::exec::execute(op, r, ev);
}
