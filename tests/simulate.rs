//! Simulation end to end: reference problems against published solutions (scd),
//! exact event times of the bouncing ball, stiff and extreme cases. Floats are compared
//! with tolerance-aware bounds; solver counters are snapshot-tested.

mod common;
#[path = "../crates/unimo-solve/tests/support/test_set.rs"]
mod test_set;

use unimo_runtime::sim::{simulate, SimOptions, SimResult};
use unimo_solve::Method;

fn load(file: &str) -> unimo_cli::LoadedModel {
    unimo_cli::load_model(&[common::root().join(file)], None)
        .unwrap_or_else(|e| panic!("{file}:\n{e}"))
}

/// Model `model` (`Package.Model`) of its package's file `tests/simulate/Package.mo`.
fn load_named(model: &str) -> unimo_cli::LoadedModel {
    let package = model.split('.').next().unwrap_or(model);
    let file = format!("tests/simulate/{package}.mo");
    unimo_cli::load_model(&[common::root().join(&file)], Some(model))
        .unwrap_or_else(|e| panic!("{file} {model}:\n{e}"))
}

/// A run from 0 to `stop` with `points` output intervals that must succeed.
fn run(
    m: &unimo_cli::LoadedModel,
    method: Method,
    rtol: f64,
    atol: f64,
    stop: f64,
    points: usize,
) -> SimResult {
    let o = SimOptions {
        atol,
        ..common::sim_options(method, rtol, 0.0, stop, stop / points as f64)
    };
    let r = simulate(&m.compiled, &o);
    assert!(
        r.error.is_none(),
        "{:?}",
        r.error.as_ref().map(|e| e.message())
    );
    r
}

/// [`run`] of the model in `file` with BDF at rtol 1e-8, atol 1e-10.
fn run_file(file: &str, stop: f64, points: usize) -> SimResult {
    run(&load(file), Method::Bdf, 1e-8, 1e-10, stop, points)
}

/// Asserts `|got - want| < tol`; `what` names the value when it fails.
#[track_caller]
fn assert_near(got: f64, want: f64, tol: f64, what: impl std::fmt::Display) {
    assert!(
        (got - want).abs() < tol,
        "{what} = {got}, expected {want} (within {tol})"
    );
}

/// The index of the output `name` in `r`'s rows.
fn column_of(r: &SimResult, name: &str) -> usize {
    (r.names.iter())
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no {name}"))
}

fn value(r: &SimResult, name: &str) -> f64 {
    r.rows.last().unwrap()[column_of(r, name)]
}

/// Significant correct digits: -log10 of the largest relative error.
fn scd(r: &SimResult, reference: &[(&str, f64)]) -> f64 {
    reference
        .iter()
        .map(|&(n, want)| ((value(r, n) - want) / want).abs())
        .fold(0.0f64, f64::max)
        .log10()
        .abs()
}

fn counters(r: &SimResult) -> String {
    let s = &r.stats.solver;
    format!(
        "steps {} rejected {} rhs {} jacobians {} lu {} events {}",
        s.steps,
        s.rejected_steps,
        s.rhs_evals,
        s.jacobian_evals,
        s.lu_factorizations,
        r.stats.events
    )
}

const ROBER: [(&str, f64); 3] = [
    ("y1", 2.083340149701255e-8),
    ("y2", 8.333360770334713e-14),
    ("y3", 0.999_999_979_166_505),
];

#[test]
fn robertson_dae_reaches_the_required_digits() {
    let m = load("models/Robertson.mo");
    for method in [Method::Bdf, Method::Radau5] {
        let r = run(&m, method, 1e-8, 1e-14, 1e11, 1);
        let d = scd(&r, &ROBER);
        assert!(d >= 5.8, "{method:?} rtol 1e-8: scd {d:.2}");
        let r = run(&m, method, 1e-10, 1e-16, 1e11, 1);
        let d = scd(&r, &ROBER);
        assert!(d >= 7.0, "{method:?} rtol 1e-10: scd {d:.2}");
    }
}

#[test]
fn hires_and_van_der_pol_match_the_test_set() {
    let hires = load("models/Hires.mo");
    let reference = test_set::HIRES_REF;
    let names: Vec<String> = (1..=8).map(|k| format!("y[{k}]")).collect();
    let hires_ref: Vec<(&str, f64)> = names.iter().map(|n| n.as_str()).zip(reference).collect();
    let vdpol = load("models/VanDerPol.mo");
    let vdpol_ref = [("y1", 1.706167732170483), ("y2", -0.8928097010247975)];
    for method in [Method::Bdf, Method::Radau5] {
        let r = run(&hires, method, 1e-8, 1e-10, test_set::HIRES_T_END, 1);
        let d = scd(&r, &hires_ref);
        assert!(d >= 5.5, "HIRES {method:?}: scd {d:.2}");
        let r = run(&vdpol, method, 1e-8, 1e-10, 2.0, 1);
        let d = scd(&r, &vdpol_ref);
        assert!(d >= 6.0, "VDPOL {method:?}: scd {d:.2}");
    }
}

/// Impact n of a ball dropped from h: t_n = (v1/g)(1 + 2e(1 - e^(n-1))/(1 - e)).
fn impact_time(n: i32, h: f64, g: f64, e: f64) -> f64 {
    let v1 = (2.0 * g * h).sqrt();
    v1 / g * (1.0 + 2.0 * e * (1.0 - e.powi(n - 1)) / (1.0 - e))
}

/// Impact times against the closed form: within 1e-12 relative for every method and
/// tolerance up to t = 12.85 (45 impacts, t* - 5.9e-4; see docs/results/runtime.md).
#[test]
fn bouncing_ball_impacts_are_exact() {
    let m = load("models/BouncingBall.mo");
    let (h, g, e): (f64, f64, f64) = (10.0, 9.81, 0.8);
    let zeno = (2.0 * h / g).sqrt() * (1.0 + e) / (1.0 - e);
    assert!((zeno - 12.850588106343585).abs() < 1e-12);
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        for rtol in [1e-6, 1e-10] {
            let stop = 12.85;
            let expected: Vec<f64> = (1..)
                .map(|n| impact_time(n, h, g, e))
                .take_while(|&t| t < stop)
                .collect();
            let r = run(&m, method, rtol, rtol / 100.0, stop, 10);
            let times: Vec<f64> = r.events.iter().map(|ev| ev.time).collect();
            assert_eq!(
                times.len(),
                expected.len(),
                "{method:?} {rtol:e}: {times:?}"
            );
            let worst = times
                .iter()
                .zip(&expected)
                .map(|(t, want)| ((t - want) / want).abs())
                .fold(0.0f64, f64::max);
            eprintln!(
                "bouncing ball {method:?} rtol {rtol:e}: {} impacts to t = {stop}, worst relative error {worst:e}",
                times.len()
            );
            assert!(
                worst <= 1e-12,
                "{method:?} rtol {rtol:e}: worst relative impact error {worst:e}"
            );
            assert_eq!(value(&r, "bounces"), expected.len() as f64);
        }
    }
}

