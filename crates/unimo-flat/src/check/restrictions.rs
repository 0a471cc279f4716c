//! Class restrictions (spec 4.7) and type prefixes: what a package, type, record,
//! connector, function and block may declare (`E2027`), where `input`, `output`,
//! `flow`, `inner` and `outer` may stand (`E2028`), and `flow`/`stream` only on Real
//! types (`E2021`).

use super::elements::{
    all_components, base_of, class_kind, component_class, component_type, type_has_causality, Base,
    ComponentInfo,
};
use super::Ctx;
use crate::error::FlatCode;
use crate::tree::ClassId;
use unimo_source::{Diagnostic, Span};
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

fn restriction(message: String, span: Span, label: &str, section: &str) -> Diagnostic {
    Diagnostic::error(FlatCode::ClassRestriction, message)
        .at(span, label.to_owned())
        .with_note(format!("Modelica specification, section {section}"))
}

fn prefix_error(message: String, span: Span, label: &str, section: &str) -> Diagnostic {
    Diagnostic::error(FlatCode::MisplacedPrefix, message)
        .at(span, label.to_owned())
        .with_note(format!("Modelica specification, section {section}"))
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
                    self.out.push(restriction(
                        format!(
                            "a {kind} may declare only classes and constants, not `{}`",
                            name.text
                        ),
                        name.span,
                        "not a constant",
                        "4.7",
                    ));
                }
                ClassKind::Type => self.out.push(restriction(
                    format!("a type may not declare components: `{}`", name.text),
                    name.span,
                    "a component in a type",
                    "4.7",
                )),
                ClassKind::Record => self.record_component(&d, &info),
                ClassKind::Connector if d.element.visibility == Visibility::Protected => {
                    self.out.push(restriction(
                        format!(
                            "a connector has only public elements: `{}` is protected",
                            name.text
                        ),
                        name.span,
                        "protected element of a connector",
                        "4.7",
                    ));
                }
                ClassKind::Function => self.function_component(&d, &info),
                ClassKind::Model | ClassKind::Block | ClassKind::Class
                    if d.clause.prefix.connection.is_some() =>
                {
                    let word = match d.clause.prefix.connection {
                        Some(Connection::Stream) => "stream",
                        _ => "flow",
                    };
                    self.out.push(prefix_error(
                        format!("`{word}` outside a connector: `{}`", name.text),
                        name.span,
                        &format!("`{word}` in a {kind}"),
                        "4.4.2.2",
                    ));
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
            self.out.push(prefix_error(
                format!(
                    "a record's element `{}` may not be declared `{prefix}`",
                    name.text
                ),
                name.span,
                &format!("`{prefix}` in a record"),
                "4.7",
            ));
        }
        if d.element.visibility == Visibility::Protected {
            self.out.push(restriction(
                format!(
                    "a record has only public elements: `{}` is protected",
                    name.text
                ),
                name.span,
                "protected element of a record",
                "4.7",
            ));
        }
        self.no_model_components(info, "record", name);
    }

    /// A record's or function's component of a model, block or connector class.
    fn no_model_components(&mut self, info: &ComponentInfo, kind: &str, name: &Ident) {
        let Some(c) = component_class(self.tree, info) else {
            return;
        };
        let (ck, _) = class_kind(self.tree, c);
        if matches!(
            ck,
            ClassKind::Model | ClassKind::Block | ClassKind::Connector
        ) {
            self.out.push(
                restriction(
                    format!(
                        "a {kind} may not have a component of the {} `{}`: `{}`",
                        ck.keyword(),
                        self.tree.full_name(c),
                        name.text
                    ),
                    name.span,
                    &format!("a {} in a {kind}", ck.keyword()),
                    "4.7",
                )
                .with_label(self.tree.get(c).def.name.span, "declared here"),
            );
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
            self.out.push(prefix_error(
                format!(
                    "a function's element `{}` may not be declared `{prefix}`",
                    name.text
                ),
                name.span,
                &format!("`{prefix}` in a function"),
                "12.2",
            ));
        }
        match (protected, p.causality) {
            (true, Some(c)) => {
                let word = if c == Causality::Input {
                    "input"
                } else {
                    "output"
                };
                self.out.push(prefix_error(
                    format!(
                        "a function's protected element `{}` may not be an {word}",
                        name.text
                    ),
                    name.span,
                    &format!("protected {word}"),
                    "12.2",
                ));
            }
            (false, None) if p.variability.is_none() => {
                self.out.push(
                    prefix_error(
                        format!(
                            "a function's public element `{}` must be an input or an output",
                            name.text
                        ),
                        name.span,
                        "neither input nor output",
                        "12.2",
                    )
                    .with_help("declare local variables of a function under `protected`"),
                );
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
            self.out.push(
                restriction(
                    format!(
                        "the public connector `{}` of a block has a variable that is neither input nor output",
                        name.text
                    ),
                    name.span,
                    "connector of a block",
                    "4.7",
                )
                .with_label(v.name_span, "neither input nor output")
                .with_help("use a model for physical connectors, or give the connector's variables `input`/`output`"),
            );
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
                Diagnostic::error(
                    FlatCode::FlowNotReal,
                    format!(
                        "`{word}` on `{}`, of type {}: {word} variables are Real",
                        d.decl.name.text,
                        base.map_or("?", Base::name)
                    ),
                )
                .at(d.clause.type_name.span, "not a Real type")
                .with_note("Modelica specification, section 9.3: flow and stream variables are subtypes of Real"),
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
            self.out.push(restriction(
                "a function may not have an initial algorithm".to_owned(),
                a.span,
                "initial algorithm in a function",
                "12.2",
            ));
        } else if algorithms.len() > 1 {
            self.out.push(
                restriction(
                    "a function has at most one algorithm section".to_owned(),
                    algorithms[1].span,
                    "second algorithm section",
                    "12.2",
                )
                .with_label(algorithms[0].span, "first algorithm section"),
            );
        } else if let (Some(a), Some(x)) = (algorithms.first(), &composition.external) {
            self.out.push(
                restriction(
                    "a function has an algorithm section or an external clause, not both"
                        .to_owned(),
                    x.span,
                    "external clause",
                    "12.2",
                )
                .with_label(a.span, "algorithm section"),
            );
        }
    }
}
