//! The class tree: every class the current run knows, with typed ids, loaded lazily.
//!
//! A class comes from a user file, from a nested class definition, or from a library
//! folder laid out as Modelica packages (`P/package.mo`, `P/Q.mo`, `P/R/package.mo`).
//! A library file is read and parsed only when a name inside it is looked up, so a
//! scene pays only for the classes it uses (`LoadStats` counts them).

use crate::provider::{LibLocation, SourceProvider};
use rustc_hash::FxHashMap as HashMap;
use smol_str::SmolStr;
use std::sync::Arc;
use unimo_source::{Diagnostic, FileId, SourceMap};
use unimo_syntax::ast::{ClassDef, ElementKind, StoredDefinition};

/// Index of a class in the [`ClassTree`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct ClassId(pub u32);

/// One class: its definition and where it sits.
#[derive(Debug)]
pub struct ClassEntry {
    pub name: SmolStr,
    pub parent: Option<ClassId>,
    pub def: Arc<ClassDef>,
    pub file: FileId,
    /// The library folder holding this package's children, if it is a package folder.
    pub location: Option<LibLocation>,
    /// Child classes resolved so far (`None`: known not to exist).
    children: HashMap<SmolStr, Option<ClassId>>,
    /// Names of the components (and enumeration literals) declared here, built on
    /// first use: lookups in classes with 10^5 components stay O(1).
    declared: std::sync::OnceLock<std::collections::HashSet<SmolStr>>,
    /// Nested class definitions by name (index into the composition's elements).
    nested: std::sync::OnceLock<HashMap<SmolStr, usize>>,
    /// Indices of the import elements.
    imports: std::sync::OnceLock<Vec<usize>>,
}

impl ClassEntry {
    fn new(
        name: SmolStr,
        parent: Option<ClassId>,
        def: Arc<ClassDef>,
        file: FileId,
        location: Option<LibLocation>,
    ) -> ClassEntry {
        ClassEntry {
            name,
            parent,
            def,
            file,
            location,
            children: HashMap::default(),
            declared: Default::default(),
            nested: Default::default(),
            imports: Default::default(),
        }
    }

    /// The import clauses of this class.
    pub fn imports(&self) -> Vec<&unimo_syntax::ast::Import> {
        let unimo_syntax::ast::ClassBody::Long { composition, .. } = &self.def.body else {
            return Vec::new();
        };
        self.imports
            .get_or_init(|| {
                composition
                    .elements
                    .iter()
                    .enumerate()
                    .filter_map(|(i, e)| matches!(e.kind, ElementKind::Import(_)).then_some(i))
                    .collect()
            })
            .iter()
            .filter_map(|&i| match &composition.elements[i].kind {
                ElementKind::Import(imp) => Some(imp),
                _ => None,
            })
            .collect()
    }

    /// The nested class definition `name`, found through an index built on first use.
    fn nested_class(&self, name: &str) -> Option<ClassDef> {
        let unimo_syntax::ast::ClassBody::Long { composition, .. } = &self.def.body else {
            return None;
        };
        let index = self.nested.get_or_init(|| {
            composition
                .elements
                .iter()
                .enumerate()
                .filter_map(|(i, e)| match &e.kind {
                    ElementKind::Class(c) => Some((c.name.text.clone(), i)),
                    _ => None,
                })
                .collect()
        });
        let i = *index.get(name)?;
        match &composition.elements[i].kind {
            ElementKind::Class(c) => Some((**c).clone()),
            _ => None,
        }
    }

    /// Whether this class itself declares the component (or literal) `name`.
    pub fn declares(&self, name: &str) -> bool {
        self.declared
            .get_or_init(|| match &self.def.body {
                unimo_syntax::ast::ClassBody::Long { composition, .. } => composition
                    .elements
                    .iter()
                    .filter_map(|e| match &e.kind {
                        ElementKind::Component(cc) => {
                            Some(cc.components.iter().map(|d| d.name.text.clone()))
                        }
                        _ => None,
                    })
                    .flatten()
                    .collect(),
                unimo_syntax::ast::ClassBody::Enumeration { literals, .. } => {
                    literals.iter().map(|l| l.name.text.clone()).collect()
                }
                unimo_syntax::ast::ClassBody::Short { .. }
                | unimo_syntax::ast::ClassBody::Der { .. } => Default::default(),
            })
            .contains(name)
    }
}

/// How much the lazy loader read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadStats {
    /// Library files read and parsed (user files not counted).
    pub library_files: usize,
    /// Bytes of those files.
    pub library_bytes: usize,
    /// Classes entered in the tree (user and library).
    pub classes: usize,
}

