//! Stiff reference problems from the Bari/CWI test set (ROBER as a DAE, HIRES, VDPOL) with BDF
//! and Radau5, measured in significant correct digits `scd = -log10(max relative error)`.

#[path = "support/problems.rs"]
mod problems;

use problems::{
    counters, significant_digits, solve_to, Benchmark, Harmonic, Hires, Pollu, Reference, Rober,
    VanDerPol,
};
use unimo_solve::{Method, Options, Stats, System};

fn measure(
    method: Method,
    system: &mut dyn System,
    reference: &Reference,
    options: Options,
) -> (f64, Stats) {
    let (state, stats) = solve_to(method, system, &reference.x0, reference.t_end, options)
        .unwrap_or_else(|error| panic!("{} {method:?}: {error}", reference.name));
    (significant_digits(&state, &reference.solution), stats)
}

fn check(
    method: Method,
    system: &mut dyn System,
    reference: &Reference,
    (rtol, atol): (f64, f64),
    minimum_scd: f64,
) -> String {
    let (scd, stats) = measure(
        method,
        system,
        reference,
        Options::with_tolerances(rtol, atol),
    );
    assert!(
        scd >= minimum_scd,
        "{} {method:?} rtol {rtol:e}: scd {scd:.2} < {minimum_scd}",
        reference.name
    );
    format!(
        "{} {method:?} rtol {rtol:e} atol {atol:e}: scd >= {minimum_scd}\n{}",
        reference.name,
        counters(&stats)
    )
}

// ROBER, measured: BDF 6.06 / 7.40, Radau5 7.71 / 9.74 (rtol 1e-8 / 1e-10).
#[test]
fn rober_dae_bdf() {
    let reference = Rober::reference();
    let mut rober = Rober {
        analytic_jacobian: true,
    };
    insta::assert_snapshot!(check(
        Method::Bdf,
        &mut rober,
        &reference,
        (1e-8, 1e-14),
        5.8
    ));
    insta::assert_snapshot!(check(
        Method::Bdf,
        &mut rober,
        &reference,
        (1e-10, 1e-16),
        7.0
    ));
}

#[test]
fn rober_dae_radau5() {
    let reference = Rober::reference();
    let mut rober = Rober {
        analytic_jacobian: true,
    };
    insta::assert_snapshot!(check(
        Method::Radau5,
        &mut rober,
        &reference,
        (1e-8, 1e-14),
        5.8
    ));
    insta::assert_snapshot!(check(
        Method::Radau5,
        &mut rober,
        &reference,
        (1e-10, 1e-16),
        7.0
    ));
}

#[test]
fn rober_dae_with_finite_difference_jacobian() {
    let reference = Rober::reference();
    for method in [Method::Bdf, Method::Radau5] {
        let mut rober = Rober {
            analytic_jacobian: false,
        };
        check(method, &mut rober, &reference, (1e-8, 1e-14), 5.8);
    }
}

#[test]
fn rober_dae_bdf_suppressing_algebraic_error() {
    let reference = Rober::reference();
    let mut rober = Rober {
        analytic_jacobian: true,
    };
    let options = Options {
        suppress_algebraic_error: true,
        ..Options::with_tolerances(1e-10, 1e-16)
    };
    let (scd, stats) = measure(Method::Bdf, &mut rober, &reference, options);
    assert!(scd >= 7.0, "scd {scd:.2}");
    // The algebraic y3 ~ 1e-5 cannot be computed to atol 1e-16 from 1 - y1 - y2 (rounding
    // 1e-16): leaving it out of the error test avoids rejections caused by that noise
    // (measured 7,438 steps against 19,667 with y3 in the test).
    let options = Options::with_tolerances(1e-10, 1e-16);
    let (_, with_algebraic) = measure(Method::Bdf, &mut rober, &reference, options);
    assert!(
        (stats.steps as f64) < 0.6 * with_algebraic.steps as f64,
        "{stats:?} against {with_algebraic:?}"
    );
}

