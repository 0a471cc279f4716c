//! Interoperability of `unimo simulate`: MAT v4 result files (read back by our reader,
//! and by scipy and DyMat when they are installed) and parameter overrides.

mod common;

use common::{root, unimo};
use std::path::{Path, PathBuf};
use std::process::Command;
use unimo_cli::results::mat;

fn temp_file(name: &str) -> PathBuf {
    common::temp("interop", name)
}

fn simulate_to(model: &str, out: &Path, extra: &[&str]) {
    let out_s = out.to_string_lossy();
    let mut args = vec!["simulate", model, "--output", &out_s];
    args.extend_from_slice(extra);
    let o = unimo(&args);
    common::assert_success(&o);
}

/// The CSV as (header, columns).
fn read_csv(path: &Path) -> Vec<(String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut cols: Vec<(String, Vec<f64>)> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|n| (n.to_owned(), Vec::new()))
        .collect();
    for line in lines {
        for (k, v) in line.split(',').enumerate() {
            cols[k].1.push(v.parse().unwrap());
        }
    }
    cols
}

/// Runs a model to CSV and to MAT and returns the largest difference over the CSV's
/// columns, with the MAT file's matrices and variables.
fn csv_against_mat(
    model: &str,
    stem: &str,
    args: &[&str],
) -> (f64, mat::MatFile, Vec<(String, Vec<f64>)>) {
    let (csv, mat_path) = (
        temp_file(&format!("{stem}.csv")),
        temp_file(&format!("{stem}.mat")),
    );
    simulate_to(model, &csv, args);
    simulate_to(model, &mat_path, args);
    let file = mat::read(&std::fs::read(&mat_path).unwrap()).unwrap();
    let vars = mat::trajectories(&file).unwrap();
    let mut worst = 0.0f64;
    for (name, values) in read_csv(&csv) {
        let (_, from_mat) = vars
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("{name} missing in the MAT file"));
        assert_eq!(from_mat.len(), values.len(), "{name}");
        for (a, b) in from_mat.iter().zip(&values) {
            worst = worst.max((a - b).abs());
        }
    }
    (worst, file, vars)
}

#[test]
fn bouncing_ball_mat_file_matches_the_csv() {
    let (worst, file, vars) = csv_against_mat("models/BouncingBall.mo", "ball", &[]);
    assert!(worst <= 1e-12, "max |MAT - CSV| = {worst:e}");
    let aclass: Vec<String> = (0..4)
        .map(|r| {
            let m = &file["Aclass"];
            let mat::MatData::Text(b) = &m.data else {
                panic!()
            };
            let row: String = (0..m.cols).map(|c| b[c * m.rows + r] as char).collect();
            row.trim_end().to_owned()
        })
        .collect();
    assert_eq!(aclass[0], "Atrajectory");
    assert_eq!(aclass[1], "1.1");
    assert_eq!(aclass[3], "binTrans");
    let names: Vec<&str> = vars.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        ["time", "g", "e", "h0", "h", "v", "bounces", "der(h)", "der(v)"]
    );
    let description = &file["description"];
    assert_eq!(description.text_column(0), "Simulation time [s]");
    assert_eq!(description.text_column(2), "Coefficient of restitution");
    // Parameters are time-invariant: data_1, start and stop time.
    assert_eq!(file["data_1"].rows, 4);
    assert_eq!(file["data_1"].cols, 2);
}

#[test]
fn aliases_are_stored_once_and_units_follow_descriptions() {
    // k kept tunable: folded, it would be the constant 2 and w a column of its own.
    let (worst, file, _) = csv_against_mat(
        "tests/interop/AliasesAndUnits.mo",
        "aliases",
        &["--tunable", "k"],
    );
    assert!(worst <= 1e-12, "max |MAT - CSV| = {worst:e}");
    let names = &file["name"];
    let index = |wanted: &str| {
        (0..names.cols)
            .find(|&k| names.text_column(k) == wanted)
            .unwrap_or_else(|| panic!("{wanted}"))
    };
    let info = |k: usize| match &file["dataInfo"].data {
        mat::MatData::Int32(v) => (v[4 * k], v[4 * k + 1]),
        _ => panic!("dataInfo is int32"),
    };
    let (x, y, z, w, k) = (index("x"), index("y"), index("z"), index("w"), index("k"));
    assert_eq!(info(x).0, 2);
    assert_eq!(info(y), info(x), "y = x is an alias");
    assert_eq!(info(z), (2, -info(x).1), "z = -x is a negated alias");
    assert_eq!(info(w), info(k), "w = k points at the parameter in data_1");
    assert_eq!(info(k).0, 1);
    assert_eq!(file["description"].text_column(x), "Position [m]");
    assert_eq!(file["description"].text_column(k), "Decay rate [1/s]");
    // time and the trajectories that are not aliases: x, der(x), a[1..3].
    assert_eq!(file["data_2"].rows, 6);
}

