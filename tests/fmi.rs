//! FMU export checked by a real importer: `unimo fmu` writes FMI 2.0 and 3.0 FMUs
//! (Model Exchange and Co-Simulation), FMPy validates and simulates them
//! (`tests/python/check_fmu.py`) and its results must agree with `unimo simulate`;
//! `tests/python/check_fmu_api.py` drives the C functions in the wrong order, with bad
//! arguments and with two instances side by side. The Python checks run when `python3`
//! can import FMPy (`.ci/run` installs it); without it they print a note and pass,
//! except when `UNIMO_REQUIRE_PYTHON_CHECKS` is set (`.ci/run` sets it), where a missing
//! FMPy is a failure.

mod common;

use common::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn unimo(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(args)
        .args(["--color", "never"])
        .current_dir(root())
        .output()
        .unwrap()
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("unimo-fmi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn ok(o: &Output) {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Whether FMPy can be used; false prints why (and fails under CI).
fn fmpy_available() -> bool {
    let found = Command::new("python3")
        .args(["-c", "import fmpy, numpy"])
        .status()
        .is_ok_and(|s| s.success());
    if !found {
        assert!(
            std::env::var_os("UNIMO_REQUIRE_PYTHON_CHECKS").is_none(),
            "UNIMO_REQUIRE_PYTHON_CHECKS is set but python3 cannot import fmpy (.ci/run installs it)"
        );
        eprintln!("note: python3 cannot import fmpy: the FMU checks were not run");
    }
    found
}

/// One exported model: its source arguments, the variables compared, and the largest
/// error allowed (relative to each variable's scale, see `check_fmu.py`).
struct Case<'a> {
    stem: &'a str,
    source: &'a [&'a str],
    vars: &'a str,
    extra: &'a [&'a str],
}

fn export(case: &Case<'_>, fmi: &str, kind: &str) -> PathBuf {
    let fmu = temp(&format!("{}-{fmi}-{kind}.fmu", case.stem));
    let fmu_s = fmu.to_string_lossy().into_owned();
    let mut args = vec!["fmu"];
    args.extend_from_slice(case.source);
    args.extend_from_slice(&["--fmi", fmi, "--kind", kind, "-o", &fmu_s]);
    ok(&unimo(&args));
    fmu
}

/// `unimo simulate` to CSV, then FMPy on the FMU against it.
fn agree(case: &Case<'_>, fmi: &str, kind: &str, tolerance: f64, check_args: &[&str]) {
    let fmu = export(case, fmi, kind);
    let csv = temp(&format!("{}.csv", case.stem));
    let csv_s = csv.to_string_lossy().into_owned();
    let mut args = vec!["simulate"];
    args.extend_from_slice(case.source);
    args.extend_from_slice(&["--vars", case.vars, "--output", &csv_s]);
    args.extend_from_slice(case.extra);
    ok(&unimo(&args));
    let out = python(
        "tests/python/check_fmu.py",
        &[&fmu.to_string_lossy(), &csv_s, case.vars, &tolerance.to_string()],
        check_args,
    );
    eprintln!("{} FMI {fmi} {kind}:\n{out}", case.stem);
}

fn python(script: &str, args: &[&str], more: &[&str]) -> String {
    let o = Command::new("python3")
        .arg(script)
        .args(args)
        .args(more)
        .current_dir(root())
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(o.status.code(), Some(0), "{script}:\n{text}");
    text
}

const BALL: Case = Case {
    stem: "ball",
    source: &["models/BouncingBall.mo"],
    vars: "h,v",
    extra: &[],
};

const VAN_DER_POL: Case = Case {
    stem: "vdp",
    source: &["models/VanDerPol.mo"],
    vars: "y1,y2",
    extra: &[],
};

#[test]
fn bouncing_ball_fmus_agree_with_unimo_simulate() {
    if !fmpy_available() {
        return;
    }
    agree(&BALL, "2", "me", 2e-4, &[]);
    agree(&BALL, "3", "me", 2e-4, &[]);
    agree(&BALL, "2", "cs", 1e-5, &[]);
    agree(&BALL, "3", "cs", 1e-5, &[]);
}

#[test]
fn van_der_pol_fmus_agree_with_unimo_simulate() {
    if !fmpy_available() {
        return;
    }
    agree(&VAN_DER_POL, "2", "me", 1e-3, &[]);
    agree(&VAN_DER_POL, "3", "cs", 1e-3, &[]);
}

#[test]
fn calls_in_the_wrong_order_fail_cleanly_and_instances_are_independent() {
    if !fmpy_available() {
        return;
    }
    let cs2 = export(&BALL, "2", "cs");
    let me3 = export(&BALL, "3", "me");
    let out = python(
        "tests/python/check_fmu_api.py",
        &[&cs2.to_string_lossy(), &me3.to_string_lossy()],
        &[],
    );
    eprintln!("{out}");
}

#[test]
fn a_missing_fmu_library_is_a_coded_error() {
    let fmu = temp("missing.fmu");
    let o = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["fmu", "models/BouncingBall.mo", "-o"])
        .arg(&fmu)
        .env("UNIMO_FMI_LIBRARY", Path::new("/nonexistent/libunimo_fmi.so"))
        .current_dir(root())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("error[E4707]"), "{err}");
    assert!(!fmu.exists());
}
