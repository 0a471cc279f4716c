//! Name-resolution tests: `unimo check` on `tests/names/ok` must pass; each file in
//! `tests/names/err` must fail with the codes at the line:col listed in `expected.txt`,
//! and its rendered diagnostics (with "did you mean") are snapshot-tested.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn check(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .arg("check")
        .args(["--color", "never"])
        .args(args)
        .current_dir(root())
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn expected() -> BTreeMap<String, Vec<String>> {
    common::manifest("tests/names/err/expected.txt")
}

#[test]
fn valid_names_resolve() {
    let (code, stderr) = check(&["tests/names/ok", "stdlib", "models", "tests/flatten/ok"]);
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn unknown_names_are_reported_where_they_are() {
    let manifest = expected();
    assert!(manifest.len() >= 10);
    for (file, want) in &manifest {
        let rel = format!("tests/names/err/{file}");
        let (code, stderr) = check(&[&rel]);
        assert_eq!(code, Some(1), "{file}: {stderr}");
        let got = common::rendered_codes(&stderr);
        assert_eq!(&got, want, "{file}:\n{stderr}");
        insta::assert_snapshot!(format!("names_{}", file.trim_end_matches(".mo")), stderr);
    }
}

/// The library is read lazily: checking one model reads only the packages it names.
#[test]
fn library_is_loaded_lazily() {
    let (code, stderr) = check(&["--stats", "tests/names/ok/enumerations_and_functions.mo"]);
    assert_eq!(code, Some(0), "{stderr}");
    let loaded: usize = stderr
        .split_whitespace()
        .find_map(|w| w.strip_prefix("library_files_loaded="))
        .and_then(|n| n.parse().ok())
        .expect("stats line");
    let total = 48;
    assert!(
        loaded > 0 && loaded < total / 4,
        "loaded {loaded} library files\n{stderr}"
    );
}

/// `--lib DIR` and `UNIMO_PATH` add library roots searched before the bundled library.
#[test]
fn library_roots_from_flag_and_environment() {
    let tmp = std::env::temp_dir().join(format!("unimo-lib-{}", std::process::id()));
    let lib = tmp.join("lib");
    std::fs::create_dir_all(lib.join("Extra")).unwrap();
    std::fs::write(
        lib.join("Extra/package.mo"),
        "within;\npackage Extra\n  model Decay\n    Real x(start = 1, fixed = true);\n  equation\n    der(x) = -x;\n  end Decay;\nend Extra;\n",
    )
    .unwrap();
    let user = tmp.join("user.mo");
    std::fs::write(&user, "model User\n  Extra.Decay d;\nend User;\n").unwrap();
    let user_s = user.to_string_lossy().to_string();
    let lib_s = lib.to_string_lossy().to_string();

    let (code, stderr) = check(&[&user_s]);
    assert_eq!(code, Some(1), "without the library: {stderr}");
    assert!(stderr.contains("E2001"), "{stderr}");

    let (code, stderr) = check(&["--lib", &lib_s, &user_s]);
    assert_eq!(code, Some(0), "with --lib: {stderr}");

    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["check", "--color", "never", &user_s])
        .env("UNIMO_PATH", &lib_s)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "with UNIMO_PATH: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&tmp);
}
