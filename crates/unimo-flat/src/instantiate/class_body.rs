//! Instantiation of a class body: its elements, extends clauses, equations and
//! algorithms at an instance prefix; `outer` components; the check that every modified
//! name is an element of the class.

use super::{instance_key, part, Instantiator, Kind, MAX_DEPTH, MAX_SELF_NESTING};
use crate::error::FlatError;
use crate::flat::Variability;
use crate::lookup::Found;
use crate::modif::{Mod, Scope};
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// A class body to instantiate: the class, the instance's prefix and modification, the
/// variability its component imposes, and whether it is the top-level model or one of
/// its connectors (whose variables are the model's interface).
#[derive(Clone, Copy)]
pub(super) struct Body<'a> {
    pub class: ClassId,
    pub prefix: &'a [RefPart],
    pub m: &'a Mod,
    pub variability: Option<Variability>,
    pub top: bool,
}

impl<'a> Body<'a> {
    pub fn new(
        class: ClassId,
        prefix: &'a [RefPart],
        m: &'a Mod,
        variability: Option<Variability>,
        top: bool,
    ) -> Self {
        Body {
            class,
            prefix,
            m,
            variability,
            top,
        }
    }
}

impl Instantiator<'_, '_> {
    /// Instantiates the elements and equations of `body.class` at `body.prefix`.
    pub(super) fn class_body(&mut self, body: Body<'_>) {
        let class = body.class;
        // A class inside itself (a record with a component of its own type): legal
        // only while conditions stop the recursion, which they do within a few levels;
        // past MAX_SELF_NESTING it would grow exponentially until memory runs out.
        let nesting = self.ancestors.iter().filter(|&&c| c == class).count();
        if nesting >= MAX_SELF_NESTING {
            if !self.stopped {
                self.stopped = true;
                let def = &self.tree.get(class).def;
                let (name, span) = (def.name.text.clone(), def.name.span);
                self.report(FlatError::SelfNesting {
                    name: name.to_string(),
                    limit: MAX_SELF_NESTING,
                    span,
                });
            }
            return;
        }
        self.ancestors.push(class);
        let check = !self.duplicate_free.contains(&class);
        let level = check.then(|| self.declared_pool.pop().unwrap_or_default());
        self.declared.push(level);
        self.duplicate_found.push(false);
        // The `inner` components of the instance, those of its bases included, are
        // visible to the `outer` ones below it until the instance is done.
        let inners_before = self.inners.len();
        self.class_body_inner(body, true);
        self.inners.truncate(inners_before);
        self.ancestors.pop();
        let found = self.duplicate_found.pop().unwrap_or(true);
        if let Some(Some(mut level)) = self.declared.pop() {
            level.clear();
            self.declared_pool.push(level);
            if !found {
                self.duplicate_free.insert(class);
            }
        }
    }

