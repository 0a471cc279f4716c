//! Connector classes as declared: a connector with stream variables has exactly one
//! scalar flow variable (`E2034`, spec 15.1), a connector with flow variables has as
//! many scalar flow variables as potential ones (`E2037`, spec 9.3.1), and a component
//! of a connector type is neither a parameter nor a constant (`E2028`, spec 9.3).

use super::elements::{
    all_components, base_of, class_kind, component_class, component_type, is_array, type_is_array,
    Base, ComponentInfo,
};
use super::Ctx;
use crate::error::FlatError;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

impl Ctx<'_, '_> {
    /// `E2034` for a non-partial connector class with stream variables and not exactly
    /// one scalar flow variable (inherited elements count).
    pub(super) fn stream_connector(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        if !concrete_connector(&def) {
            return;
        }
        let components = all_components(self.tree, id);
        let Some(stream) = components
            .iter()
            .find(|c| c.prefix.connection == Some(Connection::Stream))
        else {
            return;
        };
        let flows: Vec<_> = components
            .iter()
            .filter(|c| c.prefix.connection == Some(Connection::Flow))
            .collect();
        let problem = match flows.as_slice() {
            [] => "no flow variable".to_owned(),
            [one] if is_array(self.tree, one) => "an array of flow variables".to_owned(),
            [_] => return,
            many => format!("{} flow variables", many.len()),
        };
        self.out.push(
            FlatError::StreamFlowCount {
                name: def.name.text.to_string(),
                problem,
                span: def.name.span,
                stream: stream.name_span,
                flows: flows.iter().map(|f| f.name_span).collect(),
            }
            .into(),
        );
    }

    /// The number of scalars of a component of a predefined type with literal
    /// dimensions; None for anything else (a record, an overdetermined type, a size
    /// given by a parameter).
    fn literal_scalars(&mut self, c: &ComponentInfo) -> Option<i64> {
        let t = component_type(self.tree, c)?;
        if matches!(base_of(self.tree, t), None | Some(Base::Other)) || type_is_array(self.tree, t)
        {
            return None;
        }
        c.dims.iter().try_fold(1i64, |n, s| match s {
            Subscript::Expr(Expr {
                kind: ExprKind::Integer(k),
                ..
            }) => Some(n * k),
            _ => None,
        })
    }

    /// `E2037` for a non-partial, non-expandable connector class with flow variables
    /// whose scalar flow and potential counts differ (counted when every such element
    /// is of a predefined type with literal sizes; a potential variable neither
    /// `parameter`, `constant`, `input`, `output`, `flow` nor `stream`).
    pub(super) fn connector_balance(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        if !concrete_connector(&def) {
            return;
        }
        let (mut flows, mut potentials, mut stream) = (0i64, 0i64, false);
        for c in all_components(self.tree, id) {
            // Reported already: protected elements of a connector (`E2027`), flow on a
            // non-Real type (`E2021`).
            if c.protected {
                continue;
            }
            let counted = match (
                c.prefix.connection,
                c.prefix.variability,
                c.prefix.causality,
            ) {
                (Some(Connection::Flow), ..) => {
                    let real = component_type(self.tree, &c)
                        .is_some_and(|t| base_of(self.tree, t) == Some(Base::Real));
                    if !real {
                        return;
                    }
                    &mut flows
                }
                (Some(Connection::Stream), ..) => {
                    stream = true;
                    continue;
                }
                (None, Some(Variability::Parameter | Variability::Constant), _) => continue,
                (None, _, Some(_)) => continue,
                (None, _, None) => &mut potentials,
            };
            let Some(n) = self.literal_scalars(&c) else {
                return;
            };
            *counted += n;
        }
        // A stream connector without exactly one flow is `E2034`.
        if flows == 0 || flows == potentials || (stream && flows != 1) {
            return;
        }
        self.out.push(
            FlatError::UnbalancedConnector {
                name: def.name.text.to_string(),
                flows,
                potentials,
                span: def.name.span,
            }
            .into(),
        );
    }

    /// `E2028` for a component of a connector type declared `parameter` or `constant`.
    pub(super) fn constant_connectors(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        for (e, cc) in def.component_clauses() {
            let word = match cc.prefix.variability {
                Some(Variability::Parameter) => "parameter",
                Some(Variability::Constant) => "constant",
                _ => continue,
            };
            for d in &cc.components {
                let info = super::elements::ComponentInfo::new(id, e, cc, d);
                let Some(c) = component_class(self.tree, &info) else {
                    continue;
                };
                if class_kind(self.tree, c).0 != ClassKind::Connector {
                    continue;
                }
                self.out.push(
                    FlatError::ConstantConnector {
                        word,
                        name: d.name.text.to_string(),
                        span: d.name.span,
                        connector: self.tree.get(c).def.name.span,
                    }
                    .into(),
                );
            }
        }
    }
}

/// A connector class whose own elements are its interface: not partial, not
/// expandable, written in the long form.
fn concrete_connector(def: &ClassDef) -> bool {
    def.kind == ClassKind::Connector
        && !def.partial
        && !def.prefixes.expandable
        && matches!(def.body, ClassBody::Long { .. })
}
