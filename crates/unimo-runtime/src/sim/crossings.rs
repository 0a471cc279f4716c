//! Zero crossings at and between events: the outcome forced by a located crossing,
//! relations settled on the side the flow moves to (and sliding modes detected), and
//! crossings the root search could not see (a relation disagreeing with its operands).

use super::{after_crossing, Crossed, SimError, Simulator, ROOT_NOISE};
use crate::exec::EventState;
use crate::exec::Run;
use unimo_codegen::model::CompiledModel;
use unimo_dae::expr::RelOp;
use unimo_solve::{group_window, Direction, Solver};

/// What settling the relations after an event found.
pub(super) struct Settled {
    /// The flow with the settled values drives some of the crossing functions back
    /// across zero (a sliding mode: the flow points at the surface from both sides).
    pub sliding: bool,
    /// A `when` condition became true with the settled values.
    pub fires: bool,
}

/// The roots whose held relation (or rounding) disagrees with the operands in `regs`
/// (after the roots tape ran) beyond rounding noise, with the direction they crossed.
pub(super) fn disagreements(m: &CompiledModel, regs: &[f64], ev: &EventState) -> Crossed {
    let n_relations = m.root_ops.len();
    let mut out = Vec::new();
    for (k, &(a, b)) in m.roots.iter().enumerate() {
        let (a, b) = (regs[a as usize], regs[b as usize]);
        let g = a - b;
        if g.abs() <= ROOT_NOISE * a.abs().max(b.abs()).max(1.0) || g.is_nan() {
            continue;
        }
        let rising = g > 0.0;
        let missed = if k < n_relations {
            if !m.relation_held[k] {
                continue;
            }
            let held = ev.relations[k] != 0.0;
            match m.root_ops[k] {
                RelOp::Lt | RelOp::Le => held == rising,
                RelOp::Gt | RelOp::Ge => held != rising,
                RelOp::Eq | RelOp::Ne => false,
            }
        } else {
            // Held rounding: inside its interval lower root >= 0, upper root <= 0.
            let upper = (k - n_relations) % 2 == 1;
            upper == rising
        };
        if missed {
            let dir = if rising {
                Direction::Rising
            } else {
                Direction::Falling
            };
            out.push((k, dir));
        }
    }
    out
}

/// Whether a root function with value `g` (operands of size up to `size`) and slope
/// `slope` at `t` is at zero after an event: inside the noise band that
/// [`disagreements`] ignores, or within the root search's grouping window
/// ([`group_window`], 64 ulp of `t`) of its root along the flow. The two bands agree,
/// so a relation settled on the side the flow moves to is never one that disagrees
/// with its operands at the next step (the function crosses within the window, before
/// any step ends).
pub(super) fn at_zero(t: f64, g: f64, size: f64, slope: f64) -> bool {
    g.abs() <= ROOT_NOISE * size.max(1.0) + group_window(t) * slope.abs()
}

