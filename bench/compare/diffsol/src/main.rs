//! diffsol side of the unimo comparison: ROBER (DAE with a singular mass matrix),
//! HIRES, VDPOL, POLLU and BRUSS2D, with diffsol's BDF and its SDIRK methods (TR-BDF2,
//! ESDIRK34).
//!
//! The Jacobian is given analytically as a Jacobian-vector product (`rhs_implicit`).
//! ROBER, HIRES, VDPOL, POLLU: dense nalgebra matrices and diffsol's default dense LU
//! (`NalgebraLU`), diffsol assembling the dense Jacobian from the products. BRUSS2D
//! (2,048 unknowns): faer sparse matrices (`FaerSparseMat`) and faer's sparse LU
//! (`FaerSparseLU`); diffsol finds the sparsity pattern when the problem is built and
//! assembles the sparse Jacobian by column colouring. All solver options are diffsol's
//! defaults apart from rtol and a scalar atol.
//!
//! Usage: compare-diffsol [RUNS] [PROBLEM...]   (RUNS default 5; problems rober hires vdpol
//!        pollu bruss2d; BRUSS2D's reference is read from $BRUSS2D_REF, default
//!        bench/compare/refs/bruss2d.csv; $METHODS: a subset such as `bdf,esdirk34`)
//! Prints one tab-separated line per configuration:
//! problem tool method rtol atol scd steps median_ms status

use diffsol::{
    FaerSparseLU, FaerSparseMat, NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod,
    OdeSolverStopReason, Vector,
};
use std::time::Instant;

#[path = "../../../../crates/unimo-solve/tests/support/test_set.rs"]
mod test_set;
use test_set::{HIRES_REF, POLLU_K, POLLU_REACTANTS, POLLU_REF, POLLU_STOICH, POLLU_Y0};

type M = NalgebraMat<f64>;
type LS = NalgebraLU<f64>;
type SparseM = FaerSparseMat<f64>;
type SparseLS = FaerSparseLU<f64>;

const ROBER_REF: [f64; 3] = [
    2.083340149701255e-8,
    8.333360770334713e-14,
    0.9999999791665050,
];
const VDPOL_REF: [f64; 2] = [1.706167732170483, -0.8928097010247975];
const EPS: f64 = 1e-6;

fn scd(y: &[f64], r: &[f64]) -> f64 {
    let worst = y
        .iter()
        .zip(r)
        .map(|(a, b)| ((a - b) / b).abs())
        .fold(
            0.0f64,
            |m, e| if e.is_nan() { f64::INFINITY } else { m.max(e) },
        );
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
    s.set_stop_time(t_end)
        .map_err(|e| Failure(e.to_string(), 0))?;
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
    Ok((
        s.state().y.clone_as_vec(),
        s.get_statistics().number_of_steps,
    ))
}

/// Builds the problem and runs one method on it; the whole thing is what is timed.
macro_rules! solve_with {
    ($problem:expr, $method:expr, $t_end:expr) => {
        solve_with!($problem, $method, $t_end, LS)
    };
    ($problem:expr, $method:expr, $t_end:expr, $ls:ty) => {{
        let fail = |e: diffsol::DiffsolError| Failure(format!("{e} (while setting up)"), 0);
        let problem = $problem.map_err(fail)?;
        match $method {
            "bdf" => integrate(problem.bdf::<$ls>().map_err(fail)?, $t_end),
            "tr_bdf2" => integrate(problem.tr_bdf2::<$ls>().map_err(fail)?, $t_end),
            "esdirk34" => integrate(problem.esdirk34::<$ls>().map_err(fail)?, $t_end),
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
                test_set::hires_rhs(x, y);
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
                y.copy_from_slice(&test_set::HIRES_X0);
            },
            8,
        )
        .build();
    solve_with!(problem, method, test_set::HIRES_T_END)
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

// ---- POLLU (test set pollu.f): f = S r(y), r_k = k_k y_a (y_b) ------------------------
fn pollu(method: &str, rtol: f64, atol: f64) -> Result<(Vec<f64>, usize), Failure> {
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| {
                y.fill(0.0);
                for (k, &(a, b)) in POLLU_REACTANTS.iter().enumerate() {
                    let r = POLLU_K[k] * x[a] * b.map_or(1.0, |b| x[b]);
                    for &(i, s) in POLLU_STOICH[k] {
                        y[i] += s * r;
                    }
                }
            },
            |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| {
                y.fill(0.0);
                for (k, &(a, b)) in POLLU_REACTANTS.iter().enumerate() {
                    // d r_k = k (v_a x_b + x_a v_b), or k v_a for a first-order reaction
                    let dr = POLLU_K[k] * b.map_or(v[a], |b| v[a] * x[b] + x[a] * v[b]);
                    for &(i, s) in POLLU_STOICH[k] {
                        y[i] += s * dr;
                    }
                }
            },
        )
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&POLLU_Y0),
            20,
        )
        .build();
    solve_with!(problem, method, 60.0)
}

