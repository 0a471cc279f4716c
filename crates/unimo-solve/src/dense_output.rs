//! Dense output: every method keeps, after each accepted step, a continuous approximation of
//! the solution on that step (Dormand–Prince's free 4th-order interpolant, the Radau IIA
//! collocation polynomial, the BDF interpolating polynomial through the history). Root
//! location and output grids evaluate it instead of interpolating linearly.

/// A continuous solution on the last accepted step `[start, end]`.
pub trait DenseOutput {
    /// `(start, end)` of the step the interpolant is valid on.
    fn interval(&self) -> (f64, f64);

    /// Writes the interpolated state at `t` into `out`. Meant for `t` within `interval()`;
    /// outside it the polynomial is extrapolated.
    fn evaluate(&self, t: f64, out: &mut [f64]);
}

/// A one-step method's interpolant at `t` on `[start, end]`: `None` at the step's end or
/// on an empty step, where the stored end state is exact; else `(t - origin) / (end - start)`.
pub(crate) fn step_fraction(start: f64, end: f64, t: f64, origin: f64) -> Option<f64> {
    let step = end - start;
    (t != end && step != 0.0).then(|| (t - origin) / step)
}
