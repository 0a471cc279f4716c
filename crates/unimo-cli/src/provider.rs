//! Library roots for the flattener: `--lib` folders, then `UNIMO_PATH` folders, then
//! the standard library embedded in the binary.

use std::path::{Path, PathBuf};
use unimo_flat::{LibFile, LibLocation, SourceProvider};

pub struct CliProvider {
    disk: Vec<PathBuf>,
}

impl CliProvider {
    /// `--lib` folders first, then `UNIMO_PATH` (separated like `PATH`).
    pub fn new(libs: &[PathBuf]) -> CliProvider {
        let mut disk: Vec<PathBuf> = libs.to_vec();
        if let Some(p) = std::env::var_os("UNIMO_PATH") {
            disk.extend(std::env::split_paths(&p).filter(|p| !p.as_os_str().is_empty()));
        }
        CliProvider { disk }
    }

    fn path(&self, root: usize, rel: &str) -> Option<PathBuf> {
        self.disk.get(root).map(|d| d.join(rel))
    }

    fn embedded(&self, root: usize) -> bool {
        root == self.disk.len()
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
        if self.embedded(file.root) {
            return unimo_stdlib::file(&file.path).is_some();
        }
        self.path(file.root, &file.path)
            .is_some_and(|p| p.is_file())
    }

    fn read(&self, file: &LibFile) -> Result<String, String> {
        if self.embedded(file.root) {
            return unimo_stdlib::file(&file.path)
                .map(str::to_owned)
                .ok_or_else(|| "not in the embedded library".to_owned());
        }
        let p = self.path(file.root, &file.path).ok_or("no such root")?;
        std::fs::read_to_string(&p).map_err(|e| e.to_string())
    }

    fn list(&self, dir: &LibLocation) -> Vec<String> {
        if self.embedded(dir.root) {
            let prefix = if dir.dir.is_empty() {
                String::new()
            } else {
                format!("{}/", dir.dir)
            };
            let mut names: Vec<String> = unimo_stdlib::FILES
                .iter()
                .filter_map(|(p, _)| p.strip_prefix(prefix.as_str()))
                .filter_map(|rest| match rest.split_once('/') {
                    Some((d, "package.mo")) => Some(d.to_owned()),
                    None if rest != "package.mo" => rest.strip_suffix(".mo").map(str::to_owned),
                    _ => None,
                })
                .collect();
            names.sort();
            names.dedup();
            return names;
        }
        self.path(dir.root, &dir.dir)
            .map(|p| list_dir(&p))
            .unwrap_or_default()
    }

    fn display(&self, file: &LibFile) -> PathBuf {
        if self.embedded(file.root) {
            return PathBuf::from("<stdlib>").join(&file.path);
        }
        self.path(file.root, &file.path).unwrap_or_default()
    }
}