#[test]
fn guarded_ball_rests_past_the_zeno_time() {
    let m = load("models/BouncingBallResting.mo");
    let r = run(&m, Method::Auto, 1e-8, 1e-10, 20.0, 20);
    assert_eq!(value(&r, "resting"), 1.0);
    assert_eq!(value(&r, "h"), 0.0);
    assert_eq!(value(&r, "v"), 0.0);
    // It came to rest at the Zeno time (within the guard's speed).
    let rest = r.events.last().unwrap().time;
    assert_near(rest, 12.850588106343585, 1e-6, "time of rest");
}

#[test]
fn stiff_extremes_finish_in_few_steps() {
    let mut report = String::new();
    let dahlquist = load("models/Dahlquist.mo");
    let vdp = load("models/VanDerPolStiff.mo");
    for method in [Method::Bdf, Method::Radau5] {
        let r = run(&dahlquist, method, 1e-6, 1e-8, 1.0, 1);
        assert!(value(&r, "y").abs() < 1e-8);
        assert!(r.stats.solver.steps < 500, "{}", counters(&r));
        report += &format!("Dahlquist {method:?}: {}\n", counters(&r));
        let r = run(&vdp, method, 1e-6, 1e-6, 2e6, 1);
        // Two relaxation jumps (period 1.614 mu): back on the upper branch.
        assert!((value(&r, "x") - 1.7055).abs() < 1e-3);
        // BDF works to rtol / 100 (its tolerance calibration, bdf.rs): 3,132 steps measured,
        // 1,488 with the tolerance as requested.
        let bound = if method == Method::Bdf { 4000 } else { 3000 };
        assert!(r.stats.solver.steps < bound, "{}", counters(&r));
        report += &format!("VanDerPol mu=1e6 {method:?}: {}\n", counters(&r));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn stiff_penalty_ball_never_gains_energy() {
    let m = load("models/PenaltyBall.mo");
    for method in [Method::Bdf, Method::Radau5] {
        let o = SimOptions {
            every_step: true,
            ..common::sim_options(method, 1e-6, 0.0, 3.0, 0.01)
        };
        let r = simulate(&m.compiled, &o);
        assert!(r.error.is_none());
        let k = column_of(&r, "E");
        let e: Vec<f64> = r.rows.iter().map(|row| row[k]).collect();
        let e0 = e[0];
        let max = e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            max <= e0 * (1.0 + 1e-12),
            "{method:?}: energy rose to {max} from {e0}"
        );
        assert!(
            *e.last().unwrap() < 0.9 * e0,
            "{method:?}: the damper took no energy"
        );
    }
}

#[test]
fn pendulum_keeps_its_constraint() {
    let m = load("models/Pendulum.mo");
    let o = common::sim_options(Method::Auto, 1e-8, 0.0, 10.0, 0.01);
    let r = simulate(&m.compiled, &o);
    assert!(r.error.is_none());
    let k = column_of(&r, "drift");
    let drift = r.rows.iter().map(|row| row[k].abs()).fold(0.0f64, f64::max);
    assert!(drift < 1e-12, "constraint drift {drift:e}");
}

/// `sample(0.05, 0.1)` fires exactly at 0.05 + 0.1 k, once per instant.
#[test]
fn sample_instants_are_hit_exactly() {
    let m = load("models/SampleCounter.mo");
    let r = run(&m, Method::Auto, 1e-6, 1e-8, 1.0, 10);
    assert_eq!(value(&r, "count"), 10.0);
    let times: Vec<f64> = r.events.iter().map(|e| e.time).collect();
    assert_eq!(times.len(), 10, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        let want = 0.05 + 0.1 * k as f64;
        assert!((t - want).abs() <= 4.0 * f64::EPSILON, "{t} vs {want}");
    }
}

/// `--vars` leaves out what the outputs do not need, but never what initialization
/// reads: x(0) = guess(0) = 3 must survive asking only for y.
/// Simulates `file` pruned to the one output `var` (as `--vars var` does), to t = 1.
fn run_pruned(file: &str, var: &str, rtol: f64) -> (SimResult, usize) {
    let m = load(file);
    let s = m
        .dae
        .ids()
        .find(|&s| m.dae.name(s) == var)
        .unwrap_or_else(|| panic!("{var} is a variable"));
    let mut plan = m.analysis.plan.clone();
    let pruned = unimo_dae::prune::prune(&m.dae, &mut plan, &[s]);
    let compiled = unimo_codegen::model::compile(&m.dae, &plan);
    let o = common::sim_options(Method::Bdf, rtol, 0.0, 1.0, 0.5);
    let r = simulate(&compiled, &o);
    assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
    (r, pruned)
}

#[test]
fn pruning_keeps_what_initialization_reads() {
    let (r, pruned) = run_pruned("tests/simulate/PruneKeepsInitialization.mo", "y", 1e-8);
    let k = column_of(&r, "y");
    let y0 = r.rows[0][k];
    let y1 = r.rows.last().unwrap()[k];
    assert_near(y0, 3.0, 1e-12, format_args!("y(0), pruned {pruned}"));
    assert_near(y1, 3.0 * (-1.0f64).exp(), 1e-6, "y(1)");
}

/// Pruning reaches events: a relation that only a left-out equation holds is no zero
/// crossing (no root function, no event) and the algebraic loop nobody reads goes, while
/// the requested state follows the same trajectory (the run with the events restarts
/// the integrator at each one, so the two agree at the tolerance, not to round-off).
#[test]
fn pruning_leaves_out_the_events_of_what_is_left_out() {
    let file = "tests/simulate/PruneLeavesOutEvents.mo";
    let m = load(file);
    let id = |name: &str| m.dae.ids().find(|&s| m.dae.name(s) == name).unwrap();
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, 3.0, 0.01);
    let mut outcomes = Vec::new();
    for wanted in [vec![id("x")], vec![id("x"), id("above")]] {
        let mut plan = m.analysis.plan.clone();
        let pruned = unimo_dae::prune::prune(&m.dae, &mut plan, &wanted);
        let compiled = unimo_codegen::model::compile(&m.dae, &plan);
        let r = simulate(&compiled, &o);
        assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
        let k = column_of(&r, "x");
        let x: Vec<f64> = r.rows.iter().map(|row| row[k]).collect();
        outcomes.push((pruned, compiled.roots.len(), r.stats.events, x, r.times));
    }
    let (pruned, roots, events, x, times) = &outcomes[0];
    assert_eq!((*pruned, *roots, *events), (3, 0, 0), "x alone");
    let (pruned_both, roots_both, events_both, x_both, times_both) = &outcomes[1];
    assert_eq!((*pruned_both, *roots_both), (2, 1), "x and above");
    assert!(*events_both >= 2, "x crosses 0.5: {events_both} events");
    // Compare at the output times (the run with events has extra rows at them).
    let mut worst = 0.0f64;
    for (t, v) in times.iter().zip(x) {
        let i = times_both.iter().rposition(|u| u == t).unwrap();
        worst = worst.max((v - x_both[i]).abs());
    }
    assert!(worst <= 1e-6, "x differs by {worst:e}");
}

