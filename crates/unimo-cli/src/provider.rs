//! Library roots for the flattener: `--lib` folders, then the folders of the standard
//! `MODELICAPATH` variable, then `UNIMO_PATH` folders, then the standard library
//! embedded in the binary. A top-level package is taken whole from the first root that
//! has it, so a user's `Modelica` library always wins over the bundled subset, and the
//! two never mix.

use std::path::{Path, PathBuf};
use unimo_flat::{LibFile, LibLocation, MemoryProvider, SourceProvider};

pub struct CliProvider {
    disk: Vec<PathBuf>,
    /// The embedded `stdlib/`, as the last root.
    embedded: MemoryProvider,
}

impl CliProvider {
    /// `--lib` folders first, then `MODELICAPATH` and `UNIMO_PATH` (each separated like
    /// `PATH`).
    pub fn new(libs: &[PathBuf]) -> CliProvider {
        let mut disk: Vec<PathBuf> = libs.to_vec();
        for var in ["MODELICAPATH", "UNIMO_PATH"] {
            if let Some(p) = std::env::var_os(var) {
                disk.extend(std::env::split_paths(&p).filter(|p| !p.as_os_str().is_empty()));
            }
        }
        let embedded = MemoryProvider::new().with_root(
            "<stdlib>",
            unimo_stdlib::FILES
                .iter()
                .map(|(p, t)| (p.to_string(), t.to_string())),
        );
        CliProvider { disk, embedded }
    }

    fn path(&self, root: usize, rel: &str) -> Option<PathBuf> {
        self.disk.get(root).map(|d| d.join(rel))
    }

    /// The same file or folder in the embedded provider, if `root` is the embedded one.
    fn embedded_root(&self, root: usize) -> Option<usize> {
        (root == self.disk.len()).then_some(0)
    }
}

fn list_dir(dir: &Path) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .filter_map(|e| {
                    let p = e.path();
                    let name = p.file_name()?.to_string_lossy().to_string();
                    if p.is_dir() && p.join("package.mo").is_file() {
                        Some(name)
                    } else if name != "package.mo" {
                        name.strip_suffix(".mo").map(str::to_owned)
                    } else {
                        None
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

impl SourceProvider for CliProvider {
    fn roots(&self) -> usize {
        self.disk.len() + 1
    }

    fn exists(&self, file: &LibFile) -> bool {
        match self.embedded_root(file.root) {
            Some(root) => self.embedded.exists(&LibFile {
                root,
                ..file.clone()
            }),
            None => self
                .path(file.root, &file.path)
                .is_some_and(|p| p.is_file()),
        }
    }

    fn read(&self, file: &LibFile) -> Result<String, String> {
        match self.embedded_root(file.root) {
            Some(root) => self.embedded.read(&LibFile {
                root,
                ..file.clone()
            }),
            None => {
                let p = self.path(file.root, &file.path).ok_or("no such root")?;
                std::fs::read_to_string(&p).map_err(|e| e.to_string())
            }
        }
    }

    fn list(&self, dir: &LibLocation) -> Vec<String> {
        match self.embedded_root(dir.root) {
            Some(root) => self.embedded.list(&LibLocation {
                root,
                ..dir.clone()
            }),
            None => self
                .path(dir.root, &dir.dir)
                .map(|p| list_dir(&p))
                .unwrap_or_default(),
        }
    }

    fn display(&self, file: &LibFile) -> PathBuf {
        match self.embedded_root(file.root) {
            Some(root) => self.embedded.display(&LibFile {
                root,
                ..file.clone()
            }),
            None => self.path(file.root, &file.path).unwrap_or_default(),
        }
    }
}
