//! Instance: a shared shape placed by an affine transform, without copying it.
//!
//! With `M` the world-from-object matrix, a world ray `o + t d` is the object ray
//! `M^-1 o + t (M^-1 d)`. The object-space direction `d' = M^-1 d` is no longer
//! unit, and every shape expects a unit direction, so it is normalized,
//! `u = d' / |d'|`, and parameters convert as `t_object = |d'| t_world` (the
//! same point, measured in the object's units). The normal transforms with the
//! inverse transpose, `n = normalize(M^-T n')`, which keeps it perpendicular to the
//! surface under non-uniform scale and keeps it outward (`M^-T` preserves the
//! side of the tangent plane a vector is on). The bounds are the box around the
//! eight transformed corners of the object's box.
//!
//! Surface coordinates are the shape's at the object-space point `M^-1 p` (with
//! normal `normalize(M^T n)`); `dp/du`, `dp/dv` and a mesh's tangent are vectors,
//! mapped by `M`.

use std::sync::Arc;

use super::{Shape, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::ray::Ray;
use crate::Error;

/// A shape moved by `world_from_object` (see the module documentation).
#[derive(Clone, Debug)]
pub struct Instance {
    shape: Arc<dyn Shape>,
    world_from_object: Mat4,
    object_from_world: Mat4,
    /// `(M^-1)^T`, upper 3x3 used for normals.
    normal_matrix: Mat4,
    /// Largest stretch of `M` (bounds the growth of the shape's error bound).
    max_scale: f64,
    bounds: Aabb,
}

/// `shape` under `m`: itself for the identity, else an [`Instance`].
pub fn placed(shape: Arc<dyn Shape>, m: &Mat4) -> Result<Arc<dyn Shape>, Error> {
    if *m == Mat4::IDENTITY {
        Ok(shape)
    } else {
        Ok(Arc::new(Instance::new(shape, *m)?))
    }
}

impl Instance {
    /// Places `shape` by `world_from_object`, which must be finite, affine (last row
    /// `0 0 0 1`) and invertible.
    pub fn new(shape: Arc<dyn Shape>, world_from_object: Mat4) -> Result<Instance, Error> {
        let m = world_from_object;
        if !m.is_finite() || m.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
            return Err(Error::invalid("transform", "must be a finite affine matrix (last row 0 0 0 1)"));
        }
        let det = m.determinant();
        let scale = m.x_axis.truncate().length().max(m.y_axis.truncate().length()).max(m.z_axis.truncate().length());
        if !(det.abs() > 1e-12 * scale.powi(3)) || !det.is_finite() {
            return Err(Error::DegenerateGeometry("transform is singular (a zero scale)".into()));
        }
        let inverse = m.inverse();
        let object_box = shape.bounds();
        let bounds = if object_box.is_empty() {
            Aabb::EMPTY
        } else if !object_box.is_finite() {
            Aabb::INFINITE
        } else {
            let (lo, hi) = (object_box.min, object_box.max);
            Aabb::from_points((0..8).map(|i| {
                let corner = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                m.transform_point3(corner)
            }))
        };
        Ok(Instance {
            shape,
            world_from_object: m,
            object_from_world: inverse,
            normal_matrix: inverse.transpose(),
            max_scale: scale,
            bounds,
        })
    }

    /// The world-from-object matrix.
    pub fn transform(&self) -> Mat4 {
        self.world_from_object
    }

    /// The shared shape.
    pub fn shape(&self) -> &Arc<dyn Shape> {
        &self.shape
    }

    /// The object-space ray (unit direction) and the factor `|d'|` that turns world
    /// parameters into object parameters.
    #[inline]
    fn object_ray(&self, ray: &Ray) -> Option<(Ray, f64)> {
        let dir = self.object_from_world.transform_vector3(ray.dir);
        let length = dir.length();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        Some((Ray::unit(self.object_from_world.transform_point3(ray.origin), dir / length), length))
    }
}