/// Requesting only `s_rel` (the state index reduction chose) must keep the variable
/// whose fixed start determines it. With x = s + 0.5: x'' = -x - d x', x(0) = 0.5,
/// x'(0) = 0, so x = 0.5 e^(-dt/2) (cos wt + d/(2w) sin wt), w = sqrt(1 - d^2/4), and
/// s_rel = 1 - s = 1.5 - x.
#[test]
fn pruning_keeps_fixed_starts_of_dummy_states() {
    let (r, pruned) = run_pruned("tests/simulate/PruneKeepsFixedDummyState.mo", "s_rel", 1e-9);
    let k = column_of(&r, "s_rel");
    let d = 0.1f64;
    let w = (1.0 - d * d / 4.0).sqrt();
    let exact =
        |t: f64| 1.5 - 0.5 * (-d * t / 2.0).exp() * ((w * t).cos() + d / (2.0 * w) * (w * t).sin());
    for (t, row) in r.times.iter().zip(&r.rows) {
        assert_near(
            row[k],
            exact(*t),
            1e-6,
            format_args!("s_rel({t}), pruned {pruned}"),
        );
    }
}

/// A model without continuous states still has its events: the counter steps at
/// t = -0.035 + 0.1 k, so at t = 0.3 it has stepped three times, last at t = 0.265.
#[test]
fn time_events_fire_in_models_without_states() {
    let r = run_file("tests/simulate/StatelessTimeEvents.mo", 0.3, 3);
    assert_eq!(value(&r, "count"), 3.0);
    assert_near(value(&r, "T_start"), 0.265, 1e-9, "T_start");
    assert_eq!(r.stats.events, 3, "{}", counters(&r));
}

/// `initial equation pre(y) = true` sets the hysteresis's state before the start:
/// x = t up to t = 1, then x = 2 - t (with pre(y) = false it would fall from the start).
#[test]
fn initial_equations_of_pre_values_set_the_state_before_the_start() {
    let r = run_file("tests/simulate/PreInitialEquation.mo", 1.6, 4);
    assert_near(value(&r, "x"), 0.4, 1e-6, "x(1.6)");
    assert_eq!(r.stats.events, 1, "{}", counters(&r));
}

/// `[t[1], 1; t, {3, 5}]` is 3x2 (a vector is a column), and the `if` whose other
/// branch is 1x2 is decided by the parameter: sum(m) = 2 + 1 + 2 + 3 + 4 + 5 = 17.
#[test]
fn structural_if_bindings_of_different_sizes_take_their_branch() {
    let r = run_file("tests/simulate/StructuralIfSizes.mo", 1.0, 2);
    assert_near(value(&r, "y"), 17.0, 1e-12, "y(1)");
}

/// The limited op-amp in the linear band: vout = V0 vin / (1 + V0 R1 / (R1 + R2)) at
/// every output point (plain Newton cycled between the two saturations and failed).
#[test]
fn newton_damps_steps_across_saturations() {
    let m = load("tests/simulate/LimitedOpAmp.mo");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 1.0, 50);
    let (kin, kout) = (column_of(&r, "vin"), column_of(&r, "vout"));
    let gain = 15000.0 / (1.0 + 15000.0 * 0.5);
    for row in &r.rows {
        let want = gain * row[kin];
        assert_near(row[kout], want, 1e-9, "vout");
    }
}

