//! Flattening tests: every model in `tests/flatten/ok` flattens (snapshot of the flat
//! Modelica), balances, and flattens again to the same text from its own output (the
//! round trip); every file in `tests/flatten/err` fails with the codes at the line:col
//! of `expected.txt` (snapshot of the diagnostics).

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn flatten(args: &[&Path]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["flatten", "--color", "never"])
        .args(args)
        .current_dir(root())
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn files(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mo"))
        .collect();
    v.sort();
    v
}

#[test]
fn flatten_suite_round_trips() {
    let tmp = std::env::temp_dir().join(format!("unimo-flatten-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut n = 0;
    // The flatten suite and every bundled model.
    for f in files("tests/flatten/ok").into_iter().chain(files("models")) {
        let rel = f.strip_prefix(root()).unwrap().to_path_buf();
        let (code, first, stderr) = flatten(&[&rel]);
        assert_eq!(code, Some(0), "{}: {stderr}", rel.display());
        let flat = tmp.join(rel.file_name().unwrap());
        std::fs::write(&flat, &first).unwrap();
        // The flat text stands alone: its functions, records and enumeration types
        // are printed with it.
        let (code, second, stderr) = flatten(&[&flat]);
        assert_eq!(code, Some(0), "{} (second pass): {stderr}", rel.display());
        assert_eq!(
            first,
            second,
            "{}: flattening the flat model changed it",
            rel.display()
        );
        let name = rel.file_stem().unwrap().to_string_lossy().to_string();
        insta::assert_snapshot!(format!("flat_{name}"), first);
        n += 1;
    }
    assert!(n >= 12);
    let _ = std::fs::remove_dir_all(&tmp);
}

fn expected() -> BTreeMap<String, Vec<String>> {
    common::manifest("tests/flatten/err/expected.txt")
}

#[test]
fn flatten_errors_name_the_problem() {
    let manifest = expected();
    assert_eq!(manifest.len(), files("tests/flatten/err").len());
    for (file, want) in &manifest {
        let rel = PathBuf::from(format!("tests/flatten/err/{file}"));
        let (code, _, stderr) = flatten(&[&rel]);
        assert_eq!(code, Some(1), "{file}: {stderr}");
        let got = common::rendered_codes(&stderr);
        assert_eq!(&got, want, "{file}:\n{stderr}");
        insta::assert_snapshot!(format!("flat_err_{}", file.trim_end_matches(".mo")), stderr);
    }
}
