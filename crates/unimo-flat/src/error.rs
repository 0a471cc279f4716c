//! The coded errors of the instantiation stage (`E2xxx`), turned into diagnostics.

use unimo_source::{Code, Diagnostic, Span};

/// The codes of the instantiation stage, one variant each; `docs/errors.md` has a row
/// per code (a test checks it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FlatCode {
    /// E2001: a name that denotes nothing where it is used.
    UnknownName,
    /// E2003: a value needed at compile time that cannot be evaluated.
    NotKnownAtCompileTime,
    /// E2004: a modifier of an element or attribute the class does not have.
    UnknownModifier,
    /// E2005: an element declared twice in one instance.
    DuplicateElement,
    /// E2006: `connect` of connectors whose variables differ.
    ConnectorMismatch,
    /// E2007: two outputs connected.
    OutputsConnected,
    /// E2008: a parameter or constant whose binding depends on itself.
    CyclicBinding,
    /// E2009: a `partial` class instantiated.
    PartialInstantiated,
    /// E2010: the model's equation and unknown counts differ.
    Unbalanced,
    /// E2011: instances nested more than 100 deep.
    TooDeep,
    /// E2012: `extends` of a predefined type in a long class.
    ExtendsPredefined,
    /// E2013: an `outer` component with no `inner`.
    MissingInner,
    /// E2014: the model is too large.
    TooLarge,
    /// E2015: a `redeclare` of an element that is not `replaceable`, or misplaced.
    InvalidRedeclare,
    /// E2016: a modifier of a `final` element.
    FinalModified,
    /// E2017: more subscripts than dimensions.
    TooManySubscripts,
    /// E2018: the sides of an equation or binding certainly differ in size or type.
    SideMismatch,
    /// E2019: a binding of higher variability than its variable.
    BindingVariability,
    /// E2020: an operator applied to a variable of the wrong type.
    OperatorType,
    /// E2021: `flow` or `stream` on a non-Real component.
    FlowNotReal,
    /// E2022: a protected element accessed through dot notation.
    ProtectedAccess,
    /// E2023: a modifier of a protected element.
    ProtectedModified,
    /// E2024: `each` where nothing is an array.
    EachOnScalar,
    /// E2025: an assignment to a constant, or to a parameter outside initial algorithms.
    AssignsConstant,
    /// E2026: an assignment to a function's input.
    AssignsInput,
    /// E2027: a class restriction broken.
    ClassRestriction,
    /// E2028: a prefix where it is not allowed.
    MisplacedPrefix,
    /// E2029: a `pure` function calls an `impure` one.
    PureCallsImpure,
    /// E2030: an argument of `connect` that is not a connector.
    ConnectNonConnector,
    /// E2031: a connector connected to itself.
    ConnectToItself,
    /// E2032: `pre` of a continuous-time Real outside `when`.
    PreOfContinuous,
    /// W2001 (a warning): a parameter with neither a binding nor a start value.
    UnboundParameter,
    /// E2033: a discrete-time variable given a continuous-time value outside `when`.
    DiscreteGivenContinuous,
    /// E2034: a stream connector without exactly one flow variable.
    StreamFlowCount,
    /// E2035: an `inner` component whose type is not a subtype of the `outer` one's.
    InnerOuterMismatch,
    /// W2002 (a warning): an `outer` component without `inner`, created by default.
    DefaultInner,
    /// E2036: an overconstrained-connection operator misused.
    Overconstrained,
    /// E2037: a connector whose flow and potential variable counts differ.
    UnbalancedConnector,
}

