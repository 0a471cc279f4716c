//! diffsol side of the unimo comparison: ROBER (DAE with a singular mass matrix),
//! HIRES and VDPOL, with diffsol's BDF and its SDIRK methods (TR-BDF2, ESDIRK34).
//!
//! Dense nalgebra matrices and diffsol's default dense LU (`NalgebraLU`); the
//! Jacobian is given analytically as a Jacobian-vector product (`rhs_implicit`),
//! from which diffsol assembles the dense Jacobian. All solver options are
//! diffsol's defaults apart from rtol and a scalar atol.
//!
//! Usage: compare-diffsol [RUNS] [PROBLEM...]   (RUNS default 5; problems rober hires vdpol)
//! Prints one tab-separated line per configuration:
//! problem tool method rtol atol scd steps median_ms status

use diffsol::{
    NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector,
};
use std::time::Instant;

type M = NalgebraMat<f64>;
type LS = NalgebraLU<f64>;

const ROBER_REF: [f64; 3] = [2.083340149701255e-8, 8.333360770334713e-14, 0.9999999791665050];
const HIRES_REF: [f64; 8] = [
    7.371312573325668e-4,
    1.442485726316185e-4,
    5.888729740967575e-5,
    1.175651343283149e-3,
    2.386356198831331e-3,
    6.238968252742796e-3,
    2.849998395185769e-3,
    2.850001604814231e-3,
];
const VDPOL_REF: [f64; 2] = [1.706167732170483, -0.8928097010247975];
const EPS: f64 = 1e-6;

fn scd(y: &[f64], r: &[f64]) -> f64 {
    let worst = y
        .iter()
        .zip(r)
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(0.0f64, |m, e| if e.is_nan() { f64::INFINITY } else { m.max(e) });
    -worst.log10()
}

/// A failed solve: the message and the steps taken before it.
struct Failure(String, usize);

/// Steps `s` to `t_end` without storing output; returns (y(t_end), steps).
fn integrate<'a, Eqn, S>(mut s: S, t_end: f64) -> Result<(Vec<f64>, usize), Failure>
where
    Eqn: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    s.set_stop_time(t_end).map_err(|e| Failure(e.to_string(), 0))?;
    loop {
        match s.step() {
            Ok(OdeSolverStopReason::TstopReached) => break,
            Ok(OdeSolverStopReason::InternalTimestep) => {}
            Ok(OdeSolverStopReason::RootFound(..)) => {
                return Err(Failure("unexpected root".into(), 0))
            }
            Err(e) => {
                let steps = s.get_statistics().number_of_steps;
                return Err(Failure(format!("{e} (t = {:e})", s.state().t), steps));
            }
        }
    }
    Ok((s.state().y.clone_as_vec(), s.get_statistics().number_of_steps))
}

/// Builds the problem and runs one method on it; the whole thing is what is timed.
macro_rules! solve_with {
    ($problem:expr, $method:expr, $t_end:expr) => {{
        let fail = |e: diffsol::DiffsolError| Failure(format!("{e} (while setting up)"), 0);
        let problem = $problem.map_err(fail)?;
        match $method {
            "bdf" => integrate(problem.bdf::<LS>().map_err(fail)?, $t_end),
            "tr_bdf2" => integrate(problem.tr_bdf2::<LS>().map_err(fail)?, $t_end),
            "esdirk34" => integrate(problem.esdirk34::<LS>().map_err(fail)?, $t_end),
            m => Err(Failure(format!("unknown method {m}"), 0)),
        }
    }};
}

fn rober(method: &str, rtol: f64, atol: f64) -> Result<(Vec<f64>, usize), Failure> {
    // y1' = -k1 y1 + k3 y2 y3, y2' = k1 y1 - k3 y2 y3 - k2 y2^2, 0 = y1 + y2 + y3 - 1
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| {
                y[0] = -0.04 * x[0] + 1e4 * x[1] * x[2];
                y[1] = 0.04 * x[0] - 1e4 * x[1] * x[2] - 3e7 * x[1] * x[1];
                y[2] = x[0] + x[1] + x[2] - 1.0;
            },
            |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| {
                y[0] = -0.04 * v[0] + 1e4 * (v[1] * x[2] + x[1] * v[2]);
                y[1] = 0.04 * v[0] - 1e4 * (v[1] * x[2] + x[1] * v[2]) - 6e7 * x[1] * v[1];
                y[2] = v[0] + v[1] + v[2];
            },
        )
        .mass(|x: &[f64], _p: &[f64], _t: f64, beta: f64, y: &mut [f64]| {
            y[0] = x[0] + beta * y[0];
            y[1] = x[1] + beta * y[1];
            y[2] = beta * y[2];
        })
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| {
                y[0] = 1.0;
                y[1] = 0.0;
                y[2] = 0.0;
            },
            3,
        )
        .build();
    solve_with!(problem, method, 1e11)
}

