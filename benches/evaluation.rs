//! Compiled evaluation against hand-written Rust: right-hand-side evaluations of ROBER,
//! HIRES and a 1,000-state chain, through the runtime's register tape, through native
//! code compiled from the tapes with Cranelift (`unimo-codegen`) and as plain Rust
//! functions, measured in one run (`cargo bench --bench evaluation`). A model of one
//! state and one negation (`tiny`) measures the fixed cost of a call.
//!
//! Both sides compute the same thing: the hand-written functions take the time and the
//! states and write the derivatives, called through a function pointer (not inlined
//! into the loop), as the evaluator's native code is; the same arithmetic, except
//! where the compiler orders it differently (ROBER's `y3 = -((y1 + y2) + -1)`).

use std::path::PathBuf;
use unimo_runtime::eval::RhsEvaluator;
use unimo_runtime::native::execute_shim;

#[path = "../crates/unimo-solve/tests/support/test_set.rs"]
mod test_set;

fn main() {
    divan::main();
}

fn model(file: &str) -> unimo_cli::LoadedModel {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(file);
    unimo_cli::load_model(&[path], None).expect("model compiles")
}

fn chain_file(n: usize) -> PathBuf {
    let path = std::env::temp_dir().join(format!("unimo-bench-chain-{n}.mo"));
    let text = format!(
        "model Chain\n  parameter Integer n = {n};\n  Real x[n](each start = 1, each fixed = true);\nequation\n  der(x[1]) = -x[1];\n  for i in 2:n loop\n    der(x[i]) = x[i-1] - 2*x[i] + 0.5*sin(x[i]);\n  end for;\nend Chain;\n"
    );
    std::fs::write(&path, text).expect("temp file");
    path
}

fn tiny_file() -> PathBuf {
    let path = std::env::temp_dir().join("unimo-bench-tiny.mo");
    let text =
        "model Tiny\n  Real x(start = 1, fixed = true);\nequation\n  der(x) = -x;\nend Tiny;\n";
    std::fs::write(&path, text).expect("temp file");
    path
}

/// A hand-written right-hand side.
type Rhs = fn(f64, &[f64], &mut [f64]);

fn tiny_hand(_t: f64, x: &[f64], f: &mut [f64]) {
    f[0] = -x[0];
}

fn rober_hand(_t: f64, y: &[f64], f: &mut [f64]) {
    // y3 = 1 - y1 - y2 (the algebraic equation, solved)
    let y3 = 1.0 - y[0] - y[1];
    f[0] = -0.04 * y[0] + 1e4 * y[1] * y3;
    f[1] = 0.04 * y[0] - 1e4 * y[1] * y3 - 3e7 * y[1] * y[1];
}

fn hires_hand(_t: f64, y: &[f64], f: &mut [f64]) {
    test_set::hires_rhs(y, f);
}

fn chain_hand(_t: f64, x: &[f64], f: &mut [f64]) {
    f[0] = -x[0];
    for i in 1..x.len() {
        f[i] = x[i - 1] - 2.0 * x[i] + 0.5 * x[i].sin();
    }
}

fn state(n: usize) -> Vec<f64> {
    (0..n).map(|k| 0.3 + 0.01 * k as f64).collect()
}

fn load(which: &str) -> unimo_cli::LoadedModel {
    match which {
        "rober" => model("models/Robertson.mo"),
        "hires" => model("models/Hires.mo"),
        "tiny" => unimo_cli::load_model(&[tiny_file()], None).expect("tiny"),
        _ => unimo_cli::load_model(&[chain_file(1000)], None).expect("chain"),
    }
}

#[divan::bench(args = ["tiny", "rober", "hires", "chain1000"])]
fn native(bencher: divan::Bencher, which: &str) {
    let mut m = load(which);
    let options = unimo_codegen::NativeOptions::default();
    let stats =
        unimo_codegen::compile_model(&mut m.compiled, &options, execute_shim).expect("native code");
    assert!(stats.functions > 0);
    bench_rhs(bencher, &m);
}

/// One evaluation of the right-hand side of `m` at t = 1 and the test state.
fn bench_rhs(bencher: divan::Bencher, m: &unimo_cli::LoadedModel) {
    let mut ev = RhsEvaluator::new(&m.compiled);
    let n = m.compiled.states.len();
    let x = state(n);
    let mut out = vec![0.0; n];
    bencher.bench_local(|| {
        ev.rhs(1.0, divan::black_box(&x), &mut out)
            .expect("evaluates");
        divan::black_box(&out);
    });
}

/// Native compilation of the model's hot tapes (the cost `--engine native` adds).
#[divan::bench(args = ["rober", "hires", "chain1000"], sample_count = 10)]
fn native_compile(bencher: divan::Bencher, which: &str) {
    let m = load(which);
    let options = unimo_codegen::NativeOptions::default();
    bencher
        .with_inputs(|| m.compiled.clone())
        .bench_local_values(|mut c| {
            unimo_codegen::compile_model(&mut c, &options, execute_shim).map(|_| c)
        });
}

#[divan::bench(args = ["tiny", "rober", "hires", "chain1000"])]
fn compiled(bencher: divan::Bencher, which: &str) {
    let m = load(which);
    bench_rhs(bencher, &m);
}

#[divan::bench(args = ["tiny", "rober", "hires", "chain1000"])]
fn hand_written(bencher: divan::Bencher, which: &str) {
    let (f, n): (Rhs, usize) = match which {
        "rober" => (rober_hand, 2),
        "hires" => (hires_hand, 8),
        "tiny" => (tiny_hand, 1),
        _ => (chain_hand, 1000),
    };
    let x = state(n);
    let mut out = vec![0.0; n];
    bencher.bench_local(|| {
        f(1.0, divan::black_box(&x), &mut out);
        divan::black_box(&out);
    });
}
