//! `unimo fmu`: a model exported as an FMU (FMI 2.0 or 3.0, Model Exchange or
//! Co-Simulation). The model is flattened here; `unimo-fmi` writes the description
//! and the archive around the prebuilt FMU library (`libunimo_fmi.so`), which this
//! module locates: `UNIMO_FMI_LIBRARY`, else next to the `unimo` executable (or in its
//! `deps/` folder, where cargo builds it). See `docs/fmi.md`.

use crate::api;
use std::path::PathBuf;
use unimo_fmi::package::{self, Request};
use unimo_fmi::{FmiError, Kind, Version};

/// The FMI version.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum FmiVersionArg {
    #[value(name = "2")]
    Two,
    #[value(name = "3")]
    Three,
}

/// The FMU kind.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum KindArg {
    /// Model Exchange: the importer integrates.
    Me,
    /// Co-Simulation: the FMU integrates with unimo's solvers.
    Cs,
}

#[derive(clap::Args, Debug, Clone)]
pub struct FmuArgs {
    #[command(flatten)]
    pub source: crate::ModelArgs,
    /// FMI version.
    #[arg(long = "fmi", value_enum, default_value_t = FmiVersionArg::Two)]
    pub version: FmiVersionArg,
    /// Model Exchange or Co-Simulation.
    #[arg(long, value_enum, default_value_t = KindArg::Me)]
    pub kind: KindArg,
    /// The FMU to write (`NAME.fmu`).
    #[arg(long, short, value_name = "FILE")]
    pub output: PathBuf,
}

/// The file name of the FMU library.
const LIBRARY: &str = "libunimo_fmi.so";

/// Where the FMU library is: `UNIMO_FMI_LIBRARY`, else beside the executable (or in
/// its `deps/`).
pub fn locate_library() -> Result<PathBuf, FmiError> {
    if let Some(path) = std::env::var_os("UNIMO_FMI_LIBRARY") {
        let path = PathBuf::from(path);
        return if path.is_file() {
            Ok(path)
        } else {
            Err(FmiError::LibraryMissing(format!(
                "UNIMO_FMI_LIBRARY names {}, which is not a file",
                path.display()
            )))
        };
    }
    let exe = std::env::current_exe().map_err(|e| FmiError::LibraryMissing(e.to_string()))?;
    let dir = exe.parent().map(PathBuf::from).unwrap_or_default();
    let candidates = [dir.join(LIBRARY), dir.join("deps").join(LIBRARY)];
    candidates
        .iter()
        .find(|p| p.is_file())
        .cloned()
        .ok_or_else(|| {
            FmiError::LibraryMissing(format!(
            "the FMU library {LIBRARY} is not next to {} (build it with `cargo build -p unimo-fmi` \
             in the same profile, or set UNIMO_FMI_LIBRARY)",
            exe.display()
        ))
        })
}

pub fn command(a: &FmuArgs) -> i32 {
    let source = a.source.source(unimo_dae::FoldOptions::default());
    let text = match api::with_session(&source, |s| s.flat().to_modelica()) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{}", e.rendered);
            return e.kind.exit_code();
        }
    };
    let written = locate_library().and_then(|library| {
        let request = Request {
            flat_text: &text,
            version: match a.version {
                FmiVersionArg::Two => Version::Fmi2,
                FmiVersionArg::Three => Version::Fmi3,
            },
            kind: match a.kind {
                KindArg::Me => Kind::ModelExchange,
                KindArg::Cs => Kind::CoSimulation,
            },
            library: &library,
        };
        let (bytes, summary) = package::build(&request)?;
        package::write(&a.output, &bytes)?;
        Ok(summary)
    });
    match written {
        Ok(s) => {
            eprintln!(
                "wrote {} ({} bytes{}): model identifier {}, {} variables, {} states, {} event indicators",
                a.output.display(),
                s.bytes,
                if s.stripped {
                    ""
                } else {
                    "; the library is not stripped: neither strip nor objcopy was found"
                },
                s.identifier,
                s.variables,
                s.states,
                s.event_indicators
            );
            crate::EXIT_OK
        }
        Err(e) => {
            eprintln!("error[{}]: {e}", e.code());
            match e {
                FmiError::Model(_) | FmiError::Unsupported(_) => crate::EXIT_MODEL_ERROR,
                FmiError::Simulation { .. } => crate::EXIT_SIMULATION_FAILURE,
                _ => crate::EXIT_USAGE,
            }
        }
    }
}
