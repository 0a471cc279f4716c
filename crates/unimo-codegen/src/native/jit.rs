//! The Cranelift side: one JIT module per model, one function per part of a tape,
//! linked once; the module's memory lives as long as a tape refers to it.

use crate::native::{ExecuteShim, NativeFn, NativeRhsFn};
use crate::tape::{Op, Reg};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{types, AbiParam, FuncRef, InstBuilder, UserFuncName, Value};
use cranelift_codegen::isa::TargetFrontendConfig;
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Module};
use std::sync::Arc;

use super::translate::{
    locals, registers, rhs_locals, Counts, Interpreted, Params, Signatures, Translator,
};
use super::{CodegenError, NativeOptions, NativeStats};
use crate::model::RegisterUse;
use rustc_hash::FxHashSet as HashSet;

/// The code of one model: the JIT module and the instructions its code hands to the
/// interpreter (their addresses are in the code).
struct NativeCode {
    module: Option<JITModule>,
    _interpreted_ops: Interpreted,
}

// SAFETY: after `finalize_definitions` the module is never used again except by
// `Drop`, which has exclusive access; the machine code it owns is immutable and reads
// no state but its arguments and the boxed instructions (immutable too), so sharing
// and sending it between threads is sound.
unsafe impl Send for NativeCode {}
// SAFETY: see `Send`: nothing reachable through a shared reference is mutated.
unsafe impl Sync for NativeCode {}

impl Drop for NativeCode {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: the last `Arc` is gone, so no `NativeTape` refers to the code and
            // none of its functions can run any more.
            unsafe { module.free_memory() };
        }
    }
}

/// One tape's code.
pub(crate) struct TapeCode {
    pub functions: Vec<NativeFn>,
    /// One past the highest register the tape uses.
    pub min_registers: usize,
    /// One past the highest relation index it reads.
    pub min_relations: usize,
}

/// The compiled tapes of a model.
pub(crate) struct Compiled {
    pub tapes: Vec<TapeCode>,
    pub rhs: Option<RhsCode>,
    pub owner: Arc<dyn std::any::Any + Send + Sync>,
    pub stats: NativeStats,
}

fn new_module(options: &NativeOptions) -> Result<JITModule, CodegenError> {
    let mut flags = settings::builder();
    let set = |f: &mut settings::Builder, k: &str, v: &str| {
        f.set(k, v)
            .map_err(|e| CodegenError::Settings(format!("{k}={v}: {e}")))
    };
    set(&mut flags, "use_colocated_libcalls", "false")?;
    set(&mut flags, "is_pic", "false")?;
    set(&mut flags, "opt_level", options.opt_level)?;
    let verify = if cfg!(debug_assertions) {
        "true"
    } else {
        "false"
    };
    set(&mut flags, "enable_verifier", verify)?;
    let isa = cranelift_native::builder()
        .map_err(|e| CodegenError::UnsupportedHost(e.to_string()))?
        .finish(settings::Flags::new(flags))
        .map_err(|e| CodegenError::Settings(e.to_string()))?;
    Ok(JITModule::new(JITBuilder::with_isa(
        isa,
        default_libcall_names(),
    )))
}

/// A whole right-hand side to compile as one function (see
/// `crate::native::NativeRhs`): the plan's one step and where time, states and
/// derivatives live.
pub(crate) struct RhsSpec<'a> {
    pub ops: &'a [Op],
    /// The index of the step's tape among the tapes compiled with it.
    pub tape: usize,
    pub time: Reg,
    pub states: &'a [Reg],
    pub derivatives: &'a [Reg],
}

/// What the right-hand side function of `spec` runs: a step of at most `chunk`
/// instructions translated into it (with its own local values), a longer one as calls
/// of the step tape's functions (`ids[spec.tape]`).
fn rhs_body<'a>(
    spec: &RhsSpec<'_>,
    ids: &'a [Vec<FuncId>],
    chunk: usize,
    interpreted: &'a mut Interpreted,
) -> (&'a mut Interpreted, HashSet<Reg>, &'a [FuncId]) {
    if spec.ops.len() <= chunk {
        (interpreted, rhs_locals(spec.ops), &[])
    } else {
        (interpreted, HashSet::default(), &ids[spec.tape])
    }
}

/// The compiled right-hand side.
pub(crate) struct RhsCode {
    pub function: NativeRhsFn,
    pub min_registers: usize,
    pub min_relations: usize,
}

