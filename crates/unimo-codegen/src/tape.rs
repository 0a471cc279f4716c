//! The compiled form of expressions: a flat list of register instructions. Compiling
//! walks the expression graph once (shared nodes compiled once); evaluating runs the
//! list over a register file with no lookups, allocation or recursion.
//!
//! Relations outside `noEvent` are compiled with an index into the relation state:
//! between events they return the stored value (so the right-hand side stays smooth
//! while the solver steps across a crossing), in event mode they are computed and
//! stored.

use rustc_hash::FxHashMap as HashMap;
use unimo_dae::expr::{ExprArena, ExprId, Fn1, Fn2, Node, RelOp, ScalarId};
use unimo_dae::external::ExtFn;

/// A register index.
pub type Reg = u32;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    Const(Reg, f64),
    Copy(Reg, Reg),
    Add(Reg, Reg, Reg),
    Sub(Reg, Reg, Reg),
    Mul(Reg, Reg, Reg),
    Div(Reg, Reg, Reg),
    Pow(Reg, Reg, Reg),
    /// `x^n` for a small integer `n`.
    Powi(Reg, Reg, i32),
    Neg(Reg, Reg),
    Fn1(Fn1, Reg, Reg),
    Fn2(Fn2, Reg, Reg, Reg),
    /// A relation evaluated literally (inside `noEvent`).
    Rel(RelOp, Reg, Reg, Reg),
    /// A relation with event semantics: relation state index.
    RelEvent(RelOp, Reg, Reg, Reg, u32),
    And(Reg, Reg, Reg),
    Or(Reg, Reg, Reg),
    Not(Reg, Reg),
    /// `dst = if c then a else b` (both operands were computed).
    Select(Reg, Reg, Reg, Reg),
    /// `dst = sample state k` (true only during the event at a sample instant).
    Sample(Reg, u32),
    /// `dst = f(object, a, b)`: a function of the external object whose handle is in
    /// the first register (a table lookup, `unimo_runtime::tables`).
    Ext(ExtFn, Reg, [Reg; 4]),
    /// An event-generating rounding (`floor`, `ceil`, `integer`, and the quotient of
    /// `div`, `mod`, `rem`) of the argument register, held value `k`: computed and
    /// stored in event mode, read between events (MLS 3.7.2).
    Held(Rounding, Reg, Reg, u32),
    /// The interval `(lo, hi)` of the argument in which held value `k` stays valid:
    /// the operands of its two zero crossings `arg - lo` and `arg - hi`.
    HeldBounds(Rounding, Reg, Reg, u32),
}

impl Op {
    /// The registers the instruction writes, in order: one, or two for
    /// `HeldBounds` (`lo`, `hi`). The one home of this fact for the interpreter's
    /// verifier, the cost profile and the native code generator.
    pub fn written(&self) -> impl Iterator<Item = Reg> {
        let (first, second) = match *self {
            Op::HeldBounds(_, lo, hi, _) => (lo, Some(hi)),
            Op::Const(d, _)
            | Op::Copy(d, _)
            | Op::Add(d, ..)
            | Op::Sub(d, ..)
            | Op::Mul(d, ..)
            | Op::Div(d, ..)
            | Op::Pow(d, ..)
            | Op::Powi(d, ..)
            | Op::Neg(d, _)
            | Op::Fn1(_, d, _)
            | Op::Fn2(_, d, ..)
            | Op::Rel(_, d, ..)
            | Op::RelEvent(_, d, ..)
            | Op::And(d, ..)
            | Op::Or(d, ..)
            | Op::Not(d, _)
            | Op::Select(d, ..)
            | Op::Sample(d, _)
            | Op::Ext(_, d, _)
            | Op::Held(_, d, ..) => (d, None),
        };
        std::iter::once(first).chain(second)
    }

    /// The registers the instruction reads, in operand order (`HeldBounds` reads the
    /// held value's state, no register).
    pub fn read(&self) -> Vec<Reg> {
        match *self {
            Op::Const(..) | Op::Sample(..) | Op::HeldBounds(..) => vec![],
            Op::Copy(_, a)
            | Op::Neg(_, a)
            | Op::Not(_, a)
            | Op::Fn1(_, _, a)
            | Op::Powi(_, a, _)
            | Op::Held(_, _, a, _) => vec![a],
            Op::Add(_, a, b)
            | Op::Sub(_, a, b)
            | Op::Mul(_, a, b)
            | Op::Div(_, a, b)
            | Op::Pow(_, a, b)
            | Op::Fn2(_, _, a, b)
            | Op::Rel(_, _, a, b)
            | Op::RelEvent(_, _, a, b, _)
            | Op::And(_, a, b)
            | Op::Or(_, a, b) => vec![a, b],
            Op::Select(_, c, a, b) => vec![c, a, b],
            Op::Ext(_, _, args) => args.to_vec(),
        }
    }
}

