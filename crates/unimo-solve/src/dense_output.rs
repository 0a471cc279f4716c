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
