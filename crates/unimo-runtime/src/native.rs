//! Calling native code: a tape may carry machine code compiled from its instructions
//! (`unimo-codegen`), which [`crate::exec::Run::run`] calls instead of interpreting.
//! The runtime never generates code itself; it only calls what it is given, after
//! checking that the code was compiled from the tape as it is and that the register
//! file and relation state are as large as the code assumes. It also supplies the
//! one-instruction interpreter the code calls back ([`execute_shim`]).

use crate::exec::EventState;
use std::marker::PhantomData;
use unimo_codegen::model::CompiledModel;
use unimo_codegen::native::{Events, NativeRhsFn, NativeTape};
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

/// A model's compiled right-hand side, checked once against the model (see
/// [`RhsCall::new`]), so that a call checks only the lengths of its arguments.
///
/// The code leaves the time and the states in the register file but not the plan's
/// values at them (`unimo_codegen::native::NativeRhs`): a caller that reads the plan's
/// values from the register file after [`RhsCall::call_fitted`] runs the plan first.
#[derive(Clone, Copy)]
pub struct RhsCall<'m> {
    function: NativeRhsFn,
    n_states: usize,
    min_registers: usize,
    min_relations: usize,
    /// The model holds the code's memory (`NativeRhs::owner`) and cannot change while
    /// it is borrowed.
    _model: PhantomData<&'m CompiledModel>,
}

impl<'m> RhsCall<'m> {
    /// The right-hand side code of `m`, when it has some and it was compiled from the
    /// model as it is: a plan of one explicit step with the instruction count the code
    /// was compiled from, the same states, a register file as large as the code uses.
    pub fn new(m: &'m CompiledModel) -> Option<RhsCall<'m>> {
        let native = m.native_rhs.as_ref()?;
        let fits = m.single_step_ops() == Some(native.n_ops)
            && m.states.len() == native.n_states
            && m.derivatives.len() == native.n_states
            && m.n_registers >= native.min_registers;
        fits.then_some(RhsCall {
            function: native.function,
            n_states: native.n_states,
            min_registers: native.min_registers,
            min_relations: native.min_relations,
            _model: PhantomData,
        })
    }

    /// Whether the code may run on `registers` and `ev`: they are as large as it assumes.
    #[inline]
    pub fn fits(&self, registers: &[f64], ev: &EventState) -> bool {
        registers.len() >= self.min_registers && ev.relations.len() >= self.min_relations
    }

    /// Evaluates the right-hand side at `(t, x)` into `out` on `registers` and `ev`
    /// (those of the model `self` was made from); false, doing nothing, when `x` and
    /// `out` do not hold one value per state. The caller checks [`RhsCall::fits`] first:
    /// just before, or once on a register file and relation state that cannot have
    /// shrunk since.
    ///
    /// # Safety
    /// `self.fits(registers, ev)` holds.
    #[inline]
    pub unsafe fn call_fitted(
        &self,
        t: f64,
        x: &[f64],
        out: &mut [f64],
        registers: &mut [f64],
        ev: &mut EventState,
    ) -> bool {
        if x.len() != self.n_states || out.len() != self.n_states {
            return false;
        }
        // In event mode the code reads no relation values (it asks the interpreter).
        let relations = if ev.event_mode {
            std::ptr::null()
        } else {
            ev.relations.as_ptr()
        };
        let (regs, n) = (registers.as_mut_ptr(), registers.len());
        let events = events_ptr(ev);
        // SAFETY: `unimo-codegen` compiled the function from the plan's one step as it
        // is (checked by `new`; the model is borrowed, so it has not changed since), it
        // reads and writes registers below `min_registers <= n`, relation values below
        // `min_relations <= ev.relations.len()` (none in event mode; both guaranteed by
        // the caller), `n_states` values at `x` and `out` (checked above), and passes
        // `events` only to
        // [`execute_shim`], which does not resize the relation vector, so `relations`
        // stays valid during the call. The model holds the code's memory.
        unsafe { (self.function)(regs, x.as_ptr(), out.as_mut_ptr(), relations, events, n, t) };
        true
    }
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