/// scipy.io.loadmat and DyMat read the file as the CSV says (skipped, with a note,
/// when Python or the packages are not installed: `pip install scipy DyMat`).
#[test]
fn python_readers_agree_with_the_csv() {
    for (model, stem) in [
        ("models/BouncingBall.mo", "py_ball"),
        ("tests/interop/AliasesAndUnits.mo", "py_aliases"),
    ] {
        let (csv, mat_path) = (
            temp_file(&format!("{stem}.csv")),
            temp_file(&format!("{stem}.mat")),
        );
        simulate_to(model, &csv, &[]);
        simulate_to(model, &mat_path, &[]);
        let script = root().join("tests/python/check_mat.py");
        let Ok(o) = Command::new("python3")
            .arg(&script)
            .arg(&mat_path)
            .arg(&csv)
            .output()
        else {
            assert!(
                require_python().is_none(),
                "no python3 (UNIMO_REQUIRE_PYTHON_CHECKS is set)"
            );
            eprintln!("skipped: no python3");
            return;
        };
        let stdout = String::from_utf8_lossy(&o.stdout);
        if o.status.code() == Some(77) {
            assert!(
                require_python().is_none(),
                "{stdout} (UNIMO_REQUIRE_PYTHON_CHECKS is set: .ci/run installs scipy and DyMat)"
            );
            eprintln!("skipped: {stdout}");
            return;
        }
        assert_eq!(
            o.status.code(),
            Some(0),
            "{model}: {stdout}{}",
            String::from_utf8_lossy(&o.stderr)
        );
        eprintln!("{model}: {stdout}");
    }
}

/// Set by `.ci/run` (which installs scipy, DyMat and FMPy): the Python checks must run.
fn require_python() -> Option<std::ffi::OsString> {
    std::env::var_os("UNIMO_REQUIRE_PYTHON_CHECKS")
}

/// The largest height between the first and the second impact of the bouncing ball.
fn first_rebound_height(extra: &[&str]) -> f64 {
    let csv = temp_file(&format!(
        "rebound{}.csv",
        extra.join("_").replace(['=', '/'], "_")
    ));
    // Up to t = 2.8: past the first apex of every case below (2.57 s for h0 = 10,
    // e = 0.8) and before the Zeno point of h0 = 5, e = 0.5 (3.03 s), where the run may
    // stop with E4006 (chattering) or pass through, by rounding.
    let mut args = vec![
        "--vars",
        "h,v",
        "--every-step",
        "--tolerance",
        "1e-10",
        "--stop-time",
        "2.8",
    ];
    args.extend_from_slice(extra);
    simulate_to("models/BouncingBall.mo", &csv, &args);
    let cols = read_csv(&csv);
    let (h, v) = (&cols[1].1, &cols[2].1);
    // After the first impact v > 0 until the apex: the largest h while rising or at rest.
    let first_impact = v.iter().position(|&x| x > 0.0).unwrap();
    let second_fall_end = (first_impact..v.len())
        .find(|&k| h[k] < 1e-9 && v[k] < 0.0 && k > first_impact + 2)
        .unwrap_or(h.len());
    h[first_impact..second_fall_end]
        .iter()
        .cloned()
        .fold(0.0, f64::max)
}

#[test]
fn param_override_changes_the_rebound_as_the_closed_form_says() {
    // h1 = e^2 h0 for restitution e: 6.4 with the model's e = 0.8, 2.5 with e = 0.5.
    let default = first_rebound_height(&[]);
    let changed = first_rebound_height(&["-p", "e=0.5"]);
    assert!((default - 6.4).abs() < 1e-3, "e = 0.8: {default}");
    assert!((changed - 2.5).abs() < 1e-3, "e = 0.5: {changed}");
    // Two at once, one from a file (the flag wins over the file).
    let file = temp_file("overrides.txt");
    std::fs::write(&file, "# restitution and height\ne = 0.9\nh0=5 # metres\n").unwrap();
    let file_s = file.to_string_lossy().into_owned();
    let both = first_rebound_height(&["--override-file", &file_s, "-p", "e=0.5"]);
    assert!((both - 0.25 * 5.0).abs() < 1e-3, "e = 0.5, h0 = 5: {both}");
}

