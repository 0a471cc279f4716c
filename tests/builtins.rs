//! The table of built-ins (`unimo_builtins::BUILTINS`) against the two evaluators that
//! read it: every entry with a scalar evaluation gives the same value (bitwise, or
//! within one ulp) from flattening's constant evaluator (`constant Real p = f(c)`,
//! its binding evaluated) and from compiled code (`y = f(time)` run on the tapes at
//! `time = c`); where the constant evaluator refuses (an Integer result that is no
//! Integer), compiled code gives a value that is no Integer either. Also: the name
//! check and lowering know every entry.

use unimo_builtins::{Eval, Kind, Ty, BUILTINS};
use unimo_runtime::exec::{Instance, Run};

/// Flattens `text` (its last class) in memory.
fn flatten_text(text: &str) -> Result<unimo_flat::FlatModel, String> {
    let provider = unimo_flat::MemoryProvider::new();
    let mut tree = unimo_flat::ClassTree::new(&provider);
    let file = tree.sources.add("builtins.mo", text.to_owned());
    let parsed = unimo_syntax::parse(file, text);
    assert!(!parsed.has_errors(), "{text}");
    let classes = tree.add_user_file(file, parsed.ast);
    let (model, diags) = unimo_flat::flatten(&mut tree, *classes.last().unwrap());
    let errors: Vec<String> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{} {}", d.code, d.message))
        .collect();
    if errors.is_empty() {
        Ok(model)
    } else {
        Err(errors.join("; "))
    }
}

/// An environment without variables: the binding must be a constant expression.
struct NoVariables;

impl unimo_flat::eval::Env for NoVariables {
    fn var(
        &mut self,
        key: &str,
        span: unimo_source::Span,
    ) -> Result<unimo_flat::eval::Value, unimo_flat::eval::EvalError> {
        Err(unimo_flat::eval::EvalError::NotConstant {
            span,
            what: key.to_owned(),
        })
    }
}

/// `call` evaluated by the constant evaluator; `Err` when it refuses.
fn constant_value(call: &str) -> Result<f64, String> {
    let model = flatten_text(&format!("model C\n  constant Real p = {call};\nend C;\n"))?;
    let p = model.vars.iter().find(|v| v.name == "p").expect("p");
    let binding = p.binding.as_ref().expect("a binding");
    let v = unimo_flat::eval::eval(binding, &mut NoVariables, &mut Vec::new())
        .map_err(|e| format!("{e:?}"))?;
    v.as_f64().ok_or_else(|| format!("not a number: {v:?}"))
}

/// `y = call` (which reads `time`) compiled and run once on the tapes at `time = t`.
fn compiled_value(call: &str, t: f64) -> f64 {
    let text = format!("model M\n  Real y;\nequation\n  y = {call};\nend M;\n");
    let flat = flatten_text(&text).unwrap_or_else(|e| panic!("{call}: {e}"));
    let (dae, analysis) = unimo_dae::analyze_model(&flat).unwrap_or_else(|d| {
        panic!(
            "{call}: {:?}",
            d.iter().map(|d| &d.message).collect::<Vec<_>>()
        )
    });
    let m = unimo_codegen::model::compile(&dae, &analysis.plan);
    let mut r = m.new_registers();
    let mut ev = m.new_event_state();
    // Event mode: roundings and relations are computed, not held.
    ev.event_mode = true;
    m.run_parameters(&mut r, &mut ev).expect("parameters");
    r[m.layout.time as usize] = t;
    let mut work = unimo_runtime::eval::Workspace::default();
    unimo_runtime::eval::eval_steps(&m, &mut r, &mut ev, &mut work).expect("the plan");
    m.alias_tape.run(&mut r, &mut ev);
    let (_, reg) = m.outputs.iter().find(|(n, _)| n == "y").expect("y");
    r[*reg as usize]
}

