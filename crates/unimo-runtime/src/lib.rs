//! The runtime: runs what `unimo-codegen` compiled — the tape interpreter and native
//! calls, the external objects (tables, FFT, the collision world), initialization,
//! events and the simulation driver. It never compiles.
pub mod collision;
pub mod delay;
pub mod eval;
pub mod exec;
pub mod fft;
mod modes;
pub mod native;
pub mod sim;
pub mod tables;
