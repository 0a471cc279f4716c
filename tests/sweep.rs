//! Parameter sweeps: `unimo sweep` (grid, CSV table, a failing point reported while the
//! others complete) and the library's `sweep::run` (the first rebound of the bouncing
//! ball reaches e² h0).

mod common;

use common::root;
use std::process::Command;
use unimo_cli::api::Source;
use unimo_cli::sweep::{self, SweepSettings};

#[test]
fn the_command_writes_one_row_per_point_and_keeps_failures() {
    let out = std::env::temp_dir().join(format!("unimo-sweep-{}.csv", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["sweep", "models/BouncingBall.mo", "-p", "e=0.5:0.9:3"])
        .args(["-p", "h0=10,20,abc", "--jobs", "2", "--stop-time", "1"])
        .args(["--vars", "h", "-o", out.to_str().unwrap()])
        .current_dir(root())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(3),
        "a point failed: exit code 3\n{stderr}"
    );
    assert!(stderr.contains("9 points, 3 failed, 2 jobs"), "{stderr}");
    let table = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines[0], "e,h0,status,error_code,error_message,time,h");
    assert_eq!(lines.len(), 10);
    for line in &lines[1..] {
        let cells: Vec<&str> = line.split(',').collect();
        assert!(["0.5", "0.7", "0.9"].contains(&cells[0]), "{line}");
        if cells[1] == "abc" {
            assert_eq!(cells[2..4], ["failed", "E0004"], "{line}");
            continue;
        }
        assert_eq!(cells[2], "ok", "{line}");
        // Before the first bounce: h = h0 - g t^2 / 2 at t = 1.
        let h0: f64 = cells[1].parse().unwrap();
        let h: f64 = cells[6].parse().unwrap();
        assert!((h - (h0 - 9.81 / 2.0)).abs() < 1e-6, "{line}");
    }
    let _ = std::fs::remove_file(out);
}

#[test]
fn the_first_rebound_reaches_e_squared_h0_on_every_thread() {
    let source = Source {
        files: vec![(root().join("models/BouncingBall.mo"), None)],
        ..Source::default()
    };
    let points: Vec<sweep::Point> = ["0.5", "0.6", "0.7", "0.8", "oops"]
        .iter()
        .map(|e| vec![("e".to_owned(), e.to_string())])
        .collect();
    let settings = SweepSettings {
        outputs: Vec::new(),
        overrides: unimo_runtime::sim::Overrides {
            stop: Some(3.5),
            points: Some(3500),
            ..Default::default()
        },
        method: unimo_solve::Method::Auto,
        jobs: 2,
        keep_results: true,
    };
    let outcomes = sweep::run(&source, &points, &settings).unwrap();
    for (point, o) in points.iter().zip(&outcomes).take(4) {
        let e: f64 = point[0].1.parse().unwrap();
        assert!(o.error.is_none(), "{:?}", o.error);
        let r = o.result.as_ref().unwrap();
        let h = r.names.iter().position(|n| n == "h").unwrap();
        let bounces = r.names.iter().position(|n| n == "bounces").unwrap();
        let first_rebound = r
            .rows
            .iter()
            .filter(|row| row[bounces] == 1.0)
            .map(|row| row[h])
            .fold(f64::MIN, f64::max);
        assert!(
            (first_rebound - e * e * 10.0).abs() < 1e-3,
            "e = {e}: {first_rebound}"
        );
        assert!(o.stats.iter().any(|(n, v)| *n == "events" && *v >= 1.0));
    }
    let failed = outcomes[4].error.as_ref().unwrap();
    assert_eq!(failed.code, "E0004");
    assert_eq!(failed.location.as_deref(), Some("<command line>:1:3"));
}