/// All classes known to this run, plus the sources they came from.
pub struct ClassTree<'p> {
    provider: &'p dyn SourceProvider,
    pub sources: SourceMap,
    classes: Vec<ClassEntry>,
    /// Top-level classes of user files (no `within`, or `within;`), by name; several
    /// files may define the same name (each is checked in its own file's context).
    user_top: HashMap<SmolStr, Vec<ClassId>>,
    /// Library top-level names looked up so far.
    library_top: HashMap<SmolStr, Option<ClassId>>,
    /// Parse errors of library files, reported once.
    pub diagnostics: Vec<Diagnostic>,
    pub stats: LoadStats,
    /// Base classes of each class, resolved once.
    pub(crate) bases_cache: HashMap<ClassId, Vec<ClassId>>,
}

impl<'p> ClassTree<'p> {
    pub fn new(provider: &'p dyn SourceProvider) -> ClassTree<'p> {
        ClassTree {
            provider,
            sources: SourceMap::new(),
            classes: Vec::new(),
            user_top: HashMap::default(),
            library_top: HashMap::default(),
            diagnostics: Vec::new(),
            stats: LoadStats::default(),
            bases_cache: HashMap::default(),
        }
    }

    pub fn get(&self, id: ClassId) -> &ClassEntry {
        &self.classes[id.0 as usize]
    }

    fn add(&mut self, entry: ClassEntry) -> ClassId {
        let id = ClassId(self.classes.len() as u32);
        self.classes.push(entry);
        self.stats.classes += 1;
        id
    }

    /// The full dotted name of a class (`Modelica.Units.SI.Length`).
    pub fn full_name(&self, id: ClassId) -> String {
        let mut parts = vec![self.get(id).name.to_string()];
        let mut cur = self.get(id).parent;
        while let Some(p) = cur {
            parts.push(self.get(p).name.to_string());
            cur = self.get(p).parent;
        }
        parts.reverse();
        parts.join(".")
    }

    /// Adds a parsed user file. Its classes are placed under their `within` package
    /// (looked up in the library) or at the top level. Returns the new classes.
    pub fn add_user_file(&mut self, file: FileId, def: StoredDefinition) -> Vec<ClassId> {
        let parent = match &def.within {
            Some(Some(name)) => {
                let parts: Vec<&str> = name.parts.iter().map(|p| p.text.as_str()).collect();
                self.lookup_global(&parts)
            }
            _ => None,
        };
        let mut out = Vec::new();
        for c in def.classes {
            let name = c.name.text.clone();
            // A user file that is also in the library (`unimo check stdlib`) is checked
            // in place, but lookups keep using the library's copy, which knows its
            // package folder.
            let in_library = match parent {
                Some(p) => self.child_class(p, &name).is_some(),
                None => self.library_top_level(&name).is_some(),
            };
            let id = self.add(ClassEntry::new(
                name.clone(),
                parent,
                Arc::new(c),
                file,
                None,
            ));
            if !in_library {
                match parent {
                    Some(p) => {
                        self.classes[p.0 as usize].children.insert(name, Some(id));
                    }
                    None => self.user_top.entry(name).or_default().push(id),
                }
            }
            out.push(id);
        }
        out
    }

    /// Looks up a dotted name from the top level (user files first, then the library).
    pub fn lookup_global(&mut self, parts: &[&str]) -> Option<ClassId> {
        let (first, rest) = parts.split_first()?;
        let mut cur = self.top_level(first)?;
        for p in rest {
            cur = self.child_class(cur, p)?;
        }
        Some(cur)
    }

    /// A top-level class by name: a user file's class, or a library root's package.
    pub fn top_level(&mut self, name: &str) -> Option<ClassId> {
        self.top_level_in(name, None)
    }

    /// As [`ClassTree::top_level`], preferring the user classes of file `prefer` when
    /// several user files define the name.
    pub fn top_level_in(&mut self, name: &str, prefer: Option<FileId>) -> Option<ClassId> {
        if let Some(ids) = self.user_top.get(name) {
            let pick = ids
                .iter()
                .find(|id| Some(self.get(**id).file) == prefer)
                .or(ids.first());
            if let Some(&id) = pick {
                return Some(id);
            }
        }
        self.library_top_level(name)
    }

    fn library_top_level(&mut self, name: &str) -> Option<ClassId> {
        if let Some(&cached) = self.library_top.get(name) {
            return cached;
        }
        let mut found = None;
        for root in 0..self.provider.roots() {
            let here = LibLocation {
                root,
                dir: String::new(),
            };
            if let Some(id) = self.load_child(None, &here, name) {
                found = Some(id);
                break;
            }
        }
        self.library_top.insert(SmolStr::new(name), found);
        found
    }

    /// The directly declared child class `name` of `class` (nested definition or file
    /// in its package folder), loading it if needed. Inherited classes are not here:
    /// see [`crate::lookup`].
    /// A class written inside a modifier (`redeclare model M = N(...)`): known by id,
    /// looked up from `parent`, but no member of it.
    pub fn add_detached(&mut self, parent: ClassId, def: Arc<ClassDef>) -> ClassId {
        let file = self.get(parent).file;
        self.add(ClassEntry::new(
            def.name.text.clone(),
            Some(parent),
            def,
            file,
            None,
        ))
    }

    pub fn child_class(&mut self, class: ClassId, name: &str) -> Option<ClassId> {
        if let Some(&cached) = self.get(class).children.get(name) {
            return cached;
        }
        let found = self.find_child(class, name);
        self.classes[class.0 as usize]
            .children
            .insert(SmolStr::new(name), found);
        found
    }

    fn find_child(&mut self, class: ClassId, name: &str) -> Option<ClassId> {
        let entry = self.get(class);
        let nested = entry.nested_class(name);
        if let Some(def) = nested {
            let file = entry.file;
            return Some(self.add(ClassEntry::new(
                SmolStr::new(name),
                Some(class),
                Arc::new(def),
                file,
                None,
            )));
        }
        let location = entry.location.clone()?;
        self.load_child(Some(class), &location, name)
    }

    /// Loads `name` from the library folder `here`: `name/package.mo` or `name.mo`.
    fn load_child(
        &mut self,
        parent: Option<ClassId>,
        here: &LibLocation,
        name: &str,
    ) -> Option<ClassId> {
        let sub = here.join(name);
        let package_file = sub.file("package.mo");
        let (file_loc, location) = if self.provider.exists(&package_file) {
            (package_file, Some(sub))
        } else {
            let single = here.file(&format!("{name}.mo"));
            if !self.provider.exists(&single) {
                return None;
            }
            (single, None)
        };
        let text = match self.provider.read(&file_loc) {
            Ok(t) => t,
            Err(e) => {
                let path = self.provider.display(&file_loc).display().to_string();
                let reason = e.to_string();
                let error = crate::error::LibraryError::Unreadable { path, reason };
                self.diagnostics.push(error.into());
                return None;
            }
        };
        self.stats.library_files += 1;
        self.stats.library_bytes += text.len();
        let file = self.sources.add(self.provider.display(&file_loc), text);
        let parsed = unimo_syntax::parse(file, self.sources.get(file).text());
        self.diagnostics.extend(parsed.diagnostics);
        let def = parsed
            .ast
            .classes
            .into_iter()
            .find(|c| c.name.text == name)?;
        Some(self.add(ClassEntry::new(
            SmolStr::new(name),
            parent,
            Arc::new(def),
            file,
            location,
        )))
    }

    /// Names of the classes declared directly in `class` and in its package folder:
    /// candidates for "did you mean".
    pub fn child_names(&self, class: ClassId) -> Vec<String> {
        let entry = self.get(class);
        let mut names: Vec<String> = match &entry.def.body {
            unimo_syntax::ast::ClassBody::Long { composition, .. } => composition
                .elements
                .iter()
                .filter_map(|e| match &e.kind {
                    ElementKind::Class(c) => Some(c.name.text.to_string()),
                    ElementKind::Component(cc) => {
                        Some(cc.components.first()?.name.text.to_string())
                    }
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        };
        if let Some(loc) = &entry.location {
            names.extend(self.provider.list(loc));
        }
        names
    }

    /// The top-level classes of the user file `file` (files given on the command line
    /// without a `within` clause), in no particular order.
    pub fn user_top_classes_in(&self, file: FileId) -> Vec<ClassId> {
        let mut out: Vec<ClassId> = self
            .user_top
            .values()
            .flatten()
            .copied()
            .filter(|&c| self.get(c).file == file)
            .collect();
        out.sort_unstable();
        out
    }

    /// Names at the top level: user classes and library root entries.
    pub fn top_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.user_top.keys().map(|k| k.to_string()).collect();
        for root in 0..self.provider.roots() {
            names.extend(self.provider.list(&LibLocation {
                root,
                dir: String::new(),
            }));
        }
        names
    }
}
