//! The run-time side of the real FFT (`unimo_dae::external_fft`): each FFT site's
//! scratch area, filled by the `FftPush` instructions of a pass, and its transform,
//! computed once per distinct input ([`unimo_dae::fft::real_fft`]). Kept in the event
//! state, so each simulation run has its own.

use unimo_dae::fft::{real_fft, RealFft, SITE_STRIDE};

/// The scratch areas and transforms of a model's FFT sites.
#[derive(Clone, Debug, Default)]
pub struct FftScratch {
    /// Input values of each site, as pushed.
    inputs: Vec<Vec<f64>>,
    /// Each site's transform, `None` when a push changed its input since.
    cache: Vec<Option<RealFft>>,
}

/// The site and position encoded in a slot (see `SITE_STRIDE`).
fn site_of(slot: f64) -> (usize, usize) {
    let site = (slot / SITE_STRIDE).floor().max(0.0);
    (site as usize, (slot - site * SITE_STRIDE).max(0.0) as usize)
}

impl FftScratch {
    /// `FftPush(slot, a, b, c)`: writes the values (a change drops the site's
    /// transform); returns the site's base.
    pub fn push(&mut self, slot: f64, values: [f64; 3]) -> f64 {
        let (site, pos) = site_of(slot);
        if self.inputs.len() <= site {
            self.inputs.resize(site + 1, Vec::new());
        }
        let area = &mut self.inputs[site];
        if area.len() < pos + 3 {
            area.resize(pos + 3, 0.0);
        }
        if area[pos..pos + 3] != values {
            area[pos..pos + 3].copy_from_slice(&values);
            if let Some(c) = self.cache.get_mut(site) {
                *c = None;
            }
        }
        site as f64 * SITE_STRIDE
    }

    /// `RealFft(kind)(base, k, n)`: amplitude (0), phase (1) or info (2) of the
    /// transform of the site's first `n` values.
    pub fn output(&mut self, base: f64, kind: u8, k: f64, n: f64) -> f64 {
        let (site, _) = site_of(base);
        let n = n.max(0.0) as usize;
        let Some(input) = self.inputs.get(site).filter(|a| a.len() >= n) else {
            return f64::NAN;
        };
        let input = &input[..n];
        if self.cache.len() <= site {
            self.cache.resize(site + 1, None);
        }
        let result = self.cache[site].get_or_insert_with(|| real_fft(input));
        let k = k.max(0.0) as usize;
        match kind {
            0 => result.amplitudes.get(k).copied().unwrap_or(f64::NAN),
            1 => result.phases.get(k).copied().unwrap_or(f64::NAN),
            _ => f64::from(result.info),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pushes_fill_the_site_and_the_transform_follows_the_input() {
        let mut s = FftScratch::default();
        let base = SITE_STRIDE;
        assert_eq!(s.push(base + 3.0, [0.0, 1.0, 0.0]), base);
        assert_eq!(s.push(base, [1.0, 0.0, -1.0]), base);
        // u = cos(pi j / 2), n = 4: X = (0, 2, 0) for k = 0..2, amplitude 2 / 3.
        assert_eq!(s.output(base, 2, 0.0, 4.0), 0.0);
        assert!((s.output(base, 0, 1.0, 4.0) - 2.0 / 3.0).abs() < 1e-15);
        assert!(s.output(base, 0, 2.0, 4.0).abs() < 1e-15);
        // A new input is transformed again.
        s.push(base, [2.0, 0.0, 2.0]);
        assert!((s.output(base, 0, 0.0, 4.0) - 4.0 / 3.0).abs() < 1e-15);
    }
}