/// How an event-generating integer function rounds its argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rounding {
    Floor,
    Ceil,
    /// Towards zero (`div`, `rem`).
    Trunc,
}

impl Rounding {
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Rounding::Floor => x.floor(),
            Rounding::Ceil => x.ceil(),
            Rounding::Trunc => x.trunc(),
        }
    }

    /// The bounds of the arguments that round to `n` (inclusive at the integer).
    pub fn bounds(self, n: f64) -> (f64, f64) {
        match self {
            Rounding::Floor => (n, n + 1.0),
            Rounding::Ceil => (n - 1.0, n),
            Rounding::Trunc if n > 0.0 => (n, n + 1.0),
            Rounding::Trunc if n < 0.0 => (n - 1.0, n),
            Rounding::Trunc => (-1.0, 1.0),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Rounding::Floor => "floor",
            Rounding::Ceil => "ceil",
            Rounding::Trunc => "trunc",
        }
    }
}

/// Where special values live in the register file.
#[derive(Clone, Copy, Debug, Default)]
pub struct Layout {
    pub n_scalars: u32,
    /// Registers `pre_base + s` hold `pre(s)`.
    pub pre_base: u32,
    pub time: Reg,
    pub initial: Reg,
    pub terminal: Reg,
    /// 1 while initialization solves the simplified model of `homotopy` (see
    /// `unimo_dae::expr::Node::HomotopyStart`), else 0.
    pub homotopy: Reg,
    /// First temporary register.
    pub temp_base: u32,
}

impl Layout {
    pub fn new(n_scalars: usize) -> Layout {
        let n = n_scalars as u32;
        Layout {
            n_scalars: n,
            pre_base: n,
            time: 2 * n,
            initial: 2 * n + 1,
            terminal: 2 * n + 2,
            homotopy: 2 * n + 3,
            temp_base: 2 * n + 4,
        }
    }

    pub fn var(&self, s: ScalarId) -> Reg {
        s.0
    }
}

/// A compiled instruction list.
#[derive(Clone, Debug, Default)]
pub struct Tape {
    pub ops: Vec<Op>,
    /// Machine code compiled from `ops`, run instead of the interpreter.
    pub native: Option<crate::native::NativeTape>,
}

impl Tape {
    /// A tape of these instructions (no native code).
    pub fn new(ops: Vec<Op>) -> Tape {
        Tape { ops, native: None }
    }

    /// Whether native code is attached and still matches the instructions.
    pub fn is_native(&self) -> bool {
        self.native
            .as_ref()
            .is_some_and(|n| n.n_ops == self.ops.len())
    }
}

/// Compiles expressions into tapes; temporaries are allocated from a shared counter so
/// that tapes of one model can share the register file.
pub struct Compiler<'a> {
    pub arena: &'a ExprArena,
    pub layout: Layout,
    next_temp: u32,
    /// Relation node -> relation state index (relations with event semantics).
    pub relation_index: &'a HashMap<ExprId, u32>,
    pub sample_index: &'a HashMap<ExprId, u32>,
    /// Event-generating rounding node -> held value index (see [`Op::Held`]).
    pub held_index: Option<&'a HashMap<ExprId, u32>>,
    /// Nodes already computed by earlier, still-valid tapes.
    pub shared: HashMap<ExprId, Reg>,
    /// Constant registers, written once before any tape runs.
    pub constants: Vec<(Reg, f64)>,
    constant_regs: HashMap<u64, Reg>,
}

impl<'a> Compiler<'a> {
    pub fn new(
        arena: &'a ExprArena,
        layout: Layout,
        relation_index: &'a HashMap<ExprId, u32>,
        sample_index: &'a HashMap<ExprId, u32>,
    ) -> Self {
        Compiler {
            arena,
            layout,
            next_temp: layout.temp_base,
            relation_index,
            sample_index,
            held_index: None,
            shared: HashMap::default(),
            constants: Vec::new(),
            constant_regs: HashMap::default(),
        }
    }

