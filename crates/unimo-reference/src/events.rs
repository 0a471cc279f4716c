//! The event-driven run: Dormand–Prince 5(4) of `unimo-solve` between events, root
//! functions per phase, and the library's discrete logic applied at each root (impact
//! mask, predicted jump height, landing at the apex of a jump below the tolerance,
//! lift-off when the normal force would pull, slide/roll switches at `|v_t| = delta`).

use unimo_solve::{Direction, EvalError, Method, Options, SolveError, Solver, StopReason, System};

use crate::dynamics::{
    apply_impact, contact_force, energy, free_gap_acceleration, rhs, slip_phase, ImpactError,
    Phase, Scene,
};
use crate::geometry::{kinematics, norm, STATE_LEN};

/// One event of the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    Impact,
    /// Flight -> Sliding or Rolling.
    Landing(Phase),
    /// Sliding or Rolling -> Flight.
    LiftOff,
    SlideToRoll,
    RollToSlide,
}

impl EventKind {
    /// A short name for tables.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Impact => "impact",
            EventKind::Landing(Phase::Rolling) => "landing-rolling",
            EventKind::Landing(_) => "landing-sliding",
            EventKind::LiftOff => "lift-off",
            EventKind::SlideToRoll => "slide-roll",
            EventKind::RollToSlide => "roll-slide",
        }
    }
}

/// An event at physical time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    pub t: f64,
    pub kind: EventKind,
}

/// Settings of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    pub rtol: f64,
    pub atol: f64,
    pub t_stop: f64,
    /// The run stops with an error after this many events (a Zeno guard).
    pub max_events: usize,
}

/// What a run returns.
#[derive(Debug, Clone)]
pub struct Run {
    pub events: Vec<Event>,
    pub final_time: f64,
    pub final_state: Vec<f64>,
    pub final_phase: Phase,
    pub energy: f64,
    pub steps: u64,
    pub rhs_evals: u64,
    /// Largest `|gap|` seen at the events in contact (before their projection).
    pub max_contact_gap: f64,
}

impl Run {
    /// Number of events of one kind.
    pub fn count(&self, pick: impl Fn(EventKind) -> bool) -> usize {
        self.events.iter().filter(|e| pick(e.kind)).count()
    }

    /// Time of the first transfer to Rolling.
    pub fn first_rolling(&self) -> Option<f64> {
        self.events
            .iter()
            .find(|e| {
                matches!(
                    e.kind,
                    EventKind::SlideToRoll | EventKind::Landing(Phase::Rolling)
                )
            })
            .map(|e| e.t)
    }
}

/// Why a run failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunError {
    #[error("at t = {t}: {source}")]
    Solver { t: f64, source: SolveError },
    #[error("at t = {t}: {source}")]
    Impact { t: f64, source: ImpactError },
    #[error("E4902 more than {0} events (a Zeno sequence that does not land?)")]
    TooManyEvents(usize),
    #[error("E4903 invalid settings: {0}")]
    Invalid(String),
}

/// The system integrated between events: the body in one phase.
struct PhaseSystem {
    scene: Scene,
    phase: Phase,
}

/// Root functions: Flight `[gap, d gap/dt, d2 gap/dt2 free]`; contact `[N, |v_t| - delta,
/// 1]`.
const N_ROOTS: usize = 3;

impl System for PhaseSystem {
    fn len(&self) -> usize {
        STATE_LEN
    }

    fn differential(&self) -> &[bool] {
        &[true; STATE_LEN]
    }

    fn rhs(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        rhs(&self.scene, self.phase, x, out);
        Ok(())
    }

    fn n_roots(&self) -> usize {
        N_ROOTS
    }

    fn roots(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let k = kinematics(&self.scene.body, x);
        if self.phase == Phase::Flight {
            out[0] = k.gap;
            out[1] = k.gap_rate;
            out[2] = free_gap_acceleration(&self.scene, &k, x);
        } else {
            out[0] = contact_force(&self.scene, &k, x, self.phase).0;
            out[1] = norm(k.slip) - self.scene.delta;
            out[2] = 1.0;
        }
        Ok(())
    }
}

/// The discrete state carried between events.
struct Discrete {
    impact_mask: bool,
    clearance: f64,
}

/// Puts the support point on the plane with zero normal velocity (contact states).
fn project_onto_plane(scene: &Scene, x: &mut [f64]) -> f64 {
    let k = kinematics(&scene.body, x);
    x[1] -= k.gap;
    x[4] -= k.gap_rate;
    k.gap.abs()
}

