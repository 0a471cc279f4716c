//! Events and extreme cases (issue 15) against independent references: closed forms of
//! event instants, of the held values of `integer`/`floor`/`ceil`/`div`/`mod`/`rem`, of
//! the bouncing ball's impacts, of stiff and huge-valued solutions; failures must stop
//! with their code (never exit 0 with NaN or inf in the result).

mod common;

use unimo_runtime::sim::{simulate, SimError, SimOptions, SimResult};
use unimo_solve::Method;

fn run(file: &str, o: &SimOptions) -> SimResult {
    let m = common::load(file, None);
    simulate(&m.compiled, o)
}

fn ok(file: &str, o: &SimOptions) -> SimResult {
    let r = run(file, o);
    assert!(
        r.error.is_none(),
        "{file} {:?}: {:?}",
        o.method,
        r.error.as_ref().map(|e| e.message())
    );
    r
}

fn column(r: &SimResult, name: &str) -> Vec<f64> {
    common::column(r, name)
}

fn last(r: &SimResult, name: &str) -> f64 {
    *column(r, name).last().unwrap()
}

/// Times at which `name` changed value (the right-limit row of each event).
fn changes(r: &SimResult, name: &str) -> Vec<f64> {
    let values = column(r, name);
    (1..values.len())
        .filter(|&i| values[i] != values[i - 1])
        .map(|i| r.times[i])
        .collect()
}

fn assert_finite(r: &SimResult) {
    for (t, row) in r.times.iter().zip(&r.rows) {
        assert!(
            row.iter().all(|v| v.is_finite()),
            "non-finite row at t = {t}: {row:?}"
        );
    }
}

/// `integer(time/0.1)` changes at k/10 (to 1e-12) and `when change(tick)` fires each
/// time; `mod`, `div`, `rem`, `ceil` of time equal their closed forms away from their
/// jumps, for every method.
#[test]
fn roundings_of_time_are_held_and_fire_at_their_instants() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/HeldTimeEvents.mo",
            &common::sim_options(method, 1e-6, 0.0, 0.95, 0.01),
        );
        let ticks = changes(&r, "tick");
        assert_eq!(ticks.len(), 9, "{method:?}: {ticks:?}");
        for (k, t) in ticks.iter().enumerate() {
            let want = 0.1 * (k + 1) as f64;
            assert!(
                (t - want).abs() <= 1e-12,
                "{method:?}: tick {k} at {t}, want {want}"
            );
        }
        assert_eq!(
            changes(&r, "changes"),
            ticks,
            "{method:?}: change(tick) fired elsewhere"
        );
        assert_eq!(last(&r, "changes"), 9.0);
        // Closed forms on rows away (1e-9) from every jump.
        let jumps = |t: f64, period: f64, offset: f64| {
            let u = (t - offset) / period;
            (u - u.round()).abs() * period < 1e-9
        };
        let (saw, q, rem, c) = (
            column(&r, "saw"),
            column(&r, "q"),
            column(&r, "r"),
            column(&r, "c"),
        );
        for (i, &t) in r.times.iter().enumerate() {
            if !jumps(t, 0.25, 0.0) {
                let want = t - (t / 0.25).floor() * 0.25;
                assert!(
                    (saw[i] - want).abs() < 1e-12,
                    "{method:?} mod at {t}: {} vs {want}",
                    saw[i]
                );
                assert_eq!(c[i], (4.0 * t).ceil(), "{method:?} ceil at {t}");
            }
            if !jumps(t, 0.2, 0.55) {
                let quotient = ((t - 0.55) / 0.2).trunc();
                assert_eq!(q[i], quotient, "{method:?} div at {t}");
                let want = (t - 0.55) - quotient * 0.2;
                assert!((rem[i] - want).abs() < 1e-12, "{method:?} rem at {t}");
            }
        }
        // div and rem of a negative argument truncate towards zero: -0.55/0.2 -> -2.
        assert_eq!(q[0], -2.0);
    }
}

