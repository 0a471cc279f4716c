//! Connections as written (spec 9.1): both sides of a `connect` are connectors
//! (`E2030`), a connector is not connected to itself (`E2031`), and the parameters and
//! constants of two connected connectors match (`E2006`, spec 9.3).

use super::elements::{
    all_components, class_kind, component_class, component_type, find_component,
};
use super::walk::for_each_equation;
use super::Ctx;
use crate::error::FlatError;
use crate::lookup::Found;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

/// Whether two references are the same text (names and subscripts, spans aside).
fn same_reference(a: &ComponentRef, b: &ComponentRef) -> bool {
    a.global == b.global && unimo_syntax::print::cref(a) == unimo_syntax::print::cref(b)
}

impl Ctx<'_, '_> {
    /// `E2030`/`E2031` for the `connect` equations of class `id`.
    pub(super) fn connections(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let mut connects: Vec<(ComponentRef, ComponentRef, unimo_source::Span)> = Vec::new();
        for s in &composition.sections {
            let Section::Equation(es) = s else { continue };
            for_each_equation(&es.equations, &mut |eq| {
                if let EquationKind::Connect { a, b } = &eq.kind {
                    connects.push((a.clone(), b.clone(), eq.span));
                }
            });
        }
        for (a, b, span) in &connects {
            if same_reference(a, b) {
                self.out.push(
                    FlatError::ConnectToItself {
                        name: unimo_syntax::print::cref(a),
                        span: *span,
                    }
                    .into(),
                );
                continue;
            }
            for side in [a, b] {
                self.connector_side(id, side);
            }
            self.connected_variabilities(id, a, b, *span);
        }
    }

    /// The class of the component `r` denotes from class `id`, when it resolves.
    fn referenced_class(&mut self, id: ClassId, r: &ComponentRef) -> Option<ClassId> {
        let mut cur = find_component(self.tree, id, &r.parts[0].name.text)?;
        for p in &r.parts[1..] {
            let c = component_class(self.tree, &cur)?;
            cur = find_component(self.tree, c, &p.name.text)?;
        }
        component_class(self.tree, &cur)
    }

    /// `E2006` when `connect(a, b)` matches a parameter or constant of one connector
    /// with an element of the other of another variability (spec 9.3: parameters
    /// connect to parameters only, constants to constants).
    fn connected_variabilities(
        &mut self,
        id: ClassId,
        a: &ComponentRef,
        b: &ComponentRef,
        span: unimo_source::Span,
    ) {
        let (Some(ca), Some(cb)) = (self.referenced_class(id, a), self.referenced_class(id, b))
        else {
            return;
        };
        if ca == cb
            || class_kind(self.tree, ca) != (ClassKind::Connector, false)
            || class_kind(self.tree, cb) != (ClassKind::Connector, false)
        {
            return;
        }
        let fixed = |v: Option<Variability>| match v {
            Some(Variability::Parameter) => "a parameter",
            Some(Variability::Constant) => "a constant",
            _ => "a variable",
        };
        for x in all_components(self.tree, ca) {
            let name = x.name.clone();
            let Some(y) = find_component(self.tree, cb, &name) else {
                continue;
            };
            let (vx, vy) = (fixed(x.prefix.variability), fixed(y.prefix.variability));
            if vx == vy {
                continue;
            }
            self.out.push(
                FlatError::VariabilitiesDiffer {
                    a: unimo_syntax::print::cref(a),
                    b: unimo_syntax::print::cref(b),
                    member: name.to_string(),
                    kind_a: vx,
                    kind_b: vy,
                    span,
                    declared_a: x.name_span,
                    declared_b: y.name_span,
                }
                .into(),
            );
            return;
        }
    }

    /// `E2030` when `r` denotes a component that is not a connector.
    fn connector_side(&mut self, id: ClassId, r: &ComponentRef) {
        let Some(mut cur) = find_component(self.tree, id, &r.parts[0].name.text) else {
            return;
        };
        for p in &r.parts[1..] {
            let Some(Found::Class(c)) = component_type(self.tree, &cur) else {
                return;
            };
            // Members of an expandable connector need not be declared.
            if class_kind(self.tree, c) == (ClassKind::Connector, true) {
                return;
            }
            let Some(next) = find_component(self.tree, c, &p.name.text) else {
                return;
            };
            cur = next;
        }
        let what = match component_type(self.tree, &cur) {
            Some(Found::Builtin(b)) => format!("a variable of type {b}"),
            Some(Found::Class(c)) => match class_kind(self.tree, c) {
                (ClassKind::Connector, _) => return,
                (kind, _) => format!(
                    "an instance of the {} `{}`",
                    kind.keyword(),
                    self.tree.full_name(c)
                ),
            },
            _ => return,
        };
        self.out.push(
            FlatError::ConnectNonConnector {
                name: unimo_syntax::print::cref(r),
                what,
                span: r.span,
                declared: cur.name_span,
            }
            .into(),
        );
    }
}
