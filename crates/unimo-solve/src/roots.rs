//! Zero crossings of the system's root functions `g(t, x)`, located on the dense output.
//!
//! # Contract
//! * After every accepted step (or at every output position inside it) the signs of `g` at
//!   the left end `t_left` (where the last search stopped) and the right end are compared.
//!   Component `i` crosses when `g_i(t_left) != 0` and `g_i(t_right)` is zero or has the other
//!   sign.
//! * The earliest crossing is bracketed by the Illinois variant of regula falsi (as in CVODE's
//!   `cvRootfind`), evaluating `g` on the method's dense output, until the bracket
//!   `(a, b]` is shorter than `4 eps max(|t|, 1)`. The root is reported at `b`, the end of the
//!   bracket where the sign has already changed (or `g` is exactly zero), together with every
//!   component that changes sign in the final bracket or within `64 eps max(|t|, 1)` after it
//!   (simultaneous roots, up to rounding) and its direction.
//! * A component that is exactly zero at `t_left`, and every component reported at a root
//!   (its value there is zero up to the bracket width), gets its reference sign from a probe at
//!   `t_left + 100 eps (|t_left| + |h|)` after the next step; the search then starts at the
//!   probe. So a `g` that sits at its root after an event (with or without a `reset`) and moves
//!   away is not reported again, and a `g` that stays at zero is never a crossing; it becomes
//!   active at the first point where it is nonzero.

use crate::dense_output::DenseOutput;
use crate::error::EvalError;
use crate::evaluate::roots_checked;
use crate::stats::Stats;
use crate::system::System;

/// Direction of a zero crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// `g` goes from negative to zero or positive.
    Rising,
    /// `g` goes from positive to zero or negative.
    Falling,
}

/// A located root: its time and the components crossing there.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RootFound {
    pub time: f64,
    pub components: Vec<(usize, Direction)>,
}

/// Remembers `g` at the left end of the part of the solution not yet searched.
#[derive(Debug, Clone)]
pub(crate) struct RootTracker {
    g_left: Vec<f64>,
    /// The component's reference at `t_left` is zero: take it from a probe just after.
    zero_at_left: Vec<bool>,
    g_right: Vec<f64>,
    g_middle: Vec<f64>,
    state_scratch: Vec<f64>,
    /// `g_left` and `zero_at_left` kept by [`RootTracker::save`].
    saved_left: Vec<f64>,
    saved_zero: Vec<bool>,
}

/// Bracket width at which the search stops.
pub(crate) fn root_tolerance(t: f64) -> f64 {
    4.0 * f64::EPSILON * t.abs().max(1.0)
}

/// Roots this close after the located one are reported with it (the runtime's
/// settling of relations after an event counts a function that the flow takes across
/// zero within this window as at zero).
pub fn group_window(t: f64) -> f64 {
    64.0 * f64::EPSILON * t.abs().max(1.0)
}

impl RootTracker {
    pub fn new(root_count: usize, state_len: usize) -> Self {
        RootTracker {
            g_left: vec![0.0; root_count],
            zero_at_left: vec![false; root_count],
            g_right: vec![0.0; root_count],
            g_middle: vec![0.0; root_count],
            state_scratch: vec![0.0; state_len],
            saved_left: vec![0.0; root_count],
            saved_zero: vec![false; root_count],
        }
    }

    pub fn is_empty(&self) -> bool {
        self.g_left.is_empty()
    }

    /// Starts tracking at `(t, x)`; components in `known_zero` are treated as being at their
    /// root there (they were just reported).
    pub fn restart(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &[f64],
        known_zero: &[usize],
        stats: &mut Stats,
    ) -> Result<(), EvalError> {
        if self.is_empty() {
            return Ok(());
        }
        roots_checked(system, t, x, &mut self.g_left, stats)?;
        for (flag, value) in self.zero_at_left.iter_mut().zip(&self.g_left) {
            *flag = *value == 0.0;
        }
        for &i in known_zero {
            self.zero_at_left[i] = true;
        }
        Ok(())
    }

    /// Keeps the references at the left end, so that a search can be repeated over a
    /// solution that was computed again ([`RootTracker::restore`]).
    pub fn save(&mut self) {
        self.saved_left.copy_from_slice(&self.g_left);
        self.saved_zero.copy_from_slice(&self.zero_at_left);
    }

    /// Back to the references kept by the last [`RootTracker::save`].
    pub fn restore(&mut self) {
        self.g_left.copy_from_slice(&self.saved_left);
        self.zero_at_left.copy_from_slice(&self.saved_zero);
    }

