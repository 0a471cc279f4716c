//! The Modelica files of the repository's test corpus and their random mutations, shared
//! by the tests that feed mutated models to the parsers and to flattening
//! (`tests/fast_path.rs`, `crates/unimo-flat/tests/never_panics.rs`, which include this
//! file by path).
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// Every `.mo` file below `dir`, sorted, appended to `out`.
pub fn files_below(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            files_below(&e, out);
        } else if e.extension().is_some_and(|x| x == "mo") {
            out.push(e);
        }
    }
}

/// The `.mo` files below the folders `dirs` of `root`.
pub fn files(root: &Path, dirs: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for d in dirs {
        files_below(&root.join(d), &mut out);
    }
    out
}

/// `text` after `edits`, in order: each `(at, insert, delete)` moves `at` (modulo the
/// length) back to a character boundary, then deletes the `delete_len` bytes there
/// (widened to a boundary) when `delete`, else inserts `insert`.
pub fn mutate(text: &str, edits: &[(usize, &str, bool)], delete_len: usize) -> String {
    let mut text = text.to_owned();
    for &(at, insert, delete) in edits {
        let mut at = at % text.len().max(1);
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        if delete {
            let mut end = (at + delete_len).min(text.len());
            while !text.is_char_boundary(end) {
                end += 1;
            }
            text.replace_range(at..end, "");
        } else {
            text.insert_str(at, insert);
        }
    }
    text
}
