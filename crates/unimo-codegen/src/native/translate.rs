//! One part of a tape as one Cranelift function, instruction for instruction: every
//! result is stored to its register (later tapes and the simulator read them) and kept
//! in an SSA value, so a register written or read earlier in the function is not
//! loaded again. Arithmetic, comparisons, logic, `Select`, `abs` and `sqrt` are machine
//! instructions (IEEE operations, the same bits as the interpreter); other maths calls
//! the built-ins' own Rust functions; relations with events read the relation state
//! between events and call the interpreter's instruction in event mode; samples,
//! tables and held roundings always call it.

use crate::model::RegisterUse;
use crate::native::ExecuteShim;
use crate::tape::{Op, Reg};
use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    types, AbiParam, BlockArg, InstBuilder, MemFlagsData, SigRef, Signature, Value,
};
use cranelift_frontend::FunctionBuilder;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use unimo_dae::expr::{Fn1, RelOp};

use super::shims;

/// The function's parameters, as values.
pub(crate) struct Params {
    pub registers: Value,
    pub n_registers: Value,
    pub events: Value,
    pub relations: Value,
    pub event_mode: Value,
}

/// Signatures of the functions native code calls.
pub(crate) struct Signatures {
    pub unary: SigRef,
    pub binary: SigRef,
    /// The runtime's one-instruction interpreter ([`ExecuteShim`]).
    pub execute: SigRef,
}

impl Signatures {
    pub fn import(
        b: &mut FunctionBuilder<'_>,
        call_conv: cranelift_codegen::isa::CallConv,
    ) -> Self {
        let ptr = types::I64;
        let mut unary = Signature::new(call_conv);
        unary.params.push(AbiParam::new(types::F64));
        unary.returns.push(AbiParam::new(types::F64));
        let mut binary = unary.clone();
        binary.params.push(AbiParam::new(types::F64));
        let mut execute = Signature::new(call_conv);
        execute
            .params
            .extend([ptr, ptr, ptr, ptr].map(AbiParam::new));
        Signatures {
            unary: b.import_signature(unary),
            binary: b.import_signature(binary),
            execute: b.import_signature(execute),
        }
    }
}

/// An instruction whose address is baked into native code: boxed, so that it stays
/// where it is while the vector holding it grows.
pub(crate) struct PinnedOp(Box<Op>);

/// The instructions native code hands to the runtime's interpreter, and the
/// interpreter's entry (given by the caller of `compile_model`).
pub(crate) struct Interpreted {
    pub shim: ExecuteShim,
    pub ops: Vec<PinnedOp>,
}

/// Counts of what one function does.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Counts {
    /// Instructions translated to machine instructions or maths calls.
    pub native: usize,
    /// Instructions run by a call of the interpreter's instruction.
    pub interpreted: usize,
}

/// Translates instructions into the function being built.
pub(crate) struct Translator<'a, 'b> {
    pub b: &'a mut FunctionBuilder<'b>,
    pub params: Params,
    pub sigs: Signatures,
    /// Registers whose value is known as an SSA value dominating the current point,
    /// with the number of calls made before it was learnt (`u32::MAX` for a local
    /// value). A stored value is loaded again after a call (see [`Translator::get`]).
    known: HashMap<Reg, (Value, u32)>,
    /// Calls emitted so far.
    calls: u32,
    /// Float constants made since the last call, by their bits: a non-zero one costs
    /// two instructions on x86-64 (an integer move and a transfer), so it is made once
    /// between calls (not kept across one: it would be spilled, like a loaded value).
    constants: HashMap<u64, (Value, u32)>,
    /// Registers that no one reads from the register file (see [`locals`]): their
    /// values stay SSA values, never stored.
    local: HashSet<Reg>,
    /// Instructions handed to the interpreter: boxed so that their addresses, baked
    /// into the code, stay valid; kept alive with the code.
    pub interpreted_ops: &'a mut Interpreted,
    pub counts: Counts,
}

const FLAGS: MemFlagsData = MemFlagsData::trusted();

/// The sign bit of an `f64`.
const SIGN: u64 = 1 << 63;

fn offset(r: Reg) -> i32 {
    // Registers are checked below 2^28 before translation.
    (r as i32) * 8
}

