//! [`BUILTINS`]: every built-in function and operator, one entry each. Order matters
//! only for the name check's suggestions and for a compiled form named by two entries
//! (`floor` before `integer`: [`Fn1::Floor`]'s entry is `floor`).

use crate::maths;
use crate::{Arity, Builtin, Compiled, Derivative, Eval, Events, Fn1, Fn2, Kind, Ty};

use Arity::{Fixed, Range, Variadic};

/// An entry with no evaluation, no compiled form and no events.
const fn op(
    name: &'static str,
    kind: Kind,
    arity: Arity,
    args: &'static [Ty],
    result: Ty,
    doc: &'static str,
) -> Builtin {
    Builtin {
        name,
        doc,
        arity,
        args,
        result,
        kind,
        elementwise: false,
        eval: Eval::None,
        compiled: None,
        derivative: Derivative::ByLowering,
        events: Events::None,
        external: false,
    }
}

/// A continuous element-wise Real function of one argument.
const fn math1(
    name: &'static str,
    f: fn(f64) -> f64,
    compiled: Fn1,
    derivative: Derivative,
    doc: &'static str,
) -> Builtin {
    Builtin {
        elementwise: true,
        eval: Eval::Unary(f),
        compiled: Some(Compiled::Unary(compiled)),
        derivative,
        ..op(name, Kind::Math, Fixed(1), &[Ty::Real], Ty::Real, doc)
    }
}

/// A function of two scalars.
#[allow(clippy::too_many_arguments)]
const fn math2(
    name: &'static str,
    kind: Kind,
    arity: Arity,
    f: fn(f64, f64) -> f64,
    compiled: Fn2,
    derivative: Derivative,
    result: Ty,
    doc: &'static str,
) -> Builtin {
    Builtin {
        eval: Eval::Binary(f),
        compiled: Some(Compiled::Binary(compiled)),
        derivative,
        events: if matches!(kind, Kind::Rounding) {
            Events::Rounding
        } else {
            Events::None
        },
        ..op(name, kind, arity, &[Ty::Numeric, Ty::Numeric], result, doc)
    }
}

/// An event-triggering rounding of one Real argument.
const fn rounding1(
    name: &'static str,
    f: fn(f64) -> f64,
    compiled: Fn1,
    result: Ty,
    elementwise: bool,
    doc: &'static str,
) -> Builtin {
    Builtin {
        elementwise,
        eval: Eval::Unary(f),
        compiled: Some(Compiled::Unary(compiled)),
        derivative: Derivative::Zero,
        events: Events::Rounding,
        ..op(name, Kind::Rounding, Fixed(1), &[Ty::Real], result, doc)
    }
}

/// An operator of the given kind with the given events.
const fn with_events(b: Builtin, events: Events) -> Builtin {
    Builtin { events, ..b }
}

/// Applied element by element to an array argument.
const fn elementwise(b: Builtin) -> Builtin {
    Builtin {
        elementwise: true,
        ..b
    }
}

const fn unsupported(name: &'static str, doc: &'static str) -> Builtin {
    op(
        name,
        Kind::Unsupported,
        Variadic(0),
        &[Ty::Any],
        Ty::Any,
        doc,
    )
}

const N: Ty = Ty::Numeric;
const R: Ty = Ty::Real;
const I: Ty = Ty::Integer;
const B: Ty = Ty::Boolean;
const A: Ty = Ty::Array;
const ANY: Ty = Ty::Any;

