//! Errors of the lowering and structural stages (`E3xxx`), as data; the CLI renders.
//! `DaeError` has one variant per situation, with the names, sizes and spans its message
//! uses; `From<DaeError> for Diagnostic` adds its labels, notes and help.

use crate::tensor::fmt_dims;
use unimo_source::{Diagnostic, Span};

/// The codes of the lowering and structural stages, one variant each; `docs/errors.md`
/// has a row per code (a test checks it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DaeCode {
    /// E3001: a construct the back end does not support yet.
    Unsupported,
    /// E3002: an index, size or range that must be known at compile time is not.
    NotKnownAtCompileTime,
    /// E3003: array sizes do not match, or a scalar was needed.
    SizeMismatch,
    /// E3004: a call of something that is not a known function.
    UnknownFunction,
    /// E3005: missing, surplus or unknown arguments of a call.
    WrongArguments,
    /// E3006: `reinit` of a variable that is not a state.
    ReinitOfNonState,
    /// E3007: inside `when`: a left side that is not a variable, or a nested `when`.
    InvalidInWhen,
    /// E3010: a reference to something the flat model has no scalar for.
    NoSuchScalar,
    /// E3011: branches of a non-parameter `if`-equation with different numbers of equations.
    UnequalIfBranches,
    /// E3012: a function output or local used before it is assigned.
    UnassignedLocal,
    /// E3013: an index out of bounds.
    IndexOutOfBounds,
    /// E3014: `pre`, `edge` or `change` of something that is not a variable.
    PreOfNonVariable,
    /// E3015: a `while` loop known at compile time that does not end.
    EndlessLoop,
    /// E3016: a function assigns a model variable.
    FunctionAssignsModel,
    /// E3017: `reinit` outside `when`.
    ReinitOutsideWhen,
    /// E3018: functions calling each other too deep while inlined.
    InliningTooDeep,
    /// E3019: wrong arguments of the collision built-ins.
    CollisionArguments,
    /// E3020: an external function unimo does not provide, or bad arguments of one it does.
    MissingExternal,
    /// E3021: a table given as an empty matrix.
    EmptyTable,
    /// E3022: the plan needs the derivative of a top-level input.
    DifferentiatedInput,
    /// E3023: an `experiment` setting of unimo's with a value it does not know.
    ExperimentSetting,
    /// E3024: `delay` with arguments the specification does not allow.
    DelayArguments,
    /// W3001 (a warning): a call statement that is not executed, since the function
    /// reaches an external function unimo does not provide (writing a file, printing).
    CallNotExecuted,
    /// E3201: the model is structurally singular.
    StructurallySingular,
    /// E3202: index reduction must differentiate an equation that cannot be.
    CannotDifferentiate,
    /// E3203: index reduction would differentiate an equation too often.
    DifferentiationLimit,
    /// E3204: no dummy derivatives can be chosen at some level.
    NoDummyDerivatives,
    /// E3290: an internal consistency error of the structural algorithms (a bug).
    InternalStructure,
}

