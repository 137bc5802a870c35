//! A moving instance: a shape that moves while the shutter is open, for
//! motion blur. Each ray is intersected with the shape where it stands at the
//! ray's instant ([`Ray::time`]).
//!
//! The shape is given placed as it stands at the rendered frame, with its
//! motion as keys `(t_k, R_k)`: `R_k` is the affine map from where the shape
//! stands at the frame to where it stands at time `t_k` (in frames from the
//! frame; `R = I` at the frame itself). Between keys the motion is
//! interpolated as pbrt-v4's `AnimatedTransform` does, by parts: each `R_k`
//! is split about the centre `c` of the shape's box as
//!
//! ```text
//! R_k(x) = c + T_k + Q_k S_k (x - c)
//! ```
//!
//! with `Q_k S_k` the polar decomposition of its linear part (`Q` a
//! rotation, `S` a symmetric stretch, found by the iteration
//! `Q <- (Q + Q^-T) / 2`), and at `t` between two keys `T` is interpolated
//! linearly, `Q` by slerp (the shorter way) and `S` linearly. A shape moving
//! at constant velocity (linear `T`, constant `Q` and `S`) is exact at every
//! instant, whatever the keys.
//!
//! A ray at time `t` is mapped into the frame's placement by the inverse,
//! `x' = c + S^-1 Q^T (x - c - T)`, and the parameter and normal convert as
//! for [`super::Instance`] (`t_frame = |A^-1 d| t`, `n = normalize(A^-T n')`,
//! `A = Q S`).
//!
//! **The bounds cover every instant** of the keys, so the scene's BVH is built
//! once: over a segment where `Q` is constant each corner of the box moves on
//! a straight line, so the boxes of the two ends hold it; where `Q` turns,
//! `Q S (x - c)` stays within `|S|_F |x - c|` of the centre (the stretch of a
//! linear interpolation is at most its ends' largest, the Frobenius norm bounds
//! the operator norm), so a ball of that radius swept along the segment of `T`
//! holds it.

use std::sync::Arc;

use glam::{DMat3 as Mat3, DQuat as Quat};

use super::{Shape, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::ray::Ray;
use crate::Error;

/// Most keys one moving instance takes.
pub const MAX_MOTION_KEYS: usize = 1024;

/// One key of the motion: the map at `time`, in parts.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    time: f64,
    translation: Vec3,
    rotation: Quat,
    stretch: Mat3,
}

/// The motion at one instant: `x -> centre + translation + linear (x - centre)`.
#[derive(Clone, Copy, Debug)]
struct Pose {
    translation: Vec3,
    linear: Mat3,
    inverse: Mat3,
}

/// A shape that moves during the shutter (see the module documentation).
#[derive(Clone, Debug)]
pub struct MovingInstance {
    shape: Arc<dyn Shape>,
    centre: Vec3,
    keys: Vec<Key>,
    bounds: Aabb,
}

/// The rotation and stretch of the polar decomposition `a = Q S`, for
/// `det a > 0`.
fn polar(a: Mat3) -> (Quat, Mat3) {
    let mut q = a;
    for _ in 0..64 {
        let next = (q + q.inverse().transpose()) * 0.5;
        let change = (next - q).to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()));
        q = next;
        if change <= 1e-15 * (1.0 + q.to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()))) {
            break;
        }
    }
    let rotation = Quat::from_mat3(&q).normalize();
    let stretch = Mat3::from_quat(rotation).transpose() * a;
    (rotation, stretch)
}

