//! The back-end stages on the command line: `emit --stage dae|structure`.

use crate::check::{render_stage, with_flat_model};
use crate::{EXIT_MODEL_ERROR, EXIT_OK};
use std::path::PathBuf;
use unimo_source::{SourceMap, Span};

/// `file:line` of a span, for dumps.
pub fn origin(map: &SourceMap, span: Span) -> String {
    if span == Span::default() {
        return String::new();
    }
    let file = map.get(span.file);
    let lc = file.line_col(span.start as usize);
    let name = file
        .path()
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    format!("{name}:{}", lc.line)
}

/// The back-end stage `emit` prints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackStage {
    /// The hybrid DAE after lowering and alias elimination.
    Dae,
    /// The structural analysis and causal plan.
    Structure,
    /// The compiled tapes.
    Tape,
}

/// `emit --stage dae|structure|tape`: the model flattened, lowered with `fold`'s choice
/// of tunable parameters (`E0020` for a name that covers none), and the stage printed.
pub fn emit(
    stage: BackStage,
    files: &[PathBuf],
    model: Option<&str>,
    libs: &[PathBuf],
    fold: &unimo_dae::FoldOptions,
    color: bool,
) -> i32 {
    with_flat_model(files, model, libs, color, false, &mut |flat, map, _| {
        if let Err(unknown) = crate::simulate::check_tunable(flat, fold) {
            return crate::simulate::report_all(&unknown);
        }
        if stage == BackStage::Dae {
            let (mut dae, diags) = unimo_dae::lower_with(flat, fold);
            if render_stage(&diags, map, color) {
                return EXIT_MODEL_ERROR;
            }
            unimo_dae::alias::eliminate_aliases(&mut dae);
            print!("{}", unimo_dae::dump::dump(&dae, &|s| origin(map, s)));
            return EXIT_OK;
        }
        let (dae, analysis) = match unimo_dae::analyze_model_with(flat, fold) {
            Ok(done) => done,
            Err(diags) => {
                render_stage(&diags, map, color);
                return EXIT_MODEL_ERROR;
            }
        };
        if stage == BackStage::Structure {
            print!("{}", analysis.dump);
        } else {
            let compiled = unimo_codegen::model::compile(&dae, &analysis.plan);
            let names: Vec<String> = dae.ids().map(|s| dae.name(s)).collect();
            println!("tape {}", dae.name);
            print!("{}", unimo_codegen::dump::tape_dump(&compiled, &names));
        }
        EXIT_OK
    })
}
