//! Acceleration structures: bounding boxes and the bounding volume hierarchy.

mod aabb;
mod bvh;
mod sah;

pub use aabb::Aabb;
pub use bvh::{Bvh, BvhStats};
