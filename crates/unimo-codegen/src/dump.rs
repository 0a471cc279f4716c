//! The compiled model as text (`unimo emit --stage tape`): every tape, one instruction
//! a line, registers by the scalar they hold (`x`, `pre(x)`, `time`) or as temporaries
//! (`t12`). For reading what the hot path evaluates; the format is for people and
//! snapshot tests, not for parsing back.

use crate::model::{Action, CompiledModel, CompiledStep};
use crate::tape::{Op, Reg, Tape};
use std::fmt::Write;

/// Names registers: scalars by `names` (indexed by scalar id), `pre(...)` of them,
/// `time`/`initial()`/`terminal()`, temporaries as `tN`.
struct Names<'a> {
    m: &'a CompiledModel,
    names: &'a [String],
}

impl Names<'_> {
    fn reg(&self, r: Reg) -> String {
        let l = &self.m.layout;
        if r < l.n_scalars {
            return self
                .names
                .get(r as usize)
                .cloned()
                .unwrap_or_else(|| format!("s{r}"));
        }
        if r < l.pre_base + l.n_scalars {
            return format!("pre({})", self.reg(r - l.pre_base));
        }
        if r == l.time {
            return "time".into();
        }
        if r == l.initial {
            return "initial()".into();
        }
        if r == l.terminal {
            return "terminal()".into();
        }
        format!("t{}", r - l.temp_base)
    }

    fn op(&self, op: &Op) -> String {
        let n = |r: Reg| self.reg(r);
        match op {
            Op::Const(d, x) => format!("{} = {x:?}", n(*d)),
            Op::Copy(d, a) => format!("{} = {}", n(*d), n(*a)),
            Op::Add(d, a, b) => format!("{} = {} + {}", n(*d), n(*a), n(*b)),
            Op::Sub(d, a, b) => format!("{} = {} - {}", n(*d), n(*a), n(*b)),
            Op::Mul(d, a, b) => format!("{} = {} * {}", n(*d), n(*a), n(*b)),
            Op::Div(d, a, b) => format!("{} = {} / {}", n(*d), n(*a), n(*b)),
            Op::Pow(d, a, b) => format!("{} = {} ^ {}", n(*d), n(*a), n(*b)),
            Op::Powi(d, a, k) => format!("{} = {} ^ {k}", n(*d), n(*a)),
            Op::Neg(d, a) => format!("{} = -{}", n(*d), n(*a)),
            Op::Fn1(f, d, a) => format!("{} = {}({})", n(*d), f.name(), n(*a)),
            Op::Fn2(f, d, a, b) => format!("{} = {}({}, {})", n(*d), f.name(), n(*a), n(*b)),
            Op::Rel(o, d, a, b) => {
                format!("{} = noEvent({} {} {})", n(*d), n(*a), o.symbol(), n(*b))
            }
            Op::RelEvent(o, d, a, b, k) => {
                format!("{} = {} {} {}  (z{k})", n(*d), n(*a), o.symbol(), n(*b))
            }
            Op::And(d, a, b) => format!("{} = {} and {}", n(*d), n(*a), n(*b)),
            Op::Or(d, a, b) => format!("{} = {} or {}", n(*d), n(*a), n(*b)),
            Op::Not(d, a) => format!("{} = not {}", n(*d), n(*a)),
            Op::Select(d, c, a, b) => {
                format!("{} = if {} then {} else {}", n(*d), n(*c), n(*a), n(*b))
            }
            Op::Sample(d, k) => format!("{} = sample {k}", n(*d)),
            Op::Ext(f, d, args) => {
                let args: Vec<String> = args.iter().take(1 + f.arity()).map(|a| n(*a)).collect();
                format!("{} = {f:?}({})", n(*d), args.join(", "))
            }
            Op::Held(r, d, a, k) => format!("{} = {r:?}({})  (held {k})", n(*d), n(*a)),
            Op::HeldBounds(r, lo, hi, k) => {
                format!("{}, {} = bounds of {r:?}  (held {k})", n(*lo), n(*hi))
            }
        }
    }

    fn tape(&self, o: &mut String, title: &str, t: &Tape) {
        if t.ops.is_empty() {
            return;
        }
        let _ = writeln!(o, "{title}: {} instructions", t.ops.len());
        for op in &t.ops {
            let _ = writeln!(o, "  {}", self.op(op));
        }
    }
}