/// `floor(x)` of the state x = 2.5 sin(t) changes exactly where x crosses an integer:
/// t = asin(k/2.5) and its mirror images, located to the integration accuracy.
#[test]
fn floor_of_a_state_changes_at_the_crossings() {
    let a: f64 = 2.5;
    let mut want: Vec<f64> = Vec::new();
    for k in -2..=2 {
        let base = (k as f64 / a).asin();
        for t in [
            base,
            std::f64::consts::PI - base,
            2.0 * std::f64::consts::PI + base,
        ] {
            if t > 1e-9 && t < 6.0 {
                want.push(t);
            }
        }
    }
    want.sort_by(f64::total_cmp);
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/HeldStateEvents.mo",
            &common::sim_options(method, 1e-10, 0.0, 6.0, 0.1),
        );
        let got = changes(&r, "n");
        assert_eq!(got.len(), want.len(), "{method:?}: {got:?} vs {want:?}");
        for (t, w) in got.iter().zip(&want) {
            assert!(
                (t - w).abs() < 1e-7,
                "{method:?}: floor changed at {t}, want {w}"
            );
        }
        // The held value is floor(x) on every row.
        for (n, x) in column(&r, "n").iter().zip(column(&r, "x")) {
            if (x - x.round()).abs() > 1e-9 {
                assert_eq!(*n, x.floor(), "{method:?}: n = {n} at x = {x}");
            }
        }
        assert_eq!(last(&r, "changes"), want.len() as f64);
    }
}

/// Impact n of a ball dropped from h: t_n = (v1/g)(1 + 2e(1 - e^(n-1))/(1 - e)).
fn impact_time(n: i32, h: f64, g: f64, e: f64) -> f64 {
    let v1 = (2.0 * g * h).sqrt();
    v1 / g * (1.0 + 2.0 * e * (1.0 - e.powi(n - 1)) / (1.0 - e))
}

/// The resting rule of issue 15 (`v` stays exactly 0 after the last bounce, so its
/// crossing function is identically zero): the ball rests at the Zeno time and the
/// run finishes, for every method, with the impacts at their closed-form times.
#[test]
fn resting_ball_rests_instead_of_collapsing_the_step() {
    let (h, g, e): (f64, f64, f64) = (10.0, 9.81, 0.8);
    let zeno = (2.0 * h / g).sqrt() * (1.0 + e) / (1.0 - e);
    // vmin = 1e-6, and 1e-9: then the last bounces are below what the tolerances
    // resolve (heights of 1e-14), where a crossing function leaves zero unseen.
    for model in ["RestingBall", "RestingBallTiny"] {
        let m = common::load("tests/extreme/RestingBall.mo", Some(model));
        for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
            for rtol in [1e-6, 1e-8] {
                let r = simulate(
                    &m.compiled,
                    &common::sim_options(method, rtol, 0.0, 20.0, 0.05),
                );
                let case = format!("{model} {method:?} {rtol:e}");
                assert!(
                    r.error.is_none(),
                    "{case}: {:?}",
                    r.error.map(|e| e.message())
                );
                assert_eq!(last(&r, "flying"), 0.0, "{case}");
                assert_eq!(last(&r, "v"), 0.0, "{case}");
                let rest_height = last(&r, "h");
                assert!(rest_height.abs() < 1e-9, "{case}: h = {rest_height}");
                let bounces = changes(&r, "bounces");
                let rest = *changes(&r, "flying").last().expect("it comes to rest");
                assert!(
                    (rest - zeno).abs() < 1e-5,
                    "{case}: rests at {rest}, Zeno time {zeno}"
                );
                // The first 30 impacts against the closed form.
                for (n, t) in bounces.iter().take(30).enumerate() {
                    let want = impact_time(n as i32 + 1, h, g, e);
                    assert!(
                        ((t - want) / want).abs() < 1e-9,
                        "{case}: impact {n} at {t}, want {want}"
                    );
                }
            }
        }
    }
}

