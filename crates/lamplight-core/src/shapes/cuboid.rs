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
//!
//! Surface coordinates: each face is `[0, 1]^2`. On the faces of axis `i`, with
//! `(a, b) = (i + 1, i + 2) mod 3` and `f_k = (l_k - min_k) / (max_k - min_k)` for
//! the local point `l`: `(u, v) = (f_a, f_b)` on the `max` face and
//! `(1 - f_a, f_b)` on the `min` face, so that `dp/du x dp/dv` points out of the
//! box on all six (`dp/du = +-M e_a (max_a - min_a)`, `dp/dv = M e_b (max_b - min_b)`);
//! `uv_layout = "mitsuba"` lays them out as Mitsuba's `cube` ([`super::box_uv`]).

use std::sync::Arc;

use glam::DMat3;

use super::box_uv::BoxUv;
use super::{Shape, ShapeKind, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `box`: one solid shape that keeps the whole affine matrix (shear included).
pub const KIND: ShapeKind = Kind {
    name: "box",
    summary: "the box `[min, max]` as one solid; under a transform it keeps the exact matrix (rotated, scaled, sheared)",
    params: &[
        Param::new("min", T::Point, "", "", "low corner"),
        Param::new("max", T::Point, "", "", "high corner, above `min` on every axis"),
        Param::new(
            "uv_layout",
            T::String,
            "\"faces\"",
            "",
            "`\"faces\"`: each face `[0, 1]^2`, `dp/du x dp/dv` outward; `\"mitsuba\"`: the texture coordinates of Mitsuba's `cube` mesh",
        ),
    ],
    build: |p, m| {
        let (lo, hi) = (p.required_vec3("min")?, p.required_vec3("max")?);
        if !(lo.cmplt(hi).all()) {
            return Err(p.error(format!("min {lo} must be below max {hi} on every axis")));
        }
        let uv = if p.choice("uv_layout", &["faces", "mitsuba"])? == "mitsuba" { BoxUv::Mitsuba } else { BoxUv::Faces };
        Ok(vec![Arc::new(Cuboid::new(lo, hi, *m).map_err(|e| p.core_error(e))?.with_uv(uv))])
    },
};

/// The box `[min, max]` placed by an affine `world_from_local` matrix; its faces
/// are numbered +x, -x, +y, -y, +z, -z (the order of [`super::Rectangle::box_faces`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Cuboid {
    min: Vec3,
    max: Vec3,
    world_from_local: Mat4,
    /// Linear part of `M^-1`: a world point `p` is `local_linear p + c` locally,
    /// with `c` the translation of `M^-1`.
    local_linear: DMat3,
    /// `min - c` and `max - c`: the slab planes seen from the untranslated local
    /// point `local_linear p`, which saves adding `c` to every ray origin.
    lo_shift: Vec3,
    hi_shift: Vec3,
    /// World outward unit normals of the six faces.
    normals: [Vec3; 6],
    /// World areas of the six faces.
    face_areas: [f64; 6],
    area: f64,
    bounds: Aabb,
    /// The layout of its surface coordinates ([`BoxUv`]).
    uv: BoxUv,
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
        let (lo_shift, hi_shift) = (min - local_offset, max - local_offset);
        Ok(Cuboid { min, max, world_from_local: m, local_linear, lo_shift, hi_shift, normals, face_areas, area, bounds, uv: BoxUv::Faces })
    }

    /// This box with its surface coordinates laid out as `uv` ([`BoxUv`]).
    pub fn with_uv(mut self, uv: BoxUv) -> Cuboid {
        self.uv = uv;
        self
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

    /// The hit parameter, the entry of the box interval when it is in
    /// `(t_min, t_max)`, else its exit, and what [`SlabHit::face`] needs.
    #[inline(always)]
    fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SlabHit> {
        let o = self.local_linear * ray.origin;
        let d = self.local_linear * ray.dir;
        // A zero component of `d` gives an infinite inverse: the slab bounds are
        // then +-inf (origin outside or strictly inside the slab) or 0 * inf = NaN
        // (origin on a slab plane: the ray lies in the closed slab). Near and far
        // are picked by the sign of the inverse, never by comparing the bounds, and
        // the comparisons below are false for NaN, so such a bound is ignored.
        let inv = d.recip();
        let to_lo = (self.lo_shift - o) * inv;
        let to_hi = (self.hi_shift - o) * inv;
        // Going up an axis (inverse > 0, also d = +0) the ray enters through the
        // min face and leaves through the max face.
        let pick = |up: bool, a: f64, b: f64| if up { a } else { b };
        let up = [inv.x >= 0.0, inv.y >= 0.0, inv.z >= 0.0];
        let near = Vec3::new(pick(up[0], to_lo.x, to_hi.x), pick(up[1], to_lo.y, to_hi.y), pick(up[2], to_lo.z, to_hi.z));
        let far = Vec3::new(pick(up[0], to_hi.x, to_lo.x), pick(up[1], to_hi.y, to_lo.y), pick(up[2], to_hi.z, to_lo.z));
        let later = |a: f64, b: f64| if b > a { b } else { a };
        let earlier = |a: f64, b: f64| if b < a { b } else { a };
        let enter = later(later(later(f64::NEG_INFINITY, near.x), near.y), near.z);
        let exit = earlier(earlier(earlier(f64::INFINITY, far.x), far.y), far.z);
        if !(enter <= exit) {
            return None;
        }
        let (t, entering) = if enter > t_min {
            (enter < t_max).then_some((enter, true))?
        } else {
            (exit > t_min && exit < t_max).then_some((exit, false))?
        };
        Some(SlabHit { t, entering, bound: if entering { near } else { far }, up })
    }
}

