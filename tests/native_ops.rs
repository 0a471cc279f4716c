//! Every instruction, compiled natively and interpreted, on the same registers: the
//! same bits (NaN for NaN), in and out of event mode.

use unimo_codegen::model::{CompiledModel, CompiledStep};
use unimo_codegen::tape::{Op, Rounding, Tape};
use unimo_codegen::{compile_model, NativeOptions};
use unimo_dae::expr::{Fn1, Fn2, RelOp};
use unimo_runtime::exec::{EventState, Run};
use unimo_runtime::native::{execute_shim, RhsCall};

/// Interesting values: signed zeros, infinities, NaN, integers, halves, large.
const VALUES: [f64; 12] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    -2.5,
    3.0,
    1e300,
    -7.25e-3,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
];

const RELS: [RelOp; 6] = [
    RelOp::Lt,
    RelOp::Le,
    RelOp::Gt,
    RelOp::Ge,
    RelOp::Eq,
    RelOp::Ne,
];

/// Registers 0 and 1 are inputs, 2 a condition; results from 3 on.
fn program() -> Vec<Op> {
    let mut ops = vec![
        Op::Const(3, 0.1),
        Op::Copy(4, 0),
        Op::Add(5, 0, 1),
        Op::Sub(6, 0, 1),
        Op::Mul(7, 0, 1),
        Op::Div(8, 0, 1),
        Op::Pow(9, 0, 1),
        Op::Neg(10, 0),
        Op::And(11, 0, 1),
        Op::Or(12, 0, 1),
        Op::Not(13, 0),
        Op::Select(14, 2, 0, 1),
        Op::Sample(15, 0),
        Op::Held(Rounding::Floor, 16, 0, 0),
        Op::HeldBounds(Rounding::Trunc, 17, 18, 0),
        // A register read after an instruction the interpreter runs wrote it.
        Op::Add(19, 16, 17),
    ];
    let mut next = 20;
    for n in -16..=16 {
        ops.push(Op::Powi(next, 0, n));
        next += 1;
    }
    for &f in &Fn1::ALL {
        ops.push(Op::Fn1(f, next, 0));
        next += 1;
    }
    for &f in &Fn2::ALL {
        ops.push(Op::Fn2(f, next, 0, 1));
        next += 1;
    }
    for (k, &rel) in RELS.iter().enumerate() {
        ops.push(Op::Rel(rel, next, 0, 1));
        ops.push(Op::RelEvent(rel, next + 1, 0, 1, k as u32));
        // The relation's value read again (from the SSA value after the branch).
        ops.push(Op::Add(next + 2, next + 1, next));
        next += 3;
    }
    ops
}

/// A model of one explicit step whose every register counts as a scalar (none is a
/// temporary, so the native code stores every result, which the tests compare).
fn model(ops: Vec<Op>, n_registers: usize) -> CompiledModel {
    let mut m = CompiledModel {
        n_registers,
        root_ops: RELS.to_vec(),
        ..CompiledModel::default()
    };
    m.layout.temp_base = n_registers as u32;
    m.steps.push(CompiledStep::Explicit(Tape::new(ops)));
    m
}

