//! A built [`Scene`] as a batch target: every object, `f64` geometry.
//!
//! The ray is normalized (`dir / |dir|`) and traced by
//! [`Scene::first_intersect`], whose parameter is then already the distance `t`.
//! Objects are numbered as in [`Scene::objects`]; the primitive is the face index
//! of a triangle mesh (also when the mesh is placed by an instance transform) and
//! `None` for every other shape. The normal is the shape's outward geometric
//! normal, which `first_intersect` turned to face the ray and is turned back here.
//!
//! Far from a shape, precision is that of `f64`: the distance `t` is rounded to
//! about `1.1e-16 t` (a ray from `z = 1e17` towards a unit sphere reports
//! `t = 1e17`, good to some 16 units), while the normal is computed from the
//! hit's offset to the shape rather than from the rounded point, so it stays a
//! finite unit vector (`[0, 0, 1]` there). A hit whose normal the shape still
//! cannot compute finitely is answered as a miss: the batch API never returns
//! a NaN normal.

use super::{BatchRay, BatchTarget, Float, RayHit};
use crate::math::{max_abs, Vec3};
use crate::ray::Ray;
use crate::Scene;

/// Ulps of the magnitudes involved that a closed-form hit distance may be off:
/// normalizing the direction, the root's few operations and the point's
/// evaluation each lose one or two, with a factor of two to spare.
const ROUNDING_ULPS: f64 = 32.0;

/// The unit-direction ray the scene traces.
fn unit_ray<T: Float>(ray: &BatchRay<T>) -> Ray {
    Ray::unit(Vec3::from_array(ray.origin.map(T::to_f64)), Vec3::from_array(ray.dir.map(T::to_f64)) / ray.length())
}

impl BatchTarget for Scene {
    const NORMALS: bool = true;
    const ERRORS: bool = true;

    fn nearest<T: Float>(&self, ray: &BatchRay<T>) -> Option<RayHit> {
        let hit = self.first_intersect(&unit_ray(ray), f64::INFINITY)?;
        let outward = self.shape_outward(&hit);
        if !outward.is_finite() {
            // The shape could not resolve where the ray meets it (see the module doc).
            return None;
        }
        Some(RayHit { t: hit.t, object: hit.object, primitive: hit.primitive, normal: Some(outward.to_array()), shape_error: hit.error })
    }

    fn t_error<T: Float>(&self, ray: &BatchRay<T>, hit: &RayHit) -> f64 {
        let bounds = self.objects[hit.object].shape.bounds();
        let scale =
            [bounds.min, bounds.max].iter().flat_map(|c| c.to_array()).filter(|x| x.is_finite()).fold(0.0, |m: f64, x| m.max(x.abs()));
        let origin = max_abs(Vec3::from_array(ray.origin.map(T::to_f64)));
        ROUNDING_ULPS * f64::EPSILON * (origin + hit.t + scale) + hit.shape_error
    }

    fn occluded<T: Float>(&self, ray: &BatchRay<T>, t_max: f64) -> bool {
        self.first_intersect(&unit_ray(ray), t_max).is_some()
    }
}
