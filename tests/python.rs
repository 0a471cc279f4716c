//! The Python package's tests (`python/tests`, pytest, with a Dask `LocalCluster` of two
//! workers) and the FlySlideRoll example script (`docs/examples/fly_slide_roll.py`:
//! a restitution sweep, its plot, the animation of one run) from `cargo test`, when
//! `UNIMO_PYTHON` names a Python with the package, pytest and Dask installed (`.ci/run`
//! and `python/run-tests.sh` make one). Without it they print a note and pass, except
//! under CI (`CI` set), where they fail: CI must run them.

mod common;

use std::ffi::OsString;
use std::process::Command;

/// The Python to test with, or None (with a note) outside CI.
fn python() -> Option<OsString> {
    let Some(python) = std::env::var_os("UNIMO_PYTHON") else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must run the Python tests: set UNIMO_PYTHON (.ci/run does)"
        );
        eprintln!(
            "note: UNIMO_PYTHON is not set: the Python package's tests were not run \
             (python/run-tests.sh runs them)"
        );
        return None;
    };
    let has_package = Command::new(&python)
        .args(["-c", "import unimo, pytest, dask.distributed"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        has_package,
        "UNIMO_PYTHON={python:?} cannot import unimo, pytest and dask.distributed"
    );
    Some(python)
}

#[test]
fn the_python_package_passes_its_tests() {
    let Some(python) = python() else { return };
    let out = Command::new(&python)
        .args(["-m", "pytest", "-q", "python/tests"])
        .current_dir(common::root())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    // pytest: 0 all passed; 1 failures; 2 interrupted; 3 internal error; 4 usage;
    // 5 no test collected. Only 0 passes (5 would mean nothing was tested).
    assert_eq!(
        out.status.code(),
        Some(0),
        "pytest failed\n{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("passed") && !text.contains("skipped"),
        "{text}"
    );
    eprintln!("{}", text.lines().last().unwrap_or(""));
}

#[test]
fn the_fly_slide_roll_example_sweeps_plots_and_animates() {
    let Some(python) = python() else { return };
    let out_dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fly_slide_roll");
    let _ = std::fs::remove_dir_all(&out_dir);
    let out = Command::new(&python)
        .args(["docs/examples/fly_slide_roll.py", "--points", "2"])
        .args(["--t-stop", "10", "--jobs", "2", "--out"])
        .arg(&out_dir)
        .env("UNIMO_BIN", env!("CARGO_BIN_EXE_unimo"))
        .current_dir(common::root())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    eprintln!("{stdout}");
    // one row per k (0.3 and 0.8), each run to its end
    let sweep = std::fs::read_to_string(out_dir.join("sweep.csv")).unwrap();
    assert_eq!(sweep.lines().count(), 3, "{sweep}");
    assert!(sweep.lines().skip(1).all(|l| l.contains(",ok,")), "{sweep}");
    let plot = ["first_rolling.png", "first_rolling.svg"]
        .iter()
        .any(|p| out_dir.join(p).exists());
    assert!(plot, "no plot in {out_dir:?}");
    let page = std::fs::read_to_string(out_dir.join("run.html")).unwrap();
    assert!(page.contains("\"shape\":\"ellipsoid\"") && page.contains("\"clock\":\"t\""));
}
