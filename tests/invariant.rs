//! Invariants (`Unimo.invariant`): the simulator projects the states onto `g = 0`
//! after each accepted step and event while the invariant's branch is taken, so `g`
//! holds to rounding whatever the tolerance, and not where it is not declared.

mod common;

use unimo_solve::Method;

/// At rtol 1e-6 the circle's radius drifts by about the tolerance per revolution; with
/// the projection it stays at rounding on every row while the invariant is active, and
/// drifts again after (t > 5, where the model no longer declares it). The state the
/// invariant does not read (`w`) follows its own solution.
#[test]
fn a_declared_invariant_holds_to_rounding_at_a_loose_tolerance() {
    let m = common::load("tests/invariant/Circle.mo", None);
    for method in [Method::Bdf, Method::Radau5, Method::Dopri5] {
        let r = common::run_ok(&m, method, 1e-6, 10.0, 0.05);
        let (t, r2, w) = (&r.times, common::column(&r, "r2"), common::column(&r, "w"));
        let on = common::column(&r, "on");
        let held = (0..t.len())
            .filter(|&k| on[k] != 0.0)
            .map(|k| r2[k].abs())
            .fold(0.0, f64::max);
        let after = (0..t.len())
            .filter(|&k| t[k] > 9.0)
            .map(|k| r2[k].abs())
            .fold(0.0, f64::max);
        assert!(
            held < 1e-12,
            "{method:?}: |x^2 + y^2 - 1| = {held:e} while declared"
        );
        assert!(
            after > 1e-10,
            "{method:?}: without the invariant the drift is the integration error, {after:e}"
        );
        let w_err = (0..t.len())
            .map(|k| (w[k] - 0.5 * (-t[k]).exp()).abs())
            .fold(0.0, f64::max);
        assert!(w_err < 1e-5, "{method:?}: w off by {w_err:e}");
        let stats = r
            .stats
            .projection
            .clone()
            .expect("the model has invariants");
        assert!(stats.projections > 10, "{method:?}: {stats:?}");
    }
}

/// The flat model keeps the call, the DAE lists the invariant with its condition, and a
/// wrong call is a coded error.
#[test]
fn the_dae_lists_the_invariant_and_its_condition() {
    let out = common::unimo(&["emit", "--stage", "dae", "tests/invariant/Circle.mo"]);
    common::assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("invariants: 1"), "{text}");
    assert!(text.contains("0 = "), "{text}");
}
