//! Rows between the output grid's points where a straight line between the written
//! rows would misstate the solution: the states of the steps not written since the last
//! row must lie within the output tolerance of the chord from that row to the next
//! point, and when the next point would break that, the last step that kept it is
//! written. Readers that interpolate the result linearly (plots, comparisons with
//! references on another grid) then see the states to that tolerance at the steps; a
//! smooth solution on a fine grid gets no extra rows.
//!
//! The test is the swing-door one: per state, the slopes from the last row that keep
//! every pending step within its tolerance form an interval, narrowed at each step, so
//! a step costs one pass over the states however many steps are pending.

/// The chord test of the rows written so far (one per simulation).
#[derive(Clone, Debug, Default)]
pub(super) struct Refine {
    /// Relative output tolerance (of each state's largest magnitude so far); 0: off.
    rtol: f64,
    /// Absolute floor of the tolerance.
    atol: f64,
    /// Time and states of the last row written.
    anchor: Option<(f64, Vec<f64>)>,
    /// The last accepted step since the last row, not written.
    pending: Option<(f64, Vec<f64>)>,
    /// Per state, the slopes from the anchor that keep every pending step within its
    /// tolerance: (lowest, highest).
    slopes: Vec<(f64, f64)>,
    /// Each state's largest magnitude so far.
    scale: Vec<f64>,
    /// Scratch for the states at a step's end or at a row (reused: no allocation per
    /// step); taken out while in use (`take_scratch`, `put_scratch`).
    scratch: Vec<f64>,
}

impl Refine {
    /// The scratch vector, emptied, for the caller to fill and give back.
    pub(super) fn take_scratch(&mut self) -> Vec<f64> {
        let mut x = std::mem::take(&mut self.scratch);
        x.clear();
        x
    }

    pub(super) fn put_scratch(&mut self, x: Vec<f64>) {
        self.scratch = x;
    }

    pub(super) fn new(rtol: f64, atol: f64) -> Refine {
        Refine {
            rtol,
            atol,
            ..Refine::default()
        }
    }

    pub(super) fn enabled(&self) -> bool {
        self.rtol > 0.0
    }

    /// A row was written at `t` with states `x`: it is the new anchor.
    pub(super) fn written(&mut self, t: f64, x: &[f64]) {
        if !self.enabled() {
            return;
        }
        self.widen(x);
        self.pending = None;
        self.slopes.clear();
        self.slopes
            .resize(x.len(), (f64::NEG_INFINITY, f64::INFINITY));
        match &mut self.anchor {
            Some((ta, xa)) if xa.len() == x.len() => {
                *ta = t;
                xa.copy_from_slice(x);
            }
            _ => self.anchor = Some((t, x.to_vec())),
        }
    }

    fn widen(&mut self, x: &[f64]) {
        if self.scale.len() != x.len() {
            self.scale = vec![0.0; x.len()];
        }
        for (s, v) in self.scale.iter_mut().zip(x) {
            *s = s.max(v.abs());
        }
    }

    /// Whether the chord from the anchor to `(t, x)` keeps every pending step within
    /// the tolerance.
    fn chord_holds(&self, t: f64, x: &[f64]) -> bool {
        let Some((ta, xa)) = &self.anchor else {
            return true;
        };
        let span = t - ta;
        if span <= 0.0 || xa.len() != x.len() {
            return true;
        }
        x.iter()
            .zip(xa)
            .zip(&self.slopes)
            .all(|((&v, &a), &(lo, hi))| {
                let slope = (v - a) / span;
                lo <= slope && slope <= hi
            })
    }

    /// Before a row at `(t, x)` or the end of a step there: the pending step that must
    /// be written first (the last one, which the chord from the anchor still
    /// represented with all before it), if the chord to `(t, x)` would not hold.
    pub(super) fn needed_before(&mut self, t: f64, x: &[f64]) -> Option<(f64, Vec<f64>)> {
        if !self.enabled() || self.pending.is_none() {
            return None;
        }
        self.widen(x);
        if self.chord_holds(t, x) {
            return None;
        }
        self.pending.take()
    }

    /// An accepted step ended at `(t, x)` without a row there.
    pub(super) fn step_ended(&mut self, t: f64, x: &[f64]) {
        if !self.enabled() {
            return;
        }
        self.widen(x);
        let Some((ta, xa)) = &self.anchor else {
            return;
        };
        let span = t - ta;
        if span <= 0.0 || xa.len() != x.len() {
            return;
        }
        for (i, (lo, hi)) in self.slopes.iter_mut().enumerate() {
            let tol = self.rtol * self.scale[i] + self.atol;
            *lo = lo.max((x[i] - tol - xa[i]) / span);
            *hi = hi.min((x[i] + tol - xa[i]) / span);
        }
        match &mut self.pending {
            Some((tp, xp)) => {
                *tp = t;
                xp.copy_from_slice(x);
            }
            None => self.pending = Some((t, x.to_vec())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Refine;

    /// Steps along x = t^2 from an anchor at 0: the chord to t = 1 misses t = 0.5 by
    /// 0.25, beyond a tolerance of 0.1 of the scale 1, so t = 0.5 must be written.
    #[test]
    fn a_step_the_chord_misses_is_written_and_one_it_keeps_is_not() {
        let mut r = Refine::new(0.1, 0.0);
        r.written(0.0, &[0.0]);
        r.step_ended(0.5, &[0.25]);
        assert_eq!(r.needed_before(1.0, &[1.0]), Some((0.5, vec![0.25])));
        // A straight line: nothing to write.
        let mut r = Refine::new(0.1, 0.0);
        r.written(0.0, &[0.0]);
        r.step_ended(0.5, &[0.5]);
        assert_eq!(r.needed_before(1.0, &[1.0]), None);
        // Off: never.
        let mut r = Refine::new(0.0, 0.0);
        r.written(0.0, &[0.0]);
        r.step_ended(0.5, &[0.25]);
        assert_eq!(r.needed_before(1.0, &[1.0]), None);
    }
}
