//! A hand-written recursive-descent parser over the scanner's tokens: the fast path.
//!
//! The pest grammar (`modelica.pest`) is the grammar of record. This parser accepts a
//! subset of what it accepts — every valid file in practice — and builds exactly the
//! same tree (spans and diagnostics included) about twenty times faster. Whenever it
//! meets anything it is not sure of, it gives up (`None`) and the pest parser, with its
//! error recovery and messages, takes over. Differential tests (`tests/fast_path.rs`
//! and the fuzz target) check that both parsers agree wherever the fast one answers.

use crate::ast::*;
use crate::build::unescape;
use crate::lexer::{Sym, Token, TokenKind};
use crate::shared;
use smol_str::SmolStr;
use unimo_source::{Diagnostic, FileId, Span};

/// Parses a whole file; `None` means "ask pest".
pub(crate) fn parse_file(
    file: FileId,
    text: &str,
    tokens: &[Token],
    diags: &mut Vec<Diagnostic>,
) -> Option<StoredDefinition> {
    let mut p = P {
        file,
        text,
        toks: tokens,
        pos: 0,
        diags,
    };
    let mut within = None;
    if p.at(Sym::KwWithin) {
        p.pos += 1;
        let name = if p.at(Sym::Semi) {
            None
        } else {
            Some(p.name()?)
        };
        p.expect(Sym::Semi)?;
        within = Some(name);
    }
    let mut classes = Vec::new();
    while p.pos < p.toks.len() {
        if p.at(Sym::KwFinal) {
            p.pos += 1;
        }
        classes.push(p.class_definition()?);
        p.expect(Sym::Semi)?;
    }
    Some(StoredDefinition {
        within,
        classes,
        span: Span::new(file, 0, text.len()),
    })
}

struct P<'a, 'd> {
    file: FileId,
    text: &'a str,
    toks: &'a [Token],
    pos: usize,
    diags: &'d mut Vec<Diagnostic>,
}

/// A keyword that names a kind of class (`operator` included).
fn is_kind_keyword(sym: Sym) -> bool {
    matches!(
        sym,
        Sym::KwClass
            | Sym::KwModel
            | Sym::KwRecord
            | Sym::KwBlock
            | Sym::KwConnector
            | Sym::KwType
            | Sym::KwPackage
            | Sym::KwFunction
            | Sym::KwOperator
    )
}

/// A keyword that can start a class definition's prefixes and kind.
fn is_class_kind(sym: Sym) -> bool {
    is_kind_keyword(sym) || matches!(sym, Sym::KwExpandable | Sym::KwPure | Sym::KwImpure)
}

