//! The crates' layering (docs/ARCHITECTURE.md): each crate depends only on crates of
//! earlier pipeline stages, so there is no import circle, and the stages that must stay
//! apart do (the compiler never depends on the runtime, the solvers and the geometry on
//! nothing of the compiler, the reference on nothing but the solvers).

use std::collections::BTreeMap;
use std::path::Path;

/// The workspace crates in pipeline order: a crate may depend on crates listed before it.
const ORDER: &[&str] = &[
    "unimo-source",
    "unimo-builtins",
    "unimo-stdlib",
    "unimo-structure",
    "unimo-solve",
    "unimo-geometry",
    "unimo-reference",
    "unimo-syntax",
    "unimo-flat",
    "unimo-dae",
    "unimo-codegen",
    "unimo-runtime",
    "unimo-fmi",
    "unimo-cli",
    "unimo-python",
];

/// Dependencies each crate must never have, whatever the order allows.
const FORBIDDEN: &[(&str, &[&str])] = &[
    // Compilation never runs a tape: the runtime's types reach it only as opaque
    // pointers and the interpreter entry its caller passes.
    (
        "unimo-codegen",
        &["unimo-runtime", "unimo-solve", "unimo-geometry"],
    ),
    // The solvers know systems, not models.
    (
        "unimo-solve",
        &["unimo-dae", "unimo-flat", "unimo-syntax", "unimo-codegen"],
    ),
    // A defect of the compiler or the library cannot hide in both sides of the
    // cross-check.
    (
        "unimo-reference",
        &["unimo-dae", "unimo-flat", "unimo-codegen", "unimo-runtime"],
    ),
];

/// The `unimo-*` crates under `[dependencies]` of a manifest (not dev-dependencies).
fn dependencies(manifest: &str) -> Vec<String> {
    let mut in_deps = false;
    let mut out = Vec::new();
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            in_deps = line == "[dependencies]";
            continue;
        }
        if in_deps && line.starts_with("unimo-") {
            let name = line
                .split(|c: char| c == '.' || c == '=' || c.is_whitespace())
                .next()
                .unwrap_or_default();
            out.push(name.to_string());
        }
    }
    out
}

fn workspace_dependencies() -> BTreeMap<String, Vec<String>> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates");
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(&crates).expect("crates/") {
        let dir = entry.expect("entry").path();
        let manifest = dir.join("Cargo.toml");
        let Ok(text) = std::fs::read_to_string(&manifest) else {
            continue;
        };
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        out.insert(name, dependencies(&text));
    }
    out
}

#[test]
fn every_crate_depends_only_on_earlier_stages() {
    let deps = workspace_dependencies();
    let rank = |name: &str| ORDER.iter().position(|&c| c == name);
    let mut problems = Vec::new();
    for (krate, ds) in &deps {
        let Some(own) = rank(krate) else {
            problems.push(format!(
                "{krate} is not placed in the pipeline order of tests/layers.rs"
            ));
            continue;
        };
        for d in ds {
            match rank(d) {
                Some(r) if r < own => {}
                _ => problems.push(format!(
                    "{krate} depends on {d}, a later (or unknown) stage"
                )),
            }
        }
    }
    assert!(
        problems.is_empty(),
        "layering broken:\n{}",
        problems.join("\n")
    );
}

#[test]
fn stages_that_must_stay_apart_do() {
    let deps = workspace_dependencies();
    for (krate, forbidden) in FORBIDDEN {
        let ds = deps.get(*krate).unwrap_or_else(|| panic!("{krate} exists"));
        for f in *forbidden {
            assert!(!ds.iter().any(|d| d == f), "{krate} must not depend on {f}");
        }
    }
    // The compiler's own manifest is read, not an empty one.
    assert_eq!(deps["unimo-codegen"], ["unimo-dae"]);
}

#[test]
fn the_manifest_reader_sees_dependencies_only() {
    let manifest = "[package]\nname = \"x\"\n[dependencies]\nunimo-dae.workspace = true\n\
                    unimo-solve = { path = \"../s\" }\nthiserror.workspace = true\n\
                    [dev-dependencies]\nunimo-runtime.workspace = true\n";
    assert_eq!(dependencies(manifest), ["unimo-dae", "unimo-solve"]);
}
