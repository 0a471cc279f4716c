//! The back end's expressions: a hash-consed arena of scalar nodes with simplifying
//! constructors (constant folding, neutral elements, canonical operand order), so equal
//! subexpressions are one node (common subexpressions come for free).

use rustc_hash::FxHashMap as HashMap;
use std::fmt;

/// Index of an expression node in an [`ExprArena`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct ExprId(pub u32);

impl ExprId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Index of a scalar variable (state, algebraic, derivative, discrete, parameter).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct ScalarId(pub u32);

impl ScalarId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The compiled forms of the numeric built-ins: names, evaluation, derivative rules
/// and events come from their entries in `unimo_builtins::BUILTINS`.
pub use unimo_builtins::{Fn1, Fn2};

/// Relational operators, the AST's: a relation is 1.0 when true and 0.0 when false.
pub use unimo_syntax::ast::RelOp;

/// The pattern of the leaves other than constants and variables: the nodes without
/// operands whose value only the run knows (`pre` values, `time`, `initial()`,
/// `terminal()`, the homotopy flag, external outputs). A new leaf of that kind is added
/// here, so that the passes that treat them alike (operands, substitution, linearity,
/// parameter and alias checks, the tape's leaves) see it.
#[macro_export]
macro_rules! run_time_leaf {
    () => {
        $crate::expr::Node::Pre(_)
            | $crate::expr::Node::Time
            | $crate::expr::Node::Initial
            | $crate::expr::Node::Terminal
            | $crate::expr::Node::HomotopyStart
            | $crate::expr::Node::External(..)
    };
}

/// One expression node. Booleans are 1.0/0.0; Integers and enumeration ordinals are
/// exact in f64.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// The bits of an f64 (never -0.0 or a NaN other than the canonical one).
    Const(u64),
    Var(ScalarId),
    /// The value of a variable before the current event (left limit).
    Pre(ScalarId),
    Time,
    Add(ExprId, ExprId),
    Mul(ExprId, ExprId),
    Div(ExprId, ExprId),
    Pow(ExprId, ExprId),
    Neg(ExprId),
    Fn1(Fn1, ExprId),
    Fn2(Fn2, ExprId, ExprId),
    Rel(RelOp, ExprId, ExprId),
    And(ExprId, ExprId),
    Or(ExprId, ExprId),
    Not(ExprId),
    /// `if c then a else b`
    If(ExprId, ExprId, ExprId),
    /// `noEvent(e)`: relations inside never generate events.
    NoEvent(ExprId),
    /// `initial()`: true during initialization.
    Initial,
    /// `terminal()`: true at the end of a successful simulation.
    Terminal,
    /// True while initialization solves the simplified model of `homotopy(actual,
    /// simplified)` (the start of its continuation), false otherwise.
    HomotopyStart,
    /// `sample(start, interval)`: true at the sample instants.
    Sample(ExprId, ExprId),
    /// Output `out` of external object site `site` (a collision body's force and
    /// torque, or the collision world's gaps): computed by the runtime from states and
    /// parameters before each pass of the plan; a leaf for the symbolic layer.
    External(u32, u32),
    /// A function unimo provides for external C code ([`crate::external::ExtFn`]): a
    /// table lookup of an object handle and up to two operands, or a random number
    /// generator's step of up to four state words (unused operands are 0).
    Ext(crate::external::ExtFn, [ExprId; 4]),
}

/// The arena. Nodes are immutable; constructors simplify and share.
#[derive(Clone, Debug, Default)]
pub struct ExprArena {
    nodes: Vec<Node>,
    index: HashMap<Node, ExprId>,
}

fn canonical_bits(x: f64) -> u64 {
    if x == 0.0 {
        0
    } else if x.is_nan() {
        f64::NAN.to_bits()
    } else {
        x.to_bits()
    }
}

impl ExprArena {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    pub fn node(&self, id: ExprId) -> Node {
        self.nodes[id.index()]
    }

    pub(crate) fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    pub fn constant(&mut self, x: f64) -> ExprId {
        self.intern(Node::Const(canonical_bits(x)))
    }

    pub fn boolean(&mut self, b: bool) -> ExprId {
        self.constant(if b { 1.0 } else { 0.0 })
    }

