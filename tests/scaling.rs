//! The sparse path of large models (issue #23 point 5), checked by counters, never by
//! time: the chain of `bench/scaling/gen_chain.py` with a Newton block per state gets a
//! structural Jacobian pattern (bidiagonal), column-coloured differences and the sparse
//! LU, and its results agree with an explicit method's. Small sparse models take the
//! scheduled LU, and its refusals of diagonal pivots the dense one.

use std::path::PathBuf;
use unimo_runtime::sim::{jacobian_pattern, simulate, Overrides, SimOptions, SimResult};
use unimo_solve::{LinearSolverKind, Method};

#[path = "../crates/unimo-solve/tests/support/test_set.rs"]
mod test_set;

/// The chain with `y[i] + 0.1*sin(y[i]) = x[i]` (a scalar nonlinear block per state),
/// as `gen_chain.py N newton` writes it.
fn newton_chain(n: usize) -> PathBuf {
    let m = (n / 5).max(1);
    let text = format!(
        "model Chain\n  parameter Integer n = {n};\n  parameter Integer m = {m};\n  Real x[n](each start = 1, each fixed = true);\n  Real y[n];\n  Real w[m];\nequation\n  der(x[1]) = -x[1];\n  for i in 1:n loop\n    y[i] + 0.1*sin(y[i]) = x[i];\n  end for;\n  for i in 2:n loop\n    der(x[i]) = y[i-1] - 2*x[i] + 0.5*y[i];\n  end for;\n  for k in 1:m loop\n    w[k] = x[5*k - 4] + y[5*k - 4];\n  end for;\nend Chain;\n"
    );
    let path =
        std::env::temp_dir().join(format!("unimo-scaling-chain-{n}-{}.mo", std::process::id()));
    std::fs::write(&path, text).expect("temp file");
    path
}

fn load(n: usize) -> unimo_cli::LoadedModel {
    load_path(newton_chain(n))
}

/// Loads a model file and removes it.
fn load_path(path: PathBuf) -> unimo_cli::LoadedModel {
    let m = unimo_cli::load_model(std::slice::from_ref(&path), None).expect("model compiles");
    let _ = std::fs::remove_file(path);
    m
}

fn run(m: &unimo_cli::LoadedModel, method: Method, rtol: f64) -> SimResult {
    run_to(m, method, 1.0, (rtol, rtol * 1e-2))
}

fn run_to(
    m: &unimo_cli::LoadedModel,
    method: Method,
    stop: f64,
    (rtol, atol): (f64, f64),
) -> SimResult {
    let overrides = Overrides {
        stop: Some(stop),
        rtol: Some(rtol),
        atol: Some(atol),
        points: Some(10),
        ..Overrides::default()
    };
    let o = SimOptions::resolve(&Default::default(), &overrides, method, false).expect("options");
    let r = simulate(&m.compiled, &o);
    assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
    r
}

#[test]
fn newton_chain_of_2000_states_takes_the_sparse_path() {
    let n = 2000;
    let m = load(n);
    assert!(m.compiled.jacobian.is_none(), "the plan has Newton blocks");
    assert_eq!(m.compiled.states.len(), n);
    let r = run(&m, Method::Bdf, 1e-6);
    let s = &r.stats;
    assert_eq!(s.jacobian_nonzeros, Some(2 * n - 1), "bidiagonal pattern");
    assert!(s.sparse_lu);
    // Coloured differences: 2 evaluations per Jacobian (a bidiagonal needs two colours)
    // instead of one per state.
    let per_step = s.solver.steps + s.solver.newton_iterations + 10;
    assert!(
        s.solver.rhs_evals <= per_step + 2 * s.solver.jacobian_evals,
        "{:?}",
        s.solver
    );
}

#[test]
fn structural_pattern_holds_every_nonzero_of_the_difference_jacobian() {
    let n = 30;
    let m = load(n);
    let pattern = jacobian_pattern(&m.compiled).expect("a structural pattern");
    assert_eq!(pattern.nonzeros(), 2 * n - 1);
    let mut ev = unimo_runtime::eval::RhsEvaluator::new(&m.compiled);
    let x: Vec<f64> = (0..n).map(|k| 0.3 + 0.05 * k as f64).collect();
    let (mut f0, mut f1) = (vec![0.0; n], vec![0.0; n]);
    ev.rhs(0.0, &x, &mut f0).expect("evaluates");
    for j in 0..n {
        let mut xp = x.clone();
        xp[j] += 1e-6;
        ev.rhs(0.0, &xp, &mut f1).expect("evaluates");
        for i in 0..n {
            let d = (f1[i] - f0[i]) / 1e-6;
            if d.abs() > 1e-6 {
                assert!(pattern.column(j).contains(&i), "d f{i} / d x{j} = {d}");
            }
        }
    }
}

