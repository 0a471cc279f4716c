//! Events: Modelica's event iteration (`when` branches fired against their previous
//! conditions, `reinit` at the end of each step), and the state, sample and terminal
//! events of a run with their chattering checks.

use super::{
    output_names, EventRecord, SimError, Simulator, CHATTER_COUNT, CHATTER_WINDOW,
    MAX_EVENT_ITERATIONS,
};
use crate::exec::Run;
use unimo_codegen::model::Action;
use unimo_solve::{Direction, Solver};

impl Simulator<'_> {
    /// Modelica's event iteration at `t`: evaluate with `pre` values, fire `when`
    /// branches whose condition became true, repeat until no discrete value changes;
    /// then apply `reinit`s.
    pub(super) fn event_iteration(&mut self, t: f64, initial: bool) -> Result<(), SimError> {
        let m = self.m();
        let layout = m.layout;
        self.ode.regs[layout.time as usize] = t;
        self.ode.ev.event_mode = true;
        self.ode.ev.sticky = !initial;
        self.reinit_buffer.clear();
        let mut iterations = 0;
        loop {
            iterations += 1;
            self.result.stats.event_iterations += 1;
            // pre := current, for every variable.
            for s in 0..layout.n_scalars {
                self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
            }
            let fired = self.fire_whens(t)?;
            let assigned = self.apply_fired(t, &fired)?;
            for &c in &m.conditions {
                self.cond_prev[c as usize] = self.ode.regs[c as usize];
            }
            let changed = self.changed_discretes(assigned);
            // Relations forced by the located crossing hold only for the first pass.
            for f in self.ode.ev.forced.iter_mut() {
                *f = None;
            }
            // reinit at the end of this event iteration step (MLS 8.3.6), then another
            // step: what the new state values change (a condition that becomes true, e.g.
            // an `elsewhen`; discrete variables defined by equations) happens at this
            // event, instead of being recorded as the new `pre` without firing.
            let reinits = std::mem::take(&mut self.reinit_buffer);
            let reinitialized = !reinits.is_empty();
            for (target, v) in reinits {
                self.ode.regs[target as usize] = v;
            }
            if changed.is_empty() && !reinitialized {
                break;
            }
            if iterations >= MAX_EVENT_ITERATIONS {
                let culprits = output_names(m, &changed);
                return Err(SimError::EventIteration { time: t, culprits });
            }
        }
        for s in 0..layout.n_scalars {
            self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
        }
        self.ode.ev.event_mode = false;
        self.ode.ev.sticky = false;
        // A rounding whose bound was crossed keeps its new value through every pass of
        // the event (its argument may sit a rounding error before the bound).
        for f in self.ode.ev.held_forced.iter_mut() {
            *f = None;
        }
        Ok(())
    }

    /// One step of the event iteration: which `when` branches fire (per branch, in
    /// declaration order).
    ///
    /// The assignments of the `when` branches that fire belong to this step like any
    /// equation: the system is evaluated again with them until they agree, so what
    /// depends on a `when`-assigned variable sees its new value before other `when`
    /// conditions are decided (e.g. a mask closed at a lift-off must block the impact
    /// test at the same instant). A branch fires at most once per step (its condition
    /// became true against the previous step), as a `when`-statement executes once per
    /// evaluation of its algorithm; several clauses may assign the same variable, the
    /// later one in declaration order wins within the step, and a clause that becomes
    /// true because of another's assignment fires in this same step.
    fn fire_whens(&mut self, t: f64) -> Result<Vec<bool>, SimError> {
        let m = self.m();
        let n_branches: usize = m.whens.iter().map(|w| w.branches.len()).sum();
        let mut fired = vec![false; n_branches];
        let mut settled = false;
        let mut unsettled: Vec<u32> = Vec::new();
        let mut pending: Vec<(u32, f64)> = Vec::new();
        // Where a target's value sits in `pending` (checked against the entry: stale
        // positions from an earlier pass point elsewhere), so that a branch assigning
        // thousands of variables (an FFT buffer) is not quadratic.
        let mut slots: Vec<u32> = vec![u32::MAX; self.ode.regs.len()];
        for _ in 0..MAX_EVENT_ITERATIONS {
            self.eval_plan()?;
            m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
            unsettled.clear();
            let mut any = self.when_pass(&mut fired, &mut pending, &mut slots);
            for (target, v) in pending.drain(..) {
                if self.ode.regs[target as usize] != v {
                    self.ode.regs[target as usize] = v;
                    unsettled.push(target);
                    any = true;
                }
            }
            if !any {
                settled = true;
                break;
            }
        }
        if !settled {
            let culprits = output_names(m, &unsettled);
            return Err(SimError::EventIteration { time: t, culprits });
        }
        Ok(fired)
    }

    /// One pass over the `when` clauses: marks the branches that fire now in `fired`
    /// and collects the assignments of every fired branch in `pending`. Returns
    /// whether a branch fired in this pass.
    fn when_pass(
        &mut self,
        fired: &mut [bool],
        pending: &mut Vec<(u32, f64)>,
        slots: &mut [u32],
    ) -> bool {
        let m = self.m();
        let mut any = false;
        let mut b = 0;
        for w in &m.whens {
            let first = b;
            b += w.branches.len();
            for (k, (conds, actions)) in w.branches.iter().enumerate() {
                let active = conds.iter().any(|&c| self.ode.regs[c as usize] != 0.0);
                let fires = !fired[first + k]
                    && conds.iter().any(|&c| {
                        self.ode.regs[c as usize] != 0.0 && self.cond_prev[c as usize] == 0.0
                    });
                // Every branch fired in this step is applied again in each
                // pass, in declaration order (the later one wins a variable
                // several assign): its equations hold at the instant with the
                // values the other branches assigned since (`r = f(r_raw)`
                // beside `r_raw = random(pre(state))`, whichever comes first).
                if fires || fired[first + k] {
                    fired[first + k] = true;
                    any |= fires;
                    for a in actions {
                        if let Action::Assign { target, value } = a {
                            let v = self.ode.regs[*value as usize];
                            let slot = &mut slots[*target as usize];
                            match pending.get_mut(*slot as usize) {
                                Some(p) if p.0 == *target => p.1 = v,
                                _ => {
                                    *slot = pending.len() as u32;
                                    pending.push((*target, v));
                                }
                            }
                        }
                    }
                }
                // elsewhen: later branches only when this one is not active.
                if active || fired[first + k] {
                    break;
                }
            }
        }
        any
    }

    /// The actions of the fired branches: `reinit`s buffered, `terminate` noted,
    /// assertions checked. Returns the variables the fired branches assign.
    fn apply_fired(&mut self, t: f64, fired: &[bool]) -> Result<Vec<u32>, SimError> {
        let m = self.m();
        let mut assigned: Vec<u32> = Vec::new();
        let mut b = 0;
        for w in &m.whens {
            for (_, actions) in &w.branches {
                if fired[b] {
                    for a in actions {
                        match a {
                            Action::Assign { target, .. } => assigned.push(*target),
                            Action::Reinit { target, value } => self
                                .reinit_buffer
                                .push((*target, self.ode.regs[*value as usize])),
                            Action::Terminate(msg) => self.terminate = Some(msg.clone()),
                            Action::Assert { condition, message } => {
                                if self.ode.regs[*condition as usize] == 0.0 {
                                    return Err(SimError::Assert {
                                        time: t,
                                        message: message.clone(),
                                    });
                                }
                            }
                        }
                    }
                }
                b += 1;
            }
        }
        Ok(assigned)
    }

    /// The variables that differ from their `pre` values: those `assigned` by `when`
    /// branches, then the discrete variables defined by equations.
    fn changed_discretes(&self, assigned: Vec<u32>) -> Vec<u32> {
        let m = self.m();
        let layout = m.layout;
        let mut changed = Vec::new();
        for target in assigned {
            let pre = self.ode.regs[(layout.pre_base + target) as usize];
            if self.ode.regs[target as usize] != pre && !changed.contains(&target) {
                changed.push(target);
            }
        }
        // Discrete variables defined by equations (not `when`) changed too?
        for &d in &m.discretes {
            let pre = self.ode.regs[(layout.pre_base + d) as usize];
            if self.ode.regs[d as usize] != pre && !changed.contains(&d) {
                changed.push(d);
            }
        }
        changed
    }

    /// At the end of a successful run of a model that reads `terminal()`: one more
    /// event at the stop time with `terminal()` true (its `when terminal()` clauses
    /// fire), recorded as the last row.
    pub(super) fn terminal_event(&mut self, t: f64) -> Result<(), SimError> {
        let m = self.m();
        if !m.uses_terminal {
            return Ok(());
        }
        self.ode.regs[m.layout.terminal as usize] = 1.0;
        self.event_iteration(t, false)?;
        self.record(t);
        Ok(())
    }
    pub(super) fn check_assertions(&mut self, t: f64) -> Result<(), SimError> {
        let m = self.m();
        if m.assertions.is_empty() {
            return Ok(());
        }
        // After a native right-hand side the registers hold its point but not the
        // plan's values there.
        self.ode
            .refresh()
            .map_err(|failure| SimError::Block { time: t, failure })?;
        m.assert_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for (r, msg, warning) in &m.assertions {
            if self.ode.regs[*r as usize] == 0.0 && !warning {
                return Err(SimError::Assert {
                    time: t,
                    message: msg.clone(),
                });
            }
        }
        Ok(())
    }

    pub(super) fn state_event(
        &mut self,
        t: f64,
        x: &[f64],
        components: &[(usize, Direction)],
        mut solver: Option<&mut Solver>,
    ) -> Result<(), SimError> {
        // The event starts from the state at the crossing on the active invariants
        // (an interpolated state is off them by the interpolant's error).
        let mut x = x.to_vec();
        self.project(solver.as_deref_mut(), t, &mut x)?;
        self.load_state(t, &x)?;
        self.record(t);
        let quiet = self.ode.quiet_crossings(t, components);
        for &(k, dir) in components {
            self.force_crossing(k, dir);
        }
        let what = components
            .iter()
            .map(|&(k, d)| {
                format!(
                    "z{k} {}",
                    if d == Direction::Rising {
                        "rising"
                    } else {
                        "falling"
                    }
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        let first = components.first().map(|c| c.0);
        self.after_event(t, what, first, solver.as_deref_mut())?;
        if self.states() != x {
            self.ode.watch_quiet_reinits(&quiet);
        }
        let mut settled = self.settle_relations(t, components);
        if settled.fires {
            // The relations just after t make a `when` condition true: it fires now.
            let what = "settled relations".to_string();
            self.after_event(t, what, first, solver)?;
            settled = self.settle_relations(t, components);
            if settled.fires {
                // Keep the baseline consistent; the next crossing decides.
                let m = self.m();
                for &c in &m.conditions {
                    self.cond_prev[c as usize] = self.ode.regs[c as usize];
                }
            }
        }
        if settled.sliding {
            self.sliding_events += 1;
        } else {
            self.sliding_events = 0;
        }
        if self.sliding_events >= CHATTER_COUNT {
            let k = components[0].0;
            return Err(SimError::Chattering {
                time: t,
                crossing: format!("z{k}: {}", self.m().root_names[k]),
                events: self.sliding_events,
                sliding: true,
            });
        }
        Ok(())
    }

    pub(super) fn sample_event(
        &mut self,
        t: f64,
        solver: Option<&mut Solver>,
    ) -> Result<(), SimError> {
        let m = self.m();
        let mut due = Vec::new();
        for (k, next) in self.sample_next.iter_mut().enumerate() {
            if *next <= t * (1.0 + 1e-15) + 1e-300 {
                due.push(k);
                // Instant n is start + n * interval (no accumulated rounding).
                let start = self.ode.regs[m.samples[k].0 as usize];
                let interval = self.ode.regs[m.samples[k].1 as usize];
                let n = ((t - start) / interval).round() + 1.0;
                *next = start + n * interval;
            }
        }
        self.record(t);
        for &k in &due {
            self.ode.ev.samples[k] = 1.0;
        }
        let r = self.after_event(t, format!("sample {due:?}"), None, solver);
        for s in self.ode.ev.samples.iter_mut() {
            *s = 0.0;
        }
        // The sample conditions are false again right after the instant, and so is a
        // discrete variable the plan computes from them (`trig = sample(0, 0.1)`): its
        // value between the instants is the left limit `pre(trig)` at the next one.
        // Record that, so the next instant is an edge of `when trig`.
        if r.is_ok() && self.eval_plan().is_ok() {
            let pre_base = m.layout.pre_base;
            for &d in &m.discretes {
                self.ode.regs[(pre_base + d) as usize] = self.ode.regs[d as usize];
            }
        }
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        r
    }

    pub(super) fn after_event(
        &mut self,
        t: f64,
        what: String,
        crossing: Option<usize>,
        mut solver: Option<&mut Solver>,
    ) -> Result<(), SimError> {
        self.record_delays(t);
        if let Err(e) = self.event_iteration(t, false) {
            return Err(self.assertion_first(t, e));
        }
        // The invariants active after the event (e.g. a contact that just began) hold
        // from its end on.
        let mut x = self.states();
        if self.project(solver.as_deref_mut(), t, &mut x)? {
            self.load_state(t, &x)?;
        }
        self.result.stats.events += 1;
        self.result.events.push(EventRecord { time: t, what });
        // Chattering: many events in a row at (almost) the same time.
        let scale = t.abs().max(1.0);
        if t - self.chatter.1 <= CHATTER_WINDOW * scale {
            self.chatter.0 += 1;
        } else {
            self.chatter.0 = 0;
        }
        self.chatter.1 = t;
        self.record_delays(t);
        self.ode.ev.delays.split(t);
        self.ode.ev.delays.mark(t);
        if self.chatter.0 >= CHATTER_COUNT {
            let m = self.m();
            let crossing = crossing
                .map(|k| format!("z{k}: {}", m.root_names[k]))
                .unwrap_or_else(|| "a time event".into());
            return Err(SimError::Chattering {
                time: t,
                crossing,
                events: self.chatter.0,
                sliding: false,
            });
        }
        self.record(t);
        let x = self.states();
        self.ode.last_roots = (f64::NEG_INFINITY, Vec::new());
        // Without a solver (an FMU's Model Exchange: the importer integrates), the
        // importer restarts its own after the event.
        match solver {
            Some(solver) => solver.reset(&mut self.ode, t, &x).map_err(|e| {
                let e = self.solver_error(e);
                self.assertion_first(t, e)
            }),
            None => Ok(()),
        }
    }

    /// Projects `x` at `t` onto the model's active invariants (`Unimo.invariant`) with
    /// the solver's weights; true when `x` moved. Without a solver (an FMU's Model
    /// Exchange) or invariants, nothing.
    pub(super) fn project(
        &mut self,
        solver: Option<&mut Solver>,
        t: f64,
        x: &mut [f64],
    ) -> Result<bool, SimError> {
        let Some(solver) = solver else {
            return Ok(false);
        };
        if self.m().invariants.is_empty() {
            return Ok(false);
        }
        solver
            .project(&mut self.ode, t, x)
            .map_err(|e| self.solver_error(e))
    }

    /// An evaluation that failed right after an event's `reinit`s: when one of the
    /// model's own assertions fails on the new values, it says why (a time scale
    /// reinitialised to 1e-17 fails its assertion before the loops it scales fail),
    /// so it is reported, with the failure it explains after it.
    fn assertion_first(&mut self, t: f64, failure: SimError) -> SimError {
        match self.check_assertions(t) {
            Err(SimError::Assert { time, message }) => SimError::Assert {
                time,
                message: format!("{message} (then: {})", failure.message()),
            },
            _ => failure,
        }
    }
}
