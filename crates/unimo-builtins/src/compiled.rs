//! The compiled forms of the numeric built-ins: the expression nodes of `unimo-dae`
//! and the instructions of the runtime's tapes. Each variant is an index into
//! [`BUILTINS`]: its name, evaluation, derivative and events are the table's.

use crate::{Builtin, Compiled, Derivative, Eval, Events, BUILTINS};

/// Functions of one argument.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Fn1 {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Log,
    Log10,
    Sqrt,
    Abs,
    Sign,
    /// `floor`, and `integer` (which lowers to it).
    Floor,
    Ceil,
}

/// Functions of two arguments.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Fn2 {
    Atan2,
    Min,
    Max,
    /// `mod(x, y) = x - floor(x / y) * y`
    Mod,
    /// `rem(x, y) = x - div(x, y) * y`
    Rem,
    /// `div(x, y)`: the quotient truncated toward zero.
    Div,
}

impl Fn1 {
    pub const ALL: [Fn1; 17] = [
        Fn1::Sin,
        Fn1::Cos,
        Fn1::Tan,
        Fn1::Asin,
        Fn1::Acos,
        Fn1::Atan,
        Fn1::Sinh,
        Fn1::Cosh,
        Fn1::Tanh,
        Fn1::Exp,
        Fn1::Log,
        Fn1::Log10,
        Fn1::Sqrt,
        Fn1::Abs,
        Fn1::Sign,
        Fn1::Floor,
        Fn1::Ceil,
    ];

    /// Its table entry (the first naming it: `floor` for [`Fn1::Floor`]).
    pub fn entry(self) -> &'static Builtin {
        &BUILTINS[UNARY_ENTRIES[self as usize]]
    }

    pub fn name(self) -> &'static str {
        self.entry().name
    }

    /// The compiled form of the built-in `name` of one argument (`integer` is
    /// [`Fn1::Floor`]).
    pub fn from_name(name: &str) -> Option<Fn1> {
        match crate::find(name)?.compiled? {
            Compiled::Unary(f) => Some(f),
            Compiled::Binary(_) => None,
        }
    }

    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self.entry().eval {
            Eval::Unary(f) => f(x),
            _ => unreachable!("a unary entry has a unary evaluation (checked at compile time)"),
        }
    }

    /// Piecewise constant: its value changes only at jumps (`sign`) or events.
    pub fn is_discontinuous(self) -> bool {
        self.entry().derivative == Derivative::Zero
    }

    /// A rounding whose value the runtime holds between events (`floor`, `ceil`).
    pub fn generates_events(self) -> bool {
        self.entry().events == Events::Rounding
    }

    pub fn derivative(self) -> Derivative {
        self.entry().derivative
    }
}

impl Fn2 {
    pub const ALL: [Fn2; 6] = [Fn2::Atan2, Fn2::Min, Fn2::Max, Fn2::Mod, Fn2::Rem, Fn2::Div];

    /// Its table entry.
    pub fn entry(self) -> &'static Builtin {
        &BUILTINS[BINARY_ENTRIES[self as usize]]
    }

    pub fn name(self) -> &'static str {
        self.entry().name
    }

    /// The compiled form of the built-in `name` called with two arguments.
    pub fn from_name(name: &str) -> Option<Fn2> {
        match crate::find(name)?.compiled? {
            Compiled::Binary(f) => Some(f),
            Compiled::Unary(_) => None,
        }
    }

    #[inline]
    pub fn apply(self, x: f64, y: f64) -> f64 {
        match self.entry().eval {
            Eval::Binary(f) => f(x, y),
            _ => unreachable!("a binary entry has a binary evaluation (checked at compile time)"),
        }
    }

    /// A rounding whose value the runtime holds between events (`div`, `mod`, `rem`).
    pub fn generates_events(self) -> bool {
        self.entry().events == Events::Rounding
    }

    pub fn derivative(self) -> Derivative {
        self.entry().derivative
    }
}

/// The first entry whose compiled form is `want` (a compile-time error when none,
/// or when its evaluation has the wrong number of arguments).
const fn entry_of(want: Compiled) -> usize {
    let mut i = 0;
    while i < BUILTINS.len() {
        let b = &BUILTINS[i];
        match (b.compiled, want, b.eval) {
            (Some(Compiled::Unary(f)), Compiled::Unary(g), Eval::Unary(_))
                if f as u8 == g as u8 =>
            {
                return i
            }
            (Some(Compiled::Binary(f)), Compiled::Binary(g), Eval::Binary(_))
                if f as u8 == g as u8 =>
            {
                return i
            }
            _ => {}
        }
        i += 1;
    }
    panic!("a compiled form without a table entry of its arity")
}

const UNARY_ENTRIES: [usize; Fn1::ALL.len()] = {
    let mut out = [0; Fn1::ALL.len()];
    let mut k = 0;
    while k < out.len() {
        assert!(Fn1::ALL[k] as usize == k);
        out[k] = entry_of(Compiled::Unary(Fn1::ALL[k]));
        k += 1;
    }
    out
};

const BINARY_ENTRIES: [usize; Fn2::ALL.len()] = {
    let mut out = [0; Fn2::ALL.len()];
    let mut k = 0;
    while k < out.len() {
        assert!(Fn2::ALL[k] as usize == k);
        out[k] = entry_of(Compiled::Binary(Fn2::ALL[k]));
        k += 1;
    }
    out
};