/// Sliding on x = 0 (`der(x) = if x > 0 then -1 else 1`): a relation never stays on the
/// wrong side of its crossing; the run stops with E4006 naming the relation at t = 1.
#[test]
fn chattering_stops_with_a_coded_error_naming_the_relation() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = run(
            "tests/extreme/Chattering.mo",
            &common::sim_options(method, 1e-6, 0.0, 2.0, 0.01),
        );
        let e = r
            .error
            .as_ref()
            .unwrap_or_else(|| panic!("{method:?}: no error"));
        assert_eq!(e.code(), "E4006", "{method:?}: {}", e.message());
        assert!(e.message().contains("x > 0"), "{}", e.message());
        let SimError::Chattering { time, .. } = e else {
            unreachable!()
        };
        // It slides from the closed-form instant t = 1 on.
        let first = r.events.first().expect("events").time;
        assert!(
            (first - 1.0).abs() < 1e-12,
            "{method:?}: first event at {first}"
        );
        assert!(
            *time >= first && *time < 1.001,
            "{method:?}: chattering at {time}"
        );
        // Before the error x followed 1 - t, never below 0 by more than the tolerance.
        for x in column(&r, "x") {
            assert!(
                x > -1e-6,
                "{method:?}: x = {x}: the relation stayed true below 0"
            );
        }
        assert_finite(&r);
    }
}

/// A NaN (`sqrt` of a negative number after t = 1) stops the run with E4007 naming the
/// variable and the equation; no row with a NaN is written.
#[test]
fn nan_names_the_variable_and_equation() {
    let m = common::load("tests/extreme/SqrtOfNegative.mo", None);
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = simulate(
            &m.compiled,
            &common::sim_options(method, 1e-6, 0.0, 2.0, 0.004),
        );
        let e = r.error.as_ref().expect("NaN is an error");
        assert_eq!(e.code(), "E4007", "{}", e.message());
        let SimError::NonFinite {
            time,
            variable,
            value,
            equation,
            step,
        } = e
        else {
            unreachable!()
        };
        assert_eq!(variable, "y");
        assert!(value.is_nan());
        assert!(
            *time >= 1.0 && *time <= 1.004 + 1e-12,
            "{method:?}: NaN at {time}"
        );
        assert!(step.is_some());
        let eq = &m.dae.equations[equation.expect("an equation").index()];
        let mut text = String::new();
        let name = |s| m.dae.name(s);
        m.dae.arena.write(eq.lhs, &name, &mut text).unwrap();
        text += " = ";
        m.dae.arena.write(eq.rhs, &name, &mut text).unwrap();
        assert_eq!(text, "y = sqrt(x)");
        assert_finite(&r);
    }
}

/// exp(1000 t) overflows at t* = ln(f64::MAX)/1000: E4007 at the first output point
/// after t*, every written row finite.
#[test]
fn overflow_is_an_error_not_an_inf_in_the_result() {
    let t_star = f64::MAX.ln() / 1000.0;
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = run(
            "tests/extreme/Overflow.mo",
            &common::sim_options(method, 1e-6, 0.0, 1.0, 0.002),
        );
        let e = r.error.as_ref().expect("overflow is an error");
        let SimError::NonFinite {
            time,
            variable,
            value,
            ..
        } = e
        else {
            panic!("{method:?}: {}", e.message())
        };
        assert_eq!(variable, "y");
        assert!(value.is_infinite());
        assert!(
            *time >= t_star && *time <= t_star + 0.002,
            "{method:?}: inf at {time}, t* = {t_star}"
        );
        assert_finite(&r);
    }
}

