//! Method behavior beyond the reference set: stiff scalar and Van der Pol problems in a
//! bounded number of steps, non-stiff Kepler and oscillator problems with Dormand–Prince
//! against exact solutions, sparse versus dense linear algebra, options and failures.

#[path = "support/problems.rs"]
mod problems;

use problems::{
    counters, significant_digits, solve_to, Dahlquist, Harmonic, Kepler, Rober, VanDerPolUnscaled,
};
use unimo_solve::{
    EvalError, JacobianMatrix, LinearSolverChoice, Method, Options, SolveError, Solver,
    SparsityPattern, StopReason, System, Tolerance,
};

#[test]
fn dahlquist_stiff_decay_in_few_steps() {
    let mut report = String::new();
    for method in [Method::Bdf, Method::Radau5] {
        let mut system = Dahlquist { lambda: -1e6 };
        let (state, stats) = solve_to(
            method,
            &mut system,
            &[1.0],
            1.0,
            Options::with_tolerances(1e-6, 1e-10),
        )
        .unwrap();
        assert!(state[0].abs() <= 1e-10, "{method:?}: {}", state[0]);
        // Accuracy-limited transient (23 time constants to reach atol; BDF: 28 to its
        // calibrated atol / 100, 444 steps measured, 232 with the tolerances as requested),
        // then the step grows.
        let bound = if method == Method::Bdf { 600 } else { 400 };
        assert!(stats.steps <= bound, "{method:?}: {stats:?}");
        report += &format!("{method:?}\n{}", counters(&stats));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn dahlquist_transient_is_accurate() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let mut system = Dahlquist { lambda: -2.0 };
        let (state, _) = solve_to(
            method,
            &mut system,
            &[1.0],
            3.0,
            Options::with_tolerances(1e-9, 1e-14),
        )
        .unwrap();
        let scd = significant_digits(&state, &[(-6.0f64).exp()]);
        assert!(scd >= 7.0, "{method:?}: scd {scd:.2}");
    }
}

