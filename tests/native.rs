//! Differential tests of the native engine (`unimo-codegen`, `--engine native`)
//! against the tape interpreter, its oracle: every model in `models/` and every
//! simulate test model, run with both engines, gives the same event log, the same
//! counters and the same values (to 1e-14 relative; in practice the same bits). Each
//! run checks that native code was compiled for every hot tape, and one test checks
//! that the simulator really runs it (a tape changed behind the native code's back
//! still computes the original results).

mod common;

use std::path::{Path, PathBuf};
use unimo_codegen::model::{CompiledModel, CompiledStep};
use unimo_codegen::{compile_model, NativeOptions, NativeStats};
use unimo_runtime::native::execute_shim;
use unimo_runtime::sim::{Overrides, SimOptions, SimResult};
use unimo_solve::Method;

/// A copy of the compiled model with native code for its hot tapes. The whole
/// right-hand side writes NaN to the registers it leaves unwritten
/// (`NativeOptions::poison_unstored`), so that a reader of the register file that does
/// not run the plan first after it changes the results.
fn native(m: &CompiledModel) -> (CompiledModel, NativeStats) {
    let mut n = m.clone();
    let options = NativeOptions {
        poison_unstored: true,
        ..NativeOptions::default()
    };
    let stats = compile_model(&mut n, &options, execute_shim).expect("native code");
    assert!(!stats.above_threshold);
    for step in &n.steps {
        match step {
            CompiledStep::Explicit(t) => assert!(t.is_native()),
            CompiledStep::Block(b) => {
                assert!(b.residual_tape.is_native());
                assert!(b.jacobian_tape.ops.is_empty() || b.jacobian_tape.is_native());
            }
        }
    }
    assert!(n.roots_tape.ops.is_empty() || n.roots_tape.is_native());
    assert!(n.when_tape.ops.is_empty() || n.when_tape.is_native());
    (n, stats)
}

/// The experiment's settings, the stop time capped at `max_stop`.
fn options(l: &unimo_cli::LoadedModel, max_stop: f64) -> SimOptions {
    let mut o = SimOptions::resolve(
        &l.dae.experiment,
        &Overrides::default(),
        Method::Auto,
        false,
    )
    .expect("options");
    if o.stop - o.start > max_stop {
        o.stop = o.start + max_stop;
        o.interval = o.interval.min(max_stop / 50.0);
    }
    o
}

/// The largest relative difference between the two runs' values; panics when their
/// times, events, counters or outcome differ.
fn compare(name: &str, tape: &SimResult, native: &SimResult) -> f64 {
    assert_eq!(
        tape.error.as_ref().map(|e| e.message()),
        native.error.as_ref().map(|e| e.message()),
        "{name}: outcome"
    );
    assert_eq!(tape.events, native.events, "{name}: event log");
    // Plan evaluations aside: the interpreter skips the evaluation of the root functions
    // at the point the right-hand side just evaluated; the native right-hand side
    // writes the registers itself and does not record that point.
    let plan_evaluations_aside = |s: &unimo_runtime::sim::SimStats| unimo_runtime::sim::SimStats {
        rhs_evaluations: 0,
        ..s.clone()
    };
    assert_eq!(
        plan_evaluations_aside(&tape.stats),
        plan_evaluations_aside(&native.stats),
        "{name}: counters"
    );
    assert!(
        tape.stats.rhs_evaluations <= native.stats.rhs_evaluations,
        "{name}: the interpreter evaluates the plan at most as often"
    );
    assert_eq!(tape.times.len(), native.times.len(), "{name}: rows");
    let mut worst = 0.0f64;
    for (k, (a, b)) in tape.times.iter().zip(&native.times).enumerate() {
        assert_eq!(a.to_bits(), b.to_bits(), "{name}: time of row {k}");
    }
    for (ra, rb) in tape.rows.iter().zip(&native.rows) {
        for (c, (&a, &b)) in ra.iter().zip(rb).enumerate() {
            if a.is_nan() && b.is_nan() || a == b {
                continue;
            }
            let rel = (a - b).abs() / a.abs().max(b.abs());
            assert!(rel <= 1e-14, "{name}: {} = {a} vs {b}", tape.names[c]);
            worst = worst.max(rel);
        }
    }
    worst
}

/// The models of a file: the one model it holds, else every `Package.Model` of a
/// package file (the simulate tests keep several models in one file). Err: the
/// diagnostics of a file none of whose models compiles.
fn models_of(file: &Path) -> Result<Vec<(String, unimo_cli::LoadedModel)>, String> {
    if let Ok(l) = unimo_cli::load_model(&[file.to_path_buf()], None) {
        return Ok(vec![(String::new(), l)]);
    }
    let text = std::fs::read_to_string(file).map_err(|e| e.to_string())?;
    let word_after = |line: &str, kw: &str| {
        let rest = line.trim_start().strip_prefix(kw)?;
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        (!name.is_empty()).then_some(name)
    };
    let package = text.lines().find_map(|l| word_after(l, "package "));
    let mut out = Vec::new();
    let mut last = String::from("no model");
    for name in text.lines().filter_map(|l| word_after(l, "model ")) {
        let full = match &package {
            Some(p) => format!("{p}.{name}"),
            None => name,
        };
        match unimo_cli::load_model(&[file.to_path_buf()], Some(&full)) {
            Ok(l) => out.push((format!(" ({full})"), l)),
            Err(e) => last = e,
        }
    }
    if out.is_empty() {
        Err(last)
    } else {
        Ok(out)
    }
}

