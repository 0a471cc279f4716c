//! Flattening tests: every model in `tests/flatten/ok` flattens (snapshot of the flat
//! Modelica), balances, and flattens again to the same text from its own output (the
//! round trip); every file in `tests/flatten/err` fails with the codes at the line:col
//! of `expected.txt` (snapshot of the diagnostics).

mod common;

use common::root;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn flatten(args: &[&Path]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["flatten", "--color", "never"])
        .args(args)
        .current_dir(root())
        .output()
        .unwrap();
    common::code_and_text(out)
}

#[test]
fn flatten_suite_round_trips() {
    let tmp = std::env::temp_dir().join(format!("unimo-flatten-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut n = 0;
    // The flatten suite and every bundled model; `flat_only` holds models that flatten
    // but are not meant to be analysed further (a loop of rigid links, statically
    // indeterminate in its torques: what it tests is the overconstrained-connection
    // pass of flattening), so `tests/names.rs` leaves them out of `unimo check`.
    for f in common::mo_files("tests/flatten/ok")
        .into_iter()
        .chain(common::mo_files("tests/flatten/flat_only"))
        .chain(common::mo_files("models"))
    {
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
    assert_eq!(manifest.len(), common::mo_files("tests/flatten/err").len());
    for (file, want) in &manifest {
        let rel = PathBuf::from(format!("tests/flatten/err/{file}"));
        let (code, _, stderr) = flatten(&[&rel]);
        assert_eq!(code, Some(1), "{file}: {stderr}");
        let got = common::rendered_codes(&stderr);
        assert_eq!(&got, want, "{file}:\n{stderr}");
        insta::assert_snapshot!(format!("flat_err_{}", file.trim_end_matches(".mo")), stderr);
    }
}

/// A chain of `links` springs and masses through connectors, with `extra` declarations
/// and `extra_eq` equations added to the top-level model (the scale benchmark's model).
fn chain_source(links: usize, extra: &str, extra_eq: &str) -> String {
    use std::fmt::Write;
    let mut s = String::from(
        "connector Flange\n  Real s;\n  flow Real f;\nend Flange;\n\
         connector Switch\n  Boolean s;\n  flow Real f;\nend Switch;\n\
         model Mass\n  parameter Real m = 1;\n  Flange a, b;\n  Real s(start = 0, fixed = true), v(start = 0, fixed = true);\n\
         equation\n  a.s = s;\n  b.s = s;\n  der(s) = v;\n  m * der(v) = a.f + b.f;\nend Mass;\n\
         model Spring\n  parameter Real c = 1;\n  Flange a, b;\nequation\n  a.f = c * (a.s - b.s);\n  b.f = -a.f;\nend Spring;\n\
         model Fixed\n  Flange b;\nequation\n  b.s = 0;\nend Fixed;\n",
    );
    s.push_str("model Chain\n  Fixed fixed;\n");
    s.push_str(extra);
    for i in 1..=links {
        let _ = writeln!(s, "  Spring s{i}(c = {i});\n  Mass m{i};");
    }
    s.push_str("equation\n  connect(fixed.b, s1.a);\n");
    s.push_str(extra_eq);
    for i in 1..=links {
        let _ = writeln!(s, "  connect(s{i}.b, m{i}.a);");
        if i < links {
            let _ = writeln!(s, "  connect(m{i}.b, s{}.a);", i + 1);
        }
    }
    s.push_str("end Chain;\n");
    s
}

/// Flattens `text` (its last class) in memory: the model and the diagnostic codes.
fn flatten_text(text: &str) -> (unimo_flat::FlatModel, Vec<String>) {
    let provider = unimo_flat::MemoryProvider::new();
    let mut tree = unimo_flat::ClassTree::new(&provider);
    let file = tree.sources.add("chain.mo", text.to_owned());
    let parsed = unimo_syntax::parse(file, text);
    assert!(!parsed.has_errors());
    let classes = tree.add_user_file(file, parsed.ast);
    let (model, diags) = unimo_flat::flatten(&mut tree, *classes.last().unwrap());
    let codes = diags.iter().map(|d| d.code.to_string()).collect();
    (model, codes)
}

/// Large models (past the size where the type check runs beside the connection
/// sets) are checked like small ones: a sound chain balances, a Boolean side of a
/// Real equation is `E2018`, a Boolean connected to a Real is `E2006`.
#[test]
fn large_models_are_checked_like_small_ones() {
    // 24,001 equations before the connections; 10 unknowns per link.
    let links = 4_000;
    let (model, codes) = flatten_text(&chain_source(links, "", ""));
    assert!(codes.is_empty(), "{codes:?}");
    let b = unimo_flat::balance::count(&model);
    assert_eq!((b.equations, b.unknowns), (10 * links + 2, 10 * links + 2));

    let (_, codes) = flatten_text(&chain_source(links, "  Boolean flag;\n", "  flag = 1.5;\n"));
    assert_eq!(codes, ["E2018"]);

    let (_, codes) = flatten_text(&chain_source(
        links,
        "  Switch sw;\n",
        "  connect(sw, m1.b);\n",
    ));
    assert_eq!(codes, ["E2006"]);
}
