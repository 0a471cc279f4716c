//! The MSL's real FFT (`Modelica.Math.FastFourierTransform.Internal.rawRealFFT`,
//! external C function `ModelicaFFT_kiss_fftr`, which wraps KissFFT), written again in
//! Rust: a recursive mixed-radix discrete Fourier transform (radices 2, 3, 4, 5 and, for
//! any other prime factor, a direct sum), with the outputs as `ModelicaFFT.c` forms
//! them.
//!
//! For `u` of even length `n` and `nf = n/2 + 1`, with `X[k] = sum_j u[j] e^(-2 pi i j
//! k / n)`: `amplitudes[k] = |X[k]| / nf` and `phases[k] = atan2(Im X[k], Re X[k])` (in
//! radians; `realFFT` converts them to degrees), `k = 0 .. nf - 1`; `info = 0`. An odd
//! `n` gives `info = 1` (and zero outputs), as the C function returns before computing.

use std::f64::consts::PI;

/// The distance between the scratch areas of two FFT sites: a site's base is its
/// number times this, a value's slot the base plus its position.
pub const SITE_STRIDE: f64 = 1e7;

/// A complex number `(re, im)`.
type Complex = (f64, f64);

fn mul(a: Complex, b: Complex) -> Complex {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

/// `e^(-2 pi i k / n)`.
fn twiddle(k: usize, n: usize) -> Complex {
    let angle = -2.0 * PI * (k % n) as f64 / n as f64;
    (angle.cos(), angle.sin())
}

/// The smallest factor of `n` among 4, 2, 3, 5, else its smallest prime factor.
fn radix(n: usize) -> usize {
    for r in [4, 2, 3, 5] {
        if n.is_multiple_of(r) {
            return r;
        }
    }
    (7..=n)
        .step_by(2)
        .find(|&r| n.is_multiple_of(r))
        .unwrap_or(n)
}

/// The discrete Fourier transform of `x` (forward, unscaled), by decimation in time:
/// `x` split into `r` interleaved subsequences of length `m = n / r`, each transformed,
/// then combined by a direct `r`-point transform of the twiddled values.
pub fn dft(x: &[Complex]) -> Vec<Complex> {
    let table: Vec<Complex> = (0..x.len()).map(|k| twiddle(k, x.len())).collect();
    dft_with(x, &table)
}

/// [`dft`] of `x`, whose length divides the length `N` of `table`, the twiddles
/// `e^(-2 pi i k / N)`.
fn dft_with(x: &[Complex], table: &[Complex]) -> Vec<Complex> {
    let n = x.len();
    if n <= 1 {
        return x.to_vec();
    }
    let step = table.len() / n;
    let w = |k: usize| table[(k % n) * step];
    let r = radix(n);
    let m = n / r;
    let parts: Vec<Vec<Complex>> = (0..r)
        .map(|j| {
            let sub: Vec<Complex> = x.iter().skip(j).step_by(r).copied().collect();
            dft_with(&sub, table)
        })
        .collect();
    let mut out = vec![(0.0, 0.0); n];
    let mut t = vec![(0.0, 0.0); r];
    for k in 0..m {
        for (j, part) in parts.iter().enumerate() {
            t[j] = if j == 0 {
                part[k]
            } else {
                mul(part[k], w(j * k))
            };
        }
        for q in 0..r {
            let mut acc = (0.0, 0.0);
            for (j, &tj) in t.iter().enumerate() {
                let w = w(j * q * m);
                let p = mul(tj, w);
                acc = (acc.0 + p.0, acc.1 + p.1);
            }
            out[k + q * m] = acc;
        }
    }
    out
}

/// What `ModelicaFFT_kiss_fftr` returns for the real signal `u`.
#[derive(Clone, Debug, PartialEq)]
pub struct RealFft {
    /// 0 computed; 1 the length of `u` is odd.
    pub info: i32,
    /// `n/2 + 1` amplitudes.
    pub amplitudes: Vec<f64>,
    /// `n/2 + 1` phases in radians.
    pub phases: Vec<f64>,
}

/// The real FFT of `u` (see the module comment).
pub fn real_fft(u: &[f64]) -> RealFft {
    let n = u.len();
    let nf = n / 2 + 1;
    if !n.is_multiple_of(2) {
        return RealFft {
            info: 1,
            amplitudes: vec![0.0; nf],
            phases: vec![0.0; nf],
        };
    }
    let x: Vec<Complex> = u.iter().map(|&v| (v, 0.0)).collect();
    let spectrum = dft(&x);
    let scale = nf as f64;
    RealFft {
        info: 0,
        amplitudes: spectrum[..nf]
            .iter()
            .map(|c| c.0.hypot(c.1) / scale)
            .collect(),
        phases: spectrum[..nf].iter().map(|c| c.1.atan2(c.0)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The transform by its definition, `O(n^2)`: the oracle.
    fn naive(x: &[Complex]) -> Vec<Complex> {
        let n = x.len();
        (0..n)
            .map(|k| {
                x.iter().enumerate().fold((0.0, 0.0), |acc, (j, &v)| {
                    let p = mul(v, twiddle(j * k, n));
                    (acc.0 + p.0, acc.1 + p.1)
                })
            })
            .collect()
    }

    #[test]
    fn mixed_radix_matches_the_definition() {
        // Lengths with factors 2, 3, 4, 5, a prime (7, 11) and the example's 4000.
        for n in [
            1, 2, 3, 4, 5, 6, 8, 10, 12, 14, 30, 44, 60, 98, 120, 250, 4000,
        ] {
            let x: Vec<Complex> = (0..n)
                .map(|j| {
                    let t = j as f64;
                    ((0.3 * t).sin() + 0.01 * t, (0.7 * t).cos() - 0.5)
                })
                .collect();
            let (fast, slow) = (dft(&x), naive(&x));
            let size = slow.iter().map(|c| c.0.hypot(c.1)).fold(1.0, f64::max);
            for (k, (a, b)) in fast.iter().zip(&slow).enumerate() {
                let err = (a.0 - b.0).hypot(a.1 - b.1);
                assert!(err <= 1e-12 * size, "n = {n}, k = {k}: {a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn real_fft_of_known_spectra() {
        // u = 2 + 3 cos(2 pi 5 j / n + 0.4) - 1.5 sin(2 pi 12 j / n), n = 60: X[0] = 2 n,
        // X[5] = 3 n / 2 e^(0.4 i), X[12] = 1.5 n / 2 e^(i pi / 2); amplitudes |X| / nf.
        let n = 60;
        let nf = (n / 2 + 1) as f64;
        let u: Vec<f64> = (0..n)
            .map(|j| {
                let w = 2.0 * PI * j as f64 / n as f64;
                2.0 + 3.0 * (5.0 * w + 0.4).cos() - 1.5 * (12.0 * w).sin()
            })
            .collect();
        let r = real_fft(&u);
        assert_eq!(r.info, 0);
        assert_eq!(r.amplitudes.len(), 31);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
        assert!(close(r.amplitudes[0], 2.0 * n as f64 / nf));
        assert!(close(r.amplitudes[5], 1.5 * n as f64 / nf));
        assert!(close(r.phases[5], 0.4));
        assert!(close(r.amplitudes[12], 0.75 * n as f64 / nf));
        assert!(close(r.phases[12], PI / 2.0));
        for k in (1..31).filter(|&k| k != 5 && k != 12) {
            assert!(r.amplitudes[k] < 1e-12, "k = {k}: {}", r.amplitudes[k]);
        }
    }

    #[test]
    fn odd_length_is_info_1() {
        let r = real_fft(&[1.0, 2.0, 3.0]);
        assert_eq!(r.info, 1);
        assert_eq!(r.amplitudes, vec![0.0, 0.0]);
    }
}
