//! Triangle, and the watertight ray/triangle kernel shared with [`super::TriangleMesh`].
//!
//! The lecture intersects the plane of the triangle, `t = (r1 - s).n / (d.n)`, then
//! keeps the point `p` when it lies on the inner side of all three edges,
//! `((r2 - r1) x (p - r1)).n > 0` and cyclically. Evaluated in floating point those
//! three tests are computed differently by the two triangles that share an edge, so
//! a ray through the edge can fail both: a crack through which light leaks.
//!
//! The kernel here (Woop, Benthin and Wald 2013, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1)) answers the same question in a frame where the ray is
//! the `z` axis: the vertices are translated to the ray origin, their axes permuted
//! so that `z` is the dominant direction axis, and sheared so that the direction
//! becomes `(0, 0, 1)`. The edge tests become 2D edge functions of the projected
//! vertices, `U = Cx By - Cy Bx`, `V = Ax Cy - Ay Cx`, `W = Bx Ay - By Ax`, and the
//! point is inside when they share a sign (zero counts as inside). A projected
//! vertex depends only on the vertex and the ray, and swapping an edge's two
//! vertices negates its edge function exactly, so two triangles sharing an edge
//! always agree on which side of it the ray passes: no cracks. Where an edge
//! function rounds to exactly zero it is recomputed exactly from the rounding errors
//! of its two products (the paper falls back to double precision; in `f64` the
//! error-free product via `mul_add` plays that role). Then
//! `t = (U Az + V Bz + W Cz) / (U + V + W)` and the barycentric coordinates of
//! `A, B, C` are `U, V, W` divided by the same determinant.
//!
//! Both sides of a triangle are hit; the outward normal is
//! `normalize((p1 - p0) x (p2 - p0))`, so counter-clockwise vertices (seen from
//! outside) face outward.

use std::sync::Arc;

use super::{Shape, ShapeKind, SurfaceHit};
use crate::accel::Aabb;
use crate::math::Vec3;
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `triangle`: maps its three vertices.
pub const KIND: ShapeKind = Kind {
    name: "triangle",
    summary: "a triangle; outward normal by the right-hand rule",
    params: &[Param::new("vertices", T::Array, "", "3 points", "the corners, counter-clockwise seen from outside")],
    build: |p, m| {
        let v = p.vec3_list("vertices")?.ok_or_else(|| p.error("needs `vertices` (3 points)"))?;
        let [a, b, c] = <[Vec3; 3]>::try_from(v).map_err(|v| p.key_error("vertices", format!("expected 3 points, got {}", v.len())))?;
        let [a, b, c] = [a, b, c].map(|v| m.transform_point3(v));
        Ok(vec![Arc::new(Triangle::new(a, b, c).map_err(|e| p.core_error(e))?)])
    },
};

/// A ray prepared for [`intersect_triangle`]: the axis permutation and shear that
/// map its direction to `+z`. Computed once per ray and reused for every triangle
/// it is tested against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WatertightRay {
    origin: Vec3,
    /// Permuted axes: `kz` is the direction's largest component, and `kx, ky`
    /// follow it cyclically (swapped when `dir[kz] < 0` to keep the winding).
    kx: usize,
    ky: usize,
    kz: usize,
    /// Shear `(dir[kx] / dir[kz], dir[ky] / dir[kz], 1 / dir[kz])`.
    sx: f64,
    sy: f64,
    sz: f64,
}

impl WatertightRay {
    /// Prepares `ray` (its direction must be non-zero).
    #[inline]
    pub fn new(ray: &Ray) -> WatertightRay {
        let d = ray.dir;
        let a = d.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Arrays, not `Vec3` indexing: glam's `Index` is a `match` per access,
        // which cost 4 % of a textured mesh render (BENCHMARKS.md, session 26).
        let d = d.to_array();
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        WatertightRay { origin: ray.origin, kx, ky, kz, sx: d[kx] / d[kz], sy: d[ky] / d[kz], sz: 1.0 / d[kz] }
    }

