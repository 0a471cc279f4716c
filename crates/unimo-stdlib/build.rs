//! Embeds every file under the workspace's `stdlib/` folder, so that the library is
//! always present whatever the working directory of the `unimo` binary.

use std::fmt::Write;
use std::path::{Path, PathBuf};

fn walk(dir: &Path, base: &Path, out: &mut Vec<(String, PathBuf)>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            walk(&e, base, out);
        } else if e.extension().is_some_and(|x| x == "mo") {
            let rel = e
                .strip_prefix(base)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push((rel, e));
        }
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let stdlib = manifest
        .join("../../stdlib")
        .canonicalize()
        .expect("stdlib/ next to crates/");
    println!("cargo:rerun-if-changed={}", stdlib.display());
    let mut files = Vec::new();
    walk(&stdlib, &stdlib, &mut files);
    let mut code = String::from("/// `(path relative to stdlib/, contents)` of every `.mo` file.\npub static FILES: &[(&str, &str)] = &[\n");
    for (rel, abs) in &files {
        println!("cargo:rerun-if-changed={}", abs.display());
        let _ = writeln!(
            code,
            "    ({rel:?}, include_str!({:?})),",
            abs.display().to_string()
        );
    }
    code.push_str("];\n");
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("files.rs");
    std::fs::write(out, code).unwrap();
}
