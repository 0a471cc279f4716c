//! The abstract syntax tree: one node type per construct of the subset, a span on every node.
//!
//! The tree is what the source says, nothing resolved: names are text, no lookup has
//! been done and no expression has been simplified. Later stages never mutate it.

use smol_str::SmolStr;
use unimo_source::Span;

/// An identifier with its span. Quoted identifiers keep their quotes (`'a b'`).
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub text: SmolStr,
    pub span: Span,
}

/// A dotted name such as `Modelica.SIunits.Length`; `global` for a leading dot.
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    pub global: bool,
    pub parts: Vec<Ident>,
    pub span: Span,
}

impl Name {
    /// A name with no parts at `span` (a placeholder the parser fills in).
    pub(crate) fn empty(span: Span) -> Name {
        Name {
            global: false,
            parts: Vec::new(),
            span,
        }
    }

    /// The name as written, parts joined by dots.
    pub fn to_dotted(&self) -> String {
        dotted(self.global, self.parts.iter().map(|p| p.text.as_str()))
    }
}

/// Parts joined by dots, with a leading dot for a global name.
fn dotted<'a>(global: bool, parts: impl Iterator<Item = &'a str>) -> String {
    let mut s = String::new();
    if global {
        s.push('.');
    }
    for (i, p) in parts.enumerate() {
        if i > 0 {
            s.push('.');
        }
        s.push_str(p);
    }
    s
}

/// One parsed file.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredDefinition {
    /// `within A.B;` — `Some(None)` for a bare `within;`.
    pub within: Option<Option<Name>>,
    pub classes: Vec<ClassDef>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClassKind {
    Class,
    Model,
    Block,
    Connector,
    Record,
    Package,
    Function,
    Type,
    /// `operator`: a package-like class holding the functions of one overloaded operator.
    Operator,
}

impl ClassKind {
    /// Whether a class of this kind may have equation sections (not functions,
    /// records, connectors, types, packages and operators).
    pub fn may_have_equations(self) -> bool {
        self != ClassKind::Function && self.may_have_algorithms()
    }

    /// Whether a class of this kind may have algorithm sections (not records,
    /// connectors, types, packages and operators).
    pub fn may_have_algorithms(self) -> bool {
        !matches!(
            self,
            ClassKind::Record
                | ClassKind::Connector
                | ClassKind::Type
                | ClassKind::Package
                | ClassKind::Operator
        )
    }

    pub fn keyword(self) -> &'static str {
        match self {
            ClassKind::Class => "class",
            ClassKind::Model => "model",
            ClassKind::Block => "block",
            ClassKind::Connector => "connector",
            ClassKind::Record => "record",
            ClassKind::Package => "package",
            ClassKind::Function => "function",
            ClassKind::Type => "type",
            ClassKind::Operator => "operator",
        }
    }
}

/// `pure` or `impure` before `function`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purity {
    Pure,
    Impure,
}

/// The prefixes that refine a class kind: `expandable connector`, `operator record`,
/// `operator function`, `pure function`, `impure operator function`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ClassPrefixes {
    pub expandable: bool,
    pub operator: bool,
    pub purity: Option<Purity>,
}

impl ClassPrefixes {
    /// The prefix words as written before the class keyword (empty when none).
    pub fn keywords(self) -> String {
        let mut s = String::new();
        if self.expandable {
            s.push_str("expandable ");
        }
        match self.purity {
            Some(Purity::Pure) => s.push_str("pure "),
            Some(Purity::Impure) => s.push_str("impure "),
            None => {}
        }
        if self.operator {
            s.push_str("operator ");
        }
        s
    }
}

/// A class definition, long, short or enumeration.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassDef {
    pub encapsulated: bool,
    pub partial: bool,
    pub prefixes: ClassPrefixes,
    pub kind: ClassKind,
    pub name: Ident,
    pub body: ClassBody,
    pub span: Span,
}

/// A class's prefixes as both parsers read them: `partial`, the other prefixes and the
/// kind.
pub type ClassHead = (bool, ClassPrefixes, ClassKind);