#[test]
fn van_der_pol_mu_1e6_finishes_in_bounded_steps() {
    let mut report = String::new();
    for method in [Method::Bdf, Method::Radau5] {
        let mut system = VanDerPolUnscaled { mu: 1e6 };
        let (state, stats) = solve_to(
            method,
            &mut system,
            &[2.0, 0.0],
            2e6,
            Options::with_tolerances(1e-6, 1e-6),
        )
        .unwrap();
        // Two relaxation jumps (period 1.614 mu): back on the upper branch, y1 = 1.7055 (the
        // scaled problem with eps = 1/mu^2 at t = 2).
        assert!((state[0] - 1.7055).abs() < 1e-3, "{method:?}: {state:?}");
        // BDF works to rtol / 100 (its tolerance calibration): 3,082 steps measured, 1,471
        // with the tolerance as requested.
        let bound = if method == Method::Bdf { 4000 } else { 2000 };
        assert!(stats.steps <= bound, "{method:?}: {stats:?}");
        report += &format!("{method:?}\n{}", counters(&stats));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn dopri5_kepler_orbit_returns_after_one_period() {
    let initial = Kepler::initial(0.5);
    let period = 2.0 * std::f64::consts::PI;
    let mut report = String::new();
    for (rtol, minimum_scd) in [(1e-6, 4.0), (1e-10, 8.0)] {
        let (state, stats) = solve_to(
            Method::Dopri5,
            &mut Kepler,
            &initial,
            period,
            Options::with_tolerances(rtol, rtol * 1e-3),
        )
        .unwrap();
        // Compare the components that are nonzero at the start.
        let scd = significant_digits(&[state[0], state[3]], &[initial[0], initial[3]]);
        assert!(scd >= minimum_scd, "rtol {rtol:e}: scd {scd:.2}");
        // Global (phase) error of an eccentric orbit: a few tens of rtol after one period.
        assert!(
            state[1].abs() < 100.0 * rtol && state[2].abs() < 100.0 * rtol,
            "{state:?}"
        );
        report += &format!("rtol {rtol:e}\n{}", counters(&stats));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn dopri5_harmonic_oscillator_matches_cosine() {
    let t_end = 20.0;
    let (state, _) = solve_to(
        Method::Dopri5,
        &mut Harmonic,
        &[1.0, 0.0],
        t_end,
        Options::with_tolerances(1e-10, 1e-12),
    )
    .unwrap();
    let exact = [t_end.cos(), -t_end.sin()];
    let scd = significant_digits(&state, &exact);
    assert!(scd >= 8.0, "scd {scd:.2}");
}

#[test]
fn dopri5_refuses_algebraic_rows() {
    let error = Solver::new(
        Method::Dopri5,
        &mut Rober {
            analytic_jacobian: false,
        },
        0.0,
        &[1.0, 0.0, 0.0],
        Options::default(),
    )
    .unwrap_err();
    assert_eq!(error.code(), "E4502");
    assert!(error.to_string().contains("algebraic"), "{error}");
}

/// Heat equation `u' = D u` on a line (tridiagonal), with a pattern.
struct Heat {
    size: usize,
    pattern: SparsityPattern,
    differential: Vec<bool>,
}

impl Heat {
    fn new(size: usize) -> Self {
        let entries = (0..size).flat_map(|j: usize| {
            [j.wrapping_sub(1), j, j + 1]
                .into_iter()
                .filter(move |&i| i < size)
                .map(move |i| (i, j))
        });
        Heat {
            size,
            pattern: SparsityPattern::from_entries(size, entries).unwrap(),
            differential: vec![true; size],
        }
    }
}

impl System for Heat {
    fn len(&self) -> usize {
        self.size
    }
    fn differential(&self) -> &[bool] {
        &self.differential
    }
    fn rhs(&mut self, _t: f64, u: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let n = self.size;
        let scale = (n as f64 + 1.0).powi(2);
        for i in 0..n {
            let left = if i > 0 { u[i - 1] } else { 0.0 };
            let right = if i + 1 < n { u[i + 1] } else { 0.0 };
            out[i] = scale * (left - 2.0 * u[i] + right);
        }
        Ok(())
    }
    fn sparsity(&self) -> Option<&SparsityPattern> {
        Some(&self.pattern)
    }
}

#[test]
fn sparse_and_dense_linear_solvers_agree() {
    let size = 150;
    let initial: Vec<f64> = (0..size)
        .map(|i| (std::f64::consts::PI * (i + 1) as f64 / (size + 1) as f64).sin())
        .collect();
    for method in [Method::Bdf, Method::Radau5] {
        let run = |choice: LinearSolverChoice| {
            let options = Options {
                linear_solver: choice,
                ..Options::with_tolerances(1e-8, 1e-10)
            };
            solve_to(method, &mut Heat::new(size), &initial, 0.1, options).unwrap()
        };
        let (dense, dense_stats) = run(LinearSolverChoice::Dense);
        let (sparse, sparse_stats) = run(LinearSolverChoice::Sparse);
        // The exact solution decays like exp(-lambda t) with lambda ~ pi^2.
        let decay = (-std::f64::consts::PI.powi(2) * 0.1).exp();
        let middle = size / 2;
        assert!((dense[middle] / initial[middle] - decay).abs() < 1e-4);
        let difference = dense
            .iter()
            .zip(&sparse)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(difference < 1e-9, "{method:?}: {difference:e}");
        // Colored finite differences: 3 evaluations per Jacobian instead of 150.
        assert!(sparse_stats.rhs_evals <= dense_stats.rhs_evals);
    }
}

/// `y' = 1` that fails (NaN or an error) for `t > 1.5`.
struct Breaks {
    nan: bool,
}

impl System for Breaks {
    fn len(&self) -> usize {
        1
    }
    fn differential(&self) -> &[bool] {
        &[true]
    }
    fn rhs(&mut self, t: f64, _y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        if t > 1.5 {
            if self.nan {
                out[0] = f64::NAN;
                return Ok(());
            }
            return Err(EvalError::domain("sqrt of a negative number"));
        }
        out[0] = 1.0;
        Ok(())
    }
}

#[test]
fn failing_evaluations_reduce_the_step_then_fail_clearly() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        for nan in [true, false] {
            let mut system = Breaks { nan };
            let mut solver =
                Solver::new(method, &mut system, 0.0, &[0.0], Options::default()).unwrap();
            let error = solver.step_until(&mut system, 3.0).unwrap_err();
            assert!(
                matches!(
                    error,
                    SolveError::Eval { .. }
                        | SolveError::StepSizeTooSmall { .. }
                        | SolveError::NewtonFailed { .. }
                ),
                "{method:?}: {error}"
            );
            assert!(
                (solver.internal_time() - 1.5).abs() < 1e-6,
                "{method:?}: {error}"
            );
            assert!((solver.state()[0] - solver.current_time()).abs() < 1e-9);
        }
    }
}

#[test]
fn invalid_input_is_reported() {
    let mut system = Dahlquist { lambda: -1.0 };
    let bad_length = Solver::new(
        Method::Bdf,
        &mut system,
        0.0,
        &[1.0, 2.0],
        Options::default(),
    );
    assert_eq!(bad_length.unwrap_err().code(), "E4501");
    let bad_tolerance = Options {
        absolute_tolerance: Tolerance::PerComponent(vec![1e-8, 1e-8]),
        ..Options::default()
    };
    let error = Solver::new(Method::Radau5, &mut system, 0.0, &[1.0], bad_tolerance).unwrap_err();
    assert_eq!(error.code(), "E4501");
    let mut solver =
        Solver::new(Method::Bdf, &mut system, 1.0, &[1.0], Options::default()).unwrap();
    assert_eq!(
        solver.step_until(&mut system, 0.5).unwrap_err().code(),
        "E4501"
    );
}

#[test]
fn per_component_tolerances_and_max_step_are_respected() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let options = Options {
            relative_tolerance: Tolerance::PerComponent(vec![1e-8, 1e-8]),
            absolute_tolerance: Tolerance::PerComponent(vec![1e-10, 1e-10]),
            max_step: 0.01,
            ..Options::default()
        };
        let mut solver = Solver::new(method, &mut Harmonic, 0.0, &[1.0, 0.0], options).unwrap();
        let mut previous = 0.0;
        loop {
            let reason = solver.step(&mut Harmonic, 1.0).unwrap();
            let step = solver.current_time() - previous;
            assert!(step <= 0.01 * (1.0 + 1e-12), "{method:?}: step {step}");
            previous = solver.current_time();
            if reason == StopReason::ReachedStop {
                break;
            }
        }
        assert!(solver.stats().steps >= 100);
        assert!((solver.state()[0] - 1f64.cos()).abs() < 1e-7, "{method:?}");
    }
}

