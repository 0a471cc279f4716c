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

/// `sqrt(mean((v_i / scale_i)^2))`; NaN propagates (callers treat a non-finite norm as failure).
pub(crate) fn weighted_rms(values: &[f64], scale: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let sum: f64 = values
        .iter()
        .zip(scale)
        .map(|(v, s)| {
            let ratio = v / s;
            ratio * ratio
        })
        .sum();
    (sum / values.len() as f64).sqrt()
}

/// Like [`weighted_rms`] but only over components where `mask[i]` is true; the mean still
/// divides by the full length (as IDA's masked norm does).
pub(crate) fn weighted_rms_masked(values: &[f64], scale: &[f64], mask: &[bool]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let sum: f64 = values
        .iter()
        .zip(scale)
        .zip(mask)
        .filter(|(_, keep)| **keep)
        .map(|((v, s), _)| {
            let ratio = v / s;
            ratio * ratio
        })
        .sum();
    (sum / values.len() as f64).sqrt()
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

    #[test]
    fn worst_components_are_sorted() {
        let worst = worst_components(&[1.0, 10.0, f64::NAN], &[1.0, 1.0, 1.0]);
        assert_eq!(worst[0].0, 2);
        assert_eq!(worst[1], (1, 10.0));
    }
}