    /// Registers in use so far (the register file's size).
    pub fn n_registers(&self) -> usize {
        self.next_temp as usize
    }

    /// Takes over the register counter and constant pool of `other` (two compilers over
    /// different arenas filling one register file).
    pub fn continue_from(&mut self, other: &Compiler<'_>) {
        self.next_temp = other.next_temp;
        self.constants = other.constants.clone();
        self.constant_regs = other.constant_regs.clone();
    }

    /// A fresh temporary register.
    pub fn temp_public(&mut self) -> Reg {
        self.temp()
    }

    fn temp(&mut self) -> Reg {
        let r = self.next_temp;
        self.next_temp += 1;
        r
    }

    /// Compiles `e` into `tape` with a local memo; returns the register with its value.
    pub fn expr(&mut self, e: ExprId, tape: &mut Tape, memo: &mut HashMap<ExprId, Reg>) -> Reg {
        self.expr_in(e, tape, memo, false)
    }

    /// Compiles `e` with every relation compared literally (as under `noEvent`): for
    /// conditions checked after each step, such as assertions.
    pub fn expr_no_event(
        &mut self,
        e: ExprId,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
    ) -> Reg {
        self.expr_in(e, tape, memo, true)
    }

    fn expr_in(
        &mut self,
        e: ExprId,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
        no_event: bool,
    ) -> Reg {
        if let Some(&r) = memo.get(&e).or_else(|| self.shared.get(&e)) {
            return r;
        }
        // Iterative post-order so deep expressions cannot overflow the stack.
        let mut stack: Vec<(ExprId, bool, bool)> = vec![(e, no_event, false)];
        while let Some((x, ne, expanded)) = stack.pop() {
            if memo.contains_key(&x) || self.shared.contains_key(&x) {
                continue;
            }
            let node = self.arena.node(x);
            if self.leaf(x, node, memo) {
                continue;
            }
            let child_ne = ne || matches!(node, Node::NoEvent(_));
            if !expanded {
                stack.push((x, ne, true));
                for (i, c) in self.arena.children(x).enumerate() {
                    // `a + (-b)` is `Sub(a, b)` (see `op_of`): the negation itself is
                    // not computed unless something else needs it.
                    let c = match (node, self.arena.node(c)) {
                        (Node::Add(..), Node::Neg(nb)) if i == 1 => nb,
                        _ => c,
                    };
                    stack.push((c, child_ne, false));
                }
                continue;
            }
            if !ne {
                if let Some(&k) = self.held_index.and_then(|h| h.get(&x)) {
                    let d = self.held(node, k, tape, memo);
                    memo.insert(x, d);
                    continue;
                }
            }
            let out = self.op_of(x, node, ne, memo);
            let op = match out {
                Ok(op) => op,
                Err(alias) => {
                    memo.insert(x, alias);
                    continue;
                }
            };
            let d = self.temp();
            tape.ops.push(with_dst(op, d));
            memo.insert(x, d);
        }
        *memo
            .get(&e)
            .or_else(|| self.shared.get(&e))
            .expect("compiled")
    }

    /// A leaf's register into `memo` (an external output's into `shared`): true when
    /// `node` is a leaf.
    fn leaf(&mut self, x: ExprId, node: Node, memo: &mut HashMap<ExprId, Reg>) -> bool {
        match node {
            Node::Var(s) => {
                memo.insert(x, self.layout.var(s));
            }
            Node::Pre(s) => {
                memo.insert(x, self.layout.pre_base + s.0);
            }
            Node::Time => {
                memo.insert(x, self.layout.time);
            }
            Node::Initial => {
                memo.insert(x, self.layout.initial);
            }
            Node::Terminal => {
                memo.insert(x, self.layout.terminal);
            }
            Node::HomotopyStart => {
                memo.insert(x, self.layout.homotopy);
            }
            Node::External(..) => {
                // Output registers of external objects are allocated up front by
                // `model::compile` (in `shared`); this is only a fallback.
                let reg = self.next_temp;
                self.next_temp += 1;
                self.shared.insert(x, reg);
            }
            Node::Const(bits) => {
                // Constants live in registers of their own, set once.
                let reg = match self.constant_regs.get(&bits) {
                    Some(&r) => r,
                    None => {
                        let r = self.temp();
                        self.constant_regs.insert(bits, r);
                        self.constants.push((r, f64::from_bits(bits)));
                        r
                    }
                };
                memo.insert(x, reg);
            }
            _ => return false,
        }
        true
    }

