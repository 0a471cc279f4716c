//! A failed solve of an algebraic loop leaves the loop's iteration variables where they
//! were before it: the integrator retries the step from the registers, and an iterate
//! Newton's method gave up on (NaN, or far off the solution) must not be its start.

mod common;

use unimo_runtime::eval::RhsEvaluator;

#[test]
fn a_failed_loop_solve_does_not_poison_the_next_start() {
    let m = unimo_cli::load_model(
        &[common::root().join("tests/newton_restart/Restart.mo")],
        Some("Restart"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut rhs = RhsEvaluator::new(&m.compiled);
    let mut der = [0.0];
    // x = 1: y = 1 solves y + log(y) = x.
    rhs.rhs(0.0, &[1.0], &mut der)
        .expect("the loop solves at x = 1");
    assert!((der[0] + 1.0).abs() <= 1e-12, "{der:?}");
    // x = -1e300: no double solves it (y + log(y) >= -745 for y > 0). Newton's first
    // step from y = 1 is about -5e299, and every shortened step (down to a millionth)
    // is negative too, where log(y) is NaN: the solve fails with its last iterate at
    // y < 0.
    assert!(rhs.rhs(0.0, &[-1e300], &mut der).is_err());
    // x = 1 again: solved from the last good solution (y = 1). From the failed iterate
    // (y < 0, log(y) NaN) the solve would fail at once.
    rhs.rhs(0.0, &[1.0], &mut der)
        .expect("the loop solves at x = 1 after a failed solve");
    assert!((der[0] + 1.0).abs() <= 1e-12, "{der:?}");
}
