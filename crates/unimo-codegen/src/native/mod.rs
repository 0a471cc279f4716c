//! What native code looks like to the rest of the system: the signatures of the
//! compiled functions and the code attached to a tape ([`NativeTape`]) or to a whole
//! right-hand side ([`NativeRhs`]). The runtime calls them (`unimo_runtime::native`);
//! this crate makes them (`compile_model`) and never calls them itself.
//!
//! The event state is the runtime's: native code receives it as an opaque pointer
//! ([`Events`]) and hands it only to the runtime's one-instruction interpreter
//! ([`ExecuteShim`]), which the caller of `compile_model` supplies.

use std::any::Any;
use std::sync::Arc;

use crate::tape::Op;

/// The runtime's event state as native code sees it: an address it passes on and never
/// reads.
pub enum Events {}

/// The signature of a compiled tape (or of one part of a long one): the register file
/// (pointer and length), the event state, the relation values (read between events)
/// and whether the call is in event mode (1) or not (0).
pub type NativeFn = unsafe extern "C" fn(
    registers: *mut f64,
    n_registers: usize,
    events: *mut Events,
    relations: *const f64,
    event_mode: u32,
);

/// The signature of a compiled right-hand side: the register file, the states
/// (`n_states` values), where the derivatives go (`n_states`), the relation values
/// (null in event mode: the code then decides relations with events by the
/// interpreter's instruction instead of reading them), the event state, the number of
/// registers and the time. Every argument is passed in a machine register (six
/// integer ones and a float one: on x86-64 with the System V convention and on
/// AArch64), so the code of a small step needs no stack frame.
pub type NativeRhsFn = unsafe extern "C" fn(
    registers: *mut f64,
    states: *const f64,
    derivatives: *mut f64,
    relations: *const f64,
    events: *mut Events,
    n_registers: usize,
    time: f64,
);

/// The runtime's interpreter of one instruction, which native code calls for the
/// instructions it does not translate (event-mode relations, samples, tables, held
/// roundings): the instruction, the register file (pointer and length), the event
/// state.
pub type ExecuteShim = unsafe extern "C" fn(
    op: *const Op,
    registers: *mut f64,
    n_registers: usize,
    events: *mut Events,
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

/// Machine code for a whole right-hand side evaluation of a plan that is one explicit
/// step: it writes the time and the states into the register file, runs the step and
/// writes the derivatives to its output, in one call (the per-call bookkeeping of the
/// tape path costs as much as a small model's arithmetic).
///
/// **What it leaves in the register file.** The time and the states of the call, and
/// the values the interpreter's instructions read during the call (samples, tables,
/// held roundings, relations in event mode); the step's other results (algebraic
/// variables, temporaries, the derivatives) stay in machine registers. So after a call
/// the register file holds the plan's inputs but not its values at them: whoever reads
/// the plan's values from the register file runs the plan first (the simulator does:
/// `docs/backend.md`, "One call per right-hand side"). Code compiled with
/// `NativeOptions::poison_unstored` (the default in debug builds) writes NaN to each
/// of those registers instead, so that a reader that does not is seen.
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

mod compile;
mod jit;
pub mod shims;
mod translate;

pub use compile::{compile_model, hot_ops, CodegenError, NativeOptions, NativeStats};
