//! The hybrid DAE: scalar variables, continuous equations as residuals, `when`
//! clauses with their actions, initial equations, assertions. Lean by design:
//! matchings, blocks and Jacobians live in the structural plan, not here.

use crate::expr::{ExprArena, ExprId, ScalarId};
use unimo_source::Span;

/// What kind of quantity a scalar is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ScalarKind {
    Constant,
    Parameter,
    /// A continuous-time Real: a state or an algebraic variable (decided by the
    /// structural stage).
    Continuous,
    /// The time derivative of another scalar (`der(x)`).
    Derivative,
    /// Boolean, Integer, enumeration, `discrete` Real, or assigned in `when`.
    Discrete,
}

/// The value type of a scalar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScalarType {
    Real,
    Integer,
    Boolean,
    /// An enumeration, by index into [`Dae::enumerations`].
    Enumeration(u32),
}

/// `stateSelect` (spec 4.9.7.1): the structural analysis' own priority, so that the
/// scalar's attribute is what dummy-derivative selection reads.
pub use unimo_structure::StateSelectPriority as StateSelect;

#[derive(Clone, Debug)]
pub struct Scalar {
    /// Full name with subscripts (`body.r[2]`), or `der(x)` for derivatives.
    pub name: String,
    pub kind: ScalarKind,
    pub ty: ScalarType,
    /// The binding of a parameter or constant.
    pub binding: Option<ExprId>,
    pub start: Option<ExprId>,
    pub fixed: Option<bool>,
    pub nominal: Option<ExprId>,
    pub min: Option<ExprId>,
    pub max: Option<ExprId>,
    pub state_select: StateSelect,
    /// For a derivative: the scalar it is the derivative of.
    pub derivative_of: Option<ScalarId>,
    /// The scalar's derivative, once one exists.
    pub derivative: Option<ScalarId>,
    /// A top-level input (its value comes from outside; zero when not given).
    pub input: bool,
    /// Set by alias elimination: the scalar equals this expression (of its
    /// representative, or a constant/parameter expression) and is no longer an unknown.
    pub alias: Option<ExprId>,
    pub description: Option<String>,
    pub origin: Span,
}

impl Scalar {
    pub fn new(name: String, kind: ScalarKind, ty: ScalarType, origin: Span) -> Scalar {
        Scalar {
            name,
            kind,
            ty,
            binding: None,
            start: None,
            fixed: None,
            nominal: None,
            min: None,
            max: None,
            state_select: StateSelect::Default,
            derivative_of: None,
            derivative: None,
            input: false,
            alias: None,
            description: None,
            origin,
        }
    }
}

/// Index of a continuous equation.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct EqId(pub u32);

impl EqId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A continuous (or discrete-valued, outside `when`) equation `lhs = rhs`.
#[derive(Clone, Debug)]
pub struct Equation {
    pub lhs: ExprId,
    pub rhs: ExprId,
    pub origin: Span,
    /// Set for equations made by differentiating another (index reduction).
    pub derivative_of: Option<EqId>,
}

/// What a `when` branch does when its condition becomes true.
#[derive(Clone, Debug)]
pub enum WhenAction {
    /// `v = value` (a discrete variable).
    Assign {
        target: ScalarId,
        value: ExprId,
    },
    /// `reinit(x, value)` of a state, applied at the end of the event step.
    Reinit {
        state: ScalarId,
        value: ExprId,
    },
    Terminate {
        message: String,
    },
    Assert {
        condition: ExprId,
        message: String,
    },
}

/// `when c1 then ... elsewhen c2 then ... end when`: the first branch whose condition
/// becomes true acts.
#[derive(Clone, Debug)]
pub struct WhenClause {
    pub branches: Vec<WhenBranch>,
    pub origin: Span,
}

/// One branch of a `when`: it fires when any of its conditions becomes true
/// (`when {a, b}` has two).
#[derive(Clone, Debug)]
pub struct WhenBranch {
    pub conditions: Vec<ExprId>,
    pub actions: Vec<(WhenAction, Span)>,
}

/// An `assert` outside `when`, checked after every accepted step and event.
#[derive(Clone, Debug)]
pub struct Assertion {
    pub condition: ExprId,
    pub message: String,
    /// `AssertionLevel.warning`: report and continue.
    pub warning: bool,
    pub origin: Span,
}

/// An invariant `Unimo.invariant(g)`: `g = 0` holds on the solution wherever `active`
/// is true (the conditions of the if-equation branches it stands in). The simulator
/// projects the states onto `g = 0` after each accepted step and event (coordinate
/// projection, `docs/backend.md`); `g` is not an equation of the DAE.
#[derive(Clone, Debug)]
pub struct Invariant {
    pub value: ExprId,
    pub active: ExprId,
    pub origin: Span,
}