/// Compiles every tape (`(name, instructions)`), splitting long ones, and `rhs`.
pub(crate) fn compile(
    tapes: &[(&str, &[Op])],
    rhs: Option<&RhsSpec<'_>>,
    registers: &RegisterUse,
    options: &NativeOptions,
    shim: ExecuteShim,
) -> Result<Compiled, CodegenError> {
    let mut module = new_module(options)?;
    let mut ctx = module.make_context();
    let mut builder_ctx = FunctionBuilderContext::new();
    let mut signature = module.make_signature();
    let ptr = types::I64;
    signature
        .params
        .extend([ptr, ptr, ptr, ptr, types::I32].map(AbiParam::new));
    let mut interpreted_ops = Interpreted {
        shim,
        ops: Vec::new(),
    };
    let mut ids: Vec<Vec<FuncId>> = Vec::with_capacity(tapes.len());
    let mut stats = NativeStats::default();
    let chunk = options.max_ops_per_function.max(1);
    for &(name, ops) in tapes {
        let mut tape_ids = Vec::new();
        for part in ops.chunks(chunk) {
            let id = module
                .declare_anonymous_function(&signature)
                .map_err(|e| compile_error(name, e))?;
            ctx.func.signature = signature.clone();
            ctx.func.name = UserFuncName::user(0, id.as_u32());
            let target = module.target_config();
            let counts = build(
                &mut ctx.func,
                &mut builder_ctx,
                part,
                (&mut interpreted_ops, locals(part, registers)),
                target,
            );
            stats.native_ops += counts.native;
            stats.interpreted_ops += counts.interpreted;
            module
                .define_function(id, &mut ctx)
                .map_err(|e| compile_error(name, e))?;
            if let Some(code) = ctx.compiled_code() {
                stats.code_bytes += code.code_buffer().len();
            }
            module.clear_context(&mut ctx);
            tape_ids.push(id);
        }
        stats.functions += tape_ids.len();
        ids.push(tape_ids);
    }
    let rhs_id = match rhs {
        Some(spec) => Some(define_rhs(
            &mut module,
            (&mut ctx, &mut builder_ctx),
            spec,
            rhs_body(spec, &ids, chunk, &mut interpreted_ops),
            (options.poison_unstored, &mut stats),
        )?),
        None => None,
    };
    module
        .finalize_definitions()
        .map_err(|e| CodegenError::Link(e.to_string()))?;
    let rhs = rhs.zip(rhs_id).map(|(spec, id)| {
        let address = module.get_finalized_function(id);
        RhsCode {
            // SAFETY: built with the signature `NativeRhsFn` describes (six
            // pointer-sized arguments and an `f64`, the platform's C calling
            // convention) and finalized.
            function: unsafe { std::mem::transmute::<*const u8, NativeRhsFn>(address) },
            min_registers: min_registers(spec.ops).max(spec.time as usize + 1).max(
                spec.states
                    .iter()
                    .chain(spec.derivatives)
                    .map(|&r| r as usize + 1)
                    .max()
                    .unwrap_or(0),
            ),
            min_relations: min_relations(spec.ops),
        }
    });
    let codes = tapes
        .iter()
        .zip(&ids)
        .map(|(&(_, ops), tape_ids)| tape_code(&module, ops, tape_ids))
        .collect();
    let owner = Arc::new(NativeCode {
        module: Some(module),
        _interpreted_ops: interpreted_ops,
    });
    Ok(Compiled {
        tapes: codes,
        rhs,
        owner,
        stats,
    })
}

/// One past the highest register `ops` read or write.
fn min_registers(ops: &[Op]) -> usize {
    ops.iter()
        .flat_map(|&op| registers(op))
        .max()
        .map_or(0, |r| r as usize + 1)
}

/// One past the highest relation index `ops` read.
fn min_relations(ops: &[Op]) -> usize {
    ops.iter()
        .filter_map(|op| match *op {
            Op::RelEvent(_, _, _, _, k) => Some(k as usize + 1),
            _ => None,
        })
        .max()
        .unwrap_or(0)
}

fn compile_error(tape: &str, e: impl std::fmt::Display) -> CodegenError {
    CodegenError::Compile {
        tape: tape.to_owned(),
        message: e.to_string(),
    }
}

/// The entry block with the function's parameters: the common ones, and the rest.
fn entry(b: &mut FunctionBuilder<'_>) -> (Params, Vec<Value>) {
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    b.seal_block(entry);
    let p = b.block_params(entry).to_vec();
    let params = Params {
        registers: p[0],
        n_registers: p[1],
        events: p[2],
        relations: p[3],
        event_mode: p[4],
    };
    (params, p[5..].to_vec())
}

/// Builds one function from `ops`.
fn build(
    func: &mut cranelift_codegen::ir::Function,
    builder_ctx: &mut FunctionBuilderContext,
    ops: &[Op],
    (interpreted_ops, local): (&mut Interpreted, HashSet<Reg>),
    target: TargetFrontendConfig,
) -> Counts {
    let call_conv = func.signature.call_conv;
    let mut b = FunctionBuilder::new(func, builder_ctx);
    let (params, _) = entry(&mut b);
    let sigs = Signatures::import(&mut b, call_conv);
    let mut t = Translator::new(&mut b, params, sigs, interpreted_ops, local);
    for &op in ops {
        t.op(op);
    }
    let counts = t.counts;
    b.ins().return_(&[]);
    b.finalize(target);
    counts
}