/// Fixed starts on both ends of a rigid link are redundant: consistent ones are
/// accepted (x1 = -0.5 + 0.5 cos t), contradicting ones are E4001 naming the reason.
#[test]
fn redundant_fixed_starts_are_checked_not_refused() {
    let m = load("tests/simulate/RedundantFixedStarts.mo");
    let r = run(&m, Method::Bdf, 1e-9, 1e-11, 1.0, 2);
    let x1 = value(&r, "x1");
    assert_near(x1, -0.5 + 0.5 * 1f64.cos(), 1e-6, "x1(1)");
    let text =
        std::fs::read_to_string(common::root().join("tests/simulate/RedundantFixedStarts.mo"))
            .unwrap()
            .replace("x2_start = 1;", "x2_start = 2;");
    let dir = std::env::temp_dir().join(format!("unimo-redundant-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("RedundantFixedStarts.mo");
    std::fs::write(&path, text).unwrap();
    let bad = unimo_cli::load_model(&[path], None).unwrap();
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, 1.0, 0.5);
    let e = simulate(&bad.compiled, &o)
        .error
        .expect("contradicting starts fail");
    assert!(e.message().contains("contradict"), "{}", e.message());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `when terminal()` fires once, at the stop time, with the final state: atEnd = e^-1;
/// the five sample instants 0, 0.25, ..., 1 all fire before it.
#[test]
fn terminal_fires_at_the_end() {
    let m = load("tests/simulate/TerminalEvent.mo");
    let r = run(&m, Method::Bdf, 1e-9, 1e-11, 1.0, 2);
    assert_near(value(&r, "atEnd"), (-1.0f64).exp(), 1e-7, "atEnd");
    assert_eq!(value(&r, "n"), 5.0);
    let k = column_of(&r, "atEnd");
    let before: Vec<f64> = r.rows[..r.rows.len() - 1]
        .iter()
        .map(|row| row[k])
        .collect();
    assert!(before.iter().all(|&v| v == 0.0), "{before:?}");
}

/// A function output sized by an input is sized when the call is inlined: y = {t, 2t, 3t}.
#[test]
fn function_outputs_sized_by_inputs() {
    let m = common::load(
        "tests/simulate/FunctionOutputSize.mo",
        Some("FunctionOutputSize.Use"),
    );
    let r = run(&m, Method::Bdf, 1e-8, 1e-10, 1.0, 2);
    for k in 1..=3 {
        let name = format!("y[{k}]");
        assert_near(value(&r, &name), k as f64, 1e-12, &name);
    }
}

/// References through arrays of components (`sum(port.Q_flow)`, `s[2:3].port.Q_flow`),
/// a String parameter compared at translation, array flows connected whole, and
/// `buf[tick] := ..` at a run-time index (the MSL's RealFFT and machine models).
#[test]
fn component_array_references_strings_and_dynamic_indices() {
    let r = run_file("tests/simulate/ComponentArrayRefs.mo", 1.0, 4);
    let expect = [
        ("total", 6.0),
        ("temperatures", 900.0),
        ("twoFlows", -5.0),
        ("scaled", 2.0),
        ("sourceCurrent", -6.0),
        ("buf[1]", 10.25),
        ("buf[2]", 20.5),
        ("buf[3]", 30.75),
    ];
    for (name, want) in expect {
        let got = value(&r, name);
        assert_near(got, want, 1e-9 * want.abs().max(1.0), name);
    }
}

/// A built-in of the language that unimo does not implement (clocks, streams,
/// overconstrained connections) passes the name check and is E3001 naming it.
#[test]
fn unimplemented_builtins_are_reported_as_not_supported() {
    let file = common::root().join("tests/simulate/ClockedNotSupported.mo");
    let err = unimo_cli::load_model(&[file], None)
        .err()
        .expect("not supported");
    assert!(err.contains("E3001") && err.contains("`previous`"), "{err}");
    assert!(!err.contains("E2001"), "{err}");
}

/// An if-equation on a discrete condition inside an algebraic loop (`F = 0` in one
/// branch, `D = 0` in the other): the variable solved in one branch only must not be
/// torn by dividing by its coefficient, which is 0 in the other branch.
#[test]
fn switched_equation_in_a_loop_is_not_divided_by_zero() {
    let r = run_file("tests/simulate/SwitchedLoop.mo", 1.0, 10);
    let (kx, kd, kf) = (column_of(&r, "x"), column_of(&r, "D"), column_of(&r, "F"));
    // before the switch F = 0 and x decays; after it D = der(x) = 0
    assert_eq!(r.rows[0][kf], 0.0);
    let last = r.rows.last().unwrap();
    assert!(last[kd].abs() < 1e-12, "D = {}", last[kd]);
    assert!(last[kx] < 1.0 && last[kx] > 0.0, "x = {}", last[kx]);
}

/// Records as structured variables (`tests/flatten/ok/records.mo`): record parameters
/// from constructors and other records, a record equation with a function of records,
/// a function with a record local and field assignments, a constructor default, and
/// inherited fields — against the closed form z(t) = exp(-(1 + 2i) t), w = i z,
/// g = 3 (t, 2t), r = |z| + 11. The printed flat model simulates to the same values.
#[test]
fn records_simulate_to_the_closed_form() {
    let (c, s) = ((-2.0f64).cos(), (-2.0f64).sin());
    let e = (-1.0f64).exp();
    let want = [
        ("z.re", e * c),
        ("z.im", e * s),
        ("w.re", -e * s),
        ("w.im", e * c),
        ("g.origin.x", 3.0),
        ("g.origin.y", 6.0),
        ("g.axis[1]", 3.0),
        ("g.axis[2]", 2.0),
        ("r", e + 11.0),
    ];
    let m = load("tests/flatten/ok/records.mo");
    let r = run(&m, Method::Radau5, 1e-10, 1e-12, 1.0, 1);
    let digits = scd(&r, &want);
    assert!(digits >= 8.0, "records: scd {digits}");
    // The flat text stands alone and gives the same values.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["flatten", "tests/flatten/ok/records.mo"])
        .current_dir(common::root())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let flat = out.stdout;
    let dir = std::env::temp_dir().join(format!("unimo-records-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("records_flat.mo");
    std::fs::write(&file, flat).unwrap();
    let m2 = unimo_cli::load_model(&[file], None).unwrap_or_else(|e| panic!("flat:\n{e}"));
    let r2 = run(&m2, Method::Radau5, 1e-10, 1e-12, 1.0, 1);
    for (name, _) in want {
        assert_eq!(value(&r, name), value(&r2, name), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `parameter Real k(fixed = false)` is an unknown of the initialization: `k * k = 9`
/// from the start guess 1 gives k = 3; the parameter `k2 = 2 * k` follows it, and
/// x(t) = 2 exp(-3 t).
#[test]
fn fixed_false_parameters_are_solved_at_initialization() {
    let m = load("tests/flatten/ok/free_parameter.mo");
    let r = run(&m, Method::Radau5, 1e-10, 1e-12, 1.0, 1);
    let want = [("y", 6.0), ("x", 2.0 * (-3.0f64).exp())];
    let digits = scd(&r, &want);
    assert!(digits >= 8.0, "free parameter: scd {digits}");
}

/// Functions with algorithm sections count as one equation per output: `(r, phi) =
/// polar(x, y)` (two outputs), `ds = step(s, k)` (a record in and out, a protected
/// local), a while loop — the model balances and follows the closed form
/// x = cos t, y = sin t, r = 1, phi = t, s.p = cos(2t), total = 10.
#[test]
fn functions_with_algorithms_tuples_and_records_balance() {
    let m = load("tests/simulate/FunctionsCount.mo");
    let r = run(&m, Method::Radau5, 1e-10, 1e-12, 1.0, 1);
    let want = [
        ("x", 1.0f64.cos()),
        ("y", 1.0f64.sin()),
        ("r", 1.0),
        ("phi", 1.0),
        ("s.p", 2.0f64.cos()),
        ("s.v", -2.0 * 2.0f64.sin()),
        ("total", 10.0),
    ];
    let digits = scd(&r, &want);
    assert!(digits >= 8.0, "scd {digits}");
}

/// `return` and `break` under conditions that depend on variables: the inlined body
/// merges each exit into the result (`k` = index of the first element above 0.5, a
/// sum capped with `break`, early returns), against the values computed by hand.
#[test]
fn conditional_return_and_break_are_inlined() {
    let m = load("tests/simulate/ConditionalExits.mo");
    for (stop, k, s, y) in [
        (0.3, 2.0, 1.8, -0.8),
        (0.15, 0.0, 0.9, -1.0),
        (1.0, 1.0, 3.0, 1.0),
    ] {
        let r = run(&m, Method::Radau5, 1e-10, 1e-12, stop, 1);
        assert_eq!(value(&r, "k"), k, "k at {stop}");
        assert!((value(&r, "s") - s).abs() < 1e-12, "s at {stop}");
        assert!((value(&r, "y") - y).abs() < 1e-12, "y at {stop}");
    }
}

/// `connect(r.p, a)` over an array of components (`tests/flatten/ok/
/// component_array_connect.mo`): three sources of 1, 2, 3 V across three 2 Ω resistors
/// give 0.5, 1, 1.5 A.
#[test]
fn connects_over_arrays_of_components_connect_each_element() {
    let m = load("tests/flatten/ok/component_array_connect.mo");
    let r = run(&m, Method::Radau5, 1e-10, 1e-12, 1.0, 1);
    for (k, want) in [(1, 0.5), (2, 1.0), (3, 1.5)] {
        let i = value(&r, &format!("bank.r[{k}].p.i"));
        assert!((i - want).abs() < 1e-12, "r[{k}]: {i}");
    }
}

/// The Newton blocks are solved to what the tolerances ask: at rtol 1e-12 every
/// algebraic variable of the nonlinear loops in `AlgebraicLoops.mo` equals its closed
/// form to 1e-12 relative at every output point, also the one whose residual is scaled
/// by 1e-12 (an absolute residual threshold would have accepted it 1e-10 wide).
#[test]
fn algebraic_loops_reach_the_requested_tolerance() {
    let m = load("tests/simulate/AlgebraicLoops.mo");
    let structure = &m.analysis.dump;
    assert!(
        structure.matches("nonlinear block").count() >= 3,
        "{structure}"
    );
    let r = run(&m, Method::Bdf, 1e-12, 1e-14, 3.0, 300);
    let t = r.times.clone();
    let mut worst = 0.0f64;
    for (name, exact) in [
        ("y", (|t: f64| t) as fn(f64) -> f64),
        ("a", f64::cos),
        ("b", f64::sin),
        ("z", |t| t),
    ] {
        for (v, &t) in common::column(&r, name).iter().zip(&t) {
            let e = (v - exact(t)).abs() / (1.0 + exact(t).abs());
            assert!(e <= 1e-12, "{name} at t = {t}: {v} against {}", exact(t));
            worst = worst.max(e);
        }
    }
    eprintln!("algebraic loops at rtol 1e-12: largest relative error {worst:.1e}");
}

/// An if-expression with a parameter condition takes its branch at compile time: the
/// `der(y)` of the branch not taken is no derivative to reduce the index for (before,
/// the equation of y was differentiated and der(y) made a dummy derivative).
#[test]
fn parameter_conditions_of_if_expressions_are_decided_at_compile_time() {
    let m = load("tests/simulate/ParameterIf.mo");
    let dump = &m.analysis.dump;
    assert!(!dump.contains("der(y)"), "{dump}");
    assert!(dump.contains("(0 differentiated)"), "{dump}");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 1.0, 10);
    assert_eq!(value(&r, "y1"), 0.0);
    assert_near(value(&r, "y"), 1f64.sin(), 1e-12, "y(1)");
}

/// `when trig` with `trig = sample(0.1, 0.1)` fires at every instant, as
/// `when sample(0.1, 0.1)` does: 10 instants in (0, 1] (the last at the stop time).
#[test]
fn a_boolean_defined_by_sample_fires_at_every_instant() {
    let m = load("tests/simulate/SampleDefinedBoolean.mo");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 1.0, 10);
    assert_eq!(value(&r, "m"), 10.0);
    assert_eq!(value(&r, "n"), 10.0);
    // Between the instants trig is false.
    let trig = common::column(&r, "trig");
    assert!(r
        .times
        .iter()
        .zip(&trig)
        .any(|(&t, &b)| (t - 0.55).abs() < 0.06 && b == 0.0));
}

/// A held rounding whose step no requested output needs still updates at its events:
/// `mod(phi, 2 pi)` with only `phi` requested runs 20 s with its 3 wrap events (it
/// chattered at the first: E4006).
#[test]
fn pruning_keeps_the_steps_of_held_roundings() {
    let m = load("tests/simulate/PrunedWrap.mo");
    let phi = m.dae.ids().find(|&s| m.dae.name(s) == "phi").unwrap();
    let mut plan = m.analysis.plan.clone();
    unimo_dae::prune::prune(&m.dae, &mut plan, &[phi]);
    let compiled = unimo_codegen::model::compile(&m.dae, &plan);
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, 20.0, 0.5);
    let r = simulate(&compiled, &o);
    assert!(r.error.is_none(), "{:?}", r.error.map(|e| e.message()));
    assert_eq!(r.stats.events, 3);
    assert_near(value(&r, "phi"), 20.0, 1e-6, "phi(20)");
}

/// A `while` loop whose condition depends on variables runs (unrolled, with a check
/// that it ended): the table search gives floor(t) + 2 with its events at the whole
/// seconds; a search that would need more than the unrolled iterations stops with an
/// assertion error (E4004) at the instant it would, not with a wrong index.
#[test]
fn while_loops_on_variables_run_and_stop_when_they_would_need_more() {
    let m = load_named("WhileLoops.Search");
    let r = run(&m, Method::Bdf, 1e-8, 1e-10, 4.5, 9);
    for (t, k) in r.times.iter().zip(common::column(&r, "k")) {
        let mid = (t.fract() - 0.5).abs() < 1e-9;
        if mid {
            assert_eq!(k, t.floor() + 2.0, "t = {t}");
        }
    }
    assert_eq!(value(&r, "k"), 6.0);
    let m = load_named("WhileLoops.TooLong");
    let o = common::sim_options(Method::Bdf, 1e-8, 0.0, 1.0, 0.1);
    let r = simulate(&m.compiled, &o);
    let e = r.error.expect("the loop needs more than 64 iterations");
    assert_eq!(e.code(), "E4004");
    assert!(
        e.message().contains("more than 64 iterations"),
        "{}",
        e.message()
    );
    // 100 t passes table[65] = 64/99 there.
    let t = *r.times.last().unwrap();
    assert!((t - 0.0064646).abs() < 1e-4, "{t}");
}

/// At initialization a discrete variable whose `pre` the initial equations set equals
/// it (its `when` is not active): s = {3, 4}, then {4, 7} at t = 0, {7, 11} at 0.1 and
/// {11, 18} at 0.2; a clause reading `s` sees the value the other clause assigns at the
/// same instant, whichever comes first (twice = 2 s[2] = 36 after t = 0.2).
#[test]
fn when_clauses_of_one_instant_see_each_other() {
    let m = load_named("DiscreteInstants.Fibonacci");
    let r = run(&m, Method::Bdf, 1e-8, 1e-10, 0.25, 5);
    let at = |name: &str, t: f64| {
        let k = r.names.iter().position(|n| n == name).unwrap();
        // The last row at or before t.
        r.times
            .iter()
            .zip(&r.rows)
            .rfind(|(ti, _)| **ti <= t + 1e-12)
            .unwrap()
            .1[k]
    };
    assert_eq!(r.rows[0][column_of(&r, "s[2]")], 4.0);
    assert_eq!((at("s[1]", 0.05), at("s[2]", 0.05)), (4.0, 7.0));
    assert_eq!((at("s[1]", 0.15), at("s[2]", 0.15)), (7.0, 11.0));
    assert_eq!(at("r", 0.15), 4.0);
    assert_eq!(at("twice", 0.05), 14.0);
    assert_eq!(value(&r, "s[2]"), 18.0);
    assert_eq!(value(&r, "twice"), 36.0);
}

/// An Integer parameter with fixed = false solved from 67867967 (a difference step of
/// 1e-10 from 0 is lost in its rounding; the Jacobian entry comes from a larger step):
/// x(1) = e^-1 + k 1e-9 (1 - e^-1) with k = 2 seed.
#[test]
fn initialization_solves_for_large_integer_parameters() {
    let m = load_named("DiscreteInstants.LargeSeed");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 2);
    let e = (-1.0f64).exp();
    let exact = e + 2.0 * 67_867_967.0 * 1e-9 * (1.0 - e);
    assert_near(value(&r, "x"), exact, 1e-8, "x(1)");
}

/// A parameter with `annotation(Evaluate = true)` and one bound to it alone are fixed
/// at translation: `C * der(v2)` with C = 0 vanishes, v2 = 2/3 x = 2/3 e^-t; the DAE
/// keeps the other parameter.
#[test]
fn evaluated_parameters_fold_into_the_equations() {
    let m = load("tests/simulate/EvaluatedParameters.mo");
    let dae = unimo_dae::dump::dump(&m.dae, &|_| String::new());
    assert!(dae.contains("i = 0"), "{dae}");
    assert!(dae.contains("R2"), "{dae}");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 2);
    let exact = 2.0 / 3.0 * (-1.0f64).exp();
    assert_near(value(&r, "v2"), exact, 1e-8, "v2");
}

/// A signal an expandable connector declares but nothing uses is not part of the model
/// (spec 9.1.3): the model balances and z = 2 t + 1.
#[test]
fn unused_signals_of_an_expandable_connector_are_left_out() {
    let m = load_named("ExpandableBus.Use");
    let r = run(&m, Method::Bdf, 1e-8, 1e-10, 1.0, 2);
    assert_near(value(&r, "z"), 3.0, 1e-9, "z(1)");
    assert!(!r.names.iter().any(|n| n == "bus.unused"), "{:?}", r.names);
    // Connected buses augment each other; a set of members no component uses stays
    // absent on all of them (MultiBody's RobotR3 axis bus, 55 equations short before).
    let m = load_named("ExpandableBus.Chain");
    let r = run(&m, Method::Bdf, 1e-8, 1e-10, 1.0, 2);
    assert_near(value(&r, "b.w"), 4.0, 1e-9, "b.w");
    assert!(
        !r.names.iter().any(|n| n.ends_with(".unused")),
        "{:?}",
        r.names
    );
}

/// `x'' + 3 x' + 2 x = 1` from rest in controller form (x[2] the position): x(t) =
/// 1/2 - e^-t + e^-2t / 2, with the parameter declared after the binding that needs
/// it and `a[2:na] * x` counted as one equation.
#[test]
fn parameters_bound_to_later_ones_and_parameter_slices() {
    let m = load("tests/simulate/ParameterOrder.mo");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 2);
    let t = 1.0f64;
    let exact = 0.5 - (-t).exp() + (-2.0 * t).exp() / 2.0;
    assert_near(value(&r, "x[2]"), exact, 1e-8, "x[2]");
}

/// The one parameter evaluator (`unimo_dae::params`): a parameter with `fixed = false`
/// has no value at translation, so no structural decision is taken on its start value.
/// Before, the hidden-constraint search read a = 1 (its start), found the derivative
/// rows singular and failed the initialization. Closed form with a = 2:
/// x = (e^{l1 t} + e^{l2 t})/2, y = (e^{l2 t} - e^{l1 t})/sqrt(2), l = 1 +- sqrt(2).
#[test]
fn a_parameter_computed_at_initialization_is_not_its_start_value() {
    let m = load("tests/simulate/FixedFalseParameter.mo");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 4);
    let (l1, l2) = (1.0 + 2f64.sqrt(), 1.0 - 2f64.sqrt());
    let (kx, ky) = (column_of(&r, "x"), column_of(&r, "y"));
    for (t, row) in r.times.iter().zip(&r.rows) {
        let x = ((l1 * t).exp() + (l2 * t).exp()) / 2.0;
        let y = ((l2 * t).exp() - (l1 * t).exp()) / 2f64.sqrt();
        assert_near(row[kx], x, 1e-7 * x.abs().max(1.0), format_args!("x({t})"));
        assert_near(row[ky], y, 1e-7 * y.abs().max(1.0), format_args!("y({t})"));
    }
    assert_eq!(r.times.len(), 5);
}

