//! Cuboid: the axis-aligned box `[min, max]` placed by an affine matrix `M`
//! (rotation, non-uniform scale, shear, translation), hit as one solid.
//!
//! A world ray `o + t d` is the local ray `M^-1 o + t (M^-1 d)`. The local
//! direction is left unnormalized so that `t` is the world parameter. In the local
//! frame the box is an intersection of three slabs (Kay and Kajiya 1986): along
//! axis `i` the ray is inside for `t` between `(min_i - o_i) / d_i` and
//! `(max_i - o_i) / d_i`; the box interval is `[max of the entries, min of the
//! exits]`, and the hit is its entry, or its exit for a ray starting inside. The
//! face hit is the one whose slab set that bound; its outward normal is the local
//! axis normal mapped by the inverse transpose, `normalize(M^-T n)` (outward for
//! every invertible `M`, since `(M^-T n).(M v) = n.v`), precomputed for all six faces.
//!
//! The faces are parallelograms `M(corner) + a M(e_u) + b M(e_v)`; the area of the
//! face with normal `+-x` is `|M e_y x M e_z| (max_y - min_y)(max_z - min_z)` (and
//! likewise), which is what area sampling draws faces by.

use glam::DMat3;

use super::{Shape, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::ray::Ray;
use crate::Error;

/// The box `[min, max]` placed by an affine `world_from_local` matrix; its faces
/// are numbered +x, -x, +y, -y, +z, -z (the order of [`super::Rectangle::box_faces`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Cuboid {
    min: Vec3,
    max: Vec3,
    world_from_local: Mat4,
    /// Linear part of `M^-1`.
    local_linear: DMat3,
    /// Translation of `M^-1`: a world point `p` is `local_linear p + local_offset`.
    local_offset: Vec3,
    /// World outward unit normals of the six faces.
    normals: [Vec3; 6],
    /// World areas of the six faces.
    face_areas: [f64; 6],
    area: f64,
    bounds: Aabb,
}

impl Cuboid {
    /// The box `[min, max]` (finite, `min < max` on every axis) under
    /// `world_from_local`, which must be finite, affine (last row `0 0 0 1`) and
    /// invertible.
    pub fn new(min: Vec3, max: Vec3, world_from_local: Mat4) -> Result<Cuboid, Error> {
        if !(min.is_finite() && max.is_finite()) {
            return Err(Error::invalid("box", "min and max must be finite"));
        }
        if !min.cmplt(max).all() {
            return Err(Error::invalid("box", format!("min {min} must be below max {max} on every axis")));
        }
        let m = world_from_local;
        if !m.is_finite() || m.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
            return Err(Error::invalid("transform", "must be a finite affine matrix (last row 0 0 0 1)"));
        }
        let linear = DMat3::from_mat4(m);
        let det = linear.determinant();
        let scale = linear.x_axis.length().max(linear.y_axis.length()).max(linear.z_axis.length());
        if !(det.abs() > 1e-12 * scale.powi(3)) || !det.is_finite() {
            return Err(Error::DegenerateGeometry("box transform is singular (a zero scale)".into()));
        }
        let local_linear = linear.inverse();
        let local_offset = -(local_linear * m.w_axis.truncate());
        let normal_matrix = local_linear.transpose();
        let mut normals = [Vec3::ZERO; 6];
        for (axis, unit) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            let n = (normal_matrix * unit).try_normalize().ok_or_else(|| Error::DegenerateGeometry("box normal is not finite".into()))?;
            normals[2 * axis] = n;
            normals[2 * axis + 1] = -n;
        }
        let size = max - min;
        let (ex, ey, ez) = (linear.x_axis * size.x, linear.y_axis * size.y, linear.z_axis * size.z);
        let (ax, ay, az) = (ey.cross(ez).length(), ez.cross(ex).length(), ex.cross(ey).length());
        let face_areas = [ax, ax, ay, ay, az, az];
        let area = 2.0 * (ax + ay + az);
        let bounds = Aabb::from_points((0..8).map(|i| {
            let corner = Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            );
            m.transform_point3(corner)
        }));
        if !(area.is_finite() && bounds.is_finite()) {
            return Err(Error::invalid("box", "is too large to represent"));
        }
        Ok(Cuboid { min, max, world_from_local: m, local_linear, local_offset, normals, face_areas, area, bounds })
    }

    /// The local box's lower corner.
    pub fn min(&self) -> Vec3 {
        self.min
    }

    /// The local box's upper corner.
    pub fn max(&self) -> Vec3 {
        self.max
    }

    /// The world-from-local matrix.
    pub fn transform(&self) -> Mat4 {
        self.world_from_local
    }

    /// World outward unit normal of face `face` (+x, -x, +y, -y, +z, -z for 0..6).
    pub fn face_normal(&self, face: usize) -> Vec3 {
        self.normals[face]
    }

    /// The hit parameter and the face it lies on: the entry of the box interval
    /// when it is in `(t_min, t_max)`, else its exit.
    #[inline(always)]
    fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, usize)> {
        let o = self.local_linear * ray.origin + self.local_offset;
        let d = self.local_linear * ray.dir;
        let mut span = Span { enter: f64::NEG_INFINITY, enter_face: 0, exit: f64::INFINITY, exit_face: 0 };
        span.slab(self.min.x, self.max.x, o.x, d.x, 0);
        span.slab(self.min.y, self.max.y, o.y, d.y, 2);
        span.slab(self.min.z, self.max.z, o.z, d.z, 4);
        let Span { enter, enter_face, exit, exit_face } = span;
        if !(enter <= exit) {
            return None;
        }
        if enter > t_min {
            (enter < t_max).then_some((enter, enter_face))
        } else {
            (exit > t_min && exit < t_max).then_some((exit, exit_face))
        }
    }
}

