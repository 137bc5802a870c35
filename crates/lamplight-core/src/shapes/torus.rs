//! Torus: `f(p) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) = 0` in its local frame.
//!
//! The local frame has the torus centre at the origin and its axis (the axis of
//! rotational symmetry, through the hole) along `+z`; `R` is the major radius (axis
//! to tube centre) and `r` the minor radius (the tube's), `0 < r < R` (a ring torus,
//! with a hole). A ray is moved into the local frame by a rotation, which keeps `t`.
//!
//! Substituting `p = o + d u` gives a quartic in `u`. With `g(u) = a u^2 + 2 b u + c`,
//! `a = d.d`, `b = o.d`, `c = |o|^2 + R^2 - r^2`, and `e = dx^2 + dy^2`,
//! `h = ox dx + oy dy`, `k = ox^2 + oy^2`:
//!
//! `a^2 u^4 + 4ab u^3 + (4b^2 + 2ac - 4R^2 e) u^2 + (4bc - 8R^2 h) u + c^2 - 4R^2 k = 0`.
//!
//! Robustness comes from three choices. The origin `o` is first moved to where the
//! ray enters the torus's bounding box (within the asked interval), so the
//! coefficients are computed from numbers of the torus's own size and a far camera
//! costs no precision. The roots are isolated on the box's slab interval by
//! recursive subdivision at the derivative's roots (see `polynomial.rs`), so none is
//! skipped, and each is refined by bisection with Newton steps to full precision. A
//! local minimum of `|f|` within its rounding error counts as a (double) root, so a
//! ray tangent to the surface still hits it. The normal is the gradient
//! `4 (|p|^2 + R^2 - r^2) p - 8 R^2 (x, y, 0)`. `SurfaceHit::error` is the hit point's
//! exact distance from the surface, `| |(sqrt(x^2 + y^2) - R, z)| - r |`.
//!
//! Surface coordinates (neither pbrt nor Mitsuba has a torus; these follow their
//! angle-over-range convention): the local point is
//! `((R + r cos theta) cos phi, (R + r cos theta) sin phi, r sin theta)` with
//! `u = phi / (2 pi)` around the axis and `v = theta / (2 pi)` around the tube
//! (`v = 0` on the outer equator), both in `[0, 1)`;
//! `dp/du = 2 pi (-y, x, 0)`, `dp/dv = 2 pi r (-sin theta cos phi, -sin theta sin phi, cos theta)`.

mod polynomial;

use polynomial::{roots_in, Poly};

use std::sync::Arc;

