//! Sphere: `|r - c|^2 = R^2`.
//!
//! | parameter | type | default | meaning |
//! |-----------|------|---------|---------|
//! | `center` | point | required | centre |
//! | `radius` | number | required | radius, > 0 |
//!
//! Under a rotation, translation and uniform scale it stays a sphere (the
//! rotation is kept for its surface coordinates); under any other affine
//! transform it becomes the ellipsoid quadric it maps to.
//!
//! Surface coordinates (pbrt-v4's sphere): with `q = R^T (p - c)` the point in
//! the sphere's own frame (`R` the rotation it was placed by, the identity when
//! it was not), `phi = atan2(q.y, q.x)` in `[0, 2 pi)` and
//! `theta = acos(q.z / r)`, `u = phi / (2 pi)`, `v = (pi - theta) / pi` (0 at the
//! `-z` pole, 1 at `+z`), `dp/du = R 2 pi (-q.y, q.x, 0)` and
//! `dp/dv = R (-pi) (q.z cos phi, q.z sin phi, -r sin theta)`.

use std::sync::Arc;

use glam::DMat3;

use super::surface::{revolution, Meridian};
use super::{Quadric, Shape, ShapeKind, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{similarity_scale, Mat4, Vec3};
use crate::params::{Kind, Param, ParamResult, ParamType, Params};
use crate::ray::Ray;
use crate::Error;

/// The `sphere` kind.
pub const KIND: ShapeKind = Kind {
    name: "sphere",
    summary: "a sphere",
    params: &[
        Param::new("center", ParamType::Point, "", "scene units", "centre"),
        Param::new("radius", ParamType::Number, "", "scene units, > 0", "radius"),
    ],
    build,
};

fn build(p: &mut Params<'_>, m: &Mat4) -> ParamResult<Vec<Arc<dyn Shape>>> {
    let (c, r) = (p.required_vec3("center")?, p.required_number("radius")?);
    let shape: Arc<dyn Shape> = if *m == Mat4::IDENTITY {
        Arc::new(Sphere::new(c, r).map_err(|e| p.core_error(e))?)
    } else if let Some(s) = similarity_scale(m) {
        let rotation = DMat3::from_mat4(*m) * (1.0 / s);
        Arc::new(Sphere::new(m.transform_point3(c), r * s).map_err(|e| p.core_error(e))?.rotated(rotation))
    } else {
        Arc::new(Quadric::ellipsoid(c, Vec3::splat(r)).and_then(|q| q.transformed(*m)).map_err(|e| p.core_error(e))?)
    };
    Ok(vec![shape])
}

/// A sphere with centre `center` and radius `radius > 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius, positive.
    pub radius: f64,
    /// `1 / radius`, so that the normal costs a multiplication.
    inv_radius: f64,
    /// The rotation `R` from the sphere's own frame to the world (surface coordinates only).
    rotation: DMat3,
}

/// A ray's root on a sphere ([`Sphere::roots`]): the one reported, the
/// smaller of the two, `f - (f.d) d` and the discriminant.
struct Roots {
    t: f64,
    t0: f64,
    perpendicular: Vec3,
    discriminant: f64,
}

impl Sphere {
    /// The root `t` in `(t_min, t_max)` that [`Shape::intersect`] reports
    /// (module doc: the discriminant free of cancellation, the stable pair of
    /// roots), with what its normal is made from where `p - c` cancels.
    #[inline(always)]
    fn roots(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Roots> {
        let f = ray.origin - self.center;
        let b_half = f.dot(ray.dir);
        let perpendicular = f - ray.dir * b_half;
        let r2 = self.radius * self.radius;
        let discriminant = r2 - perpendicular.length_squared();
        if discriminant < 0.0 {
            return None;
        }
        let c = f.length_squared() - r2;
        let q = -(b_half + discriminant.sqrt().copysign(b_half));
        let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (q, c / q) };
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let t = if t0 > t_min && t0 < t_max {
            t0
        } else if t1 > t_min && t1 < t_max {
            t1
        } else {
            return None;
        };
        Some(Roots { t, t0, perpendicular, discriminant })
    }

