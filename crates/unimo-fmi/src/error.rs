//! Coded errors of FMU export and of the FMU's library (`E47xx`, `docs/errors.md`).

use thiserror::Error;

#[derive(Clone, Debug, Error, PartialEq)]
pub enum FmiError {
    /// The model (the flat text in `resources/`) does not compile.
    #[error("the model does not compile: {0}")]
    Model(String),
    /// The model uses something the FMU cannot expose.
    #[error("the model cannot be exported as an FMU: {0}")]
    Unsupported(String),
    /// The FMU's `resources/` folder is missing or does not match the library.
    #[error("the FMU's resources cannot be used: {0}")]
    Resources(String),
    /// A function was called in a state that does not allow it.
    #[error("{function} is not allowed in the state {state}")]
    WrongState {
        function: &'static str,
        state: &'static str,
    },
    /// A bad argument: an unknown value reference, a wrong size, a null pointer.
    #[error("{function}: {message}")]
    BadArgument {
        function: &'static str,
        message: String,
    },
    /// The simulation failed (the runtime's `E40xx` code is in the message).
    #[error("simulation failed: error[{code}]: {message}")]
    Simulation { code: &'static str, message: String },
    /// `unimo fmu` cannot find the prebuilt FMU library.
    #[error("{0}")]
    LibraryMissing(String),
    /// The FMU cannot be written.
    #[error("cannot write the FMU: {0}")]
    Write(String),
    /// A panic inside the library (a bug in unimo), caught at the C boundary.
    #[error("internal error: {0}")]
    Internal(String),
}

impl FmiError {
    pub fn code(&self) -> &'static str {
        match self {
            FmiError::Model(_) => "E4701",
            FmiError::Unsupported(_) => "E4702",
            FmiError::Resources(_) => "E4703",
            FmiError::WrongState { .. } => "E4704",
            FmiError::BadArgument { .. } => "E4705",
            FmiError::Simulation { .. } => "E4706",
            FmiError::LibraryMissing(_) => "E4707",
            FmiError::Write(_) => "E4708",
            FmiError::Internal(_) => "E4709",
        }
    }

    pub fn simulation(e: &unimo_runtime::sim::SimError) -> FmiError {
        FmiError::Simulation {
            code: e.code(),
            message: e.message(),
        }
    }
}