    /// A vertex relative to the origin in the sheared frame: `(x, y)` before the `z`
    /// scale, and the unscaled `z`.
    #[inline]
    fn project(&self, p: Vec3) -> (f64, f64, f64) {
        let a = (p - self.origin).to_array();
        (a[self.kx] - self.sx * a[self.kz], a[self.ky] - self.sy * a[self.kz], a[self.kz])
    }
}

/// Where a ray meets a triangle: the ray parameter and the barycentric weights of
/// the three vertices (`point = b0 p0 + b1 p1 + b2 p2`, `b0 + b1 + b2 = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter.
    pub t: f64,
    /// Weight of `p0`.
    pub b0: f64,
    /// Weight of `p1`.
    pub b1: f64,
    /// Weight of `p2`.
    pub b2: f64,
}

/// `a b - c d`, with the sign exact whenever the plain evaluation rounds to zero.
///
/// The plain form is antisymmetric in floating point (`c d - a b` is its exact
/// negation), which is what makes shared edges agree. When it is zero the two
/// rounded products are equal, so the exact value is the difference of their
/// rounding errors, each exact through `mul_add`; that difference is antisymmetric
/// too and correctly rounded, so its sign is right.
#[inline]
fn edge_function(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let ab = a * b;
    let cd = c * d;
    let e = ab - cd;
    if e != 0.0 {
        return e;
    }
    a.mul_add(b, -ab) - c.mul_add(d, -cd)
}

/// The watertight ray/triangle test (Woop, Benthin and Wald 2013) in `f64`: the hit
/// of the prepared ray with triangle `(p0, p1, p2)` when its parameter lies in the
/// open interval `(t_min, t_max)`. Both faces are hit; a degenerate triangle (or a
/// ray in its plane) never is.
#[inline]
pub fn intersect_triangle(ray: &WatertightRay, p0: Vec3, p1: Vec3, p2: Vec3, t_min: f64, t_max: f64) -> Option<TriangleHit> {
    let (ax, ay, az) = ray.project(p0);
    let (bx, by, bz) = ray.project(p1);
    let (cx, cy, cz) = ray.project(p2);
    let u = edge_function(cx, by, cy, bx);
    let v = edge_function(ax, cy, ay, cx);
    let w = edge_function(bx, ay, by, ax);
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let scaled_t = u * (ray.sz * az) + v * (ray.sz * bz) + w * (ray.sz * cz);
    let t = scaled_t / det;
    if !(t > t_min && t < t_max) {
        return None;
    }
    let inv = 1.0 / det;
    Some(TriangleHit { t, b0: u * inv, b1: v * inv, b2: w * inv })
}

/// Unit outward normal `normalize((p1 - p0) x (p2 - p0))`, or `None` for a
/// triangle with zero area (or non-finite vertices).
#[inline]
pub(crate) fn face_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Option<Vec3> {
    (p1 - p0).cross(p2 - p0).try_normalize()
}

/// A single triangle with vertices `p0, p1, p2`; counter-clockwise (seen from the
/// outside) is the front. For many triangles use [`super::TriangleMesh`], which
/// shares vertices and has its own BVH.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    p0: Vec3,
    p1: Vec3,
    p2: Vec3,
    normal: Vec3,
}

impl Triangle {
    /// A triangle; the vertices must be finite and not collinear
    /// ([`Error::DegenerateGeometry`] otherwise).
    pub fn new(p0: Vec3, p1: Vec3, p2: Vec3) -> Result<Triangle, Error> {
        if !(p0.is_finite() && p1.is_finite() && p2.is_finite()) {
            return Err(Error::invalid("triangle", "vertices must be finite"));
        }
        let normal =
            face_normal(p0, p1, p2).ok_or_else(|| Error::DegenerateGeometry(format!("triangle {p0}, {p1}, {p2} has zero area")))?;
        Ok(Triangle { p0, p1, p2, normal })
    }

    /// The three vertices in order.
    pub fn vertices(&self) -> [Vec3; 3] {
        [self.p0, self.p1, self.p2]
    }

    /// Unit outward normal.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }
}

impl Shape for Triangle {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn is_convex(&self) -> bool {
        true
    }