    pub fn zero(&mut self) -> ExprId {
        self.constant(0.0)
    }

    pub fn one(&mut self) -> ExprId {
        self.constant(1.0)
    }

    pub fn var(&mut self, s: ScalarId) -> ExprId {
        self.intern(Node::Var(s))
    }

    pub fn pre(&mut self, s: ScalarId) -> ExprId {
        self.intern(Node::Pre(s))
    }

    pub fn time(&mut self) -> ExprId {
        self.intern(Node::Time)
    }

    pub fn terminal(&mut self) -> ExprId {
        self.intern(Node::Terminal)
    }

    pub fn initial(&mut self) -> ExprId {
        self.intern(Node::Initial)
    }

    /// See [`Node::HomotopyStart`].
    pub fn homotopy_start(&mut self) -> ExprId {
        self.intern(Node::HomotopyStart)
    }

    /// The id of an existing node, if it was ever built.
    pub fn find(&self, n: Node) -> Option<ExprId> {
        self.index.get(&n).copied()
    }

    pub fn external(&mut self, site: u32, out: u32) -> ExprId {
        self.intern(Node::External(site, out))
    }

    /// The value of a constant node.
    pub fn as_const(&self, id: ExprId) -> Option<f64> {
        match self.nodes[id.index()] {
            Node::Const(b) => Some(f64::from_bits(b)),
            _ => None,
        }
    }

    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x + y),
            (Some(0.0), _) => return b,
            (_, Some(0.0)) => return a,
            _ => {}
        }
        if let Node::Neg(nb) = self.node(b) {
            if nb == a {
                return self.zero();
            }
        }
        if let Node::Neg(na) = self.node(a) {
            if na == b {
                return self.zero();
            }
        }
        // Constants last; otherwise a canonical order so `a + b` and `b + a` share.
        let (a, b) = self.canonical(a, b, false);
        self.intern(Node::Add(a, b))
    }

    /// The operands of a commutative node in one order: a constant first
    /// (`constant_first`) or last, otherwise the smaller id first.
    fn canonical(&self, a: ExprId, b: ExprId, constant_first: bool) -> (ExprId, ExprId) {
        let (ca, cb) = (self.as_const(a).is_some(), self.as_const(b).is_some());
        let (late, early) = if constant_first { (cb, ca) } else { (ca, cb) };
        if late || (!early && b < a) {
            (b, a)
        } else {
            (a, b)
        }
    }

    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        if a == b {
            return self.zero();
        }
        let nb = self.neg(b);
        self.add(a, nb)
    }

    pub fn neg(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(b) => self.constant(-f64::from_bits(b)),
            Node::Neg(x) => x,
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(0.0), _) => return a,
            (_, Some(0.0)) => return b,
            (Some(1.0), _) => return b,
            (_, Some(1.0)) => return a,
            (Some(-1.0), _) => return self.neg(b),
            (_, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        // Signs out: (-a) * b = -(a * b).
        if let Node::Neg(x) = self.node(a) {
            let m = self.mul(x, b);
            return self.neg(m);
        }
        if let Node::Neg(y) = self.node(b) {
            let m = self.mul(a, y);
            return self.neg(m);
        }
        // Constants first.
        let (a, b) = self.canonical(a, b, true);
        self.intern(Node::Mul(a, b))
    }

    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) if y != 0.0 => return self.constant(x / y),
            (Some(0.0), _) => return a,
            (_, Some(1.0)) => return a,
            (_, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        if a == b {
            return self.one();
        }
        if let Node::Neg(x) = self.node(a) {
            let d = self.div(x, b);
            return self.neg(d);
        }
        self.intern(Node::Div(a, b))
    }

    pub fn pow(&mut self, a: ExprId, b: ExprId) -> ExprId {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x.powf(y)),
            (_, Some(1.0)) => return a,
            (_, Some(0.0)) => return self.one(),
            _ => {}
        }
        self.intern(Node::Pow(a, b))
    }

    pub fn fn1(&mut self, f: Fn1, a: ExprId) -> ExprId {
        if let Some(x) = self.as_const(a) {
            return self.constant(f.apply(x));
        }
        if f == Fn1::Abs {
            if let Node::Neg(x) = self.node(a) {
                return self.fn1(Fn1::Abs, x);
            }
        }
        self.intern(Node::Fn1(f, a))
    }

    pub fn fn2(&mut self, f: Fn2, a: ExprId, b: ExprId) -> ExprId {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(f.apply(x, y));
        }
        if matches!(f, Fn2::Min | Fn2::Max) && a == b {
            return a;
        }
        self.intern(Node::Fn2(f, a, b))
    }

    pub fn rel(&mut self, op: RelOp, a: ExprId, b: ExprId) -> ExprId {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.boolean(op.apply(x, y));
        }
        self.intern(Node::Rel(op, a, b))
    }

    pub fn and(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.logical(a, b, false, Node::And)
    }

    pub fn or(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.logical(a, b, true, Node::Or)
    }

    /// `a and b` (`absorbing` false) or `a or b` (`absorbing` true): a constant operand
    /// whose truth is `absorbing` decides the result, any other constant leaves the
    /// other operand, and `x op x` is `x`.
    fn logical(
        &mut self,
        a: ExprId,
        b: ExprId,
        absorbing: bool,
        node: fn(ExprId, ExprId) -> Node,
    ) -> ExprId {
        let decides = |c: f64| (c != 0.0) == absorbing;
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), _) if decides(x) => return self.boolean(absorbing),
            (_, Some(y)) if decides(y) => return self.boolean(absorbing),
            (Some(_), _) => return b,
            (_, Some(_)) => return a,
            _ => {}
        }
        if a == b {
            return a;
        }
        self.intern(node(a, b))
    }

    pub fn not(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(b) => self.boolean(f64::from_bits(b) == 0.0),
            Node::Not(x) => x,
            _ => self.intern(Node::Not(a)),
        }
    }

    pub fn if_(&mut self, c: ExprId, a: ExprId, b: ExprId) -> ExprId {
        if let Some(x) = self.as_const(c) {
            return if x != 0.0 { a } else { b };
        }
        if a == b {
            return a;
        }
        self.intern(Node::If(c, a, b))
    }

    pub fn no_event(&mut self, a: ExprId) -> ExprId {
        match self.node(a) {
            Node::Const(_) | Node::Var(_) | Node::Pre(_) | Node::Time | Node::NoEvent(_) => a,
            _ => self.intern(Node::NoEvent(a)),
        }
    }

    pub fn sample(&mut self, start: ExprId, interval: ExprId) -> ExprId {
        self.intern(Node::Sample(start, interval))
    }

    /// The operands of a node, in order.
    pub fn children(&self, id: ExprId) -> impl Iterator<Item = ExprId> {
        if let Node::Ext(_, ops) = self.node(id) {
            return ops.map(Some).into_iter().flatten();
        }
        let (a, b, c): (Option<ExprId>, Option<ExprId>, Option<ExprId>) = match self.node(id) {
            Node::Const(_) | Node::Var(_) | crate::run_time_leaf!() => (None, None, None),
            Node::Neg(x) | Node::Fn1(_, x) | Node::Not(x) | Node::NoEvent(x) => {
                (Some(x), None, None)
            }
            Node::Add(x, y)
            | Node::Mul(x, y)
            | Node::Div(x, y)
            | Node::Pow(x, y)
            | Node::Fn2(_, x, y)
            | Node::Rel(_, x, y)
            | Node::And(x, y)
            | Node::Or(x, y)
            | Node::Sample(x, y) => (Some(x), Some(y), None),
            Node::If(c, x, y) => (Some(c), Some(x), Some(y)),
            // Returned above with its four operands.
            Node::Ext(..) => (None, None, None),
        };
        [a, b, c, None].into_iter().flatten()
    }

    /// Every variable (`Var`, not `Pre`) occurring in `id`, each once, in order of
    /// first occurrence.
    pub fn vars(&self, id: ExprId) -> Vec<ScalarId> {
        let mut out = Vec::new();
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![id];
        let mut visited = rustc_hash::FxHashSet::default();
        while let Some(e) = stack.pop() {
            if !visited.insert(e) {
                continue;
            }
            if let Node::Var(s) = self.node(e) {
                if seen.insert(s) {
                    out.push(s);
                }
            }
            let mut kids: Vec<ExprId> = self.children(e).collect();
            kids.reverse();
            stack.extend(kids);
        }
        out
    }

    /// Whether `id` depends on a variable for which `pred` holds.
    pub fn depends_on(&self, id: ExprId, pred: &dyn Fn(ScalarId) -> bool) -> bool {
        self.vars(id).into_iter().any(pred)
    }

    /// `id` with variables replaced by `map` (memoized over the shared graph).
    pub fn substitute(
        &mut self,
        id: ExprId,
        map: &dyn Fn(ScalarId) -> Option<ExprId>,
        memo: &mut HashMap<ExprId, ExprId>,
    ) -> ExprId {
        if let Some(&r) = memo.get(&id) {
            return r;
        }
        let r = match self.node(id) {
            Node::Var(s) => map(s).unwrap_or(id),
            Node::Const(_) | crate::run_time_leaf!() => id,
            node => {
                let kids: Vec<ExprId> = self.children(id).collect();
                let new: Vec<ExprId> = kids
                    .iter()
                    .map(|&k| self.substitute(k, map, memo))
                    .collect();
                if new == kids {
                    id
                } else {
                    self.rebuild(node, &new)
                }
            }
        };
        memo.insert(id, r);
        r
    }

    /// A node of the same kind as `node` over new operands (simplified again).
    pub fn rebuild(&mut self, node: Node, k: &[ExprId]) -> ExprId {
        match node {
            Node::Const(_) | Node::Var(_) | crate::run_time_leaf!() => self.intern(node),
            Node::Add(..) => self.add(k[0], k[1]),
            Node::Mul(..) => self.mul(k[0], k[1]),
            Node::Div(..) => self.div(k[0], k[1]),
            Node::Pow(..) => self.pow(k[0], k[1]),
            Node::Neg(_) => self.neg(k[0]),
            Node::Fn1(f, _) => self.fn1(f, k[0]),
            Node::Fn2(f, ..) => self.fn2(f, k[0], k[1]),
            Node::Rel(op, ..) => self.rel(op, k[0], k[1]),
            Node::And(..) => self.and(k[0], k[1]),
            Node::Or(..) => self.or(k[0], k[1]),
            Node::Not(_) => self.not(k[0]),
            Node::If(..) => self.if_(k[0], k[1], k[2]),
            Node::NoEvent(_) => self.no_event(k[0]),
            Node::Sample(..) => self.sample(k[0], k[1]),
            Node::Ext(f, _) => {
                let ops = [k[0], k[1], k[2], k[3]];
                match f.eval_pure(ops.map(|x| self.as_const(x))) {
                    Some(v) => self.constant(v),
                    None => self.intern(Node::Ext(f, ops)),
                }
            }
        }
    }

    /// Evaluates `id` with `value` for variables and `pre` for pre-values; relations
    /// are evaluated literally (no event semantics). For tests and constant folding of
    /// parameters, not the hot path.
    pub fn eval(&self, id: ExprId, env: &dyn EvalEnv) -> f64 {
        // Shared subexpressions once each: the arena is a DAG, and a tree walk of a
        // deeply shared one (a filter's coefficients computed by loops) is exponential.
        let mut memo = HashMap::default();
        self.eval_memo(id, env, &mut memo)
    }

    fn eval_memo(&self, id: ExprId, env: &dyn EvalEnv, memo: &mut HashMap<ExprId, f64>) -> f64 {
        if let Some(&v) = memo.get(&id) {
            return v;
        }
        let v = self.eval_node(id, env, memo);
        memo.insert(id, v);
        v
    }

    fn eval_node(&self, id: ExprId, env: &dyn EvalEnv, memo: &mut HashMap<ExprId, f64>) -> f64 {
        let mut e = |x: ExprId| self.eval_memo(x, env, memo);
        match self.node(id) {
            Node::Const(b) => f64::from_bits(b),
            Node::Var(s) => env.value(s),
            Node::Pre(s) => env.pre(s),
            Node::Time => env.time(),
            Node::Initial => f64::from(env.initial()),
            Node::Terminal | Node::HomotopyStart => 0.0,
            Node::Add(a, b) => e(a) + e(b),
            Node::Mul(a, b) => e(a) * e(b),
            Node::Div(a, b) => e(a) / e(b),
            Node::Pow(a, b) => e(a).powf(e(b)),
            Node::Neg(a) => -e(a),
            Node::Fn1(f, a) => f.apply(e(a)),
            Node::Fn2(f, a, b) => f.apply(e(a), e(b)),
            Node::Rel(op, a, b) => f64::from(op.apply(e(a), e(b))),
            Node::And(a, b) => f64::from(e(a) != 0.0 && e(b) != 0.0),
            Node::Or(a, b) => f64::from(e(a) != 0.0 || e(b) != 0.0),
            Node::Not(a) => f64::from(e(a) == 0.0),
            Node::If(c, a, b) => {
                if e(c) != 0.0 {
                    e(a)
                } else {
                    e(b)
                }
            }
            Node::NoEvent(a) => e(a),
            Node::Sample(..) => 0.0,
            // Not known to the symbolic layer (computed by the runtime).
            Node::Ext(f, ops) if f.is_pure() => f.apply_pure(ops.map(e)),
            Node::External(..) | Node::Ext(..) => f64::NAN,
        }
    }

    /// Writes `id` in Modelica syntax, naming variables with `name`.
    pub fn write(
        &self,
        id: ExprId,
        name: &dyn Fn(ScalarId) -> String,
        out: &mut String,
    ) -> fmt::Result {
        self.write_prec(id, name, out, 0, usize::MAX)
    }

    /// `id` as text of at most about `limit` bytes (cut with `...`): for messages
    /// about expressions that may be huge when written out as trees.
    pub fn to_short_string(
        &self,
        id: ExprId,
        name: &dyn Fn(ScalarId) -> String,
        limit: usize,
    ) -> String {
        let mut s = String::new();
        if self.write_prec(id, name, &mut s, 0, limit).is_err() || s.len() > limit {
            let mut cut = limit.min(s.len());
            while !s.is_char_boundary(cut) {
                cut -= 1;
            }
            s.truncate(cut);
            s.push_str("...");
        }
        s
    }

    fn write_prec(
        &self,
        id: ExprId,
        name: &dyn Fn(ScalarId) -> String,
        out: &mut String,
        outer: u8,
        limit: usize,
    ) -> fmt::Result {
        use std::fmt::Write;
        if out.len() > limit {
            return Err(fmt::Error);
        }
        let prec = precedence(self.node(id));
        let paren = prec < outer || (prec == 7 && outer == 7);
        if paren {
            out.push('(');
        }
        let w = |x: ExprId, p: u8, out: &mut String| self.write_prec(x, name, out, p, limit);
        // `a op b` with the precedences its operands are written at.
        let infix = |(a, pa): (ExprId, u8), op: &str, (b, pb): (ExprId, u8), out: &mut String| {
            w(a, pa, out)?;
            out.push_str(op);
            w(b, pb, out)
        };
        match self.node(id) {
            Node::Const(b) => {
                let x = f64::from_bits(b);
                if x < 0.0 && outer > 6 {
                    write!(out, "({})", fmt_num(x))?;
                } else {
                    out.push_str(&fmt_num(x));
                }
            }
            Node::Var(s) => out.push_str(&name(s)),
            Node::Pre(s) => write!(out, "pre({})", name(s))?,
            Node::Time => out.push_str("time"),
            Node::Initial => out.push_str("initial()"),
            Node::Terminal => out.push_str("terminal()"),
            Node::HomotopyStart => out.push_str("$homotopyStart"),
            Node::External(site, k) => write!(out, "external({site}, {k})")?,
            Node::Add(a, b) => self.write_sum(a, b, name, out, limit)?,
            Node::Mul(a, b) => infix((a, 8), " * ", (b, 9), out)?,
            Node::Div(a, b) => infix((a, 8), " / ", (b, 9), out)?,
            Node::Pow(a, b) => infix((a, 10), " ^ ", (b, 10), out)?,
            Node::Neg(a) => {
                out.push('-');
                w(a, 8, out)?;
            }
            Node::Fn1(f, a) => self.write_call(f.name(), &[a], name, out, limit)?,
            Node::Fn2(f, a, b) => self.write_call(f.name(), &[a, b], name, out, limit)?,
            Node::Rel(op, a, b) => infix((a, 6), &format!(" {} ", op.symbol()), (b, 6), out)?,
            Node::And(a, b) => infix((a, 3), " and ", (b, 4), out)?,
            Node::Or(a, b) => infix((a, 2), " or ", (b, 3), out)?,
            Node::Not(a) => {
                out.push_str("not ");
                w(a, 5, out)?;
            }
            Node::If(c, a, b) => {
                out.push_str("if ");
                w(c, 0, out)?;
                out.push_str(" then ");
                w(a, 0, out)?;
                out.push_str(" else ");
                w(b, 1, out)?;
            }
            Node::NoEvent(a) => self.write_call("noEvent", &[a], name, out, limit)?,
            Node::Sample(a, b) => self.write_call("sample", &[a, b], name, out, limit)?,
            Node::Ext(f, args) => {
                let n = (1 + f.arity()).min(args.len());
                self.write_call(f.name(), &args[..n], name, out, limit)?
            }
        }
        if paren {
            out.push(')');
        }
        Ok(())
    }

    /// A sum `a + b`, written `a - x` when `b` is `-x` or a negative constant.
    fn write_sum(
        &self,
        a: ExprId,
        b: ExprId,
        name: &dyn Fn(ScalarId) -> String,
        out: &mut String,
        limit: usize,
    ) -> fmt::Result {
        use std::fmt::Write;
        let w = |x: ExprId, p: u8, out: &mut String| self.write_prec(x, name, out, p, limit);
        w(a, 6, out)?;
        match self.node(b) {
            Node::Neg(x) => {
                out.push_str(" - ");
                w(x, 7, out)?;
            }
            Node::Const(c) if f64::from_bits(c) < 0.0 => {
                write!(out, " - {}", fmt_num(-f64::from_bits(c)))?;
            }
            _ => {
                out.push_str(" + ");
                w(b, 6, out)?;
            }
        }
        Ok(())
    }

    /// A call `func(args...)`, each argument written as a whole.
    fn write_call(
        &self,
        func: &str,
        args: &[ExprId],
        name: &dyn Fn(ScalarId) -> String,
        out: &mut String,
        limit: usize,
    ) -> fmt::Result {
        out.push_str(func);
        out.push('(');
        for (k, &x) in args.iter().enumerate() {
            if k > 0 {
                out.push_str(", ");
            }
            self.write_prec(x, name, out, 0, limit)?;
        }
        out.push(')');
        Ok(())
    }

    /// `id` as a string (see [`ExprArena::write`]).
    pub fn to_string(&self, id: ExprId, name: &dyn Fn(ScalarId) -> String) -> String {
        let mut s = String::new();
        let _ = self.write(id, name, &mut s);
        s
    }
}

/// Shortest text that reads back as the same f64.
pub fn fmt_num(x: f64) -> String {
    if x.is_finite() && x == x.trunc() && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

/// What [`ExprArena::eval`] needs.
pub trait EvalEnv {
    fn value(&self, s: ScalarId) -> f64;
    fn pre(&self, s: ScalarId) -> f64 {
        self.value(s)
    }
    fn time(&self) -> f64 {
        0.0
    }
    fn initial(&self) -> bool {
        false
    }
}

impl EvalEnv for [f64] {
    fn value(&self, s: ScalarId) -> f64 {
        self[s.index()]
    }
}

/// The precedence of a node when printed: the higher, the tighter it binds.
fn precedence(node: Node) -> u8 {
    match node {
        Node::If(..) => 1,
        Node::Or(..) => 2,
        Node::And(..) => 3,
        Node::Not(_) => 4,
        Node::Rel(..) => 5,
        Node::Add(..) => 6,
        Node::Neg(_) => 7,
        Node::Mul(..) | Node::Div(..) => 8,
        Node::Pow(..) => 9,
        _ => 10,
    }
}
