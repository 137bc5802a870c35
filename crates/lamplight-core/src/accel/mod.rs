//! Acceleration structures: bounding boxes and the bounding volume hierarchy.

mod aabb;
mod bvh;
mod mesh_bvh;
mod sah;
mod slab;
pub mod tri4;

pub use aabb::Aabb;
pub use bvh::{Bvh, BvhStats};
pub use mesh_bvh::{MeshBvh, MeshBvhStats};
pub use sah::Costs;