impl DaeCode {
    /// Every code of the stage.
    pub const ALL: &'static [DaeCode] = &[
        DaeCode::Unsupported,
        DaeCode::NotKnownAtCompileTime,
        DaeCode::SizeMismatch,
        DaeCode::UnknownFunction,
        DaeCode::WrongArguments,
        DaeCode::ReinitOfNonState,
        DaeCode::InvalidInWhen,
        DaeCode::NoSuchScalar,
        DaeCode::UnequalIfBranches,
        DaeCode::UnassignedLocal,
        DaeCode::IndexOutOfBounds,
        DaeCode::PreOfNonVariable,
        DaeCode::EndlessLoop,
        DaeCode::FunctionAssignsModel,
        DaeCode::ReinitOutsideWhen,
        DaeCode::InliningTooDeep,
        DaeCode::CollisionArguments,
        DaeCode::MissingExternal,
        DaeCode::EmptyTable,
        DaeCode::DifferentiatedInput,
        DaeCode::ExperimentSetting,
        DaeCode::DelayArguments,
        DaeCode::CallNotExecuted,
        DaeCode::StructurallySingular,
        DaeCode::CannotDifferentiate,
        DaeCode::DifferentiationLimit,
        DaeCode::NoDummyDerivatives,
        DaeCode::InternalStructure,
    ];

    /// Whether the code is a warning (`W3xxx`): reported, and the model goes on.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }

    /// The code as printed (`E3001`).
    pub fn as_str(self) -> &'static str {
        match self {
            DaeCode::Unsupported => "E3001",
            DaeCode::NotKnownAtCompileTime => "E3002",
            DaeCode::SizeMismatch => "E3003",
            DaeCode::UnknownFunction => "E3004",
            DaeCode::WrongArguments => "E3005",
            DaeCode::ReinitOfNonState => "E3006",
            DaeCode::InvalidInWhen => "E3007",
            DaeCode::NoSuchScalar => "E3010",
            DaeCode::UnequalIfBranches => "E3011",
            DaeCode::UnassignedLocal => "E3012",
            DaeCode::IndexOutOfBounds => "E3013",
            DaeCode::PreOfNonVariable => "E3014",
            DaeCode::EndlessLoop => "E3015",
            DaeCode::FunctionAssignsModel => "E3016",
            DaeCode::ReinitOutsideWhen => "E3017",
            DaeCode::InliningTooDeep => "E3018",
            DaeCode::CollisionArguments => "E3019",
            DaeCode::MissingExternal => "E3020",
            DaeCode::EmptyTable => "E3021",
            DaeCode::DifferentiatedInput => "E3022",
            DaeCode::ExperimentSetting => "E3023",
            DaeCode::DelayArguments => "E3024",
            DaeCode::CallNotExecuted => "W3001",
            DaeCode::StructurallySingular => "E3201",
            DaeCode::CannotDifferentiate => "E3202",
            DaeCode::DifferentiationLimit => "E3203",
            DaeCode::NoDummyDerivatives => "E3204",
            DaeCode::InternalStructure => "E3290",
        }
    }
}

impl std::fmt::Display for DaeCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The help of every size, index and range that must be a constant.
const CONSTANT_HELP: &str = "sizes, indices and ranges must be known at compile time";

/// `sep`-joined.
fn joined(items: &[String], sep: &str) -> String {
    items.join(sep)
}

