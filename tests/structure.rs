//! The structural stage end to end: `unimo emit --stage dae|structure` on small models
//! with known structure (index reduction, dummy derivatives, alias sets, tearing),
//! snapshot-tested, and structurally singular models with their diagnostics.

mod common;

use std::path::Path;
use std::process::Command;

fn emit(stage: &str, file: &Path) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args(["--color", "never", "emit", "--stage", stage])
        .arg(file)
        .output()
        .expect("run unimo");
    common::code_and_text(out)
}

#[test]
fn structure_dumps() {
    let all = common::mo_files("tests/structure/ok");
    assert!(all.len() >= 6);
    for f in all {
        let name = f.file_stem().unwrap().to_string_lossy().into_owned();
        let rel = f.strip_prefix(common::root()).unwrap().to_path_buf();
        let (code, dae, err) = emit("dae", &rel);
        assert_eq!(code, Some(0), "{name}: {err}");
        insta::assert_snapshot!(format!("dae_{name}"), dae);
        let (code, structure, err) = emit("structure", &rel);
        assert_eq!(code, Some(0), "{name}: {err}");
        insta::assert_snapshot!(format!("structure_{name}"), structure);
    }
}

/// The Cartesian pendulum: index 3 reduced to index 1 with dummy derivatives; its
/// position and velocity candidates form two dynamic state sets (the Jacobian of the
/// constraint, `(2x, 2y)`, depends on the state), each with one state.
#[test]
fn pendulum_has_dynamic_state_sets_and_an_index_one_blt() {
    let (code, out, err) = emit("structure", Path::new("tests/structure/ok/Pendulum.mo"));
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("max differentiations: 2"), "{out}");
    let states = out.lines().find(|l| l.starts_with("states:")).unwrap();
    assert_eq!(states, "states: $set1.x[1], $set2.x[1]");
    let sets: Vec<&str> = out.lines().filter(|l| l.starts_with("state set")).collect();
    assert_eq!(sets.len(), 2, "{out}");
    // Candidates x and y; x, whose start is fixed, is the first state.
    assert!(
        sets[1].contains("of {x, y}") || sets[1].contains("of {y, x}"),
        "{}",
        sets[1]
    );
    assert!(sets[1].ends_with("first {x}"), "{}", sets[1]);
    // Every unknown is computed: the 9 equations, the 4 of index reduction and the
    // sets' 4 (s = A x and der(s) = A der(x)) for as many unknowns.
    assert!(
        out.contains("equations: 13 (6 differentiated), unknowns: 13"),
        "{out}"
    );
}

/// A stateSelect on the candidates decides statically: no state set.
#[test]
fn state_select_prefer_keeps_the_static_choice() {
    let (code, out, err) = emit("structure", Path::new("models/Pendulum.mo"));
    assert_eq!(code, Some(0), "{err}");
    assert!(!out.contains("state set"), "{out}");
    let states = out.lines().find(|l| l.starts_with("states:")).unwrap();
    assert_eq!(states, "states: x, vx");
}

/// The loop of three equations is torn to one iteration variable.
#[test]
fn algebraic_loop_is_torn_to_size_one() {
    let (code, out, err) = emit(
        "structure",
        Path::new("tests/structure/ok/AlgebraicLoop.mo"),
    );
    assert_eq!(code, Some(0), "{err}");
    let block = out.lines().find(|l| l.contains("block of 3")).expect(&out);
    let iter = block.split("iter {").nth(1).unwrap().trim_end_matches('}');
    assert_eq!(iter.split(',').count(), 1, "{block}");
}

/// Alias elimination removes the connection equations of the RLC circuit.
#[test]
fn rlc_alias_sets_are_eliminated() {
    let (code, out, _) = emit("dae", Path::new("tests/structure/ok/RLCCircuit.mo"));
    assert_eq!(code, Some(0));
    let count = |title: &str| -> usize {
        out.lines()
            .find_map(|l| l.strip_prefix(title))
            .and_then(|n| n.trim().parse().ok())
            .unwrap_or(0)
    };
    assert_eq!(count("aliases:"), 21, "{out}");
    assert_eq!(count("equations:"), 5, "{out}");
}

