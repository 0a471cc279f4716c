//! Flattening never panics: every class of every corpus file, and mutated copies of the
//! flatten suite, go through lookup, the name check, instantiation, connections and the
//! balance count; only diagnostics may come out.

use proptest::test_runner::{Config, RngSeed};
use std::path::PathBuf;
use unimo_flat::{ClassTree, MemoryProvider};

#[path = "../../../tests/common/corpus.rs"]
mod corpus_files;

fn corpus() -> Vec<String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    corpus_files::texts(
        &root,
        &[
            "tests/syntax/ok",
            "tests/syntax/err",
            "tests/flatten",
            "tests/names",
            "models",
        ],
    )
}

/// Flattens every class of `text` (errors allowed, panics not).
fn flatten_all(text: &str) {
    let provider = MemoryProvider::new();
    let mut tree = ClassTree::new(&provider);
    let file = tree.sources.add("t.mo", text.to_owned());
    let parsed = unimo_syntax::parse(file, text);
    let classes = tree.add_user_file(file, parsed.ast);
    for c in classes {
        let (model, _) = unimo_flat::flatten(&mut tree, c);
        let _ = unimo_flat::balance::count(&model);
        let _ = model.to_modelica();
    }
}

#[test]
fn every_corpus_class_flattens_without_panic() {
    let files = corpus();
    assert!(files.len() > 100);
    for text in &files {
        flatten_all(text);
    }
}

#[test]
fn mutated_models_flatten_without_panic() {
    let texts = corpus();
    const TOKENS: &str = "; ( ) [ ] { } = end model x 1 0 -1 n . , extends connect for loop if \
        then else parameter inner outer redeclare each Real Integer start fixed : der 1:3";
    // Each token inserted after a space.
    let tokens: Vec<String> = TOKENS.split_whitespace().map(|t| format!(" {t}")).collect();
    let tokens: Vec<&str> = tokens.iter().map(String::as_str).collect();
    // 300 cases from a fixed seed by default, so that a run is repeatable;
    // `UNIMO_STRESS_CASES=N` for a longer run and `UNIMO_STRESS_SEED=N|random` for
    // other cases (a failure prints its minimal edits).
    let cases = std::env::var("UNIMO_STRESS_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    let rng_seed = match std::env::var("UNIMO_STRESS_SEED").ok().as_deref() {
        Some("random") => RngSeed::Random,
        Some(n) => RngSeed::Fixed(n.parse().expect("UNIMO_STRESS_SEED: a number or `random`")),
        None => RngSeed::Fixed(20_261_126),
    };
    let config = Config {
        cases,
        rng_seed,
        failure_persistence: None,
        ..Config::default()
    };
    corpus_files::check_mutations(&texts, &tokens, 2, config, |text| {
        flatten_all(text);
        Ok(())
    });
}