#[test]
fn reset_restarts_from_a_changed_state() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let mut system = Dahlquist { lambda: -1.0 };
        let options = Options::with_tolerances(1e-9, 1e-12);
        let mut solver = Solver::new(method, &mut system, 0.0, &[1.0], options).unwrap();
        solver.step_until(&mut system, 1.0).unwrap();
        solver.reset(&mut system, 1.0, &[2.0]).unwrap();
        solver.step_until(&mut system, 2.0).unwrap();
        let expected = 2.0 * (-1.0f64).exp();
        assert!(
            (solver.state()[0] - expected).abs() < 1e-7,
            "{method:?}: {}",
            solver.state()[0]
        );
    }
}

/// ROBER with an analytic Jacobian in sparse storage (pattern given).
struct SparseRober {
    inner: Rober,
    pattern: SparsityPattern,
}

impl System for SparseRober {
    fn len(&self) -> usize {
        3
    }
    fn differential(&self) -> &[bool] {
        self.inner.differential()
    }
    fn rhs(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.inner.rhs(t, y, out)
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut JacobianMatrix) -> Result<bool, EvalError> {
        self.inner.jacobian(t, y, jac)
    }
    fn sparsity(&self) -> Option<&SparsityPattern> {
        Some(&self.pattern)
    }
}

#[test]
fn sparse_lu_solves_the_rober_dae() {
    let reference = Rober::reference();
    for method in [Method::Bdf, Method::Radau5] {
        let mut system = SparseRober {
            inner: Rober {
                analytic_jacobian: true,
            },
            pattern: SparsityPattern::dense(3),
        };
        let options = Options {
            linear_solver: LinearSolverChoice::Sparse,
            ..Options::with_tolerances(1e-8, 1e-14)
        };
        let (state, _) =
            solve_to(method, &mut system, &reference.x0, reference.t_end, options).unwrap();
        let scd = significant_digits(&state, &reference.solution);
        assert!(scd >= 5.8, "{method:?}: scd {scd:.2}");
    }
}

#[test]
fn too_many_steps_is_reported_with_the_time_reached() {
    let options = Options {
        max_steps_per_call: 5,
        ..Options::with_tolerances(1e-10, 1e-12)
    };
    let mut solver = Solver::new(Method::Dopri5, &mut Harmonic, 0.0, &[1.0, 0.0], options).unwrap();
    let error = solver.step_until(&mut Harmonic, 100.0).unwrap_err();
    match error {
        SolveError::TooManySteps { time, max_steps } => {
            assert_eq!(max_steps, 5);
            assert_eq!(time, solver.current_time());
            assert!(time > 0.0 && time < 100.0);
        }
        other => panic!("{other}"),
    }
    // The next call goes on from there.
    assert!(solver
        .step_until(&mut Harmonic, solver.current_time() + 0.01)
        .is_ok());
}

#[test]
fn solver_can_move_between_threads() {
    fn assert_send<T: Send>() {}
    assert_send::<Solver>();
    assert_send::<unimo_solve::Bdf>();
    assert_send::<unimo_solve::Radau5>();
    assert_send::<unimo_solve::Dopri5>();
}

