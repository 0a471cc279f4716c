//! Where the nonlinear loops' Newton iterations start: the solution of the latest
//! evaluation at a time not after the one being evaluated, else the trajectory's last
//! point (a continuation in time, as OpenModelica's initial guesses are taken from
//! the solutions stored by time).
//!
//! A loop with several solutions (an op-amp in positive feedback under `noEvent`, a
//! Schmitt trigger) keeps its branch through its start: Newton converges to the
//! solution nearest the start. The integrator evaluates at trial points it may throw
//! away: a predictor beyond the fold where the branch ends, a rejected step. Had the
//! next evaluation, at an earlier time, started from such a trial's solution, the
//! loop would take the other branch before its own ends (the multivibrator switched at
//! `c.v = -7.21` instead of at the fold `-7.5`). So a solution found at a later time
//! than the evaluation's is never its start; the committed point (initial values, an
//! event, an output point, the last evaluation of an accepted step) is.

use unimo_codegen::model::{CompiledModel, CompiledStep};
use unimo_codegen::tape::Reg;

/// The iteration variables of the nonlinear loops at a time.
#[derive(Debug, Clone)]
struct Point {
    time: f64,
    values: Vec<f64>,
}

/// The loops' iteration registers and the solutions their starts are taken from.
#[derive(Debug, Default)]
pub(super) struct LoopStarts {
    /// The iteration registers of the nonlinear blocks.
    regs: Vec<Reg>,
    /// The trajectory's last point; none until the first commit.
    committed: Option<Point>,
    /// The last successful evaluation (wherever the solver tried it).
    latest: Option<Point>,
    /// The start values (the guesses initialization started from).
    guesses: Option<Point>,
}

/// Which stored solution an evaluation started from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Start {
    Latest,
    Committed,
    Guesses,
}

impl LoopStarts {
    pub(super) fn new(m: &CompiledModel) -> Self {
        let regs = m
            .steps
            .iter()
            .filter_map(|s| match s {
                CompiledStep::Block(b) if !b.linear => Some(&b.iteration),
                _ => None,
            })
            .flatten()
            .copied()
            .collect();
        Self::with_registers(regs)
    }

    fn with_registers(regs: Vec<Reg>) -> Self {
        LoopStarts {
            regs,
            committed: None,
            latest: None,
            guesses: None,
        }
    }

    fn point(&self, which: Start) -> Option<&Point> {
        match which {
            Start::Latest => self.latest.as_ref(),
            Start::Committed => self.committed.as_ref(),
            Start::Guesses => self.guesses.as_ref(),
        }
    }

    /// The start for an evaluation at `time`: the latest solution when it is not later
    /// than `time` and not older than the committed point, else the committed point
    /// (else the latest, before the first commit).
    pub(super) fn choose(&self, time: f64) -> Option<Start> {
        if self.regs.is_empty() {
            return None;
        }
        match (&self.latest, &self.committed) {
            (Some(l), Some(c)) if l.time <= time && l.time >= c.time => Some(Start::Latest),
            (_, Some(_)) => Some(Start::Committed),
            (Some(_), None) => Some(Start::Latest),
            (None, None) => None,
        }
    }

    /// The starts tried, in order, after an evaluation failed from `tried`: the other
    /// stored solution (at a fold where the branch ends, the other branch may be where a
    /// trial found it), then the start values (a branch that ends where no trial went:
    /// Newton from the last point of the branch cycles between the kinks of a
    /// saturation). Starts equal to one tried before are left out.
    pub(super) fn fallbacks(&self, tried: Option<Start>) -> Vec<Start> {
        let order = match tried {
            Some(Start::Latest) => [Start::Committed, Start::Guesses],
            _ => [Start::Latest, Start::Guesses],
        };
        let mut seen: Vec<&[f64]> = tried
            .and_then(|t| self.point(t))
            .map(|p| p.values.as_slice())
            .into_iter()
            .collect();
        let mut out = Vec::new();
        for which in order {
            if let Some(p) = self.point(which) {
                if !seen.contains(&p.values.as_slice()) {
                    seen.push(&p.values);
                    out.push(which);
                }
            }
        }
        out
    }

    /// Writes the chosen solution into the registers.
    pub(super) fn write(&self, which: Start, regs: &mut [f64]) {
        if let Some(p) = self.point(which) {
            for (&r, &v) in self.regs.iter().zip(&p.values) {
                regs[r as usize] = v;
            }
        }
    }