#[test]
fn sparse_path_agrees_with_an_explicit_method() {
    // 150 states: above the sparse LU's threshold of 100.
    let m = load(150);
    let reference = run(&m, Method::Dopri5, 1e-11);
    for method in [Method::Bdf, Method::Radau5] {
        let r = run(&m, method, 1e-8);
        assert!(r.stats.sparse_lu);
        let (a, b) = (&r.final_states, &reference.final_states);
        let worst = a
            .iter()
            .zip(b)
            .map(|(p, q)| (p - q).abs() / q.abs().max(1e-3))
            .fold(0.0, f64::max);
        assert!(worst < 1e-5, "{method:?}: relative difference {worst:e}");
    }
}

/// `Simulator::on_row_only` (what `unimo simulate` uses when it streams a CSV): the
/// sink gets, bit for bit, the rows a plain run keeps (each output row re-solves the
/// Newton blocks), and the result keeps their times but no second copy of the rows.
#[test]
fn streamed_rows_of_the_newton_chain_equal_the_kept_ones() {
    let m = load(40);
    let kept = run(&m, Method::Radau5, 1e-6);
    let o = SimOptions {
        start: 0.0,
        stop: 1.0,
        rtol: 1e-6,
        atol: 1e-8,
        method: Method::Radau5,
        interval: 0.1,
        every_step: false,
        output_rtol: 0.0,
    };
    let mut streamed: Vec<(f64, Vec<f64>)> = Vec::new();
    let r = unimo_runtime::sim::Simulator::new(&m.compiled)
        .on_row_only(Box::new(|t, row| streamed.push((t, row.to_vec()))))
        .run(&o);
    assert!(r.error.is_none());
    assert!(r.rows.is_empty(), "the rows went to the sink only");
    assert_eq!(r.times, kept.times);
    assert_eq!(streamed.len(), kept.rows.len());
    for ((t, row), (kt, krow)) in streamed.iter().zip(kept.times.iter().zip(&kept.rows)) {
        assert_eq!(t.to_bits(), kt.to_bits());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(row), bits(krow), "row at t = {t}");
    }
}

/// POLLU (20 states, 82 Jacobian entries) is factored by the scheduled sparse LU (106
/// multiply-adds a factorization against the dense LU's 2,660), without a refused pivot,
/// and reaches the test set's reference as the dense LU did (`crates/unimo-solve`'s
/// `pollu_radau5`: 3, 4 and 6 digits at rtol 1e-4, 1e-6, 1e-8).
#[test]
fn pollu_takes_the_scheduled_lu_and_reaches_the_reference() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models/Pollu.mo");
    let m = unimo_cli::load_model(std::slice::from_ref(&path), None).expect("Pollu compiles");
    for method in [Method::Bdf, Method::Radau5] {
        for (rtol, digits) in [(1e-4, 3.0), (1e-6, 4.0), (1e-8, 6.0)] {
            let r = run_to(&m, method, test_set::POLLU_T_END, (rtol, rtol));
            assert_eq!(
                r.stats.linear_solver,
                Some(LinearSolverKind::Scheduled { refused: false })
            );
            let worst = r
                .final_states
                .iter()
                .zip(&test_set::POLLU_REF)
                .map(|(y, reference)| ((y - reference) / reference).abs())
                .fold(0.0, f64::max);
            assert!(
                -worst.log10() >= digits,
                "{method:?} rtol {rtol:e}: {:.2} digits",
                -worst.log10()
            );
        }
    }
}

/// Ten copies of `x' = y, y' = -1e6 (x + y)`: after the fast transient `y = -x` and `x`
/// decays at rate 1, the steps grow, and `x`'s diagonal pivot (the method's shift, of the
/// order of `1/h`) falls below 1e-3 of the `1e6` under it: the scheduled LU refuses it
/// and the dense LU with partial pivoting factors the matrices. The result is the
/// closed form's.
#[test]
fn refused_diagonal_pivots_fall_back_to_partial_pivoting() {
    let path = std::env::temp_dir().join(format!("unimo-refusals-{}.mo", std::process::id()));
    std::fs::write(
        &path,
        "model Refusals\n  Real x[10](each start = 1, each fixed = true);\n  Real y[10](each start = 0, each fixed = true);\nequation\n  for i in 1:10 loop\n    der(x[i]) = y[i];\n    der(y[i]) = -1e6*x[i] - 1e6*y[i];\n  end for;\nend Refusals;\n",
    )
    .expect("temp file");
    let m = load_path(path);
    // s^2 + 1e6 s + 1e6 = 0; x(0) = 1, x'(0) = y(0) = 0.
    let disc = (1e12f64 - 4e6).sqrt();
    let (slow, fast) = ((-1e6 + disc) / 2.0, (-1e6 - disc) / 2.0);
    let exact = |t: f64| (fast * (slow * t).exp() - slow * (fast * t).exp()) / (fast - slow);
    for method in [Method::Bdf, Method::Radau5] {
        let r = run_to(&m, method, 2.0, (1e-8, 1e-10));
        assert_eq!(
            r.stats.linear_solver,
            Some(LinearSolverKind::Scheduled { refused: true }),
            "{method:?}"
        );
        let x = r.final_states[0];
        assert!(
            ((x - exact(2.0)) / exact(2.0)).abs() < 1e-6,
            "{method:?}: x(2) = {x}, exact {}",
            exact(2.0)
        );
    }
}