// ---- BRUSS2D: u, v on an N x N periodic grid; (u, v) of cell (i, j) at 2 (i N + j) ------
const BRUSS_N: usize = 32;
const BRUSS_ALPHA: f64 = 1.0;
const BRUSS_C: f64 = BRUSS_ALPHA * (BRUSS_N * BRUSS_N) as f64;

/// Index of u in cell (i, j), the indices wrapped around the periodic grid.
fn cell(i: isize, j: isize) -> usize {
    let n = BRUSS_N as isize;
    2 * ((i.rem_euclid(n) * n + j.rem_euclid(n)) as usize)
}

/// The five-point Laplacian of species `s` (0: u, 1: v) of `x` at cell (i, j).
fn laplacian(x: &[f64], i: isize, j: isize, s: usize) -> f64 {
    x[cell(i + 1, j) + s] + x[cell(i - 1, j) + s] + x[cell(i, j + 1) + s] + x[cell(i, j - 1) + s]
        - 4.0 * x[cell(i, j) + s]
}

fn bruss2d(method: &str, rtol: f64, atol: f64) -> Result<(Vec<f64>, usize), Failure> {
    let n = BRUSS_N as isize;
    let problem = OdeBuilder::<SparseM>::new()
        .rtol(rtol)
        .atol([atol])
        .rhs_implicit(
            move |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| {
                for i in 0..n {
                    for j in 0..n {
                        let k = cell(i, j);
                        let (u, v) = (x[k], x[k + 1]);
                        let uuv = u * u * v;
                        y[k] = 1.0 + uuv - 4.4 * u + BRUSS_C * laplacian(x, i, j, 0);
                        y[k + 1] = 3.4 * u - uuv + BRUSS_C * laplacian(x, i, j, 1);
                    }
                }
            },
            move |x: &[f64], _p: &[f64], _t: f64, w: &[f64], y: &mut [f64]| {
                for i in 0..n {
                    for j in 0..n {
                        let k = cell(i, j);
                        let (u, v, du, dv) = (x[k], x[k + 1], w[k], w[k + 1]);
                        let duuv = 2.0 * u * v * du + u * u * dv;
                        y[k] = duuv - 4.4 * du + BRUSS_C * laplacian(w, i, j, 0);
                        y[k + 1] = 3.4 * du - duuv + BRUSS_C * laplacian(w, i, j, 1);
                    }
                }
            },
        )
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| {
                for i in 0..n {
                    for j in 0..n {
                        let (gx, gy) = (i as f64 / n as f64, j as f64 / n as f64);
                        y[cell(i, j)] = 22.0 * gy * (1.0 - gy).powf(1.5);
                        y[cell(i, j) + 1] = 27.0 * gx * (1.0 - gx).powf(1.5);
                    }
                }
            },
            2 * BRUSS_N * BRUSS_N,
        )
        .build();
    solve_with!(problem, method, 11.5, SparseLS)
}

/// The reference row of a reference CSV (a header, then `t,y...`).
fn read_reference(path: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read the reference {path}: {e}"));
    let row = text.lines().nth(1).expect("a reference row");
    row.split(',')
        .skip(1)
        .map(|v| v.trim().parse().expect("a number"))
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let mut problems: Vec<&str> = args.iter().skip(1).map(String::as_str).collect();
    if problems.is_empty() {
        problems = vec!["rober", "hires", "vdpol", "pollu", "bruss2d"];
    }
    // METHODS: a comma-separated subset of bdf,tr_bdf2,esdirk34 (default: all three).
    let methods: Vec<String> = std::env::var("METHODS")
        .unwrap_or_else(|_| "bdf,tr_bdf2,esdirk34".into())
        .split(',')
        .map(str::to_owned)
        .collect();
    let bruss_path =
        std::env::var("BRUSS2D_REF").unwrap_or_else(|_| "bench/compare/refs/bruss2d.csv".into());
    let rtols = [1e-4, 1e-6, 1e-8, 1e-10];
    for problem in problems {
        let bruss_ref;
        let (name, factor, reference, f): (&str, f64, &[f64], fn(&str, f64, f64) -> _) =
            match problem {
                "rober" => ("ROBER", 1e-6, &ROBER_REF[..], rober),
                "hires" => ("HIRES", 1e-2, &HIRES_REF[..], hires),
                "vdpol" => ("VDPOL", 1e-2, &VDPOL_REF[..], vdpol),
                "pollu" => ("POLLU", 1.0, &POLLU_REF[..], pollu),
                "bruss2d" => {
                    bruss_ref = read_reference(&bruss_path);
                    ("BRUSS2D", 1e-2, &bruss_ref[..], bruss2d)
                }
                p => panic!("unknown problem {p}"),
            };
        for method in methods.iter().map(String::as_str) {
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
                        if y.len() <= 20 {
                            eprintln!("{name} diffsol {method} {rtol:.0e}: y = {y:?}");
                        } else {
                            let head = &y[..4];
                            eprintln!("{name} diffsol {method} {rtol:.0e}: y = {head:?} ... ({} values)", y.len());
                        }
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