/// A loop that is linear in each mode of its relations is solved by one Newton step
/// (the plan marks it "switched linear"); the same loop under `noEvent` iterates as a
/// general switched block. Both give `x = w = exp(-t/3)` (y = x/3 in the mode y > 0).
#[test]
fn switched_linear_loops_are_solved_in_one_step() {
    let m = load("tests/structure/ok/SwitchedLinearLoop.mo");
    let dump = &m.analysis.dump;
    assert!(dump.contains("switched linear block of 2"), "{dump}");
    assert!(dump.contains("  b2: switched block of 2"), "{dump}");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 3.0, 30);
    for name in ["x", "w"] {
        for (v, &t) in common::column(&r, name).iter().zip(&r.times) {
            let exact = (-t / 3.0).exp();
            assert!(
                (v - exact).abs() <= 1e-8,
                "{name} at t = {t}: {v} against {exact}"
            );
        }
    }
}

/// A function called through a component (`world.field(x)`, spec 5.3.2) is the
/// function of that instance: its short class's modifiers read the instance's
/// parameters (through `outer`), a redeclaration in the instance's modifier wins, and
/// arguments given in the call win over the modifiers.
#[test]
fn functions_called_through_components_use_the_instance() {
    let col = |r: &SimResult, n: &str| r.names.iter().position(|x| x == n).unwrap();
    let m = load_named("FunctionThroughComponent.Default");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 4);
    let kx = col(&r, "b.x");
    for (t, row) in r.times.iter().zip(&r.rows) {
        let x = 2.0 * (-t).exp() - 1.0;
        assert_near(row[kx], x, 1e-7, format_args!("x({t})"));
    }
    let m = load_named("FunctionThroughComponent.Redeclared");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 4);
    let (kx, kz, kw) = (col(&r, "b.x"), col(&r, "z"), col(&r, "w"));
    for (t, row) in r.times.iter().zip(&r.rows) {
        let x = 1.0 / (1.0 + 3.0 * t);
        assert_near(row[kx], x, 1e-7, format_args!("x({t})"));
        assert_eq!((row[kz], row[kw]), (19.0, 9.0));
    }
}

