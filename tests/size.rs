//! Size limits of the crates' code: no source file over 1,000 lines and no function
//! over 100 (from its `fn` line to its closing brace, as rustfmt lays it out). The
//! crates in `ENFORCED` meet them and must keep meeting them; the others are listed
//! with their excess (`cargo test --test size -- --nocapture`) until they are split.

use std::path::{Path, PathBuf};

mod common;

const MAX_FILE_LINES: usize = 1000;
const MAX_FN_LINES: usize = 100;

/// The crates held to the limits.
const ENFORCED: &[&str] = &[
    "unimo-builtins",
    "unimo-cli",
    "unimo-codegen",
    "unimo-dae",
    "unimo-fmi",
    "unimo-flat",
    "unimo-geometry",
    "unimo-python",
    "unimo-reference",
    "unimo-runtime",
    "unimo-solve",
    "unimo-source",
    "unimo-stdlib",
    "unimo-structure",
    "unimo-syntax",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The functions of a file longer than the limit: (line, length).
fn long_functions(text: &str) -> Vec<(usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, l) in lines.iter().enumerate() {
        let body = l.trim_start();
        let indent = &l[..l.len() - body.len()];
        let rest = body
            .strip_prefix("pub(crate) ")
            .or_else(|| body.strip_prefix("pub(super) "))
            .or_else(|| body.strip_prefix("pub "))
            .unwrap_or(body);
        let rest = rest.strip_prefix("const ").unwrap_or(rest);
        if !rest.starts_with("fn ") || l.trim_end().ends_with(';') {
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(j) = (i + 1..lines.len()).find(|&j| lines[j] == close) {
            let n = j - i + 1;
            if n > MAX_FN_LINES {
                out.push((i + 1, n));
            }
        }
    }
    out
}

/// Every excess in one crate, as text.
fn excesses(krate: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(&krate.join("src"), &mut files);
    files.sort();
    let mut out = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let n = text.lines().count();
        if n > MAX_FILE_LINES {
            out.push(format!("{}: {n} lines", f.display()));
        }
        for (line, len) in long_functions(&text) {
            out.push(format!("{}:{line}: a function of {len} lines", f.display()));
        }
    }
    out
}

#[test]
fn files_and_functions_stay_within_the_limits() {
    let crates = common::root().join("crates");
    let mut failures = Vec::new();
    let mut names: Vec<String> = std::fs::read_dir(&crates)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    for name in names {
        let found = excesses(&crates.join(&name));
        if ENFORCED.contains(&name.as_str()) {
            failures.extend(found);
        } else if !found.is_empty() {
            eprintln!("{name} (not enforced yet): {} excesses", found.len());
            for f in found {
                eprintln!("  {f}");
            }
        }
    }
    assert!(
        failures.is_empty(),
        "over the limits:\n{}",
        failures.join("\n")
    );
}

#[test]
fn the_function_counter_sees_long_functions() {
    let mut text = String::from("fn short() {\n}\n    pub fn long() {\n");
    for _ in 0..MAX_FN_LINES {
        text.push_str("        x();\n");
    }
    text.push_str("    }\nfn decl();\n");
    assert_eq!(long_functions(&text), vec![(3, MAX_FN_LINES + 2)]);
}
