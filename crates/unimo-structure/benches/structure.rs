//! Structural pipeline on generated sparse systems of 1e3, 1e4 and 1e5 equations:
//! an index-0 chain, a chain of coupled index-3 pendulums, and many small algebraic loops.

use divan::Bencher;
use unimo_structure::{
    analyze, blt, maximum_matching, pantelides, select_dummy_derivatives, tear_blocks, EqId,
    IndexReductionSystem, StateSelectPriority, StructuralSystem, VarId,
};

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [1_000, 10_000, 100_000];

/// n equations: der(x_i) = y_i; y_i = g(x_i, y_{i-1}). Index 0, blocks of size one.
fn ode_chain(n: usize) -> StructuralSystem {
    let mut s = StructuralSystem::new();
    let mut previous: Option<VarId> = None;
    for _ in 0..n / 2 {
        let x = s.add_var("");
        let y = s.add_var("");
        let dx = s.derivative(x);
        s.add_eq("", &[dx, y]).unwrap();
        let mut row = vec![y, x];
        row.extend(previous);
        s.add_eq("", &row).unwrap();
        previous = Some(y);
    }
    s
}

/// n/5 Cartesian pendulums (index 3), each pulled by the previous one's rod force.
fn pendulum_chain(n: usize) -> StructuralSystem {
    let mut s = StructuralSystem::new();
    let mut previous_force: Option<VarId> = None;
    for _ in 0..n / 5 {
        let [x, y, vx, vy, f] = [(); 5].map(|_| s.add_var(""));
        let [dx, dy, dvx, dvy] = [x, y, vx, vy].map(|v| s.derivative(v));
        s.add_eq("", &[dx, vx]).unwrap();
        s.add_eq("", &[dy, vy]).unwrap();
        let mut row = vec![dvx, f, x];
        row.extend(previous_force);
        s.add_eq("", &row).unwrap();
        s.add_eq("", &[dvy, f, y]).unwrap();
        s.add_eq("", &[x, y]).unwrap();
        previous_force = Some(f);
    }
    s
}

/// Algebraic loops of sizes 2, 3, 4 in turn, each fed by the previous loop: about n
/// equations, each loop one block that tears to one iteration variable.
fn small_loops(n: usize) -> StructuralSystem {
    let mut s = StructuralSystem::new();
    let mut input: Option<VarId> = None;
    let mut made = 0;
    let mut size = 2;
    while made + size <= n {
        let ys: Vec<VarId> = (0..size).map(|_| s.add_var("")).collect();
        for i in 0..size {
            let mut row = vec![ys[i], ys[(i + 1) % size]];
            row.extend(input);
            s.add_eq("", &row).unwrap();
        }
        input = Some(ys[0]);
        made += size;
        size = if size == 4 { 2 } else { size + 1 };
    }
    s
}

fn default_priority(_: VarId) -> StateSelectPriority {
    StateSelectPriority::Default
}

fn all_solvable(_: EqId, _: VarId) -> bool {
    true
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn matching_ode_chain(bencher: Bencher, n: usize) {
    let s = ode_chain(n);
    bencher.bench_local(|| maximum_matching(s.graph()));
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn matching_small_loops(bencher: Bencher, n: usize) {
    let s = small_loops(n);
    bencher.bench_local(|| maximum_matching(s.graph()));
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn pantelides_pendulums(bencher: Bencher, n: usize) {
    bencher
        .with_inputs(|| pendulum_chain(n))
        .bench_local_values(|mut s| pantelides(&mut s).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn dummy_derivatives_pendulums(bencher: Bencher, n: usize) {
    let mut s = pendulum_chain(n);
    let reduced = pantelides(&mut s).unwrap();
    bencher
        .bench_local(|| select_dummy_derivatives(s.graph(), &reduced, default_priority).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn blt_and_tearing_small_loops(bencher: Bencher, n: usize) {
    let s = small_loops(n);
    let matching = maximum_matching(s.graph());
    bencher.bench_local(|| {
        let blocks = blt(s.graph(), &matching, |_| true).unwrap();
        tear_blocks(s.graph(), &blocks, all_solvable).unwrap()
    });
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn pipeline_ode_chain(bencher: Bencher, n: usize) {
    bencher
        .with_inputs(|| ode_chain(n))
        .bench_local_values(|mut s| analyze(&mut s, default_priority, all_solvable).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn pipeline_pendulums(bencher: Bencher, n: usize) {
    bencher
        .with_inputs(|| pendulum_chain(n))
        .bench_local_values(|mut s| analyze(&mut s, default_priority, all_solvable).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 10)]
fn pipeline_small_loops(bencher: Bencher, n: usize) {
    bencher
        .with_inputs(|| small_loops(n))
        .bench_local_values(|mut s| analyze(&mut s, default_priority, all_solvable).unwrap());
}