/// Runs every model of every file of `dir` with both engines. Returns the number of
/// models compared and the files none of whose models compiles (the tests of refused
/// constructs).
/// With `must_succeed`, each run must also end without an error (the bundled models,
/// under the command line's defaults; the test models include failures on purpose).
fn compare_folder(dir: &Path, max_stop: f64, must_succeed: bool) -> (usize, Vec<String>) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "mo"))
        .collect();
    files.sort();
    let (mut compared, mut skipped) = (0, Vec::new());
    for file in files {
        let file_name = file
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let Ok(models) = models_of(&file) else {
            eprintln!("{file_name}: does not compile (skipped)");
            skipped.push(file_name);
            continue;
        };
        for (model, l) in models {
            let name = format!("{file_name}{model}");
            let o = options(&l, max_stop);
            let (n, stats) = native(&l.compiled);
            let tape = unimo_runtime::sim::simulate(&l.compiled, &o);
            let native = unimo_runtime::sim::simulate(&n, &o);
            let worst = compare(&name, &tape, &native);
            if must_succeed {
                assert!(
                    tape.error.is_none(),
                    "{name}: {:?}",
                    tape.error.as_ref().map(|e| e.message())
                );
            }
            eprintln!(
                "{name}: {} rows, {} events, {} native functions ({} instructions, {} \
                 interpreted), largest difference {worst:e}",
                tape.times.len(),
                tape.events.len(),
                stats.functions,
                stats.native_ops,
                stats.interpreted_ops
            );
            // A class of parameters only (a package's `World` with its functions) has
            // nothing to compile; every other model must run native code.
            if stats.functions == 0 && tape.names.is_empty() {
                continue;
            }
            assert!(stats.functions > 0, "{name}: no native code");
            compared += 1;
        }
    }
    (compared, skipped)
}

/// Every model of `models/` ends without an error under its experiment's settings and
/// the command line's defaults (rows between grid points included), and native code
/// gives the interpreter's results.
#[test]
fn every_bundled_model_runs_and_runs_the_same_natively() {
    let (compared, skipped) = compare_folder(&common::root().join("models"), 5.0, true);
    assert!(skipped.is_empty(), "{skipped:?}");
    assert!(compared >= 28, "{compared}");
}

#[test]
fn every_simulate_test_model_runs_the_same_natively() {
    let (compared, skipped) = compare_folder(&common::root().join("tests/simulate"), 5.0, false);
    // Clocked partitions and an unknown `__unimo_method` are refused with coded
    // errors (`tests/simulate.rs`).
    assert_eq!(skipped, ["ClockedNotSupported.mo", "UnknownMethod.mo"]);
    assert!(compared >= 24, "{compared}");
}

#[test]
fn the_simulator_runs_the_native_code() {
    let l = common::load("models/BouncingBall.mo", None);
    let o = options(&l, 3.0);
    let (mut n, _) = native(&l.compiled);
    let reference = unimo_runtime::sim::simulate(&n, &o);
    // Change the interpreted instructions of every explicit step without changing
    // their number: the native code, compiled before, still computes the model.
    let mut changed = 0;
    for step in &mut n.steps {
        if let CompiledStep::Explicit(t) = step {
            for op in &mut t.ops {
                if let unimo_codegen::tape::Op::Copy(d, _) = *op {
                    *op = unimo_codegen::tape::Op::Const(d, 0.0);
                    changed += 1;
                }
            }
        }
    }
    assert!(changed > 0);
    let again = unimo_runtime::sim::simulate(&n, &o);
    compare("BouncingBall (native)", &reference, &again);
    // The interpreter on the same changed instructions computes something else.
    for step in &mut n.steps {
        if let CompiledStep::Explicit(t) = step {
            t.native = None;
        }
    }
    n.native_rhs = None;
    let interpreted = unimo_runtime::sim::simulate(&n, &o);
    assert!(
        interpreted.rows != reference.rows || interpreted.error.is_some(),
        "the change must be visible to the interpreter"
    );
}