/// A Modelica literal of `x` (Integer form when `integer`).
fn literal(x: f64, integer: bool) -> String {
    if integer {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

fn whole(x: f64) -> bool {
    x.fract() == 0.0 && x.abs() < 1e15
}

/// Equal bitwise, or as numbers (0 and -0), or within one ulp, or both NaN.
fn same(a: f64, b: f64) -> bool {
    a == b
        || (a.is_nan() && b.is_nan())
        || (a.is_finite() && b.is_finite() && (a.to_bits() as i64 - b.to_bits() as i64).abs() <= 1)
}

const UNARY_POINTS: &[f64] = &[
    0.0, 0.5, -0.5, 1.0, -1.0, 2.0, -3.7, 7.0, 1e-300, 1e300, -1e300, 710.0, 3.0e10,
];

const BINARY_POINTS: &[(f64, f64)] = &[
    (1.0, 2.0),
    (-1.0, 2.0),
    (7.0, 2.0),
    (-7.0, 2.0),
    (7.0, -2.0),
    (-7.0, -2.0),
    (0.5, -0.25),
    (3.0, 3.0),
    (0.0, 0.0),
    (1.0, 0.0),
    (-1.0, 0.0),
    (1e300, 1e-300),
    (-2.5, 1e300),
];

/// Compares the two evaluators at one point; returns a description of a mismatch.
fn check(name: &str, args: &[f64], integer_args: bool, compiled: f64) -> Option<String> {
    let text: Vec<String> = args.iter().map(|&x| literal(x, integer_args)).collect();
    let call = format!("{name}({})", text.join(", "));
    match constant_value(&call) {
        Ok(c) if same(c, compiled) => None,
        Ok(c) => Some(format!("{call}: constant {c:e}, compiled {compiled:e}")),
        // Refused: an Integer result that is none; compiled code has no Integer either.
        Err(e) if unimo_builtins::maths::to_integer(compiled).is_none() => {
            assert!(e.contains("no Integer"), "{call}: {e}");
            None
        }
        Err(e) => Some(format!(
            "{call}: constant refused ({e}), compiled {compiled:e}"
        )),
    }
}

/// The differential test: every entry with a scalar evaluation, at every point.
#[test]
fn constant_evaluator_and_compiled_code_agree_on_every_builtin() {
    let mut mismatches = Vec::new();
    let (mut entries, mut points) = (0, 0);
    for b in BUILTINS {
        let integers_allowed =
            matches!(b.result, Ty::SameAsArguments | Ty::Integer) || b.kind == Kind::Rounding;
        match b.eval {
            Eval::None => continue,
            Eval::Unary(_) => {
                for &x in UNARY_POINTS {
                    let y = compiled_value(&format!("{}(time)", b.name), x);
                    mismatches.extend(check(b.name, &[x], false, y));
                    if integers_allowed && whole(x) {
                        mismatches.extend(check(b.name, &[x], true, y));
                    }
                    points += 1;
                }
            }
            Eval::Binary(_) => {
                for &(x, y) in BINARY_POINTS {
                    // Each argument in turn the one computed at run time.
                    let first =
                        compiled_value(&format!("{}(time, {})", b.name, literal(y, false)), x);
                    let second =
                        compiled_value(&format!("{}({}, time)", b.name, literal(x, false)), y);
                    assert!(
                        same(first, second),
                        "{}({x}, {y}): {first} vs {second}",
                        b.name
                    );
                    mismatches.extend(check(b.name, &[x, y], false, first));
                    if integers_allowed && whole(x) && whole(y) {
                        mismatches.extend(check(b.name, &[x, y], true, first));
                    }
                    points += 1;
                }
            }
        }
        entries += 1;
    }
    assert_eq!(entries, 24, "entries with a scalar evaluation");
    assert!(points >= 24 * 10);
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
}

/// Points where the two evaluators disagreed before the table (the constant
/// evaluator picked an operand by `<=`, saturated `integer` to 64 bits).
#[test]
fn former_disagreements_are_gone() {
    // min/max with a NaN operand: `f64::min` everywhere (the other operand).
    assert_eq!(constant_value("min(1.0, sqrt(-1.0))"), Ok(1.0));
    assert_eq!(constant_value("max(sqrt(-1.0), 2.0)"), Ok(2.0));
    assert_eq!(compiled_value("min(1.0, sqrt(time))", -1.0), 1.0);
    // integer() of a value beyond the Integer range is refused, not saturated.
    assert!(constant_value("integer(1e300)").is_err());
    assert!(constant_value("div(1, 0)").is_err());
    assert_eq!(constant_value("integer(-2.5)"), Ok(-3.0));
    // log10 of an array is element-wise in the balance count as elsewhere (balance.rs's
    // own list lacked it; the count was right anyway, since the left side decides).
    let model = flatten_text(
        "model L\n  Real x[3] = {1, 2, 3};\n  Real y[3];\nequation\n  y = log10(x);\nend L;\n",
    )
    .expect("flattens");
    let b = unimo_flat::balance::count(&model);
    assert_eq!((b.equations, b.unknowns), (6, 6));
}

/// The name check and lowering know every entry: the former hand-kept list of
/// built-in function names is in the table, and every implemented entry is a
/// built-in to the name check (the unsupported ones are refused by lowering).
#[test]
fn every_builtin_name_has_one_entry() {
    const FORMER_LIST: &[&str] = &[
        "abs",
        "acos",
        "asin",
        "assert",
        "atan",
        "atan2",
        "array",
        "cardinality",
        "cat",
        "ceil",
        "change",
        "cos",
        "cosh",
        "cross",
        "delay",
        "der",
        "diagonal",
        "div",
        "edge",
        "exp",
        "fill",
        "floor",
        "collisionBody",
        "collisionGaps",
        "homotopy",
        "identity",
        "initial",
        "integer",
        "invariant",
        "linspace",
        "log",
        "log10",
        "matrix",
        "max",
        "min",
        "mod",
        "ndims",
        "noEvent",
        "ones",
        "outerProduct",
        "pre",
        "product",
        "reinit",
        "rem",
        "sample",
        "scalar",
        "semiLinear",
        "sign",
        "sin",
        "sinh",
        "size",
        "skew",
        "smooth",
        "sqrt",
        "String",
        "sum",
        "symmetric",
        "tan",
        "tanh",
        "terminal",
        "terminate",
        "transpose",
        "vector",
        "zeros",
        "Integer",
        "Boolean",
        "Real",
    ];
    let names: Vec<&str> = unimo_builtins::function_names().collect();
    assert_eq!(names, FORMER_LIST, "the name check's list, in its order");
    for (i, b) in BUILTINS.iter().enumerate() {
        assert!(
            BUILTINS[..i].iter().all(|o| o.name != b.name),
            "`{}` twice",
            b.name
        );
        let implemented = b.kind != Kind::Unsupported;
        assert_eq!(
            unimo_flat::lookup::is_builtin_function(b.name),
            implemented,
            "{}",
            b.name
        );
        assert_eq!(
            unimo_flat::lookup::is_unsupported_builtin(b.name),
            !implemented,
            "{}",
            b.name
        );
    }
}
