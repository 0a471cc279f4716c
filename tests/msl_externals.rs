//! The MSL's external C functions that unimo writes again in Rust, end to end through
//! `unimo simulate` on the MSL 4.1.0 test data beside the project (`../shared/msl`):
//! the impure random number generator (xorshift1024*, `ModelicaRandom.c`) against the
//! Modelica Association's reference result, and the real FFT (`ModelicaFFT.c`) of
//! `Modelica.Math.FastFourierTransform.realFFT` on a signal of known spectrum.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn shared(dir: &str) -> PathBuf {
    let path = common::root().join("..").join("shared").join(dir);
    assert!(
        path.is_dir(),
        "the MSL test data is missing: {}",
        path.display()
    );
    path
}

/// Column `name` of a CSV result (`None` when it is missing).
fn csv_column(path: &Path, name: &str) -> Option<Vec<f64>> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut lines = text.lines();
    let head: Vec<String> = lines
        .next()?
        .split(',')
        .map(|h| h.trim().trim_matches('"').to_owned())
        .collect();
    let k = head.iter().position(|h| h == name)?;
    Some(
        lines
            .filter_map(|l| l.split(',').nth(k))
            .map(|c| c.trim().parse().unwrap_or(f64::NAN))
            .collect(),
    )
}

/// Simulates `model` of `file` with the MSL as library; the result CSV.
fn simulate(file: &Path, model: &str, vars: &str, out: &Path) -> PathBuf {
    let msl = shared("msl");
    let run = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .arg("simulate")
        .arg(file)
        .args(["--model", model, "--lib"])
        .arg(&msl)
        .args(["--vars", vars, "--output"])
        .arg(out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{model}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    out.to_path_buf()
}

/// The values a piecewise-constant signal takes, in order (repeats dropped).
fn steps(y: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for &v in y {
        if out.last() != Some(&v) {
            out.push(v);
        }
    }
    out
}

/// `ImpureGenerator` draws one number at `initial()` and at each of its 200 samples:
/// the sequence is the reference's, number for number. (The instants are compared by
/// msl-check; the reference puts the 26th sample a rounding after t = 0.26, where
/// unimo's `start + n * interval` gives 0.26 exactly.)
#[test]
fn impure_random_draws_the_reference_sequence() {
    let msl = shared("msl");
    let model = "Modelica.Blocks.Examples.Noise.ImpureGenerator";
    let out = common::temp("msl-externals", "ImpureGenerator.csv");
    simulate(
        &msl.join("Modelica/package.mo"),
        model,
        "impureRandom_y",
        &out,
    );
    let reference = shared("msl-reference")
        .join("Modelica/Blocks/Examples/Noise/ImpureGenerator/ImpureGenerator.csv");
    let ours = steps(&csv_column(&out, "impureRandom_y").unwrap());
    let theirs = steps(&csv_column(&reference, "impureRandom_y").unwrap());
    assert_eq!(ours.len(), 201);
    assert_eq!(ours.len(), theirs.len());
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert!((a - b).abs() <= 1e-15, "number {k}: {a} vs {b}");
    }
}

/// `realFFT` of `u = 2 + 3 cos(2 pi 5 j / 60 + 0.4) - 1.5 sin(2 pi 12 j / 60)`, 60
/// points: the mean as amplitude 1, `|X[k]| / nf` (nf = 31) at the two lines, phases in
/// degrees (0.4 rad, and 90 degrees for the sine), zero elsewhere.
#[test]
fn real_fft_of_a_signal_of_known_spectrum() {
    let source = "model FftKnown
  constant Real pi = Modelica.Constants.pi;
  parameter Integer n = 60;
  parameter Real u[n] = {2 + 3*cos(2*pi*5*(k - 1)/n + 0.4) - 1.5*sin(2*pi*12*(k - 1)/n) for k in 1:n};
  Integer info;
  Real amplitudes[31];
  Real phases[31];
equation
  (info, amplitudes, phases) = Modelica.Math.FastFourierTransform.realFFT(u, 31);
  annotation(experiment(StopTime = 1));
end FftKnown;
";
    let file = common::temp("msl-externals", "FftKnown.mo");
    std::fs::write(&file, source).unwrap();
    let out = common::temp("msl-externals", "FftKnown.csv");
    let vars = "info,amplitudes[1],amplitudes[6],phases[6],amplitudes[13],phases[13],amplitudes[8],phases[8]";
    simulate(&file, "FftKnown", vars, &out);
    let last = |name: &str| *csv_column(&out, name).unwrap().last().unwrap();
    let close = |name: &str, expected: f64| {
        let v = last(name);
        assert!(
            (v - expected).abs() <= 1e-9 * expected.abs().max(1.0),
            "{name}: {v} vs {expected}"
        );
    };
    close("info", 0.0);
    close("amplitudes[1]", 2.0);
    close("amplitudes[6]", 1.5 * 60.0 / 31.0);
    close("phases[6]", 0.4f64.to_degrees());
    close("amplitudes[13]", 0.75 * 60.0 / 31.0);
    close("phases[13]", 90.0);
    close("amplitudes[8]", 0.0);
    close("phases[8]", 0.0);
}
