//! `delay(e, delayTime[, delayMax])` (spec 3.7.4.1) against closed forms: a delay
//! differential equation solved by the method of steps, delayed sines with fixed and
//! varying delays, a delayed jump, the MSL's `FixedDelay` and `VariableDelay` blocks and
//! lossless transmission lines (`../shared/msl`, skipped without it), and the coded
//! error for a delay time that is no parameter expression. The models are in
//! `tests/simulate/Delays.mo` (also run natively by `tests/native.rs`) and `tests/delay/`.

mod common;

use std::path::{Path, PathBuf};
use unimo_runtime::sim::{Overrides, SimOptions, SimResult};
use unimo_solve::Method;

/// Simulates `Delays.<model>` with the tolerance, method and output interval given.
fn run(model: &str, rtol: f64, method: Method, interval: f64) -> SimResult {
    let l = common::load("tests/simulate/Delays.mo", Some(&format!("Delays.{model}")));
    let over = Overrides {
        rtol: Some(rtol),
        interval: Some(interval),
        ..Overrides::default()
    };
    let o = SimOptions::resolve(&l.dae.experiment, &over, method, false).expect("options");
    let r = unimo_runtime::sim::simulate(&l.compiled, &o);
    assert!(r.error.is_none(), "{model}: {:?}", r.error);
    r
}

/// Column `name` of a result.
fn column(r: &SimResult, name: &str) -> Vec<f64> {
    let k = r.names.iter().position(|n| n == name).expect(name);
    r.rows.iter().map(|row| row[k]).collect()
}

/// The largest difference between column `name` and `exact` over the rows.
fn worst(r: &SimResult, name: &str, exact: impl Fn(f64) -> f64) -> f64 {
    let y = column(r, name);
    r.times
        .iter()
        .zip(&y)
        .map(|(&t, &v)| (v - exact(t)).abs())
        .fold(0.0, f64::max)
}

/// x' = -x(t - 1), x = 1 up to t = 0: x = 1 - t on [0, 1], then + (t - 1)^2/2 on
/// [1, 2], then - (t - 2)^3/6 on [2, 3].
fn method_of_steps(t: f64) -> f64 {
    let mut x = 1.0 - t;
    if t > 1.0 {
        x += (t - 1.0).powi(2) / 2.0;
    }
    if t > 2.0 {
        x -= (t - 2.0).powi(3) / 6.0;
    }
    x
}

#[test]
fn a_delay_differential_equation_follows_the_method_of_steps() {
    for method in [Method::Bdf, Method::Radau5] {
        let r = run("Closed", 1e-8, method, 0.5);
        let x = column(&r, "x");
        for t in [1.0, 2.0, 3.0] {
            let k = r.times.iter().position(|&s| s == t).expect("grid point");
            let err = (x[k] - method_of_steps(t)).abs();
            assert!(err < 1e-6, "{method:?}: x({t}) off by {err:e}");
        }
        // The steps end where the delay moves the start's discontinuity (t = 1, 2,
        // 3), so each piece is a polynomial the methods integrate to rounding: without
        // those breakpoints BDF stays 4e-8 off at t = 3 whatever the tolerance.
        let r = run("Closed", 1e-10, method, 0.5);
        let err = (column(&r, "x").last().unwrap() - method_of_steps(3.0)).abs();
        assert!(err < 1e-11, "{method:?} at 1e-10: x(3) off by {err:e}");
        assert_eq!(r.times.iter().filter(|&&t| t == 3.0).count(), 1);
    }
}

#[test]
fn a_delayed_sine_is_the_sine_before() {
    let exact = |t: f64| if t > 0.5 { (t - 0.5).sin() } else { 0.0 };
    // Without states (the output grid) and with a state whose steps do not follow the
    // sine (the history is refined where its interpolant misses the dense output).
    let r = run("Sine", 1e-8, Method::Auto, 0.0123);
    assert!(worst(&r, "y", exact) < 1e-8, "{:e}", worst(&r, "y", exact));
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = run("SineWithState", 1e-10, method, 0.0123);
        let err = worst(&r, "y", exact);
        assert!(err < 1e-8, "{method:?}: {err:e}");
    }
}

#[test]
fn a_varying_delay_reads_its_own_time() {
    let at = |t: f64| t - (0.5 + 0.25 * t.sin());
    let r = run("Variable", 1e-8, Method::Bdf, 0.01);
    let err = worst(&r, "y", |t| (2.0 * at(t).max(0.0)).cos());
    assert!(err < 1e-7, "{err:e}");
    // x = integral of y: 1 up to t0, where t0 - d(t0) = 0, then cos(2 at(t)).
    let x = column(&r, "x");
    let (k, t) = (r.times.len() - 1, *r.times.last().unwrap());
    let t0 = (0..100).fold(0.5f64, |s, _| 0.5 + 0.25 * s.sin());
    let n = 200_000;
    let h = (t - t0) / n as f64;
    let integral: f64 = (0..n)
        .map(|i| (2.0 * at(t0 + (i as f64 + 0.5) * h)).cos() * h)
        .sum();
    let err = (x[k] - (t0 + integral)).abs();
    assert!(err < 1e-6, "x({t}) off by {err:e}");
}

#[test]
fn a_varying_delay_time_is_held_in_its_bounds() {
    let r = run("Held", 1e-8, Method::Auto, 0.01);
    let at = |t: f64| t - (2.0 * t.sin()).clamp(0.0, 1.0);
    let err = worst(&r, "y", |t| at(t).max(0.0));
    assert!(err < 1e-12, "{err:e}");
}