#[test]
fn hires_bdf_and_radau5() {
    let reference = Hires::reference();
    let mut report = String::new();
    for (method, tolerances, minimum) in [
        (Method::Bdf, (1e-6, 1e-10), 4.5),
        (Method::Bdf, (1e-10, 1e-14), 8.5),
        (Method::Radau5, (1e-6, 1e-10), 6.0),
        (Method::Radau5, (1e-10, 1e-14), 8.5),
    ] {
        report += &check(method, &mut Hires, &reference, tolerances, minimum);
    }
    insta::assert_snapshot!(report);
}

#[test]
fn vdpol_bdf_and_radau5() {
    let reference = VanDerPol::reference();
    let mut report = String::new();
    for (method, tolerances, minimum) in [
        (Method::Bdf, (1e-6, 1e-6), 4.5),
        (Method::Bdf, (1e-10, 1e-10), 8.0),
        (Method::Radau5, (1e-6, 1e-6), 6.0),
        (Method::Radau5, (1e-10, 1e-10), 9.5),
    ] {
        let mut system = VanDerPol { epsilon: 1e-6 };
        report += &check(method, &mut system, &reference, tolerances, minimum);
    }
    insta::assert_snapshot!(report);
}

/// BDF's calibrated tolerances (bdf.rs, "Tolerance calibration"): at the same `rtol` its
/// global error is within ten times Radau5's on the oscillator and the three stiff
/// problems. With the tolerances used as requested it was 13 to 80 times Radau5's
/// (oscillator rtol 1e-8: scd 6.57 against 7.69; ROBER rtol 1e-8: 5.94 against 7.85).
#[test]
fn bdf_tolerance_buys_the_accuracy_of_radau5() {
    let mut report = Vec::new();
    for rtol in [1e-8, 1e-10] {
        let digits = |method| {
            let options = Options::with_tolerances(rtol, rtol * 1e-2);
            let (state, _) = solve_to(method, &mut Harmonic, &[1.0, 0.0], 40.0, options)
                .unwrap_or_else(|error| panic!("oscillator {method:?}: {error}"));
            significant_digits(&state, &[40f64.cos(), -40f64.sin()])
        };
        report.push((
            "oscillator".to_string(),
            rtol,
            digits(Method::Bdf),
            digits(Method::Radau5),
        ));
    }
    for benchmark in Benchmark::ALL {
        let digits = |method| {
            benchmark
                .run(method, 1e-8)
                .unwrap_or_else(|error| panic!("{benchmark:?} {method:?}: {error}"))
                .0
        };
        report.push((
            format!("{benchmark:?}"),
            1e-8,
            digits(Method::Bdf),
            digits(Method::Radau5),
        ));
    }
    for (name, rtol, bdf, radau5) in report {
        assert!(
            bdf >= radau5 - 1.0,
            "{name} rtol {rtol:e}: BDF scd {bdf:.2}, Radau5 {radau5:.2}"
        );
    }
}

/// POLLU at rtol = atol (the test set's setting): its smallest components stay near atol
/// while the fast ones settle. Radau5 once accepted a first Newton iterate on the contraction
/// of an earlier step's matrix, and the stages of the steps after the start were solved to
/// only ~1e-4 there: y12 went to -1.6e-4 at t = 0.04 at rtol 1e-4 (scd 1.27, 2.26, 4.08 at
/// rtol 1e-4, 1e-6, 1e-8; now 3.4, 4.2, 6.4).
#[test]
fn pollu_radau5() {
    let reference = Pollu::reference();
    let mut report = String::new();
    for (rtol, minimum) in [(1e-4, 3.0), (1e-6, 4.0), (1e-8, 6.0)] {
        report += &check(
            Method::Radau5,
            &mut Pollu,
            &reference,
            (rtol, rtol),
            minimum,
        );
    }
    insta::assert_snapshot!(report);
}