#[test]
fn structural_parameters_take_effect_and_are_reported() {
    let csv = temp_file("structural.csv");
    simulate_to(
        "tests/interop/AliasesAndUnits.mo",
        &csv,
        &["-p", "n=5", "--vars", "a"],
    );
    let header: Vec<String> = read_csv(&csv).into_iter().map(|(n, _)| n).collect();
    assert_eq!(header, ["time", "a[1]", "a[2]", "a[3]", "a[4]", "a[5]"]);
    let o = unimo(&[
        "simulate",
        "tests/interop/AliasesAndUnits.mo",
        "--list-params",
        "-p",
        "mode=fast",
    ]);
    assert_eq!(o.status.code(), Some(0));
    insta::assert_snapshot!("list_params", String::from_utf8_lossy(&o.stdout));
}

/// Array parameters are set whole (`-p g={3, 4}`); a wrong shape or element is E0004.
#[test]
fn array_parameters_are_overridden_whole() {
    let csv = temp_file("arrays.csv");
    let model = "tests/interop/ArrayParameters.mo";
    simulate_to(model, &csv, &["--vars", "x"]);
    let x = |csv: &Path| read_csv(csv)[1].1.last().copied().unwrap();
    // x(1) = g[1] + g[2] + m[1, 2]: 3 with the declared values.
    assert!((x(&csv) - 3.0).abs() < 1e-9, "{}", x(&csv));
    simulate_to(
        model,
        &csv,
        &["--vars", "x", "-p", "g={3, 4}", "-p", "m={{1, 5}, {0, 1}}"],
    );
    assert!((x(&csv) - 12.0).abs() < 1e-9, "{}", x(&csv));
    let o = unimo(&[
        "simulate",
        model,
        "-p",
        "g={1}",
        "-p",
        "g=2",
        "-p",
        "m={{1, 2}, {3, 4.5}}",
        "-p",
        "g[1]=2",
    ]);
    assert_eq!(o.status.code(), Some(2), "usage errors exit with 2");
    insta::assert_snapshot!("array_override_errors", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn bad_overrides_are_coded_errors() {
    let o = unimo(&[
        "simulate",
        "tests/interop/AliasesAndUnits.mo",
        "-p",
        "kk=1",
        "-p",
        "n=1.5",
        "-p",
        "on=3",
        "-p",
        "on=True",
        "-p",
        "c=2",
        "-p",
        "mode=medium",
        "-p",
        "x=1",
        "-p",
        "k=abc",
        "-p",
        "bad",
    ]);
    assert_eq!(o.status.code(), Some(2), "usage errors exit with 2");
    insta::assert_snapshot!("override_errors", String::from_utf8_lossy(&o.stderr));
}

/// The command line's errors that point into no file are one coded line each
/// (`CliError::line`) and exit with 2; they were uncoded `error: ...` lines before.
#[test]
fn usage_errors_are_one_coded_line() {
    let two = temp_file("TwoModels.mo");
    let text = "model A\n  Real x = 1;\nend A;\nmodel B\n  Real y = 2;\nend B;\n";
    std::fs::write(&two, text).unwrap();
    let two = two.to_string_lossy();
    let ball = "models/BouncingBall.mo";
    let cases: [(&[&str], &str); 8] = [
        (
            &["emit", "--stage", "ast", "tests/interop/Missing.mo"],
            "error[E0001]: cannot read `tests/interop/Missing.mo`: ",
        ),
        (
            &["check", "tests/interop/NoSuchFolder"],
            "error[E0001]: no such file or folder: `tests/interop/NoSuchFolder`",
        ),
        (
            &["emit", "--stage", "ast", "--model", "A"],
            "error[E0010]: `emit --stage ast` prints the tree of a file: give the file",
        ),
        (
            &["simulate", &two],
            "error[E0008]: the file has several models (A, B); choose one with --model",
        ),
        (
            &["simulate", &two, "--model", "C"],
            "error[E0008]: no class `C` in the file or the library",
        ),
        (
            &["simulate", ball, "--vars", "nosuch"],
            "error[E0003]: no variable `nosuch` in the model",
        ),
        (
            &["simulate", ball, "--output-tolerance=-1"],
            "error[E0007]: the output tolerance must be 0 or positive",
        ),
        (
            &["sweep", ball, "-p", "e"],
            "error[E0006]: `e` is not NAME=VALUES (e.g. k=0.5:0.9:5 or f=0.05,0.1)",
        ),
    ];
    for (args, line) in cases {
        let o = unimo(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.starts_with(line), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    }
}
