//! Modelica name lookup (spec 5.3): a name used in a class is searched in the class
//! (its own and inherited elements), then its imports, then each enclosing class —
//! stopping at an `encapsulated` one — and finally at the top level.

use crate::tree::{ClassId, ClassTree};
use unimo_syntax::ast::{ClassBody, ElementKind, ImportKind};

/// The predefined types (spec 4.8).
pub const BUILTIN_TYPES: &[&str] = &[
    "Real",
    "Integer",
    "Boolean",
    "String",
    "StateSelect",
    "AssertionLevel",
    // The base class of external object classes (spec 12.9.7), not a type of its own.
    "ExternalObject",
];

// Built-in functions and operators (spec 3.7) are the entries of
// `unimo_builtins::BUILTINS`: `is_builtin_function`, `is_unsupported_builtin` and
// `unimo_builtins::is_elementwise` read it.

/// Operators that combine arrays element by element (`+`, `-` and the `.` ones).
pub fn is_elementwise(op: unimo_syntax::ast::BinaryOp) -> bool {
    use unimo_syntax::ast::BinaryOp::*;
    matches!(
        op,
        Add | Sub | ElemAdd | ElemSub | ElemMul | ElemDiv | ElemPow
    )
}

/// Operators whose result is a Boolean (relations and `and`/`or`).
pub fn is_boolean(op: unimo_syntax::ast::BinaryOp) -> bool {
    use unimo_syntax::ast::BinaryOp::*;
    matches!(op, Rel(_) | And | Or)
}

/// The argument of a call of an element-wise builtin with one positional argument
/// (`der(x)`, `sin(v)`), whose result has the argument's shape.
pub fn elementwise_arg<'e>(
    func: &unimo_syntax::ast::Name,
    args: &'e unimo_syntax::ast::CallArgs,
) -> Option<&'e unimo_syntax::ast::Expr> {
    (!func.global
        && func.parts.len() == 1
        && unimo_builtins::is_elementwise(&func.parts[0].text)
        && args.positional.len() == 1
        && args.named.is_empty()
        && args.iterators.is_empty())
    .then(|| &args.positional[0])
}

/// Whether `name` is a built-in function or operator unimo implements (an entry of
/// `unimo_builtins::BUILTINS`).
pub fn is_builtin_function(name: &str) -> bool {
    unimo_builtins::is_function(name)
}

/// Built-in operators of the language that unimo names but does not implement yet:
/// stream connectors (spec 15), synchronous and clocked features (16), state machines
/// (17), overconstrained connections (9.4). The name check accepts them; lowering
/// reports each as "not supported yet" (`E3001`).
pub fn is_unsupported_builtin(name: &str) -> bool {
    unimo_builtins::is_unsupported(name)
}

/// Most levels of inheritance followed before giving up (cycles, or absurd depth).
const MAX_INHERITANCE_DEPTH: usize = 64;

/// What a simple name denotes in a scope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Found {
    /// A class (also a package or a function).
    Class(ClassId),
    /// A component declared (or inherited) in this class.
    Component(ClassId),
    /// A predefined type.
    Builtin(&'static str),
}