    /// Stores the registers' values at `time` into `slot`, reusing its buffer (this
    /// runs at every evaluation of the plan: no allocation of a large model's loops).
    fn store(regs_of: &[Reg], slot: &mut Option<Point>, time: f64, regs: &[f64]) {
        if regs_of.is_empty() {
            return;
        }
        let p = slot.get_or_insert_with(|| Point {
            time,
            values: Vec::with_capacity(regs_of.len()),
        });
        p.time = time;
        p.values.clear();
        p.values.extend(regs_of.iter().map(|&r| regs[r as usize]));
    }

    fn read(&self, time: f64, regs: &[f64]) -> Option<Point> {
        let mut p = None;
        Self::store(&self.regs, &mut p, time, regs);
        p
    }

    /// Notes the registers' values after a successful evaluation at `time`.
    pub(super) fn note_latest(&mut self, time: f64, regs: &[f64]) {
        Self::store(&self.regs, &mut self.latest, time, regs);
    }

    /// The solver accepted the step the last evaluation belonged to: its solution
    /// becomes the committed point.
    pub(super) fn accept_latest(&mut self) {
        if let Some(p) = &self.latest {
            match &mut self.committed {
                Some(c) => {
                    c.time = p.time;
                    c.values.clone_from(&p.values);
                }
                None => self.committed = Some(p.clone()),
            }
        }
    }

    /// Notes the start values (the registers just after the start tape ran).
    pub(super) fn note_guesses(&mut self, regs: &[f64]) {
        self.guesses = self.read(f64::NEG_INFINITY, regs);
    }

    /// Takes the registers' values at `time` as the committed point.
    pub(super) fn commit(&mut self, time: f64, regs: &[f64]) {
        Self::store(&self.regs, &mut self.committed, time, regs);
    }
}

#[cfg(test)]
mod tests {
    use super::{LoopStarts, Start};

    /// A solution found at a later time than the evaluation's is never its start (a
    /// rejected step's trial); one at an earlier or the same time is (the corrector's
    /// iterations of one step); the committed point otherwise, and the other stored
    /// solution is the fallback.
    #[test]
    fn starts_are_never_taken_from_a_later_time() {
        let mut starts = LoopStarts::with_registers(vec![1, 3]);
        let mut regs = vec![0.0, 1.0, 0.0, 2.0];
        assert_eq!(
            starts.choose(0.0),
            None,
            "no start before anything is stored"
        );
        assert_eq!(starts.fallbacks(None), []);
        starts.commit(0.0, &regs);
        assert_eq!(starts.choose(0.0), Some(Start::Committed));
        // A trial at t = 0.5 finds the other branch...
        regs[1] = -1.0;
        regs[3] = -2.0;
        starts.note_latest(0.5, &regs);
        assert_eq!(starts.choose(0.5), Some(Start::Latest));
        assert_eq!(starts.choose(0.7), Some(Start::Latest));
        // ...and the retry at t = 0.25 starts from the committed point, with the
        // trial's solution as its fallback.
        assert_eq!(starts.choose(0.25), Some(Start::Committed));
        starts.write(Start::Committed, &mut regs);
        assert_eq!(regs, [0.0, 1.0, 0.0, 2.0]);
        assert_eq!(starts.fallbacks(Some(Start::Committed)), [Start::Latest]);
        // The accepted step's last evaluation becomes the committed point.
        regs[1] = 1.5;
        starts.note_latest(0.25, &regs);
        starts.accept_latest();
        assert_eq!(starts.choose(0.25), Some(Start::Latest));
        assert_eq!(starts.fallbacks(Some(Start::Latest)), [], "the same values");
        // The start values come last.
        starts.note_guesses(&[0.0, 0.0, 0.0, 0.0]);
        assert_eq!(starts.fallbacks(Some(Start::Latest)), [Start::Guesses]);
        // A commit at an output point before the latest evaluation's time.
        regs[1] = 9.0;
        starts.note_latest(0.4, &regs);
        starts.commit(0.3, &[0.0, 1.25, 0.0, 2.0]);
        assert_eq!(starts.choose(0.45), Some(Start::Latest));
        assert_eq!(starts.choose(0.35), Some(Start::Committed));
    }
}