impl Shape for Cuboid {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let (t, face) = self.hit(ray, t_min, t_max)?;
        Some(SurfaceHit::new(t, self.normals[face]))
    }

    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.hit(ray, t_min, t_max).is_some()
    }

    fn area(&self) -> Option<f64> {
        Some(self.area)
    }

    /// A face chosen with probability proportional to its area (by `u.0`, rescaled
    /// to `[0, 1)` within the face's share), then a uniform point on it: an affine
    /// map keeps area ratios within a plane, so uniform in the local face is
    /// uniform in the world face.
    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        let mut x = u.0.clamp(0.0, 1.0) * self.area;
        let mut face = 5;
        for (k, &a) in self.face_areas.iter().enumerate() {
            if x < a || k == 5 {
                face = k;
                break;
            }
            x -= a;
        }
        let s = (x / self.face_areas[face]).clamp(0.0, 1.0);
        let v = u.1.clamp(0.0, 1.0);
        let axis = face / 2;
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut local = Vec3::ZERO;
        local[axis] = if face % 2 == 0 { self.max[axis] } else { self.min[axis] };
        local[a] = self.min[a] + (self.max[a] - self.min[a]) * s;
        local[b] = self.min[b] + (self.max[b] - self.min[b]) * v;
        Some((self.world_from_local.transform_point3(local), self.normals[face]))
    }
}

/// The parameter interval of a local ray inside the box, narrowed slab by slab,
/// with the face that set each end.
struct Span {
    enter: f64,
    enter_face: usize,
    exit: f64,
    exit_face: usize,
}

impl Span {
    /// Narrows the interval by the slab `lo <= o + t d <= hi` of the axis whose
    /// +face has index `plus_face` (its -face is `plus_face + 1`).
    #[inline(always)]
    fn slab(&mut self, lo: f64, hi: f64, o: f64, d: f64, plus_face: usize) {
        // A zero component gives an infinite inverse: the slab bounds are then
        // +-inf (origin outside or strictly inside the slab) or 0 * inf = NaN
        // (origin on a slab plane, so the ray lies in the closed slab). The
        // comparisons below are false for NaN, so such a bound is ignored.
        let inv = 1.0 / d;
        let to_lo = (lo - o) * inv;
        let to_hi = (hi - o) * inv;
        // Going up the axis (inv > 0, also d = +0) the ray enters through the
        // min face and leaves through the max face.
        let (near, near_face, far, far_face) =
            if inv >= 0.0 { (to_lo, plus_face + 1, to_hi, plus_face) } else { (to_hi, plus_face, to_lo, plus_face + 1) };
        if near > self.enter {
            self.enter = near;
            self.enter_face = near_face;
        }
        if far < self.exit {
            self.exit = far;
            self.exit_face = far_face;
        }
    }
}

#[cfg(test)]
mod tests;
