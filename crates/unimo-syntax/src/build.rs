//! Turns pest's parse tree into the [`crate::ast`] types, attaching a span to every node.
//!
//! The grammar guarantees the shape of each pair, so children are taken in order; a
//! shape this code does not expect is a bug in the grammar, reported as an internal
//! diagnostic rather than a panic.

use crate::ast::*;
use crate::grammar::Rule;
use crate::lexer::Token;
use crate::shared;
use pest::iterators::{Pair, Pairs};
use pest::pratt_parser::{Assoc, Op, PrattParser};
use smol_str::SmolStr;
use std::sync::LazyLock;
use unimo_source::{Diagnostic, FileId, Span};

static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::or_op, Assoc::Left))
        .op(Op::infix(Rule::and_op, Assoc::Left))
        .op(Op::prefix(Rule::not_op))
        .op(Op::infix(Rule::lt_op, Assoc::Left)
            | Op::infix(Rule::le_op, Assoc::Left)
            | Op::infix(Rule::gt_op, Assoc::Left)
            | Op::infix(Rule::ge_op, Assoc::Left)
            | Op::infix(Rule::eq_eq_op, Assoc::Left)
            | Op::infix(Rule::ne_op, Assoc::Left))
        .op(Op::infix(Rule::add_op, Assoc::Left)
            | Op::infix(Rule::sub_op, Assoc::Left)
            | Op::infix(Rule::ew_add, Assoc::Left)
            | Op::infix(Rule::ew_sub, Assoc::Left))
        // pest binds a prefix operator's operand at one level below the operator's own
        // level, so unary minus gets a level of its own above `+`: `-a + b` is
        // `(-a) + b`, while `-a * b` is `-(a * b)` and `-a ^ 2` is `-(a ^ 2)`.
        .op(Op::prefix(Rule::neg_op) | Op::prefix(Rule::pos_op))
        .op(Op::infix(Rule::mul_op, Assoc::Left)
            | Op::infix(Rule::div_op, Assoc::Left)
            | Op::infix(Rule::ew_mul, Assoc::Left)
            | Op::infix(Rule::ew_div, Assoc::Left))
        .op(Op::infix(Rule::pow_op, Assoc::Right) | Op::infix(Rule::ew_pow, Assoc::Right))
});

/// Builds AST nodes for one file, collecting diagnostics found while building.
pub(crate) struct Builder<'d> {
    pub file: FileId,
    pub diags: &'d mut Vec<Diagnostic>,
    /// The scanner's tokens of the text being built, to make spans token-tight.
    pub tokens: &'d [Token],
}

fn is_token(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::kw_within
            | Rule::kw_if
            | Rule::kw_then
            | Rule::kw_else
            | Rule::kw_elseif
            | Rule::kw_for
            | Rule::kw_loop
            | Rule::kw_in
            | Rule::kw_when
            | Rule::kw_elsewhen
            | Rule::kw_while
            | Rule::kw_connect
            | Rule::kw_equation
            | Rule::kw_algorithm
            | Rule::kw_import
            | Rule::kw_extends
            | Rule::kw_constrainedby
            | Rule::kw_annotation
            | Rule::kw_enumeration
            | Rule::kw_return
            | Rule::kw_break
            | Rule::kw_public
            | Rule::kw_protected
            | Rule::kw_function
            | Rule::kw_end
            | Rule::semi
            | Rule::EOI
    )
}

