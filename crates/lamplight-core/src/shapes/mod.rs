//! Geometric shapes: one file per shape, each implementing [`Shape`].
//!
//! A shape answers one question, the lecture's `intersect`: where does a ray first
//! meet me within a parameter interval, and what is my outward normal there? The
//! scene ([`crate::scene::Scene::first_intersect`]) keeps the nearest answer over
//! all shapes through the BVH and turns the normal to face the ray.
//!
//! To add a shape: a new file here with the struct, its constructor (which
//! validates its parameters and returns [`crate::Error`]), `impl Shape`, its
//! scene kind (a [`ShapeKind`]: name, parameter table, builder) and its tests;
//! then one `mod` line below and one line in the scene crate's registry.

use std::sync::Arc;

use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::params::{Kind, ParamResult, Params};
use crate::ray::Ray;

/// Builds a shape kind's shapes from its parameters, placed by the world matrix.
pub type ShapeBuild = fn(&mut Params<'_>, &Mat4) -> ParamResult<Vec<Arc<dyn Shape>>>;
/// A shape kind of the scene format.
pub type ShapeKind = Kind<ShapeBuild>;

pub mod box_uv;
pub mod cuboid;
pub mod disk_uv;
mod implicit;
mod inlined;
mod instance;
mod mesh;
pub mod moving;
pub mod plane;
pub mod quadric;
pub mod sdf_grid;
pub mod sphere;
pub mod surface;
pub mod torus;
pub mod triangle;

pub use cuboid::Cuboid;
pub use implicit::{GradientFn, Implicit, ImplicitFn};
pub use inlined::Inlined;
pub use instance::{placed, Instance};
pub use mesh::{TriangleMesh, VertexAttributes};
pub use moving::MovingInstance;
pub use plane::{Disk, Plane, Rectangle};
pub use quadric::{Clip, Quadric, Sheets};
pub use sdf_grid::SdfGrid;
pub use sphere::Sphere;
pub use surface::{SecondUv, SurfaceCoords};
pub use torus::Torus;
pub use triangle::{intersect_triangle, Triangle, TriangleHit, WatertightRay};

/// What a shape reports about a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Ray parameter of the hit, inside the interval asked for.
    pub t: f64,
    /// Unit geometric normal on the shape's outward side (for an open surface, the
    /// side its definition calls outward). Not yet turned towards the ray.
    pub normal: Vec3,
    /// Unit shading normal (interpolated vertex normals of a mesh), outward like
    /// `normal`; equal to `normal` for analytic shapes.
    pub shading_normal: Vec3,
    /// Absolute error bound of the hit point, for shapes whose root finding is
    /// iterative (0 for closed-form shapes, whose error is covered by the relative
    /// offset in [`crate::ray::offset_origin`]).
    pub error: f64,
    /// Index of the triangle hit within a triangle mesh, in its face order (kept
    /// through an [`Instance`]); [`SurfaceHit::NO_PRIMITIVE`] for every other
    /// shape ([`SurfaceHit::primitive`] says which). Batch ray queries report it
    /// ([`crate::batch`]).
    ///
    /// A plain `u32`, not an `Option<u32>`: a shape's test wrote the option as
    /// two 4-byte stores (tag, value) and the render loops read it back as one
    /// 8-byte load right after the call, which the core cannot forward from
    /// the store buffer: a stall on every hit of a box (issue 24).
    pub primitive_index: u32,
}

impl SurfaceHit {
    /// A hit with one normal used for both geometry and shading.
    #[inline]
    pub fn new(t: f64, normal: Vec3) -> SurfaceHit {
        SurfaceHit { t, normal, shading_normal: normal, error: 0.0, primitive_index: SurfaceHit::NO_PRIMITIVE }
    }

    /// [`SurfaceHit::primitive_index`] of a hit that is not on a mesh's triangle.
    pub const NO_PRIMITIVE: u32 = u32::MAX;

    /// The triangle hit within a mesh, `None` for every other shape.
    #[inline]
    pub fn primitive(&self) -> Option<u32> {
        (self.primitive_index != SurfaceHit::NO_PRIMITIVE).then_some(self.primitive_index)
    }
}

/// A surface that rays can hit.
pub trait Shape: Send + Sync + std::fmt::Debug {
    /// A box that contains the whole surface; [`Aabb::INFINITE`] for an unbounded one.
    fn bounds(&self) -> Aabb;

    /// This shape as a kind the scene's queries test without a virtual call
    /// ([`Inlined`]), asked once when the scene is built; `None` (the default)
    /// keeps the virtual call.
    fn inlined(self: Arc<Self>) -> Option<Inlined> {
        None
    }