/// The steps are capped at the delay (uncapped, Dormand–Prince's 78 steps read past
/// the last accepted point and end 1e-2 off).
#[test]
fn a_delay_shorter_than_the_steps_caps_them() {
    let exact = |t: f64| if t > 0.1 { 1.0 - (t - 0.1).cos() } else { 0.0 };
    for method in [Method::Radau5, Method::Dopri5] {
        let r = run("Short", 1e-6, method, 0.05);
        let err = worst(&r, "x", exact);
        assert!(err < 1e-5, "{method:?}: {err:e}");
    }
}

#[test]
fn a_delayed_jump_comes_later_and_whole() {
    let r = run("Jump", 1e-8, Method::Bdf, 0.25);
    let y = column(&r, "y");
    for (&t, &v) in r.times.iter().zip(&y) {
        let exact = if t >= 1.5 { 1.0 } else { 0.0 };
        assert!((v - exact).abs() < 1e-12, "y({t}) = {v}");
    }
    // x = integral of y = t - 1.5 after 1.5.
    let x = column(&r, "x");
    assert!(
        (x.last().unwrap() - 1.5).abs() < 1e-8,
        "{}",
        x.last().unwrap()
    );
}

#[test]
fn a_delay_time_that_varies_needs_a_delay_max() {
    let o = common::unimo(&["simulate", "tests/delay/BadDelay.mo", "-o", "/dev/null"]);
    assert_eq!(o.status.code(), Some(1));
    let text = String::from_utf8_lossy(&o.stderr);
    assert!(text.contains("error[E3024]") && text.contains("BadDelay.mo:4:22"));
    insta::assert_snapshot!(text);
}

/// The MSL beside the project, or `None` (the test is then skipped).
fn msl() -> Option<PathBuf> {
    let path = common::root().join("..").join("shared").join("msl");
    if path.is_dir() {
        Some(path)
    } else {
        eprintln!("skipped: the MSL is not at {}", path.display());
        None
    }
}

/// Simulates `model` (of `file`, or of the library) with the MSL; the result's rows.
fn simulate_msl(msl: &Path, file: Option<&str>, model: &str, out: &str) -> SimCsv {
    let out = common::temp("delay", out);
    let mut args: Vec<String> = vec!["simulate".into()];
    args.extend(file.map(String::from));
    args.extend(["--model", model, "--lib"].map(String::from));
    args.push(msl.display().to_string());
    args.extend(["-o".into(), out.display().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = common::unimo(&args);
    common::assert_success(&run);
    SimCsv::read(&out)
}

/// A CSV result: its header and rows.
struct SimCsv {
    names: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl SimCsv {
    fn read(path: &Path) -> SimCsv {
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let names = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect();
        SimCsv { names, rows }
    }

    /// The largest difference of column `name` from `exact(time)`, rows within `skip`
    /// of `jumps` left out.
    fn worst(&self, name: &str, exact: impl Fn(f64) -> f64, jumps: &[f64], skip: f64) -> f64 {
        let k = self.names.iter().position(|n| n == name).expect(name);
        self.rows
            .iter()
            .filter(|r| jumps.iter().all(|j| (r[0] - j).abs() > skip))
            .map(|r| (r[k] - exact(r[0])).abs())
            .fold(0.0, f64::max)
    }
}

#[test]
fn the_msl_delay_blocks_delay_a_sine() {
    let Some(msl) = msl() else { return };
    let r = simulate_msl(
        &msl,
        Some("tests/delay/FixedDelaySine.mo"),
        "FixedDelaySine",
        "FixedDelaySine.csv",
    );
    let sine = |t: f64| 2.0 * (2.0 * std::f64::consts::PI * t.max(0.0)).sin();
    let ramp = |t: f64| 0.2 + 0.25 * t.clamp(0.0, 2.0);
    let fixed = r.worst("fixedDelay.y", |t| sine(t - 0.3), &[], 0.0);
    let variable = r.worst("variableDelay.y", |t| sine(t - ramp(t)), &[], 0.0);
    assert!(fixed < 1e-8 && variable < 1e-7, "{fixed:e}, {variable:e}");
}

/// `CompareLosslessLines`: a 10 V pulse on [2.5, 5) ns through a 50 Ohm source into
/// three lines of delay 5 ns: matched (the half-voltage wave arrives once), open (it
/// doubles at the end and comes back to the matched source) and shorted (it comes
/// back inverted).
#[test]
fn lossless_lines_carry_a_pulse_as_waves() {
    let Some(msl) = msl() else { return };
    let r = simulate_msl(
        &msl,
        None,
        "Modelica.Electrical.Analog.Examples.Lines.CompareLosslessLines",
        "CompareLosslessLines.csv",
    );
    let on = |t: f64, a: f64, b: f64| f64::from(u8::from(a * 1e-9 <= t && t < b * 1e-9));
    let jumps: Vec<f64> = (1..=6).map(|k| 2.5e-9 * k as f64).collect();
    let cases: [(&str, &dyn Fn(f64) -> f64); 6] = [
        ("line1.v1", &|t| 5.0 * (on(t, 2.5, 5.0) + on(t, 12.5, 15.0))),
        ("line1.v2", &|t| 10.0 * on(t, 7.5, 10.0)),
        ("line2.v1", &|t| 5.0 * on(t, 2.5, 5.0)),
        ("line2.v2", &|t| 5.0 * on(t, 7.5, 10.0)),
        ("line3.v1", &|t| 5.0 * (on(t, 2.5, 5.0) - on(t, 12.5, 15.0))),
        ("line3.v2", &|_| 0.0),
    ];
    assert!(r.rows.len() > 100);
    for (name, exact) in cases {
        let err = r.worst(name, exact, &jumps, 1e-13);
        assert!(err < 1e-9, "{name}: {err:e}");
    }
}
