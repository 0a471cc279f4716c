//! The compiled model: every expression the runtime evaluates, compiled to tapes over
//! one register file: parameters, start values, the plan's steps (explicit assignments
//! and Newton blocks with their symbolic Jacobians), zero crossings, `when` conditions
//! and actions, assertions and alias outputs.

use crate::tape::{Layout, Reg, Tape};
use rustc_hash::FxHashMap as HashMap;
use unimo_dae::collision_args::{CollisionBodyArgs, CollisionWorldArgs};

mod compile;
mod compile_external;
mod compile_initial;
mod registers;

pub use compile::compile;
pub use registers::RegisterUse;

/// A Newton block in compiled form.
#[derive(Clone, Debug)]
pub struct CompiledBlock {
    pub iteration: Vec<Reg>,
    /// Inner assignments then residuals.
    pub residual_tape: Tape,
    pub residuals: Vec<Reg>,
    pub jacobian_tape: Tape,
    /// Row-major, `residuals.len() x iteration.len()`.
    pub jacobian: Vec<Reg>,
    pub linear: bool,
    /// The relations (indices into the event state's) the residuals hold, decided at
    /// events; sorted.
    pub relations: Vec<u32>,
    /// Names of the iteration variables (for errors).
    pub names: Vec<String>,
}

// The steps sit in one vector walked at every evaluation: a block inline costs some
// bytes per explicit step, a boxed one a pointer chase per block.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum CompiledStep {
    Explicit(Tape),
    Block(CompiledBlock),
}

/// A compiled `when` action.
#[derive(Clone, Debug)]
pub enum Action {
    Assign { target: Reg, value: Reg },
    Reinit { target: Reg, value: Reg },
    Terminate(String),
    Assert { condition: Reg, message: String },
}

#[derive(Clone, Debug)]
pub struct CompiledWhen {
    /// Per branch: condition registers and actions.
    pub branches: Vec<(Vec<Reg>, Vec<Action>)>,
}

/// The compiled symbolic Jacobian: its tape and its nonzeros (row, column, register).
pub type SymbolicJacobian = (Tape, Vec<(usize, usize, Reg)>);

