//! The one table of Modelica's built-in functions and operators (spec 3.7), read by
//! flattening (`unimo-flat`: name check, element-wise shapes, the constant evaluator)
//! and by lowering (`unimo-dae`: the compiled forms [`Fn1`]/[`Fn2`], their derivatives
//! and events) and, through those forms, by the runtime's tapes.
//!
//! Adding a built-in is one entry of [`BUILTINS`] plus its tests; the differential
//! test (`tests/builtins.rs`) evaluates every entry with a scalar evaluation by the
//! constant evaluator and by compiled code and asserts they agree.
//!
//! Invariants: std only; each name appears once; every [`Fn1`]/[`Fn2`] variant has
//! exactly one first entry naming it (checked at compile time), whose `eval` is the
//! one place its maths is written.

mod compiled;
pub mod maths;
mod table;

pub use compiled::{Fn1, Fn2};
pub use table::BUILTINS;

/// How many arguments a built-in takes (positional; named ones aside).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arity {
    /// Exactly n.
    Fixed(u8),
    /// From the first to the second, inclusive.
    Range(u8, u8),
    /// At least n.
    Variadic(u8),
}

impl Arity {
    /// Whether `n` arguments fit.
    pub fn accepts(self, n: usize) -> bool {
        match self {
            Arity::Fixed(k) => n == k as usize,
            Arity::Range(lo, hi) => (lo as usize..=hi as usize).contains(&n),
            Arity::Variadic(lo) => n >= lo as usize,
        }
    }
}

/// Argument and result types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ty {
    Real,
    Integer,
    Boolean,
    String,
    /// Integer or Real.
    Numeric,
    /// The type of the (first numeric) argument: Integer when every argument is.
    SameAsArguments,
    /// An array of any element type.
    Array,
    /// Any type (a variable, an expression of any type, or an enumeration).
    Any,
    /// No value: a statement-like operator (`assert`, `reinit`, `terminate`).
    Nothing,
}

/// What sort of built-in an entry is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A continuous mathematical function of Real arguments (`sin`, `atan2`, `abs`).
    Math,
    /// An event-triggering rounding (spec 3.7.1.1: `div`, `mod`, `rem`, `ceil`,
    /// `floor`, `integer`): piecewise constant between events.
    Rounding,
    /// A reduction of an array or of an iterator expression (`sum`; `min`/`max`, whose
    /// two-argument form is the continuous pairwise function).
    Reduction,
    /// Builds an array (`zeros`, `fill`, `identity`, `cat`).
    ArrayConstructor,
    /// Reshapes or combines arrays (`transpose`, `cross`, `vector`).
    ArrayFunction,
    /// A question about sizes or connections (`size`, `ndims`, `cardinality`).
    Query,
    /// A type conversion (`Integer(e)` of an enumeration, `String`, `Real`).
    Conversion,
    /// An event operator (`pre`, `edge`, `change`, `initial`, `terminal`, `sample`).
    Event,
    /// A special operator lowering treats on its own (`der`, `delay`, `smooth`,
    /// `noEvent`, `homotopy`, `semiLinear`).
    Special,
    /// A statement-like operator without a value (`assert`, `terminate`, `reinit`).
    Statement,
    /// Evaluated by an external object of the runtime (the collision world).
    External,
    /// Named by the language but not implemented yet: the name check accepts it,
    /// lowering reports "not supported yet" (`E3001`).
    Unsupported,
}

/// The scalar evaluation of a numeric built-in, on f64 (Integers are exact in f64).
#[derive(Clone, Copy, Debug)]
pub enum Eval {
    None,
    Unary(fn(f64) -> f64),
    Binary(fn(f64, f64) -> f64),
}

/// Where a numeric built-in's compiled form is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compiled {
    Unary(Fn1),
    /// A function of two arguments; for an entry whose arity also admits another
    /// number (`min(a)`, `max(a)`) only the two-argument call.
    Binary(Fn2),
}

