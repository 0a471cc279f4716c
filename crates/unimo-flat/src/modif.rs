//! Modifications as a tree, merged outer-over-inner (Modelica spec 7.2): the value a
//! declaration gives is overridden by an `extends` modifier, which is overridden by the
//! modifier of the component that instantiates the class.

use crate::tree::ClassId;
use smol_str::SmolStr;
use unimo_syntax::ast::{
    Argument, ClassModification, ComponentClause, ComponentDecl, Expr, Modification, Name,
    RedeclaredElement, RefPart,
};

/// Where an expression was written: the class (for name lookup) and the instance path
/// of that class in the model (for prefixing its component references). Cloned into
/// every binding it scopes: the path is shared, not copied.
#[derive(Clone, Debug)]
pub struct Scope {
    pub class: ClassId,
    pub prefix: std::sync::Arc<[RefPart]>,
}

/// A value with the scope it must be evaluated in.
#[derive(Clone, Debug)]
pub struct Bound {
    pub expr: Expr,
    pub scope: Scope,
}

/// A merged modification: a binding, modifications of named children, a redeclared
/// type.
#[derive(Clone, Debug, Default)]
pub struct Mod {
    pub binding: Option<Bound>,
    pub children: Vec<(SmolStr, Mod)>,
    /// `redeclare Type name` applied to this element, with the scope of the new type name.
    pub redeclare: Option<(Name, Scope)>,
    /// `redeclare model Name = ...` applied to this (class) element: the new class
    /// definition, with the scope it was written in.
    pub class_redeclare: Option<(std::sync::Arc<unimo_syntax::ast::ClassDef>, Scope)>,
    pub each: bool,
    pub is_final: bool,
}

impl Mod {
    pub fn child(&self, name: &str) -> Option<&Mod> {
        self.children
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, m)| m)
    }

    pub fn is_empty(&self) -> bool {
        self.binding.is_none()
            && self.children.is_empty()
            && self.redeclare.is_none()
            && self.class_redeclare.is_none()
    }

    /// `self` over `inner`: `self`'s values win, children merge by name.
    pub fn over(&self, inner: &Mod) -> Mod {
        let mut out = inner.clone();
        if self.binding.is_some() {
            out.binding = self.binding.clone();
        }
        if self.redeclare.is_some() {
            out.redeclare = self.redeclare.clone();
        }
        if self.class_redeclare.is_some() {
            out.class_redeclare = self.class_redeclare.clone();
        }
        out.each |= self.each;
        out.is_final |= self.is_final;
        for (name, m) in &self.children {
            match out.children.iter_mut().find(|(n, _)| n == name) {
                Some((_, existing)) => *existing = m.over(existing),
                None => out.children.push((name.clone(), m.clone())),
            }
        }
        out
    }

    /// `self` over `inner` like [`Mod::over`], consuming both: nothing is copied.
    pub fn over_into(self, mut inner: Mod) -> Mod {
        if self.binding.is_some() {
            inner.binding = self.binding;
        }
        if self.redeclare.is_some() {
            inner.redeclare = self.redeclare;
        }
        if self.class_redeclare.is_some() {
            inner.class_redeclare = self.class_redeclare;
        }
        inner.each |= self.each;
        inner.is_final |= self.is_final;
        for (name, m) in self.children {
            match inner.children.iter_mut().find(|(n, _)| *n == name) {
                Some((_, existing)) => {
                    let old = std::mem::take(existing);
                    *existing = m.over_into(old);
                }
                None => inner.children.push((name, m)),
            }
        }
        inner
    }

    /// The modification a class modification writes, in `scope`.
    pub fn from_class_mod(cm: &ClassModification, scope: &Scope) -> Mod {
        let mut out = Mod::default();
        for a in &cm.args {
            match a {
                Argument::Modify {
                    each,
                    is_final,
                    name,
                    modification,
                    ..
                } => {
                    let mut m = modification
                        .as_ref()
                        .map(|m| Mod::from_modification(m, scope))
                        .unwrap_or_default();
                    m.each |= *each;
                    m.is_final |= *is_final;
                    // `a.b.c = 1` is `a(b(c = 1))`.
                    for part in name.parts.iter().skip(1).rev() {
                        m = Mod {
                            children: vec![(part.text.clone(), m)],
                            ..Mod::default()
                        };
                    }
                    if let Some(first) = name.parts.first() {
                        out = Mod {
                            children: vec![(first.text.clone(), m)],
                            ..Mod::default()
                        }
                        .over_into(out);
                    }
                }
                Argument::Redeclare { element, each, .. } => {
                    if let RedeclaredElement::Class(cd) = element {
                        let m = Mod {
                            class_redeclare: Some((
                                std::sync::Arc::new((**cd).clone()),
                                scope.clone(),
                            )),
                            ..Mod::default()
                        };
                        out = Mod {
                            children: vec![(cd.name.text.clone(), m)],
                            ..Mod::default()
                        }
                        .over_into(out);
                    }
                    if let RedeclaredElement::Component(cc) = element {
                        for d in &cc.components {
                            let mut m = Mod::redeclaring(cc, d, scope);
                            m.each |= *each;
                            out = Mod {
                                children: vec![(d.name.text.clone(), m)],
                                ..Mod::default()
                            }
                            .over_into(out);
                        }
                    }
                }
            }
        }
        out
    }

    /// The modifier `redeclare T x(...)` gives `x` (declaration `d` of clause `cc`): its
    /// own modification and the new type `T`, both in `scope`.
    pub(crate) fn redeclaring(cc: &ComponentClause, d: &ComponentDecl, scope: &Scope) -> Mod {
        let mut m = d
            .modification
            .as_ref()
            .map(|m| Mod::from_modification(m, scope))
            .unwrap_or_default();
        m.redeclare = Some((cc.type_name.clone(), scope.clone()));
        m
    }

    /// The modification of one declaration or modifier argument, in `scope`.
    pub fn from_modification(m: &Modification, scope: &Scope) -> Mod {
        let mut out = m
            .class_mod
            .as_ref()
            .map(|cm| Mod::from_class_mod(cm, scope))
            .unwrap_or_default();
        if let Some(b) = &m.binding {
            out.binding = Some(Bound {
                expr: b.clone(),
                scope: scope.clone(),
            });
        }
        out
    }
}
