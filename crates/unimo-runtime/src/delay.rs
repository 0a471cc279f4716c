//! The histories of `delay` (`unimo_dae::delay`): per site, the recorded times and
//! values of the delayed expression, appended after every accepted step, at
//! initialization and before and after every event (two entries at one time: a jump
//! of the expression is delayed as a jump), and read at `time - delayTime`.
//!
//! A read between two recorded times is a cubic Hermite interpolation whose slopes at
//! the recorded points are the derivatives of the polynomial through up to five
//! neighbouring points (never across a jump): the interpolant is continuously
//! differentiable, exact for cubics, and its error is of fourth order in the spacing.
//! Before the first entry the value is the first entry's (`e(time.start)`); beyond the
//! last one (a delay shorter than the step) the last point's tangent. Without any entry
//! (during initialization) a read gives the site's guess, which the simulator
//! iterates to the initial value (`sim/delays.rs`). Entries older than `time -
//! delayMax` are dropped (the latest `delayMax` a read passed).
//!
//! Reads allocate nothing; pushes amortised (the dropped prefix is compacted when it
//! is more than half of the buffer).

/// Points on each side of the one whose slope a stencil estimates.
const STENCIL: usize = 2;
/// Multiples of a constant delay after a discontinuity where the steps end: the
/// discontinuity is smoothed by one derivative at each (a state delayed into its own
/// derivative), so past the solvers' highest order it no longer matters.
const BREAKPOINTS: usize = 5;

/// One site's history.
#[derive(Clone, Debug, Default)]
pub struct DelayLine {
    times: Vec<f64>,
    values: Vec<f64>,
    /// The first live entry (those before it were dropped).
    head: usize,
    /// The largest delay reads may ask for (the reads' `delayMax`; none before a read).
    delay_max: Option<f64>,
    /// The value reads give while the history is empty.
    guess: f64,
    /// The first entry: the value before it (kept when older entries are dropped).
    start: Option<(f64, f64)>,
    /// The delay time, when it is constant (from the reads).
    fixed: Option<f64>,
    /// Times where the recorded expression may be discontinuous (the start, events)
    /// whose consequences a constant delay has not yet moved past the last entry.
    marks: Vec<f64>,
}

impl DelayLine {
    fn len(&self) -> usize {
        self.times.len()
    }

    /// Appends `(t, v)`. A repeated point is not stored again; a point before the last
    /// drops the entries after it (a run taken back).
    pub fn push(&mut self, t: f64, v: f64) {
        while self.len() > self.head && self.times[self.len() - 1] > t {
            self.times.pop();
            self.values.pop();
        }
        if let (Some(&lt), Some(&lv)) = (self.times.last(), self.values.last()) {
            if lt == t && (lv == v || (lv.is_nan() && v.is_nan())) {
                return;
            }
        }
        // Reads may still come from anywhere after the previous entry (the output
        // points inside the step just accepted).
        let previous = self.times.last().copied().unwrap_or(t);
        self.start.get_or_insert((t, v));
        self.times.push(t);
        self.values.push(v);
        self.drop_old(previous);
    }

    /// Drops the entries no read from `t` on can reach (older than `t - delayMax`,
    /// keeping the stencil's points before it).
    fn drop_old(&mut self, t: f64) {
        let Some(dmax) = self.delay_max.filter(|d| d.is_finite()) else {
            return;
        };
        let cutoff = t - dmax;
        let keep = 2 * STENCIL + 1;
        while self.head + keep < self.len() && self.times[self.head + keep] < cutoff {
            self.head += 1;
        }
        if self.head > 64 && 2 * self.head > self.len() {
            self.times.drain(..self.head);
            self.values.drain(..self.head);
            self.head = 0;
        }
    }

    /// Ends a piece of the history at its last entry (a restart or event at `t`, where
    /// the expression's derivatives may jump): the entry is repeated, and no slope
    /// stencil reaches across it.
    pub fn split(&mut self, t: f64) {
        if let (Some(&lt), Some(&lv)) = (self.times.last(), self.values.last()) {
            let n = self.len();
            let split = n >= 2 && self.times[n - 2] == lt;
            if lt == t && !split {
                self.times.push(t);
                self.values.push(lv);
            }
        }
    }

