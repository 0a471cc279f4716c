//! Work-precision benchmark: ROBER, HIRES and VDPOL with BDF and Radau5 at four tolerances.
//! The matching accuracy table comes from `examples/work_precision.rs`.

#[path = "../tests/support/problems.rs"]
mod problems;

use problems::Benchmark;
use unimo_solve::Method;

fn main() {
    divan::main();
}

const TOLERANCES: [f64; 4] = [1e-4, 1e-6, 1e-8, 1e-10];

fn solve(benchmark: Benchmark, method: Method, rtol: f64) {
    let result = benchmark.run(method, divan::black_box(rtol));
    divan::black_box(result.map(|(scd, stats)| (scd, stats.steps)).ok());
}

#[divan::bench(args = TOLERANCES)]
fn rober_bdf(rtol: f64) {
    solve(Benchmark::Rober, Method::Bdf, rtol);
}

#[divan::bench(args = TOLERANCES)]
fn rober_radau5(rtol: f64) {
    solve(Benchmark::Rober, Method::Radau5, rtol);
}

#[divan::bench(args = TOLERANCES)]
fn hires_bdf(rtol: f64) {
    solve(Benchmark::Hires, Method::Bdf, rtol);
}

#[divan::bench(args = TOLERANCES)]
fn hires_radau5(rtol: f64) {
    solve(Benchmark::Hires, Method::Radau5, rtol);
}

#[divan::bench(args = TOLERANCES)]
fn vdpol_bdf(rtol: f64) {
    solve(Benchmark::VanDerPol, Method::Bdf, rtol);
}

#[divan::bench(args = TOLERANCES)]
fn vdpol_radau5(rtol: f64) {
    solve(Benchmark::VanDerPol, Method::Radau5, rtol);
}
