//! Initialization: parameters and start values, the fixed constraints checked, the
//! initial equations solved by Newton (free states and free parameters as unknowns,
//! with messages that name the equations that do not hold), and the initial event.

use super::{SimError, Simulator};
use crate::eval::eval_steps_lenient;
use crate::exec::{Instance, Run};
use unimo_codegen::model::CompiledModel;
use unimo_solve::dense::{independent_rows_and_columns, independent_rows_in_order, newton_step};

/// The unknowns of the initial equations, and the messages about their failures.
struct InitialUnknowns<'a> {
    m: &'a CompiledModel,
    /// The number of initial equations.
    n_eq: usize,
    /// Unknowns as (register, name): free states, then free parameters.
    unknowns: Vec<(usize, String)>,
    /// Every unknown's index.
    free: Vec<usize>,
}

impl InitialUnknowns<'_> {
    fn names(&self, ks: &[usize]) -> Vec<String> {
        ks.iter()
            .map(|&k| self.unknowns[k].1.clone())
            .collect::<Vec<_>>()
    }

    /// More initial equations than unknowns is legal when the extra ones are redundant
    /// and hold at the solution (fixed starts on both ends of a rigid connection): the
    /// independent equations are solved, the others checked. The equations that do not
    /// hold once the independent ones are solved, and the model equations through which
    /// they contradict the solved ones.
    fn explain(&self, f: &[f64], solved: &[usize]) -> (String, Vec<String>) {
        let m = self.m;
        let mut off = Vec::new();
        let mut through: Vec<String> = Vec::new();
        let mut culprits = Vec::new();
        // The solved equations of the same order as one that is off take part.
        let orders: Vec<u32> = (0..f.len())
            .filter(|&i| f[i].abs() > 1e-9 && !solved.contains(&i))
            .map(|i| m.initial_orders.get(i).copied().unwrap_or(u32::MAX))
            .collect();
        let involved = |i: usize| {
            f[i].abs() > 1e-9
                || (solved.contains(&i)
                    && orders.contains(&m.initial_orders.get(i).copied().unwrap_or(u32::MAX)))
        };
        for (i, (text, constraint)) in m.initial_names.iter().enumerate() {
            if involved(i) {
                if !solved.contains(&i) {
                    off.push(format!("`{text}` is off by {:.3e}", f[i].abs()));
                }
                if let Some(c) = constraint.as_ref().filter(|c| !through.contains(c)) {
                    through.push(c.clone());
                }
                culprits.push(text.split(" = ").next().unwrap_or(text).to_string());
            }
        }
        let held: Vec<String> = solved
            .iter()
            .filter(|&&i| involved(i))
            .filter_map(|&i| m.initial_names.get(i).map(|(t, _)| format!("`{t}`")))
            .collect();
        let mut text = off.join(", ");
        if !held.is_empty() {
            text += &format!(
                " when {} {}",
                held.join(", "),
                if held.len() == 1 { "holds" } else { "hold" }
            );
        }
        if !through.is_empty() {
            text += &format!(
                "; they are related by the model's equations `{}`",
                through.join("`, `")
            );
        }
        if culprits.is_empty() {
            culprits = self.names(&self.free);
        }
        (text, culprits)
    }

    /// More equations than unknowns, and the extra ones do not hold.
    fn too_many(&self, f: &[f64], solved: &[usize]) -> SimError {
        let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let (detail, culprits) = self.explain(f, solved);
        SimError::Init {
            message: format!(
                "{} initial equations for {} unknowns (states without fixed = true, \
                 parameters with fixed = false), and the extra ones do not hold \
                 (residual {norm:e}): the fixed start values contradict each other{}",
                self.n_eq,
                self.free.len(),
                if detail.is_empty() {
                    String::new()
                } else {
                    format!(": {detail}")
                },
            ),
            culprits,
        }
    }

    /// Any other failure, with the initial equations that are off at the last iterate.
    fn failed(&self, what: &str, f: &[f64], solved: &[usize]) -> SimError {
        let (detail, culprits) = self.explain(f, solved);
        SimError::Init {
            message: if detail.is_empty() {
                what.to_string()
            } else {
                format!("{what}; at the last iterate {detail}")
            },
            culprits,
        }
    }
}