/// A plan of one explicit step gets a whole right-hand side function
/// (`CompiledModel::native_rhs`): the same bits as the interpreter, at many points, and
/// the evaluator really calls it (an instruction changed behind its back does not
/// change its result, while the interpreter sees the change).
#[test]
fn the_whole_right_hand_side_is_one_native_call() {
    use unimo_runtime::eval::RhsEvaluator;
    for file in [
        "models/Robertson.mo",
        "models/Hires.mo",
        "models/VanDerPol.mo",
    ] {
        let l = common::load(file, None);
        assert!(
            l.compiled.native_rhs.is_none(),
            "{file}: no native code before codegen"
        );
        let (n, _) = native(&l.compiled);
        assert!(
            n.native_rhs.is_some(),
            "{file}: a plan of one explicit step"
        );
        let states = n.states.len();
        let mut tape = RhsEvaluator::new(&l.compiled);
        let mut fast = RhsEvaluator::new(&n);
        for k in 0..50 {
            let x: Vec<f64> = (0..states)
                .map(|i| 0.1 + 0.37 * ((k * states + i) as f64).sin())
                .collect();
            let t = 0.01 * k as f64;
            let (mut a, mut b) = (vec![0.0; states], vec![0.0; states]);
            tape.rhs(t, &x, &mut a).unwrap();
            fast.rhs(t, &x, &mut b).unwrap();
            let bits = |v: &[f64]| v.iter().map(|z| z.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "{file} at point {k}");
        }
    }
    let l = common::load("models/Robertson.mo", None);
    let (mut n, _) = native(&l.compiled);
    let x = [0.9, 1e-4];
    let mut before = [0.0; 2];
    RhsEvaluator::new(&n).rhs(0.0, &x, &mut before).unwrap();
    let CompiledStep::Explicit(t) = &mut n.steps[0] else {
        panic!("one explicit step")
    };
    let last = t.ops.len() - 1;
    let d = t.ops[last]
        .written()
        .next()
        .expect("the last instruction writes der(y2)");
    t.ops[last] = unimo_codegen::tape::Op::Const(d, 0.0);
    let mut after = [0.0; 2];
    RhsEvaluator::new(&n).rhs(0.0, &x, &mut after).unwrap();
    assert_eq!(
        before, after,
        "the native function ran, not the changed tape"
    );
    n.native_rhs = None;
    for step in &mut n.steps {
        if let CompiledStep::Explicit(t) = step {
            t.native = None;
        }
    }
    RhsEvaluator::new(&n).rhs(0.0, &x, &mut after).unwrap();
    assert_eq!(after[1], 0.0, "the interpreter sees the change");
    assert_ne!(before[1], 0.0);
}

/// Native code keeps a temporary in a machine register, unstored, only when nothing but
/// later instructions of the same function read it (`translate::locals`). With one
/// function per 3 instructions most temporaries are read by another function than
/// the one computing them, and the models read temporaries through the runtime (zero
/// crossings, residuals, `when` conditions), the interpreter (relations in event mode,
/// held roundings) and other tapes: every one must still be stored, so the runs give
/// the interpreter's bits. Robertson and Hires also take the whole right-hand side
/// through the step's functions (a step longer than one function).
#[test]
fn values_read_elsewhere_are_stored() {
    let tiny = NativeOptions {
        max_ops_per_function: 3,
        ..NativeOptions::default()
    };
    for file in [
        "tests/native/SharedValues.mo",
        "models/BouncingBall.mo",
        "models/Robertson.mo",
        "models/Hires.mo",
        "models/SampleCounter.mo",
        "models/FlySlideRoll.mo",
    ] {
        let l = common::load(file, None);
        let o = options(&l, 2.0);
        for (label, opts) in [
            ("default", NativeOptions::default()),
            ("tiny", tiny.clone()),
        ] {
            let mut n = l.compiled.clone();
            let stats = compile_model(&mut n, &opts, execute_shim).expect("native code");
            assert!(stats.functions > 0);
            if n.single_step_ops().is_some() {
                assert!(n.native_rhs.is_some(), "{file}: one explicit step");
            }
            let tape = unimo_runtime::sim::simulate(&l.compiled, &o);
            let native = unimo_runtime::sim::simulate(&n, &o);
            assert!(tape.error.is_none(), "{file}: {:?}", tape.error);
            assert!(tape.times.len() > 10);
            let worst = compare(&format!("{file} ({label})"), &tape, &native);
            assert_eq!(worst, 0.0, "{file} ({label}): the same bits");
        }
    }
}

/// The whole native right-hand side leaves the plan's values out of the register file
/// (`NativeRhs`); the simulator checks assertions after each solver step from the
/// registers, so it runs the plan first (`Ode::refresh`): the tape's outcome and bits,
/// with the registers left as they were (an earlier pass's values) and with NaN in
/// them. Without the refresh the assertion reads `lag` of an earlier point and fails.
#[test]
fn assertions_after_a_step_read_the_plans_current_values() {
    let l = common::load("tests/native/StaleAssert.mo", None);
    let o = options(&l, 2.0);
    let tape = unimo_runtime::sim::simulate(&l.compiled, &o);
    assert!(tape.error.is_none(), "{:?}", tape.error);
    assert!(tape.stats.solver.steps > 10, "{:?}", tape.stats.solver);
    for poison in [false, true] {
        let mut n = l.compiled.clone();
        let options = NativeOptions {
            poison_unstored: poison,
            ..NativeOptions::default()
        };
        compile_model(&mut n, &options, execute_shim).expect("native code");
        assert!(n.native_rhs.is_some(), "a plan of one explicit step");
        let native = unimo_runtime::sim::simulate(&n, &o);
        let worst = compare(&format!("StaleAssert (poison {poison})"), &tape, &native);
        assert_eq!(worst, 0.0);
    }
}