/// Every built-in function and operator (spec 3.7, 8.5, 10.3, 12.9).
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        result: Ty::SameAsArguments,
        args: &[N],
        ..math1(
            "abs",
            f64::abs,
            Fn1::Abs,
            Derivative::Sign,
            "|v| (spec: noEvent(if v >= 0 then v else -v), no events)",
        )
    },
    math1(
        "acos",
        f64::acos,
        Fn1::Acos,
        Derivative::NegInvSqrtOneMinusSquare,
        "Inverse cosine, in [0, pi]; NaN outside [-1, 1]",
    ),
    math1(
        "asin",
        f64::asin,
        Fn1::Asin,
        Derivative::InvSqrtOneMinusSquare,
        "Inverse sine, in [-pi/2, pi/2]; NaN outside [-1, 1]",
    ),
    op(
        "assert",
        Kind::Statement,
        Range(2, 3),
        &[B, Ty::String, ANY],
        Ty::Nothing,
        "assert(condition, message, level): checked at every accepted point",
    ),
    math1(
        "atan",
        f64::atan,
        Fn1::Atan,
        Derivative::InvOnePlusSquare,
        "Inverse tangent, in (-pi/2, pi/2)",
    ),
    math2(
        "atan2",
        Kind::Math,
        Fixed(2),
        f64::atan2,
        Fn2::Atan2,
        Derivative::Atan2,
        R,
        "atan2(y, x): the angle of the point (x, y), in (-pi, pi]",
    ),
    op(
        "array",
        Kind::ArrayConstructor,
        Variadic(1),
        &[ANY],
        A,
        "array(a, b, ...) = {a, b, ...}; also array(e for i in r)",
    ),
    op(
        "cardinality",
        Kind::Query,
        Fixed(1),
        &[ANY],
        I,
        "Number of connections of a connector (deprecated)",
    ),
    op(
        "cat",
        Kind::ArrayConstructor,
        Variadic(2),
        &[I, A],
        A,
        "cat(k, a, b, ...): concatenation along dimension k",
    ),
    rounding1(
        "ceil",
        f64::ceil,
        Fn1::Ceil,
        R,
        true,
        "Smallest whole Real not below x; triggers events",
    ),
    with_events(
        op(
            "change",
            Kind::Event,
            Fixed(1),
            &[ANY],
            B,
            "change(v) = v <> pre(v)",
        ),
        Events::Operator,
    ),
    math1("cos", f64::cos, Fn1::Cos, Derivative::NegSin, "Cosine"),
    math1(
        "cosh",
        f64::cosh,
        Fn1::Cosh,
        Derivative::Sinh,
        "Hyperbolic cosine",
    ),
    op(
        "cross",
        Kind::ArrayFunction,
        Fixed(2),
        &[A, A],
        A,
        "Cross product of two 3-vectors",
    ),
    op(
        "delay",
        Kind::Special,
        Range(2, 3),
        &[R, R, R],
        R,
        "delay(e, delayTime[, delayMax]): e at time - delayTime (spec 3.7.4.1)",
    ),
    elementwise(op(
        "der",
        Kind::Special,
        Fixed(1),
        &[R],
        R,
        "Time derivative",
    )),
    op(
        "diagonal",
        Kind::ArrayConstructor,
        Fixed(1),
        &[A],
        A,
        "Square matrix with the vector on its diagonal",
    ),
    math2(
        "div",
        Kind::Rounding,
        Fixed(2),
        maths::div,
        Fn2::Div,
        Derivative::Zero,
        Ty::SameAsArguments,
        "Quotient truncated toward zero; triggers events",
    ),
    with_events(
        op(
            "edge",
            Kind::Event,
            Fixed(1),
            &[B],
            B,
            "edge(b) = b and not pre(b)",
        ),
        Events::Operator,
    ),
    math1("exp", f64::exp, Fn1::Exp, Derivative::Value, "Exponential"),
    op(
        "fill",
        Kind::ArrayConstructor,
        Variadic(2),
        &[ANY, I],
        A,
        "fill(s, n1, n2, ...): an array of copies of s",
    ),
    rounding1(
        "floor",
        f64::floor,
        Fn1::Floor,
        R,
        true,
        "Largest whole Real not above x; triggers events",
    ),
    Builtin {
        external: true,
        ..op(
            "collisionBody",
            Kind::External,
            Variadic(1),
            &[R],
            A,
            "A body of the collision world: force and torque (6 values)",
        )
    },
    Builtin {
        external: true,
        ..op(
            "collisionGaps",
            Kind::External,
            Variadic(1),
            &[R],
            A,
            "The collision world's two gap functions",
        )
    },
    op(
        "homotopy",
        Kind::Special,
        Fixed(2),
        &[R, R],
        R,
        "homotopy(actual, simplified): simplified while initialization solves the start of the continuation, then actual",
    ),
    op(
        "identity",
        Kind::ArrayConstructor,
        Fixed(1),
        &[I],
        A,
        "n x n identity matrix",
    ),
    with_events(
        op(
            "initial",
            Kind::Event,
            Fixed(0),
            &[],
            B,
            "True during initialization",
        ),
        Events::Operator,
    ),
    rounding1(
        "integer",
        f64::floor,
        Fn1::Floor,
        I,
        false,
        "Largest Integer not above x (floor as an Integer); triggers events",
    ),
    op(
        "invariant",
        Kind::Statement,
        Fixed(1),
        &[A],
        Ty::Nothing,
        "invariant(g): the states are projected onto g = 0 after each step and event (Unimo.invariant)",
    ),
    op(
        "linspace",
        Kind::ArrayConstructor,
        Fixed(3),
        &[R, R, I],
        A,
        "linspace(x1, x2, n): n equally spaced values",
    ),
    math1(
        "log",
        f64::ln,
        Fn1::Log,
        Derivative::Reciprocal,
        "Natural logarithm; NaN below 0, -inf at 0",
    ),
    math1(
        "log10",
        f64::log10,
        Fn1::Log10,
        Derivative::ReciprocalLn10,
        "Base-10 logarithm; NaN below 0, -inf at 0",
    ),
    op(
        "matrix",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        A,
        "The array as a matrix",
    ),
    math2(
        "max",
        Kind::Reduction,
        Range(1, 2),
        maths::max,
        Fn2::Max,
        Derivative::MaxSelect,
        Ty::SameAsArguments,
        "max(x, y), continuous (no events); max(a): largest element",
    ),
    math2(
        "min",
        Kind::Reduction,
        Range(1, 2),
        maths::min,
        Fn2::Min,
        Derivative::MinSelect,
        Ty::SameAsArguments,
        "min(x, y), continuous (no events); min(a): smallest element",
    ),
    math2(
        "mod",
        Kind::Rounding,
        Fixed(2),
        maths::modulo,
        Fn2::Mod,
        Derivative::Mod,
        Ty::SameAsArguments,
        "x - floor(x / y) * y; triggers events",
    ),
    op(
        "ndims",
        Kind::Query,
        Fixed(1),
        &[A],
        I,
        "Number of dimensions",
    ),
    elementwise(op(
        "noEvent",
        Kind::Special,
        Fixed(1),
        &[ANY],
        ANY,
        "Relations inside generate no events",
    )),
    op(
        "ones",
        Kind::ArrayConstructor,
        Variadic(1),
        &[I],
        A,
        "ones(n1, n2, ...): an Integer array of ones",
    ),
    op(
        "outerProduct",
        Kind::ArrayFunction,
        Fixed(2),
        &[A, A],
        A,
        "Outer product of two vectors",
    ),
    elementwise(with_events(
        op(
            "pre",
            Kind::Event,
            Fixed(1),
            &[ANY],
            ANY,
            "Left limit of a variable at an event",
        ),
        Events::Operator,
    )),
    op(
        "product",
        Kind::Reduction,
        Fixed(1),
        &[A],
        Ty::SameAsArguments,
        "Product of the elements; also product(e for i in r)",
    ),
    op(
        "reinit",
        Kind::Statement,
        Fixed(2),
        &[R, R],
        Ty::Nothing,
        "reinit(x, e): a new value of a state at a when event",
    ),
    math2(
        "rem",
        Kind::Rounding,
        Fixed(2),
        maths::rem,
        Fn2::Rem,
        Derivative::Rem,
        Ty::SameAsArguments,
        "x - div(x, y) * y; triggers events",
    ),
    with_events(
        op(
            "sample",
            Kind::Event,
            Fixed(2),
            &[R, R],
            B,
            "sample(start, interval): true at the sample instants",
        ),
        Events::Operator,
    ),
    op(
        "scalar",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        ANY,
        "The one element of an array of size 1",
    ),
    op(
        "semiLinear",
        Kind::Special,
        Fixed(3),
        &[R, R, R],
        R,
        "semiLinear(x, k+, k-) = if x >= 0 then k+ x else k- x",
    ),
    Builtin {
        result: Ty::SameAsArguments,
        args: &[N],
        ..math1(
            "sign",
            maths::sign,
            Fn1::Sign,
            Derivative::Zero,
            "1, -1 or 0 (spec: expanded with noEvent, no events)",
        )
    },
    math1("sin", f64::sin, Fn1::Sin, Derivative::Cos, "Sine"),
    math1(
        "sinh",
        f64::sinh,
        Fn1::Sinh,
        Derivative::Cosh,
        "Hyperbolic sine",
    ),
    op(
        "size",
        Kind::Query,
        Range(1, 2),
        &[A, I],
        I,
        "size(a, k): a dimension; size(a): all of them",
    ),
    op(
        "skew",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        A,
        "The skew-symmetric matrix of a 3-vector",
    ),
    op(
        "smooth",
        Kind::Special,
        Fixed(2),
        &[I, ANY],
        ANY,
        "smooth(p, e): e, continuously differentiable p times",
    ),
    math1(
        "sqrt",
        f64::sqrt,
        Fn1::Sqrt,
        Derivative::HalfReciprocalOfValue,
        "Square root; NaN below 0",
    ),
    op(
        "String",
        Kind::Conversion,
        Variadic(1),
        &[ANY],
        Ty::String,
        "The value as text",
    ),
    op(
        "sum",
        Kind::Reduction,
        Fixed(1),
        &[A],
        Ty::SameAsArguments,
        "Sum of the elements; also sum(e for i in r)",
    ),
    op(
        "symmetric",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        A,
        "The upper triangle mirrored",
    ),
    math1(
        "tan",
        f64::tan,
        Fn1::Tan,
        Derivative::OnePlusSquareOfValue,
        "Tangent",
    ),
    math1(
        "tanh",
        f64::tanh,
        Fn1::Tanh,
        Derivative::OneMinusSquareOfValue,
        "Hyperbolic tangent",
    ),
    with_events(
        op(
            "terminal",
            Kind::Event,
            Fixed(0),
            &[],
            B,
            "True at the end of a successful simulation",
        ),
        Events::Operator,
    ),
    op(
        "terminate",
        Kind::Statement,
        Fixed(1),
        &[Ty::String],
        Ty::Nothing,
        "Ends the simulation successfully",
    ),
    op(
        "transpose",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        A,
        "Swaps the first two dimensions",
    ),
    op(
        "vector",
        Kind::ArrayFunction,
        Fixed(1),
        &[A],
        A,
        "The array as a vector",
    ),
    op(
        "zeros",
        Kind::ArrayConstructor,
        Variadic(1),
        &[I],
        A,
        "zeros(n1, n2, ...): an Integer array of zeros",
    ),
    op(
        "Integer",
        Kind::Conversion,
        Fixed(1),
        &[ANY],
        I,
        "The ordinal of an enumeration value",
    ),
    op(
        "Boolean",
        Kind::Conversion,
        Fixed(1),
        &[ANY],
        B,
        "Conversion to Boolean",
    ),
    op(
        "Real",
        Kind::Conversion,
        Fixed(1),
        &[ANY],
        R,
        "Conversion to Real",
    ),
    // Stream connectors (spec 15), synchronous features (16), state machines (17),
    // overconstrained connections (9.4): named, not implemented.
    unsupported("inStream", "Stream connectors (spec 15)"),
    unsupported("actualStream", "Stream connectors (spec 15)"),
    unsupported(
        "previous",
        "Clocked value before the current tick (spec 16)",
    ),
    unsupported("Clock", "Clock constructor (spec 16)"),
    unsupported("superSample", "Clock conversion (spec 16)"),
    unsupported("subSample", "Clock conversion (spec 16)"),
    unsupported("shiftSample", "Clock conversion (spec 16)"),
    unsupported("backSample", "Clock conversion (spec 16)"),
    unsupported("hold", "Clocked to continuous (spec 16)"),
    unsupported("interval", "Clock interval (spec 16)"),
    unsupported("firstTick", "First clock tick (spec 16)"),
    unsupported("noClock", "Clocked value without a clock (spec 16)"),
    unsupported("transition", "State machine transition (spec 17)"),
    unsupported("initialState", "State machine initial state (spec 17)"),
    unsupported("activeState", "State machine query (spec 17)"),
    unsupported("ticksInState", "State machine query (spec 17)"),
    unsupported("timeInState", "State machine query (spec 17)"),
    unsupported(
        "spatialDistribution",
        "Transport delay in space (spec 3.7.4.2)",
    ),
    unsupported(
        "getInstanceName",
        "The instance name (replaced by its text in flattening)",
    ),
    unsupported(
        "Connections.branch",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported("Connections.root", "Overconstrained connections (spec 9.4)"),
    unsupported(
        "Connections.potentialRoot",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported(
        "Connections.isRoot",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported(
        "Connections.rooted",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported(
        "Connections.uniqueRoot",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported(
        "Connections.uniqueRootIndices",
        "Overconstrained connections (spec 9.4)",
    ),
    unsupported(
        "rooted",
        "Overconstrained connections (deprecated form, spec 9.4)",
    ),
];