    /// Inserts `(t, v)` among the entries (a point inside the last step).
    pub fn insert(&mut self, t: f64, v: f64) {
        let i = self.head + self.times[self.head..].partition_point(|&x| x <= t);
        if i > self.head && self.times[i - 1] == t {
            return;
        }
        self.times.insert(i, t);
        self.values.insert(i, v);
    }

    /// The value at `at` (`slope`: its derivative with respect to `at`); `bounds` are
    /// the read's `delayMax` and constant delay time (NaN: it varies).
    pub fn read(&mut self, at: f64, bounds: [f64; 2], slope: bool) -> f64 {
        let [delay_max, fixed] = bounds;
        if self.delay_max != Some(delay_max) && delay_max.is_finite() {
            self.delay_max = Some(delay_max.max(0.0));
        }
        if fixed.is_finite() && fixed > 0.0 && self.fixed != Some(fixed) {
            self.fixed = Some(fixed);
        }
        self.value(at, slope)
    }

    /// Notes a possible discontinuity of the expression at `t` (the start, an event);
    /// forgets those whose consequences lie before `t`.
    pub fn mark(&mut self, t: f64) {
        let reach = self.fixed.map_or(0.0, |d| BREAKPOINTS as f64 * d);
        self.marks.retain(|&m| m + reach >= t && m != t);
        self.marks.push(t);
    }

    /// The first time after `t` where the constant delay moves a marked
    /// discontinuity (up to [`BREAKPOINTS`] delays after it); infinite without.
    fn next_breakpoint(&self, t: f64) -> f64 {
        let Some(d) = self.fixed else {
            return f64::INFINITY;
        };
        let after = t + 1e-12 * t.abs().max(d);
        let mut next = f64::INFINITY;
        for &m in &self.marks {
            let k = ((after - m) / d).floor().max(0.0) + 1.0;
            let mut b = m + k * d;
            if b <= after {
                b += d;
            }
            if b <= m + BREAKPOINTS as f64 * d * (1.0 + 1e-12) {
                next = next.min(b);
            }
        }
        next
    }

    /// [`DelayLine::read`] without a `delayMax`.
    pub fn value(&self, at: f64, slope: bool) -> f64 {
        let n = self.len();
        if n == self.head {
            return if slope { 0.0 } else { self.guess };
        }
        let (t, v) = (&self.times, &self.values);
        if at.is_nan() {
            return f64::NAN;
        }
        if at < t[self.head] {
            // Before the start: the start value; else older than `delayMax` (clamped).
            let before = match self.start {
                Some((t0, v0)) if at < t0 => v0,
                _ => v[self.head],
            };
            return if slope { 0.0 } else { before };
        }
        let last = n - 1;
        if at >= t[last] {
            let d = self.slope_at(last);
            return if slope {
                d
            } else {
                v[last] + (at - t[last]) * d
            };
        }
        // The segment [t[i], t[i + 1]) holding `at`: t[i] <= at < t[i + 1].
        let i = self.head + t[self.head..].partition_point(|&x| x <= at) - 1;
        let (t0, t1) = (t[i], t[i + 1]);
        let h = t1 - t0;
        let s = (at - t0) / h;
        let (d0, d1) = (self.slope_at(i) * h, self.slope_at(i + 1) * h);
        let (y0, y1) = (v[i], v[i + 1]);
        if slope {
            // Derivatives of the Hermite basis with respect to s, divided by h.
            let h00 = 6.0 * s * s - 6.0 * s;
            let h10 = 3.0 * s * s - 4.0 * s + 1.0;
            let h11 = 3.0 * s * s - 2.0 * s;
            (h00 * (y0 - y1) + h10 * d0 + h11 * d1) / h
        } else {
            let s2 = s * s;
            let s3 = s2 * s;
            let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
            let h10 = s3 - 2.0 * s2 + s;
            let h01 = -2.0 * s3 + 3.0 * s2;
            let h11 = s3 - s2;
            h00 * y0 + h10 * d0 + h01 * y1 + h11 * d1
        }
    }

