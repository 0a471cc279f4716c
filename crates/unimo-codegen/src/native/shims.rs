//! The Rust functions native code calls: the built-in maths of `unimo-builtins` (one
//! `extern "C"` entry per function, so a native tape computes bit for bit what the
//! interpreter computes), `powf`, and the runtime's one-instruction interpreter for the
//! instructions that are not translated (`unimo_runtime::native::execute_shim`).

use unimo_dae::expr::{Fn1, Fn2};

/// A unary maths function as native code calls it.
pub type Unary = extern "C" fn(f64) -> f64;
/// A binary maths function as native code calls it.
pub type Binary = extern "C" fn(f64, f64) -> f64;

extern "C" fn unary<const K: usize>(x: f64) -> f64 {
    Fn1::ALL[K].apply(x)
}

extern "C" fn binary<const K: usize>(x: f64, y: f64) -> f64 {
    Fn2::ALL[K].apply(x, y)
}

/// Entry `k` evaluates `Fn1::ALL[k]`.
const UNARY: [Unary; 17] = [
    unary::<0>,
    unary::<1>,
    unary::<2>,
    unary::<3>,
    unary::<4>,
    unary::<5>,
    unary::<6>,
    unary::<7>,
    unary::<8>,
    unary::<9>,
    unary::<10>,
    unary::<11>,
    unary::<12>,
    unary::<13>,
    unary::<14>,
    unary::<15>,
    unary::<16>,
];

/// Entry `k` evaluates `Fn2::ALL[k]`.
const BINARY: [Binary; 6] = [
    binary::<0>,
    binary::<1>,
    binary::<2>,
    binary::<3>,
    binary::<4>,
    binary::<5>,
];

/// The entry evaluating `f`.
pub fn unary_of(f: Fn1) -> Unary {
    let k = Fn1::ALL.iter().position(|&g| g == f).unwrap_or(0);
    UNARY[k]
}

/// The entry evaluating `f`.
pub fn binary_of(f: Fn2) -> Binary {
    let k = Fn2::ALL.iter().position(|&g| g == f).unwrap_or(0);
    BINARY[k]
}

/// `x^y` as the interpreter computes it.
pub extern "C" fn powf(x: f64, y: f64) -> f64 {
    x.powf(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_evaluates_its_own_function() {
        let points = [-2.5, -1.0, -0.3, 0.0, 0.4, 1.0, 2.7, 1e3];
        for &f in &Fn1::ALL {
            for &x in &points {
                let (a, b) = (unary_of(f)(x), f.apply(x));
                assert!(
                    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                    "{f:?}"
                );
            }
        }
        for &f in &Fn2::ALL {
            for &x in &points {
                for &y in &points {
                    let (a, b) = (binary_of(f)(x, y), f.apply(x, y));
                    assert!(a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()));
                }
            }
        }
    }
}
