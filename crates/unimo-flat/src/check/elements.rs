//! Elements of classes as declared: a component found in a class or its bases with
//! its prefixes and visibility, the class a type name denotes, the predefined type a
//! type derives from, and whether a type is an array.

use crate::lookup::Found;
use crate::tree::{ClassId, ClassTree};
use unimo_source::Span;
use unimo_syntax::ast::*;

/// Most levels of inheritance or type aliases followed.
const MAX_DEPTH: usize = 32;

/// A component declaration as found from a class.
#[derive(Clone, Debug)]
pub(crate) struct ComponentInfo {
    /// The class whose body declares it (its type name is looked up there).
    pub owner: ClassId,
    /// Protected where declared, or inherited through a protected `extends`.
    pub protected: bool,
    pub prefix: TypePrefix,
    pub type_name: Name,
    /// Dimensions written on the declaration and on its type (`Real[2] x[3]`: 2).
    pub n_dims: usize,
    pub name_span: Span,
    /// Declared `final`.
    pub is_final: bool,
    pub name: smol_str::SmolStr,
    /// The dimensions of the declaration, then those written on its type.
    pub dims: Vec<Subscript>,
}

impl ComponentInfo {
    /// Declaration `d` of clause `cc`, element `e` of class `owner`.
    pub fn new(owner: ClassId, e: &Element, cc: &ComponentClause, d: &ComponentDecl) -> Self {
        ComponentInfo {
            owner,
            protected: e.visibility == Visibility::Protected,
            prefix: cc.prefix,
            type_name: cc.type_name.clone(),
            n_dims: d.dims.len() + cc.type_dims.len(),
            name_span: d.name.span,
            is_final: e.is_final,
            name: d.name.text.clone(),
            dims: d.dims.iter().chain(&cc.type_dims).cloned().collect(),
        }
    }
}

/// The predefined type a type derives from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Base {
    Real,
    Integer,
    Boolean,
    String,
    Enumeration,
    /// A class that is not a type (a model, record, connector, ...).
    Other,
}

impl Base {
    pub fn name(self) -> &'static str {
        match self {
            Base::Real => "Real",
            Base::Integer => "Integer",
            Base::Boolean => "Boolean",
            Base::String => "String",
            Base::Enumeration => "an enumeration",
            Base::Other => "a class",
        }
    }
}

fn parts(n: &Name) -> Vec<&str> {
    n.parts.iter().map(|p| p.text.as_str()).collect()
}

/// The component `name` declared in `class` or inherited by it.
pub(crate) fn find_component(
    tree: &mut ClassTree<'_>,
    class: ClassId,
    name: &str,
) -> Option<ComponentInfo> {
    find_depth(tree, class, name, 0)
}

fn find_depth(
    tree: &mut ClassTree<'_>,
    class: ClassId,
    name: &str,
    depth: usize,
) -> Option<ComponentInfo> {
    if depth > MAX_DEPTH {
        return None;
    }
    let def = tree.get(class).def.clone();
    let composition = match &def.body {
        ClassBody::Long { composition, .. } => composition,
        ClassBody::Short { .. } => {
            for b in tree.bases(class) {
                if let Some(info) = find_depth(tree, b, name, depth + 1) {
                    return Some(info);
                }
            }
            return None;
        }
        _ => return None,
    };
    for e in &composition.elements {
        let ElementKind::Component(cc) = &e.kind else {
            continue;
        };
        if let Some(d) = cc.components.iter().find(|d| d.name.text == name) {
            return Some(ComponentInfo::new(class, e, cc, d));
        }
    }
    for e in &composition.elements {
        let ElementKind::Extends(x) = &e.kind else {
            continue;
        };
        let Some(Found::Class(b)) = tree.lookup_dotted(Some(class), &parts(&x.base), true) else {
            continue;
        };
        if b == class {
            continue;
        }
        if let Some(mut info) = find_depth(tree, b, name, depth + 1) {
            info.protected |= e.visibility == Visibility::Protected;
            return Some(info);
        }
    }
    let original = tree.extended_original(class)?;
    find_depth(tree, original, name, depth + 1)
}

/// What the type name of a component denotes.
pub(crate) fn component_type(tree: &mut ClassTree<'_>, info: &ComponentInfo) -> Option<Found> {
    match tree.lookup_dotted(Some(info.owner), &parts(&info.type_name), false)? {
        Found::Component(_) => None,
        f => Some(f),
    }
}

/// The class of a component's type, when it is a class (not a predefined type).
pub(crate) fn component_class(tree: &mut ClassTree<'_>, info: &ComponentInfo) -> Option<ClassId> {
    match component_type(tree, info)? {
        Found::Class(c) => Some(c),
        _ => None,
    }
}

/// The predefined type `found` derives from, following type aliases and `extends`.
pub(crate) fn base_of(tree: &mut ClassTree<'_>, found: Found) -> Option<Base> {
    let mut cur = found;
    for _ in 0..MAX_DEPTH {
        let c = match cur {
            Found::Builtin(b) => {
                return Some(match b {
                    "Real" => Base::Real,
                    "Integer" => Base::Integer,
                    "Boolean" => Base::Boolean,
                    "String" => Base::String,
                    "StateSelect" | "AssertionLevel" => Base::Enumeration,
                    _ => Base::Other,
                })
            }
            Found::Component(_) => return None,
            Found::Class(c) => c,
        };
        let def = tree.get(c).def.clone();
        let next = match &def.body {
            ClassBody::Enumeration { .. } => return Some(Base::Enumeration),
            ClassBody::Der { .. } => return Some(Base::Other),
            ClassBody::Short { base, .. } => {
                let scope = tree.get(c).parent;
                tree.lookup_dotted(scope, &parts(base), false)
            }
            ClassBody::Long { composition, .. } => {
                if def.kind != ClassKind::Type {
                    return Some(Base::Other);
                }
                let base = composition.elements.iter().find_map(|e| match &e.kind {
                    ElementKind::Extends(x) => Some(x.base.clone()),
                    _ => None,
                })?;
                tree.lookup_dotted(Some(c), &parts(&base), true)
            }
        };
        cur = next?;
    }
    None
}