    /// A sphere; the radius must be positive and finite and the centre finite.
    pub fn new(center: Vec3, radius: f64) -> Result<Sphere, Error> {
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(Error::invalid("radius", format!("must be a positive number, got {radius}")));
        }
        if !center.is_finite() {
            return Err(Error::invalid("center", "must be finite"));
        }
        Ok(Sphere { center, radius, inv_radius: 1.0 / radius, rotation: DMat3::IDENTITY })
    }

    /// This sphere with its own frame turned by the orthogonal `rotation` (the
    /// surface is the same; its `(u, v)` turn with it).
    pub fn rotated(mut self, rotation: DMat3) -> Sphere {
        self.rotation = rotation;
        self
    }
}

impl Shape for Sphere {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn inlined(self: std::sync::Arc<Self>) -> Option<super::Inlined> {
        Some(super::Inlined::Sphere(self))
    }

    fn is_convex(&self) -> bool {
        true
    }

    /// The sphere meets a box when the box's nearest point is no farther from
    /// the centre than the radius and its farthest corner no nearer; both with
    /// a relative allowance far above the rounding of a reported hit.
    fn may_meet(&self, region: &Aabb) -> bool {
        if region.is_empty() {
            return false;
        }
        let nearest = (self.center.clamp(region.min, region.max) - self.center).length();
        let farthest = (region.min - self.center).abs().max((region.max - self.center).abs()).length();
        let slack = 1e-9 * (self.radius + farthest + self.center.abs().max_element());
        nearest <= self.radius + slack && farthest >= self.radius - slack
    }

    fn area(&self) -> Option<f64> {
        Some(4.0 * std::f64::consts::PI * self.radius * self.radius)
    }