    fn area(&self) -> Option<f64> {
        Some(0.5 * (self.p1 - self.p0).cross(self.p2 - self.p0).length())
    }

    /// Uniform on the triangle: barycentrics `(1 - sqrt(u0), sqrt(u0) (1 - u1), sqrt(u0) u1)`.
    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        let s = u.0.sqrt();
        let p = self.p0 * (1.0 - s) + self.p1 * (s * (1.0 - u.1)) + self.p2 * (s * u.1);
        Some((p, self.normal))
    }

    fn triangles(&self) -> Option<Vec<[Vec3; 3]>> {
        Some(vec![[self.p0, self.p1, self.p2]])
    }

    fn bounds(&self) -> Aabb {
        Aabb::from_points([self.p0, self.p1, self.p2])
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let hit = intersect_triangle(&WatertightRay::new(ray), self.p0, self.p1, self.p2, t_min, t_max)?;
        Some(SurfaceHit::new(hit.t, self.normal))
    }

    /// pbrt-v4's default for a triangle without texture coordinates: the
    /// vertices are at `(0, 0)`, `(1, 0)` and `(1, 1)`.
    fn surface_coords(&self, p: Vec3, _n: Vec3, _primitive: Option<u32>) -> super::SurfaceCoords {
        let v = self.vertices();
        super::mesh::interpolated_coords(p, v, DEFAULT_UV, self.normal)
    }
}