/// A hit of the slab test, with what is needed to name its face only when asked
/// (shadow rays never ask).
struct SlabHit {
    t: f64,
    /// Whether `t` is the entry (else the exit) of the box interval.
    entering: bool,
    /// The per-axis entries (or exits); the axis whose bound is `t` set it.
    bound: Vec3,
    /// Per axis, whether the local direction goes up it.
    up: [bool; 3],
}

impl SlabHit {
    /// Face index (+x, -x, +y, -y, +z, -z): the first axis whose bound is `t` (ties
    /// at an edge or corner go to x, then y), on the min side (odd index) when
    /// entering up the axis or leaving down it.
    #[inline(always)]
    fn face(&self) -> usize {
        let axis = if self.bound.x == self.t {
            0
        } else if self.bound.y == self.t {
            1
        } else {
            2
        };
        2 * axis + usize::from(self.entering == self.up[axis])
    }
}

impl Shape for Cuboid {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn is_convex(&self) -> bool {
        true
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn lane(&self) -> Option<crate::accel::LaneShape> {
        Some(crate::accel::LaneShape::Slab(crate::accel::SlabLane {
            linear: self.local_linear,
            lo: self.lo_shift,
            hi: self.hi_shift,
            normals: self.normals,
        }))
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let hit = self.hit(ray, t_min, t_max)?;
        Some(SurfaceHit::new(hit.t, self.normals[hit.face()]))
    }

    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.hit(ray, t_min, t_max).is_some()
    }

    fn surface_coords(&self, p: Vec3, _n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        let f = (self.local_linear * p - self.lo_shift) / (self.hi_shift - self.lo_shift);
        // The face is the one the point is nearest to, in fractions of the box.
        let mut face = (0, true);
        let mut nearest = f64::INFINITY;
        for axis in 0..3 {
            for (distance, max_side) in [((1.0 - f[axis]).abs(), true), (f[axis].abs(), false)] {
                if distance < nearest {
                    nearest = distance;
                    face = (axis, max_side);
                }
            }
        }
        let (axis, max_side) = face;
        self.uv.coords(axis, max_side, f, DMat3::from_mat4(self.world_from_local), self.max - self.min)
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

#[cfg(test)]
mod tests;
