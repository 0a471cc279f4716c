//! Broadphase cost against the number of bodies: sweep and prune against all pairs on
//! a billiard-like layout (balls on a grid, a few touching).

use unimo_geometry::{Aabb, AllPairs, Broadphase, SweepAndPrune};

fn main() {
    divan::main();
}

fn layout(n: usize) -> Vec<Aabb> {
    let side = (n as f64).sqrt().ceil() as usize;
    (0..n)
        .map(|k| {
            let (x, y) = ((k % side) as f64 * 0.06, (k / side) as f64 * 0.06);
            Aabb {
                min: [x - 0.0286, y - 0.0286, -0.0286],
                max: [x + 0.0286, y + 0.0286, 0.0286],
            }
        })
        .collect()
}

#[divan::bench(args = [10, 100, 1000])]
fn sweep_and_prune(b: divan::Bencher, n: usize) {
    let boxes = layout(n);
    let mut sap = SweepAndPrune::default();
    let mut out = Vec::new();
    b.bench_local(|| sap.pairs(divan::black_box(&boxes), &mut out));
}

#[divan::bench(args = [10, 100, 1000])]
fn all_pairs(b: divan::Bencher, n: usize) {
    let boxes = layout(n);
    let mut ap = AllPairs::default();
    let mut out = Vec::new();
    b.bench_local(|| ap.pairs(divan::black_box(&boxes), &mut out));
}
