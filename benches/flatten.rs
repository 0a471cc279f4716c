//! Flattening cost against model size: a chain of masses and springs joined through
//! connectors (2 components and 2 connections per link), 10^3 to 10^5 components.
//!
//! Run: `cargo bench --bench flatten`. Reports the median time per size; near-linear
//! growth means the time per component stays flat.

use divan::Bencher;
use std::fmt::Write;
use unimo_flat::{ClassTree, MemoryProvider};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    divan::main();
}

/// A chain with `components` components (masses + springs + one fixed end).
pub fn chain_source(components: usize) -> String {
    let links = components / 2;
    let mut s = String::from(
        "connector Flange\n  Real s;\n  flow Real f;\nend Flange;\n\
         model Mass\n  parameter Real m = 1;\n  Flange a, b;\n  Real s(start = 0, fixed = true), v(start = 0, fixed = true);\n\
         equation\n  a.s = s;\n  b.s = s;\n  der(s) = v;\n  m * der(v) = a.f + b.f;\nend Mass;\n\
         model Spring\n  parameter Real c = 1;\n  Flange a, b;\nequation\n  a.f = c * (a.s - b.s);\n  b.f = -a.f;\nend Spring;\n\
         model Fixed\n  Flange b;\nequation\n  b.s = 0;\nend Fixed;\n",
    );
    s.push_str("model Chain\n  Fixed fixed;\n");
    for i in 1..=links {
        let _ = writeln!(s, "  Spring s{i}(c = {i});\n  Mass m{i};");
    }
    s.push_str("equation\n  connect(fixed.b, s1.a);\n");
    for i in 1..=links {
        let _ = writeln!(s, "  connect(s{i}.b, m{i}.a);");
        if i < links {
            let _ = writeln!(s, "  connect(m{i}.b, s{}.a);", i + 1);
        }
    }
    s.push_str("end Chain;\n");
    s
}

fn flatten(text: &str) -> usize {
    let provider = MemoryProvider::new();
    let mut tree = ClassTree::new(&provider);
    let file = tree.sources.add("chain.mo", text.to_owned());
    let parsed = unimo_syntax::parse(file, text);
    let classes = tree.add_user_file(file, parsed.ast);
    let chain = *classes.last().unwrap();
    let (model, diags) = unimo_flat::flatten(&mut tree, chain);
    assert!(diags.is_empty(), "{diags:?}");
    let b = unimo_flat::balance::count(&model);
    assert_eq!(b.equations, b.unknowns);
    model.vars.len()
}

#[divan::bench(args = [1_000, 10_000, 100_000], sample_count = 3)]
fn parse_and_flatten_chain(bencher: Bencher, components: usize) {
    let text = chain_source(components);
    bencher.bench(|| flatten(divan::black_box(&text)));
}
