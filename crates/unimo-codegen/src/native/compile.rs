//! Native code for the register tapes: every hot tape of a compiled model
//! (the plan's explicit steps, the Newton blocks' residuals and Jacobians, the zero
//! crossings, the `when` conditions and actions, assertions, aliases, the symbolic
//! Jacobian and the state sets' Jacobians) translated instruction for instruction to
//! machine code with Cranelift and attached to its tape (`Tape::native`), which then
//! runs it instead of the interpreter. The interpreter stays the oracle: native code
//! computes the same bits (see `translate`).
//!
//! Tapes that run once (parameters, start values, initial equations, table arguments,
//! collision-world arguments) stay interpreted: compiling them would cost more than it
//! saves.

use super::jit;
use super::{ExecuteShim, NativeRhs, NativeTape};
use crate::model::{CompiledModel, CompiledStep};
use crate::tape::{Op, Tape};
use std::time::Instant;

/// Why native code could not be made (the model then runs on the tape).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CodegenError {
    #[error("E4601: this machine is not supported by the native code generator: {0}")]
    UnsupportedHost(String),
    #[error("E4602: the native code generator rejected its settings: {0}")]
    Settings(String),
    #[error("E4603: compiling {tape} to native code failed: {message}")]
    Compile { tape: String, message: String },
    #[error("E4604: linking the native code failed: {0}")]
    Link(String),
    #[error("E4605: the register file has {0} registers, more than native code addresses")]
    TooManyRegisters(usize),
}

impl CodegenError {
    /// The code of this error (`E46xx`), which its message also starts with.
    pub fn code(&self) -> &'static str {
        match self {
            CodegenError::UnsupportedHost(_) => "E4601",
            CodegenError::Settings(_) => "E4602",
            CodegenError::Compile { .. } => "E4603",
            CodegenError::Link(_) => "E4604",
            CodegenError::TooManyRegisters(_) => "E4605",
        }
    }
}

/// Choices of the native compilation.
#[derive(Clone, Debug)]
pub struct NativeOptions {
    /// Instructions per native function: a longer tape becomes several functions
    /// called in order (keeps register allocation, which grows faster than the
    /// function, linear in the model).
    pub max_ops_per_function: usize,
    /// Models with more hot instructions than this keep the tape (compiling would
    /// take longer than a short simulation): see `docs/backend.md`.
    pub max_model_ops: usize,
    /// Cranelift's optimisation level: `none`, `speed` or `speed_and_size`.
    pub opt_level: &'static str,
    /// The whole right-hand side function (`NativeRhs`) writes NaN to every register
    /// its step computes but does not store, so that a reader of the register file
    /// that does not run the plan first after a native right-hand side reads NaN
    /// rather than a value of an earlier pass (the differential tests then see it).
    /// On in debug builds.
    pub poison_unstored: bool,
}

impl Default for NativeOptions {
    fn default() -> Self {
        NativeOptions {
            max_ops_per_function: 2_000,
            max_model_ops: 120_000,
            opt_level: "none",
            poison_unstored: cfg!(debug_assertions),
        }
    }
}

/// What the native compilation did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NativeStats {
    /// Tapes that run native code.
    pub tapes: usize,
    /// Native functions made (a long tape is several).
    pub functions: usize,
    /// Instructions translated to machine instructions or maths calls.
    pub native_ops: usize,
    /// Instructions that native code runs by calling the interpreter's instruction
    /// (samples, tables, held roundings; relations with events in event mode only are
    /// not counted here).
    pub interpreted_ops: usize,
    /// Bytes of machine code.
    pub code_bytes: usize,
    /// Wall time of the compilation.
    pub compile_ms: f64,
    /// The model was larger than `max_model_ops`: nothing was compiled.
    pub above_threshold: bool,
}

/// The hot tapes of `m`, with a name for messages.
fn hot_tapes(m: &mut CompiledModel) -> Vec<(String, &mut Tape)> {
    let mut out = Vec::new();
    for (i, step) in m.steps.iter_mut().enumerate() {
        match step {
            CompiledStep::Explicit(t) => out.push((format!("step {i}"), t)),
            CompiledStep::Block(b) => {
                out.push((format!("step {i} (residuals)"), &mut b.residual_tape));
                out.push((format!("step {i} (Jacobian)"), &mut b.jacobian_tape));
            }
        }
    }
    out.push(("zero crossings".into(), &mut m.roots_tape));
    out.push(("when conditions".into(), &mut m.when_tape));
    out.push(("assertions".into(), &mut m.assert_tape));
    out.push(("aliases".into(), &mut m.alias_tape));
    if let Some((t, _)) = &mut m.jacobian {
        out.push(("Jacobian".into(), t));
    }
    for (i, s) in m.state_sets.iter_mut().enumerate() {
        out.push((format!("state set {i} (Jacobian)"), &mut s.jacobian_tape));
    }
    out.retain(|(_, t)| !t.ops.is_empty());
    out
}

