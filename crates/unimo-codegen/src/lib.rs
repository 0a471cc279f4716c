//! Compilation of the causal plan: `unimo-dae`'s plan in, a [`model::CompiledModel`]
//! out — register tapes for every part of the model (parameters, start values, initial
//! equations, the plan's steps and Newton blocks, zero crossings, `when` clauses, the
//! external objects' and the collision world's arguments), their verifier
//! ([`verify`]), their text dump ([`dump`]) and their cost by component ([`cost`]);
//! then, optionally, native code for the hot tapes with Cranelift ([`native`]).
//!
//! This crate never runs a tape: the runtime (`unimo-runtime`) interprets them, calls
//! their native code, and owns the event state and the external objects (tables, FFT,
//! the collision world), which the tapes reach by handles and registers only.

pub mod cost;
pub mod dump;
pub mod model;
pub mod native;
pub mod tape;
pub mod verify;

pub use native::{compile_model, hot_ops, CodegenError, NativeOptions, NativeStats};
