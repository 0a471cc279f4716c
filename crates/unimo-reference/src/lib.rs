//! An event-driven reference for paper A's scenes, written apart from the acausal
//! library `UnilateralMBS` to cross-check it (issue #21, point 4): a homogeneous
//! ellipsoid over the fixed plane y = 0 with the closed-form support point (no
//! integrated closest points), Newton's impact law with the regularised friction impulse,
//! the regularised Coulomb law in contact with the exact normal force, and the library's
//! landing rule (a jump predicted below `ClearanceTolerance` lands at its apex).
//!
//! The laws are the library's (spec A.4–A.7 plus the changes S1–S5 of
//! `docs/paper-a-transcription.md`); the time regularisation is left out, since it only
//! reparametrises time. Between events the body is integrated in physical time with
//! `unimo-solve`'s Dormand–Prince 5(4) (a method the acausal runs do not use).

pub mod dynamics;
pub mod events;
pub mod geometry;
pub mod scenes;

pub use dynamics::{Phase, Scene};
pub use events::{simulate, Event, EventKind, Run, RunError, RunOptions};
pub use geometry::Ellipsoid;
