//! Zeno points below the rounding noise: a crossing whose events accumulate until its
//! function no longer leaves its noise band between them, and whose last reinit is
//! lost in that noise (a bouncing ball that falls through its floor).
//!
//! The root functions are exactly zero inside their noise band (`ROOT_NOISE` relative
//! to their operands, see `Ode::roots`), so the bounces of a ball lower than the noise
//! in its height are events of the noise, not of the flow. Once a crossing fired
//! without its function leaving twice the band since its previous event (a *quiet*
//! event) and the event reinitialized a state, the function is watched: if it next
//! leaves twice the band on the side it had crossed to (the ball below the floor, never
//! back above it), the model's motion is lost and the run stops with `SimError::Zeno`.
//! Leaving on the other side (the ball back in the air) or firing again ends the watch.
//! Quiet events that go on resolving the motion (a ball whose resting rule checks
//! `v < 0`, see `tests/extreme/RestingBall.mo`) never trip it.
//!
//! The root functions are also evaluated past a crossing (the step that overshot it,
//! the root search's brackets); those evaluations are discarded when the event is
//! placed before them, so only the motion up to each event counts.

use super::{Ode, SimError, Simulator};
use unimo_solve::Direction;

/// Root function `k` is outside twice its noise band at `t`, on the negative side or
/// not: a hit when it is watched on that side, the end of its watch on the other.
pub(super) fn outside(ode: &mut Ode<'_>, k: usize, t: f64, negative: bool) {
    ode.left_noise[k] = ode.left_noise[k].min(t);
    if let Some(side) = ode.zeno_watch[k] {
        if side == negative {
            if ode.zeno_hit.is_none_or(|(_, th)| t < th) {
                ode.zeno_hit = Some((k, t));
            }
        } else {
            ode.zeno_watch[k] = None;
        }
    }
}

impl Ode<'_> {
    /// At an event at `t`: the crossings among `components` that stayed inside their
    /// noise band since their previous event, with the direction they crossed in.
    /// Forgets what was seen after `t`, and starts the fired crossings' watches anew.
    pub(super) fn quiet_crossings(
        &mut self,
        t: f64,
        components: &[(usize, Direction)],
    ) -> Vec<(usize, Direction)> {
        let quiet = components
            .iter()
            .copied()
            .filter(|&(k, _)| self.left_noise[k] >= t)
            .collect();
        for seen in &mut self.left_noise {
            if *seen > t {
                *seen = f64::INFINITY;
            }
        }
        for &(k, _) in components {
            self.left_noise[k] = f64::INFINITY;
            self.zeno_watch[k] = None;
        }
        if self.zeno_hit.is_some_and(|(_, th)| th > t) {
            self.zeno_hit = None;
        }
        quiet
    }

    /// The event reinitialized a state: watch its quiet crossings on the side they
    /// crossed to.
    pub(super) fn watch_quiet_reinits(&mut self, quiet: &[(usize, Direction)]) {
        for &(k, dir) in quiet {
            self.zeno_watch[k] = Some(dir == Direction::Falling);
        }
    }
}

impl Simulator<'_> {
    /// The Zeno point a watched crossing revealed up to `now` (the end of the step, or
    /// the event that ended it), if any.
    pub(super) fn take_zeno(&mut self, now: f64) -> Result<(), SimError> {
        match self.ode.zeno_hit.take() {
            Some((k, time)) if time <= now => Err(SimError::Zeno {
                time,
                crossing: format!("z{k}: {}", self.m().root_names[k]),
                events: self.result.stats.events,
            }),
            _ => Ok(()),
        }
    }
}
