//! Class restrictions (spec 4.7) and type prefixes: what a package, type, record,
//! connector, function and block may declare (`E2027`), where `input`, `output`,
//! `flow`, `inner` and `outer` may stand (`E2028`), and `flow`/`stream` only on Real
//! types (`E2021`).

use super::elements::{
    all_components, base_of, class_kind, component_class, component_type, type_has_causality, Base,
    ComponentInfo,
};
use super::Ctx;
use crate::error::FlatError;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

/// One component clause's declaration as written in the class checked.
struct Declared<'a> {
    element: &'a Element,
    clause: &'a ComponentClause,
    decl: &'a ComponentDecl,
}

fn declared(composition: &Composition) -> Vec<Declared<'_>> {
    composition
        .elements
        .iter()
        .filter_map(|e| match &e.kind {
            ElementKind::Component(cc) => Some((e, cc)),
            _ => None,
        })
        .flat_map(|(element, clause)| {
            clause.components.iter().map(move |decl| Declared {
                element,
                clause,
                decl,
            })
        })
        .collect()
}

fn info_of(owner: ClassId, d: &Declared<'_>) -> ComponentInfo {
    ComponentInfo::new(owner, d.element, d.clause, d.decl)
}

impl Ctx<'_, '_> {
    /// `E2027`/`E2028`: the declarations the kind of class `id` does not allow.
    pub(super) fn restrictions(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let kind = def.kind.keyword();
        if def.kind == ClassKind::Function {
            self.function_sections(composition);
        }
        for d in declared(composition) {
            let name = &d.decl.name;
            let info = info_of(id, &d);
            match def.kind {
                ClassKind::Package | ClassKind::Operator
                    if d.clause.prefix.variability != Some(Variability::Constant) =>
                {
                    self.report(FlatError::PackageComponent {
                        kind,
                        name: name.text.to_string(),
                        span: name.span,
                    });
                }
                ClassKind::Type => self.report(FlatError::TypeComponent {
                    name: name.text.to_string(),
                    span: name.span,
                }),
                ClassKind::Record => self.record_component(&d, &info),
                ClassKind::Connector if d.element.visibility == Visibility::Protected => {
                    self.report(FlatError::ProtectedInterfaceElement {
                        kind: "connector",
                        name: name.text.to_string(),
                        span: name.span,
                    });
                }
                ClassKind::Function => self.function_component(&d, &info),
                ClassKind::Model | ClassKind::Block | ClassKind::Class
                    if d.clause.prefix.connection.is_some() =>
                {
                    let word = match d.clause.prefix.connection {
                        Some(Connection::Stream) => "stream",
                        _ => "flow",
                    };
                    self.report(FlatError::FlowOutsideConnector {
                        word,
                        kind,
                        name: name.text.to_string(),
                        span: name.span,
                    });
                }
                ClassKind::Block => self.block_connector(&d, &info),
                _ => {}
            }
        }
    }

    fn record_component(&mut self, d: &Declared<'_>, info: &ComponentInfo) {
        let name = &d.decl.name;
        let p = d.clause.prefix;
        let bad_prefix = match (p.causality, p.connection) {
            (Some(Causality::Input), _) => Some("input"),
            (Some(Causality::Output), _) => Some("output"),
            (_, Some(Connection::Flow)) => Some("flow"),
            (_, Some(Connection::Stream)) => Some("stream"),
            _ if d.element.inner => Some("inner"),
            _ if d.element.outer => Some("outer"),
            _ => None,
        };
        if let Some(prefix) = bad_prefix {
            self.report(FlatError::ElementPrefix {
                kind: "record",
                prefix,
                name: name.text.to_string(),
                section: "4.7",
                span: name.span,
            });
        }
        if d.element.visibility == Visibility::Protected {
            self.report(FlatError::ProtectedInterfaceElement {
                kind: "record",
                name: name.text.to_string(),
                span: name.span,
            });
        }
        self.no_model_components(info, "record", name);
    }

    /// A record's or function's component of a model, block or connector class.
    fn no_model_components(&mut self, info: &ComponentInfo, kind: &'static str, name: &Ident) {
        let Some(c) = component_class(self.tree, info) else {
            return;
        };
        let (ck, _) = class_kind(self.tree, c);
        if matches!(
            ck,
            ClassKind::Model | ClassKind::Block | ClassKind::Connector
        ) {
            self.report(FlatError::ModelComponentIn {
                kind,
                class_kind: ck.keyword(),
                class: self.tree.full_name(c),
                name: name.text.to_string(),
                span: name.span,
                declared: self.tree.get(c).def.name.span,
            });
        }
    }

