//! Counted and checked calls of the system's functions: every call is counted in [`Stats`],
//! and a NaN or infinite value in `f` or `g` is reported as an [`EvalError`] so that the
//! integrators treat it like any other failed evaluation (smaller step, then a clear error).

use crate::error::EvalError;
use crate::stats::Stats;
use crate::system::System;

/// `f(t, x)` into `out`, counted, with non-finite values turned into an error.
pub(crate) fn rhs_checked(
    system: &mut dyn System,
    t: f64,
    x: &[f64],
    out: &mut [f64],
    stats: &mut Stats,
) -> Result<(), EvalError> {
    stats.rhs_evals += 1;
    system.rhs(t, x, out)?;
    first_non_finite(out, "f")
}

/// `g(t, x)` into `out`, counted, with non-finite values turned into an error.
pub(crate) fn roots_checked(
    system: &mut dyn System,
    t: f64,
    x: &[f64],
    out: &mut [f64],
    stats: &mut Stats,
) -> Result<(), EvalError> {
    stats.root_evals += 1;
    system.roots(t, x, out)?;
    first_non_finite(out, "g")
}

fn first_non_finite(values: &[f64], name: &str) -> Result<(), EvalError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(EvalError::failed(format!(
            "{name}[{i}] is {} (not finite)",
            values[i]
        ))),
    }
}
