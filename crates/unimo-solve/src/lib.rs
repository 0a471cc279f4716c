//! unimo's own integrators for semi-explicit index-1 DAEs `M x' = f(t, x)` with a diagonal
//! 0/1 mass matrix: variable-order BDF (IDA/DASSL style), Radau IIA of order 5 (RADAU5) and
//! Dormand–Prince 5(4) (DOPRI5), with dense output and zero-crossing location.
//!
//! # Using it
//! Implement [`System`] (size, which rows are differential, `f`, optionally the Jacobian, a
//! sparsity pattern and root functions), create a [`Solver`] with a [`Method`] and
//! [`Options`], then call [`Solver::step_until`] (never steps past its `t_stop`) or
//! [`Solver::step`] (one internal step, for output grids via [`Solver::interpolate`]). A
//! [`StopReason::Root`] leaves the solver at the root; apply the event and call
//! [`Solver::reset`].
//!
//! ```
//! use unimo_solve::{EvalError, Method, Options, Solver, StopReason, System};
//!
//! /// A ball falling from 10 m; the root function is its height.
//! struct Ball;
//!
//! impl System for Ball {
//!     fn len(&self) -> usize { 2 }
//!     fn differential(&self) -> &[bool] { &[true, true] }
//!     fn rhs(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
//!         out[0] = x[1];
//!         out[1] = -9.81;
//!         Ok(())
//!     }
//!     fn n_roots(&self) -> usize { 1 }
//!     fn roots(&mut self, _t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
//!         out[0] = x[0];
//!         Ok(())
//!     }
//! }
//!
//! let mut ball = Ball;
//! let mut solver = Solver::new(Method::Dopri5, &mut ball, 0.0, &[10.0, 0.0], Options::default())?;
//! match solver.step_until(&mut ball, 5.0)? {
//!     StopReason::Root { t, .. } => {
//!         assert!((t - (2.0 * 10.0 / 9.81f64).sqrt()).abs() < 1e-12);
//!         let velocity = solver.state()[1];
//!         solver.reset(&mut ball, t, &[solver.state()[0], -0.8 * velocity])?;
//!     }
//!     other => panic!("{other:?}"),
//! }
//! # Ok::<(), unimo_solve::SolveError>(())
//! ```
//!
//! # Methods
//! * [`Bdf`]: fixed-leading-coefficient BDF of orders 1–5 (see the `bdf` module docs): Newton
//!   with the iteration matrix `c_j M - J` reused across steps, IDA's order and step selection,
//!   IDA's error weights `1 / (rtol |x| + atol)`; algebraic components are part of the error
//!   test unless `Options::suppress_algebraic_error`.
//! * [`Radau5`]: three-stage Radau IIA (order 5, stiffly accurate, L-stable), simplified Newton
//!   on the real and complex transformed systems, Hairer's filtered error estimate and
//!   Gustafsson's predictive step control; tolerances transformed as in RADAU5.
//! * [`Dopri5`]: explicit Dormand–Prince 5(4), PI step control, free 4th-order dense output;
//!   ODEs only.
//!
//! All methods take `rtol`/`atol` as scalars or per component, choose the first step with
//! Hairer's algorithm (on the differential components), respect `Options::max_step`, and keep
//! [`Stats`]. Algebraic initial values must be consistent; consistent initialization is the
//! caller's job. A NaN or infinite value of `f`, or an [`EvalError`] from the system, fails the
//! step attempt: the step is reduced, and after repeated failures a [`SolveError`] with the time
//! and context is returned. Nothing here panics on bad numbers or prints anything.
//!
//! # Roots
//! See the `roots` module: crossings are located by the Illinois method on the dense output to
//! `4 eps max(|t|, 1)`, reported at the first time where the sign has changed, all components
//! changing sign there together; the state returned is the left limit at the root. Roots
//! sitting at zero at the start of a search (after an event, a reset or a root exactly at a step
//! end) are not reported again.

// Numeric kernels index several arrays with one loop counter; that reads best as is.
#![allow(clippy::needless_range_loop)]

mod bdf;
pub mod dense;
mod dense_output;
mod dopri5;
mod error;
mod evaluate;
mod integrator;
mod jacobian;
mod linear;
pub mod newton;
mod norm;
mod options;
pub mod project;
mod radau5;
mod roots;
mod scheduled_lu;
mod small_lu;
mod solver;
mod sparse_lu;
mod stats;
mod step_control;
mod system;

pub use bdf::{Bdf, BdfDenseOutput};
pub use dense_output::DenseOutput;
pub use dopri5::{Dopri5, Dopri5DenseOutput};
pub use error::{EvalError, SolveError, WorstComponents};
pub use integrator::Integrator;
pub use linear::{fine_timing, linear_algebra_seconds, set_fine_timing, LinearSolverKind};
pub use newton::{NewtonError, NewtonProblem, NewtonTolerance, NewtonWork};
pub use options::{LinearSolverChoice, Method, Options, Tolerance, SPARSE_AUTO_THRESHOLD};
pub use project::{ProjectionStats, Projector};
pub use radau5::{Radau5, Radau5DenseOutput};
pub use roots::{group_window, Direction};
pub use solver::{Solver, StopReason};
pub use stats::Stats;
pub use system::{Invariants, JacobianMatrix, SparsityPattern, System};
