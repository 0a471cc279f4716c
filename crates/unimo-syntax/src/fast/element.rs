//! Elements: imports, extends, component clauses and declarations, modifications and
//! redeclarations.

use super::{is_class_kind, P};
use crate::ast::*;
use crate::lexer::Sym;
use unimo_source::Span;

impl<'a> P<'a, '_> {
    pub(crate) fn element_list(
        &mut self,
        visibility: Visibility,
        out: &mut Vec<Element>,
    ) -> Option<()> {
        while self.at_element_start() {
            out.push(self.element(visibility)?);
            self.expect(Sym::Semi)?;
        }
        Some(())
    }

    pub(crate) fn element(&mut self, visibility: Visibility) -> Option<Element> {
        let first = self.pos;
        let mut e = Element::unfilled(visibility, Span::default());
        if self.at(Sym::KwImport) {
            e.kind = ElementKind::Import(self.import()?);
        } else if self.at(Sym::KwExtends) {
            e.kind = ElementKind::Extends(self.extends()?);
        } else {
            e.redeclare = self.eat(Sym::KwRedeclare);
            e.is_final = self.eat(Sym::KwFinal);
            e.inner = self.eat(Sym::KwInner);
            e.outer = self.eat(Sym::KwOuter);
            if self.eat(Sym::KwReplaceable) {
                e.replaceable = true;
                e.kind = self.element_kind()?;
                if self.at(Sym::KwConstrainedby) {
                    e.constrainedby = Some(self.constraining()?);
                    self.comment()?;
                }
            } else {
                e.kind = self.element_kind()?;
            }
        }
        e.span = self.span_from(first);
        Some(e)
    }

    fn element_kind(&mut self) -> Option<ElementKind> {
        if self.at_class_start() {
            Some(ElementKind::Class(Box::new(self.class_definition()?)))
        } else {
            Some(ElementKind::Component(self.component_clause(false)?))
        }
    }

    fn import(&mut self) -> Option<Import> {
        let first = self.pos;
        self.expect(Sym::KwImport)?;
        let kind = if self.at_ident() && self.sym_at(self.pos + 1, Sym::Equals) {
            let alias = self.ident()?;
            self.pos += 1;
            ImportKind::Renamed {
                alias,
                name: self.name()?,
            }
        } else {
            let name = self.name()?;
            if self.eat(Sym::DotStar) {
                ImportKind::Unqualified(name)
            } else if self.at(Sym::Dot) && self.sym_at(self.pos + 1, Sym::LBrace) {
                self.pos += 2;
                let mut items = vec![self.ident()?];
                while self.eat(Sym::Comma) {
                    items.push(self.ident()?);
                }
                self.expect(Sym::RBrace)?;
                ImportKind::Multiple { name, items }
            } else {
                ImportKind::Qualified(name)
            }
        };
        let comment = self.comment()?;
        Some(Import {
            kind,
            comment,
            span: self.span_from(first),
        })
    }

    pub(crate) fn extends(&mut self) -> Option<Extends> {
        let first = self.pos;
        self.expect(Sym::KwExtends)?;
        let base = self.name()?;
        let modification = self.parse_if(Sym::LParen, Self::class_modification)?;
        let annotation = self.parse_if(Sym::KwAnnotation, Self::annotation)?;
        Some(Extends {
            base,
            modification,
            annotation,
            span: self.span_from(first),
        })
    }

    fn constraining(&mut self) -> Option<ConstrainingClause> {
        let first = self.pos;
        self.expect(Sym::KwConstrainedby)?;
        let base = self.name()?;
        let modification = self.parse_if(Sym::LParen, Self::class_modification)?;
        Some(ConstrainingClause {
            base,
            modification,
            span: self.span_from(first),
        })
    }

    fn type_prefix(&mut self) -> TypePrefix {
        let mut t = TypePrefix::default();
        if self.eat(Sym::KwFlow) {
            t.connection = Some(Connection::Flow);
        } else if self.eat(Sym::KwStream) {
            t.connection = Some(Connection::Stream);
        }
        if self.eat(Sym::KwDiscrete) {
            t.variability = Some(Variability::Discrete);
        } else if self.eat(Sym::KwParameter) {
            t.variability = Some(Variability::Parameter);
        } else if self.eat(Sym::KwConstant) {
            t.variability = Some(Variability::Constant);
        }
        t.causality = self.causality();
        t
    }

    /// `single`: the one-declaration form used in redeclarations (`component_clause1`).
    fn component_clause(&mut self, single: bool) -> Option<ComponentClause> {
        let prefix = self.type_prefix();
        let type_name = self.name()?;
        let type_dims = if !single && self.at(Sym::LBracket) {
            self.array_subscripts()?
        } else {
            Vec::new()
        };
        let mut components = vec![self.component_declaration(!single)?];
        while !single && self.eat(Sym::Comma) {
            components.push(self.component_declaration(true)?);
        }
        Some(ComponentClause {
            prefix,
            type_name,
            type_dims,
            components,
        })
    }

    fn component_declaration(&mut self, with_condition: bool) -> Option<ComponentDecl> {
        let first = self.pos;
        let name = self.ident()?;
        let dims = if self.at(Sym::LBracket) {
            self.array_subscripts()?
        } else {
            Vec::new()
        };
        let modification = if self.at(Sym::LParen) || self.at(Sym::Equals) || self.at(Sym::Assign) {
            Some(self.modification()?)
        } else {
            None
        };
        let condition = if with_condition && self.eat(Sym::KwIf) {
            Some(self.expression()?)
        } else {
            None
        };
        let comment = self.comment()?;
        Some(ComponentDecl {
            name,
            dims,
            modification,
            condition,
            comment,
            span: self.span_from(first),
        })
    }

    pub(crate) fn modification(&mut self) -> Option<Modification> {
        let first = self.pos;
        let class_mod = self.parse_if(Sym::LParen, Self::class_modification)?;
        let mut binding = None;
        let mut assign = false;
        if self.at(Sym::Equals) || self.at(Sym::Assign) {
            assign = self.at(Sym::Assign);
            self.pos += 1;
            binding = Some(self.expression()?);
        }
        if class_mod.is_none() && binding.is_none() {
            return None;
        }
        Some(Modification {
            class_mod,
            binding,
            assign,
            span: self.span_from(first),
        })
    }

    /// `( item, item, ... )`, possibly empty.
    pub(crate) fn paren_list<T>(
        &mut self,
        mut item: impl FnMut(&mut Self) -> Option<T>,
    ) -> Option<Vec<T>> {
        self.expect(Sym::LParen)?;
        let mut items = Vec::new();
        if !self.at(Sym::RParen) {
            loop {
                items.push(item(self)?);
                if !self.eat(Sym::Comma) {
                    break;
                }
            }
        }
        self.expect(Sym::RParen)?;
        Some(items)
    }

    pub(crate) fn class_modification(&mut self) -> Option<ClassModification> {
        let first = self.pos;
        let args = self.paren_list(Self::argument)?;
        Some(ClassModification {
            args,
            span: self.span_from(first),
        })
    }

    fn argument(&mut self) -> Option<Argument> {
        let first = self.pos;
        let redeclare = self.eat(Sym::KwRedeclare);
        let each = self.eat(Sym::KwEach);
        let is_final = self.eat(Sym::KwFinal);
        if self.eat(Sym::KwReplaceable) {
            let element = self.redeclared()?;
            let constrainedby = self.parse_if(Sym::KwConstrainedby, Self::constraining)?;
            return Some(Argument::Redeclare {
                redeclare,
                each,
                is_final,
                replaceable: true,
                element,
                constrainedby,
                span: self.span_from(first),
            });
        }
        if redeclare {
            let element = self.redeclared()?;
            return Some(Argument::Redeclare {
                redeclare,
                each,
                is_final,
                replaceable: false,
                element,
                constrainedby: None,
                span: self.span_from(first),
            });
        }
        let name = self.name()?;
        let modification = if self.at(Sym::LParen) || self.at(Sym::Equals) || self.at(Sym::Assign) {
            Some(self.modification()?)
        } else {
            None
        };
        let description = self.description();
        Some(Argument::Modify {
            each,
            is_final,
            name,
            modification,
            description,
            span: self.span_from(first),
        })
    }

    fn redeclared(&mut self) -> Option<RedeclaredElement> {
        if self.at(Sym::KwPartial) || is_class_kind(self.sym()) {
            let first = self.pos;
            let head = self.class_prefixes()?;
            let specifier = self.class_specifier(true)?;
            let span = self.span_from(first);
            return Some(RedeclaredElement::Class(Box::new(ClassDef::new(
                false, head, specifier, span,
            ))));
        }
        Some(RedeclaredElement::Component(self.component_clause(true)?))
    }
}