fn events(event_mode: bool, sticky: bool) -> EventState {
    EventState {
        event_mode,
        sticky,
        relations: vec![1.0, 0.0, 1.0, 0.0, 1.0, 0.0],
        forced: vec![None, Some(1.0), None, None, None, None],
        samples: vec![1.0],
        held: vec![2.0],
        held_forced: vec![None],
        ..EventState::default()
    }
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

#[test]
fn native_code_computes_the_interpreters_bits() {
    let ops = program();
    let n = 200;
    let mut m = model(ops, n);
    let stats = compile_model(&mut m, &NativeOptions::default(), execute_shim).expect("compiles");
    // The step's function, and the whole right-hand side's (the plan is one step).
    assert_eq!(stats.functions, 2);
    assert!(m.native_rhs.is_some());
    assert_eq!(stats.interpreted_ops, 3);
    let CompiledStep::Explicit(tape) = &m.steps[0] else {
        unreachable!()
    };
    assert!(tape.is_native());
    let mut checked = 0;
    for &(event_mode, sticky) in &[(false, false), (true, false), (true, true)] {
        for &x in &VALUES {
            for &y in &VALUES {
                for &c in &[0.0, 1.0, f64::NAN] {
                    let mut ra = vec![0.0; n];
                    ra[..3].copy_from_slice(&[x, y, c]);
                    let mut rb = ra.clone();
                    let (mut ea, mut eb) = (events(event_mode, sticky), events(event_mode, sticky));
                    tape.run(&mut ra, &mut ea);
                    tape.interpret(&mut rb, &mut eb);
                    for k in 0..n {
                        assert!(
                            same(ra[k], rb[k]),
                            "register {k} at ({x}, {y}, {c}): {} vs {}",
                            ra[k],
                            rb[k]
                        );
                    }
                    assert_eq!(format!("{:?}", ea.relations), format!("{:?}", eb.relations));
                    assert_eq!(format!("{:?}", ea.held), format!("{:?}", eb.held));
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 3 * 12 * 12 * 3);
}

/// The whole right-hand side function (`NativeRhs`, called through `RhsCall`) made of
/// the same program, with every result a derivative: the interpreter's bits, in and
/// out of event mode (where the function gets no relation values and asks the
/// interpreter), and the same relation and held states afterwards; with and without
/// NaN written to the registers it does not store.
#[test]
fn the_right_hand_side_function_computes_the_interpreters_bits() {
    let ops = program();
    let used = ops
        .iter()
        .flat_map(|op| op.written())
        .max()
        .expect("results")
        + 1;
    let n = 400;
    let mut m = model(ops, n);
    let results: Vec<u32> = (3..used).collect();
    // The inputs x, y, c as states, then unused registers, one state per derivative.
    let fillers = 200..(200 + results.len() as u32 - 3);
    m.states = [0, 1, 2].into_iter().chain(fillers).collect();
    m.derivatives = results.clone();
    m.layout.time = (n - 1) as u32;
    let CompiledStep::Explicit(tape) = &m.steps[0] else {
        unreachable!()
    };
    let tape = tape.clone();
    let (mut checked, mut poisoned) = (0, 0);
    for poison in [false, true] {
        let mut c = m.clone();
        let options = NativeOptions {
            poison_unstored: poison,
            ..NativeOptions::default()
        };
        compile_model(&mut c, &options, execute_shim).expect("compiles");
        let call = RhsCall::new(&c).expect("the right-hand side fits its model");
        for &(event_mode, sticky) in &[(false, false), (true, false), (true, true)] {
            for &x in &VALUES {
                for &y in &VALUES {
                    for &cond in &[0.0, 1.0, f64::NAN] {
                        let mut ra = vec![0.0; n];
                        ra[..3].copy_from_slice(&[x, y, cond]);
                        let mut rb = ra.clone();
                        let (mut ea, mut eb) =
                            (events(event_mode, sticky), events(event_mode, sticky));
                        let xs: Vec<f64> = c.states.iter().map(|&s| ra[s as usize]).collect();
                        let mut out = vec![0.0; results.len()];
                        assert!(call.fits(&ra, &ea));
                        // SAFETY: `fits` holds on `ra` and `ea`.
                        let done =
                            unsafe { call.call_fitted(0.25, &xs, &mut out, &mut ra, &mut ea) };
                        assert!(done);
                        tape.interpret(&mut rb, &mut eb);
                        for (k, &r) in results.iter().enumerate() {
                            assert!(
                                same(out[k], rb[r as usize]),
                                "register {r} at ({x}, {y}, {cond}), event mode \
                                 {event_mode}: {} vs {}",
                                out[k],
                                rb[r as usize]
                            );
                        }
                        assert_eq!(format!("{:?}", ea.relations), format!("{:?}", eb.relations));
                        assert_eq!(format!("{:?}", ea.held), format!("{:?}", eb.held));
                        checked += 1;
                        if poison {
                            poisoned += results
                                .iter()
                                .filter(|&&r| ra[r as usize].is_nan() && !rb[r as usize].is_nan())
                                .count();
                        }
                    }
                }
            }
        }
    }
    assert_eq!(checked, 2 * 3 * 12 * 12 * 3);
    // Results left in machine registers read NaN in the register file.
    assert!(poisoned > 0);
}

#[test]
fn powi_matches_the_standard_library_on_many_values() {
    let mut ops = Vec::new();
    for n in -16..=16 {
        ops.push(Op::Powi((n + 17) as u32, 0, n));
    }
    let mut m = model(ops, 40);
    compile_model(&mut m, &NativeOptions::default(), execute_shim).expect("compiles");
    let CompiledStep::Explicit(tape) = &m.steps[0] else {
        unreachable!()
    };
    let mut x = 0.123_456_789_f64;
    for _ in 0..2_000 {
        x = (x * 7.31 + 0.17).fract() * 4.0 - 2.0;
        let mut r = vec![0.0; 40];
        r[0] = x;
        tape.run(&mut r, &mut events(false, false));
        for n in -16..=16 {
            assert!(same(r[(n + 17) as usize], x.powi(n)), "{x}^{n}");
        }
    }
}

#[test]
fn long_tapes_are_split_and_a_changed_tape_is_interpreted() {
    let ops: Vec<Op> = (0..100).map(|k| Op::Add(k + 3, k + 2, 0)).collect();
    let mut m = model(ops, 200);
    let options = NativeOptions {
        max_ops_per_function: 7,
        ..NativeOptions::default()
    };
    let stats = compile_model(&mut m, &options, execute_shim).expect("compiles");
    // 15 parts, and the whole right-hand side calling them.
    assert_eq!(stats.functions, 16);
    assert!(m.native_rhs.is_some());
    let CompiledStep::Explicit(tape) = &mut m.steps[0] else {
        unreachable!()
    };
    let mut r = vec![0.0; 200];
    r[0] = 1.5;
    tape.run(&mut r, &mut events(false, false));
    assert_eq!(r[102], 150.0);
    // The native code follows the instructions it was compiled from; a tape whose
    // length changed runs the interpreter again.
    tape.ops.push(Op::Const(150, 4.0));
    assert!(!tape.is_native());
    tape.run(&mut r, &mut events(false, false));
    assert_eq!(r[150], 4.0);
}

#[test]
fn a_model_above_the_threshold_keeps_its_tapes() {
    let mut m = model(vec![Op::Add(3, 0, 1); 50], 10);
    let options = NativeOptions {
        max_model_ops: 10,
        ..NativeOptions::default()
    };
    let stats = compile_model(&mut m, &options, execute_shim).expect("no error");
    assert!(stats.above_threshold);
    assert_eq!(stats.functions, 0);
}
