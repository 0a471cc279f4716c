//! Elements of a composition: imports, extends, components, modifications, redeclarations,
//! annotations and comments.

use super::{causality_of, class_prefixes, kids, unescape, Builder};
use crate::ast::*;
use crate::grammar::Rule;
use pest::iterators::Pair;
use smol_str::SmolStr;

impl Builder<'_> {
    pub(crate) fn element_list(
        &mut self,
        pair: Pair<'_, Rule>,
        vis: Visibility,
        out: &mut Vec<Element>,
    ) {
        for p in kids(pair) {
            if let Some(e) = self.element(p, vis) {
                out.push(e);
            }
        }
    }

    pub(crate) fn element(
        &mut self,
        pair: Pair<'_, Rule>,
        visibility: Visibility,
    ) -> Option<Element> {
        let span = self.span(&pair);
        let inner = pair.into_inner().next()?;
        let mut e = Element::unfilled(visibility, span);
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
            kind: kind.unwrap_or(ImportKind::Qualified(Name::empty(span))),
            comment,
            span,
        }
    }

    pub(crate) fn extends(&mut self, pair: Pair<'_, Rule>) -> Extends {
        let span = self.span(&pair);
        let mut base = Name::empty(span);
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
        let base = it.next().map(|n| self.name(n)).unwrap_or(Name::empty(span));
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
        let mut clause = ComponentClause::empty(span);
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

    pub(crate) fn modification(&mut self, pair: Pair<'_, Rule>) -> Modification {
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
                name: name.unwrap_or(Name::empty(span)),
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
            element: element.unwrap_or(RedeclaredElement::Component(ComponentClause::empty(span))),
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
            let head = (partial, prefixes, kind);
            return RedeclaredElement::Class(Box::new(ClassDef::new(
                false,
                head,
                (name, body),
                span,
            )));
        }
        RedeclaredElement::Component(self.component_clause(pair))
    }

    pub(crate) fn annotation(&mut self, pair: Pair<'_, Rule>) -> Option<ClassModification> {
        kids(pair).next().map(|m| self.class_modification(m))
    }

    pub(crate) fn description(&mut self, pair: Pair<'_, Rule>) -> Option<String> {
        let mut out: Option<String> = None;
        for s in pair.into_inner() {
            let v = self.string_value(&s);
            out.get_or_insert_with(String::new).push_str(&v);
        }
        out
    }

    pub(crate) fn comment(&mut self, pair: Pair<'_, Rule>) -> Comment {
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

    pub(crate) fn string_value(&mut self, pair: &Pair<'_, Rule>) -> String {
        let raw = pair.as_str();
        let inner = &raw[1..raw.len().saturating_sub(1).max(1)];
        unescape(inner)
    }
}