    /// The operation computing the interior node `x` from its compiled children, or
    /// Err(the register) of a node that is its child's value (`noEvent`).
    fn op_of(
        &self,
        x: ExprId,
        node: Node,
        ne: bool,
        memo: &HashMap<ExprId, Reg>,
    ) -> Result<Op, Reg> {
        let shared = &self.shared;
        let memo_ref = memo;
        let g = |c: ExprId| -> Reg {
            *memo_ref
                .get(&c)
                .or_else(|| shared.get(&c))
                .expect("children first")
        };
        let known = |c: ExprId| memo_ref.get(&c).or_else(|| shared.get(&c)).copied();
        match node {
            Node::Const(b) => Ok(Op::Const(0, f64::from_bits(b))),
            Node::NoEvent(a) => Err(g(a)),
            Node::Add(a, b) => match self.arena.node(b) {
                Node::Neg(nb) if known(nb).is_some() => {
                    Ok(Op::Sub(0, g(a), known(nb).expect("checked")))
                }
                _ => Ok(Op::Add(0, g(a), g(b))),
            },
            Node::Mul(a, b) => Ok(Op::Mul(0, g(a), g(b))),
            Node::Div(a, b) => Ok(Op::Div(0, g(a), g(b))),
            Node::Pow(a, b) => Ok(match self.arena.as_const(b) {
                Some(n) if n == n.trunc() && n.abs() <= 16.0 => Op::Powi(0, g(a), n as i32),
                _ => Op::Pow(0, g(a), g(b)),
            }),
            Node::Neg(a) => Ok(Op::Neg(0, g(a))),
            Node::Fn1(f, a) => Ok(Op::Fn1(f, 0, g(a))),
            Node::Fn2(f, a, b) => Ok(Op::Fn2(f, 0, g(a), g(b))),
            Node::Rel(op, a, b) => Ok(match (ne, self.relation_index.get(&x)) {
                (false, Some(&k)) => Op::RelEvent(op, 0, g(a), g(b), k),
                _ => Op::Rel(op, 0, g(a), g(b)),
            }),
            Node::And(a, b) => Ok(Op::And(0, g(a), g(b))),
            Node::Or(a, b) => Ok(Op::Or(0, g(a), g(b))),
            Node::Not(a) => Ok(Op::Not(0, g(a))),
            Node::If(c, a, b) => Ok(Op::Select(0, g(c), g(a), g(b))),
            Node::Ext(f, ops) => Ok(Op::Ext(f, 0, ops.map(g))),
            Node::Sample(..) => Ok(Op::Sample(
                0,
                self.sample_index.get(&x).copied().unwrap_or(0),
            )),
            Node::Var(_) | unimo_dae::run_time_leaf!() => unreachable!("leaves are handled above"),
        }
    }

    /// The register of an already compiled child.
    fn compiled(&self, e: ExprId, memo: &HashMap<ExprId, Reg>) -> Reg {
        *memo
            .get(&e)
            .or_else(|| self.shared.get(&e))
            .expect("children first")
    }

    /// The argument of an event-generating rounding node (the quotient for `div`,
    /// `mod` and `rem`), compiled into `tape`.
    fn held_argument(
        &mut self,
        node: Node,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
    ) -> Reg {
        match node {
            Node::Fn2(_, a, b) => {
                let (ra, rb) = (self.expr(a, tape, memo), self.expr(b, tape, memo));
                let q = self.temp();
                tape.ops.push(Op::Div(q, ra, rb));
                q
            }
            Node::Fn1(_, a) => self.expr(a, tape, memo),
            _ => unreachable!("only roundings are held"),
        }
    }

    /// `floor`, `ceil`, `integer`, `div`, `mod`, `rem` with events: the rounding is
    /// held between events; `mod` and `rem` are `a - held * b`.
    fn held(
        &mut self,
        node: Node,
        k: u32,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
    ) -> Reg {
        let kind = held_rounding(node).expect("only roundings are held");
        let argument = self.held_argument(node, tape, memo);
        let n = self.temp();
        tape.ops.push(Op::Held(kind, n, argument, k));
        match node {
            Node::Fn2(Fn2::Mod | Fn2::Rem, a, b) => {
                let (ra, rb) = (self.compiled(a, memo), self.compiled(b, memo));
                let p = self.temp();
                tape.ops.push(Op::Mul(p, n, rb));
                let d = self.temp();
                tape.ops.push(Op::Sub(d, ra, p));
                d
            }
            _ => n,
        }
    }

