//! Counted and checked calls of the system's functions: every call is counted in [`Stats`],
//! and a NaN or infinite value in `f` or `g` is reported as an [`EvalError`] so that the
//! integrators treat it like any other failed evaluation (smaller step, then a clear error).

use crate::error::EvalError;
use crate::stats::Stats;
use crate::system::System;

/// A counted, checked call of one of the system's functions: `$name(system, t, x, out,
/// stats)` calls `system.$method(t, x, out)`, counts it in `stats.$counter` and reports a
/// NaN or infinite value of `out` as an error that names it `$symbol[i]`.
macro_rules! checked_call {
    ($(#[$doc:meta])* $name:ident, $method:ident, $counter:ident, $symbol:literal) => {
        $(#[$doc])*
        pub(crate) fn $name(
            system: &mut dyn System,
            t: f64,
            x: &[f64],
            out: &mut [f64],
            stats: &mut Stats,
        ) -> Result<(), EvalError> {
            stats.$counter += 1;
            system.$method(t, x, out)?;
            first_non_finite(out, $symbol)
        }
    };
}

checked_call!(
    /// `f(t, x)` into `out`, counted, with non-finite values turned into an error.
    rhs_checked, rhs, rhs_evals, "f"
);
checked_call!(
    /// `g(t, x)` into `out`, counted, with non-finite values turned into an error.
    roots_checked, roots, root_evals, "g"
);

fn first_non_finite(values: &[f64], name: &str) -> Result<(), EvalError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(EvalError::failed(format!(
            "{name}[{i}] is {} (not finite)",
            values[i]
        ))),
    }
}