/// Candidates that all carry one `stateSelect` (`avoid`, as the MSL's quaternions) leave
/// the static order arbitrary: they get dynamic state selection, and the spin passes the
/// instants where each static choice is singular.
#[test]
fn candidates_of_one_priority_are_selected_at_run_time() {
    let m = load("tests/simulate/QuaternionSpin.mo");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 10.0, 20);
    assert_eq!(r.times.last().copied(), Some(10.0));
    let col = |n: &str| r.names.iter().position(|x| x == n).unwrap();
    let (k1, k4) = (col("Q[1]"), col("Q[4]"));
    for (t, row) in r.times.iter().zip(&r.rows) {
        let (q1, q4) = ((t / 2.0).sin(), (t / 2.0).cos());
        assert_near(row[k1], q1, 1e-6, format_args!("Q[1]({t})"));
        assert_near(row[k4], q4, 1e-6, format_args!("Q[4]({t})"));
    }
}

/// A loop with two solutions and no events (an op-amp in positive feedback under
/// `noEvent`) keeps the branch it is on until that branch ends at its fold
/// (`|v| = 7.499`), as the MSL's Multivibrator reference does: a solution the solver
/// found at a trial point beyond the fold (a rejected step, at a later time) must not be
/// the start of the evaluations before it (the output switched at `v = -7.21`).
#[test]
fn a_bistable_loop_keeps_its_branch_until_the_fold() {
    let m = load("tests/simulate/Multivibrator.mo");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 0.2, 20_000);
    let kv = column_of(&r, "v");
    let kout = column_of(&r, "vout");
    let mut switches = Vec::new();
    for w in r.rows.windows(2) {
        if (w[0][kout] > 0.0) != (w[1][kout] > 0.0) {
            switches.push(w[0][kv]);
        }
    }
    // From v = 1 to the first fold at -7.499, then every 0.05 s between the folds.
    assert_eq!(switches.len(), 4, "{switches:?}");
    for v in switches {
        assert!(
            (7.495..7.4991).contains(&v.abs()),
            "switched at v = {v}, not at the fold"
        );
    }
}