/// `|m|_F`, which bounds how far `m` stretches any vector.
fn frobenius(m: &Mat3) -> f64 {
    m.to_cols_array().iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl MovingInstance {
    /// `shape`, placed as it stands at the frame, moved by `motion`: pairs
    /// `(time, R)` in increasing time, at least two, each `R` a finite affine
    /// map that keeps the shape's handedness and does not squash it flat.
    pub fn new(shape: Arc<dyn Shape>, motion: &[(f64, Mat4)]) -> Result<MovingInstance, Error> {
        if motion.len() < 2 || motion.len() > MAX_MOTION_KEYS {
            return Err(Error::invalid("motion", format!("needs 2 to {MAX_MOTION_KEYS} keys, got {}", motion.len())));
        }
        if motion.windows(2).any(|w| !(w[0].0 < w[1].0)) || motion.iter().any(|(t, _)| !t.is_finite()) {
            return Err(Error::invalid("motion", "the keys' times must be finite and increasing"));
        }
        let inner = shape.bounds();
        if !inner.is_finite() || inner.is_empty() {
            return Err(Error::invalid("motion", "only a bounded shape can move"));
        }
        let centre = (inner.min + inner.max) * 0.5;
        let mut keys = Vec::with_capacity(motion.len());
        for &(time, m) in motion {
            if !m.is_finite() || m.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
                return Err(Error::invalid("motion", "each key must be a finite affine matrix (last row 0 0 0 1)"));
            }
            let linear = Mat3::from_mat4(m);
            let scale = frobenius(&linear);
            let det = linear.determinant();
            if !(det > 1e-12 * scale.powi(3)) {
                return Err(Error::DegenerateGeometry(format!(
                    "the motion at time {time} {} the shape (determinant {det:e})",
                    if det < 0.0 { "mirrors" } else { "squashes" }
                )));
            }
            let (rotation, stretch) = polar(linear);
            let translation = m.transform_point3(centre) - centre;
            keys.push(Key { time, translation, rotation, stretch });
        }
        let mut moving = MovingInstance { shape, centre, keys, bounds: Aabb::EMPTY };
        moving.bounds = moving.swept_bounds(inner);
        Ok(moving)
    }

    /// The box holding the shape at every instant (module documentation).
    fn swept_bounds(&self, inner: Aabb) -> Aabb {
        let half = (inner.max - inner.min) * 0.5;
        let radius = half.length();
        let corners = |key: &Key| {
            let pose = Pose::of(key);
            Aabb::from_points((0..8).map(move |i| {
                let corner = Vec3::new(
                    if i & 1 == 0 { -half.x } else { half.x },
                    if i & 2 == 0 { -half.y } else { half.y },
                    if i & 4 == 0 { -half.z } else { half.z },
                );
                self.centre + pose.translation + pose.linear * corner
            }))
        };
        let mut bounds = Aabb::EMPTY;
        for pair in self.keys.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            bounds = bounds.union(corners(a)).union(corners(b));
            if a.rotation.dot(b.rotation).abs() < 1.0 - 1e-14 {
                let reach = radius * frobenius(&a.stretch).max(frobenius(&b.stretch));
                for t in [a.translation, b.translation] {
                    let p = self.centre + t;
                    bounds = bounds.union(Aabb { min: p - Vec3::splat(reach), max: p + Vec3::splat(reach) });
                }
            }
        }
        // Rounding in the corners' products: a relative margin keeps every
        // instant's surface inside.
        let pad = 1e-9 * (crate::math::max_abs(bounds.min).max(crate::math::max_abs(bounds.max)) + radius);
        Aabb { min: bounds.min - Vec3::splat(pad), max: bounds.max + Vec3::splat(pad) }
    }

    /// The motion at `time`, clamped to the keys' span.
    #[inline]
    fn pose(&self, time: f64) -> Pose {
        let keys = &self.keys;
        let last = keys.len() - 1;
        if !(time > keys[0].time) {
            return Pose::of(&keys[0]);
        }
        if time >= keys[last].time {
            return Pose::of(&keys[last]);
        }
        // The segment [t_i, t_i+1] holding `time`.
        let i = keys.partition_point(|k| k.time <= time) - 1;
        let (a, b) = (&keys[i], &keys[i + 1]);
        let s = (time - a.time) / (b.time - a.time);
        let key = Key {
            time,
            translation: a.translation.lerp(b.translation, s),
            rotation: a.rotation.slerp(b.rotation, s),
            stretch: a.stretch * (1.0 - s) + b.stretch * s,
        };
        Pose::of(&key)
    }

    /// The ray at the frame's placement (unit direction) and `|A^-1 d|`, which
    /// turns the ray's parameters into those of the mapped ray.
    #[inline]
    fn frame_ray(&self, ray: &Ray, pose: &Pose) -> Option<(Ray, f64)> {
        let dir = pose.inverse * ray.dir;
        let length = dir.length();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let origin = self.centre + pose.inverse * (ray.origin - self.centre - pose.translation);
        Some((Ray { origin, dir: dir / length, time: ray.time }, length))
    }
}