    fn function_component(&mut self, d: &Declared<'_>, info: &ComponentInfo) {
        let name = &d.decl.name;
        let p = d.clause.prefix;
        let protected = d.element.visibility == Visibility::Protected;
        let bad_prefix = match p.connection {
            Some(Connection::Flow) => Some("flow"),
            Some(Connection::Stream) => Some("stream"),
            None if d.element.inner => Some("inner"),
            None if d.element.outer => Some("outer"),
            None => None,
        };
        if let Some(prefix) = bad_prefix {
            self.report(FlatError::ElementPrefix {
                kind: "function",
                prefix,
                name: name.text.to_string(),
                section: "12.2",
                span: name.span,
            });
        }
        match (protected, p.causality) {
            (true, Some(c)) => {
                let word = if c == Causality::Input {
                    "input"
                } else {
                    "output"
                };
                self.report(FlatError::ProtectedFunctionInterface {
                    word,
                    name: name.text.to_string(),
                    span: name.span,
                });
            }
            (false, None) if p.variability.is_none() => {
                self.report(FlatError::PublicFunctionLocal {
                    name: name.text.to_string(),
                    span: name.span,
                });
            }
            _ => {}
        }
        self.no_model_components(info, "function", name);
    }

    /// `E2027`: a block's public connector with variables of no causality.
    fn block_connector(&mut self, d: &Declared<'_>, info: &ComponentInfo) {
        if d.element.visibility == Visibility::Protected || d.clause.prefix.causality.is_some() {
            return;
        }
        let Some(c) = component_class(self.tree, info) else {
            return;
        };
        if class_kind(self.tree, c) != (ClassKind::Connector, false)
            || type_has_causality(self.tree, c)
        {
            return;
        }
        let acausal = all_components(self.tree, c).into_iter().find(|v| {
            v.prefix.causality.is_none()
                && v.prefix.variability.is_none()
                && component_type(self.tree, v)
                    .and_then(|t| base_of(self.tree, t))
                    .is_some_and(|b| b != Base::Other)
        });
        if let Some(v) = acausal {
            let name = &d.decl.name;
            self.report(FlatError::AcausalBlockConnector {
                name: name.text.to_string(),
                span: name.span,
                variable: v.name_span,
            });
        }
    }

    /// `E2021`: `flow` or `stream` on a component whose type is not Real.
    pub(super) fn prefixes(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        for d in declared(composition) {
            let Some(conn) = d.clause.prefix.connection else {
                continue;
            };
            let info = info_of(id, &d);
            let Some(t) = component_type(self.tree, &info) else {
                continue;
            };
            let base = base_of(self.tree, t);
            if !matches!(
                base,
                Some(Base::Integer | Base::Boolean | Base::String | Base::Enumeration)
            ) {
                continue;
            }
            let word = if conn == Connection::Flow {
                "flow"
            } else {
                "stream"
            };
            self.out.push(
                FlatError::FlowNotReal {
                    word,
                    name: d.decl.name.text.to_string(),
                    base: base.map_or("?", Base::name),
                    span: d.clause.type_name.span,
                }
                .into(),
            );
        }
    }

    /// `E2027`: a function has at most one algorithm section, or an external clause
    /// instead (spec 12.2), and no initial algorithm.
    fn function_sections(&mut self, composition: &Composition) {
        let algorithms: Vec<&AlgorithmSection> = composition
            .sections
            .iter()
            .filter_map(|s| match s {
                Section::Algorithm(a) => Some(a),
                Section::Equation(_) => None,
            })
            .collect();
        if let Some(a) = algorithms.iter().find(|a| a.initial) {
            self.report(FlatError::InitialAlgorithmInFunction { span: a.span });
        } else if algorithms.len() > 1 {
            self.report(FlatError::SecondAlgorithm {
                span: algorithms[1].span,
                first: algorithms[0].span,
            });
        } else if let (Some(a), Some(x)) = (algorithms.first(), &composition.external) {
            self.report(FlatError::AlgorithmAndExternal {
                span: x.span,
                algorithm: a.span,
            });
        }
    }
}
