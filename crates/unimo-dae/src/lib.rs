//! The symbolic back end: a hash-consed expression arena, symbolic differentiation,
//! lowering of the flat model to a hybrid DAE (scalarized, functions inlined), alias
//! elimination and the causal plan made with `unimo-structure`.
//!
//! Invariants: no printing and no file access; every problem is a coded `E3xxx`
//! error; the DAE holds no structural results (those are in the plan).

pub mod algo;
pub mod alias;
pub mod analysis;
pub mod collision_args;
pub mod dae;
pub mod delay;
pub mod diff;
pub mod dump;
pub mod equations;
pub mod error;
pub mod events;
pub mod expr;
pub mod external;
mod external_fft;
pub mod fft;
pub mod fold;
mod impure;
mod linearity;
pub mod lower;
pub mod params;
pub mod plan;
pub mod prune;
pub mod random;
mod records;
pub mod singular;
pub mod tensor;
pub mod verify;

pub use dae::Dae;
pub use equations::{lower, lower_with};
pub use error::DaeError;
pub use fold::FoldOptions;

/// Lowering, alias elimination and structural analysis in one call.
pub fn analyze_model(
    model: &unimo_flat::FlatModel,
) -> Result<(Dae, analysis::Analysis), Vec<unimo_source::Diagnostic>> {
    analyze_model_with(model, &FoldOptions::default())
}

/// [`analyze_model`] with a choice of the parameters kept tunable (the others are
/// folded into the code).
pub fn analyze_model_with(
    model: &unimo_flat::FlatModel,
    fold: &FoldOptions,
) -> Result<(Dae, analysis::Analysis), Vec<unimo_source::Diagnostic>> {
    analyze_model_timed(model, fold, &mut [0.0; 2])
}

/// [`analyze_model_with`], writing the seconds spent in `seconds`: lowering with alias
/// elimination, then the structural analysis (index reduction, matching, BLT, tearing,
/// the plan).
pub fn analyze_model_timed(
    model: &unimo_flat::FlatModel,
    fold: &FoldOptions,
    seconds: &mut [f64; 2],
) -> Result<(Dae, analysis::Analysis), Vec<unimo_source::Diagnostic>> {
    let started = std::time::Instant::now();
    let (mut dae, diags) = lower_with(model, fold);
    if diags.iter().any(|d| d.is_error()) {
        return Err(diags);
    }
    dae.warnings = diags;
    let aliases = alias::eliminate_aliases(&mut dae);
    seconds[0] = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let analyzed = analysis::analyze(&mut dae).map_err(|e| vec![e.to_diagnostic()]);
    seconds[1] = started.elapsed().as_secs_f64();
    let mut a = analyzed?;
    if let Some(e) = differentiated_input(&dae, &a.plan) {
        return Err(vec![e.to_diagnostic()]);
    }
    a.plan.stats.aliases_removed = aliases.aliases;
    a.plan.stats.parameters_folded = dae.folded_parameters.len();
    a.plan.stats.constants_removed = aliases.constants;
    if cfg!(debug_assertions) {
        let checked = verify::verify_dae(&dae).and_then(|_| verify::verify_plan(&dae, &a.plan));
        if let Err(e) = checked {
            panic!("{} ({e})", dae.name);
        }
    }
    Ok((dae, a))
}

/// `E3022` when the plan reads the derivative of a top-level input that no step
/// computes: index reduction differentiated an equation through the input, and an
/// input's derivative is not given (the simulator would read zero).
fn differentiated_input(dae: &Dae, plan: &plan::Plan) -> Option<DaeError> {
    use plan::PlanStep;
    let mut computed = std::collections::HashSet::new();
    let mut read = Vec::new();
    for step in &plan.steps {
        match step {
            PlanStep::Assign { var, value, .. } => {
                computed.insert(*var);
                read.push(*value);
            }
            PlanStep::Block(b) => {
                computed.extend(b.iteration_vars.iter().copied());
                computed.extend(b.inner.iter().map(|&(v, _)| v));
                read.extend(b.inner.iter().map(|&(_, e)| e));
                read.extend(b.residuals.iter().copied());
            }
        }
    }
    let d = read
        .into_iter()
        .flat_map(|e| dae.arena.vars(e))
        .find(|&s| {
            !computed.contains(&s)
                && dae.scalar(s).kind == dae::ScalarKind::Derivative
                && dae
                    .scalar(s)
                    .derivative_of
                    .is_some_and(|u| dae.scalar(u).input)
        })?;
    let u = dae.scalar(dae.scalar(d).derivative_of?);
    Some(DaeError::DifferentiatedInput {
        derivative: dae.scalar(d).name.to_string(),
        input: u.name.to_string(),
        span: u.origin,
    })
}
