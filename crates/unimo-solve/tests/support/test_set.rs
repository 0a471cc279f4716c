//! The plain maths of the Bari/CWI test-set problems that several programs restate:
//! HIRES's right-hand side and reference solution. Included by path (no dependencies)
//! by the solver's tests (`problems.rs`), the evaluation benchmark
//! (`benches/evaluation.rs`), the simulation tests (`tests/simulate.rs`) and the diffsol
//! comparison (`bench/compare/diffsol`); the C program of the IDA comparison writes it
//! again (`bench/compare/ida/ida_compare.c`).
#![allow(dead_code, clippy::excessive_precision)]

/// HIRES (plant physiology, 8 stiff ODEs): its end time.
pub const HIRES_T_END: f64 = 321.8122;

/// HIRES's initial state.
pub const HIRES_X0: [f64; 8] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057];

/// HIRES's reference solution at [`HIRES_T_END`] (the test set's).
pub const HIRES_REF: [f64; 8] = [
    7.371312573325668e-4,
    1.442485726316185e-4,
    5.888729740967575e-5,
    1.175651343283149e-3,
    2.386356198831331e-3,
    6.238968252742796e-3,
    2.849998395185769e-3,
    2.850001604814231e-3,
];

/// HIRES's right-hand side: `f = y'` at `y`.
pub fn hires_rhs(y: &[f64], f: &mut [f64]) {
    f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
    f[1] = 1.71 * y[0] - 8.75 * y[1];
    f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
    f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
    f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
    f[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
    f[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
    f[7] = -f[6];
}