fn hires(method: &str, rtol: f64, atol: f64) -> Result<(Vec<f64>, usize), Failure> {
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| {
                y[0] = -1.71 * x[0] + 0.43 * x[1] + 8.32 * x[2] + 0.0007;
                y[1] = 1.71 * x[0] - 8.75 * x[1];
                y[2] = -10.03 * x[2] + 0.43 * x[3] + 0.035 * x[4];
                y[3] = 8.32 * x[1] + 1.71 * x[2] - 1.12 * x[3];
                y[4] = -1.745 * x[4] + 0.43 * x[5] + 0.43 * x[6];
                y[5] = -280.0 * x[5] * x[7] + 0.69 * x[3] + 1.71 * x[4] - 0.43 * x[5]
                    + 0.69 * x[6];
                y[6] = 280.0 * x[5] * x[7] - 1.81 * x[6];
                y[7] = -280.0 * x[5] * x[7] + 1.81 * x[6];
            },
            |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| {
                let d = 280.0 * (v[5] * x[7] + x[5] * v[7]);
                y[0] = -1.71 * v[0] + 0.43 * v[1] + 8.32 * v[2];
                y[1] = 1.71 * v[0] - 8.75 * v[1];
                y[2] = -10.03 * v[2] + 0.43 * v[3] + 0.035 * v[4];
                y[3] = 8.32 * v[1] + 1.71 * v[2] - 1.12 * v[3];
                y[4] = -1.745 * v[4] + 0.43 * v[5] + 0.43 * v[6];
                y[5] = -d + 0.69 * v[3] + 1.71 * v[4] - 0.43 * v[5] + 0.69 * v[6];
                y[6] = d - 1.81 * v[6];
                y[7] = -d + 1.81 * v[6];
            },
        )
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| {
                y.fill(0.0);
                y[0] = 1.0;
                y[7] = 0.0057;
            },
            8,
        )
        .build();
    solve_with!(problem, method, 321.8122)
}

fn vdpol(method: &str, rtol: f64, atol: f64) -> Result<(Vec<f64>, usize), Failure> {
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| {
                y[0] = x[1];
                y[1] = ((1.0 - x[0] * x[0]) * x[1] - x[0]) / EPS;
            },
            |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| {
                y[0] = v[1];
                y[1] = ((-2.0 * x[0] * x[1] - 1.0) * v[0] + (1.0 - x[0] * x[0]) * v[1]) / EPS;
            },
        )
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| {
                y[0] = 2.0;
                y[1] = 0.0;
            },
            2,
        )
        .build();
    solve_with!(problem, method, 2.0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let mut problems: Vec<&str> = args.iter().skip(1).map(String::as_str).collect();
    if problems.is_empty() {
        problems = vec!["rober", "hires", "vdpol"];
    }
    let rtols = [1e-4, 1e-6, 1e-8, 1e-10];
    for problem in problems {
        let (name, factor, reference, f): (&str, f64, &[f64], fn(&str, f64, f64) -> _) =
            match problem {
                "rober" => ("ROBER", 1e-6, &ROBER_REF[..], rober),
                "hires" => ("HIRES", 1e-2, &HIRES_REF[..], hires),
                "vdpol" => ("VDPOL", 1e-2, &VDPOL_REF[..], vdpol),
                p => panic!("unknown problem {p}"),
            };
        for method in ["bdf", "tr_bdf2", "esdirk34"] {
            for rtol in rtols {
                let atol = rtol * factor;
                let mut times = Vec::new();
                let mut last = None;
                for _ in 0..runs.max(1) {
                    let t0 = Instant::now();
                    let r = f(method, rtol, atol);
                    times.push(t0.elapsed().as_secs_f64() * 1e3);
                    last = Some(r);
                }
                times.sort_by(f64::total_cmp);
                let median = times[times.len() / 2];
                match last.unwrap() {
                    Ok((y, steps)) => {
                        eprintln!("{name} diffsol {method} {rtol:.0e}: y = {y:?}");
                        println!(
                            "{name}\tdiffsol\t{method}\t{rtol:.0e}\t{atol:.0e}\t{:.2}\t{steps}\t{median:.3}\tok",
                            scd(&y, reference)
                        );
                    }
                    Err(Failure(e, steps)) => println!(
                        "{name}\tdiffsol\t{method}\t{rtol:.0e}\t{atol:.0e}\t-\t{steps}\t{median:.3}\tFAILED: {e}"
                    ),
                }
            }
        }
    }
}