    /// The slope at entry `j`: the derivative at `t[j]` of the polynomial through up
    /// to `2 STENCIL + 1` entries around it with increasing times (none across a jump).
    fn slope_at(&self, j: usize) -> f64 {
        let t = &self.times;
        let (mut lo, mut hi) = (j, j);
        let width = 2 * STENCIL;
        while lo > self.head && j - lo < width && t[lo - 1] < t[lo] {
            lo -= 1;
        }
        while hi + 1 < self.len() && hi - j < width && t[hi + 1] > t[hi] {
            hi += 1;
        }
        if hi == lo {
            return 0.0;
        }
        let points = (hi - lo + 1).min(width + 1);
        let start = j.saturating_sub(STENCIL).clamp(lo, hi + 1 - points);
        lagrange_slope(
            &t[start..start + points],
            &self.values[start..start + points],
            j - start,
        )
    }
}

/// The derivative at `x[k]` of the polynomial through `(x, y)` (distinct `x`).
fn lagrange_slope(x: &[f64], y: &[f64], k: usize) -> f64 {
    let xk = x[k];
    let mut sum = 0.0;
    for j in 0..x.len() {
        if j == k {
            let own: f64 = (0..x.len())
                .filter(|&m| m != k)
                .map(|m| 1.0 / (xk - x[m]))
                .sum();
            sum += y[k] * own;
        } else {
            let mut w = 1.0 / (x[j] - xk);
            for m in (0..x.len()).filter(|&m| m != k && m != j) {
                w *= (xk - x[m]) / (x[j] - x[m]);
            }
            sum += y[j] * w;
        }
    }
    sum
}

/// Every site's history.
#[derive(Clone, Debug, Default)]
pub struct Delays {
    pub lines: Vec<DelayLine>,
    /// The simulator's scratch space: registers saved while the history is refined,
    /// and interpolated states.
    pub(crate) saved: Vec<f64>,
    pub(crate) states: Vec<f64>,
}

impl Delays {
    /// `n` empty histories.
    pub fn new(n: usize) -> Delays {
        Delays {
            lines: vec![DelayLine::default(); n],
            ..Delays::default()
        }
    }

    /// Site `site`'s value (or slope) at `at` (`bounds`: see [`DelayLine::read`]);
    /// NaN for a site that does not exist.
    #[inline]
    pub fn read(&mut self, site: f64, bounds: [f64; 2], at: f64, slope: bool) -> f64 {
        match self.lines.get_mut(site as usize) {
            Some(line) if site >= 0.0 => line.read(at, bounds, slope),
            _ => f64::NAN,
        }
    }

    /// Notes a possible discontinuity of every site's expression at `t`.
    pub fn mark(&mut self, t: f64) {
        for line in &mut self.lines {
            line.mark(t);
        }
    }

    /// Ends every history's piece at its last entry at `t` ([`DelayLine::split`]).
    pub fn split(&mut self, t: f64) {
        for line in &mut self.lines {
            line.split(t);
        }
    }

    /// The first time after `t` where a constant delay moves a discontinuity.
    pub fn next_breakpoint(&self, t: f64) -> f64 {
        self.lines
            .iter()
            .map(|l| l.next_breakpoint(t))
            .fold(f64::INFINITY, f64::min)
    }

    /// Appends the values `v` (one per site) at `t`.
    pub fn push(&mut self, t: f64, v: impl Iterator<Item = f64>) {
        for (line, v) in self.lines.iter_mut().zip(v) {
            line.push(t, v);
        }
    }

    /// Forgets every history; reads give `guesses` (one per site) until the next push.
    pub fn restart(&mut self, guesses: impl Iterator<Item = f64>) {
        for (line, g) in self.lines.iter_mut().zip(guesses) {
            *line = DelayLine {
                guess: g,
                ..DelayLine::default()
            };
        }
    }

