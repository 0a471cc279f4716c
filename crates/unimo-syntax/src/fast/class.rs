//! Classes: prefixes, specifiers (long, short, `der`, enumeration), external clauses
//! and compositions with their sections.

use super::{is_class_kind, is_kind_keyword, P};
use crate::ast::*;
use crate::lexer::{Sym, TokenKind};

impl<'a> P<'a, '_> {
    // ------------------------------------------------------------ classes

    pub(crate) fn class_prefixes(&mut self) -> Option<ClassHead> {
        let partial = self.eat(Sym::KwPartial);
        let mut prefixes = ClassPrefixes {
            expandable: self.eat(Sym::KwExpandable),
            ..ClassPrefixes::default()
        };
        if self.eat(Sym::KwPure) {
            prefixes.purity = Some(Purity::Pure);
        } else if self.eat(Sym::KwImpure) {
            prefixes.purity = Some(Purity::Impure);
        }
        if self.at(Sym::KwOperator)
            && self
                .tok(self.pos + 1)
                .is_some_and(|t| is_kind_keyword(t.sym))
        {
            self.pos += 1;
            prefixes.operator = true;
        }
        let kind = match self.sym() {
            Sym::KwModel => ClassKind::Model,
            Sym::KwBlock => ClassKind::Block,
            Sym::KwConnector => ClassKind::Connector,
            Sym::KwRecord => ClassKind::Record,
            Sym::KwPackage => ClassKind::Package,
            Sym::KwFunction => ClassKind::Function,
            Sym::KwType => ClassKind::Type,
            Sym::KwClass => ClassKind::Class,
            Sym::KwOperator => ClassKind::Operator,
            _ => return None,
        };
        self.pos += 1;
        Some((partial, prefixes, kind))
    }

    pub(crate) fn at_class_start(&self) -> bool {
        let sym = self.sym();
        sym == Sym::KwEncapsulated || sym == Sym::KwPartial || is_class_kind(sym)
    }

    pub(crate) fn class_definition(&mut self) -> Option<ClassDef> {
        let first = self.pos;
        let encapsulated = self.eat(Sym::KwEncapsulated);
        let head = self.class_prefixes()?;
        let specifier = self.class_specifier(false)?;
        Some(ClassDef::new(
            encapsulated,
            head,
            specifier,
            self.span_from(first),
        ))
    }

    /// `short_only`: inside a modification, only short and enumeration forms exist.
    pub(crate) fn class_specifier(&mut self, short_only: bool) -> Option<(Ident, ClassBody)> {
        if self.at(Sym::KwExtends) {
            if short_only {
                return None;
            }
            let first = self.pos;
            self.pos += 1;
            let name = self.ident()?;
            let modification = self.parse_if(Sym::LParen, Self::class_modification)?;
            let extends = ClassExtends {
                modification,
                span: self.span_from(first),
            };
            return self.long_body(name, Some(Box::new(extends)));
        }
        let name = self.ident()?;
        if self.eat(Sym::Equals) {
            if self.eat(Sym::KwDer) {
                return Some((name, self.der_body()?));
            }
            if self.eat(Sym::KwEnumeration) {
                return Some((name, self.enumeration_body()?));
            }
            let causality = self.causality();
            let base = self.name()?;
            let dims = if self.at(Sym::LBracket) {
                self.array_subscripts()?
            } else {
                Vec::new()
            };
            let modification = self.parse_if(Sym::LParen, Self::class_modification)?;
            let comment = self.comment()?;
            return Some((
                name,
                ClassBody::Short {
                    causality,
                    base,
                    dims,
                    modification,
                    comment,
                },
            ));
        }
        if short_only {
            return None;
        }
        self.long_body(name, None)
    }

    /// `der(B, x, y) "comment"`, its `der` eaten.
    fn der_body(&mut self) -> Option<ClassBody> {
        self.expect(Sym::LParen)?;
        let base = self.name()?;
        let mut with_respect_to = Vec::new();
        while self.eat(Sym::Comma) {
            with_respect_to.push(self.ident()?);
        }
        if with_respect_to.is_empty() {
            return None;
        }
        self.expect(Sym::RParen)?;
        let comment = self.comment()?;
        Some(ClassBody::Der {
            base,
            with_respect_to,
            comment,
        })
    }

    /// `enumeration(a, b "comment", c)` or `enumeration(:)`, its `enumeration` eaten.
    fn enumeration_body(&mut self) -> Option<ClassBody> {
        self.expect(Sym::LParen)?;
        let mut literals = Vec::new();
        let mut open = false;
        if self.eat(Sym::Colon) {
            open = true;
        } else if self.at_ident() {
            loop {
                let lit = self.ident()?;
                let comment = self.comment()?;
                literals.push(EnumLiteral { name: lit, comment });
                if !self.eat(Sym::Comma) {
                    break;
                }
            }
        }
        self.expect(Sym::RParen)?;
        let comment = self.comment()?;
        Some(ClassBody::Enumeration {
            literals,
            open,
            comment,
        })
    }

    /// The rest of a long class specifier after its name (or class-extends head).
    fn long_body(
        &mut self,
        name: Ident,
        extends: Option<Box<ClassExtends>>,
    ) -> Option<(Ident, ClassBody)> {
        let description = self.description();
        let composition = self.composition()?;
        self.expect(Sym::KwEnd)?;
        let end_name = self.ident()?;
        Some((
            name,
            ClassBody::Long {
                description,
                composition,
                end_name,
                extends,
            },
        ))
    }

    /// `external "C" y = f(x) annotation(...);`
    fn external_clause(&mut self) -> Option<External> {
        let first = self.pos;
        self.expect(Sym::KwExternal)?;
        let language = if self
            .tok(self.pos)
            .is_some_and(|t| t.kind == TokenKind::String)
        {
            let t = &self.toks[self.pos];
            self.pos += 1;
            Some(self.string_value(t))
        } else {
            None
        };
        let call = if self.at_ident() || self.at(Sym::Dot) {
            let start = self.pos;
            let target = self.component_reference()?;
            let (output, function) = if self.eat(Sym::Equals) {
                (Some(target), self.ident()?)
            } else {
                // A bare function name: read it again as an identifier.
                self.pos = start;
                (None, self.ident()?)
            };
            let args = self.paren_list(Self::expression)?;
            Some(ExternalCall {
                output,
                function,
                args,
            })
        } else {
            None
        };
        let annotation = self.parse_if(Sym::KwAnnotation, Self::annotation)?;
        self.expect(Sym::Semi)?;
        Some(External {
            language,
            call,
            annotation,
            span: self.span_from(first),
        })
    }

    pub(crate) fn causality(&mut self) -> Option<Causality> {
        if self.eat(Sym::KwInput) {
            Some(Causality::Input)
        } else if self.eat(Sym::KwOutput) {
            Some(Causality::Output)
        } else {
            None
        }
    }

    fn composition(&mut self) -> Option<Composition> {
        let mut c = Composition::default();
        self.element_list(Visibility::Public, &mut c.elements)?;
        loop {
            if self.eat(Sym::KwPublic) {
                self.element_list(Visibility::Public, &mut c.elements)?;
            } else if self.eat(Sym::KwProtected) {
                self.element_list(Visibility::Protected, &mut c.elements)?;
            } else if self.at(Sym::KwEquation)
                || (self.at(Sym::KwInitial) && self.sym_at(self.pos + 1, Sym::KwEquation))
            {
                let first = self.pos;
                let initial = self.eat(Sym::KwInitial);
                self.pos += 1;
                let mut equations = Vec::new();
                while !self.at_section_start() && self.at_equation_start() {
                    equations.push(self.equation()?);
                    self.expect(Sym::Semi)?;
                }
                c.sections.push(Section::Equation(EquationSection {
                    initial,
                    equations,
                    span: self.span_from(first),
                }));
            } else if self.at(Sym::KwAlgorithm)
                || (self.at(Sym::KwInitial) && self.sym_at(self.pos + 1, Sym::KwAlgorithm))
            {
                let first = self.pos;
                let initial = self.eat(Sym::KwInitial);
                self.pos += 1;
                let mut statements = Vec::new();
                while !self.at_section_start() && self.at_statement_start() {
                    statements.push(self.statement()?);
                    self.expect(Sym::Semi)?;
                }
                c.sections.push(Section::Algorithm(AlgorithmSection {
                    initial,
                    statements,
                    span: self.span_from(first),
                }));
            } else {
                break;
            }
        }
        if self.at(Sym::KwExternal) {
            c.external = Some(self.external_clause()?);
        }
        if self.at(Sym::KwAnnotation) {
            c.annotation = Some(self.annotation()?);
            self.expect(Sym::Semi)?;
        }
        Some(c)
    }

    fn at_section_start(&self) -> bool {
        self.at(Sym::KwEquation)
            || self.at(Sym::KwAlgorithm)
            || self.at(Sym::KwPublic)
            || self.at(Sym::KwProtected)
            || self.at(Sym::KwEnd)
            || self.at(Sym::KwExternal)
            || (self.at(Sym::KwInitial)
                && (self.sym_at(self.pos + 1, Sym::KwEquation)
                    || self.sym_at(self.pos + 1, Sym::KwAlgorithm)))
    }

    pub(crate) fn at_block_end(&self) -> bool {
        self.at(Sym::KwElseif)
            || self.at(Sym::KwElsewhen)
            || self.at(Sym::KwElse)
            || self.at(Sym::KwEnd)
    }

    pub(crate) fn at_element_start(&self) -> bool {
        self.at_ident()
            || is_class_kind(self.sym())
            || matches!(
                self.sym(),
                Sym::Dot
                    | Sym::KwImport
                    | Sym::KwExtends
                    | Sym::KwRedeclare
                    | Sym::KwFinal
                    | Sym::KwInner
                    | Sym::KwOuter
                    | Sym::KwReplaceable
                    | Sym::KwEncapsulated
                    | Sym::KwPartial
                    | Sym::KwFlow
                    | Sym::KwStream
                    | Sym::KwDiscrete
                    | Sym::KwParameter
                    | Sym::KwConstant
                    | Sym::KwInput
                    | Sym::KwOutput
            )
    }
}
