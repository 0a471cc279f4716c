//! The plain maths of the Bari/CWI test-set problems that several programs restate:
//! HIRES's and POLLU's right-hand sides and reference solutions. Included by path (no dependencies)
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

/// POLLU (the air pollution problem, `pollu.f`, Verwer 1994; 20 stiff ODEs, 25 reactions
/// `r_k = k_k y_a (y_b)`, `f = S r`): the rate constants.
pub const POLLU_K: [f64; 25] = [
    0.35, 26.6, 1.23e4, 8.6e-4, 8.2e-4, 1.5e4, 1.3e-4, 2.4e4, 1.65e4, 9.0e3, 2.2e-2, 1.2e4, 1.88,
    1.63e4, 4.8e6, 3.5e-4, 1.75e-2, 1.0e8, 4.44e11, 1.24e3, 2.1, 5.78, 4.74e-2, 1.78e3, 3.12,
];
/// Reactants of each reaction (0-based species); `None`: first order.
pub const POLLU_REACTANTS: [(usize, Option<usize>); 25] = [
    (0, None),
    (1, Some(3)),
    (4, Some(1)),
    (6, None),
    (6, None),
    (6, Some(5)),
    (8, None),
    (8, Some(5)),
    (10, Some(1)),
    (10, Some(0)),
    (12, None),
    (9, Some(1)),
    (13, None),
    (0, Some(5)),
    (2, None),
    (3, None),
    (3, None),
    (15, None),
    (15, None),
    (16, Some(5)),
    (18, None),
    (18, None),
    (0, Some(3)),
    (18, Some(0)),
    (19, None),
];
/// Net production of each reaction: (species, coefficient).
pub const POLLU_STOICH: [&[(usize, f64)]; 25] = [
    &[(0, -1.0), (1, 1.0), (2, 1.0)],
    &[(0, 1.0), (1, -1.0), (3, -1.0)],
    &[(0, 1.0), (1, -1.0), (4, -1.0), (5, 1.0)],
    &[(4, 2.0), (6, -1.0), (7, 1.0)],
    &[(6, -1.0), (7, 1.0)],
    &[(4, 1.0), (5, -1.0), (6, -1.0), (7, 1.0)],
    &[(4, 1.0), (7, 1.0), (8, -1.0), (9, 1.0)],
    &[(5, -1.0), (8, -1.0), (10, 1.0)],
    &[(0, 1.0), (1, -1.0), (9, 1.0), (10, -1.0), (11, 1.0)],
    &[(0, -1.0), (10, -1.0), (12, 1.0)],
    &[(0, 1.0), (10, 1.0), (12, -1.0)],
    &[(0, 1.0), (1, -1.0), (9, -1.0), (13, 1.0)],
    &[(4, 1.0), (6, 1.0), (13, -1.0)],
    &[(0, -1.0), (5, -1.0), (14, 1.0)],
    &[(2, -1.0), (3, 1.0)],
    &[(3, -1.0), (15, 1.0)],
    &[(2, 1.0), (3, -1.0)],
    &[(5, 2.0), (15, -1.0)],
    &[(2, 1.0), (15, -1.0)],
    &[(4, 1.0), (5, -1.0), (16, -1.0), (17, 1.0)],
    &[(1, 1.0), (18, -1.0)],
    &[(0, 1.0), (2, 1.0), (18, -1.0)],
    &[(0, -1.0), (3, -1.0), (18, 1.0)],
    &[(0, -1.0), (18, -1.0), (19, 1.0)],
    &[(0, 1.0), (18, 1.0), (19, -1.0)],
];
/// POLLU's initial state.
pub const POLLU_Y0: [f64; 20] = [
    0.0, 0.2, 0.0, 0.04, 0.0, 0.0, 0.1, 0.3, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.007, 0.0,
    0.0, 0.0,
];
/// POLLU's reference solution at [`POLLU_T_END`] (the test set's: RADAU5 in extended
/// precision, rtol = atol = 1.1e-18).
pub const POLLU_REF: [f64; 20] = [
    0.5646255480022769e-1,
    0.1342484130422339,
    0.4139734331099427e-8,
    0.5523140207484359e-2,
    0.2018977262302196e-6,
    0.1464541863493966e-6,
    0.7784249118997964e-1,
    0.3245075353396018,
    0.7494013383880406e-2,
    0.1622293157301561e-7,
    0.1135863833257075e-7,
    0.2230505975721359e-2,
    0.2087162882798630e-3,
    0.1396921016840158e-4,
    0.8964884856898295e-2,
    0.4352846369330103e-17,
    0.6899219696263405e-2,
    0.1007803037365946e-3,
    0.1772146513969984e-5,
    0.5682943292316392e-4,
];

/// POLLU's end time.
pub const POLLU_T_END: f64 = 60.0;

/// POLLU's right-hand side: `f = y'` at `y`, from the reaction table.
pub fn pollu_rhs(y: &[f64], f: &mut [f64]) {
    f.fill(0.0);
    for (k, &(a, b)) in POLLU_REACTANTS.iter().enumerate() {
        let r = POLLU_K[k] * y[a] * b.map_or(1.0, |b| y[b]);
        for &(i, s) in POLLU_STOICH[k] {
            f[i] += s * r;
        }
    }
}