unimo_source::coded_errors! {
    /// A lowering or analysis error: its code is `code()`, its message `to_string()`.
    pub enum DaeError: DaeCode {
        /// E3001: a construct the back end does not support yet (`what`).
        #[error("not supported yet: {what}")]
        Unsupported { what: String, span: Span } = DaeCode::Unsupported,
        |d| d.at(span, "here"),
        /// E3023: `experiment(__unimo_method = ...)` that names no method unimo has.
        #[error("`__unimo_method = {given}` names no integration method")]
        UnknownMethod { given: String, span: Span } = DaeCode::ExperimentSetting,
        |d| d.at(span, "here").with_help("one of \"auto\", \"bdf\", \"radau5\", \"dopri5\" (a string)"),
        /// E3024: `delay(e, delayTime)` whose delay time is not a parameter expression.
        #[error("the delay time of `delay(e, delayTime)` must be a parameter expression")]
        DelayTimeNotParameter { span: Span } = DaeCode::DelayArguments,
        |d| d
            .at(span, "this varies during the simulation")
            .with_help("give the largest delay as a third argument: `delay(e, delayTime, delayMax)` with a parameter `delayMax`"),
        /// E3024: other arguments of `delay` the specification does not allow (`what`
        /// says which).
        #[error("`delay` {what}")]
        DelayArguments { what: &'static str, span: Span } = DaeCode::DelayArguments,
        |d| d.at(span, "here"),
        /// E3001: a `connect` equation that flattening should have replaced.
        #[error("a `connect` survived flattening")]
        ConnectAfterFlattening { span: Span } = DaeCode::Unsupported,
        |d| d.at(span, "here"),
        /// E3002: the index of an assigned element that is not a constant.
        #[error("an assigned element's index must be known at compile time")]
        AssignedIndexNotConstant { span: Span } = DaeCode::NotKnownAtCompileTime,
        |d| d.at(span, "here"),
        /// E3002: a constant Integer needed (a size, an index, a dimension number).
        #[error("a constant integer is needed here")]
        ConstantIntegerNeeded { span: Span } = DaeCode::NotKnownAtCompileTime,
        |d| d.at(span, "here").with_help(CONSTANT_HELP),
        /// E3002: a range bound or step that is not a constant.
        #[error("a range bound must be known at compile time")]
        RangeBoundNotConstant { span: Span } = DaeCode::NotKnownAtCompileTime,
        |d| d.at(span, "here"),
        /// E3003: more subscripts than the array has dimensions.
        #[error("{count} subscripts on an array of size {}", fmt_dims(.dims))]
        TooManySubscripts { count: usize, dims: Vec<usize>, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: `sum`, `product`, `min` or `max` of an empty array.
        #[error("`{function}` of an empty array")]
        ReductionOfEmpty { function: String, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: `size(x, k)` with a dimension `x` does not have.
        #[error("dimension {dimension} does not exist")]
        NoSuchDimension { dimension: i64, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: `end` outside a subscript.
        #[error("`end` outside a subscript")]
        EndOutsideSubscript { span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: a range with a step of zero.
        #[error("a range step of zero")]
        ZeroRangeStep { span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: a range with more than 1e7 elements.
        #[error("a range with more than 1e7 elements")]
        RangeTooLong { span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: `/` with an array divisor.
        #[error("division by an array")]
        DivisionByArray { span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: an array where a scalar is needed.
        #[error("a scalar is needed here, found an array of size {}", fmt_dims(.dims))]
        ScalarNeeded { dims: Vec<usize>, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: operands (or, with `equation`, the sides of an equation) whose array
        /// sizes differ.
        #[error("array sizes do not match: {} and {}", fmt_dims(.left), fmt_dims(.right))]
        SizesDiffer { left: Vec<usize>, right: Vec<usize>, equation: bool, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, if equation {
            "the two sides of this equation differ in size"
        } else {
            "in this expression"
        }),
        /// E3003: `transpose` of something that is not a matrix.
        #[error("transpose needs a matrix, found {}", fmt_dims(.dims))]
        TransposeNeedsMatrix { dims: Vec<usize>, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3003: concatenation along a dimension (counted from 1) the arrays lack.
        #[error("cannot concatenate along dimension {dimension} of {}", fmt_dims(.dims))]
        ConcatenationDimension { dimension: usize, dims: Vec<usize>, span: Span } = DaeCode::SizeMismatch,
        |d| d.at(span, "here"),
        /// E3004: a call of something that is not a known function.
        #[error("`{name}` is not a known function")]
        UnknownFunction { name: String, span: Span } = DaeCode::UnknownFunction,
        |d| d.at(span, "here"),
        /// E3005: `reinit` without its two arguments.
        #[error("`reinit` needs two arguments")]
        ReinitArguments { span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: `assert` without a condition.
        #[error("`assert` needs a condition")]
        AssertWithoutCondition { span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: `Unimo.invariant` with other than one positional argument.
        #[error("`Unimo.invariant` needs one argument, the expression that stays 0")]
        InvariantArguments { span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: more positional arguments than the function has inputs.
        #[error("too many arguments for `{function}`")]
        TooManyArguments { function: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a named argument that is no input of the function.
        #[error("`{function}` has no input `{input}`")]
        NoSuchInput { function: String, input: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: an input without argument or default.
        #[error("input `{input}` of `{function}` is not given")]
        InputNotGiven { input: String, function: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a built-in's positional argument (counted from 1) that is missing.
        #[error("argument {position} is missing")]
        ArgumentMissing { position: usize, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a reduction (`sum(... for ...)`) without its expression.
        #[error("a reduction needs an expression")]
        ReductionWithoutExpression { span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a record constructor with more arguments than fields.
        #[error("too many arguments for record `{record}`")]
        RecordConstructorArity { record: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a named argument of a record constructor that is no field.
        #[error("record `{record}` has no field `{field}`")]
        RecordConstructorField { record: String, field: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3005: a field of a record constructor without argument or default.
        #[error("field `{field}` of record `{record}` is not given")]
        RecordFieldNotGiven { field: String, record: String, span: Span } = DaeCode::WrongArguments,
        |d| d.at(span, "here"),
        /// E3006: `reinit` of something that is not a variable.
        #[error("`reinit` needs a state variable")]
        ReinitNeedsVariable { span: Span } = DaeCode::ReinitOfNonState,
        |d| d.at(span, "here"),
        /// E3006: `reinit` of a variable that is not a state.
        #[error("`reinit` of `{name}`, which is not a state")]
        ReinitOfNonState { name: String, span: Span } = DaeCode::ReinitOfNonState,
        |d| d
            .at(span, "this reinit")
            .with_help("only a variable that appears differentiated (`der(x)`) can be reinitialized (spec 8.3.6)"),
        /// E3007: a `when` equation inside `when`.
        #[error("`when` cannot be nested inside `when`")]
        NestedWhen { span: Span } = DaeCode::InvalidInWhen,
        |d| d.at(span, "here"),
        /// E3007: an equation in `when` whose left side is not a variable.
        #[error("the left side of an equation in `when` must be a variable")]
        WhenTargetNotVariable { span: Span } = DaeCode::InvalidInWhen,
        |d| d.at(span, "here"),
        /// E3010: an assignment to something that is not a variable.
        #[error("`{name}` is not a variable that can be assigned")]
        NotAssignable { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a reference the flat model has no variable for.
        #[error("`{name}` is not a variable of the flat model")]
        NoSuchVariable { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here").with_help("string variables are not lowered"),
        /// E3010: a part of a record value the flat model has no variable for.
        #[error("`{name}` is not a variable of the flat model")]
        NoSuchRecordPart { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a range of instances that the flat model does not have.
        #[error("`{name}` is not an instance of the flat model")]
        NoSuchInstance { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a global name that is neither a variable nor an enumeration literal.
        #[error("`{name}` is not a variable or enumeration literal")]
        NotVariableOrLiteral { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a record type the flat model does not have.
        #[error("`{name}` is not a known record")]
        UnknownRecord { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a field a record does not have.
        #[error("record `{record}` has no field `{field}`")]
        NoRecordField { record: String, field: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3010: a field selected from something that is not a record.
        #[error("`{name}` is not a record")]
        NotARecord { name: String, span: Span } = DaeCode::NoSuchScalar,
        |d| d.at(span, "here"),
        /// E3011: the branches of a non-parameter `if`-equation with different numbers of
        /// equations (`branch` counted from 1).
        #[error("the branches of this if-equation have different numbers of equations ({count} in branch {branch}, {else_count} in the else branch)")]
        UnequalIfBranches { count: usize, branch: usize, else_count: usize, span: Span } = DaeCode::UnequalIfBranches,
        |d| d
            .at(span, "here")
            .with_help("with a condition that is not a parameter, every branch needs the same number of equations (spec 8.3.4); add an else branch"),
        /// E3012: elements of a local assigned before its size is known.
        #[error("elements of `{name}` are assigned before its size is known")]
        AssignedBeforeSized { name: String, span: Span } = DaeCode::UnassignedLocal,
        |d| d.at(span, "here"),
        /// E3012: a function output that no path assigns.
        #[error("output `{output}` of `{function}` is never assigned")]
        OutputNeverAssigned { output: String, function: String, span: Span } = DaeCode::UnassignedLocal,
        |d| d.at(span, "here"),
        /// E3012: a function without outputs called in an expression.
        #[error("`{function}` has no output to use in an expression")]
        NoOutput { function: String, span: Span } = DaeCode::UnassignedLocal,
        |d| d.at(span, "here"),
        /// E3012: a local or output read before it is assigned.
        #[error("`{name}` is used before it is assigned")]
        UsedBeforeAssigned { name: String, span: Span } = DaeCode::UnassignedLocal,
        |d| d.at(span, "here"),
        /// E3013: a constant index outside `1..size`.
        #[error("index {index} is out of bounds 1..{size}")]
        IndexOutOfBounds { index: i64, size: usize, span: Span } = DaeCode::IndexOutOfBounds,
        |d| d.at(span, "here"),
        /// E3014: `pre`, `edge` or `change` (`operator`) of something that is not a variable.
        #[error("`{operator}` needs a variable")]
        NeedsVariable { operator: String, span: Span } = DaeCode::PreOfNonVariable,
        |d| d.at(span, "here"),
        /// E3015: a `while` loop known at compile time that does not end.
        #[error("a `while` loop ran a million times")]
        EndlessLoop { span: Span } = DaeCode::EndlessLoop,
        |d| d.at(span, "here"),
        /// E3016: a function assigns a model variable.
        #[error("a function assigns `{name}`, which is not one of its variables")]
        FunctionAssignsModel { name: String, span: Span } = DaeCode::FunctionAssignsModel,
        |d| d.at(span, "here"),
        /// E3017: `reinit` outside `when`.
        #[error("`reinit` is only allowed inside `when`")]
        ReinitOutsideWhen { span: Span } = DaeCode::ReinitOutsideWhen,
        |d| d.at(span, "here"),
        /// E3018: a function calling itself too deeply to be inlined.
        #[error("`{function}` calls itself too deeply to be inlined")]
        InliningTooDeep { function: String, span: Span } = DaeCode::InliningTooDeep,
        |d| d.at(span, "here"),
        /// E3019: `collisionGaps` with other arguments, or a second collision world.
        #[error("`collisionGaps` takes {count} scalar arguments and appears once per model; use one `Unimo.Collision.CollisionWorld`")]
        CollisionWorldArguments { count: usize, span: Span } = DaeCode::CollisionArguments,
        |d| d.at(span, "here"),
        /// E3019: `collisionBody` with another number of scalar arguments.
        #[error("`collisionBody` takes {expected} scalar arguments, got {given}; use `Unimo.Collision.CollisionBody` instead of calling it directly")]
        CollisionBodyArity { expected: usize, given: usize, span: Span } = DaeCode::CollisionArguments,
        |d| d.at(span, "here"),
        /// E3019: a constant shape or damping-law code (`what`) out of its range.
        #[error("`collisionBody`: {code} is not a {what} code (1..{count}); use `Unimo.Collision.CollisionBody`, whose enumerations give valid codes")]
        CollisionCode { code: f64, what: &'static str, count: usize, span: Span } = DaeCode::CollisionArguments,
        |d| d.at(span, "here"),
        /// E3020: an external function unimo does not provide.
        #[error("external function `{function}` (`{foreign}`) is not provided by unimo")]
        ExternalNotProvided { function: String, foreign: String, span: Span } = DaeCode::MissingExternal,
        |d| d
            .at(span, "here")
            .with_help("unimo implements the MSL's tables in Rust; other external C code cannot be linked"),
        /// E3020: a String argument of an external function that is not known at
        /// compile time.
        #[error("`{function}` needs a String known at compile time (a literal or getInstanceName())")]
        ExternalStringNotKnown { function: String, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: a random number generator's state vector that is too short.
        #[error("`{function}` needs a state vector of {needed} Integers, not {given}")]
        StateVectorSize { function: String, needed: usize, given: usize, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: a use of the impure random number generator unimo cannot provide
        /// (`what` says which).
        #[error("external function `Modelica.Math.Random.Utilities.impureRandom` (`ModelicaRandom_impureRandom_xorshift1024star`) {what}")]
        ImpureRandom { what: &'static str, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: an external call that does not pass its outputs as the function
        /// unimo provides does.
        #[error("`{function}` must pass its outputs to `{foreign}`")]
        ExternalOutputs { function: String, foreign: String, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: an external FFT call that does not pass its outputs as rawRealFFT does.
        #[error("`{function}` must pass its outputs to `{foreign}` as rawRealFFT does")]
        FftOutputs { function: String, foreign: String, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: an empty array given to an external function.
        #[error("an empty argument of `{foreign}`")]
        EmptyExternalArgument { foreign: String, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3020: an external function called with too few arguments.
        #[error("`{foreign}` is called with too few arguments")]
        TooFewExternalArguments { foreign: String, span: Span } = DaeCode::MissingExternal,
        |d| d.at(span, "here"),
        /// E3021: a table given as an empty matrix.
        #[error("the table is empty: tables read from files (`tableOnFile = true`) are not supported yet; give the table as a matrix")]
        EmptyTable { span: Span } = DaeCode::EmptyTable,
        |d| d.at(span, "here"),
        /// E3022: the plan needs the derivative of a top-level input.
        #[error("the model needs `{derivative}`, the derivative of the top-level input `{input}`, which is not given")]
        DifferentiatedInput { derivative: String, input: String, span: Span } = DaeCode::DifferentiatedInput,
        |d| d
            .at(span, "a top-level input")
            .with_note(
                "index reduction differentiated an equation that reads this input (a derivative of an \
                 output that follows the input algebraically, or a constraint through it)",
            )
            .with_help(format!(
                "give `{input}` an equation inside the model (drop `input`), or pass it through a state \
                 (`der(uf) = (u - uf)/T`) and use the filtered value"
            )),
        /// W3001: a call statement that is not executed, since the function reaches an
        /// external function unimo does not provide (`missing`).
        #[error("the call of `{function}` is not executed: it calls the external function `{missing}`, which unimo does not provide (its effects, such as a file written or a message printed, do not happen)")]
        CallNotExecuted { function: String, missing: String, span: Span } = DaeCode::CallNotExecuted,
        |d| d.at(span, "not executed"),
        /// E3201: the model is structurally singular (`report`: the parts named).
        #[error("the model is structurally singular: {} equation(s) too many for their variables, {} variable(s) not determined", .report.too_many, .report.undetermined)]
        StructurallySingular { report: Box<SingularReport>, span: Span } = DaeCode::StructurallySingular,
        |d| report.notes(d.at(span, report.label()))
            .with_help("remove a redundant equation or add one for an undetermined variable"),
        /// E3202: index reduction must differentiate an equation that cannot be.
        #[error("index reduction must differentiate `{equation}` but cannot: {reason}")]
        CannotDifferentiate { equation: String, reason: String, span: Span } = DaeCode::CannotDifferentiate,
        |d| d.at(span, "this constraint"),
        /// E3203: index reduction would differentiate an equation too often.
        #[error("index reduction would differentiate `{equation}` more than {limit} times")]
        DifferentiationLimit { equation: String, limit: u32, span: Span } = DaeCode::DifferentiationLimit,
        |d| d
            .at(span, "here")
            .with_help("the model is probably structurally singular or of very high index"),
        /// E3204: no dummy derivatives can be chosen at some level.
        #[error("no dummy derivatives can be chosen at level {level} for: {}", joined(.equations, "; "))]
        NoDummyDerivatives { level: u32, equations: Vec<String>, span: Span } = DaeCode::NoDummyDerivatives,
        |d| d.at(span, "here"),
        /// E3290: an internal consistency error of the structural algorithms (a bug).
        #[error("internal structural error: {detail}")]
        InternalStructure { detail: String, span: Span } = DaeCode::InternalStructure,
        |d| d.at(span, "here"),
        /// The error `error` met while inlining the function `function`: its code and
        /// message, with a note naming the innermost function inlined.
        #[error("{error}")]
        WhileInlining { function: String, error: Box<DaeError> } = error.code(),
        |d| Diagnostic::from(*error).with_note(format!("while inlining `{function}`")),
    }
}

/// What a structurally singular model's diagnostic names: the counts of its message and
/// (at most eight of) the equations and variables of its over- and under-determined parts.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SingularReport {
    /// Equations too many for their variables.
    pub too_many: usize,
    /// Variables no equation determines.
    pub undetermined: usize,
    pub over_equations: Vec<String>,
    pub over_variables: Vec<String>,
    pub under_variables: Vec<String>,
    /// Every under-determined variable and equation (`UNIMO_DEBUG_STRUCTURE`).
    pub debug: Option<String>,
}

impl SingularReport {
    fn label(&self) -> &'static str {
        if self.over_equations.is_empty() {
            "declared here"
        } else {
            "this equation is part of the over-determined set"
        }
    }

    fn notes(&self, mut d: Diagnostic) -> Diagnostic {
        if !self.over_equations.is_empty() {
            d = d.with_note(format!(
                "over-determined equations: {}",
                joined(&self.over_equations, "; ")
            ));
            d = d.with_note(if self.over_variables.is_empty() {
                "they involve no unknown once aliases and constants are substituted".to_owned()
            } else {
                format!("they only involve: {}", joined(&self.over_variables, ", "))
            });
        }
        if !self.under_variables.is_empty() {
            d = d.with_note(format!(
                "under-determined variables: {}",
                joined(&self.under_variables, ", ")
            ));
            if let Some(all) = &self.debug {
                d = d.with_note(all.clone());
            }
        }
        d
    }
}

impl DaeError {
    /// The error itself, without the functions inlined around it.
    pub fn innermost(&self) -> &DaeError {
        match self {
            DaeError::WhileInlining { error, .. } => error.innermost(),
            e => e,
        }
    }

    /// The error met while inlining `function`: the innermost function is named once.
    pub fn while_inlining(self, function: &str) -> DaeError {
        match self {
            e @ DaeError::WhileInlining { .. } => e,
            e => DaeError::WhileInlining {
                function: function.to_owned(),
                error: Box::new(e),
            },
        }
    }

    pub fn to_diagnostic(&self) -> Diagnostic {
        self.clone().into()
    }
}

#[cfg(test)]
impl Default for DaeError {
    fn default() -> DaeError {
        DaeError::EndlessLoop {
            span: Span::default(),
        }
    }
}

pub type DaeResult<T> = Result<T, DaeError>;

#[cfg(test)]
mod tests {
    use super::*;

    /// The code a variant's doc comment starts with (`E3003: ...`), if it names one.
    fn documented_code(doc: &str) -> Option<&str> {
        let code = doc.trim_start().split(':').next()?;
        DaeCode::ALL.iter().map(|c| c.as_str()).find(|c| *c == code)
    }

    #[test]
    fn every_code_has_a_variant() {
        for code in DaeCode::ALL {
            assert!(
                DaeError::VARIANT_DOCS
                    .iter()
                    .any(|(_, doc)| documented_code(doc) == Some(code.as_str())),
                "{code} has no variant"
            );
        }
    }

    #[test]
    fn each_variant_maps_to_its_documented_code_and_severity() {
        let samples = DaeError::samples();
        assert_eq!(samples.len(), DaeError::VARIANT_DOCS.len());
        for (e, (variant, doc)) in samples.into_iter().zip(DaeError::VARIANT_DOCS) {
            let code = e.code();
            match documented_code(doc) {
                Some(documented) => assert_eq!(code.as_str(), documented, "{variant}"),
                // Only the wrapper names no code: it has its inner error's.
                None => assert_eq!(code, e.innermost().code(), "{variant}"),
            }
            let d = e.to_diagnostic();
            assert_eq!(d.code.0, code.as_str(), "{variant}");
            assert_eq!(d.is_error(), !code.is_warning(), "{variant}");
            assert_eq!(d.message, e.to_string(), "{variant}");
            assert!(d.primary_span().is_some(), "{variant} has no primary label");
        }
    }

    #[test]
    fn the_diagnostic_carries_the_code_label_and_notes() {
        let e = DaeError::ReinitOfNonState {
            name: "x".into(),
            span: Span::default(),
        }
        .while_inlining("f")
        .while_inlining("g");
        let d = e.to_diagnostic();
        assert_eq!(d.code.0, "E3006");
        assert_eq!(d.message, "`reinit` of `x`, which is not a state");
        assert_eq!(d.labels[0].message, "this reinit");
        assert_eq!(d.notes, ["while inlining `f`"]);
        assert!(d.help.is_some_and(|h| h.contains("spec 8.3.6")));
    }
}