impl<'a> P<'a, '_> {
    // ------------------------------------------------------------ tokens

    fn tok(&self, at: usize) -> Option<&'a Token> {
        self.toks.get(at)
    }

    fn txt(&self, t: &Token) -> &'a str {
        &self.text[t.start()..t.end()]
    }

    fn sym_at(&self, at: usize, sym: Sym) -> bool {
        self.toks.get(at).is_some_and(|t| t.sym == sym)
    }

    fn at(&self, sym: Sym) -> bool {
        self.sym_at(self.pos, sym)
    }

    fn sym(&self) -> Sym {
        self.toks.get(self.pos).map_or(Sym::None, |t| t.sym)
    }

    fn eat(&mut self, sym: Sym) -> bool {
        let hit = self.at(sym);
        self.pos += hit as usize;
        hit
    }

    fn expect(&mut self, sym: Sym) -> Option<()> {
        self.eat(sym).then_some(())
    }

    fn at_ident(&self) -> bool {
        self.tok(self.pos)
            .is_some_and(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent))
    }

    /// Span from token `first` to the last consumed token.
    fn span_from(&self, first: usize) -> Span {
        let start = self.toks[first].start();
        let end = self.toks[self.pos.max(first + 1) - 1].end();
        Span::new(self.file, start, end.max(start))
    }

    fn ident(&mut self) -> Option<Ident> {
        if !self.at_ident() {
            return None;
        }
        let t = &self.toks[self.pos];
        self.pos += 1;
        Some(Ident {
            text: SmolStr::new(self.txt(t)),
            span: Span::new(self.file, t.start(), t.end()),
        })
    }

    /// `name` in pest is compound-atomic: no whitespace around its dots.
    fn name(&mut self) -> Option<Name> {
        let first = self.pos;
        let mut global = false;
        if self.at(Sym::Dot)
            && self
                .tok(self.pos + 1)
                .is_some_and(|n| n.start() == self.toks[self.pos].end())
        {
            global = true;
            self.pos += 1;
        }
        let mut parts = vec![self.ident()?];
        while let (Some(dot), Some(next)) = (self.tok(self.pos), self.tok(self.pos + 1)) {
            let adjacent =
                dot.start() == self.toks[self.pos - 1].end() && next.start() == dot.end();
            if adjacent
                && self.sym_at(self.pos, Sym::Dot)
                && matches!(next.kind, TokenKind::Ident | TokenKind::QuotedIdent)
            {
                self.pos += 1;
                parts.push(self.ident()?);
            } else {
                break;
            }
        }
        Some(Name {
            global,
            parts,
            span: self.span_from(first),
        })
    }

    fn string_value(&self, t: &Token) -> String {
        let raw = self.txt(t);
        unescape(&raw[1..raw.len().saturating_sub(1).max(1)])
    }

    fn description(&mut self) -> Option<String> {
        let mut out: Option<String> = None;
        if self
            .tok(self.pos)
            .is_some_and(|t| t.kind == TokenKind::String)
        {
            loop {
                let t = &self.toks[self.pos];
                self.pos += 1;
                out.get_or_insert_with(String::new)
                    .push_str(&self.string_value(t));
                let more = self.at(Sym::Plus)
                    && self
                        .tok(self.pos + 1)
                        .is_some_and(|n| n.kind == TokenKind::String);
                if !more {
                    break;
                }
                self.pos += 1;
            }
        }
        out
    }

    fn comment(&mut self) -> Option<Comment> {
        let description = self.description();
        let annotation = if self.at(Sym::KwAnnotation) {
            Some(self.annotation()?)
        } else {
            None
        };
        Some(Comment {
            description,
            annotation,
        })
    }

    fn annotation(&mut self) -> Option<ClassModification> {
        self.expect(Sym::KwAnnotation)?;
        self.class_modification()
    }

    // ------------------------------------------------------------ classes

    fn class_prefixes(&mut self) -> Option<(bool, ClassPrefixes, ClassKind)> {
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

    fn at_class_start(&self) -> bool {
        let sym = self.sym();
        sym == Sym::KwEncapsulated || sym == Sym::KwPartial || is_class_kind(sym)
    }

    fn class_definition(&mut self) -> Option<ClassDef> {
        let first = self.pos;
        let encapsulated = self.eat(Sym::KwEncapsulated);
        let (partial, prefixes, kind) = self.class_prefixes()?;
        let (name, body) = self.class_specifier(false)?;
        Some(ClassDef {
            encapsulated,
            partial,
            prefixes,
            kind,
            name,
            body,
            span: self.span_from(first),
        })
    }

    /// `short_only`: inside a modification, only short and enumeration forms exist.
    fn class_specifier(&mut self, short_only: bool) -> Option<(Ident, ClassBody)> {
        if self.at(Sym::KwExtends) {
            if short_only {
                return None;
            }
            let first = self.pos;
            self.pos += 1;
            let name = self.ident()?;
            let modification = if self.at(Sym::LParen) {
                Some(self.class_modification()?)
            } else {
                None
            };
            let extends = ClassExtends {
                modification,
                span: self.span_from(first),
            };
            return self.long_body(name, Some(Box::new(extends)));
        }
        let name = self.ident()?;
        if self.eat(Sym::Equals) {
            if self.eat(Sym::KwDer) {
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
                return Some((
                    name,
                    ClassBody::Der {
                        base,
                        with_respect_to,
                        comment,
                    },
                ));
            }
            if self.eat(Sym::KwEnumeration) {
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
                return Some((
                    name,
                    ClassBody::Enumeration {
                        literals,
                        open,
                        comment,
                    },
                ));
            }
            let causality = self.causality();
            let base = self.name()?;
            let dims = if self.at(Sym::LBracket) {
                self.array_subscripts()?
            } else {
                Vec::new()
            };
            let modification = if self.at(Sym::LParen) {
                Some(self.class_modification()?)
            } else {
                None
            };
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
        let annotation = if self.at(Sym::KwAnnotation) {
            Some(self.annotation()?)
        } else {
            None
        };
        self.expect(Sym::Semi)?;
        Some(External {
            language,
            call,
            annotation,
            span: self.span_from(first),
        })
    }

    fn causality(&mut self) -> Option<Causality> {
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

    fn at_block_end(&self) -> bool {
        self.at(Sym::KwElseif)
            || self.at(Sym::KwElsewhen)
            || self.at(Sym::KwElse)
            || self.at(Sym::KwEnd)
    }

    fn at_element_start(&self) -> bool {
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

    fn element_list(&mut self, visibility: Visibility, out: &mut Vec<Element>) -> Option<()> {
        while self.at_element_start() {
            out.push(self.element(visibility)?);
            self.expect(Sym::Semi)?;
        }
        Some(())
    }

    fn element(&mut self, visibility: Visibility) -> Option<Element> {
        let first = self.pos;
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
                    span: Span::default(),
                }),
                comment: Comment::default(),
                span: Span::default(),
            }),
            constrainedby: None,
            span: Span::default(),
        };
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

    fn extends(&mut self) -> Option<Extends> {
        let first = self.pos;
        self.expect(Sym::KwExtends)?;
        let base = self.name()?;
        let modification = if self.at(Sym::LParen) {
            Some(self.class_modification()?)
        } else {
            None
        };
        let annotation = if self.at(Sym::KwAnnotation) {
            Some(self.annotation()?)
        } else {
            None
        };
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
        let modification = if self.at(Sym::LParen) {
            Some(self.class_modification()?)
        } else {
            None
        };
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

    fn modification(&mut self) -> Option<Modification> {
        let first = self.pos;
        let class_mod = if self.at(Sym::LParen) {
            Some(self.class_modification()?)
        } else {
            None
        };
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
    fn paren_list<T>(&mut self, mut item: impl FnMut(&mut Self) -> Option<T>) -> Option<Vec<T>> {
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

    fn class_modification(&mut self) -> Option<ClassModification> {
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
            let constrainedby = if self.at(Sym::KwConstrainedby) {
                Some(self.constraining()?)
            } else {
                None
            };
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
            let (partial, prefixes, kind) = self.class_prefixes()?;
            let (name, body) = self.class_specifier(true)?;
            return Some(RedeclaredElement::Class(Box::new(ClassDef {
                encapsulated: false,
                partial,
                prefixes,
                kind,
                name,
                body,
                span: self.span_from(first),
            })));
        }
        Some(RedeclaredElement::Component(self.component_clause(true)?))
    }

    // ------------------------------------------------------------ equations

    fn at_expression_start(&self) -> bool {
        match self.tok(self.pos) {
            None => false,
            Some(t) => {
                matches!(
                    t.kind,
                    TokenKind::Ident
                        | TokenKind::QuotedIdent
                        | TokenKind::Number
                        | TokenKind::String
                ) || matches!(
                    t.sym,
                    Sym::LParen
                        | Sym::LBracket
                        | Sym::LBrace
                        | Sym::Dot
                        | Sym::Minus
                        | Sym::Plus
                        | Sym::KwNot
                        | Sym::KwTrue
                        | Sym::KwFalse
                        | Sym::KwDer
                        | Sym::KwInitial
                        | Sym::KwPure
                        | Sym::KwEnd
                        | Sym::KwIf
                )
            }
        }
    }

    fn at_equation_start(&self) -> bool {
        self.at_expression_start()
            || matches!(self.sym(), Sym::KwFor | Sym::KwConnect | Sym::KwWhen)
    }

    fn at_statement_start(&self) -> bool {
        self.at_ident()
            || matches!(
                self.sym(),
                Sym::Dot
                    | Sym::LParen
                    | Sym::KwIf
                    | Sym::KwFor
                    | Sym::KwWhile
                    | Sym::KwWhen
                    | Sym::KwReturn
                    | Sym::KwBreak
            )
    }

    fn equation(&mut self) -> Option<Equation> {
        let first = self.pos;
        let kind = if self.at(Sym::KwIf) {
            self.pos += 1;
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.eq_block()?));
            let mut otherwise = Vec::new();
            while self.eat(Sym::KwElseif) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.eq_block()?));
            }
            if self.eat(Sym::KwElse) {
                otherwise = self.eq_block()?;
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwIf)?;
            EquationKind::If {
                branches,
                otherwise,
            }
        } else if self.eat(Sym::KwFor) {
            let indices = self.for_indices()?;
            self.expect(Sym::KwLoop)?;
            let body = self.eq_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwFor)?;
            EquationKind::For { indices, body }
        } else if self.eat(Sym::KwConnect) {
            self.expect(Sym::LParen)?;
            let a = self.component_reference()?;
            self.expect(Sym::Comma)?;
            let b = self.component_reference()?;
            self.expect(Sym::RParen)?;
            EquationKind::Connect { a, b }
        } else if self.eat(Sym::KwWhen) {
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.eq_block()?));
            while self.eat(Sym::KwElsewhen) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.eq_block()?));
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwWhen)?;
            EquationKind::When { branches }
        } else {
            let lhs = self.simple_expression()?;
            if self.at(Sym::Equals) || self.at(Sym::Assign) {
                let op = self.toks[self.pos];
                self.pos += 1;
                if self.txt(&op) == ":=" {
                    self.diags.push(shared::assign_in_equation(Span::new(
                        self.file,
                        op.start(),
                        op.end(),
                    )));
                }
                let rhs = self.expression()?;
                EquationKind::Simple { lhs, rhs }
            } else {
                EquationKind::Call(lhs)
            }
        };
        let comment = self.comment()?;
        Some(Equation {
            kind,
            comment,
            span: self.span_from(first),
        })
    }

    fn eq_block(&mut self) -> Option<Vec<Equation>> {
        let mut out = Vec::new();
        while !self.at_block_end() && self.at_equation_start() {
            out.push(self.equation()?);
            self.expect(Sym::Semi)?;
        }
        Some(out)
    }

    fn for_indices(&mut self) -> Option<Vec<ForIndex>> {
        let mut out = Vec::new();
        loop {
            let name = self.ident()?;
            let range = if self.eat(Sym::KwIn) {
                Some(self.expression()?)
            } else {
                None
            };
            out.push(ForIndex { name, range });
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        Some(out)
    }

    // ------------------------------------------------------------ statements

    fn st_block(&mut self) -> Option<Vec<Statement>> {
        let mut out = Vec::new();
        while !self.at_block_end() && self.at_statement_start() {
            out.push(self.statement()?);
            self.expect(Sym::Semi)?;
        }
        Some(out)
    }

    fn statement(&mut self) -> Option<Statement> {
        let first = self.pos;
        let kind = if self.eat(Sym::KwIf) {
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.st_block()?));
            let mut otherwise = Vec::new();
            while self.eat(Sym::KwElseif) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.st_block()?));
            }
            if self.eat(Sym::KwElse) {
                otherwise = self.st_block()?;
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwIf)?;
            StatementKind::If {
                branches,
                otherwise,
            }
        } else if self.eat(Sym::KwFor) {
            let indices = self.for_indices()?;
            self.expect(Sym::KwLoop)?;
            let body = self.st_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwFor)?;
            StatementKind::For { indices, body }
        } else if self.eat(Sym::KwWhile) {
            let condition = self.expression()?;
            self.expect(Sym::KwLoop)?;
            let body = self.st_block()?;
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwWhile)?;
            StatementKind::While { condition, body }
        } else if self.eat(Sym::KwWhen) {
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.st_block()?));
            while self.eat(Sym::KwElsewhen) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.st_block()?));
            }
            self.expect(Sym::KwEnd)?;
            self.expect(Sym::KwWhen)?;
            StatementKind::When { branches }
        } else if self.eat(Sym::KwReturn) {
            StatementKind::Return
        } else if self.eat(Sym::KwBreak) {
            StatementKind::Break
        } else if self.at(Sym::LParen) {
            self.pos += 1;
            let targets = self.output_list()?;
            self.expect(Sym::RParen)?;
            self.expect(Sym::Assign)?;
            let cref = self.component_reference()?;
            if !self.at(Sym::LParen) {
                return None;
            }
            // Arguments before the callee check: the order the pest builder reports in.
            let args = self.call_args()?;
            let func = self.callee(&cref);
            StatementKind::MultiAssign {
                targets,
                value: Expr {
                    kind: ExprKind::Call { func, args },
                    span: self.span_from(first),
                },
            }
        } else {
            let target = self.component_reference()?;
            if self.at(Sym::LParen) {
                let func = self.callee(&target);
                let args = self.call_args()?;
                StatementKind::Call(Expr {
                    kind: ExprKind::Call { func, args },
                    span: self.span_from(first),
                })
            } else if self.at(Sym::Equals) || self.at(Sym::Assign) {
                let op = self.toks[self.pos];
                self.pos += 1;
                if self.txt(&op) == "=" {
                    self.diags.push(shared::equals_in_algorithm(Span::new(
                        self.file,
                        op.start(),
                        op.end(),
                    )));
                }
                let value = self.expression()?;
                StatementKind::Assign { target, value }
            } else {
                self.diags
                    .push(shared::statement_without_effect(target.span));
                let span = target.span;
                StatementKind::Call(Expr {
                    kind: ExprKind::Ref(target),
                    span,
                })
            }
        };
        let comment = self.comment()?;
        Some(Statement {
            kind,
            comment,
            span: self.span_from(first),
        })
    }

    // ------------------------------------------------------------ expressions

    fn expression(&mut self) -> Option<Expr> {
        if self.at(Sym::KwIf) {
            let first = self.pos;
            self.pos += 1;
            let mut branches = Vec::new();
            let c = self.expression()?;
            self.expect(Sym::KwThen)?;
            branches.push((c, self.expression()?));
            while self.eat(Sym::KwElseif) {
                let c = self.expression()?;
                self.expect(Sym::KwThen)?;
                branches.push((c, self.expression()?));
            }
            self.expect(Sym::KwElse)?;
            let otherwise = self.expression()?;
            return Some(Expr {
                kind: ExprKind::If {
                    branches,
                    otherwise: Box::new(otherwise),
                },
                span: self.span_from(first),
            });
        }
        self.simple_expression()
    }

    fn simple_expression(&mut self) -> Option<Expr> {
        let first = self.pos;
        let start = self.operand_expr()?;
        if !self.at(Sym::Colon) {
            return Some(start);
        }
        self.pos += 1;
        let second = self.operand_expr()?;
        if !self.at(Sym::Colon) {
            return Some(Expr {
                kind: ExprKind::Range {
                    start: Box::new(start),
                    step: None,
                    stop: Box::new(second),
                },
                span: self.span_from(first),
            });
        }
        self.pos += 1;
        let third = self.operand_expr()?;
        Some(Expr {
            kind: ExprKind::Range {
                start: Box::new(start),
                step: Some(Box::new(second)),
                stop: Box::new(third),
            },
            span: self.span_from(first),
        })
    }

    /// The binary operator at the cursor and its binding power (pest's Pratt levels).
    fn infix(&self) -> Option<(BinaryOp, u32)> {
        Some(match self.sym() {
            Sym::KwOr => (BinaryOp::Or, 10),
            Sym::KwAnd => (BinaryOp::And, 20),
            Sym::Lt => (BinaryOp::Lt, 40),
            Sym::Le => (BinaryOp::Le, 40),
            Sym::Gt => (BinaryOp::Gt, 40),
            Sym::Ge => (BinaryOp::Ge, 40),
            Sym::EqEq => (BinaryOp::Eq, 40),
            Sym::Ne => (BinaryOp::Ne, 40),
            Sym::Plus => (BinaryOp::Add, 50),
            Sym::Minus => (BinaryOp::Sub, 50),
            Sym::DotPlus => (BinaryOp::ElemAdd, 50),
            Sym::DotMinus => (BinaryOp::ElemSub, 50),
            Sym::Star => (BinaryOp::Mul, 70),
            Sym::Slash => (BinaryOp::Div, 70),
            Sym::DotStar => (BinaryOp::ElemMul, 70),
            Sym::DotSlash => (BinaryOp::ElemDiv, 70),
            Sym::Caret => (BinaryOp::Pow, 80),
            Sym::DotCaret => (BinaryOp::ElemPow, 80),
            _ => return None,
        })
    }

    fn operand_expr(&mut self) -> Option<Expr> {
        self.pratt(0)
    }

    /// Precedence climbing with the same levels and associativity as the pest Pratt
    /// parser in `build.rs` (so both build identical trees).
    fn pratt(&mut self, min_bp: u32) -> Option<Expr> {
        let mut lhs = self.prefix()?;
        while let Some((op, bp)) = self.infix() {
            if bp <= min_bp {
                break;
            }
            self.pos += 1;
            let right_assoc = matches!(op, BinaryOp::Pow | BinaryOp::ElemPow);
            let rhs = self.pratt(if right_assoc { bp - 1 } else { bp })?;
            let span = lhs.span.to(rhs.span);
            lhs = Expr {
                kind: ExprKind::Binary {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            };
        }
        Some(lhs)
    }

    fn prefix(&mut self) -> Option<Expr> {
        let t = *self.tok(self.pos)?;
        let op = match t.sym {
            Sym::KwNot => Some((UnaryOp::Not, 30)),
            Sym::Minus => Some((UnaryOp::Neg, 60)),
            Sym::Plus => Some((UnaryOp::Plus, 60)),
            _ => None,
        };
        match op {
            Some((op, bp)) => {
                self.pos += 1;
                // As pest's Pratt parser: the operand binds one level below the operator.
                let operand = self.pratt(bp - 1)?;
                let span = Span::new(self.file, t.start(), t.end()).to(operand.span);
                Some(Expr {
                    kind: ExprKind::Unary {
                        op,
                        operand: Box::new(operand),
                    },
                    span,
                })
            }
            None => self.primary(),
        }
    }

    fn primary(&mut self) -> Option<Expr> {
        let first = self.pos;
        let t = *self.tok(self.pos)?;
        let kind = match t.kind {
            TokenKind::Number => {
                self.pos += 1;
                let span = self.span_from(first);
                shared::number(self.txt(&t), span, self.diags)
            }
            TokenKind::String => {
                self.pos += 1;
                ExprKind::String(self.string_value(&t))
            }
            TokenKind::Keyword => match self.txt(&t) {
                // Rare here; text comparison is fine.
                "true" => {
                    self.pos += 1;
                    ExprKind::Bool(true)
                }
                "false" => {
                    self.pos += 1;
                    ExprKind::Bool(false)
                }
                "end" => {
                    self.pos += 1;
                    ExprKind::End
                }
                w @ ("der" | "initial" | "pure") => {
                    if !self.sym_at(self.pos + 1, Sym::LParen) {
                        return None;
                    }
                    self.pos += 1;
                    let args = self.call_args()?;
                    let span = self.span_from(first);
                    ExprKind::Call {
                        func: Name {
                            global: false,
                            parts: vec![Ident {
                                text: SmolStr::new(w),
                                span: Span::new(self.file, t.start(), t.end()),
                            }],
                            span,
                        },
                        args,
                    }
                }
                _ => return None,
            },
            TokenKind::Ident | TokenKind::QuotedIdent => self.ref_or_call()?,
            TokenKind::Punct => match t.sym {
                Sym::Dot => self.ref_or_call()?,
                Sym::LParen => {
                    self.pos += 1;
                    let mut items = self.output_list()?;
                    self.expect(Sym::RParen)?;
                    let span = self.span_from(first);
                    if items.len() == 1 && items[0].is_some() {
                        let mut e = items.pop().flatten()?;
                        e.span = span;
                        return Some(e);
                    }
                    ExprKind::Tuple(items)
                }
                Sym::LBrace => {
                    self.pos += 1;
                    let head = self.expression()?;
                    let kind = if self.at(Sym::KwFor) {
                        self.pos += 1;
                        let indices = self.for_indices()?;
                        ExprKind::Comprehension {
                            body: Box::new(head),
                            indices,
                        }
                    } else {
                        let mut items = vec![head];
                        while self.eat(Sym::Comma) {
                            items.push(self.expression()?);
                        }
                        ExprKind::Array(items)
                    };
                    self.expect(Sym::RBrace)?;
                    kind
                }
                Sym::LBracket => {
                    self.pos += 1;
                    let mut rows = Vec::new();
                    loop {
                        let mut row = vec![self.expression()?];
                        while self.eat(Sym::Comma) {
                            row.push(self.expression()?);
                        }
                        rows.push(row);
                        if !self.eat(Sym::Semi) {
                            break;
                        }
                    }
                    self.expect(Sym::RBracket)?;
                    ExprKind::Matrix(rows)
                }
                _ => return None,
            },
        };
        Some(Expr {
            kind,
            span: self.span_from(first),
        })
    }

    fn ref_or_call(&mut self) -> Option<ExprKind> {
        let cref = self.component_reference()?;
        if self.at(Sym::LParen) {
            let func = self.callee(&cref);
            let args = self.call_args()?;
            Some(ExprKind::Call { func, args })
        } else {
            Some(ExprKind::Ref(cref))
        }
    }

    fn callee(&mut self, cref: &ComponentRef) -> Name {
        shared::callee(cref, self.diags)
    }

    /// `expression? ("," expression?)*` as in `(a, , b)`.
    fn output_list(&mut self) -> Option<Vec<Option<Expr>>> {
        let mut items = vec![None];
        loop {
            if self.at_expression_start() {
                let e = self.expression()?;
                if let Some(last) = items.last_mut() {
                    *last = Some(e);
                }
            }
            if self.eat(Sym::Comma) {
                items.push(None);
            } else {
                break;
            }
        }
        if items.len() == 1 && items[0].is_none() {
            items.clear();
        }
        Some(items)
    }

    fn component_reference(&mut self) -> Option<ComponentRef> {
        let first = self.pos;
        let global = self.eat(Sym::Dot);
        let mut parts = Vec::new();
        loop {
            let name = self.ident()?;
            let subscripts = if self.at(Sym::LBracket) {
                self.array_subscripts()?
            } else {
                Vec::new()
            };
            parts.push(RefPart { name, subscripts });
            let more = self.at(Sym::Dot)
                && self
                    .tok(self.pos + 1)
                    .is_some_and(|t| matches!(t.kind, TokenKind::Ident | TokenKind::QuotedIdent));
            if !more {
                break;
            }
            self.pos += 1;
        }
        Some(ComponentRef {
            global,
            parts,
            span: self.span_from(first),
        })
    }

    fn array_subscripts(&mut self) -> Option<Vec<Subscript>> {
        self.expect(Sym::LBracket)?;
        let mut out = Vec::new();
        loop {
            if self.at(Sym::Colon) {
                let t = self.toks[self.pos];
                self.pos += 1;
                out.push(Subscript::Colon(Span::new(self.file, t.start(), t.end())));
            } else {
                out.push(Subscript::Expr(self.expression()?));
            }
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        self.expect(Sym::RBracket)?;
        Some(out)
    }

    fn call_args(&mut self) -> Option<Box<CallArgs>> {
        let first = self.pos;
        self.expect(Sym::LParen)?;
        let mut args = CallArgs::default();
        if !self.at(Sym::RParen) {
            loop {
                if self.at_ident() && self.sym_at(self.pos + 1, Sym::Equals) {
                    args.named = self.named_args()?;
                    break;
                }
                args.positional.push(self.function_argument()?);
                if self.at(Sym::KwFor) {
                    self.pos += 1;
                    args.iterators = self.for_indices()?;
                    break;
                }
                if !self.eat(Sym::Comma) {
                    break;
                }
            }
        }
        self.expect(Sym::RParen)?;
        args.span = self.span_from(first);
        Some(Box::new(args))
    }

    fn named_args(&mut self) -> Option<Vec<NamedArg>> {
        let mut out = Vec::new();
        loop {
            let name = self.ident()?;
            self.expect(Sym::Equals)?;
            let value = self.function_argument()?;
            out.push(NamedArg { name, value });
            if !self.eat(Sym::Comma) {
                break;
            }
        }
        Some(out)
    }

    fn function_argument(&mut self) -> Option<Expr> {
        if !self.at(Sym::KwFunction) {
            return self.expression();
        }
        let first = self.pos;
        self.pos += 1;
        let func = self.name()?;
        self.expect(Sym::LParen)?;
        let args = if self.at(Sym::RParen) {
            Vec::new()
        } else {
            self.named_args()?
        };
        self.expect(Sym::RParen)?;
        Some(Expr {
            kind: ExprKind::PartialApplication {
                func: Box::new(func),
                args,
            },
            span: self.span_from(first),
        })
    }
}