impl ClassTree<'_> {
    /// The classes `class` extends, looked up in its scope (without its own inherited
    /// elements, spec 5.6.1). A short class definition extends its base.
    pub fn bases(&mut self, class: ClassId) -> Vec<ClassId> {
        if let Some(b) = self.bases_cache.get(&class) {
            return b.clone();
        }
        // Guard against `extends` cycles while resolving: provisionally no bases.
        self.bases_cache.insert(class, Vec::new());
        let out = self.resolve_bases(class);
        self.bases_cache.insert(class, out.clone());
        out
    }

    fn resolve_bases(&mut self, class: ClassId) -> Vec<ClassId> {
        let def = self.get(class).def.clone();
        let names: Vec<Vec<String>> = match &def.body {
            ClassBody::Long { composition, .. } => composition
                .elements
                .iter()
                .filter_map(|e| match &e.kind {
                    ElementKind::Extends(x) => Some(parts(&x.base)),
                    _ => None,
                })
                .collect(),
            ClassBody::Short { base, .. } => vec![parts(base)],
            // A function's derivative has its own interface: it inherits nothing.
            ClassBody::Enumeration { .. } | ClassBody::Der { .. } => Vec::new(),
        };
        let mut out = Vec::new();
        for n in names {
            let refs: Vec<&str> = n.iter().map(String::as_str).collect();
            // A short class's base is looked up from its enclosing scope.
            let scope = match &def.body {
                ClassBody::Short { .. } => self.get(class).parent,
                _ => Some(class),
            };
            if let Some(Found::Class(c)) = self.lookup_dotted(scope, &refs, true) {
                if c != class {
                    out.push(c);
                }
            }
        }
        if let Some(original) = self.extended_original(class) {
            out.insert(0, original);
        }
        out
    }

    /// The class a class extension `model extends A(m) ... end A;` extends: the element
    /// `A` its enclosing class inherits (spec 7.3.2).
    pub fn extended_original(&mut self, class: ClassId) -> Option<ClassId> {
        let def = self.get(class).def.clone();
        let ClassBody::Long {
            extends: Some(_), ..
        } = &def.body
        else {
            return None;
        };
        let parent = self.get(class).parent?;
        self.bases(parent)
            .into_iter()
            .find_map(|b| self.member_class(b, &def.name.text))
            .filter(|&c| c != class)
    }

    /// A class member of `class`: declared, in its package folder, or inherited.
    pub fn member_class(&mut self, class: ClassId, name: &str) -> Option<ClassId> {
        self.member_class_depth(class, name, 0)
    }

    fn member_class_depth(&mut self, class: ClassId, name: &str, depth: usize) -> Option<ClassId> {
        if let Some(c) = self.child_class(class, name) {
            return Some(c);
        }
        if depth >= MAX_INHERITANCE_DEPTH {
            return None;
        }
        for b in self.bases(class) {
            if let Some(c) = self.member_class_depth(b, name, depth + 1) {
                return Some(c);
            }
        }
        None
    }

    /// Whether `class` declares or inherits a component (or enumeration literal) `name`.
    pub fn has_component(&mut self, class: ClassId, name: &str) -> bool {
        self.has_component_depth(class, name, 0)
    }

    fn has_component_depth(&mut self, class: ClassId, name: &str, depth: usize) -> bool {
        if self.get(class).declares(name) {
            return true;
        }
        if depth >= MAX_INHERITANCE_DEPTH {
            return false;
        }
        self.bases(class)
            .into_iter()
            .any(|b| self.has_component_depth(b, name, depth + 1))
    }

    /// Looks up a dotted name used inside `scope` (`None`: at the top level).
    /// `skip_inherited`: do not search the first scope's inherited elements (for the
    /// names in its own `extends` clauses).
    pub fn lookup_dotted(
        &mut self,
        scope: Option<ClassId>,
        parts: &[&str],
        skip_inherited: bool,
    ) -> Option<Found> {
        let (first, rest) = parts.split_first()?;
        let mut found = self.lookup_simple(scope, first, skip_inherited)?;
        for p in rest {
            found = match found {
                Found::Class(c) => match self.member_class(c, p) {
                    Some(m) => Found::Class(m),
                    None if self.has_component(c, p) => Found::Component(c),
                    None => return None,
                },
                // Members of components are checked when instantiating.
                Found::Component(_) => return Some(found),
                Found::Builtin(_) => return None,
            };
        }
        Some(found)
    }

    /// Looks up a simple name from `scope` outwards (spec 5.3.1).
    pub fn lookup_simple(
        &mut self,
        scope: Option<ClassId>,
        name: &str,
        skip_inherited: bool,
    ) -> Option<Found> {
        let mut cur = scope;
        let mut first = true;
        let mut file = None;
        while let Some(c) = cur {
            file = Some(self.get(c).file);
            // Components and classes share one namespace; components are indexed, so
            // try them first.
            if self.get(c).declares(name) {
                return Some(Found::Component(c));
            }
            let local = if first && skip_inherited {
                self.child_class(c, name)
            } else {
                self.member_class(c, name)
            };
            if let Some(m) = local {
                return Some(Found::Class(m));
            }
            let has = if first && skip_inherited {
                self.declares_component(c, name)
            } else {
                self.has_component(c, name)
            };
            if has {
                return Some(Found::Component(c));
            }
            if let Some(f) = self.lookup_import(c, name) {
                return Some(f);
            }
            if self.get(c).def.encapsulated {
                return BUILTIN_TYPES
                    .iter()
                    .find(|b| **b == name)
                    .map(|b| Found::Builtin(b));
            }
            first = false;
            cur = self.get(c).parent;
        }
        if let Some(b) = BUILTIN_TYPES.iter().find(|b| **b == name) {
            return Some(Found::Builtin(b));
        }
        self.top_level_in(name, file).map(Found::Class)
    }

    fn declares_component(&self, class: ClassId, name: &str) -> bool {
        self.get(class).declares(name)
    }

    /// `name` through the imports of `class` (imports are looked up globally).
    fn lookup_import(&mut self, class: ClassId, name: &str) -> Option<Found> {
        let imports: Vec<ImportKind> = self
            .get(class)
            .imports()
            .into_iter()
            .map(|i| i.kind.clone())
            .collect();
        for kind in &imports {
            match kind {
                ImportKind::Qualified(n) => {
                    if n.parts.last().is_some_and(|p| p.text == name) {
                        return self.lookup_global_found(&parts(n));
                    }
                }
                ImportKind::Renamed { alias, name: n } => {
                    if alias.text == name {
                        return self.lookup_global_found(&parts(n));
                    }
                }
                ImportKind::Unqualified(n) => {
                    if let Some(Found::Class(pkg)) = self.lookup_global_found(&parts(n)) {
                        if let Some(c) = self.member_class(pkg, name) {
                            return Some(Found::Class(c));
                        }
                        if self.has_component(pkg, name) {
                            return Some(Found::Component(pkg));
                        }
                    }
                }
                ImportKind::Multiple { name: n, items } => {
                    if items.iter().any(|i| i.text == name) {
                        let mut full = parts(n);
                        full.push(name.to_owned());
                        return self.lookup_global_found(&full);
                    }
                }
            }
        }
        None
    }

    fn lookup_global_found(&mut self, parts: &[String]) -> Option<Found> {
        let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
        self.lookup_dotted(None, &refs, false)
    }

    /// Whether `scope` or one of its enclosing classes is `encapsulated`.
    pub fn is_inside_encapsulated(&self, scope: ClassId) -> bool {
        let mut cur = Some(scope);
        while let Some(c) = cur {
            if self.get(c).def.encapsulated {
                return true;
            }
            cur = self.get(c).parent;
        }
        false
    }

    /// Names visible from `scope`, for "did you mean" suggestions.
    pub fn visible_names(&self, scope: Option<ClassId>) -> Vec<String> {
        let mut names: Vec<String> = BUILTIN_TYPES.iter().map(|s| s.to_string()).collect();
        let mut cur = scope;
        while let Some(c) = cur {
            names.extend(self.child_names(c));
            if let ClassBody::Long { composition, .. } = &self.get(c).def.body {
                for e in &composition.elements {
                    match &e.kind {
                        ElementKind::Component(cc) => {
                            names.extend(cc.components.iter().map(|d| d.name.text.to_string()))
                        }
                        ElementKind::Import(imp) => match &imp.kind {
                            ImportKind::Renamed { alias, .. } => names.push(alias.text.to_string()),
                            ImportKind::Qualified(n) => {
                                names.extend(n.parts.last().map(|p| p.text.to_string()))
                            }
                            _ => {}
                        },
                        _ => {}
                    }
                }
            }
            cur = self.get(c).parent;
        }
        names.extend(self.top_names());
        names
    }
}

fn parts(n: &unimo_syntax::ast::Name) -> Vec<String> {
    n.parts.iter().map(|p| p.text.to_string()).collect()
}