    /// `check_mods`: whether modified names are checked here (not again in bases).
    fn class_body_inner(&mut self, body: Body<'_>, check_mods: bool) {
        let Body {
            class,
            prefix,
            m,
            variability,
            top,
        } = body;
        if self.stopped {
            return;
        }
        if self.depth >= MAX_DEPTH {
            let span = self.tree.get(class).def.name.span;
            self.report(FlatError::TooDeep {
                limit: MAX_DEPTH,
                span,
            });
            return;
        }
        self.depth += 1;
        let def = self.tree.get(class).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            // A short class used as a model: instantiate its base with its modifiers.
            if let Some((Kind::Class(c), m2)) = self.resolve_type(Found::Class(class), m) {
                if c != class {
                    self.class_body(Body {
                        class: c,
                        m: &m2,
                        ..body
                    });
                }
            }
            self.depth -= 1;
            return;
        };
        let scope = Scope {
            class,
            prefix: std::sync::Arc::from(prefix),
        };
        let prefix_key = if prefix.is_empty() {
            String::new()
        } else {
            instance_key(prefix)
        };
        self.register_class_redeclares(class, composition, prefix, m);
        // `redeclare T x(...)` as an element of this class replaces the inherited `x`:
        // it travels into the bases like an extends modifier (under the instance's).
        let own_redeclares = own_redeclares(composition, &scope);
        let has_bases = crate::values::def_has_bases(&def);
        if has_bases {
            self.pending_own
                .push((prefix_key.clone(), class, m.clone(), scope.clone()));
        }
        let base_mods = (m, &own_redeclares);
        self.inherited_elements(body, &def, &scope, base_mods);
        if has_bases {
            self.pending_own.pop();
        }
        if check_mods {
            self.check_modified_names(class, composition, m);
        }
        // `inner` components of this instance are visible to `outer` ones below it.
        for e in &composition.elements {
            if let (true, ElementKind::Component(cc)) = (e.inner, &e.kind) {
                for d in &cc.components {
                    let mut path = prefix.to_vec();
                    path.push(part(&d.name.text, d.name.span));
                    self.note_inner_type(&scope, cc, d, m, &path);
                    self.inners.push((d.name.text.clone(), path));
                }
            }
        }
        // `outer` components first: parameter bindings may refer through them.
        for e in &composition.elements {
            if let (true, false, false, ElementKind::Component(cc)) =
                (e.outer, e.inner, e.redeclare, &e.kind)
            {
                for d in &cc.components {
                    self.outer_component(&scope, cc, d);
                }
            }
        }
        // Parameters and constants first: sizes and conditions of the others use them;
        // then `inner` components, whose parameters the conditions and sizes of the
        // others may read through their `outer`s (an MSL example declares `inner World
        // world` after the joints whose animation depends on `world.enableAnimation`).
        for pass in [Pass::Parameters, Pass::Inners, Pass::Others] {
            self.components(composition, &scope, m, (pass, variability), top);
        }
        self.sections(composition, &scope);
        self.depth -= 1;
    }

    /// The inherited elements of `class` (instance `scope`), each base with its extends
    /// modifier under the instance's `m` and the class's own redeclarations; a class
    /// extension `model extends A(m)` first inherits the original `A`.
    fn inherited_elements(
        &mut self,
        body: Body<'_>,
        def: &ClassDef,
        scope: &Scope,
        (m, own_redeclares): (&Mod, &Mod),
    ) {
        let class = body.class;
        let ClassBody::Long { composition, .. } = &def.body else {
            return;
        };
        if let ClassBody::Long {
            extends: Some(ext), ..
        } = &def.body
        {
            if let Some(original) = self.tree.extended_original(class) {
                let base_mod = base_modifier(m, own_redeclares, ext.modification.as_ref(), scope);
                let base = Body {
                    class: original,
                    m: &base_mod,
                    ..body
                };
                self.class_body_inner(base, false);
            }
        }
        // Inherited elements first, each base with the extends modifier under ours.
        for e in &composition.elements {
            if let ElementKind::Extends(x) = &e.kind {
                let parts: Vec<&str> = x.base.parts.iter().map(|p| p.text.as_str()).collect();
                match self.tree.lookup_dotted(Some(class), &parts, true) {
                    Some(Found::Class(b)) => {
                        let base_mod =
                            base_modifier(m, own_redeclares, x.modification.as_ref(), scope);
                        let base = Body {
                            class: b,
                            m: &base_mod,
                            ..body
                        };
                        self.class_body_inner(base, false);
                    }
                    Some(Found::Builtin("ExternalObject")) => {} // an external object class
                    Some(Found::Builtin(_)) => {
                        self.report(FlatError::ExtendsPredefined { span: x.base.span });
                    }
                    _ => {} // reported by the name check
                }
            }
        }
    }

    /// Instantiates the component declarations of a composition: its parameters and
    /// constants (`parameters`) or its other components.
    fn components(
        &mut self,
        composition: &Composition,
        scope: &Scope,
        m: &Mod,
        (pass, variability): (Pass, Option<Variability>),
        top: bool,
    ) {
        let prefix_key = &if scope.prefix.is_empty() {
            String::new()
        } else {
            instance_key(&scope.prefix)
        };
        for e in &composition.elements {
            let ElementKind::Component(cc) = &e.kind else {
                continue;
            };
            let is_param = matches!(
                cc.prefix.variability,
                Some(
                    unimo_syntax::ast::Variability::Parameter
                        | unimo_syntax::ast::Variability::Constant
                )
            );
            let this_pass = match (is_param, e.inner) {
                (true, _) => Pass::Parameters,
                (false, true) => Pass::Inners,
                (false, false) => Pass::Others,
            };
            if pass != this_pass {
                continue;
            }
            if e.redeclare {
                continue; // instantiated in the base it replaces an element of
            }
            for d in &cc.components {
                if e.outer && !e.inner {
                    continue; // aliased above
                }
                if let Some(child) = m.child(&d.name.text) {
                    self.check_element_modifier(e, d, child);
                }
                // `replaceable T x constrainedby C(mods)`: the constraining
                // modifiers apply to `x`, whatever type it ends up with.
                if let Some(cm) = e
                    .constrainedby
                    .as_ref()
                    .and_then(|c| c.modification.as_ref())
                {
                    let cmod = Mod::from_class_mod(cm, scope);
                    let mut m2 = m.clone();
                    let name = d.name.text.clone();
                    let child = m.child(&name).cloned().unwrap_or_default().over(&cmod);
                    m2.children.retain(|(n, _)| *n != name);
                    m2.children.push((name, child));
                    self.element_final = e.is_final;
                    self.component(scope, prefix_key, cc, d, &m2, variability, top);
                    continue;
                }
                self.element_final = e.is_final;
                self.component(scope, prefix_key, cc, d, m, variability, top);
            }
        }
    }

    /// The equation and algorithm sections of a composition, flattened into the model.
    fn sections(&mut self, composition: &Composition, scope: &Scope) {
        for s in &composition.sections {
            match s {
                Section::Equation(es) => {
                    let mut out = Vec::new();
                    for eq in &es.equations {
                        self.equation(eq, scope, &mut Vec::new(), &mut out);
                    }
                    if es.initial {
                        self.model.initial_equations.extend(out);
                    } else {
                        self.model.equations.extend(out);
                    }
                }
                Section::Algorithm(al) => {
                    let mut stmts: Vec<Statement> = Vec::new();
                    self.model_statements(&al.statements, scope, &mut Vec::new(), &mut stmts);
                    if al.initial {
                        self.model.initial_algorithms.push(stmts);
                    } else {
                        self.model.algorithms.push(stmts);
                    }
                }
            }
        }
    }

    /// Every modified name must be an element of the class (or one of its bases).
    fn check_modified_names(&mut self, class: ClassId, _composition: &Composition, m: &Mod) {
        for (name, child) in &m.children {
            if !self.tree.has_component(class, name)
                && self.tree.member_class(class, name).is_none()
            {
                let span = child
                    .binding
                    .as_ref()
                    .map_or(Span::default(), |b| b.expr.span);
                let cname = self.tree.full_name(class);
                self.diags.push(
                    FlatError::ModifierOfMissing {
                        name: name.to_string(),
                        class: cname,
                        span,
                    }
                    .into(),
                );
            }
        }
    }
}

/// The modifier a base class is instantiated with: the `extends` clause's modification
/// under the class's own redeclarations, under the modifier `m` of the instance.
fn base_modifier(
    m: &Mod,
    own_redeclares: &Mod,
    modification: Option<&ClassModification>,
    scope: &Scope,
) -> Mod {
    let ext = modification
        .map(|cm| Mod::from_class_mod(cm, scope))
        .unwrap_or_default();
    m.over(&own_redeclares.over(&ext))
}

/// `redeclare T x(...)` elements of a class, as modifiers of the elements they replace.
fn own_redeclares(composition: &Composition, scope: &Scope) -> Mod {
    let mut own_redeclares = Mod::default();
    for e in &composition.elements {
        if let (true, ElementKind::Component(cc)) = (e.redeclare, &e.kind) {
            for d in &cc.components {
                let dm = Mod::redeclaring(cc, d, scope);
                own_redeclares.children.push((d.name.text.clone(), dm));
            }
        }
    }
    own_redeclares
}

/// The order in which a class's own components are instantiated.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pass {
    /// Parameters and constants.
    Parameters,
    /// The other `inner` components.
    Inners,
    /// Everything else.
    Others,
}