/// Applies the Flight logic at a root; returns the events it fired.
fn flight_root(
    scene: &Scene,
    discrete: &mut Discrete,
    x: &mut [f64],
    hit: &[(usize, Direction)],
) -> Result<Vec<(EventKind, Phase)>, ImpactError> {
    let crossed = |i: usize| hit.iter().any(|&(j, d)| j == i && d == Direction::Falling);
    let k = kinematics(&scene.body, x);
    let free = free_gap_acceleration(scene, &k, x);
    // the library's relan > 0 (accelerating towards the plane) opens the mask
    if !discrete.impact_mask && (free < 0.0 || crossed(2)) {
        discrete.impact_mask = true;
    }
    let touching = k.gap <= 0.0 || crossed(0);
    if discrete.impact_mask && touching && k.gap_rate < 0.0 {
        // the predicted height of the next jump, k^2 v^2 / (2 |a|) (change S3)
        discrete.clearance =
            0.5 * (scene.restitution * k.gap_rate).powi(2) / free.abs().max(f64::MIN_POSITIVE);
        apply_impact(scene, x)?;
        return Ok(vec![(EventKind::Impact, Phase::Flight)]);
    }
    let approaching = k.gap_rate <= 0.0 || crossed(1);
    let accelerating_down = free <= 0.0 || crossed(2);
    if discrete.clearance < scene.clearance_tolerance && approaching && accelerating_down {
        project_onto_plane(scene, x);
        let phase = slip_phase(scene, &kinematics(&scene.body, x));
        discrete.clearance = 1.0;
        return Ok(vec![(EventKind::Landing(phase), phase)]);
    }
    Ok(Vec::new())
}

/// Applies the contact logic at a root; returns the events and the new phase.
fn contact_root(
    scene: &Scene,
    phase: Phase,
    discrete: &mut Discrete,
    x: &mut [f64],
    hit: &[(usize, Direction)],
    max_gap: &mut f64,
) -> (Vec<EventKind>, Phase) {
    let crossed = |i: usize, d: Direction| hit.iter().any(|&(j, e)| j == i && e == d);
    *max_gap = max_gap.max(project_onto_plane(scene, x));
    let k = kinematics(&scene.body, x);
    let (normal, _) = contact_force(scene, &k, x, phase);
    // at the located root N is zero up to rounding (-0.0 included): the crossing decides
    if normal < 0.0 || crossed(0, Direction::Falling) {
        discrete.impact_mask = false;
        return (vec![EventKind::LiftOff], Phase::Flight);
    }
    let slip = norm(k.slip);
    let to_roll = slip <= scene.delta || crossed(1, Direction::Falling);
    let to_slide = slip > scene.delta || crossed(1, Direction::Rising);
    match phase {
        Phase::Sliding if to_roll && scene.friction > 0.0 => {
            (vec![EventKind::SlideToRoll], Phase::Rolling)
        }
        Phase::Rolling if to_slide => (vec![EventKind::RollToSlide], Phase::Sliding),
        _ => (Vec::new(), phase),
    }
}

/// Runs the scene from `x0` (in Flight when its gap is positive, else in the contact
/// state its slip selects) up to `options.t_stop`.
pub fn simulate(scene: &Scene, x0: &[f64], options: &RunOptions) -> Result<Run, RunError> {
    if x0.len() != STATE_LEN || options.rtol <= 0.0 || options.atol <= 0.0 {
        return Err(RunError::Invalid(format!(
            "state of length {} (needs {STATE_LEN}), rtol {}, atol {}",
            x0.len(),
            options.rtol,
            options.atol
        )));
    }
    let mut x = x0.to_vec();
    let k0 = kinematics(&scene.body, &x);
    let phase = if k0.gap > 0.0 {
        Phase::Flight
    } else {
        project_onto_plane(scene, &mut x);
        slip_phase(scene, &kinematics(&scene.body, &x))
    };
    let mut system = PhaseSystem {
        scene: *scene,
        phase,
    };
    let solver_options = Options::with_tolerances(options.rtol, options.atol);
    let fail = |t: f64| move |source| RunError::Solver { t, source };
    let mut solver =
        Solver::new(Method::Dopri5, &mut system, 0.0, &x, solver_options).map_err(fail(0.0))?;
    let mut discrete = Discrete {
        impact_mask: true,
        clearance: 1.0,
    };
    let mut events = Vec::new();
    let mut max_contact_gap = 0.0f64;
    loop {
        let t_now = solver.current_time();
        let stop = solver
            .step_until(&mut system, options.t_stop)
            .map_err(fail(t_now))?;
        let StopReason::Root { t, components } = stop else {
            break;
        };
        let mut y = solver.state().to_vec();
        if system.phase == Phase::Flight {
            let fired = flight_root(scene, &mut discrete, &mut y, &components)
                .map_err(|source| RunError::Impact { t, source })?;
            for (kind, phase) in fired {
                events.push(Event { t, kind });
                system.phase = phase;
            }
        } else {
            let (fired, phase) = contact_root(
                scene,
                system.phase,
                &mut discrete,
                &mut y,
                &components,
                &mut max_contact_gap,
            );
            events.extend(fired.into_iter().map(|kind| Event { t, kind }));
            system.phase = phase;
        }
        if events.len() > options.max_events {
            return Err(RunError::TooManyEvents(options.max_events));
        }
        solver.reset(&mut system, t, &y).map_err(fail(t))?;
    }
    let stats = solver.stats();
    let final_state = solver.state().to_vec();
    Ok(Run {
        events,
        final_time: solver.current_time(),
        energy: energy(scene, &final_state),
        final_state,
        final_phase: system.phase,
        steps: stats.steps,
        rhs_evals: stats.rhs_evals,
        max_contact_gap,
    })
}
