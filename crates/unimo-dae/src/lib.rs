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
pub mod diff;
pub mod dump;
pub mod equations;
pub mod error;
pub mod events;
pub mod expr;
pub mod external;
pub mod fold;
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
    let (mut dae, diags) = lower_with(model, fold);
    if diags.iter().any(|d| d.is_error()) {
        return Err(diags);
    }
    let aliases = alias::eliminate_aliases(&mut dae);
    let mut a = analysis::analyze(&mut dae).map_err(|e| vec![e.to_diagnostic()])?;
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
