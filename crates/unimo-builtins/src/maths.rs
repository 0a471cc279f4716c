//! The scalar maths of the built-ins std does not provide as one method, written once:
//! the table's evaluations point here or at `f64`'s methods.

/// `sign(x)`: 1, -1 or 0 (0 for NaN too).
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// `div(x, y)`: the quotient truncated toward zero.
pub fn div(x: f64, y: f64) -> f64 {
    (x / y).trunc()
}

/// `mod(x, y) = x - floor(x / y) * y`.
pub fn modulo(x: f64, y: f64) -> f64 {
    x - (x / y).floor() * y
}

/// `rem(x, y) = x - div(x, y) * y`.
pub fn rem(x: f64, y: f64) -> f64 {
    x - (x / y).trunc() * y
}

/// `min(x, y)` of two scalars (`f64::min`: a NaN operand gives the other).
pub fn min(x: f64, y: f64) -> f64 {
    x.min(y)
}

/// `max(x, y)` of two scalars (`f64::max`: a NaN operand gives the other).
pub fn max(x: f64, y: f64) -> f64 {
    x.max(y)
}

/// `r` as an Integer when it is one: whole and inside the 64-bit range (NaN and
/// infinities are not).
pub fn to_integer(r: f64) -> Option<i64> {
    // 2^63 is the first f64 beyond i64::MAX; -2^63 is i64::MIN exactly.
    const LIMIT: f64 = 9_223_372_036_854_775_808.0;
    (r.fract() == 0.0 && (-LIMIT..LIMIT).contains(&r)).then_some(r as i64)
}