/// The derivative rule, as data that `unimo-dae`'s `diff.rs` interprets. For `y =
/// f(x)` the rule gives f'(x) (it may read `y` itself); for two arguments it gives
/// the total derivative from dx and dy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Derivative {
    /// cos(x)
    Cos,
    /// -sin(x)
    NegSin,
    /// 1 + y^2 (`tan`)
    OnePlusSquareOfValue,
    /// 1 / sqrt(1 - x^2) (`asin`)
    InvSqrtOneMinusSquare,
    /// -1 / sqrt(1 - x^2) (`acos`)
    NegInvSqrtOneMinusSquare,
    /// 1 / (1 + x^2) (`atan`)
    InvOnePlusSquare,
    /// cosh(x)
    Cosh,
    /// sinh(x)
    Sinh,
    /// 1 - y^2 (`tanh`)
    OneMinusSquareOfValue,
    /// y itself (`exp`)
    Value,
    /// 1 / x (`log`)
    Reciprocal,
    /// 1 / (ln(10) x) (`log10`)
    ReciprocalLn10,
    /// 1 / (2 y) (`sqrt`)
    HalfReciprocalOfValue,
    /// sign(x) (`abs`)
    Sign,
    /// 0: piecewise constant (changes only at events or jumps).
    Zero,
    /// (y dx - x dy) / (x^2 + y^2) (`atan2(x, y)`)
    Atan2,
    /// if x < y then dx else dy
    MinSelect,
    /// if x > y then dx else dy
    MaxSelect,
    /// dx - floor(x / y) dy
    Mod,
    /// dx - div(x, y) dy
    Rem,
    /// Lowering differentiates what the operator lowers to (`der`, `noEvent`, ...),
    /// or the built-in has no value to differentiate.
    ByLowering,
}

/// Whether a built-in triggers events (spec 3.7.1.1 and 8.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Events {
    /// Never: continuous (`sin`), or expanded with `noEvent` by the spec (`abs`,
    /// `sign`), or without a value of its own.
    None,
    /// Its value changes only at events, which the runtime locates (a rounding whose
    /// result is held between events: `floor`, `ceil`, `integer`, `div`, `mod`, `rem`).
    Rounding,
    /// An event operator (`sample`, `edge`, `change`, `initial`, `terminal`, `pre`):
    /// its meaning is about events.
    Operator,
}

/// One built-in function or operator.
#[derive(Clone, Copy, Debug)]
pub struct Builtin {
    pub name: &'static str,
    /// One line: what it is, in Modelica terms.
    pub doc: &'static str,
    pub arity: Arity,
    /// Argument types by position (the last repeats for variadic entries).
    pub args: &'static [Ty],
    pub result: Ty,
    pub kind: Kind,
    /// Applied element by element to an array argument (one positional argument).
    pub elementwise: bool,
    pub eval: Eval,
    pub compiled: Option<Compiled>,
    pub derivative: Derivative,
    pub events: Events,
    /// Evaluated outside the expression tapes (an external object of the runtime).
    pub external: bool,
}

/// The entry named `name`.
pub fn find(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// Whether `name` is a built-in function unimo implements (the name check accepts it).
pub fn is_function(name: &str) -> bool {
    find(name).is_some_and(|b| b.kind != Kind::Unsupported)
}

/// Whether `name` is a built-in the language has and unimo does not implement yet.
pub fn is_unsupported(name: &str) -> bool {
    find(name).is_some_and(|b| b.kind == Kind::Unsupported)
}

/// Whether `name` applies element by element to an array argument.
pub fn is_elementwise(name: &str) -> bool {
    find(name).is_some_and(|b| b.elementwise)
}

/// The names of the implemented built-in functions, in table order.
pub fn function_names() -> impl Iterator<Item = &'static str> {
    BUILTINS
        .iter()
        .filter(|b| b.kind != Kind::Unsupported)
        .map(|b| b.name)
}

impl Builtin {
    /// The Integer value of `r` when this built-in's result is an Integer for
    /// arguments whose Integer-ness is `all_integer`: `Some(Ok(i))`; `Some(Err(()))`
    /// when the result should be an Integer but `r` is not one (NaN, infinite or
    /// beyond the 64-bit range); `None` when the result is Real.
    #[allow(clippy::result_unit_err)]
    pub fn integer_result(&self, r: f64, all_integer: bool) -> Option<Result<i64, ()>> {
        let integer = match self.result {
            Ty::Integer => true,
            Ty::SameAsArguments => all_integer,
            _ => false,
        };
        integer.then(|| maths::to_integer(r).ok_or(()))
    }
}

#[cfg(test)]
mod tests;