/// Everything the simulator runs.
#[derive(Clone, Debug, Default)]
pub struct CompiledModel {
    pub layout: Layout,
    /// Registers holding constants, written once before anything runs.
    pub constants: Vec<(Reg, f64)>,
    pub n_registers: usize,
    pub parameters: Tape,
    pub starts: Tape,
    pub steps: Vec<CompiledStep>,
    /// Zero-crossing functions: `g_k = reg_a - reg_b` of relation k.
    pub roots_tape: Tape,
    pub roots: Vec<(Reg, Reg)>,
    /// The relation each of the first `root_ops.len()` roots belongs to (its kind
    /// decides the post-crossing value). The roots after them come in pairs, the lower
    /// and upper bound of held rounding `j` (roots `n + 2j`, `n + 2j + 1`).
    pub root_ops: Vec<unimo_dae::expr::RelOp>,
    /// Every root in Modelica syntax (for messages), e.g. `h <= 0` or `floor(time / 0.1)`.
    pub root_names: Vec<String>,
    /// Number of held roundings (`floor`, `integer`, `mod`, ... with events).
    pub n_held: usize,
    /// The equation that computes each scalar's register (explicit assignments, and
    /// a block's first equation for its unknowns), for errors naming the culprit.
    pub definitions: HashMap<Reg, unimo_dae::dae::EqId>,
    /// `sample(start, interval)`: registers of start and interval.
    pub samples: Vec<(Reg, Reg)>,
    /// Conditions and action values of every `when`, computed in event mode.
    pub when_tape: Tape,
    pub whens: Vec<CompiledWhen>,
    /// Every distinct condition register (their previous values decide edges).
    pub conditions: Vec<Reg>,
    pub assert_tape: Tape,
    pub assertions: Vec<(Reg, String, bool)>,
    /// The invariants (`Unimo.invariant(g)`), computed after a pass of the plan:
    /// (register of `g`, register of its condition: nonzero while it holds).
    pub invariant_tape: Tape,
    pub invariants: Vec<(Reg, Reg)>,
    pub alias_tape: Tape,
    pub states: Vec<Reg>,
    pub derivatives: Vec<Reg>,
    pub discretes: Vec<Reg>,
    pub state_names: Vec<String>,
    /// Scalars written to results: name and register.
    pub outputs: Vec<(String, Reg)>,
    /// The symbolic Jacobian d der(x) / dx when the plan is fully explicit (no Newton
    /// blocks): its tape (run after the plan) and its nonzero entries (row, column,
    /// register). `None`: the solvers use finite differences.
    pub jacobian: Option<SymbolicJacobian>,
    /// Nominal values of the states (for tolerances).
    pub nominals: Vec<f64>,
    /// Start attributes: which states have `fixed = true`.
    pub fixed: Vec<bool>,
    /// Parameters with `fixed = false` and no binding: solved for by the initial
    /// equations (register, name).
    pub free_parameters: Vec<(Reg, String)>,
    /// The other parameters, computed again from the free ones.
    pub dependent_parameters: Tape,
    /// Initial equations as residual registers, computed by `initial_tape` after steps.
    /// The tape also assigns the discrete variables an initial equation or initial
    /// algorithm gives explicitly (`count = integer(...)`), in their order.
    pub initial_tape: Tape,
    pub initial_residuals: Vec<Reg>,
    /// Per initial residual: the equation as text (`x = 0.6 (fixed start)` for a fixed
    /// start), and for a fixed start of a variable the plan computes, the first
    /// equation of the step computing it (the constraint a contradiction runs through).
    pub initial_names: Vec<(String, Option<String>)>,
    /// Per initial residual: how many derivatives the fixed variable has above it
    /// (`u32::MAX` for an initial equation). With more equations than unknowns the
    /// independent ones are taken in decreasing order: positions before velocities.
    pub initial_orders: Vec<u32>,
    /// Per initial residual: it reads parameters and constants only (the free
    /// parameters' own equations, solved before the rest).
    pub initial_parameter_only: Vec<bool>,
    /// Constraints (equations index reduction differentiated) whose every variable has
    /// a fixed start: checked at the start values before anything is solved. The tape
    /// computes, per constraint, its two sides.
    pub fixed_constraints_tape: Tape,
    pub fixed_constraints: Vec<FixedConstraint>,
    /// Discrete variables `initial_tape` assigns (register, name).
    pub initial_assigned: Vec<(Reg, String)>,
    /// The discrete variables whose `pre` values `initial_tape` sets (`initial
    /// equation pre(y) = y0`): at initialization, where their `when` is not active,
    /// they equal those values.
    pub initial_pre_assigned: Vec<Reg>,
    pub ops_total: usize,
    /// Relations whose value some tape holds between events (a relation that only an
    /// assertion reads is compared literally and never held).
    pub relation_held: Vec<bool>,
    /// The collision world, when the model has collision bodies.
    pub collision: Option<CollisionModel>,
    /// External objects (tables): the tape computing their constructors' arguments
    /// from the parameters, and where each object's arguments are.
    pub objects_tape: Tape,
    pub objects: Vec<ObjectSite>,
    /// The `delay` sites (`unimo_dae::delay`): the tape computing, after a pass of the
    /// plan, the value each site records, and where it is.
    pub delay_tape: Tape,
    pub delay_inputs: Vec<Reg>,
    /// The model reads `terminal()`: the run ends with a terminal event.
    pub uses_terminal: bool,
    /// Dynamically selected state sets (`unimo_dae::plan::StateSet`).
    pub state_sets: Vec<CompiledStateSet>,
    /// Some equation reads `initial()`: after initialization the simulator runs one
    /// more event iteration at the start time with it false.
    pub equations_read_initial: bool,
    /// Some equation holds `homotopy(actual, simplified)`: initialization first solves
    /// the model with `simplified` (the layout's `homotopy` register 1), then from that
    /// solution with `actual`.
    pub uses_homotopy: bool,
    /// Native code for the whole right-hand side, when the plan is one explicit step
    /// and `unimo-codegen` compiled it (see [`CompiledModel::single_step_ops`]).
    pub native_rhs: Option<crate::native::NativeRhs>,
}