impl FlatCode {
    /// Every code of the stage.
    pub const ALL: &'static [FlatCode] = &[
        FlatCode::UnknownName,
        FlatCode::NotKnownAtCompileTime,
        FlatCode::UnknownModifier,
        FlatCode::DuplicateElement,
        FlatCode::ConnectorMismatch,
        FlatCode::OutputsConnected,
        FlatCode::CyclicBinding,
        FlatCode::PartialInstantiated,
        FlatCode::Unbalanced,
        FlatCode::TooDeep,
        FlatCode::ExtendsPredefined,
        FlatCode::MissingInner,
        FlatCode::TooLarge,
        FlatCode::InvalidRedeclare,
        FlatCode::FinalModified,
        FlatCode::TooManySubscripts,
        FlatCode::SideMismatch,
        FlatCode::BindingVariability,
        FlatCode::OperatorType,
        FlatCode::FlowNotReal,
        FlatCode::ProtectedAccess,
        FlatCode::ProtectedModified,
        FlatCode::EachOnScalar,
        FlatCode::AssignsConstant,
        FlatCode::AssignsInput,
        FlatCode::ClassRestriction,
        FlatCode::MisplacedPrefix,
        FlatCode::PureCallsImpure,
        FlatCode::ConnectNonConnector,
        FlatCode::ConnectToItself,
        FlatCode::PreOfContinuous,
        FlatCode::UnboundParameter,
        FlatCode::DiscreteGivenContinuous,
        FlatCode::StreamFlowCount,
        FlatCode::InnerOuterMismatch,
        FlatCode::DefaultInner,
        FlatCode::Overconstrained,
        FlatCode::UnbalancedConnector,
    ];

    /// Whether the code is a warning (`W2xxx`): reported, and flattening goes on.
    pub fn is_warning(self) -> bool {
        self.as_str().starts_with('W')
    }

    /// The code as printed (`E2001`).
    pub fn as_str(self) -> &'static str {
        match self {
            FlatCode::UnknownName => "E2001",
            FlatCode::NotKnownAtCompileTime => "E2003",
            FlatCode::UnknownModifier => "E2004",
            FlatCode::DuplicateElement => "E2005",
            FlatCode::ConnectorMismatch => "E2006",
            FlatCode::OutputsConnected => "E2007",
            FlatCode::CyclicBinding => "E2008",
            FlatCode::PartialInstantiated => "E2009",
            FlatCode::Unbalanced => "E2010",
            FlatCode::TooDeep => "E2011",
            FlatCode::ExtendsPredefined => "E2012",
            FlatCode::MissingInner => "E2013",
            FlatCode::TooLarge => "E2014",
            FlatCode::InvalidRedeclare => "E2015",
            FlatCode::FinalModified => "E2016",
            FlatCode::TooManySubscripts => "E2017",
            FlatCode::SideMismatch => "E2018",
            FlatCode::BindingVariability => "E2019",
            FlatCode::OperatorType => "E2020",
            FlatCode::FlowNotReal => "E2021",
            FlatCode::ProtectedAccess => "E2022",
            FlatCode::ProtectedModified => "E2023",
            FlatCode::EachOnScalar => "E2024",
            FlatCode::AssignsConstant => "E2025",
            FlatCode::AssignsInput => "E2026",
            FlatCode::ClassRestriction => "E2027",
            FlatCode::MisplacedPrefix => "E2028",
            FlatCode::PureCallsImpure => "E2029",
            FlatCode::ConnectNonConnector => "E2030",
            FlatCode::ConnectToItself => "E2031",
            FlatCode::PreOfContinuous => "E2032",
            FlatCode::UnboundParameter => "W2001",
            FlatCode::DiscreteGivenContinuous => "E2033",
            FlatCode::StreamFlowCount => "E2034",
            FlatCode::InnerOuterMismatch => "E2035",
            FlatCode::DefaultInner => "W2002",
            FlatCode::Overconstrained => "E2036",
            FlatCode::UnbalancedConnector => "E2037",
        }
    }
}

impl From<FlatCode> for Code {
    fn from(c: FlatCode) -> Code {
        Code(c.as_str())
    }
}

impl std::fmt::Display for FlatCode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The help of every value that flattening must evaluate and cannot.
const EVALUATE_HELP: &str = "sizes, `for` ranges and conditions of conditional components and structural `if`s must be parameters or constants";

/// `", "`-joined.
fn list(items: &[String]) -> String {
    items.join(", ")
}

/// `s` after a count other than one.
fn plural(n: &usize) -> &'static str {
    if *n == 1 {
        ""
    } else {
        "s"
    }
}