/// The hybrid DAE of one model.
#[derive(Clone, Debug, Default)]
pub struct Dae {
    pub name: String,
    pub arena: ExprArena,
    pub scalars: Vec<Scalar>,
    pub equations: Vec<Equation>,
    pub initial_equations: Vec<Equation>,
    pub whens: Vec<WhenClause>,
    pub assertions: Vec<Assertion>,
    /// Invariants the states are projected onto (`Unimo.invariant`).
    pub invariants: Vec<Invariant>,
    pub enumerations: Vec<(String, Vec<String>)>,
    /// `experiment(StartTime, StopTime, Tolerance, Interval)` when given.
    pub experiment: Experiment,
    /// Collision bodies (`collisionBody(...)` calls), numbered by the compiler in
    /// instantiation order: site `k` of `Node::External(k, _)`.
    pub collision: Vec<CollisionBody>,
    /// The collision world's settings (`collisionGaps(margin, tolerance, broadphase, sweep)`).
    pub collision_world: Option<CollisionWorld>,
    /// External objects (the MSL's tables), made after the parameters: the handle of
    /// object `k` is the constant `k` (`crate::external`).
    pub external_objects: Vec<crate::external::ExternalObjectSite>,
    /// The `delay` calls: site `k` of `Ext(Delay, [k, ..])` (`delay.rs`).
    pub delays: Vec<crate::delay::DelaySite>,
    /// Whether the model reads `terminal()` (the simulator then ends with a terminal
    /// event at the stop time).
    pub uses_terminal: bool,
    /// The parameters folded into the equations as constants (`fold.rs`): changing
    /// one of them needs a new compilation. Sorted.
    pub folded_parameters: Vec<ScalarId>,
    /// The warnings of lowering (`W3xxx`), for the caller to report.
    pub warnings: Vec<unimo_source::Diagnostic>,
}

pub use crate::collision_args::{
    CollisionBodyArgs, CollisionWorldArgs, COLLISION_BODY_ARGS, COLLISION_WORLD_ARGS,
};

/// One collision body: the arguments of its `collisionBody(...)` call, by name.
#[derive(Clone, Debug)]
pub struct CollisionBody {
    pub args: CollisionBodyArgs<ExprId>,
    pub span: Span,
}

/// The collision world: the arguments of its `collisionGaps(...)` call, by name.
#[derive(Clone, Debug)]
pub struct CollisionWorld {
    pub args: CollisionWorldArgs<ExprId>,
    pub span: Span,
}

/// Site index of the collision world's gaps (`collisionGaps(...)`).
pub const COLLISION_GAPS_SITE: u32 = u32::MAX;

/// Simulation settings from `annotation(experiment(...))`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Experiment {
    pub start_time: Option<f64>,
    pub stop_time: Option<f64>,
    pub tolerance: Option<f64>,
    pub interval: Option<f64>,
    /// `__unimo_method = "radau5"`: the integration method the model asks for (one of
    /// [`METHOD_NAMES`]), used when the user does not choose one.
    pub method: Option<String>,
}

/// The values `experiment(__unimo_method = ...)` accepts, as the CLI's `--method` names them.
pub const METHOD_NAMES: &[&str] = &["auto", "bdf", "radau5", "dopri5"];

impl Dae {
    pub fn scalar(&self, s: ScalarId) -> &Scalar {
        &self.scalars[s.index()]
    }

    pub fn add_scalar(&mut self, s: Scalar) -> ScalarId {
        let id = ScalarId(self.scalars.len() as u32);
        self.scalars.push(s);
        id
    }

    pub fn ids(&self) -> impl Iterator<Item = ScalarId> {
        (0..self.scalars.len() as u32).map(ScalarId)
    }

    /// The derivative scalar of `s`, created when it does not exist yet.
    pub fn derivative_of(&mut self, s: ScalarId) -> ScalarId {
        if let Some(d) = self.scalars[s.index()].derivative {
            return d;
        }
        let base = &self.scalars[s.index()];
        let mut d = Scalar::new(
            format!("der({})", base.name),
            ScalarKind::Derivative,
            ScalarType::Real,
            base.origin,
        );
        d.derivative_of = Some(s);
        let id = self.add_scalar(d);
        self.scalars[s.index()].derivative = Some(id);
        id
    }

    /// Whether `s` may vary continuously (it can have a nonzero time derivative).
    pub fn is_continuous(&self, s: ScalarId) -> bool {
        matches!(
            self.scalars[s.index()].kind,
            ScalarKind::Continuous | ScalarKind::Derivative
        )
    }

    /// The residual `lhs - rhs` of an equation.
    pub fn residual(&mut self, eq: EqId) -> ExprId {
        let e = &self.equations[eq.index()];
        let (l, r) = (e.lhs, e.rhs);
        self.arena.sub(l, r)
    }

    /// Name of a scalar for dumps.
    pub fn name(&self, s: ScalarId) -> String {
        self.scalars[s.index()].name.clone()
    }

    /// `e` as Modelica text, cut after 10,000 bytes with `...` (an expression whose
    /// parts are shared, as filter coefficients computed by loops, can be
    /// exponentially long written out as a tree).
    pub fn show(&self, e: ExprId) -> String {
        self.arena.to_short_string(e, &|s| self.name(s), 10_000)
    }
}