/// Start = stop: one row with the consistent initial values.
#[test]
fn zero_length_interval_gives_the_initial_values() {
    let r = ok(
        "tests/extreme/ZeroLength.mo",
        &common::sim_options(Method::Bdf, 1e-6, 1.0, 1.0, 1.0),
    );
    assert_eq!(r.times, vec![1.0]);
    assert_eq!(last(&r, "x"), 1.0);
    assert_eq!(last(&r, "y"), 2.0);
}

/// Stiffness ratio 1e9: x' = -1e9 (x - cos t) against its closed form
/// x = (k^2 cos t + k sin t)/(k^2 + 1) - k^2/(k^2 + 1) e^(-k t), y = e^(-t).
#[test]
fn stiffness_ratio_1e9_matches_the_closed_form() {
    let k: f64 = 1e9;
    let x1 = (k * k * 1f64.cos() + k * 1f64.sin()) / (k * k + 1.0);
    for method in [Method::Bdf, Method::Radau5] {
        let r = ok(
            "tests/extreme/Stiff1e9.mo",
            &common::sim_options(method, 1e-8, 0.0, 1.0, 0.5),
        );
        let x = last(&r, "x");
        let y = last(&r, "y");
        assert!(
            ((x - x1) / x1).abs() < 1e-7,
            "{method:?}: x(1) = {x}, want {x1}"
        );
        assert!((y - (-1f64).exp()).abs() < 1e-7, "{method:?}: y(1) = {y}");
        assert!(
            r.stats.solver.steps < 2000,
            "{method:?}: {} steps",
            r.stats.solver.steps
        );
    }
}

/// 10,000 state events (a sawtooth reset at x = 1e-3): all of them, the last at
/// t = 10 to 1e-9.
#[test]
fn ten_thousand_events() {
    let r = ok(
        "tests/extreme/TenThousandEvents.mo",
        &common::sim_options(Method::Auto, 1e-8, 0.0, 10.0005, 0.5),
    );
    assert_eq!(last(&r, "resets"), 10_000.0);
    let resets = changes(&r, "resets");
    let final_event = *resets.last().unwrap();
    assert!(
        (final_event - 10.0).abs() < 1e-9,
        "last reset at {final_event}"
    );
    assert_eq!(r.stats.events, 10_000);
}

/// Start values of 1e300 (and -1e300): x = 1e300 e^(-t), z = -1e300 + t (= -1e300).
#[test]
fn start_values_of_1e300() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/HugeStart.mo",
            &common::sim_options(method, 1e-8, 0.0, 1.0, 0.1),
        );
        let want = 1e300 * (-1f64).exp();
        let x = last(&r, "x");
        assert!(
            ((x - want) / want).abs() < 1e-6,
            "{method:?}: x(1) = {x:e}, want {want:e}"
        );
        assert_eq!(last(&r, "z"), -1e300);
        assert_finite(&r);
    }
}

/// `sample(0, 0.25)` fires at the start and at the stop time too (5 instants in
/// [0, 1]); `initial()` fires once.
#[test]
fn events_at_the_start_and_at_the_stop_time() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/StartStopEvents.mo",
            &common::sim_options(method, 1e-6, 0.0, 1.0, 0.1),
        );
        assert_eq!(last(&r, "n"), 5.0, "{method:?}");
        assert_eq!(last(&r, "inits"), 1.0, "{method:?}");
        let n_changes = changes(&r, "n");
        assert_eq!(n_changes.first(), Some(&0.0), "{method:?}: {n_changes:?}");
        assert_eq!(n_changes.last(), Some(&1.0), "{method:?}: {n_changes:?}");
    }
}

/// A collision body 1e300 long (parry's manifolds panicked on such shapes): the shape
/// is refused with the geometry crate's error, and the run stops with it at t = 0.
#[test]
fn a_body_1e300_long_is_an_error_not_a_panic() {
    let r = run(
        "tests/extreme/HugeBody.mo",
        &common::sim_options(Method::Bdf, 1e-6, 0.0, 1.0, 0.01),
    );
    let e = r.error.as_ref().expect("the shape is refused");
    assert!(
        e.message()
            .contains("must be positive and at most 1e12, got 1e300"),
        "{}",
        e.message()
    );
    assert_finite(&r);
}