impl<'a, 'b> Translator<'a, 'b> {
    pub fn new(
        b: &'a mut FunctionBuilder<'b>,
        params: Params,
        sigs: Signatures,
        interpreted_ops: &'a mut Interpreted,
        local: HashSet<Reg>,
    ) -> Self {
        Translator {
            b,
            params,
            sigs,
            known: HashMap::default(),
            calls: 0,
            constants: HashMap::default(),
            local,
            interpreted_ops,
            counts: Counts::default(),
        }
    }

    /// The value of register `r` at this point: loaded once between calls. A value
    /// that is in the register file is loaded again after a call rather than kept
    /// live across it (every float register is caller-saved: keeping it would spill
    /// it to the stack, a store and a load, and lengthen what the register allocator
    /// works on); a local value is kept.
    pub fn get(&mut self, r: Reg) -> Value {
        if let Some(&(v, since)) = self.known.get(&r) {
            if since == u32::MAX || since == self.calls {
                return v;
            }
        }
        let v = self
            .b
            .ins()
            .load(types::F64, FLAGS, self.params.registers, offset(r));
        self.known.insert(r, (v, self.calls));
        v
    }

    /// Forgets every known value (after a call that wrote the register file).
    pub fn forget(&mut self) {
        self.known.clear();
    }

    /// Stores `v` to register `r` (unless only this function reads it) and remembers it.
    pub fn set(&mut self, r: Reg, v: Value) {
        let since = if self.local.contains(&r) {
            u32::MAX
        } else {
            self.b
                .ins()
                .store(FLAGS, v, self.params.registers, offset(r));
            self.calls
        };
        self.known.insert(r, (v, since));
    }

    /// The float with bits `bits`, made at most once between two calls.
    fn constant(&mut self, bits: u64) -> Value {
        if let Some(&(v, since)) = self.constants.get(&bits) {
            if since == self.calls {
                return v;
            }
        }
        let v = self.b.ins().f64const(f64::from_bits(bits));
        self.constants.insert(bits, (v, self.calls));
        v
    }

    /// 1.0 where `c` is true, else 0.0.
    fn number_of(&mut self, c: Value) -> Value {
        let one = self.constant(1f64.to_bits());
        let zero = self.b.ins().f64const(0.0);
        self.b.ins().select(c, one, zero)
    }

    /// `v != 0.0` (true for NaN, as in Rust).
    fn truthy(&mut self, v: Value) -> Value {
        let zero = self.b.ins().f64const(0.0);
        self.b.ins().fcmp(FloatCC::NotEqual, v, zero)
    }

    fn call(&mut self, sig: SigRef, address: usize, args: &[Value]) -> Option<Value> {
        let callee = self.b.ins().iconst(types::I64, address as i64);
        let call = self.b.ins().call_indirect(sig, callee, args);
        self.calls += 1;
        self.b.inst_results(call).first().copied()
    }

    fn unary_call(&mut self, f: shims::Unary, x: Value) -> Value {
        let sig = self.sigs.unary;
        self.call(sig, f as usize, &[x]).expect("one result")
    }

    fn binary_call(&mut self, f: shims::Binary, x: Value, y: Value) -> Value {
        let sig = self.sigs.binary;
        self.call(sig, f as usize, &[x, y]).expect("one result")
    }

    /// Calls the interpreter on `op`; the registers it writes are loaded again when read.
    fn interpret(&mut self, op: Op) {
        let boxed = PinnedOp(Box::new(op));
        let address = &*boxed.0 as *const Op as usize;
        self.interpreted_ops.ops.push(boxed);
        let p = &self.params;
        let args = [p.registers, p.n_registers, p.events];
        let op_ptr = self.b.ins().iconst(types::I64, address as i64);
        let sig = self.sigs.execute;
        self.call(
            sig,
            self.interpreted_ops.shim as *const () as usize,
            &[op_ptr, args[0], args[1], args[2]],
        );
        for r in written(op) {
            self.known.remove(&r);
        }
        self.counts.interpreted += 1;
    }

