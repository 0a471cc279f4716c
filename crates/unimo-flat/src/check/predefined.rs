//! Elements of predefined types: a component of type Real, Integer, Boolean, String or
//! an enumeration has no elements, so `x.start` in an expression denotes nothing
//! (`E2001`; its attributes are set by modifiers, spec 4.9).

use super::elements::{base_of, component_type, find_component, Base};
use super::walk::composition_exprs;
use super::Ctx;
use crate::error::FlatError;
use crate::flat::for_each_value_ref;
use crate::tree::ClassId;
use unimo_syntax::ast::*;

impl Ctx<'_, '_> {
    /// `E2001` for `x.name` where `x` is a component of class `id` of a predefined type.
    pub(super) fn predefined_members(&mut self, id: ClassId) {
        let def = self.tree.get(id).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        let mut dotted: Vec<ComponentRef> = Vec::new();
        composition_exprs(composition, &mut |e| {
            for_each_value_ref(e, &mut |r| {
                if !r.global && r.parts.len() > 1 {
                    dotted.push(r.clone());
                }
            })
        });
        for r in dotted {
            let Some(info) = find_component(self.tree, id, &r.parts[0].name.text) else {
                continue;
            };
            let Some(t) = component_type(self.tree, &info) else {
                continue;
            };
            let base = match base_of(self.tree, t) {
                Some(Base::Other) | None => continue,
                Some(b) => b,
            };
            let (first, member) = (&r.parts[0].name.text, &r.parts[1].name);
            self.out.push(
                FlatError::ElementOfPredefined {
                    reference: unimo_syntax::print::cref(&r),
                    first: first.to_string(),
                    base: base.name(),
                    member: member.text.to_string(),
                    span: member.span,
                    declared: info.name_span,
                }
                .into(),
            );
        }
    }
}
