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

/// Errors found while looking up names and instantiating classes.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlatError {
    /// E2001: a name that denotes nothing in its scope.
    #[error("unknown {what} `{name}`")]
    UnknownName {
        name: String,
        /// What kind of thing was expected: "type", "base class", "function", ...
        what: &'static str,
        span: Span,
        suggestion: Option<String>,
        /// The name exists globally but the scope is encapsulated.
        encapsulated: bool,
    },
}

impl FlatError {
    pub fn code(&self) -> &'static str {
        match self {
            FlatError::UnknownName { .. } => FlatCode::UnknownName.as_str(),
        }
    }
}

impl From<FlatError> for Diagnostic {
    fn from(e: FlatError) -> Diagnostic {
        let message = e.to_string();
        let code = e.code();
        match e {
            FlatError::UnknownName {
                span,
                suggestion,
                encapsulated,
                name,
                ..
            } => {
                let d = Diagnostic::error(code, message).at(span, "not found in this scope");
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
            }
        }
    }
}
