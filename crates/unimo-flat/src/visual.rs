//! Components the animation draws: instances of classes that declare
//! `annotation(__unimo_visual(...))`, in the class itself or in a class it extends
//! (docs/animation.md). Flattening only records where they are; the annotation's
//! arguments are read by the animation (`unimo animate`), names relative to the instance.

use crate::flat::FlatVisual;
use crate::instantiate::Instantiator;
use crate::tree::{ClassId, ClassTree};
use unimo_syntax::ast::{Argument, ClassBody, ClassModification};

/// The annotation's name.
pub const VISUAL_ANNOTATION: &str = "__unimo_visual";

impl ClassTree<'_> {
    /// The arguments of `annotation(__unimo_visual(...))` of `class`, else of the first
    /// of its bases (depth first, in declaration order) that has one.
    pub fn visual_annotation(&mut self, class: ClassId) -> Option<ClassModification> {
        let mut stack = vec![class];
        let mut seen = Vec::new();
        while let Some(c) = stack.pop() {
            if seen.contains(&c) {
                continue;
            }
            seen.push(c);
            if let Some(found) = own_visual(&self.get(c).def.body) {
                return Some(found);
            }
            let mut bases = self.bases(c);
            bases.reverse();
            stack.extend(bases);
        }
        None
    }
}

/// The class's own `__unimo_visual(...)` arguments.
fn own_visual(body: &ClassBody) -> Option<ClassModification> {
    let annotation = match body {
        ClassBody::Long { composition, .. } => composition.annotation.as_ref(),
        ClassBody::Short { comment, .. } => comment.annotation.as_ref(),
        ClassBody::Der { .. } | ClassBody::Enumeration { .. } => None,
    }?;
    annotation.args.iter().find_map(|arg| match arg {
        Argument::Modify {
            name,
            modification: Some(m),
            ..
        } if name.to_dotted() == VISUAL_ANNOTATION => {
            Some(m.class_mod.clone().unwrap_or(ClassModification {
                args: Vec::new(),
                span: m.span,
            }))
        }
        _ => None,
    })
}

impl Instantiator<'_, '_> {
    /// Notes the instance at `path` of class `class` when the class is drawn.
    pub(crate) fn note_visual(&mut self, class: ClassId, path: String) {
        if let Some(spec) = self.tree.visual_annotation(class) {
            let class = self.tree.full_name(class);
            self.model.visuals.push(FlatVisual { path, class, spec });
        }
    }
}