    /// Searches `(t_left, t_right]` on `dense`, which must cover it. Without a root, the
    /// tracker moves to `t_right`; with one, to the root.
    pub fn search(
        &mut self,
        system: &mut dyn System,
        dense: &dyn DenseOutput,
        t_left: f64,
        t_right: f64,
        stats: &mut Stats,
    ) -> Result<Option<RootFound>, EvalError> {
        if self.is_empty() || t_right <= t_left {
            return Ok(None);
        }
        dense.evaluate(t_right, &mut self.state_scratch);
        roots_checked(
            system,
            t_right,
            &self.state_scratch,
            &mut self.g_right,
            stats,
        )?;
        let mut t_low = t_left;
        let mut probed = true;
        if self.zero_at_left.iter().any(|z| *z) {
            let (start, end) = dense.interval();
            let t_probe = t_left + 100.0 * f64::EPSILON * (t_left.abs() + (end - start).abs());
            probed = t_probe < t_right;
            if probed {
                let mut g_probe = vec![0.0; self.g_left.len()];
                dense.evaluate(t_probe, &mut self.state_scratch);
                roots_checked(system, t_probe, &self.state_scratch, &mut g_probe, stats)?;
                // The other components may cross before the probe.
                if let Some(found) = self.locate(system, dense, t_left, t_probe, &g_probe, stats)? {
                    return Ok(Some(found));
                }
                self.g_left.copy_from_slice(&g_probe);
                for (flag, value) in self.zero_at_left.iter_mut().zip(&self.g_left) {
                    *flag = *value == 0.0;
                }
                t_low = t_probe;
            }
        }
        let g_right = std::mem::take(&mut self.g_right);
        let found = self.locate(system, dense, t_low, t_right, &g_right, stats);
        self.g_right = g_right;
        match found? {
            Some(found) => Ok(Some(found)),
            None => {
                self.move_left_to_right(probed);
                Ok(None)
            }
        }
    }

    /// Earliest crossing in `(t_low, t_high]` of the components with a nonzero reference
    /// (`g_left` at `t_low`); `None`, with the tracker unchanged, when there is none.
    fn locate(
        &mut self,
        system: &mut dyn System,
        dense: &dyn DenseOutput,
        t_low: f64,
        t_high: f64,
        g_high: &[f64],
        stats: &mut Stats,
    ) -> Result<Option<RootFound>, EvalError> {
        let active: Vec<bool> = self.zero_at_left.iter().map(|zero| !zero).collect();
        let crossing = (0..g_high.len()).any(|i| active[i] && crosses(self.g_left[i], g_high[i]));
        if !crossing {
            return Ok(None);
        }
        let mut bracket = Bracket {
            t_low,
            t_high,
            g_low: self.g_left.clone(),
            g_high: g_high.to_vec(),
            active,
        };
        let state = &mut self.state_scratch;
        bracket.illinois(
            |t, g| {
                dense.evaluate(t, state);
                roots_checked(system, t, state, g, stats)
            },
            &mut self.g_middle,
        )?;
        // Crossings within a few ulps after the root count as simultaneous.
        let t_group = (bracket.t_high + group_window(bracket.t_high)).min(t_high);
        if t_group > bracket.t_high {
            dense.evaluate(t_group, &mut self.state_scratch);
            roots_checked(
                system,
                t_group,
                &self.state_scratch,
                &mut self.g_middle,
                stats,
            )?;
        } else {
            self.g_middle.copy_from_slice(&bracket.g_high);
        }
        let components: Vec<(usize, Direction)> = (0..g_high.len())
            .filter(|&i| {
                bracket.active[i]
                    && (crosses(bracket.g_low[i], bracket.g_high[i])
                        || crosses(bracket.g_low[i], self.g_middle[i]))
            })
            .map(|i| {
                let direction = if bracket.g_low[i] > 0.0 {
                    Direction::Falling
                } else {
                    Direction::Rising
                };
                (i, direction)
            })
            .collect();
        self.g_left.copy_from_slice(&bracket.g_high);
        for (i, flag) in self.zero_at_left.iter_mut().enumerate() {
            *flag = !bracket.active[i] || bracket.g_high[i] == 0.0;
        }
        for &(i, _) in &components {
            self.zero_at_left[i] = true;
        }
        Ok(Some(RootFound {
            time: bracket.t_high,
            components,
        }))
    }

    /// No root up to `t_right`: its values become the references. Components still flagged
    /// zero keep the flag when the interval was too short to probe them.
    fn move_left_to_right(&mut self, probed: bool) {
        for i in 0..self.g_left.len() {
            if self.zero_at_left[i] && !probed {
                continue;
            }
            // A component still at zero, or leaving zero, is not a crossing; its first nonzero
            // value becomes the reference.
            self.zero_at_left[i] = self.g_right[i] == 0.0;
            self.g_left[i] = self.g_right[i];
        }
    }
}