impl Simulator<'_> {
    /// Consistent initial values: parameters, start values, initial equations solved
    /// for the states they determine, then the initial event (`initial()` true). Once
    /// per pass of `delays.rs`'s `initialize`.
    pub(super) fn initialize_once(&mut self, t0: f64) -> Result<(), SimError> {
        let m = self.m();
        if let Some(c) = m.collision.as_ref().filter(|c| !c.problems.is_empty()) {
            return Err(SimError::Init {
                message: "the collision world runs before the rest of the model, so a \
                          collision body's shape, placement and velocities must come from \
                          states and parameters, not from variables the model computes"
                    .into(),
                culprits: c.problems.clone(),
            });
        }
        let layout = m.layout;
        self.ode.regs[layout.time as usize] = t0;
        self.ode.regs[layout.initial as usize] = 1.0;
        if let Err(message) = m.run_parameters(&mut self.ode.regs, &mut self.ode.ev) {
            return Err(SimError::Init {
                message,
                culprits: Vec::new(),
            });
        }
        m.starts.run(&mut self.ode.regs, &mut self.ode.ev);
        self.ode.loop_starts.note_guesses(&self.ode.regs);
        self.check_fixed_constraints()?;
        // Dynamic state sets start with the best choice at the start values.
        self.select_states(true);
        // pre(v) starts at the start value.
        for s in 0..layout.n_scalars {
            self.ode.regs[(layout.pre_base + s) as usize] = self.ode.regs[s as usize];
        }
        self.ode.ev.event_mode = true;
        if m.uses_homotopy {
            // The start of `homotopy`'s continuation: the simplified model's solution is
            // where the actual model's solve starts (a loop with several solutions, such
            // as a limited op-amp in positive feedback, takes the one the library's
            // simplified model selects). A failure leaves the start values.
            self.ode.regs[layout.homotopy as usize] = 1.0;
            let saved = self.ode.regs.clone();
            if self
                .solve_initial_system()
                .and_then(|()| self.eval_plan())
                .is_err()
            {
                self.ode.regs.copy_from_slice(&saved);
            }
            self.ode.regs[layout.homotopy as usize] = 0.0;
        }
        self.solve_initial_system()?;
        // A discrete variable whose `pre` the initial equations set equals it at
        // initialization (its `when` is not active: `y = pre(y)`).
        let m = self.m();
        for &r in &m.initial_pre_assigned {
            self.ode.regs[r as usize] = self.ode.regs[(layout.pre_base + r) as usize];
        }
        // The discrete values the initial equations assigned are their `pre` values.
        let m = self.m();
        for &(r, _) in &m.initial_assigned {
            self.ode.regs[(layout.pre_base + r) as usize] = self.ode.regs[r as usize];
        }
        self.when_baseline()?;
        // The values of initialization, consistent with its `pre` values (an initial
        // equation `pre(y) = true`): the initial event starts from them.
        self.ode.regs[layout.initial as usize] = 1.0;
        self.eval_plan()?;
        self.event_iteration(t0, true)?;
        self.ode.regs[layout.initial as usize] = 0.0;
        if self.m().equations_read_initial {
            // After initialization `initial()` is false: the discrete variables whose
            // equations read it take their values for the run in one more event
            // iteration at the start time (a friction's `startForward`, true only
            // while initializing).
            self.ode.ev.event_mode = true;
            self.event_iteration(t0, false)?;
        }
        self.ode.ev.event_mode = false;
        let m = self.m();
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        // The consistent values may call for other states than the start values did.
        if self.select_states(true) {
            self.eval_plan()?;
        }
        let m = self.m();
        // Sample instants.
        self.sample_next = m
            .samples
            .iter()
            .map(|&(s, _)| self.ode.regs[s as usize])
            .collect();
        Ok(())
    }

    /// The initial equations (or, without any, the plan and the initial assignments).
    fn solve_initial_system(&mut self) -> Result<(), SimError> {
        let m = self.m();
        if !m.initial_residuals.is_empty() {
            self.solve_initial_equations()?;
        } else if !m.initial_assigned.is_empty() || !m.initial_pre_assigned.is_empty() {
            self.eval_plan()?;
            let m = self.m();
            m.initial_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        }
        Ok(())
    }

    /// A constraint whose variables all have fixed starts must hold at them.
    fn check_fixed_constraints(&mut self) -> Result<(), SimError> {
        let m = self.m();
        m.fixed_constraints_tape
            .run(&mut self.ode.regs, &mut self.ode.ev);
        for c in &m.fixed_constraints {
            let (l, r) = (self.ode.regs[c.lhs as usize], self.ode.regs[c.rhs as usize]);
            if (l - r).abs() > 1e-9 * (1.0 + l.abs().max(r.abs())) || !(l - r).is_finite() {
                let values: Vec<String> = c
                    .variables
                    .iter()
                    .map(|(n, reg)| format!("{n} = {:?}", self.ode.regs[*reg as usize]))
                    .collect();
                return Err(SimError::Init {
                    message: format!(
                        "the fixed start values {} contradict the equation `{}` \
                         (its sides differ by {:e}); free one of them (fixed = false) or \
                         make them consistent",
                        values.join(", "),
                        c.text,
                        (l - r).abs()
                    ),
                    culprits: c.variables.iter().map(|(n, _)| n.clone()).collect(),
                });
            }
        }
        Ok(())
    }

    /// `when` conditions fire at initialization only through `initial()`: their values
    /// with initial() false are the baseline the edges are taken against. Only the
    /// conditions are kept: the discrete values that evaluation computes (a friction's
    /// mode, locked without `initial()`) would otherwise become the `pre` values of the
    /// initial event.
    fn when_baseline(&mut self) -> Result<(), SimError> {
        let layout = self.m().layout;
        let initialized = self.ode.regs.clone();
        let relations = self.ode.ev.relations.clone();
        self.ode.regs[layout.initial as usize] = 0.0;
        let baseline = self.eval_plan();
        let m = self.m();
        m.when_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        for &c in &m.conditions {
            self.cond_prev[c as usize] = self.ode.regs[c as usize];
        }
        self.ode.regs.copy_from_slice(&initialized);
        self.ode.ev.relations = relations;
        baseline
    }

    /// The initial residuals at the current registers. The plan is evaluated leniently
    /// at the iterates: a block that the initial equations do not need may fail at the
    /// start values; that is an error only when the residuals are not finite. The event
    /// iteration afterwards is strict.
    fn initial_residual(&mut self) -> Result<Vec<f64>, SimError> {
        let t = self.ode.regs[self.m().layout.time as usize];
        let m = self.m();
        if !m.free_parameters.is_empty() {
            m.dependent_parameters
                .run(&mut self.ode.regs, &mut self.ode.ev);
        }
        let failure = eval_steps_lenient(
            self.m(),
            &mut self.ode.regs,
            &mut self.ode.ev,
            &mut self.ode.work,
        );
        if let Some(failure) = failure {
            let m = self.m();
            m.initial_tape.run(&mut self.ode.regs, &mut self.ode.ev);
            let f: Vec<f64> = m
                .initial_residuals
                .iter()
                .map(|&r| self.ode.regs[r as usize])
                .collect();
            if f.iter().any(|x| !x.is_finite()) {
                return Err(SimError::Block { time: t, failure });
            }
        }
        let m = self.m();
        m.initial_tape.run(&mut self.ode.regs, &mut self.ode.ev);
        Ok(m.initial_residuals
            .iter()
            .map(|&r| self.ode.regs[r as usize])
            .collect())
    }

    /// Finite differences of the residuals `rows` in the registers `regs` (row-major).
    fn initial_jacobian(
        &mut self,
        regs: &[usize],
        rows: &[usize],
        f: &[f64],
    ) -> Result<Vec<f64>, SimError> {
        // The perturbed evaluations leave their values behind (discrete values the
        // initial equations assign, read by the plan in the next evaluation: a noise
        // sample drawn from a perturbed seed; relations decided at a perturbed point):
        // the registers and relations of the base point are restored afterwards, so
        // that the next iterate is evaluated from them, not from the last column's.
        let base = self.ode.regs.clone();
        let relations = self.ode.ev.relations.clone();
        let jac = self.perturbed_columns(regs, rows, f);
        self.ode.regs.copy_from_slice(&base);
        self.ode.ev.relations.copy_from_slice(&relations);
        jac
    }

    /// The columns of [`Self::initial_jacobian`].
    fn perturbed_columns(
        &mut self,
        regs: &[usize],
        rows: &[usize],
        f: &[f64],
    ) -> Result<Vec<f64>, SimError> {
        let mut jac = vec![0.0; rows.len() * regs.len()];
        for (j, &reg) in regs.iter().enumerate() {
            let x = self.ode.regs[reg];
            let h = 1e-7 * x.abs().max(1e-3);
            self.ode.regs[reg] = x + h;
            let fp = self.initial_residual()?;
            self.ode.regs[reg] = x;
            for (ii, &i) in rows.iter().enumerate() {
                jac[ii * regs.len() + j] = (fp[i] - f[i]) / h;
            }
            // A step below the rounding of a large residual (`seed = 67867967`
            // from seed = 0) shows no change in it: such entries are taken from a
            // second difference with a step of 1e-8 of the largest residual.
            let big = 1e-8 * rows.iter().fold(0.0f64, |a, &i| a.max(f[i].abs()));
            let lost = |ii: usize, i: usize, jac: &[f64]| {
                jac[ii * regs.len() + j] == 0.0 && f[i].abs() * 1e-15 > h
            };
            if big > h && rows.iter().enumerate().any(|(ii, &i)| lost(ii, i, &jac)) {
                self.ode.regs[reg] = x + big;
                let fp = self.initial_residual()?;
                self.ode.regs[reg] = x;
                for (ii, &i) in rows.iter().enumerate() {
                    if lost(ii, i, &jac) {
                        jac[ii * regs.len() + j] = (fp[i] - f[i]) / big;
                    }
                }
            }
        }
        Ok(jac)
    }

    /// The initial equations of the free parameters alone (`cr = ...`, `r = -cr*w` of
    /// a filter) first: the states' equations may be singular until they hold (a
    /// steady state `der(x) = r*(x - u)` with r still 0).
    fn solve_parameter_equations(&mut self, u: &InitialUnknowns<'_>) -> Result<(), SimError> {
        let m = u.m;
        let parameter_rows: Vec<usize> = (0..u.n_eq)
            .filter(|&i| m.initial_parameter_only.get(i).copied().unwrap_or(false))
            .collect();
        let parameter_unknowns: Vec<usize> = (0..u.unknowns.len())
            .filter(|&k| k >= u.unknowns.len() - m.free_parameters.len())
            .collect();
        if parameter_rows.is_empty() || parameter_unknowns.is_empty() {
            return Ok(());
        }
        for _ in 0..30 {
            let f = self.initial_residual()?;
            let fr: Vec<f64> = parameter_rows.iter().map(|&i| f[i]).collect();
            if fr.iter().all(|x| x.abs() <= 1e-12) {
                break;
            }
            let (nr, nc) = (parameter_rows.len(), parameter_unknowns.len());
            let regs: Vec<usize> = parameter_unknowns
                .iter()
                .map(|&k| u.unknowns[k].0)
                .collect();
            let jac = self.initial_jacobian(&regs, &parameter_rows, &f)?;
            let (rows, cols) = independent_rows_and_columns(&jac, nr, nc);
            let Some(dx) = newton_step(&jac, nc, &rows, &cols, &fr) else {
                break;
            };
            for (jj, &j) in cols.iter().enumerate() {
                self.ode.regs[regs[j]] += dx[jj];
            }
        }
        Ok(())
    }

    /// Newton on the initial equations; the unknowns are the states not `fixed` and
    /// the parameters with `fixed = false`, the ones that influence the residuals most
    /// chosen by pivoting when there are more unknowns than equations.
    fn solve_initial_equations(&mut self) -> Result<(), SimError> {
        let m = self.m();
        let n_eq = m.initial_residuals.len();
        let unknowns: Vec<(usize, String)> = (0..m.states.len())
            .filter(|&k| !m.fixed[k])
            .map(|k| (m.states[k] as usize, m.state_names[k].clone()))
            .chain(
                m.free_parameters
                    .iter()
                    .map(|(r, n)| (*r as usize, n.clone())),
            )
            .collect();
        let free: Vec<usize> = (0..unknowns.len()).collect();
        let u = InitialUnknowns {
            m,
            n_eq,
            unknowns,
            free,
        };
        self.solve_parameter_equations(&u)?;
        let free = &u.free;
        let mut chosen: Option<(Vec<usize>, Vec<usize>)> = None;
        let mut deficient_steps = 0;
        let mut last_accepted = false;
        for _ in 0..50 {
            let f = self.initial_residual()?;
            let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if norm <= 1e-12 {
                return Ok(());
            }
            // Finite-difference Jacobian over the free states.
            let regs: Vec<usize> = free.iter().map(|&k| u.unknowns[k].0).collect();
            let all: Vec<usize> = (0..n_eq).collect();
            let jac = self.initial_jacobian(&regs, &all, &f)?;
            let (rows, cols) = chosen.get_or_insert_with(|| {
                if n_eq > free.len() {
                    independent_rows_in_order(&jac, n_eq, free.len(), &m.initial_orders)
                } else {
                    independent_rows_and_columns(&jac, n_eq, free.len())
                }
            });
            let deficient = rows.len() < n_eq && n_eq <= free.len();
            if deficient {
                // Singular at this iterate: the equations that are independent here
                // take a step (e.g. the parameters a filter's steady state depends on,
                // which start at 0 and make that state's rows vanish), then the rank
                // is looked at again; singular for good is an error.
                deficient_steps += 1;
                if deficient_steps > 8 || rows.is_empty() {
                    return Err(u.failed(
                        "the initial equations do not determine the states (singular)",
                        &f,
                        &[],
                    ));
                }
            }
            let (rows, cols) = (rows.clone(), cols.clone());
            if deficient {
                chosen = None;
            }
            let (rows, cols) = (&rows, &cols);
            if rows.is_empty() {
                return Err(u.too_many(&f, &[]));
            }
            let Some(dx) = newton_step(&jac, free.len(), rows, cols, &f) else {
                return Err(u.failed("the initial equations have a singular Jacobian", &f, rows));
            };
            last_accepted = true;
            for (jj, &j) in cols.iter().enumerate() {
                let x = self.ode.regs[regs[j]];
                last_accepted &= self.ode.work.tolerance.accepts(x, dx[jj]);
                self.ode.regs[regs[j]] = x + dx[jj];
            }
        }
        self.initial_not_converged(&u, chosen, last_accepted)
    }

    /// After 50 Newton steps on the initial equations without convergence to rounding:
    /// accepted when the last step was within the simulation's tolerances
    /// (unimo_solve::newton's rule) and the redundant equations, which take no step,
    /// hold; otherwise the error.
    fn initial_not_converged(
        &mut self,
        u: &InitialUnknowns<'_>,
        chosen: Option<(Vec<usize>, Vec<usize>)>,
        last_accepted: bool,
    ) -> Result<(), SimError> {
        let n_eq = u.n_eq;
        let f = self.initial_residual()?;
        let norm = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let redundant = chosen.as_ref().map_or(0.0, |(rows, _)| {
            (0..n_eq)
                .filter(|i| !rows.contains(i))
                .fold(0.0f64, |a, i| a.max(f[i].abs()))
        });
        if last_accepted && norm.is_finite() && redundant <= 1e-9 {
            return Ok(());
        }
        if let Some((rows, _)) = &chosen {
            let solved = rows.iter().fold(0.0f64, |a, &i| a.max(f[i].abs()));
            if rows.len() < n_eq && solved <= 1e-9 {
                return Err(u.too_many(&f, rows));
            }
        }
        let solved = chosen.as_ref().map(|(r, _)| r.clone()).unwrap_or_default();
        Err(u.failed(
            &format!("Newton on the initial equations did not converge (residual {norm:e})"),
            &f,
            &solved,
        ))
    }
}