    /// The zero crossings of held rounding `e` (index `k`): registers of its argument
    /// and of the bounds `lo`, `hi` of the interval where its value holds, compiled
    /// into `tape`; the crossing functions are `argument - lo` and `argument - hi`.
    pub fn held_crossings(
        &mut self,
        e: ExprId,
        k: u32,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
    ) -> (Reg, Reg, Reg) {
        let node = self.arena.node(e);
        let kind = held_rounding(node).expect("only roundings are held");
        let argument = self.held_argument(node, tape, memo);
        let (lo, hi) = (self.temp(), self.temp());
        tape.ops.push(Op::HeldBounds(kind, lo, hi, k));
        (argument, lo, hi)
    }

    /// Compiles `target := e` (a store into a scalar's register).
    pub fn assign(
        &mut self,
        target: ScalarId,
        e: ExprId,
        tape: &mut Tape,
        memo: &mut HashMap<ExprId, Reg>,
    ) {
        let r = self.expr(e, tape, memo);
        let d = self.layout.var(target);
        if r == d {
            return;
        }
        // The value was just computed into a fresh temporary: the instruction writes
        // the variable instead (one instruction and one store less), and the
        // expression's value is read from the variable from now on.
        if let Some(last) = tape.ops.last_mut() {
            if r + 1 == self.next_temp && retargetable(*last, r) {
                *last = with_dst(*last, d);
                memo.insert(e, d);
                return;
            }
        }
        tape.ops.push(Op::Copy(d, r));
    }
}

/// The rounding of an event-generating integer function node (`integer` is `floor`).
pub fn held_rounding(node: Node) -> Option<Rounding> {
    match node {
        Node::Fn1(Fn1::Floor, _) | Node::Fn2(Fn2::Mod, ..) => Some(Rounding::Floor),
        Node::Fn1(Fn1::Ceil, _) => Some(Rounding::Ceil),
        Node::Fn2(Fn2::Div | Fn2::Rem, ..) => Some(Rounding::Trunc),
        _ => None,
    }
}

/// Whether `op` is a pure arithmetic or logical instruction writing `r` alone (one
/// [`with_dst`] may point elsewhere without changing what else it does): not a copy,
/// constant, relation with events, sample, external call or held rounding.
fn retargetable(op: Op, r: Reg) -> bool {
    let pure = !matches!(
        op,
        Op::Const(..)
            | Op::Copy(..)
            | Op::RelEvent(..)
            | Op::Sample(..)
            | Op::Ext(..)
            | Op::Held(..)
            | Op::HeldBounds(..)
    );
    let mut written = op.written();
    pure && written.next() == Some(r) && written.next().is_none()
}

fn with_dst(op: Op, d: Reg) -> Op {
    match op {
        Op::Add(_, a, b) => Op::Add(d, a, b),
        Op::Sub(_, a, b) => Op::Sub(d, a, b),
        Op::Mul(_, a, b) => Op::Mul(d, a, b),
        Op::Div(_, a, b) => Op::Div(d, a, b),
        Op::Pow(_, a, b) => Op::Pow(d, a, b),
        Op::Powi(_, a, n) => Op::Powi(d, a, n),
        Op::Neg(_, a) => Op::Neg(d, a),
        Op::Fn1(f, _, a) => Op::Fn1(f, d, a),
        Op::Fn2(f, _, a, b) => Op::Fn2(f, d, a, b),
        Op::Rel(o, _, a, b) => Op::Rel(o, d, a, b),
        Op::RelEvent(o, _, a, b, k) => Op::RelEvent(o, d, a, b, k),
        Op::And(_, a, b) => Op::And(d, a, b),
        Op::Or(_, a, b) => Op::Or(d, a, b),
        Op::Not(_, a) => Op::Not(d, a),
        Op::Select(_, c, a, b) => Op::Select(d, c, a, b),
        Op::Sample(_, k) => Op::Sample(d, k),
        Op::Ext(f, _, args) => Op::Ext(f, d, args),
        Op::Held(kind, _, a, k) => Op::Held(kind, d, a, k),
        Op::HeldBounds(..) => op,
        Op::Const(_, x) => Op::Const(d, x),
        Op::Copy(_, a) => Op::Copy(d, a),
    }
}
