//! Error norms: per-component tolerance scales `atol_i + rtol_i * |x_i|` and the weighted
//! root-mean-square norm every method uses for its local error and Newton tests.

/// Relative and absolute tolerance per component.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tolerances {
    pub relative: Vec<f64>,
    pub absolute: Vec<f64>,
}

impl Tolerances {
    /// Scale of component `i` at magnitude `magnitude` (`atol_i + rtol_i * magnitude`).
    #[inline]
    pub fn scale(&self, i: usize, magnitude: f64) -> f64 {
        self.absolute[i] + self.relative[i] * magnitude
    }

    /// Fills `scale_out[i] = atol_i + rtol_i * |x_i|`.
    pub fn scales_of(&self, x: &[f64], scale_out: &mut [f64]) {
        for (i, (scale, value)) in scale_out.iter_mut().zip(x).enumerate() {
            *scale = self.scale(i, value.abs());
        }
    }

    /// Fills `scale_out[i] = atol_i + rtol_i * max(|a_i|, |b_i|)`.
    pub fn scales_of_pair(&self, a: &[f64], b: &[f64], scale_out: &mut [f64]) {
        for (i, scale) in scale_out.iter_mut().enumerate() {
            *scale = self.scale(i, a[i].abs().max(b[i].abs()));
        }
    }

    /// Smallest positive scale floor used to keep weights finite when a tolerance is zero.
    pub fn guard_zero_scales(scale: &mut [f64]) {
        for value in scale.iter_mut() {
            if value.is_nan() || *value <= f64::MIN_POSITIVE {
                *value = f64::MIN_POSITIVE;
            }
        }
    }
}

/// Vectors from this many components on are summed in [`LANES`] interleaved partial sums
/// (the loop then runs in SIMD registers: BRUSS2D's 2,048 components took a quarter of
/// its BDF's own time in these norms, one addition's latency per component); shorter
/// ones in order, as before (their rounding, and so every small model's steps, unchanged).
const INTERLEAVED_FROM: usize = 64;
/// Partial sums of a long vector's norm.
const LANES: usize = 8;

/// `sqrt(mean((v_i / scale_i)^2))`; NaN propagates (callers treat a non-finite norm as failure).
pub(crate) fn weighted_rms(values: &[f64], scale: &[f64]) -> f64 {
    root_mean(values, sum_of_squares(values, scale, None))
}

/// Like [`weighted_rms`] but only over components where `mask[i]` is true; the mean still
/// divides by the full length (as IDA's masked norm does).
pub(crate) fn weighted_rms_masked(values: &[f64], scale: &[f64], mask: &[bool]) -> f64 {
    root_mean(values, sum_of_squares(values, scale, Some(mask)))
}

fn root_mean(values: &[f64], sum: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    (sum / values.len() as f64).sqrt()
}

/// `Σ (v_i / scale_i)^2` over the components `mask` keeps (all without one): in order
/// below [`INTERLEAVED_FROM`] components, else [`interleaved_sum`].
fn sum_of_squares(values: &[f64], scale: &[f64], mask: Option<&[bool]>) -> f64 {
    if values.len() >= INTERLEAVED_FROM {
        return interleaved_sum(values, scale, mask);
    }
    values
        .iter()
        .zip(scale)
        .enumerate()
        .filter(|&(i, _)| mask.is_none_or(|mask| mask[i]))
        .map(|(_, (v, s))| {
            let ratio = v / s;
            ratio * ratio
        })
        .sum()
}

