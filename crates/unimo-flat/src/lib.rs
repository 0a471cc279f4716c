//! Instantiation and flattening: from parsed classes to one flat model.
//!
//! This crate holds the class tree (typed `ClassId`s, lazy loading of library packages
//! through a [`SourceProvider`]), Modelica name lookup, and the name-resolution check
//! that `unimo check` runs. Instantiation proper (modifiers, connections, the flat
//! model) builds on these.
//!
//! Invariants: no file system access of its own (files come through the provider), no
//! printing; every problem is a coded `E2xxx` diagnostic.

pub mod error;
pub mod lookup;
pub mod provider;
pub mod resolve;
pub mod tree;

pub use error::FlatError;
pub use provider::{LibFile, LibLocation, MemoryProvider, SourceProvider};
pub use tree::{ClassId, ClassTree, LoadStats};
