//! Algorithms and functions: no assignment to a constant or parameter (`E2025`, spec
//! 3.8 and 8.6: a parameter with `fixed = false` may be assigned in an initial
//! algorithm), nor to a function's input (`E2026`, spec 12.2); a function declared
//! `pure` calls no impure function (`E2029`, spec 12.3).

use super::elements::find_component;
use super::walk::{composition_exprs, for_each_statement};
use super::Ctx;
use crate::error::FlatError;
use crate::flat::for_each_call;
use crate::lookup::Found;
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Ctx<'_, '_> {
    /// `E2025`/`E2026` for the assignments of the algorithm sections of `id`.
    pub(super) fn algorithms(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let function = def.kind == ClassKind::Function;
        for s in &composition.sections {
            let Section::Algorithm(al) = s else { continue };
            let mut targets: Vec<(Ident, Span)> = Vec::new();
            for_each_statement(&al.statements, &mut |st| match &st.kind {
                StatementKind::Assign { target, .. } => {
                    targets.push((target.parts[0].name.clone(), target.span))
                }
                StatementKind::MultiAssign { targets: ts, .. } => {
                    for t in ts.iter().flatten() {
                        if let ExprKind::Ref(r) = &t.kind {
                            targets.push((r.parts[0].name.clone(), r.span));
                        }
                    }
                }
                _ => {}
            });
            for (name, span) in targets {
                self.assignment(id, &name, span, function, al.initial);
            }
        }
    }

    fn assignment(&mut self, id: ClassId, name: &Ident, span: Span, function: bool, initial: bool) {
        let Some(info) = find_component(self.tree, id, &name.text) else {
            return;
        };
        let p = info.prefix;
        let (name, declared) = (name.text.to_string(), info.name_span);
        let constant = |what| FlatError::AssignsConstant {
            what,
            name: name.clone(),
            span,
            declared,
        };
        let e = match (p.variability, p.causality) {
            (Some(Variability::Constant), _) => constant("the constant"),
            (Some(Variability::Parameter), _) if !initial => constant("the parameter"),
            (_, Some(Causality::Input)) if function => FlatError::AssignsInput {
                name,
                span,
                declared,
            },
            _ => return,
        };
        self.out.push(e.into());
    }

    /// `E2029`: a function declared `pure` calls a function declared `impure`.
    pub(super) fn purity(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        // A function without a prefix that calls an impure one is impure (deprecated,
        // spec 12.3): only a function declared `pure` is held to it.
        if def.kind != ClassKind::Function || def.prefixes.purity != Some(Purity::Pure) {
            return;
        }
        let mut calls: Vec<Name> = Vec::new();
        composition_exprs(composition, &mut |e| {
            for_each_call(e, &mut |_| {}, &mut |f, _| calls.push(f.clone()))
        });
        for f in calls {
            let parts: Vec<&str> = f.parts.iter().map(|p| p.text.as_str()).collect();
            let Some(Found::Class(c)) = self.tree.lookup_dotted(Some(id), &parts, false) else {
                continue;
            };
            let callee = self.tree.get(c).def.clone();
            if callee.kind != ClassKind::Function || callee.prefixes.purity != Some(Purity::Impure)
            {
                continue;
            }
            self.out.push(
                FlatError::PureCallsImpure {
                    function: def.name.text.to_string(),
                    callee: f.to_dotted(),
                    span: f.span,
                    declared: callee.name.span,
                }
                .into(),
            );
        }
    }
}
