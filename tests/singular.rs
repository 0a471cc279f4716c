//! Numerically singular structure: circuits in nodal form whose capacitors connect
//! nodes without a capacitive path to ground. Structurally regular, their coefficient
//! matrix of derivatives is singular; unimo finds the hidden constraint (a linear
//! combination of the node equations) and reduces the index. Each circuit is compared
//! with the same circuit written with the capacitor voltages as states
//! (`tests/singular/CapacitorStates.mo`) integrated at rtol 1e-12.

mod common;

use unimo_runtime::sim::SimResult;
use unimo_solve::Method;

fn load(file: &str, model: &str) -> unimo_cli::LoadedModel {
    unimo_cli::load_model(&[common::root().join(file)], Some(model))
        .unwrap_or_else(|e| panic!("{model}:\n{e}"))
}

fn run(m: &unimo_cli::LoadedModel, method: Method, rtol: f64) -> SimResult {
    common::run_ok(m, method, rtol, 0.02, 1e-4)
}

fn column(r: &SimResult, name: &str) -> Vec<f64> {
    common::column(r, name)
}

#[test]
fn nodal_circuits_with_floating_capacitors_match_capacitor_states() {
    // (model, node variables, hidden constraints)
    let cases: [(&str, &[&str], usize); 5] = [
        ("Bridge", &["U1", "U2"], 1),
        ("CouplingAmplifier", &["U1", "U2", "U3"], 1),
        ("FloatingChain", &["U1", "U2", "U3"], 1),
        ("TwoFloating", &["U1", "U2", "U3", "U4"], 2),
        ("SeriesLC", &["U1", "U2", "iL"], 1),
    ];
    for (model, nodes, hidden) in cases {
        let nodal = load("tests/singular/NodalCircuits.mo", model);
        let dump = &nodal.analysis.dump;
        let listed = dump
            .lines()
            .skip_while(|l| !l.starts_with("hidden constraints"))
            .skip(1)
            .take_while(|l| l.starts_with("  e"))
            .count();
        assert_eq!(listed, hidden, "{model}:\n{dump}");
        let reference = run(
            &load("tests/singular/CapacitorStates.mo", &format!("{model}Ref")),
            Method::Radau5,
            1e-12,
        );
        for method in [Method::Bdf, Method::Radau5] {
            let r = run(&nodal, method, 1e-8);
            let error = nodes
                .iter()
                .map(|n| {
                    column(&r, n)
                        .iter()
                        .zip(column(&reference, n))
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max)
                })
                .fold(0.0, f64::max);
            eprintln!("{model} {method:?}: largest node error {error:.1e}");
            assert!(error <= 1e-6, "{model} {method:?}: {error:e}");
        }
    }
}