/// The text of `m`; `names[s]` is the name of scalar `s` (its register is `s`).
pub fn tape_dump(m: &CompiledModel, names: &[String]) -> String {
    let n = Names { m, names };
    let mut o = String::new();
    let l = &m.layout;
    let _ = writeln!(
        o,
        "registers: {} ({} scalars, their pre values, time, initial(), terminal(), the homotopy flag, {} temporaries)",
        m.n_registers,
        l.n_scalars,
        m.n_registers.saturating_sub(l.temp_base as usize)
    );
    let list = |regs: &[Reg]| {
        regs.iter()
            .map(|&r| n.reg(r))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = writeln!(o, "states: {}", list(&m.states));
    let _ = writeln!(o, "derivatives: {}", list(&m.derivatives));
    if !m.constants.is_empty() {
        let _ = writeln!(o, "constants: {}", m.constants.len());
        for (r, x) in &m.constants {
            let _ = writeln!(o, "  {} = {x:?}", n.reg(*r));
        }
    }
    n.tape(&mut o, "parameters", &m.parameters);
    n.tape(&mut o, "start values", &m.starts);
    for (k, step) in m.steps.iter().enumerate() {
        match step {
            CompiledStep::Explicit(t) => n.tape(&mut o, &format!("step {k}: explicit"), t),
            CompiledStep::Block(b) => {
                let _ = writeln!(
                    o,
                    "step {k}: {} block of {} iter {{{}}}, residuals {{{}}}",
                    if b.linear { "linear" } else { "nonlinear" },
                    b.iteration.len(),
                    list(&b.iteration),
                    list(&b.residuals)
                );
                n.tape(&mut o, "  residual tape", &b.residual_tape);
                n.tape(&mut o, "  jacobian tape", &b.jacobian_tape);
            }
        }
    }
    if !m.roots.is_empty() {
        let _ = writeln!(o, "zero crossings: {}", m.roots.len());
        n.tape(&mut o, "  their tape", &m.roots_tape);
        for (k, (a, b)) in m.roots.iter().enumerate() {
            let _ = writeln!(o, "  z{k} = {} - {}", n.reg(*a), n.reg(*b));
        }
    }
    n.tape(&mut o, "when conditions and values", &m.when_tape);
    for (k, w) in m.whens.iter().enumerate() {
        for (conds, actions) in &w.branches {
            let _ = writeln!(o, "when {k} on {}:", list(conds));
            for a in actions {
                let text = match a {
                    Action::Assign { target, value } => {
                        format!("{} := {}", n.reg(*target), n.reg(*value))
                    }
                    Action::Reinit { target, value } => {
                        format!("reinit({}, {})", n.reg(*target), n.reg(*value))
                    }
                    Action::Terminate(msg) => format!("terminate({msg:?})"),
                    Action::Assert { condition, message } => {
                        format!("assert({}, {message:?})", n.reg(*condition))
                    }
                };
                let _ = writeln!(o, "  {text}");
            }
        }
    }
    n.tape(&mut o, "initial equations", &m.initial_tape);
    if !m.initial_residuals.is_empty() {
        let _ = writeln!(o, "  residuals: {}", list(&m.initial_residuals));
    }
    n.tape(&mut o, "assertions", &m.assert_tape);
    n.tape(&mut o, "invariants", &m.invariant_tape);
    for (g, active) in &m.invariants {
        let _ = writeln!(o, "  0 = {} while {}", n.reg(*g), n.reg(*active));
    }
    n.tape(&mut o, "aliases", &m.alias_tape);
    if !m.delay_inputs.is_empty() {
        n.tape(&mut o, "delay inputs", &m.delay_tape);
        let _ = writeln!(o, "  recorded: {}", list(&m.delay_inputs));
    }
    if let Some((t, entries)) = &m.jacobian {
        let _ = writeln!(o, "symbolic jacobian: {} entries", entries.len());
        n.tape(&mut o, "  its tape", t);
        for (i, j, r) in entries {
            let _ = writeln!(o, "  d der[{i}] / d x[{j}] = {}", n.reg(*r));
        }
    }
    let _ = writeln!(o, "plan instructions per evaluation: {}", m.plan_ops());
    o
}