/// `g` crosses between a nonzero `low` and `high` when `high` is zero or of the other sign.
fn crosses(low: f64, high: f64) -> bool {
    low != 0.0 && (high == 0.0 || (low > 0.0) != (high > 0.0))
}

/// A bracket `(t_low, t_high]` with `g` at both ends.
struct Bracket {
    t_low: f64,
    t_high: f64,
    g_low: Vec<f64>,
    g_high: Vec<f64>,
    /// Components taking part in the search.
    active: Vec<bool>,
}

impl Bracket {
    /// Component with the largest `|g_high / (g_high - g_low)|` among those that change sign
    /// (strictly) between `g_low` and `g`; `None` if none does.
    fn leading_sign_change(&self, g: &[f64]) -> Option<usize> {
        let g_low = &self.g_low;
        let mut best: Option<(usize, f64)> = None;
        for i in 0..g.len() {
            if self.active[i] && g_low[i] != 0.0 && g[i] != 0.0 && (g_low[i] > 0.0) != (g[i] > 0.0)
            {
                let fraction = (g[i] / (g[i] - g_low[i])).abs();
                let better = match best {
                    None => true,
                    Some((_, best_fraction)) => fraction > best_fraction,
                };
                if better {
                    best = Some((i, fraction));
                }
            }
        }
        best.map(|(i, _)| i)
    }

    /// Illinois iteration: shrinks the bracket around the earliest crossing.
    fn illinois(
        &mut self,
        mut evaluate: impl FnMut(f64, &mut [f64]) -> Result<(), EvalError>,
        g_middle: &mut [f64],
    ) -> Result<(), EvalError> {
        let Some(mut leading) = self.leading_sign_change(&self.g_high) else {
            // Only exact zeros at t_high: the root is t_high.
            return Ok(());
        };
        let tolerance = root_tolerance(self.t_high);
        let (mut side, mut previous_side) = (0u8, 255u8);
        let mut weight = 1.0;
        while (self.t_high - self.t_low).abs() > tolerance {
            weight = match (previous_side == side, side) {
                (true, 2) => weight * 2.0,
                (true, _) => weight * 0.5,
                (false, _) => 1.0,
            };
            let t_middle = self.next_guess(leading, weight, tolerance);
            evaluate(t_middle, g_middle)?;
            previous_side = side;
            let exact_zero = (0..g_middle.len())
                .any(|i| self.active[i] && self.g_low[i] != 0.0 && g_middle[i] == 0.0);
            if let Some(i) = self.leading_sign_change(g_middle) {
                leading = i;
                self.t_high = t_middle;
                self.g_high.copy_from_slice(g_middle);
                side = 1;
            } else if exact_zero {
                self.t_high = t_middle;
                self.g_high.copy_from_slice(g_middle);
                return Ok(());
            } else {
                self.t_low = t_middle;
                self.g_low.copy_from_slice(g_middle);
                side = 2;
            }
        }
        Ok(())
    }

    /// Weighted secant point, kept at least half a tolerance inside the bracket.
    fn next_guess(&self, leading: usize, weight: f64, tolerance: f64) -> f64 {
        let width = self.t_high - self.t_low;
        let g_high = self.g_high[leading];
        let g_low = self.g_low[leading];
        let mut t_middle = self.t_high - width * g_high / (g_high - weight * g_low);
        if !t_middle.is_finite() {
            t_middle = self.t_low + 0.5 * width;
        }
        let inward = |width: f64| {
            let intervals = width.abs() / tolerance;
            if intervals > 5.0 {
                0.1
            } else {
                0.5 / intervals
            }
        };
        if (t_middle - self.t_low).abs() < 0.5 * tolerance {
            t_middle = self.t_low + inward(width) * width;
        }
        if (self.t_high - t_middle).abs() < 0.5 * tolerance {
            t_middle = self.t_high - inward(width) * width;
        }
        t_middle
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_rules() {
        assert!(crosses(1.0, -1.0));
        assert!(crosses(-1.0, 0.0));
        assert!(!crosses(0.0, 1.0));
        assert!(!crosses(0.0, 0.0));
        assert!(!crosses(2.0, 1.0));
    }

    #[test]
    fn illinois_finds_cubic_root() {
        let g = |t: f64| t * t * t - 2.0;
        let mut bracket = Bracket {
            t_low: 0.0,
            t_high: 3.0,
            g_low: vec![g(0.0)],
            g_high: vec![g(3.0)],
            active: vec![true],
        };
        let mut middle = vec![0.0];
        bracket
            .illinois(
                |t, out| {
                    out[0] = g(t);
                    Ok(())
                },
                &mut middle,
            )
            .unwrap();
        let root = 2f64.cbrt();
        assert!((bracket.t_high - root).abs() <= root_tolerance(root));
        assert!(bracket.g_high[0] >= 0.0);
    }
}