/// The same loop with events (the MSL's limited op-amp law under `strict = false`, as
/// in `Electrical.Analog.Examples.OpAmps.SignalGenerator`): at the fold of the
/// saturated branch its relation is at its root and neither outcome holds along its
/// own flow (the saturated branch leaves it, the unstable linear one comes back); the
/// event must take the loop's other consistent mode, the opposite limit. The switch
/// times are the closed form of the RC relaxation between the folds `|v| = v_f`
/// (`v_f = 15 (V0 / 2 - 1) / V0`): from `v = 1` to `-v_f` towards -15, then every
/// `RC ln((15 + v_f) / (15 - v_f))`. Before: chattering at the first fold (E4006,
/// t = 0.0345).
#[test]
fn a_comparator_in_positive_feedback_flips_at_the_fold() {
    let m = load("tests/simulate/SchmittTrigger.mo");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 0.2, 2_000);
    let kout = r.names.iter().position(|n| n == "vout").unwrap();
    let mut switches = Vec::new();
    for (k, w) in r.rows.windows(2).enumerate() {
        if (w[0][kout] > 0.0) != (w[1][kout] > 0.0) {
            // The event's two rows (left and right limit) at its time.
            let (t0, t1) = (r.times[k], r.times[k + 1]);
            assert!(t1 - t0 < 1e-9, "a switch between output points {t0}, {t1}");
            switches.push(t1);
        }
    }
    let rc = 1000.0 / 10.0 / (2.0 * 1000.0 * 3f64.ln());
    let vf: f64 = 15.0 * (15000.0 / 2.0 - 1.0) / 15000.0;
    let first = rc * (16.0 / (15.0 - vf)).ln();
    let half = rc * ((15.0 + vf) / (15.0 - vf)).ln();
    assert_eq!(switches.len(), 4, "{switches:?}");
    for (k, t) in switches.iter().enumerate() {
        let exact = first + k as f64 * half;
        assert_near(*t, exact, 1e-6, format_args!("switch {k}'s time"));
    }
}

/// A located crossing whose event leaves the function off zero on the side it came
/// from (a `reinit` 1e-11 back above the threshold, beyond the relations' noise
/// band) while the flow drives it back down: the relation keeps the side its
/// function is on, and the second crossing, 1e-8 s later, is an edge of the `when`.
/// Before, the relation took the side the flow goes to at once (the settling band
/// was 1e-10 wide, the disagreement check's 1e-14): the second edge was lost (n = 1,
/// with an extra event), and where the function moves slowly the held value
/// disagreed with its operands at every next step (E4006 in SlideRollSwitch and
/// MarkeevEllipsoid with Radau5 at rtol 1e-4).
#[test]
fn a_relation_off_zero_after_its_event_keeps_its_side() {
    let m = load("tests/simulate/SettleOffZero.mo");
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = run(&m, method, 1e-6, 1e-8, 2.0, 200);
        assert_eq!(value(&r, "n"), 2.0, "{method:?}: {:?}", r.events);
        let times: Vec<f64> = r.events.iter().map(|e| e.time).collect();
        assert_eq!(times.len(), 2, "{method:?}: {:?}", r.events);
        assert!((times[0] - 1.0).abs() < 1e-9, "{method:?}: {times:?}");
        let second = times[0] + 1e-11 / 1e-3;
        assert!((times[1] - second).abs() < 1e-12, "{method:?}: {times:?}");
    }
}

/// Index reduction that passes through the equation of a discrete variable: its
/// derivative is identically zero and stands as `der(b) = 0` (before: E3204 "no dummy
/// derivatives can be chosen ... for 0 = 0", the MSL's `KinematicPTP2` and RobotR3).
#[test]
fn index_reduction_through_a_discrete_equation() {
    let m = load("tests/simulate/DiscreteInIndexReduction.mo");
    let r = run(&m, Method::Bdf, 1e-10, 1e-12, 1.0, 4);
    let col = |n: &str| r.names.iter().position(|x| x == n).unwrap();
    let (ks, ksd, kx) = (col("s"), col("sd"), col("x"));
    for (t, row) in r.times.iter().zip(&r.rows) {
        assert!((row[ks] - t / 2.0).abs() < 1e-9, "s({t}) = {}", row[ks]);
        assert!((row[ksd] - 0.5).abs() < 1e-9, "sd({t}) = {}", row[ksd]);
        assert!((row[kx] - t / 2.0).abs() < 1e-8, "x({t}) = {}", row[kx]);
    }
}

/// Initialization starts `homotopy(actual, simplified)` at the simplified model's
/// solution: of the three solutions of the op-amp loop at the start values the lower
/// limit's (-15) is taken, not the unstable one Newton finds from the start values (0).
#[test]
fn initialization_starts_from_homotopys_simplified_model() {
    let m = load("tests/simulate/HomotopyStart.mo");
    let r = run(&m, Method::Bdf, 1e-6, 1e-8, 0.1, 2);
    let k = column_of(&r, "vout");
    for row in &r.rows {
        assert_eq!(row[k], -15.0, "{:?}", r.rows);
    }
    let k = column_of(&r, "vin");
    assert!((r.rows[0][k] + 7.5).abs() < 1e-12, "{:?}", r.rows[0]);
}