use super::surface::azimuth;
use super::{placed, Shape, ShapeKind, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{orthonormal_basis, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `torus`: placed as an instance under a transform.
pub const KIND: ShapeKind = Kind {
    name: "torus",
    summary: "a ring torus",
    params: &[
        Param::new("center", T::Point, "", "", "centre"),
        Param::new("axis", T::Vector, "", "", "axis through the hole"),
        Param::new("major_radius", T::Number, "", "scene units", "ring radius R (axis to tube centre)"),
        Param::new("minor_radius", T::Number, "", "scene units, < R", "tube radius r"),
    ],
    build: |p, m| {
        let (c, axis) = (p.required_vec3("center")?, p.required_vec3("axis")?);
        let (major, minor) = (p.required_number("major_radius")?, p.required_number("minor_radius")?);
        let torus = Torus::new(c, axis, major, minor).map_err(|e| p.core_error(e))?;
        Ok(vec![placed(Arc::new(torus), m).map_err(|e| p.core_error(e))?])
    },
};

/// A ring torus around `axis` through `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    center: Vec3,
    /// Local frame: `frame_x, frame_y, axis` is right-handed and orthonormal.
    frame_x: Vec3,
    frame_y: Vec3,
    axis: Vec3,
    major_radius: f64,
    minor_radius: f64,
}

impl Torus {
    /// A torus with centre `center`, symmetry axis `axis` (any length), major radius
    /// `major_radius` (axis to tube centre) and minor radius `minor_radius` (tube),
    /// `0 < minor_radius < major_radius`, all finite.
    pub fn new(center: Vec3, axis: Vec3, major_radius: f64, minor_radius: f64) -> Result<Torus, Error> {
        if !center.is_finite() {
            return Err(Error::invalid("center", "must be finite"));
        }
        let axis = axis.try_normalize().ok_or_else(|| Error::invalid("axis", "must be a non-zero finite vector"))?;
        if !(minor_radius > 0.0 && minor_radius.is_finite()) {
            return Err(Error::invalid("minor_radius", format!("must be a positive number, got {minor_radius}")));
        }
        if !(major_radius > minor_radius && major_radius.is_finite()) {
            return Err(Error::invalid(
                "major_radius",
                format!("must be finite and larger than the minor radius {minor_radius}, got {major_radius}"),
            ));
        }
        let (frame_x, frame_y) = orthonormal_basis(axis);
        Ok(Torus { center, frame_x, frame_y, axis, major_radius, minor_radius })
    }

    /// Centre.
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// Unit symmetry axis (local `+z`).
    pub fn axis(&self) -> Vec3 {
        self.axis
    }

    /// Major radius `R`: from the axis to the centre of the tube.
    pub fn major_radius(&self) -> f64 {
        self.major_radius
    }

    /// Minor radius `r`: of the tube.
    pub fn minor_radius(&self) -> f64 {
        self.minor_radius
    }

    #[inline]
    fn local_from_world(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.frame_x), v.dot(self.frame_y), v.dot(self.axis))
    }

    #[inline]
    fn world_from_local(&self, v: Vec3) -> Vec3 {
        self.frame_x * v.x + self.frame_y * v.y + self.axis * v.z
    }

    /// `f(p)` in the local frame (see the module docs).
    pub fn implicit_local(&self, p: Vec3) -> f64 {
        let (rr, r) = (self.major_radius * self.major_radius, self.minor_radius * self.minor_radius);
        let g = p.length_squared() + rr - r;
        g * g - 4.0 * rr * (p.x * p.x + p.y * p.y)
    }

    /// Signed distance from the surface of the local point `p` (negative inside the tube).
    pub fn distance_local(&self, p: Vec3) -> f64 {
        (p.x.hypot(p.y) - self.major_radius).hypot(p.z) - self.minor_radius
    }

    /// Unit outward normal at the local point `p`, from the gradient of `f`.
    fn normal_local(&self, p: Vec3) -> Vec3 {
        let rr = self.major_radius * self.major_radius;
        let g = p.length_squared() + rr - self.minor_radius * self.minor_radius;
        let grad = 4.0 * g * p - 8.0 * rr * Vec3::new(p.x, p.y, 0.0);
        // The gradient of a ring torus vanishes only off the surface (on the axis
        // between the poles, or on the core circle); fall back to the tube direction.
        grad.try_normalize().unwrap_or_else(|| {
            let core = Vec3::new(p.x, p.y, 0.0).normalize_or(Vec3::X) * self.major_radius;
            (p - core).normalize_or(Vec3::Z)
        })
    }

    /// The quartic in `u` for the local ray `o + d u`, with error magnitudes.
    fn quartic(&self, o: Vec3, d: Vec3) -> Poly {
        let rr4 = 4.0 * self.major_radius * self.major_radius;
        let r2 = self.minor_radius * self.minor_radius;
        let a = d.length_squared();
        let b = o.dot(d);
        let c = o.length_squared() + rr4 * 0.25 - r2;
        let e = d.x * d.x + d.y * d.y;
        let h = o.x * d.x + o.y * d.y;
        let k = o.x * o.x + o.y * o.y;
        // Magnitudes: sums of the absolute values of the terms (see polynomial.rs).
        let mb = (o * d).abs().element_sum();
        let mc = o.length_squared() + rr4 * 0.25 + r2;
        let mh = (o.x * d.x).abs() + (o.y * d.y).abs();
        Poly {
            a: [c * c - rr4 * k, 4.0 * b * c - 2.0 * rr4 * h, 4.0 * b * b + 2.0 * a * c - rr4 * e, 4.0 * a * b, a * a],
            m: [mc * mc + rr4 * k, 4.0 * mb * mc + 2.0 * rr4 * mh, 4.0 * mb * mb + 2.0 * a * mc + rr4 * e, 4.0 * a * mb, a * a],
            n: 4,
        }
    }
}

impl Shape for Torus {
    fn bounds(&self) -> Aabb {
        // Along world axis i the ring reaches R * sqrt(1 - axis_i^2), the tube r further.
        let reach = (Vec3::ONE - self.axis * self.axis).max(Vec3::ZERO).map(f64::sqrt) * self.major_radius + Vec3::splat(self.minor_radius);
        Aabb::new(self.center - reach, self.center + reach)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let o = self.local_from_world(ray.origin - self.center);
        let d = self.local_from_world(ray.dir);
        let (big, small) = (self.major_radius, self.minor_radius);
        // The local box, a hair larger so that rounding cannot cut off a tangent hit.
        let pad = 16.0 * f64::EPSILON * (big + small);
        let half = Vec3::new(big + small, big + small, small) + Vec3::splat(pad);
        let (enter, exit) = Aabb::new(-half, half).hit_interval(o, d.recip(), t_min, t_max)?;
        // Solve from the box entry: coefficients of the torus's own size.
        let start = o + d * enter;
        let poly = self.quartic(start, d);
        let (u, t) =
            roots_in(&poly, 0.0, exit - enter).as_slice().iter().map(|&u| (u, enter + u)).find(|&(_, t)| t > t_min && t < t_max)?;
        let p = start + d * u;
        let normal = self.world_from_local(self.normal_local(p)).normalize();
        Some(SurfaceHit {
            t,
            normal,
            shading_normal: normal,
            error: self.distance_local(p).abs(),
            primitive_index: SurfaceHit::NO_PRIMITIVE,
        })
    }

    fn surface_coords(&self, p: Vec3, n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        let q = self.local_from_world(p - self.center);
        let rho = q.x.hypot(q.y);
        if !(rho > 0.0) {
            return SurfaceCoords::unparametrized(n);
        }
        let phi = azimuth(q.x, q.y);
        let theta = azimuth(rho - self.major_radius, q.z);
        let (sin_t, cos_t) = theta.sin_cos();
        let tau = std::f64::consts::TAU;
        let dpdu = Vec3::new(-q.y, q.x, 0.0) * tau;
        let dpdv = Vec3::new(-sin_t * phi.cos(), -sin_t * phi.sin(), cos_t) * (tau * self.minor_radius);
        SurfaceCoords::new([phi / tau, theta / tau], self.world_from_local(dpdu), self.world_from_local(dpdv))
    }
}

#[cfg(test)]
mod tests;