impl Shape for Instance {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The placed shape's answer, scaled: as independent of `t_max` as it is.
    fn hit_ignores_t_max(&self) -> bool {
        self.shape.hit_ignores_t_max()
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let (local, scale) = self.object_ray(ray)?;
        let hit = self.shape.intersect(&local, t_min * scale, t_max * scale)?;
        let t = hit.t / scale;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let normal = self.normal_matrix.transform_vector3(hit.normal).try_normalize()?;
        let shading_normal = self.normal_matrix.transform_vector3(hit.shading_normal).try_normalize().unwrap_or(normal);
        Some(SurfaceHit { t, normal, shading_normal, error: hit.error * self.max_scale, primitive_index: hit.primitive_index })
    }

    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        match self.object_ray(ray) {
            Some((local, scale)) => self.shape.intersect_p(&local, t_min * scale, t_max * scale),
            None => false,
        }
    }

    fn primitive_count(&self) -> usize {
        self.shape.primitive_count()
    }

    fn surface_coords(&self, p: Vec3, n: Vec3, primitive: Option<u32>) -> SurfaceCoords {
        let local = self.object_from_world.transform_point3(p);
        // n' = M^T n: the object normal that M^-T maps to n.
        let local_n = self.world_from_object.transpose().transform_vector3(n).try_normalize().unwrap_or(n);
        self.shape.surface_coords(local, local_n, primitive).transformed(&self.world_from_object)
    }

    fn warnings(&self) -> Vec<String> {
        self.shape.warnings()
    }

    /// The shape's triangles moved by `M`; a mirroring `M` (`det < 0`) reverses the
    /// winding, so two corners swap to keep the outward side counter-clockwise.
    fn triangles(&self) -> Option<Vec<[Vec3; 3]>> {
        let m = self.world_from_object;
        let mirror = m.determinant() < 0.0;
        let mut triangles = self.shape.triangles()?;
        for t in &mut triangles {
            let [a, b, c] = t.map(|p| m.transform_point3(p));
            *t = if mirror { [a, c, b] } else { [a, b, c] };
        }
        Some(triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Sphere;

    #[test]
    fn scaled_translated_sphere_is_an_ellipsoid() {
        let unit: Arc<dyn Shape> = Arc::new(Sphere::new(Vec3::ZERO, 1.0).unwrap());
        let m = Mat4::from_translation(Vec3::new(0.0, 0.0, -10.0)) * Mat4::from_scale(Vec3::new(2.0, 1.0, 3.0));
        let e = Instance::new(unit, m).unwrap();
        // Ellipsoid with semi-axes 2, 1, 3 centred at z = -10: the ray down -z meets it at z = -7.
        let hit = e.intersect(&Ray::new(Vec3::ZERO, -Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((hit.t - 7.0).abs() < 1e-12, "{}", hit.t);
        assert!((hit.normal - Vec3::Z).length() < 1e-12);
        // Sideways along x at z = -10 it meets x = -2, whose normal is -x.
        let hit = e.intersect(&Ray::new(Vec3::new(-5.0, 0.0, -10.0), Vec3::X), 0.0, f64::INFINITY).unwrap();
        assert!((hit.t - 3.0).abs() < 1e-12);
        assert!((hit.normal + Vec3::X).length() < 1e-12);
        // An oblique point: the normal is the gradient of x^2/4 + y^2 + z^2/9, not the scaled object normal.
        let p = Vec3::new(2.0 / 2f64.sqrt(), 1.0 / 2f64.sqrt(), -10.0);
        let hit = e.intersect(&Ray::new(p + Vec3::new(0.0, 5.0, 0.0), -Vec3::Y), 0.0, f64::INFINITY).unwrap();
        let expected = Vec3::new(p.x / 4.0, p.y, 0.0).normalize();
        assert!((hit.normal - expected).length() < 1e-9, "{} vs {expected}", hit.normal);
        assert!(e.intersect(&Ray::new(Vec3::ZERO, -Vec3::Z), 0.0, 6.9).is_none(), "t_max is a world distance");
        assert!(e.intersect_p(&Ray::new(Vec3::ZERO, -Vec3::Z), 0.0, 7.1));
        assert!(!e.intersect_p(&Ray::new(Vec3::ZERO, -Vec3::Z), 0.0, 6.9));
    }

    #[test]
    fn placed_triangles_keep_their_outward_side() {
        // Normal (p1 - p0) x (p2 - p0) of a moved triangle equals the normal the
        // instance reports for a hit, for a plain and for a mirroring transform.
        let tri = crate::shapes::TriangleMesh::new(vec![Vec3::ZERO, Vec3::X, Vec3::Y], vec![[0, 1, 2]], None).unwrap();
        let tri: Arc<dyn Shape> = Arc::new(tri);
        for m in [Mat4::from_scale(Vec3::new(2.0, 3.0, 1.0)), Mat4::from_scale(Vec3::new(-2.0, 1.0, 1.0))] {
            let e = Instance::new(tri.clone(), m).unwrap();
            let [a, b, c] = e.triangles().unwrap()[0];
            let n = (b - a).cross(c - a).normalize();
            let centre = (a + b + c) / 3.0;
            let hit = e.intersect(&Ray::new(centre + Vec3::Z, -Vec3::Z), 0.0, f64::INFINITY).unwrap();
            assert!((hit.normal - n).length() < 1e-12, "{} vs {n}", hit.normal);
        }
    }

    #[test]
    fn bounds_hold_the_rotated_box() {
        let cube: Arc<dyn Shape> = Arc::new(Sphere::new(Vec3::ZERO, 1.0).unwrap());
        let m = Mat4::from_rotation_z(45f64.to_radians());
        let b = Instance::new(cube, m).unwrap().bounds();
        let r = 2f64.sqrt();
        assert!((b.max.x - r).abs() < 1e-12 && (b.min.y + r).abs() < 1e-12 && (b.max.z - 1.0).abs() < 1e-12);
    }

    #[test]
    fn singular_or_projective_matrices_are_rejected() {
        let s: Arc<dyn Shape> = Arc::new(Sphere::new(Vec3::ZERO, 1.0).unwrap());
        assert!(Instance::new(s.clone(), Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0))).is_err());
        assert!(Instance::new(s.clone(), Mat4::from_cols_array(&[f64::NAN; 16])).is_err());
        let mut projective = Mat4::IDENTITY;
        projective.x_axis.w = 1.0;
        assert!(Instance::new(s, projective).is_err());
    }
}