/// Instructions the native engine would compile for `m`.
pub fn hot_ops(m: &mut CompiledModel) -> usize {
    hot_tapes(m).iter().map(|(_, t)| t.ops.len()).sum()
}

/// Compiles the hot tapes of `m` to machine code and attaches it to them. On an error
/// nothing is attached (the model stays interpreted and correct). `interpreter` is the
/// runtime's one-instruction interpreter (`unimo_runtime::native::execute_shim`), which
/// the code calls for the instructions it does not translate.
pub fn compile_model(
    m: &mut CompiledModel,
    options: &NativeOptions,
    interpreter: ExecuteShim,
) -> Result<NativeStats, CodegenError> {
    let started = Instant::now();
    let n_registers = m.n_registers;
    // A plan of one explicit step also gets a whole right-hand side function (for a
    // long step, one that calls the step's functions).
    let rhs = m.single_step_ops().and_then(|_| match m.steps.first() {
        Some(CompiledStep::Explicit(t)) => {
            Some((t.ops.clone(), m.states.clone(), m.derivatives.clone()))
        }
        _ => None,
    });
    let time = m.layout.time;
    let registers = crate::model::RegisterUse::of(m);
    let mut tapes = hot_tapes(m);
    let total: usize = tapes.iter().map(|(_, t)| t.ops.len()).sum();
    if total > options.max_model_ops {
        return Ok(NativeStats {
            above_threshold: true,
            compile_ms: started.elapsed().as_secs_f64() * 1e3,
            ..NativeStats::default()
        });
    }
    if n_registers >= 1 << 28 {
        return Err(CodegenError::TooManyRegisters(n_registers));
    }
    let views: Vec<(&str, &[Op])> = tapes
        .iter()
        .map(|(name, t)| (name.as_str(), t.ops.as_slice()))
        .collect();
    // The step is the first hot tape (the steps come first, and a step with
    // instructions is kept).
    let spec = rhs.as_ref().map(|(ops, states, derivatives)| jit::RhsSpec {
        ops,
        tape: 0,
        time,
        states,
        derivatives,
    });
    let compiled = jit::compile(&views, spec.as_ref(), &registers, options, interpreter)?;
    let mut stats = compiled.stats.clone();
    for ((_, tape), code) in tapes.iter_mut().zip(compiled.tapes) {
        tape.native = Some(NativeTape {
            functions: code.functions,
            n_ops: tape.ops.len(),
            min_registers: code.min_registers,
            min_relations: code.min_relations,
            owner: compiled.owner.clone(),
        });
    }
    stats.tapes = tapes.len();
    drop(tapes);
    m.native_rhs = rhs
        .zip(compiled.rhs)
        .map(|((ops, states, _), code)| NativeRhs {
            function: code.function,
            n_ops: ops.len(),
            n_states: states.len(),
            min_registers: code.min_registers,
            min_relations: code.min_relations,
            owner: compiled.owner.clone(),
        });
    stats.compile_ms = started.elapsed().as_secs_f64() * 1e3;
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::CodegenError;

    /// One error of each variant.
    fn samples() -> Vec<CodegenError> {
        vec![
            CodegenError::UnsupportedHost("x".into()),
            CodegenError::Settings("x".into()),
            CodegenError::Compile {
                tape: "t".into(),
                message: "x".into(),
            },
            CodegenError::Link("x".into()),
            CodegenError::TooManyRegisters(1),
        ]
    }

    #[test]
    fn each_code_is_unique_documented_and_starts_its_message() {
        let doc = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/errors.md"),
        )
        .expect("docs/errors.md");
        let mut seen = std::collections::HashSet::new();
        for e in samples() {
            let code = e.code();
            assert!(seen.insert(code), "{code} twice");
            assert!(code.starts_with("E46"), "{code} outside E46xx");
            assert!(
                e.to_string().starts_with(&format!("{code}: ")),
                "{e} does not start with {code}"
            );
            assert!(
                doc.contains(&format!("`{code}`")),
                "{code} not in docs/errors.md"
            );
        }
    }
}