/// Hairer and Wanner's 1-D Brusselator (BRUSS) with `n` grid points, `u` and `v`
/// interleaved (a band of width 5), with its pattern: a nonlinear stiff system large
/// enough for the sparse LU.
struct Brusselator1d {
    n: usize,
    pattern: SparsityPattern,
    differential: Vec<bool>,
}

impl Brusselator1d {
    fn new(n: usize) -> Self {
        let size = 2 * n;
        let entries = (0..size).flat_map(move |j: usize| {
            (j.saturating_sub(2)..(j + 3).min(size)).map(move |i| (i, j))
        });
        Brusselator1d {
            n,
            pattern: SparsityPattern::from_entries(size, entries).unwrap(),
            differential: vec![true; size],
        }
    }

    fn initial(&self) -> Vec<f64> {
        let h = 1.0 / (self.n as f64 + 1.0);
        (0..self.n)
            .flat_map(|i| {
                [
                    1.0 + (2.0 * std::f64::consts::PI * (i + 1) as f64 * h).sin(),
                    3.0,
                ]
            })
            .collect()
    }
}

impl System for Brusselator1d {
    fn len(&self) -> usize {
        2 * self.n
    }
    fn differential(&self) -> &[bool] {
        &self.differential
    }
    fn rhs(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let n = self.n;
        let c = (n as f64 + 1.0).powi(2) / 50.0;
        for i in 0..n {
            let (u, v) = (x[2 * i], x[2 * i + 1]);
            let (ul, vl) = if i > 0 {
                (x[2 * i - 2], x[2 * i - 1])
            } else {
                (1.0, 3.0)
            };
            let (ur, vr) = if i + 1 < n {
                (x[2 * i + 2], x[2 * i + 3])
            } else {
                (1.0, 3.0)
            };
            out[2 * i] = 1.0 + u * u * v - 4.0 * u + c * (ul - 2.0 * u + ur);
            out[2 * i + 1] = 3.0 * u - u * u * v + c * (vl - 2.0 * v + vr);
        }
        Ok(())
    }
    fn sparsity(&self) -> Option<&SparsityPattern> {
        Some(&self.pattern)
    }
}

/// On a large system Radau5 keeps its Jacobian while Newton contracts by 0.1 or better
/// and its step size (so its two factorizations) for step-size ratios in 0.99..2
/// (Hairer's settings for large systems): most steps reuse the last factorization, at
/// the requested accuracy.
#[test]
fn radau5_reuses_factorizations_on_a_large_system() {
    let mut system = Brusselator1d::new(100);
    let initial = system.initial();
    let tight = Options::with_tolerances(1e-12, 1e-12);
    let (reference, _) = solve_to(Method::Radau5, &mut system, &initial, 10.0, tight).unwrap();
    let options = Options::with_tolerances(1e-6, 1e-8);
    let (x, stats) = solve_to(Method::Radau5, &mut system, &initial, 10.0, options).unwrap();
    let digits = significant_digits(&x, &reference);
    eprintln!("{stats:?}, {digits:.2} digits");
    assert!(digits > 6.0, "{digits}");
    assert!(
        2 * stats.lu_factorizations < stats.steps + stats.rejected_steps,
        "{stats:?}"
    );
    assert!(2 * stats.jacobian_evals < stats.steps, "{stats:?}");
}

#[test]
fn dopri5_says_when_a_problem_is_stiff() {
    // y' = -1e4 y: after the transient (about 2e-3) Dormand–Prince's step is held at its
    // stability limit, h |λ| ≈ 3.3, whatever the tolerance asks.
    let mut system = Dahlquist { lambda: -1e4 };
    let options = || Options::with_tolerances(1e-6, 1e-12);
    let mut solver = Solver::new(Method::Dopri5, &mut system, 0.0, &[1.0], options()).unwrap();
    solver.step_until(&mut system, 0.1).unwrap();
    let since = solver.stiff_since().expect("the stiffness test fires");
    assert!(since > 0.0 && since < 0.01, "stiff from t = {since}");
    // A non-stiff oscillator over many periods: never.
    let mut solver =
        Solver::new(Method::Dopri5, &mut Harmonic, 0.0, &[1.0, 0.0], options()).unwrap();
    solver.step_until(&mut Harmonic, 50.0).unwrap();
    assert_eq!(solver.stiff_since(), None);
    // Implicit methods do not run the test.
    let mut solver = Solver::new(Method::Radau5, &mut system, 0.0, &[1.0], options()).unwrap();
    solver.step_until(&mut system, 0.1).unwrap();
    assert_eq!(solver.stiff_since(), None);
}
