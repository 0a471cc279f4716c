//! Classes: definitions, the long, short, `der` and enumeration specifiers, class
//! extensions, external clauses and compositions.

use super::{causality_of, class_prefixes, kids, Builder};
use crate::ast::*;
use crate::grammar::Rule;
use pest::iterators::Pair;
use smol_str::SmolStr;
use unimo_source::Span;

impl Builder<'_> {
    pub(crate) fn class_definition(&mut self, pair: Pair<'_, Rule>) -> ClassDef {
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
        ClassDef::new(encapsulated, (partial, prefixes, kind), (name, body), span)
    }

    pub(crate) fn class_specifier(&mut self, pair: Pair<'_, Rule>) -> (Ident, ClassBody) {
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
            Rule::long_specifier => self.long_body(it, &name, extends.map(|(_, e)| e)),
            Rule::der_specifier => self.der_body(it, name.span),
            Rule::short_specifier => self.short_body(it, name.span),
            _ => self.enumeration_body(it),
        };
        (name, body)
    }

    /// The body of `class A ... end A;` (or `class extends A ... end A;`).
    fn long_body<'i>(
        &mut self,
        it: impl Iterator<Item = Pair<'i, Rule>>,
        name: &Ident,
        extends: Option<ClassExtends>,
    ) -> ClassBody {
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
            extends: extends.map(Box::new),
        }
    }

    /// The body of `type A = der(B, x);`.
    fn der_body<'i>(
        &mut self,
        it: impl Iterator<Item = Pair<'i, Rule>>,
        name_span: Span,
    ) -> ClassBody {
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
            base: base.unwrap_or_else(|| Name::empty(name_span)),
            with_respect_to,
            comment,
        }
    }

    /// The body of `type A = input B[n](m) "comment";`.
    fn short_body<'i>(
        &mut self,
        it: impl Iterator<Item = Pair<'i, Rule>>,
        name_span: Span,
    ) -> ClassBody {
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
            base: base.unwrap_or_else(|| Name::empty(name_span)),
            dims,
            modification,
            comment,
        }
    }

    /// The body of `type A = enumeration(a, b, c);` (or `enumeration(:)`).
    fn enumeration_body<'i>(&mut self, it: impl Iterator<Item = Pair<'i, Rule>>) -> ClassBody {
        let mut literals = Vec::new();
        let mut open = false;
        let mut comment = Comment::default();
        for p in it {
            match p.as_rule() {
                Rule::enum_list => {
                    for lit in p.into_inner() {
                        let mut li = lit.into_inner();
                        let name = li.next().map(|n| self.ident(n));
                        let comment = li.next().map(|c| self.comment(c)).unwrap_or_default();
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

    pub(crate) fn composition(&mut self, pair: Pair<'_, Rule>) -> Composition {
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
}