    /// Uniform on the sphere: `z = 1 - 2 u0`, `phi = 2 pi u1` (Archimedes).
    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        let z = 1.0 - 2.0 * u.0;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * std::f64::consts::PI * u.1;
        let n = Vec3::new(r * phi.cos(), r * phi.sin(), z);
        Some((self.center + n * self.radius, n))
    }

    fn bounds(&self) -> Aabb {
        Aabb::new(self.center - Vec3::splat(self.radius), self.center + Vec3::splat(self.radius))
    }

    /// Substituting the ray into the sphere equation gives
    /// `t^2 + 2 ((s - c).d) t + |s - c|^2 - R^2 = 0` for a unit direction `d`; the
    /// smaller root in the interval wins, the normal is `(p - c) / R`.
    ///
    /// The discriminant is computed as `R^2 - |f - (f.d) d|^2` with `f = s - c`
    /// (Haines et al., Ray Tracing Gems ch. 7), free of the cancellation in `b^2 - c`,
    /// so a small sphere far from the ray origin keeps its precision; the roots use
    /// the stable pair `q = -(b + sign(b) sqrt(D))`, `t = q` and `t = c / q`.
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let Roots { t, t0, perpendicular, discriminant } = self.roots(ray, t_min, t_max)?;
        let mut normal = (ray.at(t) - self.center) * self.inv_radius;
        if (normal.length_squared() - 1.0).abs() > 1e-6 {
            // Far from the origin `ray.at(t) - c` cancels (a ray from 1e17 to a
            // unit sphere gives 0, a NaN normal). The same vector from the
            // precise parts: `p - c = f + t d = perpendicular + (t - t_c) d`,
            // where `t_c = -f.d` and `t - t_c = -+sqrt(discriminant)`.
            let along = if t == t0 { -discriminant.sqrt() } else { discriminant.sqrt() };
            normal = (perpendicular + ray.dir * along) * self.inv_radius;
        }
        Some(SurfaceHit::new(t, normal.normalize()))
    }

    /// `intersect`'s parameter without its normal (whose square root and
    /// division were most of a bulb's test in `luxo`'s shadow rays): the same
    /// roots, so the same bits (a test compares the two).
    #[inline(always)]
    fn first_t(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.roots(ray, t_min, t_max).map(|r| r.t)
    }

    fn surface_coords(&self, _p: Vec3, n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        // On the sphere itself, not a rounding error off it, so that v stays in [0, 1].
        let q = self.rotation.transpose() * (n * self.radius);
        match revolution(q, q * self.inv_radius, Meridian::Polar) {
            Some(c) => SurfaceCoords::new(c.uv, self.rotation * c.dpdu, self.rotation * c.dpdv),
            // At a pole phi is undefined: u = 0, and v is 0 or 1.
            None => {
                let v = if q.z > 0.0 { 1.0 } else { 0.0 };
                SurfaceCoords { uv: [0.0, v], ..SurfaceCoords::unparametrized(n) }
            }
        }
    }

    #[inline(always)]
    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let f = ray.origin - self.center;
        let b_half = f.dot(ray.dir);
        let perpendicular = f - ray.dir * b_half;
        let discriminant = self.radius * self.radius - perpendicular.length_squared();
        if discriminant < 0.0 {
            return false;
        }
        // Unit direction: the roots are -b_half -+ sqrt(discriminant), to the
        // precision a shadow test needs.
        let root = discriminant.sqrt();
        let (t0, t1) = (-b_half - root, -b_half + root);
        (t0 > t_min && t0 < t_max) || (t1 > t_min && t1 < t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Sphere {
        Sphere::new(Vec3::ZERO, 1.0).unwrap()
    }

    #[test]
    fn hit_from_outside_returns_near_root_and_outward_normal() {
        let hit = unit().intersect(&Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-14);
        assert!((hit.normal - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-14);
    }

    #[test]
    fn hits_far_from_the_origin_keep_their_normals() {
        // See: issue 12 ("NaN from Python"): the hit point minus the centre cancels to 0 there.
        for z in [1e17, 1e30, 1e308] {
            let hit = unit().intersect(&Ray::new(Vec3::new(0.0, 0.0, z), -Vec3::Z), 0.0, f64::INFINITY).unwrap();
            assert_eq!(hit.normal, Vec3::Z, "from z = {z}");
            assert_eq!(hit.t, z, "the distance, rounded");
        }
        let s = Sphere::new(Vec3::new(3.0, -2.0, 1.0), 0.5).unwrap();
        let dir = Vec3::new(1.0, 2.0, -2.0) / 3.0;
        let hit = s.intersect(&Ray::new(s.center - dir * 1e16 + Vec3::new(0.0, 0.1, 0.05), dir), 0.0, f64::INFINITY).unwrap();
        assert!(hit.normal.is_finite() && (hit.normal.length() - 1.0).abs() < 1e-12, "{}", hit.normal);
    }

    /// `first_t` is `intersect`'s parameter, bit for bit, over rays that hit,
    /// graze and miss, from inside and outside, near and far.
    #[test]
    fn first_t_is_the_parameter_of_intersect() {
        let s = Sphere::new(Vec3::new(0.3, -0.2, 0.1), 0.7).unwrap();
        let mut rng = crate::sampling::Rng::for_sample(31, 0, 0);
        let mut hits = 0;
        for k in 0..4000 {
            let scale = [1.0, 1e3, 1e-2][k % 3];
            let origin = Vec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 6.0 * scale;
            let target = Vec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 1.6;
            let ray = Ray::unit(origin, (target - origin).normalize());
            let t_max = if k % 2 == 0 { f64::INFINITY } else { rng.uniform() * 8.0 * scale };
            let full = s.intersect(&ray, 0.0, t_max).map(|h| h.t.to_bits());
            assert_eq!(s.first_t(&ray, 0.0, t_max).map(f64::to_bits), full, "{ray:?} to {t_max}");
            hits += usize::from(full.is_some());
        }
        assert!(hits > 1000 && hits < 3900, "{hits} hits of 4000");
    }

    #[test]
    fn miss_and_tangent() {
        let s = unit();
        assert!(s.intersect(&Ray::new(Vec3::new(0.0, 1.0001, -3.0), Vec3::Z), 0.0, f64::INFINITY).is_none());
        let tangent = s.intersect(&Ray::new(Vec3::new(0.0, 1.0, -3.0), Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((tangent.t - 3.0).abs() < 1e-6);
        assert!((tangent.normal - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn ray_starting_inside_hits_far_side() {
        let hit = unit().intersect(&Ray::new(Vec3::ZERO, Vec3::X), 0.0, f64::INFINITY).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-14);
        assert!((hit.normal - Vec3::X).length() < 1e-14, "outward normal, not yet flipped");
    }

    #[test]
    fn sphere_behind_ray_and_interval_limits() {
        let s = unit();
        assert!(s.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), Vec3::Z), 0.0, f64::INFINITY).is_none());
        assert!(s.intersect(&Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z), 0.0, 1.5).is_none());
    }

    #[test]
    fn tiny_sphere_far_away_keeps_precision() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, 1e6), 1e-3).unwrap();
        let hit = s.intersect(&Ray::new(Vec3::ZERO, Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((hit.t - (1e6 - 1e-3)).abs() < 1e-8, "t = {}", hit.t);
    }

    /// `(u, v)` at known points, and `dp/du`, `dp/dv` against central differences
    /// of the parametrization `p(u, v)`.
    #[test]
    fn surface_coordinates_follow_pbrt() {
        let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0).unwrap();
        let at = |u: f64, v: f64| {
            let (phi, theta) = (u * std::f64::consts::TAU, std::f64::consts::PI * (1.0 - v));
            s.center + Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()) * s.radius
        };
        for (u, v) in [(0.1, 0.3), (0.6, 0.8), (0.9, 0.5)] {
            let p = at(u, v);
            let c = s.surface_coords(p, (p - s.center) / s.radius, None);
            assert!((c.uv[0] - u).abs() < 1e-12 && (c.uv[1] - v).abs() < 1e-12, "{:?} vs ({u}, {v})", c.uv);
            let h = 1e-6;
            let dpdu = (at(u + h, v) - at(u - h, v)) / (2.0 * h);
            let dpdv = (at(u, v + h) - at(u, v - h)) / (2.0 * h);
            assert!((c.dpdu - dpdu).length() < 1e-6 * dpdu.length(), "{} vs {dpdu}", c.dpdu);
            assert!((c.dpdv - dpdv).length() < 1e-6 * dpdv.length(), "{} vs {dpdv}", c.dpdv);
        }
        // A rotation turns the coordinates with the sphere: +x of the frame goes to +y.
        let turned = Sphere::new(Vec3::ZERO, 1.0).unwrap().rotated(DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2));
        let c = turned.surface_coords(Vec3::Y, Vec3::Y, None);
        assert!(c.uv[0].abs() < 1e-12 && (c.uv[1] - 0.5).abs() < 1e-12, "{:?}", c.uv);
        assert_eq!(unit().surface_coords(Vec3::Z, Vec3::Z, None).uv, [0.0, 1.0], "the pole");
    }

    #[test]
    fn rejects_bad_radius() {
        assert!(Sphere::new(Vec3::ZERO, 0.0).is_err());
        assert!(Sphere::new(Vec3::ZERO, f64::NAN).is_err());
    }

    /// Every hit of random rays lies in each box placed around it, from a
    /// billionth to the whole of the ball's size, where `may_meet` is true;
    /// boxes wholly inside or outside the ball are ruled out.
    #[test]
    fn may_meet_holds_every_hit() {
        let mut rng = crate::sampling::Rng::for_sample(41, 0, 0);
        let mut rand = move || rng.uniform();
        for (centre, radius) in [(Vec3::ZERO, 1.0), (Vec3::new(3e5, -1e5, 2e5), 0.5), (Vec3::new(0.1, 0.2, 0.3), 1e-4)] {
            let ball = Sphere::new(centre, radius).unwrap();
            let mut hits = 0;
            for _ in 0..2000 {
                let origin = centre + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 6.0 * radius;
                let target = centre + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 2.0 * radius;
                let ray = Ray::new(origin, target - origin);
                let Some(hit) = ball.intersect(&ray, 0.0, f64::INFINITY) else { continue };
                hits += 1;
                let p = ray.at(hit.t);
                let extent = Vec3::new(rand(), rand(), rand()) * 2.0 * radius * 10f64.powf(-9.0 + 9.0 * rand());
                let at = if rand() < 0.5 { Vec3::ZERO } else { Vec3::new(rand(), rand(), rand()) };
                let region = Aabb::new(p - extent * at, p - extent * at + extent);
                assert!(ball.may_meet(&region), "hit {p} in {region:?}");
            }
            assert!(hits > 1000, "{hits}");
            let r = Vec3::splat(radius);
            assert!(!ball.may_meet(&Aabb::new(centre - 0.5 * r, centre + 0.5 * r)), "inside");
            assert!(!ball.may_meet(&Aabb::new(centre + 0.8 * r, centre + 2.0 * r)), "outside, within the bounds' corner");
            assert!(ball.may_meet(&Aabb::new(centre - 0.5 * r, centre + 0.6 * r)), "reaches the surface");
        }
    }
}