/// Builds the right-hand side function: time and states into their registers (and
/// known as values), the step's instructions (or, for a step longer than one function,
/// calls of the step's own functions `parts`), the derivatives out. With `poison`, NaN
/// into every register the step computes and the function does not store.
fn build_rhs(
    func: &mut cranelift_codegen::ir::Function,
    builder_ctx: &mut FunctionBuilderContext,
    spec: &RhsSpec<'_>,
    (body, poison): (RhsBody<'_>, bool),
    target: TargetFrontendConfig,
) {
    let call_conv = func.signature.call_conv;
    let mut b = FunctionBuilder::new(func, builder_ctx);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    b.seal_block(entry);
    let p = b.block_params(entry).to_vec();
    let [registers, states, derivatives, relations, events, n_registers, time] = p[..] else {
        unreachable!("the right-hand side's seven parameters")
    };
    // Event mode is a null relation pointer (no values to read).
    let event_mode = b.ins().icmp_imm_u(IntCC::Equal, relations, 0);
    let params = Params {
        registers,
        n_registers,
        events,
        relations,
        event_mode,
    };
    let sigs = Signatures::import(&mut b, call_conv);
    let mut t = Translator::new(&mut b, params, sigs, body.interpreted, body.local.clone());
    t.set(spec.time, time);
    let flags = cranelift_codegen::ir::MemFlagsData::trusted();
    for (k, &r) in spec.states.iter().enumerate() {
        let v = t.b.ins().load(types::F64, flags, states, (k * 8) as i32);
        t.set(r, v);
    }
    if body.parts.is_empty() {
        for &op in spec.ops {
            t.op(op);
        }
    } else {
        let mode = t.b.ins().uextend(types::I32, event_mode);
        let common = [registers, n_registers, events, relations, mode];
        for &part in &body.parts {
            t.b.ins().call(part, &common);
        }
        // The parts wrote the register file: nothing known before is current.
        t.forget();
    }
    for (k, &r) in spec.derivatives.iter().enumerate() {
        let v = t.get(r);
        t.b.ins().store(flags, v, derivatives, (k * 8) as i32);
    }
    if poison {
        let nan = t.b.ins().f64const(f64::NAN);
        let mut unstored: Vec<Reg> = body.local.into_iter().collect();
        unstored.sort_unstable();
        for r in unstored {
            t.b.ins().store(flags, nan, registers, (r as i32) * 8);
        }
    }
    b.ins().return_(&[]);
    b.finalize(target);
}

/// What the right-hand side function is made of besides its specification.
pub(crate) struct RhsBody<'a> {
    pub interpreted: &'a mut Interpreted,
    /// Results kept as values only (see `translate::locals`).
    pub local: HashSet<Reg>,
    /// The step's own functions when it is longer than one function (they are called
    /// in order instead of translating the instructions again), else empty.
    pub parts: Vec<FuncRef>,
}

/// Declares, builds and defines the right-hand side function of `spec` (with
/// `poison`: see `NativeOptions::poison_unstored`).
fn define_rhs(
    module: &mut JITModule,
    (ctx, builder_ctx): (&mut cranelift_codegen::Context, &mut FunctionBuilderContext),
    spec: &RhsSpec<'_>,
    (interpreted, local, parts): (&mut Interpreted, HashSet<Reg>, &[FuncId]),
    (poison, stats): (bool, &mut NativeStats),
) -> Result<FuncId, CodegenError> {
    // `NativeRhsFn`: six pointer-sized arguments and the time.
    let ptr = types::I64;
    let mut rhs_signature = module.make_signature();
    rhs_signature
        .params
        .extend([ptr, ptr, ptr, ptr, ptr, ptr, types::F64].map(AbiParam::new));
    let id = module
        .declare_anonymous_function(&rhs_signature)
        .map_err(|e| compile_error("right-hand side", e))?;
    ctx.func.signature = rhs_signature;
    ctx.func.name = UserFuncName::user(0, id.as_u32());
    let target = module.target_config();
    let parts = parts
        .iter()
        .map(|&part| module.declare_func_in_func(part, &mut ctx.func))
        .collect();
    let body = RhsBody {
        interpreted,
        local,
        parts,
    };
    build_rhs(&mut ctx.func, builder_ctx, spec, (body, poison), target);
    module
        .define_function(id, ctx)
        .map_err(|e| compile_error("right-hand side", e))?;
    if let Some(code) = ctx.compiled_code() {
        stats.code_bytes += code.code_buffer().len();
    }
    module.clear_context(ctx);
    stats.functions += 1;
    Ok(id)
}

/// The finalized functions of one tape.
fn tape_code(module: &JITModule, ops: &[Op], ids: &[FuncId]) -> TapeCode {
    TapeCode {
        functions: ids
            .iter()
            .map(|&id| {
                let address = module.get_finalized_function(id);
                // SAFETY: the function was built with the signature `NativeFn`
                // describes (four pointers and an `i32`, the platform's C calling
                // convention) and is finalized.
                unsafe { std::mem::transmute::<*const u8, NativeFn>(address) }
            })
            .collect(),
        min_registers: min_registers(ops),
        min_relations: min_relations(ops),
    }
}