impl ClassDef {
    /// A class definition from what the parsers read: `encapsulated`, its head (prefixes
    /// and kind), its specifier (name and body) and its span.
    pub fn new(
        encapsulated: bool,
        (partial, prefixes, kind): ClassHead,
        (name, body): (Ident, ClassBody),
        span: Span,
    ) -> ClassDef {
        ClassDef {
            encapsulated,
            partial,
            prefixes,
            kind,
            name,
            body,
            span,
        }
    }

    /// The component clauses a long class declares, each with its element, in
    /// declaration order (none for a short, derivative or enumeration class).
    pub fn component_clauses(&self) -> impl Iterator<Item = (&Element, &ComponentClause)> {
        let elements: &[Element] = match &self.body {
            ClassBody::Long { composition, .. } => &composition.elements,
            _ => &[],
        };
        elements.iter().filter_map(|e| match &e.kind {
            ElementKind::Component(cc) => Some((e, cc)),
            _ => None,
        })
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ClassBody {
    /// `model A "doc" ... end A;`, or with `extends` set the class extension
    /// `model extends A(m) "doc" ... end A;` of an inherited replaceable class.
    Long {
        description: Option<String>,
        composition: Composition,
        end_name: Ident,
        extends: Option<Box<ClassExtends>>,
    },
    /// `type DerF = der(F, x, y) "doc";`: the partial derivative of a function.
    Der {
        base: Name,
        with_respect_to: Vec<Ident>,
        comment: Comment,
    },
    /// `type Length = Real(unit = "m") "doc";` and `connector RealInput = input Real;`
    Short {
        causality: Option<Causality>,
        base: Name,
        dims: Vec<Subscript>,
        modification: Option<ClassModification>,
        comment: Comment,
    },
    /// `type State = enumeration(Flight, Sliding, Rolling);` (`literals` empty and
    /// `open` set for `enumeration(:)`).
    Enumeration {
        literals: Vec<EnumLiteral>,
        open: bool,
        comment: Comment,
    },
}

/// The `extends` of a class extension `model extends A(m)`: the modification of the
/// inherited class it extends.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassExtends {
    pub modification: Option<ClassModification>,
    pub span: Span,
}

/// A function's `external "C" y = f(x) annotation(...);` clause.
#[derive(Clone, Debug, PartialEq)]
pub struct External {
    /// The language string (`"C"`, `"FORTRAN 77"`, `"builtin"`), if written.
    pub language: Option<String>,
    /// The explicit call; `None` for the default call (same name, inputs in order).
    pub call: Option<ExternalCall>,
    pub annotation: Option<ClassModification>,
    pub span: Span,
}

/// `y = f(a, size(b, 1))` in an external clause.
#[derive(Clone, Debug, PartialEq)]
pub struct ExternalCall {
    pub output: Option<ComponentRef>,
    pub function: Ident,
    pub args: Vec<Expr>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct EnumLiteral {
    pub name: Ident,
    pub comment: Comment,
}

/// Everything between a long class's header and its `end`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Composition {
    pub elements: Vec<Element>,
    pub sections: Vec<Section>,
    /// A function's external clause (after the last section).
    pub external: Option<External>,
    pub annotation: Option<ClassModification>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Visibility {
    Public,
    Protected,
}

/// An element of a class: import, extends, nested class or component clause.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    pub visibility: Visibility,
    pub redeclare: bool,
    pub is_final: bool,
    pub inner: bool,
    pub outer: bool,
    pub replaceable: bool,
    pub kind: ElementKind,
    pub constrainedby: Option<ConstrainingClause>,
    pub span: Span,
}

impl Element {
    /// An element with no prefixes whose kind the parser fills in next (an empty
    /// import stands in until then).
    pub(crate) fn unfilled(visibility: Visibility, span: Span) -> Element {
        Element {
            visibility,
            redeclare: false,
            is_final: false,
            inner: false,
            outer: false,
            replaceable: false,
            kind: ElementKind::Import(Import {
                kind: ImportKind::Qualified(Name::empty(span)),
                comment: Comment::default(),
                span,
            }),
            constrainedby: None,
            span,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ElementKind {
    Import(Import),
    Extends(Extends),
    Class(Box<ClassDef>),
    Component(ComponentClause),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Import {
    pub kind: ImportKind,
    pub comment: Comment,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ImportKind {
    /// `import A.B;`
    Qualified(Name),
    /// `import X = A.B;`
    Renamed { alias: Ident, name: Name },
    /// `import A.B.*;`
    Unqualified(Name),
    /// `import A.B.{C, D};`
    Multiple { name: Name, items: Vec<Ident> },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Extends {
    pub base: Name,
    pub modification: Option<ClassModification>,
    pub annotation: Option<ClassModification>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ConstrainingClause {
    pub base: Name,
    pub modification: Option<ClassModification>,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Connection {
    Flow,
    Stream,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    Discrete,
    Parameter,
    Constant,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Input,
    Output,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct TypePrefix {
    pub connection: Option<Connection>,
    pub variability: Option<Variability>,
    pub causality: Option<Causality>,
}

/// `parameter Real[3] a, b(start = 1) "doc";`
#[derive(Clone, Debug, PartialEq)]
pub struct ComponentClause {
    pub prefix: TypePrefix,
    pub type_name: Name,
    pub type_dims: Vec<Subscript>,
    pub components: Vec<ComponentDecl>,
}

impl ComponentClause {
    /// A clause without prefixes, type or components (a placeholder the parser fills in).
    pub(crate) fn empty(span: Span) -> ComponentClause {
        ComponentClause {
            prefix: TypePrefix::default(),
            type_name: Name::empty(span),
            type_dims: Vec::new(),
            components: Vec::new(),
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct ComponentDecl {
    pub name: Ident,
    pub dims: Vec<Subscript>,
    pub modification: Option<Modification>,
    pub condition: Option<Expr>,
    pub comment: Comment,
    pub span: Span,
}

/// `(a = 1, b(start = 2)) = expr` or `= expr` or `:= expr`.
#[derive(Clone, Debug, PartialEq)]
pub struct Modification {
    pub class_mod: Option<ClassModification>,
    pub binding: Option<Expr>,
    /// The binding was written `:=` (allowed in modifications by the spec).
    pub assign: bool,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ClassModification {
    pub args: Vec<Argument>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Argument {
    /// `each final a.b(start = 1) = 2 "doc"`
    Modify {
        each: bool,
        is_final: bool,
        name: Name,
        modification: Option<Modification>,
        description: Option<String>,
        span: Span,
    },
    /// `redeclare each final Type x` or `replaceable ...` or a redeclared short class.
    Redeclare {
        redeclare: bool,
        each: bool,
        is_final: bool,
        replaceable: bool,
        element: RedeclaredElement,
        constrainedby: Option<ConstrainingClause>,
        span: Span,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub enum RedeclaredElement {
    Component(ComponentClause),
    Class(Box<ClassDef>),
}

/// A description string and an optional annotation.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Comment {
    pub description: Option<String>,
    pub annotation: Option<ClassModification>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Section {
    Equation(EquationSection),
    Algorithm(AlgorithmSection),
}

#[derive(Clone, Debug, PartialEq)]
pub struct EquationSection {
    pub initial: bool,
    pub equations: Vec<Equation>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct AlgorithmSection {
    pub initial: bool,
    pub statements: Vec<Statement>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    pub kind: EquationKind,
    pub comment: Comment,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum EquationKind {
    /// `lhs = rhs`
    Simple {
        lhs: Expr,
        rhs: Expr,
    },
    /// A bare call such as `reinit(x, 0)` or `assert(c, "msg")`.
    Call(Expr),
    Connect {
        a: ComponentRef,
        b: ComponentRef,
    },
    If {
        branches: Vec<(Expr, Vec<Equation>)>,
        otherwise: Vec<Equation>,
    },
    For {
        indices: Vec<ForIndex>,
        body: Vec<Equation>,
    },
    When {
        branches: Vec<(Expr, Vec<Equation>)>,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct ForIndex {
    pub name: Ident,
    pub range: Option<Expr>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    pub kind: StatementKind,
    pub comment: Comment,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum StatementKind {
    /// `target := value`
    Assign {
        target: ComponentRef,
        value: Expr,
    },
    /// `(a, , b) := f(x)`
    MultiAssign {
        targets: Vec<Option<Expr>>,
        value: Expr,
    },
    /// `f(x);`
    Call(Expr),
    If {
        branches: Vec<(Expr, Vec<Statement>)>,
        otherwise: Vec<Statement>,
    },
    For {
        indices: Vec<ForIndex>,
        body: Vec<Statement>,
    },
    While {
        condition: Expr,
        body: Vec<Statement>,
    },
    When {
        branches: Vec<(Expr, Vec<Statement>)>,
    },
    Return,
    Break,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    Neg,
    Plus,
    Not,
}

/// Relational operators (`<`, `<=`, `>`, `>=`, `==`, `<>`); in the DAE a relation is
/// 1.0 when true and 0.0 when false.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum RelOp {
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl RelOp {
    pub fn symbol(self) -> &'static str {
        match self {
            RelOp::Lt => "<",
            RelOp::Le => "<=",
            RelOp::Gt => ">",
            RelOp::Ge => ">=",
            RelOp::Eq => "==",
            RelOp::Ne => "<>",
        }
    }

    /// The relation between `a` and `b`.
    pub fn apply<T: PartialOrd>(self, a: T, b: T) -> bool {
        match self {
            RelOp::Lt => a < b,
            RelOp::Le => a <= b,
            RelOp::Gt => a > b,
            RelOp::Ge => a >= b,
            RelOp::Eq => a == b,
            RelOp::Ne => a != b,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    Or,
    And,
    Rel(RelOp),
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    ElemAdd,
    ElemSub,
    ElemMul,
    ElemDiv,
    ElemPow,
}

impl BinaryOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Or => "or",
            BinaryOp::And => "and",
            BinaryOp::Rel(op) => op.symbol(),
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Pow => "^",
            BinaryOp::ElemAdd => ".+",
            BinaryOp::ElemSub => ".-",
            BinaryOp::ElemMul => ".*",
            BinaryOp::ElemDiv => "./",
            BinaryOp::ElemPow => ".^",
        }
    }
}

impl UnaryOp {
    pub fn symbol(self) -> &'static str {
        match self {
            UnaryOp::Neg => "-",
            UnaryOp::Plus => "+",
            UnaryOp::Not => "not",
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Integer(i64),
    Real(f64),
    Bool(bool),
    /// The string's value, escapes resolved.
    String(String),
    Ref(ComponentRef),
    /// `f(args)`, including `der(x)` and `initial()`.
    Call {
        func: Name,
        args: Box<CallArgs>,
    },
    Unary {
        op: UnaryOp,
        operand: Box<Expr>,
    },
    Binary {
        op: BinaryOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    If {
        branches: Vec<(Expr, Expr)>,
        otherwise: Box<Expr>,
    },
    Range {
        start: Box<Expr>,
        step: Option<Box<Expr>>,
        stop: Box<Expr>,
    },
    /// `{a, b, c}`
    Array(Vec<Expr>),
    /// `{e for i in r}`
    Comprehension {
        body: Box<Expr>,
        indices: Vec<ForIndex>,
    },
    /// `[a, b; c, d]`
    Matrix(Vec<Vec<Expr>>),
    /// `(a, , b)` — only as the target list of a multiple assignment or `(x)`.
    Tuple(Vec<Option<Expr>>),
    /// `end` inside a subscript.
    End,
    /// `function f(a = 1)` passed as a functional argument.
    PartialApplication {
        func: Box<Name>,
        args: Vec<NamedArg>,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct ComponentRef {
    pub global: bool,
    pub parts: Vec<RefPart>,
    pub span: Span,
}

impl ComponentRef {
    /// The reference as written, without subscripts (`a.b.c`).
    pub fn to_dotted(&self) -> String {
        dotted(self.global, self.parts.iter().map(|p| p.name.text.as_str()))
    }

    /// A reference without subscripts seen as a name.
    pub fn as_name(&self) -> Option<Name> {
        if self.parts.iter().any(|p| !p.subscripts.is_empty()) {
            return None;
        }
        Some(Name {
            global: self.global,
            parts: self.parts.iter().map(|p| p.name.clone()).collect(),
            span: self.span,
        })
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct RefPart {
    pub name: Ident,
    pub subscripts: Vec<Subscript>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Subscript {
    /// `:`
    Colon(Span),
    Expr(Expr),
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct CallArgs {
    pub positional: Vec<Expr>,
    pub named: Vec<NamedArg>,
    /// `sum(x[i] for i in 1:n)`: the single positional argument is iterated.
    pub iterators: Vec<ForIndex>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct NamedArg {
    pub name: Ident,
    pub value: Expr,
}
