//! The reference's own checks: the impact law does what it says, and the event sequence
//! of FlySlideRoll's first 20 s (the first flight, its Zeno sequence, the first
//! landings and lift-offs) does not depend on the tolerance.

use unimo_reference::dynamics::{apply_impact, energy};
use unimo_reference::geometry::kinematics;
use unimo_reference::scenes::fly_slide_roll;
use unimo_reference::{simulate, EventKind, RunOptions};

/// A state touching the plane with an approaching, slipping support point.
fn touching_state() -> Vec<f64> {
    let example = fly_slide_roll();
    let mut x = example.initial_state.to_vec();
    let q = [0.95f64, 0.1, -0.2, 0.2];
    let l = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    for i in 0..4 {
        x[6 + i] = q[i] / l;
    }
    x[4] = -1.5;
    let k = kinematics(&example.scene.body, &x);
    x[1] -= k.gap;
    x
}

#[test]
fn an_impact_reverses_the_normal_velocity_by_the_restitution() {
    let example = fly_slide_roll();
    let mut x = touching_state();
    let before = kinematics(&example.scene.body, &x);
    assert!(before.gap_rate < 0.0);
    let e0 = energy(&example.scene, &x);
    let s = apply_impact(&example.scene, &mut x).expect("an impulse");
    let after = kinematics(&example.scene.body, &x);
    assert!(s > 0.0);
    let expected = -example.scene.restitution * before.gap_rate;
    assert!(
        (after.gap_rate - expected).abs() <= 1e-14 * expected.abs(),
        "{} vs {expected}",
        after.gap_rate
    );
    // friction opposes the slip: its tangential speed does not grow
    let slip = |k: &unimo_reference::geometry::Kinematics| unimo_reference::geometry::norm(k.slip);
    assert!(slip(&after) < slip(&before));
    assert!(energy(&example.scene, &x) < e0);
}

#[test]
fn the_first_twenty_seconds_do_not_depend_on_the_tolerance() {
    let example = fly_slide_roll();
    let run = |rtol: f64| {
        let options = RunOptions {
            rtol,
            atol: rtol / 100.0,
            t_stop: 20.0,
            max_events: 100_000,
        };
        simulate(&example.scene, &example.initial_state, &options).expect("the run finishes")
    };
    let coarse = run(1e-9);
    let fine = run(1e-11);
    assert_eq!(coarse.events.len(), fine.events.len());
    assert!(fine.events.len() > 100, "{} events", fine.events.len());
    for (a, b) in coarse.events.iter().zip(&fine.events) {
        assert_eq!(a.kind, b.kind, "at t = {}", b.t);
        assert!((a.t - b.t).abs() <= 1e-6 * b.t, "{} vs {}", a.t, b.t);
    }
    // the first flight ends in a Zeno sequence that lands, then lift-offs follow
    let first_landing = fine
        .events
        .iter()
        .position(|e| matches!(e.kind, EventKind::Landing(_)))
        .expect("a landing");
    assert!(first_landing > 20);
    assert!(fine.events[..first_landing]
        .iter()
        .all(|e| e.kind == EventKind::Impact));
    assert!((fine.events[first_landing].t - 12.05735).abs() < 1e-5);
    assert!(fine.count(|k| k == EventKind::LiftOff) > 3);
    assert!((coarse.energy - fine.energy).abs() < 1e-6 * fine.energy);
}