    /// Translates one instruction.
    pub fn op(&mut self, op: Op) {
        let ins_count = &mut self.counts.native;
        *ins_count += 1;
        match op {
            Op::Const(d, x) => {
                let v = self.b.ins().f64const(x);
                self.set(d, v);
            }
            Op::Copy(d, a) => {
                let v = self.get(a);
                self.set(d, v);
            }
            Op::Add(d, a, b) | Op::Sub(d, a, b) | Op::Mul(d, a, b) | Op::Div(d, a, b) => {
                let (x, y) = (self.get(a), self.get(b));
                let ins = self.b.ins();
                let v = match op {
                    Op::Add(..) => ins.fadd(x, y),
                    Op::Sub(..) => ins.fsub(x, y),
                    Op::Mul(..) => ins.fmul(x, y),
                    _ => ins.fdiv(x, y),
                };
                self.set(d, v);
            }
            Op::Pow(d, a, b) => {
                let (x, y) = (self.get(a), self.get(b));
                let v = self.binary_call(shims::powf, x, y);
                self.set(d, v);
            }
            Op::Powi(d, a, n) => {
                let x = self.get(a);
                let v = self.powi(x, n);
                self.set(d, v);
            }
            Op::Neg(d, a) => {
                let x = self.get(a);
                // The sign bit flipped (what `fneg` does), with the mask made once.
                let sign = self.constant(SIGN);
                let v = self.b.ins().bxor(x, sign);
                self.set(d, v);
            }
            Op::Fn1(f, d, a) => {
                let x = self.get(a);
                let v = match f {
                    Fn1::Abs => {
                        // The sign bit cleared (what `fabs` does).
                        let magnitude = self.constant(!SIGN);
                        self.b.ins().band(x, magnitude)
                    }
                    Fn1::Sqrt => self.b.ins().sqrt(x),
                    _ => self.unary_call(shims::unary_of(f), x),
                };
                self.set(d, v);
            }
            Op::Fn2(f, d, a, b) => {
                let (x, y) = (self.get(a), self.get(b));
                let v = self.binary_call(shims::binary_of(f), x, y);
                self.set(d, v);
            }
            Op::Rel(rel, d, a, b) => {
                let (x, y) = (self.get(a), self.get(b));
                let c = self.b.ins().fcmp(float_cc(rel), x, y);
                let v = self.number_of(c);
                self.set(d, v);
            }
            Op::RelEvent(_, d, _, _, k) => self.relation_with_events(op, d, k),
            Op::And(d, a, b) | Op::Or(d, a, b) => {
                let (x, y) = (self.get(a), self.get(b));
                let (cx, cy) = (self.truthy(x), self.truthy(y));
                let c = match op {
                    Op::And(..) => self.b.ins().band(cx, cy),
                    _ => self.b.ins().bor(cx, cy),
                };
                let v = self.number_of(c);
                self.set(d, v);
            }
            Op::Not(d, a) => {
                let x = self.get(a);
                let zero = self.b.ins().f64const(0.0);
                let c = self.b.ins().fcmp(FloatCC::Equal, x, zero);
                let v = self.number_of(c);
                self.set(d, v);
            }
            Op::Select(d, c, a, b) => {
                let (vc, x, y) = (self.get(c), self.get(a), self.get(b));
                let cond = self.truthy(vc);
                let v = self.b.ins().select(cond, x, y);
                self.set(d, v);
            }
            Op::Sample(..) | Op::Ext(..) | Op::Held(..) | Op::HeldBounds(..) => {
                self.counts.native -= 1;
                self.interpret(op);
            }
        }
    }

    /// A relation with events: the stored outcome between events, the interpreter's
    /// decision (forced, sticky or literal) in event mode.
    fn relation_with_events(&mut self, op: Op, d: Reg, k: u32) {
        let event = self.b.create_block();
        let between = self.b.create_block();
        let merge = self.b.create_block();
        self.b.append_block_param(merge, types::F64);
        self.b
            .ins()
            .brif(self.params.event_mode, event, &[], between, &[]);
        // Values defined in either branch do not dominate the merge: the register
        // cache must not learn them.
        let saved = (self.known.clone(), self.constants.clone());
        self.b.switch_to_block(event);
        self.b.seal_block(event);
        self.interpret(op);
        self.counts.interpreted -= 1;
        let decided = self
            .b
            .ins()
            .load(types::F64, FLAGS, self.params.registers, offset(d));
        self.b.ins().jump(merge, &[BlockArg::Value(decided)]);
        self.b.switch_to_block(between);
        self.b.seal_block(between);
        let held = self
            .b
            .ins()
            .load(types::F64, FLAGS, self.params.relations, (k as i32) * 8);
        self.b.ins().jump(merge, &[BlockArg::Value(held)]);
        self.b.switch_to_block(merge);
        self.b.seal_block(merge);
        (self.known, self.constants) = saved;
        let v = self.b.block_params(merge)[0];
        self.set(d, v);
    }