/// The meaningful children of a pair (keyword and `;` tokens dropped).
fn kids(pair: Pair<'_, Rule>) -> impl Iterator<Item = Pair<'_, Rule>> {
    pair.into_inner().filter(|p| !is_token(p.as_rule()))
}

impl Builder<'_> {
    /// The pair's span without the whitespace and comments pest includes after its last
    /// token when it ends in an empty optional part: spans run from the first token's
    /// start to the last token's end.
    fn span(&self, pair: &Pair<'_, Rule>) -> Span {
        let s = pair.as_span();
        let end = s.end();
        let last = self.tokens.partition_point(|t| t.end() <= end);
        let tight = last
            .checked_sub(1)
            .map_or(s.start(), |i| self.tokens[i].end())
            .clamp(s.start(), end);
        Span::new(self.file, s.start(), tight)
    }

    fn internal(&mut self, pair: &Pair<'_, Rule>) {
        let span = self.span(pair);
        self.diags.push(
            Diagnostic::error(
                "E1999",
                format!(
                    "internal error: unexpected `{:?}` in the parse tree",
                    pair.as_rule()
                ),
            )
            .at(span, "here")
            .with_note("this is a bug in unimo; please report it with this file"),
        );
    }

    pub fn stored_definition(&mut self, pair: Pair<'_, Rule>) -> StoredDefinition {
        let s = pair.as_span();
        let span = Span::new(self.file, s.start(), s.end());
        let mut within = None;
        let mut classes = Vec::new();
        for p in kids(pair) {
            match p.as_rule() {
                Rule::within_clause => {
                    within = Some(kids(p).next().map(|n| self.name(n)));
                }
                Rule::class_definition => classes.push(self.class_definition(p)),
                Rule::final_kw => {}
                _ => self.internal(&p),
            }
        }
        StoredDefinition {
            within,
            classes,
            span,
        }
    }

    fn ident(&self, pair: Pair<'_, Rule>) -> Ident {
        Ident {
            text: SmolStr::new(pair.as_str()),
            span: self.span(&pair),
        }
    }

    pub fn name(&self, pair: Pair<'_, Rule>) -> Name {
        let span = self.span(&pair);
        let mut global = false;
        let mut parts = Vec::new();
        let inner = if pair.as_rule() == Rule::type_specifier {
            pair.into_inner().next().map(|p| p.into_inner())
        } else {
            Some(pair.into_inner())
        };
        for p in inner.into_iter().flatten() {
            match p.as_rule() {
                Rule::global_dot => global = true,
                Rule::ident => parts.push(self.ident(p)),
                _ => {}
            }
        }
        Name {
            global,
            parts,
            span,
        }
    }

    fn class_definition(&mut self, pair: Pair<'_, Rule>) -> ClassDef {
        let span = self.span(&pair);
        let mut encapsulated = false;
        let (mut partial, mut prefixes, mut kind) =
            (false, ClassPrefixes::default(), ClassKind::Class);
        let mut spec = None;
        for p in kids(pair) {
            match p.as_rule() {
                Rule::encapsulated_kw => encapsulated = true,
                Rule::class_prefixes => (partial, prefixes, kind) = class_prefixes(p),
                Rule::class_specifier => spec = p.into_inner().next(),
                _ => self.internal(&p),
            }
        }
        let (name, body) = match spec {
            Some(s) => self.class_specifier(s),
            None => (
                Ident {
                    text: SmolStr::default(),
                    span,
                },
                ClassBody::Long {
                    description: None,
                    composition: Composition::default(),
                    end_name: Ident {
                        text: SmolStr::default(),
                        span,
                    },
                    extends: None,
                },
            ),
        };
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

    fn class_specifier(&mut self, pair: Pair<'_, Rule>) -> (Ident, ClassBody) {
        let rule = pair.as_rule();
        let mut it = kids(pair).peekable();
        let mut extends = None;
        if let Some(head) = it.next_if(|p| p.as_rule() == Rule::class_extends) {
            extends = Some(self.class_extends(head));
        }
        let name = match extends.as_mut() {
            Some((name, _)) => std::mem::replace(
                name,
                Ident {
                    text: SmolStr::default(),
                    span: Span::default(),
                },
            ),
            None => it.next().map(|p| self.ident(p)).unwrap_or_else(|| Ident {
                text: SmolStr::default(),
                span: Span::default(),
            }),
        };
        let body = match rule {
            Rule::long_specifier => {
                let mut description = None;
                let mut composition = Composition::default();
                let mut end_name = name.clone();
                for p in it {
                    match p.as_rule() {
                        Rule::description => description = self.description(p),
                        Rule::composition => composition = self.composition(p),
                        Rule::ident => end_name = self.ident(p),
                        _ => self.internal(&p),
                    }
                }
                ClassBody::Long {
                    description,
                    composition,
                    end_name,
                    extends: extends.map(|(_, e)| Box::new(e)),
                }
            }
            Rule::der_specifier => {
                let mut base = None;
                let mut with_respect_to = Vec::new();
                let mut comment = Comment::default();
                for p in it {
                    match p.as_rule() {
                        Rule::kw_der => {}
                        Rule::type_specifier => base = Some(self.name(p)),
                        Rule::ident => with_respect_to.push(self.ident(p)),
                        Rule::comment => comment = self.comment(p),
                        _ => self.internal(&p),
                    }
                }
                ClassBody::Der {
                    base: base.unwrap_or_else(|| Name {
                        global: false,
                        parts: Vec::new(),
                        span: name.span,
                    }),
                    with_respect_to,
                    comment,
                }
            }
            Rule::short_specifier => {
                let mut causality = None;
                let mut base = None;
                let mut dims = Vec::new();
                let mut modification = None;
                let mut comment = Comment::default();
                for p in it {
                    match p.as_rule() {
                        Rule::base_prefix => {
                            causality = p.into_inner().next().map(|c| causality_of(c.as_str()))
                        }
                        Rule::type_specifier => base = Some(self.name(p)),
                        Rule::array_subscripts => dims = self.subscripts(p),
                        Rule::class_modification => modification = Some(self.class_modification(p)),
                        Rule::comment => comment = self.comment(p),
                        _ => self.internal(&p),
                    }
                }
                ClassBody::Short {
                    causality,
                    base: base.unwrap_or_else(|| Name {
                        global: false,
                        parts: Vec::new(),
                        span: name.span,
                    }),
                    dims,
                    modification,
                    comment,
                }
            }
            _ => {
                let mut literals = Vec::new();
                let mut open = false;
                let mut comment = Comment::default();
                for p in it {
                    match p.as_rule() {
                        Rule::enum_list => {
                            for lit in p.into_inner() {
                                let mut li = lit.into_inner();
                                let name = li.next().map(|n| self.ident(n));
                                let comment =
                                    li.next().map(|c| self.comment(c)).unwrap_or_default();
                                if let Some(name) = name {
                                    literals.push(EnumLiteral { name, comment });
                                }
                            }
                        }
                        Rule::enum_colon => open = true,
                        Rule::comment => comment = self.comment(p),
                        _ => self.internal(&p),
                    }
                }
                ClassBody::Enumeration {
                    literals,
                    open,
                    comment,
                }
            }
        };
        (name, body)
    }

    /// `extends A(m)` at the head of a class extension: the name and the modification.
    fn class_extends(&mut self, pair: Pair<'_, Rule>) -> (Ident, ClassExtends) {
        let span = self.span(&pair);
        let mut name = None;
        let mut modification = None;
        for p in kids(pair) {
            match p.as_rule() {
                Rule::kw_extends => {}
                Rule::ident => name = Some(self.ident(p)),
                Rule::class_modification => modification = Some(self.class_modification(p)),
                _ => self.internal(&p),
            }
        }
        let name = name.unwrap_or(Ident {
            text: SmolStr::default(),
            span,
        });
        (name, ClassExtends { modification, span })
    }

    /// `external "C" y = f(x) annotation(...);`
    fn external_clause(&mut self, pair: Pair<'_, Rule>) -> External {
        let span = self.span(&pair);
        let mut ext = External {
            language: None,
            call: None,
            annotation: None,
            span,
        };
        for p in kids(pair) {
            match p.as_rule() {
                Rule::kw_external | Rule::semi => {}
                Rule::language_spec => {
                    ext.language = p.into_inner().next().map(|s| self.string_value(&s))
                }
                Rule::external_call => {
                    let mut output = None;
                    let mut function = None;
                    let mut args = Vec::new();
                    for q in kids(p) {
                        match q.as_rule() {
                            Rule::component_reference => output = Some(self.component_reference(q)),
                            Rule::ident => function = Some(self.ident(q)),
                            Rule::expression => args.push(self.expression(q)),
                            _ => self.internal(&q),
                        }
                    }
                    ext.call = function.map(|function| ExternalCall {
                        output,
                        function,
                        args,
                    });
                }
                Rule::annotation_clause => ext.annotation = self.annotation(p),
                _ => self.internal(&p),
            }
        }
        ext
    }

    fn composition(&mut self, pair: Pair<'_, Rule>) -> Composition {
        let mut c = Composition::default();
        for p in kids(pair) {
            match p.as_rule() {
                Rule::external_clause => c.external = Some(self.external_clause(p)),
                Rule::element_list => self.element_list(p, Visibility::Public, &mut c.elements),
                Rule::public_section | Rule::protected_section => {
                    let vis = if p.as_rule() == Rule::public_section {
                        Visibility::Public
                    } else {
                        Visibility::Protected
                    };
                    if let Some(list) = kids(p).next() {
                        self.element_list(list, vis, &mut c.elements);
                    }
                }
                Rule::equation_section => {
                    let span = self.span(&p);
                    let mut initial = false;
                    let mut equations = Vec::new();
                    for q in kids(p) {
                        match q.as_rule() {
                            Rule::initial_kw => initial = true,
                            Rule::equation => equations.push(self.equation(q)),
                            _ => self.internal(&q),
                        }
                    }
                    c.sections.push(Section::Equation(EquationSection {
                        initial,
                        equations,
                        span,
                    }));
                }
                Rule::algorithm_section => {
                    let span = self.span(&p);
                    let mut initial = false;
                    let mut statements = Vec::new();
                    for q in kids(p) {
                        match q.as_rule() {
                            Rule::initial_kw => initial = true,
                            Rule::statement => statements.push(self.statement(q)),
                            _ => self.internal(&q),
                        }
                    }
                    c.sections.push(Section::Algorithm(AlgorithmSection {
                        initial,
                        statements,
                        span,
                    }));
                }
                Rule::annotation_clause => c.annotation = self.annotation(p),
                _ => self.internal(&p),
            }
        }
        c
    }

    fn element_list(&mut self, pair: Pair<'_, Rule>, vis: Visibility, out: &mut Vec<Element>) {
        for p in kids(pair) {
            if let Some(e) = self.element(p, vis) {
                out.push(e);
            }
        }
    }

    fn element(&mut self, pair: Pair<'_, Rule>, visibility: Visibility) -> Option<Element> {
        let span = self.span(&pair);
        let inner = pair.into_inner().next()?;
        let mut e = Element {
            visibility,
            redeclare: false,
            is_final: false,
            inner: false,
            outer: false,
            replaceable: false,
            kind: ElementKind::Import(Import {
                kind: ImportKind::Qualified(Name {
                    global: false,
                    parts: Vec::new(),
                    span,
                }),
                comment: Comment::default(),
                span,
            }),
            constrainedby: None,
            span,
        };
        match inner.as_rule() {
            Rule::import_clause => e.kind = ElementKind::Import(self.import(inner)),
            Rule::extends_clause => e.kind = ElementKind::Extends(self.extends(inner)),
            Rule::element_body => {
                for p in kids(inner) {
                    match p.as_rule() {
                        Rule::redeclare_kw => e.redeclare = true,
                        Rule::final_kw => e.is_final = true,
                        Rule::inner_kw => e.inner = true,
                        Rule::outer_kw => e.outer = true,
                        Rule::replaceable_element => {
                            e.replaceable = true;
                            for q in kids(p) {
                                match q.as_rule() {
                                    Rule::replaceable_kw | Rule::comment => {}
                                    Rule::constraining_clause => {
                                        e.constrainedby = Some(self.constraining(q))
                                    }
                                    _ => e.kind = self.element_kind(q),
                                }
                            }
                        }
                        _ => e.kind = self.element_kind(p),
                    }
                }
            }
            _ => {
                self.internal(&inner);
                return None;
            }
        }
        Some(e)
    }

    fn element_kind(&mut self, pair: Pair<'_, Rule>) -> ElementKind {
        match pair.as_rule() {
            Rule::class_definition => ElementKind::Class(Box::new(self.class_definition(pair))),
            _ => ElementKind::Component(self.component_clause(pair)),
        }
    }

    fn import(&mut self, pair: Pair<'_, Rule>) -> Import {
        let span = self.span(&pair);
        let mut kind = None;
        let mut comment = Comment::default();
        for p in kids(pair) {
            match p.as_rule() {
                Rule::import_renamed => {
                    let mut it = p.into_inner();
                    let alias = it.next().map(|a| self.ident(a));
                    let name = it.next().map(|n| self.name(n));
                    if let (Some(alias), Some(name)) = (alias, name) {
                        kind = Some(ImportKind::Renamed { alias, name });
                    }
                }
                Rule::import_body => {
                    let mut it = p.into_inner();
                    let name = match it.next() {
                        Some(n) => self.name(n),
                        None => continue,
                    };
                    kind = Some(match it.next() {
                        None => ImportKind::Qualified(name),
                        Some(q) if q.as_rule() == Rule::import_all => ImportKind::Unqualified(name),
                        Some(q) => ImportKind::Multiple {
                            name,
                            items: q.into_inner().map(|i| self.ident(i)).collect(),
                        },
                    });
                }
                Rule::comment => comment = self.comment(p),
                _ => self.internal(&p),
            }
        }
        Import {
            kind: kind.unwrap_or(ImportKind::Qualified(Name {
                global: false,
                parts: Vec::new(),
                span,
            })),
            comment,
            span,
        }
    }

    fn extends(&mut self, pair: Pair<'_, Rule>) -> Extends {
        let span = self.span(&pair);
        let mut base = Name {
            global: false,
            parts: Vec::new(),
            span,
        };
        let mut modification = None;
        let mut annotation = None;
        for p in kids(pair) {
            match p.as_rule() {
                Rule::type_specifier => base = self.name(p),
                Rule::class_modification => modification = Some(self.class_modification(p)),
                Rule::annotation_clause => annotation = self.annotation(p),
                _ => self.internal(&p),
            }
        }
        Extends {
            base,
            modification,
            annotation,
            span,
        }
    }

    fn constraining(&mut self, pair: Pair<'_, Rule>) -> ConstrainingClause {
        let span = self.span(&pair);
        let mut it = kids(pair);
        let base = it.next().map(|n| self.name(n)).unwrap_or(Name {
            global: false,
            parts: Vec::new(),
            span,
        });
        let modification = it.next().map(|m| self.class_modification(m));
        ConstrainingClause {
            base,
            modification,
            span,
        }
    }

    fn type_prefix(&self, pair: Pair<'_, Rule>) -> TypePrefix {
        let mut t = TypePrefix::default();
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::flow_prefix => {
                    t.connection = Some(if p.as_str() == "flow" {
                        Connection::Flow
                    } else {
                        Connection::Stream
                    })
                }
                Rule::variability => {
                    t.variability = Some(match p.as_str() {
                        "discrete" => Variability::Discrete,
                        "parameter" => Variability::Parameter,
                        _ => Variability::Constant,
                    })
                }
                Rule::causality => t.causality = Some(causality_of(p.as_str())),
                _ => {}
            }
        }
        t
    }

    fn component_clause(&mut self, pair: Pair<'_, Rule>) -> ComponentClause {
        let span = self.span(&pair);
        let mut clause = ComponentClause {
            prefix: TypePrefix::default(),
            type_name: Name {
                global: false,
                parts: Vec::new(),
                span,
            },
            type_dims: Vec::new(),
            components: Vec::new(),
        };
        for p in kids(pair) {
            match p.as_rule() {
                Rule::type_prefix => clause.prefix = self.type_prefix(p),
                Rule::type_specifier => clause.type_name = self.name(p),
                Rule::array_subscripts => clause.type_dims = self.subscripts(p),
                Rule::component_list => {
                    for d in p.into_inner() {
                        clause.components.push(self.component_declaration(d));
                    }
                }
                Rule::component_declaration1 => {
                    clause.components.push(self.component_declaration(p))
                }
                _ => self.internal(&p),
            }
        }
        clause
    }

    fn component_declaration(&mut self, pair: Pair<'_, Rule>) -> ComponentDecl {
        let span = self.span(&pair);
        let mut decl = ComponentDecl {
            name: Ident {
                text: SmolStr::default(),
                span,
            },
            dims: Vec::new(),
            modification: None,
            condition: None,
            comment: Comment::default(),
            span,
        };
        for p in kids(pair) {
            match p.as_rule() {
                Rule::declaration => {
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::ident => decl.name = self.ident(q),
                            Rule::array_subscripts => decl.dims = self.subscripts(q),
                            Rule::modification => decl.modification = Some(self.modification(q)),
                            _ => self.internal(&q),
                        }
                    }
                }
                Rule::condition_attribute => {
                    decl.condition = kids(p).next().map(|e| self.expression(e))
                }
                Rule::comment => decl.comment = self.comment(p),
                _ => self.internal(&p),
            }
        }
        decl
    }

    fn modification(&mut self, pair: Pair<'_, Rule>) -> Modification {
        let span = self.span(&pair);
        let mut m = Modification {
            class_mod: None,
            binding: None,
            assign: false,
            span,
        };
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::class_modification => m.class_mod = Some(self.class_modification(p)),
                Rule::binding => {
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::assign_op => m.assign = true,
                            _ => m.binding = Some(self.expression(q)),
                        }
                    }
                }
                _ => self.internal(&p),
            }
        }
        m
    }

    pub fn class_modification(&mut self, pair: Pair<'_, Rule>) -> ClassModification {
        let span = self.span(&pair);
        let mut args = Vec::new();
        if let Some(list) = pair.into_inner().next() {
            for arg in list.into_inner() {
                if let Some(a) = arg.into_inner().next() {
                    args.push(self.argument(a));
                }
            }
        }
        ClassModification { args, span }
    }

    fn argument(&mut self, pair: Pair<'_, Rule>) -> Argument {
        let span = self.span(&pair);
        let redeclare = pair.as_rule() == Rule::element_redeclaration;
        let mut each = false;
        let mut is_final = false;
        let mut replaceable = false;
        let mut element = None;
        let mut constrainedby = None;
        let mut modify = None;
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::redeclare_kw => {}
                Rule::each_kw => each = true,
                Rule::final_kw => is_final = true,
                Rule::element_modification => {
                    let mut name = None;
                    let mut modification = None;
                    let mut description = None;
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::name => name = Some(self.name(q)),
                            Rule::modification => modification = Some(self.modification(q)),
                            Rule::description => description = self.description(q),
                            _ => self.internal(&q),
                        }
                    }
                    modify = Some((name, modification, description));
                }
                Rule::element_replaceable => {
                    replaceable = true;
                    for q in p.into_inner() {
                        match q.as_rule() {
                            Rule::replaceable_kw => {}
                            Rule::constraining_clause => constrainedby = Some(self.constraining(q)),
                            _ => element = Some(self.redeclared(q)),
                        }
                    }
                }
                Rule::short_class_definition | Rule::component_clause1 => {
                    element = Some(self.redeclared(p))
                }
                _ => self.internal(&p),
            }
        }
        if let Some((name, modification, description)) = modify {
            return Argument::Modify {
                each,
                is_final,
                name: name.unwrap_or(Name {
                    global: false,
                    parts: Vec::new(),
                    span,
                }),
                modification,
                description,
                span,
            };
        }
        Argument::Redeclare {
            redeclare,
            each,
            is_final,
            replaceable,
            element: element.unwrap_or(RedeclaredElement::Component(ComponentClause {
                prefix: TypePrefix::default(),
                type_name: Name {
                    global: false,
                    parts: Vec::new(),
                    span,
                },
                type_dims: Vec::new(),
                components: Vec::new(),
            })),
            constrainedby,
            span,
        }
    }

    fn redeclared(&mut self, pair: Pair<'_, Rule>) -> RedeclaredElement {
        if pair.as_rule() == Rule::short_class_definition {
            let span = self.span(&pair);
            let mut partial = false;
            let mut kind = ClassKind::Class;
            let mut name = Ident {
                text: SmolStr::default(),
                span,
            };
            let mut body = None;
            let mut prefixes = ClassPrefixes::default();
            for p in pair.into_inner() {
                match p.as_rule() {
                    Rule::class_prefixes => (partial, prefixes, kind) = class_prefixes(p),
                    _ => {
                        let (n, b) = self.class_specifier(p);
                        name = n;
                        body = Some(b);
                    }
                }
            }
            let body = body.unwrap_or(ClassBody::Long {
                description: None,
                composition: Composition::default(),
                end_name: name.clone(),
                extends: None,
            });
            return RedeclaredElement::Class(Box::new(ClassDef {
                encapsulated: false,
                partial,
                prefixes,
                kind,
                name,
                body,
                span,
            }));
        }
        RedeclaredElement::Component(self.component_clause(pair))
    }

    fn annotation(&mut self, pair: Pair<'_, Rule>) -> Option<ClassModification> {
        kids(pair).next().map(|m| self.class_modification(m))
    }

    fn description(&mut self, pair: Pair<'_, Rule>) -> Option<String> {
        let mut out: Option<String> = None;
        for s in pair.into_inner() {
            let v = self.string_value(&s);
            out.get_or_insert_with(String::new).push_str(&v);
        }
        out
    }

    fn comment(&mut self, pair: Pair<'_, Rule>) -> Comment {
        let mut c = Comment::default();
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::description => c.description = self.description(p),
                Rule::annotation_clause => c.annotation = self.annotation(p),
                _ => self.internal(&p),
            }
        }
        c
    }

    fn string_value(&mut self, pair: &Pair<'_, Rule>) -> String {
        let raw = pair.as_str();
        let inner = &raw[1..raw.len().saturating_sub(1).max(1)];
        unescape(inner)
    }

    // ------------------------------------------------------------ equations

    fn equation(&mut self, pair: Pair<'_, Rule>) -> Equation {
        let span = self.span(&pair);
        let mut it = kids(pair);
        let body = it.next();
        let comment = it.next().map(|c| self.comment(c)).unwrap_or_default();
        let kind = match body {
            Some(b) => self.equation_kind(b),
            None => EquationKind::Call(Expr {
                kind: ExprKind::Tuple(Vec::new()),
                span,
            }),
        };
        Equation {
            kind,
            comment,
            span,
        }
    }

    fn equation_kind(&mut self, pair: Pair<'_, Rule>) -> EquationKind {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::simple_or_call_equation => {
                let mut it = pair.into_inner();
                let lhs = match it.next() {
                    Some(p) => self.expression(p),
                    None => return EquationKind::Call(empty(span)),
                };
                match (it.next(), it.next()) {
                    (Some(op), Some(rhs)) => {
                        if op.as_str() == ":=" {
                            let op_span = self.span(&op);
                            self.diags.push(shared::assign_in_equation(op_span));
                        }
                        EquationKind::Simple {
                            lhs,
                            rhs: self.expression(rhs),
                        }
                    }
                    _ => EquationKind::Call(lhs),
                }
            }
            Rule::connect_clause => {
                let mut it = kids(pair);
                let a = it.next().map(|p| self.component_reference(p));
                let b = it.next().map(|p| self.component_reference(p));
                match (a, b) {
                    (Some(a), Some(b)) => EquationKind::Connect { a, b },
                    _ => EquationKind::Call(empty(span)),
                }
            }
            Rule::if_equation => {
                let mut branches = Vec::new();
                let mut otherwise = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.eq_block(b)));
                }
                for p in it {
                    match p.as_rule() {
                        Rule::elseif_eq => {
                            let mut q = kids(p);
                            if let (Some(c), Some(b)) = (q.next(), q.next()) {
                                branches.push((self.expression(c), self.eq_block(b)));
                            }
                        }
                        Rule::else_eq => {
                            if let Some(b) = kids(p).next() {
                                otherwise = self.eq_block(b);
                            }
                        }
                        _ => self.internal(&p),
                    }
                }
                EquationKind::If {
                    branches,
                    otherwise,
                }
            }
            Rule::for_equation => {
                let mut it = kids(pair);
                let indices = it.next().map(|p| self.for_indices(p)).unwrap_or_default();
                let body = it.next().map(|p| self.eq_block(p)).unwrap_or_default();
                EquationKind::For { indices, body }
            }
            Rule::when_equation => {
                let mut branches = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.eq_block(b)));
                }
                for p in it {
                    let mut q = kids(p);
                    if let (Some(c), Some(b)) = (q.next(), q.next()) {
                        branches.push((self.expression(c), self.eq_block(b)));
                    }
                }
                EquationKind::When { branches }
            }
            _ => {
                self.internal(&pair);
                EquationKind::Call(empty(span))
            }
        }
    }

    fn eq_block(&mut self, pair: Pair<'_, Rule>) -> Vec<Equation> {
        kids(pair).map(|p| self.equation(p)).collect()
    }

    fn for_indices(&mut self, pair: Pair<'_, Rule>) -> Vec<ForIndex> {
        let mut out = Vec::new();
        for idx in pair.into_inner() {
            let mut it = kids(idx);
            if let Some(name) = it.next() {
                let name = self.ident(name);
                let range = it.next().map(|e| self.expression(e));
                out.push(ForIndex { name, range });
            }
        }
        out
    }

    // ------------------------------------------------------------ statements

    fn statement(&mut self, pair: Pair<'_, Rule>) -> Statement {
        let span = self.span(&pair);
        let mut it = kids(pair);
        let body = it.next();
        let comment = it.next().map(|c| self.comment(c)).unwrap_or_default();
        let kind = match body {
            Some(b) => self.statement_kind(b),
            None => StatementKind::Break,
        };
        Statement {
            kind,
            comment,
            span,
        }
    }

    fn st_block(&mut self, pair: Pair<'_, Rule>) -> Vec<Statement> {
        kids(pair).map(|p| self.statement(p)).collect()
    }

    fn statement_kind(&mut self, pair: Pair<'_, Rule>) -> StatementKind {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::assign_or_call => {
                let mut it = pair.into_inner();
                let target = match it.next() {
                    Some(t) => self.component_reference(t),
                    None => return StatementKind::Break,
                };
                match it.next() {
                    Some(args) if args.as_rule() == Rule::function_call_args => {
                        let func = self.callee(&target);
                        let args = self.call_args(args);
                        StatementKind::Call(Expr {
                            kind: ExprKind::Call { func, args },
                            span,
                        })
                    }
                    Some(op) => {
                        if op.as_str() == "=" {
                            let op_span = self.span(&op);
                            self.diags.push(shared::equals_in_algorithm(op_span));
                        }
                        let value = match it.next() {
                            Some(v) => self.expression(v),
                            None => empty(span),
                        };
                        StatementKind::Assign { target, value }
                    }
                    None => {
                        self.diags
                            .push(shared::statement_without_effect(target.span));
                        StatementKind::Call(Expr {
                            kind: ExprKind::Ref(target),
                            span,
                        })
                    }
                }
            }
            Rule::multi_assign => {
                let mut it = pair.into_inner();
                let targets = it.next().map(|p| self.output_list(p)).unwrap_or_default();
                let func = it.next().map(|p| self.component_reference(p));
                let args = it.next().map(|p| self.call_args(p)).unwrap_or_default();
                let value = match func {
                    Some(f) => Expr {
                        kind: ExprKind::Call {
                            func: self.callee(&f),
                            args,
                        },
                        span,
                    },
                    None => empty(span),
                };
                StatementKind::MultiAssign { targets, value }
            }
            Rule::return_stmt => StatementKind::Return,
            Rule::break_stmt => StatementKind::Break,
            Rule::if_statement => {
                let mut branches = Vec::new();
                let mut otherwise = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.st_block(b)));
                }
                for p in it {
                    match p.as_rule() {
                        Rule::elseif_st => {
                            let mut q = kids(p);
                            if let (Some(c), Some(b)) = (q.next(), q.next()) {
                                branches.push((self.expression(c), self.st_block(b)));
                            }
                        }
                        Rule::else_st => {
                            if let Some(b) = kids(p).next() {
                                otherwise = self.st_block(b);
                            }
                        }
                        _ => self.internal(&p),
                    }
                }
                StatementKind::If {
                    branches,
                    otherwise,
                }
            }
            Rule::for_statement => {
                let mut it = kids(pair);
                let indices = it.next().map(|p| self.for_indices(p)).unwrap_or_default();
                let body = it.next().map(|p| self.st_block(p)).unwrap_or_default();
                StatementKind::For { indices, body }
            }
            Rule::while_statement => {
                let mut it = kids(pair);
                let condition = match it.next() {
                    Some(c) => self.expression(c),
                    None => empty(span),
                };
                let body = it.next().map(|p| self.st_block(p)).unwrap_or_default();
                StatementKind::While { condition, body }
            }
            Rule::when_statement => {
                let mut branches = Vec::new();
                let mut it = kids(pair);
                if let (Some(c), Some(b)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.st_block(b)));
                }
                for p in it {
                    let mut q = kids(p);
                    if let (Some(c), Some(b)) = (q.next(), q.next()) {
                        branches.push((self.expression(c), self.st_block(b)));
                    }
                }
                StatementKind::When { branches }
            }
            _ => {
                self.internal(&pair);
                StatementKind::Break
            }
        }
    }

    // ------------------------------------------------------------ expressions

    pub fn expression(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::expression | Rule::function_argument | Rule::subscript => {
                match pair.into_inner().next() {
                    Some(inner) => self.expression(inner),
                    None => empty(span),
                }
            }
            Rule::if_expression => {
                let mut it = kids(pair).peekable();
                let mut branches = Vec::new();
                if let (Some(c), Some(t)) = (it.next(), it.next()) {
                    branches.push((self.expression(c), self.expression(t)));
                }
                let mut otherwise = empty(span);
                for p in it {
                    if p.as_rule() == Rule::elseif_expr {
                        let mut q = kids(p);
                        if let (Some(c), Some(t)) = (q.next(), q.next()) {
                            branches.push((self.expression(c), self.expression(t)));
                        }
                    } else {
                        otherwise = self.expression(p);
                    }
                }
                Expr {
                    kind: ExprKind::If {
                        branches,
                        otherwise: Box::new(otherwise),
                    },
                    span,
                }
            }
            Rule::simple_expression => {
                let mut parts: Vec<Expr> =
                    pair.into_inner().map(|p| self.operand_expr(p)).collect();
                match parts.len() {
                    1 => parts.pop().unwrap_or_else(|| empty(span)),
                    2 => {
                        let stop = parts.pop().unwrap_or_else(|| empty(span));
                        let start = parts.pop().unwrap_or_else(|| empty(span));
                        Expr {
                            kind: ExprKind::Range {
                                start: Box::new(start),
                                step: None,
                                stop: Box::new(stop),
                            },
                            span,
                        }
                    }
                    _ => {
                        let stop = parts.pop().unwrap_or_else(|| empty(span));
                        let step = parts.pop().unwrap_or_else(|| empty(span));
                        let start = parts.pop().unwrap_or_else(|| empty(span));
                        Expr {
                            kind: ExprKind::Range {
                                start: Box::new(start),
                                step: Some(Box::new(step)),
                                stop: Box::new(stop),
                            },
                            span,
                        }
                    }
                }
            }
            Rule::operand_expr => self.operand_expr(pair),
            Rule::function_partial_application => {
                let mut it = kids(pair);
                let func = it.next().map(|n| self.name(n));
                let args = it.next().map(|p| self.named_args(p)).unwrap_or_default();
                Expr {
                    kind: ExprKind::PartialApplication {
                        func: Box::new(func.unwrap_or(Name {
                            global: false,
                            parts: Vec::new(),
                            span,
                        })),
                        args,
                    },
                    span,
                }
            }
            _ => {
                self.internal(&pair);
                empty(span)
            }
        }
    }

    fn operand_expr(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let file = self.file;
        let pairs: Pairs<'_, Rule> = pair.into_inner();
        PRATT
            .map_primary(|p| self.primary(p))
            .map_prefix(move |op, operand| {
                let s = op.as_span();
                let span = Span::new(file, s.start(), s.end()).to(operand.span);
                let op = match op.as_rule() {
                    Rule::not_op => UnaryOp::Not,
                    Rule::neg_op => UnaryOp::Neg,
                    _ => UnaryOp::Plus,
                };
                Expr {
                    kind: ExprKind::Unary {
                        op,
                        operand: Box::new(operand),
                    },
                    span,
                }
            })
            .map_infix(|lhs, op, rhs| {
                let span = lhs.span.to(rhs.span);
                let op = match op.as_rule() {
                    Rule::or_op => BinaryOp::Or,
                    Rule::and_op => BinaryOp::And,
                    Rule::lt_op => BinaryOp::Lt,
                    Rule::le_op => BinaryOp::Le,
                    Rule::gt_op => BinaryOp::Gt,
                    Rule::ge_op => BinaryOp::Ge,
                    Rule::eq_eq_op => BinaryOp::Eq,
                    Rule::ne_op => BinaryOp::Ne,
                    Rule::add_op => BinaryOp::Add,
                    Rule::sub_op => BinaryOp::Sub,
                    Rule::mul_op => BinaryOp::Mul,
                    Rule::div_op => BinaryOp::Div,
                    Rule::pow_op => BinaryOp::Pow,
                    Rule::ew_add => BinaryOp::ElemAdd,
                    Rule::ew_sub => BinaryOp::ElemSub,
                    Rule::ew_mul => BinaryOp::ElemMul,
                    Rule::ew_div => BinaryOp::ElemDiv,
                    _ => BinaryOp::ElemPow,
                };
                Expr {
                    kind: ExprKind::Binary {
                        op,
                        lhs: Box::new(lhs),
                        rhs: Box::new(rhs),
                    },
                    span,
                }
            })
            .parse(pairs)
    }

    fn primary(&mut self, pair: Pair<'_, Rule>) -> Expr {
        let span = self.span(&pair);
        let Some(p) = pair.into_inner().next() else {
            return empty(span);
        };
        let kind = match p.as_rule() {
            Rule::unsigned_integer | Rule::unsigned_real => {
                shared::number(p.as_str(), span, self.diags)
            }
            Rule::string => ExprKind::String(self.string_value(&p)),
            Rule::true_lit => ExprKind::Bool(true),
            Rule::false_lit => ExprKind::Bool(false),
            Rule::end_expr => ExprKind::End,
            Rule::builtin_call => {
                let mut it = p.into_inner();
                let name = it.next();
                let args = it.next().map(|a| self.call_args(a)).unwrap_or_default();
                let func = match name {
                    Some(n) => Name {
                        global: false,
                        parts: vec![self.ident(n)],
                        span,
                    },
                    None => return empty(span),
                };
                ExprKind::Call { func, args }
            }
            Rule::ref_or_call => {
                let mut it = p.into_inner();
                let cref = match it.next() {
                    Some(c) => self.component_reference(c),
                    None => return empty(span),
                };
                match it.next() {
                    Some(args) => {
                        let func = self.callee(&cref);
                        ExprKind::Call {
                            func,
                            args: self.call_args(args),
                        }
                    }
                    None => ExprKind::Ref(cref),
                }
            }
            Rule::paren_expr => {
                let list = p.into_inner().next();
                let mut items = list.map(|l| self.output_list(l)).unwrap_or_default();
                if items.len() == 1 && items[0].is_some() {
                    // Plain parentheses: keep the inner expression, widen its span.
                    let mut e = items.pop().flatten().unwrap_or_else(|| empty(span));
                    e.span = span;
                    return e;
                }
                ExprKind::Tuple(items)
            }
            Rule::array_expr => {
                let Some(args) = p.into_inner().next() else {
                    return empty(span);
                };
                let mut it = args.into_inner();
                let first = match it.next() {
                    Some(f) => self.expression(f),
                    None => return empty(span),
                };
                match it.next() {
                    Some(q) if q.as_rule() == Rule::for_kw => {
                        let indices = it.next().map(|i| self.for_indices(i)).unwrap_or_default();
                        ExprKind::Comprehension {
                            body: Box::new(first),
                            indices,
                        }
                    }
                    Some(q) => {
                        let mut items = vec![first, self.expression(q)];
                        items.extend(it.map(|e| self.expression(e)));
                        ExprKind::Array(items)
                    }
                    None => ExprKind::Array(vec![first]),
                }
            }
            Rule::matrix_expr => ExprKind::Matrix(
                p.into_inner()
                    .map(|row| row.into_inner().map(|e| self.expression(e)).collect())
                    .collect(),
            ),
            _ => {
                self.internal(&p);
                return empty(span);
            }
        };
        Expr { kind, span }
    }

    fn output_list(&mut self, pair: Pair<'_, Rule>) -> Vec<Option<Expr>> {
        let mut items = vec![None];
        for p in pair.into_inner() {
            if p.as_rule() == Rule::comma {
                items.push(None);
            } else if let Some(last) = items.last_mut() {
                *last = Some(self.expression(p));
            }
        }
        if items.len() == 1 && items[0].is_none() {
            items.clear();
        }
        items
    }

    fn callee(&mut self, cref: &ComponentRef) -> Name {
        shared::callee(cref, self.diags)
    }

    pub fn component_reference(&mut self, pair: Pair<'_, Rule>) -> ComponentRef {
        let span = self.span(&pair);
        let mut global = false;
        let mut parts = Vec::new();
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::global_dot => global = true,
                Rule::ref_part => {
                    let mut it = p.into_inner();
                    let name = match it.next() {
                        Some(n) => self.ident(n),
                        None => continue,
                    };
                    let subscripts = it.next().map(|s| self.subscripts(s)).unwrap_or_default();
                    parts.push(RefPart { name, subscripts });
                }
                _ => self.internal(&p),
            }
        }
        ComponentRef {
            global,
            parts,
            span,
        }
    }

    fn subscripts(&mut self, pair: Pair<'_, Rule>) -> Vec<Subscript> {
        pair.into_inner()
            .map(|s| {
                let span = self.span(&s);
                match s.into_inner().next() {
                    Some(c) if c.as_rule() == Rule::colon_sub => Subscript::Colon(span),
                    Some(e) => Subscript::Expr(self.expression(e)),
                    None => Subscript::Colon(span),
                }
            })
            .collect()
    }

    fn call_args(&mut self, pair: Pair<'_, Rule>) -> Box<CallArgs> {
        let span = self.span(&pair);
        let mut args = CallArgs {
            span,
            ..CallArgs::default()
        };
        let mut next = pair.into_inner().next();
        while let Some(fa) = next.take() {
            let mut it = fa.into_inner();
            let Some(first) = it.next() else { break };
            if first.as_rule() == Rule::named_arguments {
                args.named.extend(self.named_args(first));
                break;
            }
            args.positional.push(self.expression(first));
            match it.next() {
                Some(q) if q.as_rule() == Rule::for_kw => {
                    args.iterators = it.next().map(|i| self.for_indices(i)).unwrap_or_default();
                }
                Some(rest) => next = Some(rest),
                None => {}
            }
        }
        Box::new(args)
    }

    fn named_args(&mut self, pair: Pair<'_, Rule>) -> Vec<NamedArg> {
        pair.into_inner()
            .filter_map(|na| {
                let mut it = na.into_inner();
                let name = self.ident(it.next()?);
                let value = self.expression(it.next()?);
                Some(NamedArg { name, value })
            })
            .collect()
    }
}