/// A constraint all of whose variables have fixed start values.
#[derive(Clone, Debug)]
pub struct FixedConstraint {
    pub lhs: Reg,
    pub rhs: Reg,
    /// The equation as text.
    pub text: String,
    /// Its variables (name and register).
    pub variables: Vec<(String, Reg)>,
}

/// A state set in compiled form: `jacobian_tape` (run after the plan) fills
/// `jacobian` (`rows x candidates.len()`, row-major).
#[derive(Clone, Debug)]
pub struct CompiledStateSet {
    /// Index of each set state in [`CompiledModel::states`].
    pub states: Vec<usize>,
    pub candidates: Vec<Reg>,
    /// `k x n`, row-major.
    pub selectors: Vec<Reg>,
    pub jacobian_tape: Tape,
    pub jacobian: Vec<Reg>,
    pub rows: usize,
    pub candidate_names: Vec<String>,
    pub initial: Vec<usize>,
}

impl CompiledModel {
    /// Instructions evaluated by one pass of the plan (explicit steps, and per block
    /// one residual and one Jacobian evaluation): the size of the compiled model.
    pub fn plan_ops(&self) -> usize {
        self.steps
            .iter()
            .map(|s| match s {
                CompiledStep::Explicit(t) => t.ops.len(),
                CompiledStep::Block(b) => b.residual_tape.ops.len() + b.jacobian_tape.ops.len(),
            })
            .sum()
    }

    /// The instruction count of the plan's only step, when the plan is one explicit
    /// step and there is no collision world (what [`crate::native::NativeRhs`] needs).
    #[inline]
    pub fn single_step_ops(&self) -> Option<usize> {
        match self.steps.as_slice() {
            [CompiledStep::Explicit(t)] if self.collision.is_none() => Some(t.ops.len()),
            _ => None,
        }
    }

    /// A register file with the constants in place.
    pub fn new_registers(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.n_registers];
        for &(reg, v) in &self.constants {
            r[reg as usize] = v;
        }
        r
    }
}

/// An external object's constructor arguments, in registers (see
/// `unimo_dae::external::ExternalObjectSite`).
#[derive(Clone, Debug)]
pub struct ObjectSite {
    pub kind: unimo_dae::external::ObjectKind,
    pub table: Vec<Reg>,
    pub rows: usize,
    pub cols: usize,
    pub columns: Vec<Reg>,
    /// Smoothness, extrapolation, start time, shift time, time events.
    pub settings: [Reg; 5],
}

/// Per body: argument registers by name, output registers (force, torque) and, when
/// the velocities are plain states, their registers (for impulses).
#[derive(Clone, Debug)]
pub struct CollisionBodyRegs {
    pub args: CollisionBodyArgs<Reg>,
    pub outputs: [Reg; 6],
    pub velocity_states: Option<[Reg; 6]>,
    pub name: String,
}

/// The compiled collision world.
#[derive(Clone, Debug)]
pub struct CollisionModel {
    /// Computes the argument registers from states and parameters.
    pub inputs: Tape,
    pub bodies: Vec<CollisionBodyRegs>,
    pub world_args: CollisionWorldArgs<Reg>,
    pub gaps: [Reg; 2],
    /// Arguments that read variables computed by the plan (not states or parameters):
    /// the world runs before the plan, so such a model is refused.
    pub problems: Vec<String>,
}