/// Whether a type is an array type (`type Vector3 = Real[3]`, or a long type that
/// extends one).
pub(crate) fn type_is_array(tree: &mut ClassTree<'_>, found: Found) -> bool {
    let mut cur = found;
    for _ in 0..MAX_DEPTH {
        let Found::Class(c) = cur else { return false };
        let def = tree.get(c).def.clone();
        let next = match &def.body {
            ClassBody::Short { base, dims, .. } => {
                if !dims.is_empty() {
                    return true;
                }
                let scope = tree.get(c).parent;
                tree.lookup_dotted(scope, &parts(base), false)
            }
            ClassBody::Long { composition, .. } if def.kind == ClassKind::Type => {
                let Some(base) = composition.elements.iter().find_map(|e| match &e.kind {
                    ElementKind::Extends(x) => Some(x.base.clone()),
                    _ => None,
                }) else {
                    return false;
                };
                tree.lookup_dotted(Some(c), &parts(&base), true)
            }
            _ => return false,
        };
        match next {
            Some(f) => cur = f,
            None => return false,
        }
    }
    false
}

/// Whether a short class definition on the way from `class` to its base gives a
/// causality (`connector RealInput = input Real`).
pub(crate) fn type_has_causality(tree: &mut ClassTree<'_>, class: ClassId) -> bool {
    let mut c = class;
    for _ in 0..MAX_DEPTH {
        let def = tree.get(c).def.clone();
        let ClassBody::Short {
            base, causality, ..
        } = &def.body
        else {
            return false;
        };
        if causality.is_some() {
            return true;
        }
        let scope = tree.get(c).parent;
        match tree.lookup_dotted(scope, &parts(base), false) {
            Some(Found::Class(b)) => c = b,
            _ => return false,
        }
    }
    false
}

/// Whether a component is an array (its declaration or its type has dimensions).
pub(crate) fn is_array(tree: &mut ClassTree<'_>, info: &ComponentInfo) -> bool {
    info.n_dims > 0 || component_type(tree, info).is_some_and(|t| type_is_array(tree, t))
}

/// The kind of class a type denotes, following short class definitions to the first
/// class that is not a `type` alias; `expandable` for an expandable connector.
pub(crate) fn class_kind(tree: &mut ClassTree<'_>, class: ClassId) -> (ClassKind, bool) {
    let mut c = class;
    for _ in 0..MAX_DEPTH {
        let def = tree.get(c).def.clone();
        let ClassBody::Short { base, .. } = &def.body else {
            return (def.kind, def.prefixes.expandable);
        };
        if def.kind != ClassKind::Type && def.kind != ClassKind::Class {
            let expandable = def.prefixes.expandable
                || tree
                    .bases(c)
                    .first()
                    .is_some_and(|&b| tree.get(b).def.prefixes.expandable);
            return (def.kind, expandable);
        }
        let scope = tree.get(c).parent;
        match tree.lookup_dotted(scope, &parts(base), false) {
            Some(Found::Class(b)) => c = b,
            _ => return (def.kind, false),
        }
    }
    (tree.get(c).def.kind, false)
}

/// Whether class `inner` is `outer` or nested inside it.
pub(crate) fn is_within(tree: &ClassTree<'_>, inner: ClassId, outer: ClassId) -> bool {
    let mut cur = Some(inner);
    while let Some(c) = cur {
        if c == outer {
            return true;
        }
        cur = tree.get(c).parent;
    }
    false
}

/// Whether `class` declares a nested class `name` under `protected`.
pub(crate) fn declares_protected_class(
    tree: &ClassTree<'_>,
    class: ClassId,
    name: &str,
) -> Option<Span> {
    let ClassBody::Long { composition, .. } = &tree.get(class).def.body else {
        return None;
    };
    composition.elements.iter().find_map(|e| match &e.kind {
        ElementKind::Class(c) if c.name.text == name && e.visibility == Visibility::Protected => {
            Some(c.name.span)
        }
        _ => None,
    })
}

/// Every component `class` declares or inherits (through `extends`), with its info.
pub(crate) fn all_components(tree: &mut ClassTree<'_>, class: ClassId) -> Vec<ComponentInfo> {
    let mut out = Vec::new();
    collect_components(tree, class, 0, &mut out);
    out
}

fn collect_components(
    tree: &mut ClassTree<'_>,
    class: ClassId,
    depth: usize,
    out: &mut Vec<ComponentInfo>,
) {
    if depth > MAX_DEPTH {
        return;
    }
    let def = tree.get(class).def.clone();
    let ClassBody::Long { composition, .. } = &def.body else {
        for b in tree.bases(class) {
            collect_components(tree, b, depth + 1, out);
        }
        return;
    };
    for e in &composition.elements {
        match &e.kind {
            ElementKind::Component(cc) => {
                for d in &cc.components {
                    out.push(ComponentInfo::new(class, e, cc, d));
                }
            }
            ElementKind::Extends(x) => {
                if let Some(Found::Class(b)) =
                    tree.lookup_dotted(Some(class), &parts(&x.base), true)
                {
                    if b != class {
                        collect_components(tree, b, depth + 1, out);
                    }
                }
            }
            _ => {}
        }
    }
}
