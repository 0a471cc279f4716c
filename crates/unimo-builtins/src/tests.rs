//! The table's own consistency: unique names, compiled forms that round-trip, and the
//! lists flattening used to keep by hand.

use crate::*;

#[test]
fn names_are_unique_and_documented() {
    for (i, b) in BUILTINS.iter().enumerate() {
        assert!(
            BUILTINS[..i].iter().all(|o| o.name != b.name),
            "`{}` twice",
            b.name
        );
        assert!(!b.doc.is_empty(), "`{}` has no doc line", b.name);
    }
}

#[test]
fn compiled_forms_round_trip() {
    for f in Fn1::ALL {
        assert_eq!(Fn1::from_name(f.name()), Some(f));
        assert!(matches!(f.entry().eval, Eval::Unary(_)));
    }
    for f in Fn2::ALL {
        assert_eq!(Fn2::from_name(f.name()), Some(f));
        assert!(matches!(f.entry().eval, Eval::Binary(_)));
    }
    assert_eq!(Fn1::from_name("integer"), Some(Fn1::Floor));
    assert_eq!(Fn1::Floor.name(), "floor");
    // Every entry with a scalar evaluation has a compiled form of the same arity.
    for b in BUILTINS {
        match (b.eval, b.compiled) {
            (Eval::None, None)
            | (Eval::Unary(_), Some(Compiled::Unary(_)))
            | (Eval::Binary(_), Some(Compiled::Binary(_))) => {}
            _ => panic!("`{}`: evaluation and compiled form disagree", b.name),
        }
    }
}

#[test]
fn events_and_discontinuities_follow_the_spec() {
    // Spec 3.7.1.1: exactly these trigger events.
    let rounding: Vec<&str> = BUILTINS
        .iter()
        .filter(|b| b.events == Events::Rounding)
        .map(|b| b.name)
        .collect();
    assert_eq!(rounding, ["ceil", "div", "floor", "integer", "mod", "rem"]);
    let piecewise: Vec<Fn1> = Fn1::ALL
        .into_iter()
        .filter(|f| f.is_discontinuous())
        .collect();
    assert_eq!(piecewise, [Fn1::Sign, Fn1::Floor, Fn1::Ceil]);
    for f in Fn2::ALL {
        assert_eq!(
            f.generates_events(),
            matches!(f, Fn2::Div | Fn2::Mod | Fn2::Rem)
        );
    }
}

/// The element-wise list flattening kept by hand before the table.
#[test]
fn elementwise_names_are_the_former_list() {
    let names: Vec<&str> = BUILTINS
        .iter()
        .filter(|b| b.elementwise)
        .map(|b| b.name)
        .collect();
    let mut want = vec![
        "der", "pre", "abs", "sign", "sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "sinh",
        "cosh", "tanh", "exp", "log", "log10", "noEvent", "floor", "ceil",
    ];
    let mut got = names.clone();
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want);
}

#[test]
fn integer_results_refuse_non_integers() {
    let integer = find("integer").unwrap();
    assert_eq!(integer.integer_result(3.0, false), Some(Ok(3)));
    assert_eq!(integer.integer_result(f64::NAN, false), Some(Err(())));
    assert_eq!(integer.integer_result(1e300, false), Some(Err(())));
    let div = find("div").unwrap();
    assert_eq!(div.integer_result(2.0, false), None);
    assert_eq!(div.integer_result(-2.0, true), Some(Ok(-2)));
    assert_eq!(div.integer_result(f64::INFINITY, true), Some(Err(())));
}
