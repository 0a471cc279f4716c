//! Collision geometry for contact scenes: shapes (parry3d-f64 plus an ellipsoid of our
//! own), contact manifolds with several points per pair, signed distance with witness
//! points, a broadphase, time of impact, and the contact force laws. Everything at the
//! boundary is plain `[f64; 3]`; parry's glam types stay inside.

pub mod broadphase;
pub mod laws;
pub mod query;
pub mod shape;

pub use broadphase::{AllPairs, Broadphase, SweepAndPrune};
pub use query::{
    aabb, closest, contacts, time_of_impact, Aabb, ContactPoint, ContactQuery, Moving, Scratch,
    Unsupported,
};
pub use shape::{Placement, Shape, ShapeError, ShapeKind, V3};
