//! Property tests: the parser returns (tree, diagnostics) for any input, never panics,
//! and every diagnostic's span lies inside the text.

use proptest::prelude::*;
use unimo_source::FileId;

const SEED_MODEL: &str = r#"within Lib;
model Ball "bouncing ball"
  parameter Real e(min = 0, max = 1) = 0.8 "restitution";
  Real h(start = 10, fixed = true), v;
  Real a[3] = {1, 2.5e-3, .5};
equation
  der(h) = v;
  der(v) = -9.81;
  when h < 0 and not initial() then
    reinit(v, -e * pre(v));
  elsewhen sample(0, 0.1) then
    assert(h > -1, "fell through");
  end when;
  for i in 1:3 loop
    if i > 1 then a[i] = a[i - 1] ^ 2; else a[i] = 1; end if;
  end for;
algorithm
  (x, y) := f(a[2:end], k = {j for j in 1:2});
  while x > 0 loop x := x - 1; break; end while;
end Ball;
"#;

const TOKENS: &[&str] = &[
    ";", "(", ")", "[", "]", "{", "}", "=", ":=", "end", "model", "when", "if", "then", "\"", "'",
    "/*", "*/", "//", "\n", "der", "1e", ".", ",", "loop", "for", "elsewhen", "\\",
];

fn check(text: &str) {
    let parsed = unimo_syntax::parse(FileId(0), text);
    for d in &parsed.diagnostics {
        for l in &d.labels {
            assert!(l.span.end as usize <= text.len(), "span past end: {d:?}");
            assert!(l.span.start <= l.span.end);
        }
    }
    // Dumping must not panic either.
    let source = unimo_source::SourceFile::new("x.mo", text);
    let _ = unimo_syntax::dump::dump(&parsed.ast, &source);
}

#[derive(Debug, Clone)]
enum Edit {
    Delete(usize, usize),
    Insert(usize, usize),
    Swap(usize, usize),
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut s: Vec<char> = text.chars().collect();
    for e in edits {
        let n = s.len().max(1);
        match *e {
            Edit::Delete(at, len) => {
                let at = at % n;
                let end = (at + len % 8).min(s.len());
                s.drain(at.min(s.len())..end);
            }
            Edit::Insert(at, tok) => {
                let at = (at % n).min(s.len());
                let t: Vec<char> = TOKENS[tok % TOKENS.len()].chars().collect();
                s.splice(at..at, t);
            }
            Edit::Swap(a, b) => {
                if !s.is_empty() {
                    let (a, b) = (a % s.len(), b % s.len());
                    s.swap(a, b);
                }
            }
        }
    }
    s.into_iter().collect()
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Delete(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Insert(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Swap(a, b)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_token_soup_never_panics(toks in proptest::collection::vec(0usize..TOKENS.len(), 0..80)) {
        let text: String = toks.iter().map(|&i| TOKENS[i]).collect::<Vec<_>>().join(" ");
        check(&text);
    }

    #[test]
    fn mutated_models_never_panic(edits in proptest::collection::vec(edit(), 1..6)) {
        check(&apply(SEED_MODEL, &edits));
    }
}

#[test]
fn seed_model_is_valid() {
    let parsed = unimo_syntax::parse(FileId(0), SEED_MODEL);
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
}

#[test]
fn deep_nesting_is_refused_not_overflowed() {
    for text in [
        format!(
            "model A Real x = {}1{}; end A;",
            "(".repeat(100_000),
            ")".repeat(100_000)
        ),
        format!(
            "model A Real x = {}1; end A;",
            "if true then 1 else ".repeat(50_000)
        ),
        format!("model A Real x = {}1; end A;", "-".repeat(100_000)),
        format!("model A Real x = {}1; end A;", "not ".repeat(100_000)),
        format!("model A Real x = 1{}; end A;", " + 1".repeat(100_000)),
        format!("model A Real x = 1{}; end A;", " ^ 2".repeat(100_000)),
    ] {
        let parsed = unimo_syntax::parse(FileId(0), &text);
        assert!(parsed.has_errors(), "{}...", &text[..40]);
    }
}