    /// This shape's test as the path tracer's lanes run it, four rays side by
    /// side ([`crate::accel::ObjectLanes`]), asked once when the scene is
    /// built; `None` (the default) keeps the scene's rays on the walk. A shape
    /// that answers must give the parameters of a test whose every operation
    /// is that of its [`Shape::intersect`] and [`Shape::intersect_p`].
    fn lane(&self) -> Option<crate::accel::LaneShape> {
        None
    }

    /// The hit with the smallest ray parameter `t` in the open interval
    /// `(t_min, t_max)`, or `None`. `ray.dir` is a unit vector.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit>;

    /// True when any hit exists in `(t_min, t_max)` (shadow rays). The default
    /// asks `intersect`; shapes with many parts can stop at the first part hit.
    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.intersect(ray, t_min, t_max).is_some()
    }

    /// The parameter of [`Shape::intersect`]'s hit alone, the same bits (a
    /// shadow ray ends where it first meets its light's body). The default
    /// asks `intersect`; a shape whose normal costs more than its parameter
    /// (a sphere's square root and division) may leave it out.
    fn first_t(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.intersect(ray, t_min, t_max).map(|h| h.t)
    }

    /// False only when no point that [`Shape::intersect`] or
    /// [`Shape::intersect_p`] can report (rounding included) lies in `region`.
    /// Lets the light buffer ([`crate::accel::LightBuffer`]) list a shape whose
    /// box surrounds a light only in the directions its surface covers: a lamp
    /// shade around its bulb. The default, whether `region` meets
    /// [`Shape::bounds`], is always safe.
    fn may_meet(&self, region: &Aabb) -> bool {
        !self.bounds().intersection(*region).is_empty()
    }

    /// True when the hit [`Shape::intersect`] reports below `t_max` is the same,
    /// bit for bit, for every larger `t_max`: `t_max` only rejects. A closed-form
    /// test (a sphere's quadratic, a box's slabs, a mesh's nearest triangle) has
    /// it; a search over `(t_min, t_max)` (marching, root isolation on that
    /// interval) may land elsewhere. The eye's buffer (`accel/eye_buffer.rs`)
    /// asks objects with other bounds than the BVH walk would and is built only
    /// when every object says so. `false` (the default) is always safe.
    fn hit_ignores_t_max(&self) -> bool {
        false
    }

    /// True for flat shapes and boundaries of convex solids (rectangles, disks,
    /// triangles, spheres, boxes): a segment from a point outside to a point of the
    /// surface whose outward normal faces that point meets the surface nowhere
    /// else. Light sampling then knows where a shadow ray reaches the light.
    /// `false` (the default) is always safe.
    fn is_convex(&self) -> bool {
        false
    }

    /// Number of primitives inside (1 for analytic shapes, triangles for a mesh);
    /// reported in statistics.
    fn primitive_count(&self) -> usize {
        1
    }

    /// Surface area, for shapes that can be sampled as area lights; `None` (the
    /// default) when the shape cannot be sampled.
    fn area(&self) -> Option<f64> {
        None
    }

    /// A point distributed uniformly by area over the surface, from `u` in `[0, 1)^2`,
    /// with the unit outward normal there; `None` when the shape cannot be sampled.
    fn sample_area(&self, _u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        None
    }

    /// The surface as triangles, counter-clockwise seen from the outward side, for
    /// shapes made of triangles (meshes, placed meshes): how an emitting mesh becomes
    /// an area light ([`crate::lights::AreaLight`]). `None` (the default) otherwise.
    fn triangles(&self) -> Option<Vec<[Vec3; 3]>> {
        None
    }

    /// Surface coordinates `(u, v)`, `dp/du` and `dp/dv` at point `p` of the
    /// surface, where the unit outward normal is `n`, on primitive `primitive` of
    /// the hit ([`SurfaceHit::primitive`]). Asked at shading time, only by
    /// materials that read them ([`surface`]). The default, for shapes with no
    /// parametrization, is `(0, 0)` with a frame around `n`.
    fn surface_coords(&self, p: Vec3, n: Vec3, primitive: Option<u32>) -> SurfaceCoords {
        let _ = (p, primitive);
        SurfaceCoords::unparametrized(n)
    }

    /// [`Shape::surface_coords`] of a hit made by a ray at `time`
    /// ([`Ray::time`]): a moving shape ([`MovingInstance`]) maps the point back to
    /// where it stood then; every other shape ignores `time`.
    fn surface_coords_at(&self, p: Vec3, n: Vec3, primitive: Option<u32>, time: f64) -> SurfaceCoords {
        let _ = time;
        self.surface_coords(p, n, primitive)
    }

    /// True for a shape that moves while the shutter is open ([`MovingInstance`]):
    /// the integrators then give each camera sample an instant.
    fn moves(&self) -> bool {
        false
    }

    /// What the shape noticed while rendering that the user should know (an
    /// implicit surface whose Lipschitz bound was exceeded), each once; none by default.
    fn warnings(&self) -> Vec<String> {
        Vec::new()
    }
}