/// Texture coordinates of a triangle's vertices when none are given (pbrt-v4's).
pub const DEFAULT_UV: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    fn unit_vector(rng: &mut Rng) -> Vec3 {
        let z = 2.0 * rng.uniform() - 1.0;
        let phi = std::f64::consts::TAU * rng.uniform();
        let s = (1.0 - z * z).sqrt();
        Vec3::new(s * phi.cos(), s * phi.sin(), z)
    }

    /// The lecture's test: plane, then the three edge inequalities. Returns the hit
    /// parameter and the smallest of the three edge values (normalized), which says
    /// how far from an edge the point is.
    fn lecture_test(ray: &Ray, p: [Vec3; 3]) -> Option<(f64, f64)> {
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let t = (p[0] - ray.origin).dot(n) / ray.dir.dot(n);
        if !(t > 0.0 && t.is_finite()) {
            return None;
        }
        let x = ray.at(t);
        let edges = [(p[1] - p[0]).cross(x - p[0]).dot(n), (p[2] - p[1]).cross(x - p[1]).dot(n), (p[0] - p[2]).cross(x - p[2]).dot(n)];
        let margin = edges.iter().copied().fold(f64::INFINITY, f64::min) / n.length_squared();
        Some((t, margin))
    }

    #[test]
    fn hits_front_and_back_with_outward_normal() {
        let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        assert_eq!(tri.normal(), Vec3::Z);
        let front = tri.intersect(&Ray::new(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((front.t - 2.0).abs() < 1e-15);
        assert_eq!(front.normal, Vec3::Z);
        let back = tri.intersect(&Ray::new(Vec3::new(0.25, 0.25, -3.0), Vec3::Z), 0.0, f64::INFINITY).unwrap();
        assert!((back.t - 3.0).abs() < 1e-15);
        assert_eq!(back.normal, Vec3::Z, "outward normal, not turned to the ray");
        assert!(tri.intersect(&Ray::new(Vec3::new(0.75, 0.75, 2.0), -Vec3::Z), 0.0, f64::INFINITY).is_none());
        assert!(tri.intersect(&Ray::new(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z), 0.0, 2.0).is_none(), "open interval");
        assert!(tri.intersect(&Ray::new(Vec3::new(0.25, 0.25, 2.0), Vec3::X), 0.0, f64::INFINITY).is_none(), "parallel");
    }

    #[test]
    fn barycentrics_reconstruct_the_point() {
        let p = [Vec3::new(1.0, 0.0, 0.5), Vec3::new(-1.0, 2.0, 0.0), Vec3::new(0.0, -1.0, 3.0)];
        let target = 0.2 * p[0] + 0.3 * p[1] + 0.5 * p[2];
        let origin = Vec3::new(4.0, 5.0, -6.0);
        let ray = Ray::new(origin, target - origin);
        let hit = intersect_triangle(&WatertightRay::new(&ray), p[0], p[1], p[2], 0.0, f64::INFINITY).unwrap();
        assert!((hit.b0 - 0.2).abs() < 1e-14 && (hit.b1 - 0.3).abs() < 1e-14 && (hit.b2 - 0.5).abs() < 1e-14);
        assert!((hit.t - (target - origin).length()).abs() < 1e-13);
    }

    #[test]
    fn agrees_with_the_lecture_test_away_from_edges() {
        let mut rng = Rng::for_sample(7, 0, 0);
        let mut hits = 0;
        for _ in 0..20_000 {
            let p = [unit_vector(&mut rng), unit_vector(&mut rng), unit_vector(&mut rng)];
            // Aim near the triangle: barycentric weights in [-0.25, 1.25) hit about a fifth of the time.
            let (u, v) = (1.5 * rng.uniform() - 0.25, 1.5 * rng.uniform() - 0.25);
            let target = p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * v;
            let origin = unit_vector(&mut rng) * 3.0;
            let ray = Ray::new(origin, target - origin);
            let watertight = intersect_triangle(&WatertightRay::new(&ray), p[0], p[1], p[2], 0.0, f64::INFINITY);
            let Some((t_lecture, margin)) = lecture_test(&ray, p) else {
                assert!(watertight.is_none());
                continue;
            };
            if margin.abs() < 1e-9 {
                continue; // too close to an edge for the lecture's test to be trusted
            }
            assert_eq!(watertight.is_some(), margin > 0.0, "ray {ray:?}, triangle {p:?}");
            if let Some(hit) = watertight {
                hits += 1;
                assert!((hit.t - t_lecture).abs() <= 1e-12 * t_lecture.max(1.0), "{} vs {t_lecture}", hit.t);
            }
        }
        assert!(hits > 3000, "the test must exercise hits, got {hits}");
    }

    #[test]
    fn shared_edge_has_no_crack() {
        // Two triangles of a quad sharing the diagonal; rays aimed at points of the
        // diagonal (rounded, so a hair to either side) must hit exactly one or both.
        let (a, b, c, d) = (Vec3::new(0.1, 0.2, 0.3), Vec3::new(1.7, 0.1, 0.4), Vec3::new(1.9, 1.3, 0.2), Vec3::new(0.3, 1.1, 0.6));
        let mut rng = Rng::for_sample(11, 0, 0);
        for _ in 0..20_000 {
            let target = a + (c - a) * rng.uniform();
            let origin = Vec3::new(0.0, 0.0, 5.0) + unit_vector(&mut rng) * 2.0;
            let ray = Ray::new(origin, target - origin);
            let w = WatertightRay::new(&ray);
            let first = intersect_triangle(&w, a, b, c, 0.0, f64::INFINITY);
            let second = intersect_triangle(&w, a, c, d, 0.0, f64::INFINITY);
            assert!(first.is_some() || second.is_some(), "crack at {target} from {origin}");
        }
    }

    #[test]
    fn exact_edge_sign_when_products_round_equal() {
        // 1e8+1 times 1e8-1 rounds to 1e16 = 1e8 * 1e8; the exact difference is -1.
        let (a, b) = (1e8 + 1.0, 1e8 - 1.0);
        assert_eq!(a * b - 1e8 * 1e8, 0.0);
        assert_eq!(edge_function(a, b, 1e8, 1e8), -1.0);
        assert_eq!(edge_function(1e8, 1e8, a, b), 1.0);
    }

    #[test]
    fn rejects_degenerate_and_non_finite() {
        assert!(matches!(Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0), Err(Error::DegenerateGeometry(_))));
        assert!(matches!(Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::Y), Err(Error::DegenerateGeometry(_))));
        assert!(Triangle::new(Vec3::new(f64::NAN, 0.0, 0.0), Vec3::X, Vec3::Y).is_err());
    }
}
