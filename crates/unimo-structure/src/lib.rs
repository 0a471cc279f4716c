//! Structural algorithms on integer bipartite graphs.
//!
//! This crate sees an equation system only as its incidence: a [`BipartiteGraph`] of
//! equations ([`EqId`]) × variables ([`VarId`]), plus the derivative relations
//! "variable → its derivative" and "equation → its differentiated form". The symbolic
//! side plugs in through [`IndexReductionSystem`] (as in StateSelection.jl's
//! `interface.jl`) and is called back only to add a derivative variable or to
//! differentiate an equation. Nothing here prints; results are data, and [`dump`]
//! renders them as text, optionally with real names through a [`Naming`].
//!
//! # Pipeline
//!
//! [`analyze`] runs the stages in order; each is also public on its own.
//!
//! 1. **Matching** ([`matching`]): maximum matching by a greedy start followed by
//!    Hopcroft–Karp phases (`O(E √V)`), optionally restricted to allowed equations and
//!    variables; plus [`AugmentingPathSearch`], a single-source search whose visited
//!    ("colored") sets Pantelides needs. All searches are iterative.
//! 2. **Index reduction** ([`pantelides()`]): Pantelides (1988). The top equations (those
//!    not yet differentiated) are matched to the highest derivatives; when the search
//!    from an equation fails, every colored variable gets its derivative
//!    (`add_var_derivative`), every colored equation is differentiated
//!    (`differentiate_eq`), the derivatives inherit the colored pairs and the search
//!    restarts from the derivative of the failed equation. Before starting, the top
//!    equations must match distinct variable *families* (a variable with all its
//!    derivatives): without such a matching the algorithm would never stop, so the
//!    model is reported as [`StructError::Singular`] with the over-determined
//!    equations. A per-equation differentiation limit guards the loop as well.
//! 3. **Dummy derivatives** ([`select_dummy_derivatives`]): Mattsson–Söderlind in
//!    structural form. Level 1: the highest differentiated equations must be solved for
//!    as many highest derivatives that are derivatives of something; a greedy matching
//!    in priority order ([`StateSelectPriority`] of the variable that would stop being a
//!    state: `Never` first, `Always` last, then higher derivative orders first) picks
//!    them. Level k+1: the integrals of level k's equations that are themselves
//!    differentiated, with the integrals of level k's dummies as candidates. Dummies
//!    become algebraic; states are the variables whose derivative occurs and is not a
//!    dummy.
//! 4. **BLT** ([`blt()`]): iterative Tarjan on "equation e uses the unknown computed by
//!    equation f" (petgraph's `tarjan_scc` is recursive, so it is not used); blocks come
//!    out in evaluation order.
//! 5. **Tearing** ([`tear_block`]): Cellier's heuristic with per-edge solvability:
//!    forward (an equation with one unknown left computes it), backward (a variable
//!    left in one equation is computed by it, last), otherwise tear the variable that
//!    occurs in most remaining equations, ties broken by how many equations that makes
//!    explicitly solvable.
//! 6. **Dulmage–Mendelsohn** ([`dulmage_mendelsohn`]): over-, under- and
//!    well-determined parts from a maximum matching, used to describe singular models.
//!
//! Everything is near linear on sparse graphs (benchmark: `cargo bench -p
//! unimo-structure`): time-stamped marks instead of clearing arrays, a pruned greedy
//! sequence of augmenting searches for the dummy levels, a lazy heap for tearing.
//!
//! # The trait contract
//!
//! * Ids are dense: `graph()` has equations `0..n_eqs` and variables `0..n_vars`.
//! * `var_derivative` / `eq_derivative` describe chains: at most one derivative and one
//!   integral per item, no cycles ([`DerivativeChains::from_system`] checks this).
//! * `add_var_derivative(v)` adds exactly the variable `der(v)` to the graph and makes
//!   `var_derivative(v)` return it.
//! * `differentiate_eq(e)` adds the equation `der(e)` (its incidence in `graph()`),
//!   makes `eq_derivative(e)` return it, and may add derivative variables it needs.
//!   Pantelides creates the derivatives of all colored variables before differentiating
//!   the colored equations, so a structural rule (`der(e)` uses `v` and `der(v)` for
//!   each `v` of `e`) needs no other new variables.
//! * Derivatives are never removed. Contract breaches are reported as
//!   [`StructError::Invalid`] where detectable.
//!
//! # Invariants of the outputs
//!
//! * [`Matching`]: `eq_to_var` and `var_to_eq` are inverse; pairs are edges.
//! * [`PantelidesResult`]: the matching pairs exactly the top equations with
//!   highest-derivative variables (one highest variable per chain); the chains are the
//!   system's after reduction; `differentiation_count[e]` is how many derivatives were
//!   made of `e`.
//! * [`DummyDerivatives`]: as many dummies as differentiated equations, every dummy a
//!   derivative; the reduced system (all equations; unknowns = occurring variables that
//!   are not states) has a perfect matching, i.e. is structurally index 1.
//! * [`Block`]s: every equation and unknown in exactly one block, each block after the
//!   blocks computing the unknowns it uses.
//! * [`TornBlock`]: covers its block; inner assignments are solvable and in order;
//!   as many iteration variables as residual equations.
//!
//! [`verify`] checks each of these independently. [`StructuralSystem`] is a ready-made
//! [`IndexReductionSystem`] for callers (and tests, benchmarks) that have only the
//! incidence: it differentiates by the structural rule above.
//!
//! # Errors
//!
//! One enum, [`StructError`], with stable codes `E3201`–`E3206` for model errors and
//! `E3290` for broken invariants (bugs or contract breaches).

pub mod blt;
pub mod chains;
pub mod dm;
pub mod dummy;
pub mod dump;
pub mod error;
pub mod graph;
pub mod ids;
pub mod matching;
pub mod pantelides;
pub mod pipeline;
pub mod regular;
pub mod structural_system;
pub mod tearing;
pub mod verify;

pub use blt::{blt, Block};
pub use chains::DerivativeChains;
pub use dm::{dulmage_mendelsohn, dulmage_mendelsohn_where, singularity, DulmageMendelsohn, Part};
pub use dummy::{
    select_dummy_derivatives, select_dummy_derivatives_with_sets, DummyDerivatives, DummyLevel,
    StateSelectPriority, StateSetSpec,
};
pub use dump::{FnNaming, IdNaming, Naming};
pub use error::StructError;
pub use graph::{BipartiteGraph, VarIncidence};
pub use ids::{EqId, VarId};
pub use matching::{
    complete_matching_where, maximum_matching, maximum_matching_where, AugmentingPathSearch,
    Matching,
};
pub use pantelides::{
    pantelides, pantelides_with_options, IndexReductionSystem, PantelidesOptions, PantelidesResult,
};
pub use pipeline::{analyze, StructuralAnalysis};
pub use structural_system::StructuralSystem;
pub use tearing::{tear_block, tear_blocks, Tearing, TornBlock};