/// `Σ (v_i / scale_i)^2` over the components `mask` keeps (all without one), in [`LANES`]
/// partial sums: component `i` goes to sum `i % LANES`, the rest after the last whole
/// group to sum 0; the sums are added pairwise at the end.
#[inline(always)]
fn interleaved_sum(values: &[f64], scale: &[f64], mask: Option<&[bool]>) -> f64 {
    let mut lanes = [0.0f64; LANES];
    let groups = values.len() / LANES;
    let (values, tail_values) = values.split_at(groups * LANES);
    let (scale, tail_scale) = scale[..values.len() + tail_values.len()].split_at(groups * LANES);
    match mask {
        None => {
            for (v, s) in values.chunks_exact(LANES).zip(scale.chunks_exact(LANES)) {
                for lane in 0..LANES {
                    let ratio = v[lane] / s[lane];
                    lanes[lane] += ratio * ratio;
                }
            }
            for (v, s) in tail_values.iter().zip(tail_scale) {
                let ratio = v / s;
                lanes[0] += ratio * ratio;
            }
        }
        Some(mask) => {
            let (mask, tail_mask) = mask.split_at(groups * LANES);
            for ((v, s), keep) in values
                .chunks_exact(LANES)
                .zip(scale.chunks_exact(LANES))
                .zip(mask.chunks_exact(LANES))
            {
                for lane in 0..LANES {
                    // Computed for every component and then dropped (a select the loop
                    // vectorizes), never added: a masked NaN does not propagate.
                    let ratio = v[lane] / s[lane];
                    let square = ratio * ratio;
                    lanes[lane] += if keep[lane] { square } else { 0.0 };
                }
            }
            for ((v, s), &keep) in tail_values.iter().zip(tail_scale).zip(tail_mask) {
                if keep {
                    let ratio = v / s;
                    lanes[0] += ratio * ratio;
                }
            }
        }
    }
    let mut width = LANES;
    while width > 1 {
        width /= 2;
        for lane in 0..width {
            lanes[lane] += lanes[lane + width];
        }
    }
    lanes[0]
}

/// The (at most five) components with the largest `|v_i / scale_i|`, largest first.
pub(crate) fn worst_components(values: &[f64], scale: &[f64]) -> Vec<(usize, f64)> {
    let mut ranked: Vec<(usize, f64)> = values
        .iter()
        .zip(scale)
        .map(|(v, s)| (v / s).abs())
        .enumerate()
        .collect();
    ranked.sort_by(|a, b| {
        let key = |x: f64| if x.is_nan() { f64::INFINITY } else { x };
        key(b.1).total_cmp(&key(a.1))
    });
    ranked.truncate(5);
    ranked
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rms_of_unit_ratios_is_one() {
        assert_eq!(weighted_rms(&[2.0, -3.0], &[2.0, 3.0]), 1.0);
    }

    /// The interleaved sums of long vectors agree with the sum in order (to rounding), masked
    /// components count as zero, and a NaN still propagates.
    #[test]
    fn long_vectors_agree_with_the_sum_in_order() {
        for n in [64, 67, 200, 2048] {
            let values: Vec<f64> = (0..n)
                .map(|i| ((i * 37 % 101) as f64 - 50.0) * 1e-3)
                .collect();
            let scale: Vec<f64> = (0..n).map(|i| 1e-4 + (i % 7) as f64 * 1e-5).collect();
            let mask: Vec<bool> = (0..n).map(|i| i % 3 != 0).collect();
            let in_order = |keep: &dyn Fn(usize) -> bool| {
                let sum: f64 = (0..n)
                    .filter(|&i| keep(i))
                    .map(|i| (values[i] / scale[i]).powi(2))
                    .sum();
                (sum / n as f64).sqrt()
            };
            let plain = weighted_rms(&values, &scale);
            assert!(
                (plain - in_order(&|_| true)).abs() <= 1e-14 * plain,
                "n = {n}"
            );
            let masked = weighted_rms_masked(&values, &scale, &mask);
            assert!(
                (masked - in_order(&|i| mask[i])).abs() <= 1e-14 * masked,
                "n = {n}"
            );
            assert!(masked < plain);
            let mut with_nan = values.clone();
            with_nan[n - 1] = f64::NAN;
            assert!(weighted_rms(&with_nan, &scale).is_nan());
        }
    }

    #[test]
    fn worst_components_are_sorted() {
        let worst = worst_components(&[1.0, 10.0, f64::NAN], &[1.0, 1.0, 1.0]);
        assert_eq!(worst[0].0, 2);
        assert_eq!(worst[1], (1, 10.0));
    }
}