unimo_source::coded_errors! {
    /// Errors found while looking up names and instantiating classes, one variant per
    /// situation with the names, spans and counts its message uses; each turns into the
    /// diagnostic with its code, labels, help and notes (`From<FlatError> for Diagnostic`).
    pub enum FlatError: FlatCode {
        /// E2001: a name that denotes nothing in its scope.
        #[error("unknown {what} `{name}`")]
        UnknownName {
            name: String,
            what: &'static str,
            span: Span,
            suggestion: Option<String>,
            encapsulated: bool,
        } = FlatCode::UnknownName,
        |d| {
            let d = d.at(span, "not found in this scope");
            let d = match (suggestion, encapsulated) {
                (_, true) => d.with_help(format!(
                    "the enclosing class is `encapsulated`: global names are hidden; add `import {name};`"
                )),
                (Some(s), false) => d.with_help(format!("did you mean `{s}`?")),
                (None, false) => d,
            };
            d.with_note(
                "names are searched in the class (with inherited elements), its imports, \
                 the enclosing classes and the library (Modelica spec 5.3)",
            )
        },
        /// E2001: an element read from a component of a predefined type (`x.unit`).
        #[error("unknown name `{reference}`: `{first}` is of type {base}, which has no elements")]
        ElementOfPredefined {
            reference: String,
            first: String,
            base: &'static str,
            member: String,
            span: Span,
            declared: Span,
        } = FlatCode::UnknownName,
        |d| d
            .at(span, "not an element")
            .with_label(declared, "declared here")
            .with_help(format!(
                "attributes such as `{member}` are set by modifiers (`{first}({member} = ...)`), not read as elements"
            ))
            .with_note("Modelica specification, section 4.9: the attributes of predefined types"),
        /// E2003: a value needed at compile time reads a variable that is not a known
        /// parameter or constant.
        #[error("{context}: depends on {what}, which is not a known parameter or constant")]
        NotConstant { context: String, what: String, span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "needed at compile time").with_help(EVALUATE_HELP),
        /// E2003: a value needed at compile time that the evaluator cannot compute.
        #[error("{context}: cannot evaluate {what}")]
        CannotEvaluate { context: String, what: String, span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "needed at compile time").with_help(EVALUATE_HELP),
        /// E2008: a value needed at compile time reads a parameter bound to itself.
        #[error("{context}: parameter `{name}` depends on itself")]
        EvaluationCycle { context: String, name: String, span: Span } = FlatCode::CyclicBinding,
        |d| d.at(span, "needed at compile time").with_help(EVALUATE_HELP),
        /// E2003: a `for` equation without a range.
        #[error("a `for` equation needs an explicit range here")]
        ForWithoutRange { span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "no range"),
        /// E2003: a `for` range that evaluates to something other than an array.
        #[error("a `for` range must be an array")]
        ForRangeNotArray { span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "not an array"),
        /// E2003: the condition of a conditional component is not a Boolean.
        #[error("the condition of a conditional component must be Boolean")]
        ConditionNotBoolean { span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "not Boolean"),
        /// E2003: an array dimension that is not a non-negative Integer.
        #[error("an array dimension must be a non-negative Integer")]
        BadDimension { span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d.at(span, "here"),
        /// E2003: a `[:]` dimension whose size no constant binding gives.
        #[error("the size of `[:]` must follow from a constant binding")]
        ColonSizeUnknown { span: Span, refused: Option<String> } = FlatCode::NotKnownAtCompileTime,
        |d| {
            let d = d.at(span, "unknown size");
            match refused {
                Some(what) => d.with_note(format!("its binding cannot be evaluated: {what}")),
                None => d,
            }
        },
        /// E2003: a record parameter's binding that cannot be split into its fields.
        #[error("the binding of record parameter `{name}` is no record constructor, no other record and no value known at translation")]
        UnsplitRecordParameter { name: String, span: Span } = FlatCode::NotKnownAtCompileTime,
        |d| d
            .at(span, "this binding")
            .with_help("write a constructor call (`Complex(1, 2)`), a function call whose arguments are known at translation, or bind the fields one by one"),
        /// E2004: a record constructor called with more positional arguments than fields.
        #[error("record constructor `{record}` takes {expected} arguments, {given} given")]
        RecordConstructorArity { record: String, expected: usize, given: usize, span: Span } = FlatCode::UnknownModifier,
        |d| d.at(span, "these arguments"),
        /// E2004: a named argument of a record constructor that is no field.
        #[error("record `{record}` has no field `{field}` to construct")]
        NoRecordField { record: String, field: String, fields: Vec<String>, span: Span } = FlatCode::UnknownModifier,
        |d| d.at(span, "no such field").with_help(format!("its fields: {}", list(&fields))),
        /// E2004: a modifier of an element the modified class does not have.
        #[error("modifier of `{name}`, which `{class}` does not have")]
        ModifierOfMissing { name: String, class: String, span: Span } = FlatCode::UnknownModifier,
        |d| d.at(span, "value given here").with_help(format!(
            "the modified element must be declared in `{class}` or a class it extends"
        )),
        /// E2004: a modifier of a component of a predefined type that is no attribute.
        #[error("`{attribute}` is not an attribute of `{name}`")]
        NotAnAttribute { attribute: String, name: String, attributes: &'static [&'static str], span: Span } = FlatCode::UnknownModifier,
        |d| d.at(span, "value given here").with_help(format!(
            "attributes of predefined types: {}",
            attributes.join(", ")
        )),
        /// E2004: an attribute of the predefined types that this one does not have.
        #[error("`{attribute}` is not an attribute of {base}")]
        NotAttributeOfType { attribute: String, base: &'static str, allowed: &'static [&'static str], span: Span } = FlatCode::UnknownModifier,
        |d| d
            .at(span, "no such attribute")
            .with_help(format!("attributes of {base}: {}", allowed.join(", ")))
            .with_note("Modelica specification, section 4.9"),
        /// E2005: an element declared twice in one instance.
        #[error("`{name}` is declared twice in `{owner}`")]
        DuplicateElement { name: String, owner: String, second: Span, first: Span } = FlatCode::DuplicateElement,
        |d| d
            .at(second, "second declaration")
            .with_label(first, "first declared here (possibly in a base class)")
            .with_help("rename one of them; an inherited element and a local one share one name space"),
        /// E2006: a side of `connect` that is not a connector instance.
        #[error("`{name}` is not a connector instance")]
        NotAConnectorInstance { name: String, span: Span } = FlatCode::ConnectorMismatch,
        |d| d.at(span, "in this connect"),
        /// E2006: connected connectors whose variables differ.
        #[error("connectors `{a}` and `{b}` do not match")]
        ConnectorsDiffer { a: String, b: String, one_sided: Vec<String>, span: Span } = FlatCode::ConnectorMismatch,
        |d| d
            .at(span, "in this connect")
            .with_note(format!("variables on one side only: {}", list(&one_sided))),
        /// E2006: two connected variables of different kinds, shapes or types.
        #[error("`{a}` and `{b}` cannot be connected")]
        CannotConnect { a: String, b: String, why: String, span: Span } = FlatCode::ConnectorMismatch,
        |d| d.at(span, "in this connect").with_note(why),
        /// E2006: connected variables of which one is a parameter or constant and the
        /// other is not.
        #[error("`{a}.{member}` and `{b}.{member}` cannot be connected: {kind_a} and {kind_b}")]
        VariabilitiesDiffer {
            a: String,
            b: String,
            member: String,
            kind_a: &'static str,
            kind_b: &'static str,
            span: Span,
            declared_a: Span,
            declared_b: Span,
        } = FlatCode::ConnectorMismatch,
        |d| d
            .at(span, "in this connect")
            .with_label(declared_a, format!("{kind_a} here"))
            .with_label(declared_b, format!("{kind_b} here"))
            .with_note("Modelica specification, section 9.3: a connect equation matches parameters with parameters and constants with constants"),
        /// E2007: two outputs connected.
        #[error("two outputs connected: `{a}` and `{b}`")]
        OutputsConnected { a: String, b: String, span: Span } = FlatCode::OutputsConnected,
        |d| d
            .at(span, "in this connect")
            .with_help("an output may drive several inputs, but two outputs cannot be connected"),
        /// E2008: a parameter whose binding reads itself.
        #[error("parameter `{name}` depends on itself")]
        SelfDependentBinding { name: String, span: Span } = FlatCode::CyclicBinding,
        |d| d.at(span, "this binding is part of the cycle"),
        /// E2008: parameters whose bindings read each other in a cycle.
        #[error("the bindings of parameters depend on each other in a cycle: {}", .names.join(" -> "))]
        BindingCycle { names: Vec<String>, span: Span } = FlatCode::CyclicBinding,
        |d| d.at(span, "this binding is part of the cycle"),
        /// E2009: the model itself is `partial`.
        #[error("class `{name}` is partial and cannot be simulated")]
        PartialModel { name: String, span: Span } = FlatCode::PartialInstantiated,
        |d| d.at(span, "declared `partial`"),
        /// E2009: a component of a `partial` class.
        #[error("component `{name}` is an instance of the partial class `{class}`")]
        PartialComponent { name: String, class: String, span: Span, declared: Span } = FlatCode::PartialInstantiated,
        |d| d
            .at(span, "instance of a partial class")
            .with_label(declared, "declared `partial` here")
            .with_help("use a class that extends it, or redeclare the component with one"),
        /// E2010: the model's equation and unknown counts differ.
        #[error("model `{model}` is not balanced: {equations} equations for {unknowns} unknowns ({what}, {off} off)")]
        Unbalanced {
            model: String,
            equations: usize,
            unknowns: usize,
            what: &'static str,
            off: usize,
            orphans: Vec<String>,
            span: Span,
        } = FlatCode::Unbalanced,
        |d| {
            let mut d = d.at(span, "this model");
            if !orphans.is_empty() && equations < unknowns {
                d = d.with_note(format!("unknowns that no equation mentions: {}", list(&orphans)));
            }
            d.with_help("each unknown needs one equation; parameters, constants and top-level inputs are known")
        },
        /// E2011: a class whose instances contain themselves.
        #[error("instances of `{name}` nested {limit} deep in each other (a recursive model?)")]
        SelfNesting { name: String, limit: usize, span: Span } = FlatCode::TooDeep,
        |d| d.at(span, "this class contains itself"),
        /// E2011: instances nested deeper than the limit.
        #[error("instances nested more than {limit} deep (a recursive model?)")]
        TooDeep { limit: usize, span: Span } = FlatCode::TooDeep,
        |d| d.at(span, "in this class"),
        /// E2012: `extends` of a predefined type in a long class.
        #[error("extending a predefined type is only allowed in a short class definition")]
        ExtendsPredefined { span: Span } = FlatCode::ExtendsPredefined,
        |d| d.at(span, "here"),
        /// E2013: an `outer` component with no `inner`, and none can be made.
        #[error("`outer {name}` has no matching `inner` declaration")]
        MissingInner { name: String, why: String, span: Span } = FlatCode::MissingInner,
        |d| d
            .at(span, "declared `outer` here")
            .with_help(format!("declare `inner ... {name}` in an enclosing model"))
            .with_note(format!("no inner can be created by default: {why} (Modelica specification, section 5.4)")),
        /// E2014: more scalars and instances than the limit.
        #[error("the model is too large (more than {limit} scalars and instances)")]
        TooLarge { limit: usize, span: Span } = FlatCode::TooLarge,
        |d| d
            .at(span, "the limit was passed here")
            .with_help("check the array sizes and `for` ranges"),
        /// E2015: a `redeclare` element that replaces nothing of a base class.
        #[error("`redeclare` of `{name}`, which no base class declares")]
        RedeclareWithoutBase { name: String, span: Span } = FlatCode::InvalidRedeclare,
        |d| d
            .at(span, "redeclared here")
            .with_help("a redeclaration replaces a replaceable element of a base class"),
        /// E2015: a redeclaration of an element that is not `replaceable`.
        #[error("`{name}` is redeclared but not `replaceable`")]
        NotReplaceable { name: String, span: Span } = FlatCode::InvalidRedeclare,
        |d| d.at(span, "redeclared here").with_help(format!(
            "declare it `replaceable {name} ...` in the class that has it"
        )),
        /// E2015: a redeclared class without elements the class it replaces has.
        #[error("`{name}` is redeclared as a class without {}, which `{constraint}` has", list(.missing))]
        RedeclaredClassLacks { name: String, missing: Vec<String>, constraint: String, span: Span } = FlatCode::InvalidRedeclare,
        |d| d
            .at(span, "redeclared here")
            .with_help("a redeclared class must have every element of the class it replaces (or of its constraining class)"),
        /// E2015: a redeclared component with other dimensions.
        #[error("`{name}` is redeclared with {how}")]
        RedeclaredDimensions { name: String, how: String, span: Span, declared: Span } = FlatCode::InvalidRedeclare,
        |d| d
            .at(span, "redeclared here")
            .with_label(declared, "declared here")
            .with_help("a redeclared component keeps the dimensions of the one it replaces")
            .with_note("Modelica specification, section 7.3.2: the new declaration must be a subtype of the constraining one, arrays of the same sizes"),
        /// E2016: a modifier of a `final` element.
        #[error("`{name}` is declared `final` and cannot be modified")]
        FinalModified { name: String, span: Span, declared: Span } = FlatCode::FinalModified,
        |d| d.at(span, "modified here").with_label(declared, "declared `final` here"),
        /// E2016: a redeclaration of a `final` element.
        #[error("`{name}` is declared `final` and cannot be redeclared")]
        FinalRedeclared { name: String, span: Span, declared: Span } = FlatCode::FinalModified,
        |d| d
            .at(span, "redeclared here")
            .with_label(declared, "declared `final` here")
            .with_note("Modelica specification, section 7.2.6: a final element cannot be modified or redeclared"),
        /// E2017: more subscripts than dimensions.
        #[error("`{name}` has {dims} dimension{}, {given} subscripts given", plural(.dims))]
        TooManySubscripts { name: String, dims: usize, given: usize, span: Span } = FlatCode::TooManySubscripts,
        |d| d.at(span, "too many subscripts"),
        /// E2018: the sides of an equation that differ in size or type.
        #[error("the two sides have different {what}")]
        SidesDiffer { what: String, span: Span } = FlatCode::SideMismatch,
        |d| d.at(span, "in this equation"),
        /// E2019: a parameter's or constant's binding that reads `time` or a variable.
        #[error("the binding of {kind} `{name}` reads {reads}")]
        BindingVaries { kind: &'static str, name: String, reads: String, span: Span } = FlatCode::BindingVariability,
        |d| d.at(span, "varies in time").with_help(format!(
            "a {kind}'s value is fixed before the simulation starts: bind it to \
             parameters and constants, or declare `{name}` without the `{kind}` prefix"
        )),
        /// E2019: a constant's binding that reads a parameter.
        #[error("the binding of constant `{name}` reads the parameter `{parameter}`")]
        ConstantReadsParameter { name: String, parameter: String, span: Span, declared: Span } = FlatCode::BindingVariability,
        |d| d
            .at(span, "not a constant expression")
            .with_label(declared, "declared a parameter here")
            .with_help(format!("declare `{name}` a parameter, or bind it to constants only"))
            .with_note("Modelica specification, section 3.8.1"),
        /// E2020: `der` or `edge` of a variable of the wrong type.
        #[error("`{operator}` needs {needs}; this one is of type {ty}")]
        OperatorType { operator: String, needs: &'static str, ty: String, span: Span } = FlatCode::OperatorType,
        |d| d.at(span, "wrong type"),
        /// E2021: `flow` or `stream` on a non-Real component.
        #[error("`{word}` on `{name}`, of type {base}: {word} variables are Real")]
        FlowNotReal { word: &'static str, name: String, base: &'static str, span: Span } = FlatCode::FlowNotReal,
        |d| d
            .at(span, "not a Real type")
            .with_note("Modelica specification, section 9.3: flow and stream variables are subtypes of Real"),
        /// E2022: a protected element accessed through dot notation.
        #[error("`{name}` is protected: it cannot be accessed from outside")]
        ProtectedAccess { name: String, span: Span, declared: Span } = FlatCode::ProtectedAccess,
        |d| d
            .at(span, "protected element")
            .with_label(declared, "declared protected here")
            .with_note("Modelica specification, section 4.1: protected elements are not accessible through dot notation"),
        /// E2023: a modifier of a protected element.
        #[error("`{name}` is protected: it cannot be modified from outside")]
        ProtectedModified { name: String, span: Span, declared: Span } = FlatCode::ProtectedModified,
        |d| d
            .at(span, "modifier of a protected element")
            .with_label(declared, "declared protected here")
            .with_note("Modelica specification, section 4.1"),
        /// E2024: `each` where nothing is an array.
        #[error("`each` on `{name}`, which is not an element of an array")]
        EachOnScalar { name: String, span: Span } = FlatCode::EachOnScalar,
        |d| d
            .at(span, "no array here")
            .with_note("Modelica specification, section 7.2.5: `each` applies a modifier to every element of an array"),
        /// E2025: an assignment to a constant, or to a parameter outside initial
        /// algorithms (`what`: "the constant", "the parameter").
        #[error("assignment to {what} `{name}`")]
        AssignsConstant { what: &'static str, name: String, span: Span, declared: Span } = FlatCode::AssignsConstant,
        |d| d
            .at(span, "assigned here")
            .with_label(declared, "declared here")
            .with_note("Modelica specification, section 3.8"),
        /// E2026: an assignment to a function's input.
        #[error("assignment to the function's input `{name}`")]
        AssignsInput { name: String, span: Span, declared: Span } = FlatCode::AssignsInput,
        |d| d
            .at(span, "assigned here")
            .with_label(declared, "declared here")
            .with_note("Modelica specification, section 12.2"),
        /// E2027: a component of a package or operator that is not a constant.
        #[error("a {kind} may declare only classes and constants, not `{name}`")]
        PackageComponent { kind: &'static str, name: String, span: Span } = FlatCode::ClassRestriction,
        |d| d.at(span, "not a constant").with_note("Modelica specification, section 4.7"),
        /// E2027: a component of a type.
        #[error("a type may not declare components: `{name}`")]
        TypeComponent { name: String, span: Span } = FlatCode::ClassRestriction,
        |d| d.at(span, "a component in a type").with_note("Modelica specification, section 4.7"),
        /// E2027: a protected element of a connector or record (`kind`).
        #[error("a {kind} has only public elements: `{name}` is protected")]
        ProtectedInterfaceElement { kind: &'static str, name: String, span: Span } = FlatCode::ClassRestriction,
        |d| d
            .at(span, format!("protected element of a {kind}"))
            .with_note("Modelica specification, section 4.7"),
        /// E2027: a record or function (`kind`) with a component of a model, block or
        /// connector class.
        #[error("a {kind} may not have a component of the {class_kind} `{class}`: `{name}`")]
        ModelComponentIn {
            kind: &'static str,
            class_kind: &'static str,
            class: String,
            name: String,
            span: Span,
            declared: Span,
        } = FlatCode::ClassRestriction,
        |d| d
            .at(span, format!("a {class_kind} in a {kind}"))
            .with_note("Modelica specification, section 4.7")
            .with_label(declared, "declared here"),
        /// E2027: a block's public connector with a variable that has no causality.
        #[error("the public connector `{name}` of a block has a variable that is neither input nor output")]
        AcausalBlockConnector { name: String, span: Span, variable: Span } = FlatCode::ClassRestriction,
        |d| d
            .at(span, "connector of a block")
            .with_note("Modelica specification, section 4.7")
            .with_label(variable, "neither input nor output")
            .with_help("use a model for physical connectors, or give the connector's variables `input`/`output`"),
        /// E2027: an initial algorithm in a function.
        #[error("a function may not have an initial algorithm")]
        InitialAlgorithmInFunction { span: Span } = FlatCode::ClassRestriction,
        |d| d
            .at(span, "initial algorithm in a function")
            .with_note("Modelica specification, section 12.2"),
        /// E2027: a function with two algorithm sections.
        #[error("a function has at most one algorithm section")]
        SecondAlgorithm { span: Span, first: Span } = FlatCode::ClassRestriction,
        |d| d
            .at(span, "second algorithm section")
            .with_note("Modelica specification, section 12.2")
            .with_label(first, "first algorithm section"),
        /// E2027: a function with an algorithm section and an external clause.
        #[error("a function has an algorithm section or an external clause, not both")]
        AlgorithmAndExternal { span: Span, algorithm: Span } = FlatCode::ClassRestriction,
        |d| d
            .at(span, "external clause")
            .with_note("Modelica specification, section 12.2")
            .with_label(algorithm, "algorithm section"),
        /// E2028: `flow` or `stream` (`word`) in a model, block or class (`kind`).
        #[error("`{word}` outside a connector: `{name}`")]
        FlowOutsideConnector { word: &'static str, kind: &'static str, name: String, span: Span } = FlatCode::MisplacedPrefix,
        |d| d
            .at(span, format!("`{word}` in a {kind}"))
            .with_note("Modelica specification, section 4.4.2.2"),
        /// E2028: a prefix that elements of a record or function (`kind`) may not have.
        #[error("a {kind}'s element `{name}` may not be declared `{prefix}`")]
        ElementPrefix { kind: &'static str, prefix: &'static str, name: String, section: &'static str, span: Span } = FlatCode::MisplacedPrefix,
        |d| d
            .at(span, format!("`{prefix}` in a {kind}"))
            .with_note(format!("Modelica specification, section {section}")),
        /// E2028: a protected input or output (`word`) of a function.
        #[error("a function's protected element `{name}` may not be an {word}")]
        ProtectedFunctionInterface { word: &'static str, name: String, span: Span } = FlatCode::MisplacedPrefix,
        |d| d
            .at(span, format!("protected {word}"))
            .with_note("Modelica specification, section 12.2"),
        /// E2028: a public element of a function that is neither input nor output.
        #[error("a function's public element `{name}` must be an input or an output")]
        PublicFunctionLocal { name: String, span: Span } = FlatCode::MisplacedPrefix,
        |d| d
            .at(span, "neither input nor output")
            .with_note("Modelica specification, section 12.2")
            .with_help("declare local variables of a function under `protected`"),
        /// E2028: a component of a connector type declared `parameter` or `constant`.
        #[error("connector component `{name}` may not be declared `{word}`")]
        ConstantConnector { word: &'static str, name: String, span: Span, connector: Span } = FlatCode::MisplacedPrefix,
        |d| d
            .at(span, format!("a {word} of a connector type"))
            .with_label(connector, "the connector class")
            .with_help("declare the connector's own elements `parameter` instead")
            .with_note("Modelica specification, section 9.3"),
        /// E2029: a `pure` function calls an `impure` one.
        #[error("the function `{function}`, declared `pure`, calls the impure function `{callee}`")]
        PureCallsImpure { function: String, callee: String, span: Span, declared: Span } = FlatCode::PureCallsImpure,
        |d| d
            .at(span, "impure call")
            .with_label(declared, "declared `impure` here")
            .with_help("declare the calling function `impure`")
            .with_note("Modelica specification, section 12.3"),
        /// E2030: an argument of `connect` that is not a connector.
        #[error("`{name}` is not a connector: it is {what}")]
        ConnectNonConnector { name: String, what: String, span: Span, declared: Span } = FlatCode::ConnectNonConnector,
        |d| d
            .at(span, "not a connector")
            .with_label(declared, "declared here")
            .with_note("Modelica specification, section 9.1: both arguments of `connect` are connectors"),
        /// E2031: a connector connected to itself.
        #[error("`{name}` is connected to itself")]
        ConnectToItself { name: String, span: Span } = FlatCode::ConnectToItself,
        |d| d
            .at(span, "both sides are the same connector")
            .with_note("Modelica specification, section 9.1: a connect equation relates two different connectors"),
        /// E2032: `pre` of a continuous-time Real outside `when`.
        #[error("`pre({name})` of a continuous-time variable outside a when clause")]
        PreOfContinuous { name: String, span: Span, declared: Span } = FlatCode::PreOfContinuous,
        |d| d
            .at(span, "varies continuously")
            .with_label(declared, "declared here")
            .with_help("`pre` of a Real is the value before an event: assign it in a `when` clause or declare it `discrete`")
            .with_note("Modelica specification, section 3.7.5"),
        /// W2001: a parameter with neither a binding nor a start value.
        #[error("parameter `{name}` has neither a value nor a start value: it takes its type's default")]
        UnboundParameter { name: String, span: Span } = FlatCode::UnboundParameter,
        |d| d
            .at(span, "declared without a value")
            .with_help(format!(
                "give it a value (`{name} = ...` in the declaration or a modifier), or `fixed = false` with an initial equation"
            ))
            .with_note("Modelica specification, section 8.6"),
        /// E2033: a `discrete` Real given a continuous-time value.
        #[error("`{name}` is declared `discrete` but no when clause assigns it: it is given a continuous-time value")]
        DiscreteRealContinuous { name: String, why: String, span: Span, declared: Span } = FlatCode::DiscreteGivenContinuous,
        |d| d
            .at(span, why)
            .with_label(declared, "declared `discrete` here")
            .with_help("assign it in a `when` clause, or drop the `discrete` prefix")
            .with_note("Modelica specification, section 4.5.3: a Real declared `discrete` must be assigned in a when clause"),
        /// E2033: a discrete-valued variable (of type `ty`) given a continuous-time value
        /// outside `when`.
        #[error("`{name}` ({ty}) is discrete-time but is given a continuous-time value outside a when clause")]
        DiscreteValuedContinuous { name: String, ty: String, why: String, span: Span, declared: Span } = FlatCode::DiscreteGivenContinuous,
        |d| d
            .at(span, why)
            .with_label(declared, "declared here")
            .with_help("assign it in a `when` clause, or give it a discrete-time expression (a relation such as `x > 0`, `integer(x)`, `pre(...)`)")
            .with_note("Modelica specification, section 3.8.4: a discrete-valued equation holds discrete-time expressions only"),
        /// E2034: a stream connector without exactly one scalar flow variable (`problem`
        /// says what it has).
        #[error("stream connector `{name}` has {problem}: it needs exactly one scalar flow variable")]
        StreamFlowCount { name: String, problem: String, span: Span, stream: Span, flows: Vec<Span> } = FlatCode::StreamFlowCount,
        |d| {
            let mut d = d.at(span, "this connector").with_label(stream, "a stream variable");
            for f in flows {
                d = d.with_label(f, "a flow variable");
            }
            d.with_help("the stream variables are carried by the one flow (e.g. `flow Real m_flow;`)")
                .with_note("Modelica specification, section 15.1")
        },
        /// E2035: an `inner` component whose type is not a subtype of the `outer` one's.
        #[error("the `inner {name}` is not a subtype of the `outer` declaration: {why}")]
        InnerOuterMismatch { name: String, why: String, span: Span, inner: Span } = FlatCode::InnerOuterMismatch,
        |d| d
            .at(span, "declared `outer` here")
            .with_label(inner, "the matching `inner`")
            .with_note("Modelica specification, section 5.4: the inner component shall be a subtype of the corresponding outer component"),
        /// W2002: an `outer` component without `inner`, created by default.
        #[error("no `inner {name}` for this `outer`: `inner {type_name} {name}` is added at the top of the model with default values")]
        DefaultInner { name: String, type_name: String, span: Span } = FlatCode::DefaultInner,
        |d| d
            .at(span, "declared `outer` here")
            .with_help(format!("declare `inner {type_name} {name};` in the model to set its values"))
            .with_note("Modelica specification, section 5.4"),
        /// E2036: an argument of a `Connections` operator that is not overdetermined.
        #[error("`Connections.{operator}` of `{name}`, a variable {what}")]
        NotOverdetermined { operator: String, name: String, what: String, span: Span, declared: Span } = FlatCode::Overconstrained,
        |d| d
            .at(span, "not an overdetermined variable")
            .with_label(declared, "declared here")
            .with_help("the operators of `Connections` take variables of an overdetermined type or record: one with a function `equalityConstraint`")
            .with_note("Modelica specification, section 9.4"),
        /// E2037: a connector whose flow and potential variable counts differ.
        #[error("connector `{name}` has {flows} scalar flow variable(s) and {potentials} potential one(s)")]
        UnbalancedConnector { name: String, flows: i64, potentials: i64, span: Span } = FlatCode::UnbalancedConnector,
        |d| d
            .at(span, "unbalanced connector")
            .with_help("each potential variable (neither flow, stream, input, output, parameter nor constant) needs a flow variable")
            .with_note("Modelica specification, section 9.3.1"),
    }
}

/// A library file that exists but cannot be read. The library is read lazily, while
/// names are looked up, through the [`SourceProvider`](crate::SourceProvider); the
/// problem is the file's, not the model's, so its code is the command line's code for a
/// file that cannot be read (`E0001`), not one of the stage's.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LibraryError {
    /// E0001: the file cannot be read (`reason`: the provider's error).
    #[error("cannot read `{path}`: {reason}")]
    Unreadable { path: String, reason: String },
}

impl LibraryError {
    /// The code of this error (`E0001`).
    pub fn code(&self) -> &'static str {
        match self {
            LibraryError::Unreadable { .. } => "E0001",
        }
    }
}

impl From<LibraryError> for Diagnostic {
    fn from(e: LibraryError) -> Diagnostic {
        Diagnostic::error(e.code(), e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_has_a_variant_and_each_variant_its_documented_code() {
        FlatError::check_variants(FlatCode::ALL);
    }
}