impl Pose {
    #[inline]
    fn of(key: &Key) -> Pose {
        let rotation = Mat3::from_quat(key.rotation);
        let linear = rotation * key.stretch;
        Pose { translation: key.translation, linear, inverse: key.stretch.inverse() * rotation.transpose() }
    }

    /// The world map `x -> A x + (c + T - A c)` as a matrix.
    fn matrix(&self, centre: Vec3) -> Mat4 {
        let mut m = Mat4::from_mat3(self.linear);
        m.w_axis = (centre + self.translation - self.linear * centre).extend(1.0);
        m
    }
}

impl Shape for MovingInstance {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let pose = self.pose(ray.time);
        let (local, scale) = self.frame_ray(ray, &pose)?;
        let hit = self.shape.intersect(&local, t_min * scale, t_max * scale)?;
        let t = hit.t / scale;
        if !(t > t_min && t < t_max) {
            return None;
        }
        // A^-T = (S^-1 Q^T)^T.
        let normal_matrix = pose.inverse.transpose();
        let normal = (normal_matrix * hit.normal).try_normalize()?;
        let shading_normal = (normal_matrix * hit.shading_normal).try_normalize().unwrap_or(normal);
        let stretch = pose.linear.x_axis.length().max(pose.linear.y_axis.length()).max(pose.linear.z_axis.length());
        Some(SurfaceHit { t, normal, shading_normal, error: hit.error * stretch, primitive_index: hit.primitive_index })
    }

    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let pose = self.pose(ray.time);
        match self.frame_ray(ray, &pose) {
            Some((local, scale)) => self.shape.intersect_p(&local, t_min * scale, t_max * scale),
            None => false,
        }
    }

    fn is_convex(&self) -> bool {
        self.shape.is_convex()
    }

    fn primitive_count(&self) -> usize {
        self.shape.primitive_count()
    }

    fn moves(&self) -> bool {
        true
    }

    /// Where the shape stands at the frame: an emitter is not blurred (the
    /// scene places emitting shapes still).
    fn area(&self) -> Option<f64> {
        self.shape.area()
    }

    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        self.shape.sample_area(u)
    }

    fn triangles(&self) -> Option<Vec<[Vec3; 3]>> {
        self.shape.triangles()
    }

    fn surface_coords(&self, p: Vec3, n: Vec3, primitive: Option<u32>) -> SurfaceCoords {
        self.surface_coords_at(p, n, primitive, 0.0)
    }

    fn surface_coords_at(&self, p: Vec3, n: Vec3, primitive: Option<u32>, time: f64) -> SurfaceCoords {
        let pose = self.pose(time);
        let local = self.centre + pose.inverse * (p - self.centre - pose.translation);
        // n' = A^T n: the frame's normal that A^-T maps to n.
        let local_n = (pose.linear.transpose() * n).try_normalize().unwrap_or(n);
        self.shape.surface_coords_at(local, local_n, primitive, time).transformed(&pose.matrix(self.centre))
    }

    fn warnings(&self) -> Vec<String> {
        self.shape.warnings()
    }
}

#[cfg(test)]
#[path = "moving_tests.rs"]
mod tests;
