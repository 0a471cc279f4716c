//! Where library files come from. The flattener never reads files itself: the caller
//! (the CLI, or a test) hands it a [`SourceProvider`] over library roots.

use std::path::PathBuf;

/// A folder inside one library root (`dir` relative to the root, `/`-separated).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct LibLocation {
    pub root: usize,
    pub dir: String,
}

impl LibLocation {
    /// The subfolder `name`.
    pub fn join(&self, name: &str) -> LibLocation {
        LibLocation {
            root: self.root,
            dir: self.rel(name),
        }
    }

    /// The file `name` in this folder.
    pub fn file(&self, name: &str) -> LibFile {
        LibFile {
            root: self.root,
            path: self.rel(name),
        }
    }

    fn rel(&self, name: &str) -> String {
        if self.dir.is_empty() {
            name.to_owned()
        } else {
            format!("{}/{name}", self.dir)
        }
    }
}

/// A file inside one library root.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct LibFile {
    pub root: usize,
    pub path: String,
}

/// Library roots, in lookup order (earlier roots shadow later ones).
pub trait SourceProvider {
    fn roots(&self) -> usize;
    fn exists(&self, file: &LibFile) -> bool;
    fn read(&self, file: &LibFile) -> Result<String, String>;
    /// Class names available in a folder (`Name/package.mo` folders and `Name.mo` files).
    fn list(&self, dir: &LibLocation) -> Vec<String>;
    /// How to name the file in diagnostics.
    fn display(&self, file: &LibFile) -> PathBuf;
}

/// A provider over in-memory files (`root`, `path`, `text`): the embedded standard
/// library, and tests.
pub struct MemoryProvider {
    /// Per root: its display prefix and its files.
    roots: Vec<(String, Vec<(String, String)>)>,
}

impl MemoryProvider {
    pub fn new() -> MemoryProvider {
        MemoryProvider { roots: Vec::new() }
    }

    /// Adds a root named `prefix` (shown in diagnostics) with `(path, text)` files.
    pub fn with_root(
        mut self,
        prefix: &str,
        files: impl IntoIterator<Item = (String, String)>,
    ) -> MemoryProvider {
        self.roots
            .push((prefix.to_owned(), files.into_iter().collect()));
        self
    }
}

impl Default for MemoryProvider {
    fn default() -> Self {
        MemoryProvider::new()
    }
}

impl SourceProvider for MemoryProvider {
    fn roots(&self) -> usize {
        self.roots.len()
    }

    fn exists(&self, file: &LibFile) -> bool {
        self.roots
            .get(file.root)
            .is_some_and(|(_, fs)| fs.iter().any(|(p, _)| *p == file.path))
    }

    fn read(&self, file: &LibFile) -> Result<String, String> {
        self.roots
            .get(file.root)
            .and_then(|(_, fs)| fs.iter().find(|(p, _)| *p == file.path))
            .map(|(_, t)| t.clone())
            .ok_or_else(|| "no such file".to_owned())
    }

    fn list(&self, dir: &LibLocation) -> Vec<String> {
        let Some((_, files)) = self.roots.get(dir.root) else {
            return Vec::new();
        };
        let prefix = if dir.dir.is_empty() {
            String::new()
        } else {
            format!("{}/", dir.dir)
        };
        let mut names: Vec<String> = files
            .iter()
            .filter_map(|(p, _)| p.strip_prefix(&prefix))
            .filter_map(|rest| match rest.split_once('/') {
                Some((d, "package.mo")) => Some(d.to_owned()),
                None if rest != "package.mo" => rest.strip_suffix(".mo").map(str::to_owned),
                _ => None,
            })
            .collect();
        names.sort();
        names.dedup();
        names
    }

    fn display(&self, file: &LibFile) -> PathBuf {
        let prefix = self.roots.get(file.root).map_or("", |(p, _)| p.as_str());
        PathBuf::from(prefix).join(&file.path)
    }
}
