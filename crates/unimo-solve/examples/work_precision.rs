//! Work-precision table: ROBER, HIRES, VDPOL with BDF and Radau5 at rtol 1e-4 … 1e-10.
//! Prints scd (significant correct digits), steps and the median wall time of five runs.
//!
//! `cargo run -p unimo-solve --example work_precision --release`

#[path = "../tests/support/problems.rs"]
mod problems;

use std::time::Instant;

use problems::Benchmark;
use unimo_solve::Method;

fn row(benchmark: Benchmark, method: Method, rtol: f64) -> String {
    let mut times = Vec::with_capacity(5);
    let mut outcome = None;
    for _ in 0..5 {
        let start = Instant::now();
        outcome = Some(benchmark.run(method, rtol));
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let name = benchmark.reference().name;
    match outcome {
        Some(Ok((scd, stats))) => format!(
            "| {name} | {} | {rtol:.0e} | {:.2e} | {scd:.2} | {} | {} | {:.3} |",
            method.name(),
            benchmark.absolute_tolerance(rtol),
            stats.steps,
            stats.rejected_steps,
            times[2] * 1e3
        ),
        Some(Err(error)) => format!(
            "| {name} | {} | {rtol:.0e} | failed: {error} |",
            method.name()
        ),
        None => String::new(),
    }
}

fn main() {
    println!("| problem | method | rtol | atol | scd | steps | rejected | time [ms] |");
    println!("|---|---|---|---|---|---|---|---|");
    for benchmark in Benchmark::ALL {
        for method in [Method::Bdf, Method::Radau5] {
            for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
                println!("{}", row(benchmark, method, rtol));
            }
        }
    }
}
