//! The Modelica files of the repository's test corpus and their random mutations, shared
//! by the tests that feed mutated models to the parsers and to flattening
//! (`tests/fast_path.rs`, `crates/unimo-flat/tests/never_panics.rs`, which include this
//! file by path).
#![allow(dead_code)]

use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
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

/// The texts of the `.mo` files below the folders `dirs` of `root`.
pub fn texts(root: &Path, dirs: &[&str]) -> Vec<String> {
    files(root, dirs)
        .iter()
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect()
}

/// Runs `check` on the random mutations of `texts` that `config` asks for: a text and
/// one to three edits, each at a random place, inserting one of `tokens` or deleting
/// `delete_len` bytes ([`mutate`]). A failure panics with its smallest edits.
pub fn check_mutations(
    texts: &[String],
    tokens: &[&str],
    delete_len: usize,
    config: Config,
    check: impl Fn(&str) -> Result<(), TestCaseError>,
) {
    let strategy = (
        0..texts.len(),
        proptest::collection::vec((any::<usize>(), 0..tokens.len(), any::<bool>()), 1..4),
    );
    TestRunner::new(config)
        .run(&strategy, |(which, edits)| {
            let edits: Vec<_> = edits
                .into_iter()
                .map(|(at, token, delete)| (at, tokens[token], delete))
                .collect();
            check(&mutate(&texts[which], &edits, delete_len))
        })
        .unwrap();
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
