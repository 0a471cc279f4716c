//! Parse throughput on a large generated file (>= 10 MB of realistic Modelica).
//!
//! Run: `cargo bench --bench parse`. divan prints the median time and MB/s.

use divan::counter::BytesCount;
use divan::Bencher;
use std::fmt::Write;
use unimo_source::FileId;

/// The same allocator as the `unimo` binary, so the figures are what users get.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    divan::main();
}

/// One class of about 1.3 kB exercising declarations, modifiers, equations, `when`,
/// `for`, `if`, algorithms and expressions; repeated with distinct names.
fn generated_source(min_bytes: usize) -> String {
    let mut s = String::with_capacity(min_bytes + 4096);
    s.push_str("within Bench;\n");
    let mut i = 0;
    while s.len() < min_bytes {
        let _ = write!(
            s,
            r#"model Body{i} "generated body {i}"
  import SI = Modelica.SIunits;
  parameter Real m(min = 0, unit = "kg") = 1.5 "mass";
  parameter Real k[3] = {{1.0, 2.5e-3, .5}};
  parameter Integer n = 3;
  SI.Position r[3](each start = 0, each fixed = true);
  SI.Velocity v[3](start = {{0.05, 0, 0}});
  Real q[4](start = {{1, 0, 0, 0}}), omega[3];
  Boolean contact(start = false);
  discrete Integer count(start = 0);
equation
  der(r) = v;
  m * der(v) = -k .* v + {{0, -9.81 * m, 0}};
  der(q) = 0.5 * {{-q[2] * omega[1] - q[3] * omega[2] - q[4] * omega[3],
                  q[1] * omega[1] + q[3] * omega[3] - q[4] * omega[2],
                  q[1] * omega[2] - q[2] * omega[3] + q[4] * omega[1],
                  q[1] * omega[3] + q[2] * omega[2] - q[3] * omega[1]}};
  for j in 1:n loop
    der(omega[j]) = if contact and j > 1 then -omega[j] / (1 + abs(r[2])) else 0;
  end for;
  contact = r[2] < 0.1 and not pre(contact);
  when r[2] < 0 then
    reinit(v[2], -0.8 * pre(v[2]));
    count = pre(count) + 1;
  end when;
  annotation(experiment(StopTime = 10, Tolerance = 1e-6));
end Body{i};

"#
        );
        i += 1;
    }
    s
}

#[divan::bench(sample_count = 10)]
fn parse_10mb(bencher: Bencher) {
    let text = generated_source(10 << 20);
    bencher.counter(BytesCount::of_str(&text)).bench(|| {
        let parsed = unimo_syntax::parse(FileId(0), divan::black_box(&text));
        assert!(parsed.diagnostics.is_empty());
        parsed
    });
}

#[divan::bench(sample_count = 10)]
fn scan_only_10mb(bencher: Bencher) {
    let text = generated_source(10 << 20);
    bencher.counter(BytesCount::of_str(&text)).bench(|| {
        unimo_syntax::lexer::scan(divan::black_box(&text))
            .tokens
            .len()
    });
}

#[divan::bench(sample_count = 10)]
fn parse_without_validation_10mb(bencher: Bencher) {
    let text = generated_source(10 << 20);
    bencher.counter(BytesCount::of_str(&text)).bench(|| {
        unimo_syntax::differential::fast_only_unvalidated(FileId(0), divan::black_box(&text))
            .map(|p| p.ast.classes.len())
    });
}

/// The pest grammar alone (what the fast path saves), on 1 MiB: same input shape.
#[divan::bench(sample_count = 5)]
fn pest_only_1mb(bencher: Bencher) {
    let text = generated_source(1 << 20);
    bencher.counter(BytesCount::of_str(&text)).bench(|| {
        unimo_syntax::differential::pest_only(FileId(0), divan::black_box(&text))
            .ast
            .classes
            .len()
    });
}

/// The fast path alone on the same 1 MiB, for the ratio against pest in one run.
#[divan::bench(sample_count = 5)]
fn fast_only_1mb(bencher: Bencher) {
    let text = generated_source(1 << 20);
    bencher.counter(BytesCount::of_str(&text)).bench(|| {
        unimo_syntax::differential::fast_only(FileId(0), divan::black_box(&text))
            .map(|p| p.ast.classes.len())
    });
}