/// `x = cos(10 t)` on an output grid of 0.5 (longer than its period): the default
/// output adds the steps a straight line between rows would misstate, so linear
/// interpolation of the CSV follows the closed form; `--output-tolerance 0` writes the
/// grid alone, which does not.
#[test]
fn rows_between_grid_points_follow_the_solution() {
    let worst = |extra: &[&str]| {
        let csv = common::temp("simulate", &format!("coarse{}.csv", extra.len()));
        let csv_s = csv.to_string_lossy().into_owned();
        let mut args = vec![
            "simulate",
            "tests/simulate/CoarseGrid.mo",
            "--tolerance",
            "1e-8",
            "--vars",
            "x",
            "-o",
            &csv_s,
        ];
        args.extend_from_slice(extra);
        let o = common::unimo(&args);
        common::assert_success(&o);
        let text = std::fs::read_to_string(&csv).unwrap();
        let rows: Vec<(f64, f64)> = text
            .lines()
            .skip(1)
            .map(|l| {
                let mut c = l.split(',').map(|v| v.parse::<f64>().unwrap());
                (c.next().unwrap(), c.next().unwrap())
            })
            .collect();
        let at = |t: f64| {
            let k = rows.partition_point(|r| r.0 <= t).clamp(1, rows.len() - 1);
            let ((t0, x0), (t1, x1)) = (rows[k - 1], rows[k]);
            x0 + (t - t0) / (t1 - t0) * (x1 - x0)
        };
        let err = (0..=3000)
            .map(|k| k as f64 * 1e-3)
            .map(|t| (at(t) - (10.0 * t).cos()).abs())
            .fold(0.0, f64::max);
        (err, rows.len())
    };
    let (refined, n_refined) = worst(&[]);
    let (grid, n_grid) = worst(&["--output-tolerance", "0"]);
    assert_eq!(n_grid, 7, "the grid 0, 0.5, ..., 3");
    assert!(grid > 0.5, "the grid alone misses the oscillation: {grid}");
    // The chord holds at the steps to 1e-3; between steps it is the step's own chord.
    assert!(refined < 5e-3, "{refined} with {n_refined} rows");
    eprintln!("grid alone {grid:.3} ({n_grid} rows), refined {refined:.2e} ({n_refined} rows)");
}

/// A call whose outputs are unused and whose function reaches an external function
/// unimo does not provide (a file written) is not executed, and said so (`W3001`, the
/// run goes on); a pure function's unused call is dropped without a word. Before, both
/// were dropped silently.
#[test]
fn an_unexecuted_call_with_effects_is_a_warning() {
    let out = common::temp("simulate", "UnexecutedCall.csv");
    let run = common::unimo(&[
        "simulate",
        "tests/simulate/UnexecutedCall.mo",
        "--output",
        out.to_str().unwrap(),
    ]);
    let (code, _, stderr) = common::code_and_text(run);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stderr.matches("warning[W3001]").count(), 1, "{stderr}");
    assert!(
        stderr.contains("`UnexecutedCall.report`") && stderr.contains("`myWriteValue`"),
        "{stderr}"
    );
    let _ = std::fs::remove_file(out);
}

/// Two relative angles of the same flanges, both `prefer`: the dummy derivatives the
/// structure alone picks (the flanges' accelerations) have equal coefficients in both
/// constraints, a singular choice; the regular one keeps one relative angle as state.
/// x'' = -20 x, x(0) = 0.1, x'(0) = 0.
#[test]
fn dependent_preferred_states_give_up_a_regular_set_of_dummies() {
    let r = run_file("tests/simulate/DependentRelativeStates.mo", 1.0, 4);
    let x = value(&r, "x");
    let exact = 0.1 * (20f64.sqrt()).cos();
    assert_near(x, exact, 1e-6, "x(1)");
    assert_near(value(&r, "y"), x, 1e-12, "y(1)");
}

/// The initial equations draw `r = sin(seed * 1e9)` from the free parameter `seed` and
/// fix `x + r = 0`: the Jacobian's column for `seed` draws from a perturbed seed, and
/// that draw must not be what the next iterate reads (the registers of the base point
/// are restored after the columns). Without that Newton did not converge.
#[test]
fn initial_jacobian_leaves_no_perturbed_values_behind() {
    let r = run_file("tests/simulate/InitialDrawFromSeed.mo", 0.2, 1);
    let x0 = r.rows[0][r.names.iter().position(|n| n == "x").unwrap()];
    let exact = -(7e9f64).sin();
    assert_near(x0, exact, 1e-9, "x(0)");
}

/// The method of `simulate --stats`'s JSON line.
fn method_of_run(args: &[&str]) -> String {
    let o = common::unimo(args);
    common::assert_success(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    let stats = err
        .lines()
        .find(|l| l.starts_with('{'))
        .expect("a --stats line");
    let (_, rest) = stats.split_once("\"method\":\"").expect("a method");
    rest.split('"').next().unwrap().to_owned()
}

/// `experiment(__unimo_method = "radau5")` chooses the method when the user does not;
/// `--method` still wins.
#[test]
fn the_experiment_annotation_chooses_the_method_unless_the_user_does() {
    let file = "tests/simulate/ExperimentMethod.mo";
    let null = if cfg!(windows) { "NUL" } else { "/dev/null" };
    let asked = method_of_run(&["simulate", file, "--stats", "-o", null]);
    assert_eq!(asked, "radau5");
    let chosen = method_of_run(&["simulate", file, "--stats", "--method", "bdf", "-o", null]);
    assert_eq!(chosen, "bdf");
    let plain = method_of_run(&["simulate", "models/Dahlquist.mo", "--stats", "-o", null]);
    assert_eq!(plain, "auto", "no annotation: the default (BDF)");
}

/// `E3023`: a method name unimo does not have is an error at its place, not a silent BDF.
#[test]
fn an_unknown_experiment_method_is_a_coded_error() {
    let o = common::unimo(&[
        "simulate",
        "tests/simulate/UnknownMethod.mo",
        "-o",
        "/dev/null",
    ]);
    assert_eq!(o.status.code(), Some(1));
    insta::assert_snapshot!(String::from_utf8_lossy(&o.stderr));
}

/// Every name lowering accepts in `__unimo_method` is a method the runtime runs.
#[test]
fn every_experiment_method_name_is_a_method() {
    for name in unimo_dae::dae::METHOD_NAMES {
        assert!(
            unimo_solve::Method::from_name(name).is_some(),
            "{name} is accepted by lowering but names no method"
        );
    }
    assert_eq!(unimo_solve::Method::from_name("dassl"), None);
}

#[test]
fn an_explicit_method_on_a_stiff_model_says_so() {
    let run = |method: &str| {
        let out = common::unimo(&[
            "simulate",
            "tests/simulate/StiffTracking.mo",
            "--method",
            method,
            "--stats",
            "-o",
            "/dev/null",
        ]);
        common::assert_success(&out);
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        // Scripts read the `--stats` object as the last line of a run that ends well.
        let last = stderr.trim_end().lines().last().unwrap_or("");
        assert!(last.starts_with("{\"method\""), "{method}: {stderr}");
        stderr
    };
    let explicit = run("dopri5");
    assert!(
        explicit.contains("note: the problem looks stiff from t = "),
        "{explicit}"
    );
    for method in ["bdf", "radau5"] {
        let implicit = run(method);
        assert!(!implicit.contains("looks stiff"), "{method}: {implicit}");
    }
}
