//! Acceleration structures: bounding boxes and the bounding volume hierarchies.
//!
//! Two hierarchies, for two jobs:
//!
//! - [`Bvh`] (`bvh.rs`), the renderer's: 8-wide, `f32` boxes over `f64` shapes
//!   tested through a closure. It is both levels of the scene: one over the
//!   objects, and one inside every [`crate::shapes::TriangleMesh`] over its
//!   triangles. Built by the binned SAH of `sah.rs` with the cost weights of
//!   [`Costs`] (objects or triangles).
//! - [`LightBuffer`] (`light_buffer.rs`): not a hierarchy but a cube of direction
//!   cells around a point light, listing the objects in each, so that shadow
//!   rays towards the light test one cell's objects instead of walking the [`Bvh`].
//! - [`EyeBuffer`] (`eye_buffer.rs`): the same cube of cells around the camera's
//!   eye, listing every object, so that camera rays test one cell's objects,
//!   nearest first, instead of walking the [`Bvh`].
//! - [`MeshBvh`] (`mesh_bvh.rs`), batch ray casting's ([`crate::batch::MeshAccel`]):
//!   8-wide, one `f32` mesh, triangles stored inline in 4-wide packets; its
//!   traversal interleaves scattered rays (`mesh_walk.rs`) and walks coherent
//!   ones eight to a packet (`mesh_packet.rs`).
//!
//! **Why two SAH builders.** Both bin centroids into 16 bins per axis, fall back
//! to median splits below a depth, and build large subtrees on other threads, but
//! they optimise different costs on different data, and one generic builder would
//! need both as parameters:
//!
//! - *Leaf cost.* `sah.rs` prices a leaf of `n` primitives at `n` tests (cost
//!   `C_trav + (A_l n_l + A_r n_r) / A`); a [`MeshBvh`] leaf is tested four
//!   triangles at a time, so `mesh_bvh.rs` prices it at `ceil(n / 4)` packet tests
//!   (`C_node + (A_l ceil(n_l/4) + A_r ceil(n_r/4)) / A`), which changes where it
//!   splits.
//! - *Precision.* `sah.rs` works on `f64` [`Aabb`]s of `f64` shapes (boxes are
//!   rounded outwards to `f32` afterwards); `mesh_bvh.rs` on the `f32` boxes of
//!   `f32` triangles, the data it casts against.
//! - *Build cost.* `mesh_bvh.rs` partitions one reference array in place, for
//!   meshes of millions of triangles whose build time is compared with Embree's
//!   (`BENCHMARKS.md`); `sah.rs` moves primitives into a new vector per node,
//!   which is simpler and fast enough for scenes and the renderer's meshes.
//!
//! Unifying them would change the trees either one builds, and with them the
//! renderer's traversal order and the benchmarked ray-casting figures, for a
//! shared part (the binning loop) of a few dozen lines.

mod aabb;
mod bvh;
mod eye_buffer;
mod light_buffer;
mod mesh_bvh;
mod mesh_packet;
mod mesh_walk;
mod ray_lanes;
mod sah;
mod slab;
pub mod tri4;

pub use aabb::Aabb;
pub use bvh::{Bvh, BvhStats, FLAT_MAX};
pub(crate) use bvh::{Occlude, Visit};
pub use eye_buffer::EyeBuffer;
pub use light_buffer::LightBuffer;
pub use mesh_bvh::{MeshBvh, MeshBvhStats};
pub use mesh_packet::{PacketRay, PACKET};
#[cfg(target_arch = "x86_64")]
pub(crate) use ray_lanes::{rays as lane_rays, rectangle as rectangle_lanes, sphere as sphere_lanes, Rays as LaneRays};
pub use ray_lanes::{LaneShape, Nearest4, ObjectLanes, RectangleLane, SlabLane};
pub use sah::Costs;
