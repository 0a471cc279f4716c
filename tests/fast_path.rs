//! Differential tests: the hand-written fast path and the pest grammar must build the
//! same tree and the same diagnostics wherever the fast path answers, and the fast path
//! must answer on every valid file we ship.

use std::path::PathBuf;
use unimo_source::FileId;
use unimo_syntax::differential::{fast_only, pest_only};

#[path = "common/corpus.rs"]
mod corpus_files;

/// The first place two trees differ, as pretty-printed Debug lines with context.
fn first_difference<T: std::fmt::Debug>(a: &T, b: &T) -> Option<String> {
    let (a, b) = (format!("{a:#?}"), format!("{b:#?}"));
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let i = la
        .iter()
        .zip(&lb)
        .position(|(x, y)| x != y)
        .or_else(|| (la.len() != lb.len()).then(|| la.len().min(lb.len())))?;
    let from = i.saturating_sub(12);
    Some(format!(
        "fast:\n{}\npest:\n{}",
        la[from..(i + 3).min(la.len())].join("\n"),
        lb[from..(i + 3).min(lb.len())].join("\n")
    ))
}

fn corpus(dirs: &[&str]) -> Vec<PathBuf> {
    corpus_files::files(&PathBuf::from(env!("CARGO_MANIFEST_DIR")), dirs)
}

#[test]
fn fast_path_answers_and_agrees_on_every_valid_file() {
    let files = corpus(&["tests/syntax/ok", "stdlib", "models"]);
    assert!(files.len() > 50);
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let fast = fast_only(FileId(0), &text)
            .unwrap_or_else(|| panic!("fast path declined {}", f.display()));
        let pest = pest_only(FileId(0), &text);
        if let Some(d) = first_difference(&fast.ast, &pest.ast) {
            panic!("{}: trees differ\n{d}", f.display());
        }
        assert_eq!(fast.diagnostics, pest.diagnostics, "{}", f.display());
    }
}

#[test]
fn fast_path_agrees_or_declines_on_every_error_file() {
    let mut answered = 0;
    for f in corpus(&["tests/syntax/err"]) {
        let text = std::fs::read_to_string(&f).unwrap();
        if let Some(fast) = fast_only(FileId(0), &text) {
            let pest = pest_only(FileId(0), &text);
            assert_eq!(fast.ast, pest.ast, "{}", f.display());
            assert_eq!(fast.diagnostics, pest.diagnostics, "{}", f.display());
            answered += 1;
        }
    }
    // The files with only post-parse errors (validation) parse fine and must be answered.
    assert!(
        answered >= 25,
        "fast path answered only {answered} error files"
    );
}

/// Mutations of every valid corpus file: wherever the fast path answers, it agrees.
#[test]
fn fast_path_agrees_on_mutated_files() {
    use proptest::prelude::*;
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let texts = corpus_files::texts(&root, &["tests/syntax/ok", "stdlib"]);
    // Whitespace-separated, then a space and a newline as tokens of their own.
    const TOKENS: &str = "; ( ) [ ] { } = := end model when if then . , loop for - + * ^ .* : \
        not and x 1 2.5 \"s\" der initial annotation each final redeclare replaceable elseif \
        else equation algorithm protected";
    let tokens: Vec<&str> = TOKENS.split_whitespace().chain([" ", "\n"]).collect();
    let config = proptest::test_runner::Config {
        cases: 400,
        ..Default::default()
    };
    corpus_files::check_mutations(&texts, &tokens, 3, config, |text| {
        if let Some(fast) = fast_only(FileId(0), text) {
            let pest = pest_only(FileId(0), text);
            if let Some(d) = first_difference(&fast.ast, &pest.ast) {
                prop_assert!(false, "trees differ on text:\n{}\n{}", text, d);
            }
            prop_assert_eq!(&fast.diagnostics, &pest.diagnostics, "text:\n{}", text);
        }
        Ok(())
    });
}

/// The Modelica Standard Library beside the project (`../shared/msl`, test data, not
/// part of the repository): the fast path answers on every one of its files, and where
/// it answers it builds pest's tree.
#[test]
fn fast_path_answers_and_agrees_on_the_msl() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/msl");
    assert!(
        root.is_dir(),
        "the MSL test data is missing: expected MSL 4.1.0 at {}",
        root.display()
    );
    let mut files = Vec::new();
    corpus_files::files_below(&root, &mut files);
    assert!(files.len() > 2500, "only {} MSL files", files.len());
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let fast = fast_only(FileId(0), &text)
            .unwrap_or_else(|| panic!("fast path declined {}", f.display()));
        assert!(
            fast.diagnostics.is_empty(),
            "{}: {:?}",
            f.display(),
            fast.diagnostics
        );
        let pest = pest_only(FileId(0), &text);
        if fast.ast != pest.ast {
            let d = first_difference(&fast.ast, &pest.ast).unwrap_or_default();
            panic!("{}: trees differ\n{d}", f.display());
        }
    }
}
