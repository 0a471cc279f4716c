//! FMU export: FMI 2.0 and 3.0, Model Exchange and Co-Simulation. The crate is both the
//! FMU's shared library (a `cdylib` exporting the FMI C functions, `fmi2.rs` and
//! `fmi3.rs`, which reads the model from the FMU's `resources/` at instantiation) and
//! the library `unimo fmu` uses to write the model description and the archive
//! (`description.rs`, `package.rs`). See `docs/fmi.md`.

pub mod description;
pub mod error;
mod ffi;
pub mod fmi2;
pub mod fmi3;
pub mod instance;
pub mod model;
pub mod package;

pub use description::{Kind, Version};
pub use error::FmiError;
