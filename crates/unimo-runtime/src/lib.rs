//! The runtime: compiled evaluation of the causal plan, initialization, events and the simulation driver.
pub mod collision;
pub mod cost;
pub mod dump;
pub mod eval;
pub mod fft;
pub mod model;
mod modes;
pub mod native;
pub mod sim;
pub mod tables;
pub mod tape;
pub mod verify;