#[test]
fn structurally_singular_models_are_explained() {
    for f in common::mo_files("tests/structure/err") {
        let name = f.file_stem().unwrap().to_string_lossy().into_owned();
        let rel = f.strip_prefix(common::root()).unwrap().to_path_buf();
        let (code, _, err) = emit("structure", &rel);
        assert_eq!(code, Some(1), "{name}: {err}");
        assert!(err.contains("error[E3201]"), "{name}: {err}");
        assert!(err.contains("under-determined variables"), "{name}: {err}");
        insta::assert_snapshot!(format!("structure_err_{name}"), err);
    }
}

/// `unimo check` analyses every model of the syntax corpus as for simulation: all of
/// them pass (redeclared classes and packages, records included).
#[test]
fn syntax_corpus_passes_the_back_end() {
    let out = Command::new(env!("CARGO_BIN_EXE_unimo"))
        .args([
            "--color",
            "never",
            "check",
            "stdlib",
            "models",
            "tests/syntax/ok",
            "tests/structure/ok",
        ])
        .current_dir(common::root())
        .output()
        .expect("run unimo");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let mut failing: Vec<&str> = stderr
        .lines()
        .filter_map(|l| l.trim().strip_prefix("┌─ "))
        .map(|l| l.split(':').next().unwrap_or(l))
        .collect();
    failing.sort();
    failing.dedup();
    assert!(failing.is_empty(), "{stderr}");
    assert!(out.status.success(), "{stderr}");
}

/// `unimo emit --stage tape`: the compiled tapes of the bouncing ball (its zero
/// crossing, `when` with `reinit`, symbolic Jacobian).
#[test]
fn tape_dump_of_the_bouncing_ball() {
    let (code, out, err) = emit("tape", Path::new("models/BouncingBall.mo"));
    assert_eq!(code, Some(0), "{err}");
    insta::assert_snapshot!("tape_BouncingBall", out);
}

/// The DAE and plan verifiers (`unimo_dae::verify`) accept what the pipeline builds
/// and name what a broken plan or DAE does wrong.
#[test]
fn verifiers_accept_built_plans_and_reject_broken_ones() {
    use unimo_dae::plan::PlanStep;
    use unimo_dae::verify::{verify_dae, verify_plan};
    for file in [
        "models/Pendulum.mo",
        "models/FlySlideRoll.mo",
        "models/FourBar.mo",
    ] {
        let m = common::load(file, None);
        assert_eq!(verify_dae(&m.dae), Ok(()), "{file}");
        assert_eq!(verify_plan(&m.dae, &m.analysis.plan), Ok(()), "{file}");
    }
    let m = common::load("models/Pendulum.mo", None);
    let plan = &m.analysis.plan;
    // The steps in reverse: the first step that reads a later one's result is named.
    let mut reversed = plan.clone();
    reversed.steps.reverse();
    let e = verify_plan(&m.dae, &reversed).unwrap_err();
    assert!(e.message.contains("before any step computes it"), "{e}");
    // A step twice.
    let mut twice = plan.clone();
    let first = twice.steps[0].clone();
    twice.steps.push(first);
    let e = verify_plan(&m.dae, &twice).unwrap_err();
    assert!(e.message.contains("already computed"), "{e}");
    // A state computed by a step.
    let mut state = plan.clone();
    if let PlanStep::Assign { var, .. } = &mut state.steps[0] {
        *var = plan.states[0];
    }
    let e = verify_plan(&m.dae, &state).unwrap_err();
    assert!(e.message.contains("already computed"), "{e}");
    // Derivatives out of order.
    let mut swapped = plan.clone();
    swapped.derivatives.swap(0, 1);
    let e = verify_plan(&m.dae, &swapped).unwrap_err();
    assert!(e.message.contains("as its derivative"), "{e}");
    // A broken derivative link in the DAE.
    let mut dae = m.dae.clone();
    let d = dae.scalars[plan.states[0].index()].derivative.unwrap();
    dae.scalars[d.index()].derivative_of = None;
    let e = verify_dae(&dae).unwrap_err();
    assert!(e.message.contains("does not name it back"), "{e}");
}

/// `E3022`: the derivative of a top-level input is needed but not given. Before, the
/// plan read `der(u)` without any step computing it (the simulator read zero).
#[test]
fn a_differentiated_input_is_a_coded_error() {
    let (code, _, err) = emit(
        "structure",
        Path::new("tests/structure/DifferentiatedInput.mo"),
    );
    assert_eq!(code, Some(1), "{err}");
    insta::assert_snapshot!("structure_differentiated_input", err);
}