    /// The reads' guesses (one per site).
    pub fn guesses(&self) -> impl Iterator<Item = f64> + '_ {
        self.lines.iter().map(|l| l.guess)
    }

    /// The smallest constant delay (infinite without one): the largest step that
    /// never reads beyond the last accepted point.
    pub fn smallest_constant_delay(&self) -> f64 {
        self.lines
            .iter()
            .filter_map(|l| l.fixed)
            .fold(f64::INFINITY, f64::min)
    }

    /// Entries held, over all sites.
    pub fn entries(&self) -> usize {
        self.lines.iter().map(|l| l.len() - l.head).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(f: impl Fn(f64) -> f64, times: &[f64]) -> DelayLine {
        let mut l = DelayLine::default();
        for &t in times {
            l.push(t, f(t));
        }
        l
    }

    #[test]
    fn cubics_are_exact_and_the_error_is_fourth_order() {
        let cubic = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t - 0.3 * t * t * t;
        let times: Vec<f64> = (0..20)
            .map(|k| 0.1 * k as f64 + 0.01 * (k % 3) as f64)
            .collect();
        let mut l = line(cubic, &times);
        for k in 0..100 {
            let at = 0.019 * k as f64;
            assert!(
                (l.read(at, [f64::INFINITY, f64::NAN], false) - cubic(at)).abs() < 1e-12,
                "{at}"
            );
        }
        // sin on a grid of h and h/2: the error falls by about 16.
        let err = |h: f64| {
            let times: Vec<f64> = (0..(4.0 / h) as usize).map(|k| k as f64 * h).collect();
            let mut l = line(f64::sin, &times);
            (0..300)
                .map(|k| 0.5 + 0.01 * k as f64)
                .map(|at| (l.read(at, [f64::INFINITY, f64::NAN], false) - at.sin()).abs())
                .fold(0.0, f64::max)
        };
        let ratio = err(0.1) / err(0.05);
        assert!(ratio > 12.0 && ratio < 40.0, "ratio {ratio}");
        assert!(err(0.05) < 1e-6);
    }

    #[test]
    fn before_the_start_beyond_the_end_and_at_a_jump() {
        let mut l = DelayLine::default();
        assert_eq!(l.read(0.0, [1.0, 1.0], false), 0.0);
        for k in 0..=10 {
            l.push(0.1 * k as f64, 0.0);
        }
        l.push(1.0, 1.0);
        for k in 11..=20 {
            l.push(0.1 * k as f64, 1.0);
        }
        assert_eq!(l.read(-5.0, [1.0, 1.0], false), 0.0);
        assert_eq!(l.read(0.95, [1.0, 1.0], false), 0.0);
        assert_eq!(l.read(1.0, [1.0, 1.0], false), 1.0);
        assert_eq!(l.read(1.05, [1.0, 1.0], false), 1.0);
        assert_eq!(l.read(3.0, [1.0, 1.0], false), 1.0);
        // A repeated point is stored once.
        let n = l.len();
        l.push(2.0, 1.0);
        assert_eq!(l.len(), n);
    }

    #[test]
    fn breakpoints_follow_marks_and_splits_bound_the_stencils() {
        let mut l = DelayLine::default();
        l.read(0.0, [1.0, 0.4], false);
        l.push(0.0, 0.0);
        l.mark(0.0);
        let next = |l: &DelayLine, t: f64| l.next_breakpoint(t);
        assert_eq!(next(&l, 0.0), 0.4);
        assert!((next(&l, 0.4) - 0.8).abs() < 1e-15);
        assert!((next(&l, 1.95) - 2.0).abs() < 1e-15);
        assert!(next(&l, 2.05).is_infinite());
        l.mark(1.0);
        assert!((next(&l, 1.1) - 1.2).abs() < 1e-15);
        // |t| on both sides of a split at 0: the slopes see no kink.
        let mut l = line(|t: f64| t.abs(), &[-0.3, -0.2, -0.1, 0.0]);
        l.split(0.0);
        for t in [0.1, 0.2, 0.3] {
            l.push(t, t);
        }
        assert!((l.value(-0.05, false) - 0.05).abs() < 1e-15);
        assert!((l.value(0.05, false) - 0.05).abs() < 1e-15);
    }

    #[test]
    fn old_entries_are_dropped() {
        let mut l = DelayLine::default();
        l.read(0.0, [0.5, 0.5], false);
        for k in 0..100_000 {
            l.push(0.001 * k as f64, k as f64);
        }
        assert!(l.len() - l.head < 520, "{} entries", l.len() - l.head);
        assert!(l.times.len() < 1200);
        let at = 99.999 - 0.5;
        assert!((l.read(at, [0.5, 0.5], false) - at * 1000.0).abs() < 1e-6);
    }
}