fn empty(span: Span) -> Expr {
    Expr {
        kind: ExprKind::Tuple(Vec::new()),
        span,
    }
}

/// `partial`, the refining prefixes and the kind of a `class_prefixes` pair.
fn class_prefixes(pair: Pair<'_, Rule>) -> (bool, ClassPrefixes, ClassKind) {
    let (mut partial, mut prefixes, mut kind) = (false, ClassPrefixes::default(), ClassKind::Class);
    for q in pair.into_inner() {
        match q.as_rule() {
            Rule::partial_kw => partial = true,
            Rule::expandable_kw => prefixes.expandable = true,
            Rule::operator_kw => prefixes.operator = true,
            Rule::purity_kw => {
                prefixes.purity = Some(if q.as_str() == "pure" {
                    Purity::Pure
                } else {
                    Purity::Impure
                })
            }
            Rule::class_kind => kind = class_kind(q.as_str()),
            _ => {}
        }
    }
    (partial, prefixes, kind)
}

fn class_kind(s: &str) -> ClassKind {
    match s {
        "model" => ClassKind::Model,
        "block" => ClassKind::Block,
        "connector" => ClassKind::Connector,
        "record" => ClassKind::Record,
        "package" => ClassKind::Package,
        "function" => ClassKind::Function,
        "type" => ClassKind::Type,
        "operator" => ClassKind::Operator,
        _ => ClassKind::Class,
    }
}

fn causality_of(s: &str) -> Causality {
    if s == "input" {
        Causality::Input
    } else {
        Causality::Output
    }
}

/// Resolves Modelica string escapes (the lexer has already rejected invalid ones).
pub fn unescape(s: &str) -> String {
    if !s.contains('\\') {
        return s.to_owned();
    }
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('a') => out.push('\u{7}'),
            Some('b') => out.push('\u{8}'),
            Some('f') => out.push('\u{c}'),
            Some('v') => out.push('\u{b}'),
            Some(other) => out.push(other),
            None => {}
        }
    }
    out
}