/// The issue's `tick = integer(time/period)` with `when change(tick)` in a model
/// without states: the solvers step a constant clock state, so the when fires at every
/// k/10 (to 1e-12).
#[test]
fn change_of_integer_time_fires_without_states() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/TickWithoutStates.mo",
            &common::sim_options(method, 1e-6, 0.0, 0.95, 0.01),
        );
        let fired = changes(&r, "count");
        assert_eq!(fired.len(), 9, "{method:?}: {fired:?}");
        for (k, t) in fired.iter().enumerate() {
            let want = 0.1 * (k + 1) as f64;
            assert!(
                (t - want).abs() <= 1e-12,
                "{method:?}: fired at {t}, want {want}"
            );
        }
        assert_eq!(changes(&r, "tick"), fired);
        assert!(r.final_states.is_empty());
    }
}

/// `edge` and `change` of a Boolean that is true while sin(2 pi (t - 1/4)) > 0: rises
/// at 1/4 and 5/4, falls at 3/4 and 7/4 (to 1e-12), `change` at all four.
#[test]
fn edge_and_change_fire_at_the_switches() {
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = ok(
            "tests/extreme/EdgeAndChange.mo",
            &common::sim_options(method, 1e-6, 0.0, 2.0, 0.01),
        );
        let close = |got: Vec<f64>, want: &[f64]| {
            assert_eq!(got.len(), want.len(), "{method:?}: {got:?} vs {want:?}");
            for (t, w) in got.iter().zip(want) {
                assert!((t - w).abs() < 1e-12, "{method:?}: {t} vs {w}");
            }
        };
        close(changes(&r, "rises"), &[0.25, 1.25]);
        close(changes(&r, "falls"), &[0.75, 1.75]);
        close(changes(&r, "switches"), &[0.25, 0.75, 1.25, 1.75]);
    }
}

/// A ball without a resting rule past its Zeno time (`tests/extreme/LowBall.mo`): its
/// last bounces are lower than the rounding noise in `h`, where `h < 0` stays true
/// through a bounce and the ball would fall through the floor with exit status 0
/// (h = -309 m at t = 12 for h0 = 1 before `sim/zeno.rs`). Every method and tolerance
/// stops with a code at the Zeno time instead, and no row is below the floor.
#[test]
fn a_ball_past_its_zeno_time_stops_there_instead_of_falling_through() {
    let (g, e): (f64, f64) = (9.81, 0.8);
    for (model, h0) in [("LowBall", 1.0), ("LowBall2", 2.0), ("LowBall5", 5.0)] {
        let zeno = (2.0 * h0 / g).sqrt() * (1.0 + e) / (1.0 - e);
        let m = common::load("tests/extreme/LowBall.mo", Some(model));
        for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
            for rtol in [1e-4, 1e-6, 1e-8] {
                let r = simulate(
                    &m.compiled,
                    &common::sim_options(method, rtol, 0.0, 20.0, 0.05),
                );
                let case = format!("{model} {method:?} {rtol:e}");
                let code = r.error.as_ref().map(SimError::code);
                assert!(
                    matches!(code, Some("E4006" | "E4008")),
                    "{case}: {:?}",
                    r.error.as_ref().map(SimError::message)
                );
                let lowest = column(&r, "h").into_iter().fold(f64::INFINITY, f64::min);
                assert!(lowest > -1e-12, "{case}: h = {lowest}");
                let end = *r.times.last().unwrap();
                assert!(
                    (end - zeno).abs() < 1e-6,
                    "{case}: stopped at {end}, Zeno time {zeno}"
                );
            }
        }
    }
}