    /// `x^n` by the algorithm of `f64::powi` (compiler-builtins' `__powidf2`): square
    /// and multiply from the lowest bit, the reciprocal for a negative `n`. The same
    /// multiplications in the same order give the same bits.
    fn powi(&mut self, x: Value, n: i32) -> Value {
        let mut base = x;
        let mut pow = n.unsigned_abs();
        let mut product: Option<Value> = None;
        loop {
            if pow & 1 != 0 {
                product = Some(match product {
                    Some(p) => self.b.ins().fmul(p, base),
                    None => base,
                });
            }
            pow >>= 1;
            if pow == 0 {
                break;
            }
            base = self.b.ins().fmul(base, base);
        }
        let one = self.constant(1f64.to_bits());
        let product = product.unwrap_or(one);
        if n < 0 {
            self.b.ins().fdiv(one, product)
        } else {
            product
        }
    }
}

fn float_cc(rel: RelOp) -> FloatCC {
    match rel {
        RelOp::Lt => FloatCC::LessThan,
        RelOp::Le => FloatCC::LessThanOrEqual,
        RelOp::Gt => FloatCC::GreaterThan,
        RelOp::Ge => FloatCC::GreaterThanOrEqual,
        RelOp::Eq => FloatCC::Equal,
        RelOp::Ne => FloatCC::NotEqual,
    }
}

/// Whether native code runs `op` by calling the interpreter (always, or in event mode):
/// it reads its operands from the register file and writes its results there.
fn calls_interpreter(op: Op) -> bool {
    matches!(
        op,
        Op::Sample(..) | Op::Ext(..) | Op::Held(..) | Op::HeldBounds(..) | Op::RelEvent(..)
    )
}

/// The registers the function made of `ops` keeps as SSA values only, never stored:
/// private temporaries (one writer, never read by the runtime: [`RegisterUse`]) that
/// one of its machine-code instructions writes and that only later machine-code
/// instructions of the same function read. Every other result is stored, since
/// another function, tape, the interpreter or the runtime may read it.
pub(crate) fn locals(ops: &[Op], registers: &RegisterUse) -> HashSet<Reg> {
    locals_where(ops, |r, count| {
        registers.is_private(r) && registers.reads(r) == count
    })
}

/// The registers a whole right-hand side function (`crate::native::NativeRhs`) made of
/// the plan's one step `ops` keeps as SSA values only: every result of a machine-code
/// instruction that the interpreter's instructions called during the same function do
/// not read and that the step does not read before writing it (a value the next call
/// would read). Other tapes, the simulator and the next pass of the plan do not read
/// them: after a native right-hand side the plan runs again before anything reads its
/// values from the register file (the contract of `NativeRhs`).
pub(crate) fn rhs_locals(ops: &[Op]) -> HashSet<Reg> {
    locals_where(ops, |_, _| true)
}

/// The results of machine-code instructions of `ops` read only by later machine-code
/// instructions of `ops` (`count` times) and for which `unread_elsewhere(r, count)`.
fn locals_where(ops: &[Op], unread_elsewhere: impl Fn(Reg, u32) -> bool) -> HashSet<Reg> {
    let mut reads_here: HashMap<Reg, u32> = HashMap::default();
    let mut shared: HashSet<Reg> = HashSet::default();
    for &op in ops {
        let interpreted = calls_interpreter(op);
        for r in op.read() {
            match reads_here.get_mut(&r) {
                Some(count) if !interpreted => *count += 1,
                _ => {
                    shared.insert(r);
                }
            }
        }
        if !interpreted {
            for r in op.written() {
                reads_here.insert(r, 0);
            }
        }
    }
    reads_here
        .into_iter()
        .filter(|&(r, count)| !shared.contains(&r) && unread_elsewhere(r, count))
        .map(|(r, _)| r)
        .collect()
}

/// The registers an instruction writes (`Op::written`, the tape's own list).
pub(crate) fn written(op: Op) -> Vec<Reg> {
    op.written().collect()
}

/// Every register an instruction reads or writes.
pub(crate) fn registers(op: Op) -> Vec<Reg> {
    let mut out = written(op);
    out.extend(op.read());
    out
}