impl Simulator<'_> {
    /// The outcome of root `k` just after it crossed in `dir`, used by the first pass
    /// of the event iteration: a relation's value, or a held rounding one step up or
    /// down (its argument crossed the upper or lower bound).
    pub(super) fn force_crossing(&mut self, k: usize, dir: Direction) {
        let m = self.m();
        let n_relations = m.root_ops.len();
        if k < n_relations {
            self.ode.ev.forced[k] = after_crossing(m.root_ops[k], dir);
            return;
        }
        let held = (k - n_relations) / 2;
        let upper = (k - n_relations) % 2 == 1;
        let before = self.ode.ev.held[held];
        let after = match (upper, dir) {
            (true, Direction::Rising) => before + 1.0,
            (false, Direction::Falling) => before - 1.0,
            // Back into the interval (its value came out a rounding error outside it).
            _ => return,
        };
        self.ode.ev.held_forced[held] = Some((before, after));
    }

    /// After an event the solver does not report the crossings it just reported again,
    /// so a relation whose function is still (numerically) zero takes the value it
    /// will have just after `t`: the side `g` moves to along the flow.
    pub(super) fn settle_relations(
        &mut self,
        t: f64,
        components: &[(usize, Direction)],
    ) -> Settled {
        let m = self.m();
        let unchanged = Settled {
            sliding: false,
            fires: false,
        };
        if components.is_empty() {
            return unchanged;
        }
        let x = self.states();
        let Some(sides) = self.flow_sides(t, &x, components) else {
            return unchanged;
        };
        let mut changed = Vec::new();
        for (&(k, _), side) in components.iter().zip(sides) {
            if let Some(v) = side {
                if self.ode.ev.relations[k] != v {
                    self.ode.ev.relations[k] = v;
                    changed.push((k, v));
                }
            }
        }
        let mut sliding = false;
        if !changed.is_empty() {
            let settled: Vec<(usize, Direction)> = changed
                .iter()
                .map(|&(k, _)| (k, Direction::Rising))
                .collect();
            // The registers (the warm start of Newton blocks) as without this check.
            let registers = self.ode.regs.clone();
            if let Some(again) = self.flow_sides(t, &x, &settled) {
                sliding = changed
                    .iter()
                    .zip(again)
                    .any(|(&(_, v), side)| side.is_some_and(|w| w != v));
            }
            self.ode.regs.copy_from_slice(&registers);
            // Neither outcome holds along its own flow: a loop whose branch ended at
            // its fold (a comparator in positive feedback) has another consistent mode.
            if sliding && self.jump_mode(t, &x, &changed) {
                sliding = false;
            }
        }
        // Restore the registers to the state at t with the settled relations.
        let _ = self.load_state(t, &x);
        let mut fires = false;
        if !changed.is_empty() {
            m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
            // A `when` condition that the settled values make true fires at this event
            // (the caller runs the event iteration again); otherwise they are the
            // baseline the next edges are taken against.
            fires = m
                .conditions
                .iter()
                .any(|&c| self.ode.regs[c as usize] != 0.0 && self.cond_prev[c as usize] == 0.0);
            if !fires {
                for &c in &m.conditions {
                    self.cond_prev[c as usize] = self.ode.regs[c as usize];
                }
            }
        }
        Settled { sliding, fires }
    }

    /// A sliding relation (`changed`: each outcome drives its function back across
    /// zero) decided as Modelica's event iteration decides relations with the new
    /// continuous values: the model is evaluated in event mode just after `t` along
    /// the flow, so a Newton block searches its modes for one consistent with its own
    /// solution (the other limit of a saturated positive-feedback loop: its relations
    /// away from their roots). Kept, and true returned, when at `t` too that mode
    /// leaves none of the `changed` relations sliding; otherwise the relations and the
    /// registers are restored.
    fn jump_mode(&mut self, t: f64, x: &[f64], changed: &[(usize, f64)]) -> bool {
        let m = self.m();
        let saved = self.ode.ev.relations.clone();
        let registers = self.ode.regs.clone();
        let restore = |me: &mut Self| {
            me.ode.ev.relations.copy_from_slice(&saved);
            me.ode.regs.copy_from_slice(&registers);
        };
        if self.load_state(t, x).is_err() {
            restore(self);
            return false;
        }
        let delta = 1e-8 * t.abs().max(1.0);
        let x1: Vec<f64> = (0..x.len())
            .map(|i| {
                let dx = m
                    .derivatives
                    .get(i)
                    .map_or(0.0, |&r| self.ode.regs[r as usize]);
                x[i] + delta * dx
            })
            .collect();
        let sticky = self.ode.ev.sticky;
        self.ode.ev.event_mode = true;
        self.ode.ev.sticky = false;
        let loaded = self.load_state(t + delta, &x1).is_ok();
        self.ode.ev.event_mode = false;
        self.ode.ev.sticky = sticky;
        if !loaded || self.ode.ev.relations == saved {
            restore(self);
            return false;
        }
        let components: Vec<(usize, Direction)> = changed
            .iter()
            .map(|&(k, _)| (k, Direction::Rising))
            .collect();
        let consistent = self.flow_sides(t, x, &components).is_some_and(|sides| {
            components
                .iter()
                .zip(sides)
                .all(|(&(k, _), side)| side.is_none_or(|w| w == self.ode.ev.relations[k]))
        });
        if !consistent {
            restore(self);
            return false;
        }
        self.ode.regs.copy_from_slice(&registers);
        true
    }

    /// Per component (a relation, at its root at `(t, x)`): the value the relation
    /// takes just after `t` along the flow with the current relation values, `None`
    /// when its function does not move or the relation has no sides (`==`, `<>`).
    ///
    /// A function at zero (see [`at_zero`]) takes the side the flow moves it to; one
    /// off zero keeps the side it is on, where the flow moves it does not matter: a
    /// relation that disagrees with its operands beyond the noise is a crossing
    /// ([`disagreements`]), so holding the flow's side early would be an event again
    /// at the next step (the root search locates the crossing when the flow gets
    /// there).
    fn flow_sides(
        &mut self,
        t: f64,
        x: &[f64],
        components: &[(usize, Direction)],
    ) -> Option<Vec<Option<f64>>> {
        let m = self.m();
        let n = x.len();
        // Raw differences and their operands' size, not the differences with Newton
        // noise flushed to zero that the solver sees: a function that moves slowly off
        // its root has a slope.
        let g = |me: &mut Self, t: f64, x: &[f64]| -> Option<Vec<(f64, f64)>> {
            me.ode.load(t, x).ok()?;
            m.roots_tape.run(&mut me.ode.regs, &mut me.ode.ev);
            let regs = &me.ode.regs;
            let out = m.roots.iter().map(|&(a, b)| {
                let (a, b) = (regs[a as usize], regs[b as usize]);
                (a - b, a.abs().max(b.abs()))
            });
            Some(out.collect())
        };
        let g0 = g(self, t, x)?;
        let dx: Vec<f64> = m
            .derivatives
            .iter()
            .map(|&r| self.ode.regs[r as usize])
            .collect();
        let delta = 1e-8 * t.abs().max(1.0);
        // (A clock state, see `Ode`, has no derivative register: it stays.)
        let x1: Vec<f64> = (0..n)
            .map(|i| x[i] + delta * dx.get(i).copied().unwrap_or(0.0))
            .collect();
        let g1 = g(self, t + delta, &x1)?;
        let side = |k: usize| {
            if k >= m.root_ops.len() {
                return None;
            }
            let ((value, size), slope) = (g0[k], (g1[k].0 - g0[k].0) / delta);
            let dir = if !at_zero(t, value, size, slope) {
                // Off zero: the side it is on.
                if value > 0.0 {
                    Direction::Rising
                } else {
                    Direction::Falling
                }
            } else if slope > 0.0 {
                Direction::Rising
            } else if slope < 0.0 {
                Direction::Falling
            } else {
                return None;
            };
            after_crossing(m.root_ops[k], dir)
        };
        Some(components.iter().map(|&(k, _)| side(k)).collect())
    }

    /// Which roots disagree, beyond rounding noise, with the value their relation (or
    /// held rounding) holds, at `(t, x)`: a crossing the root search could not see
    /// (its function sat in the noise band at zero and left it on the other side).
    fn disagreeing(&mut self, t: f64, x: &[f64]) -> Result<Crossed, SimError> {
        let m = self.m();
        self.load_state(t, x)?;
        m.roots_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        Ok(disagreements(m, &self.ode.regs, &self.ode.ev))
    }

    /// A crossing in `(t_left, t_right]` that the solver did not report: a relation
    /// whose value disagrees with its operands at `t_right` (see `disagreeing`). Located
    /// by bisection on the dense output to the root tolerance; `None` when every
    /// relation agrees.
    pub(super) fn missed_crossing(
        &mut self,
        solver: &Solver,
        t_left: f64,
        t_right: f64,
    ) -> Result<Option<(f64, Crossed)>, SimError> {
        if self.m().roots.is_empty() || t_right <= t_left {
            return Ok(None);
        }
        let mut x = solver.state().to_vec();
        // The root search evaluated the functions at the step's end already.
        let mut found = match &self.ode.last_roots {
            (t, found) if *t == t_right => found.clone(),
            _ => self.disagreeing(t_right, &x)?,
        };
        if found.is_empty() {
            return Ok(None);
        }
        let (mut low, mut high) = (t_left, t_right);
        let tolerance = 4.0 * f64::EPSILON * t_right.abs().max(1.0);
        while high - low > tolerance {
            let middle = 0.5 * (low + high);
            if middle <= low || middle >= high || solver.interpolate(middle, &mut x).is_err() {
                break;
            }
            let here = self.disagreeing(middle, &x)?;
            if here.is_empty() {
                low = middle;
            } else {
                high = middle;
                found = here;
            }
        }
        // Leave the registers at the state the solver holds (the caller records from
        // them); the event itself loads its own state.
        let _ = solver.interpolate(high, &mut x);
        self.load_state(high, &x)?;
        Ok(Some((high, found)))
    }
}
