//! Planar shapes: the infinite plane, a bounded rectangle (parallelogram) and a disk.
//!
//! All three solve the lecture's plane equation `(ray(t) - p0).n = 0`, i.e.
//! `t = (p0 - s).n / (d.n)`, then test whether the point lies inside the bounds.
//! They are infinitely thin, with the same material on both sides; `normal` is the
//! side called outward.
//!
//! Surface coordinates:
//!
//! | shape | `(u, v)` | `dp/du`, `dp/dv` |
//! |---|---|---|
//! | plane | `((p - point).t, (p - point).b)`, scene units, with `(t, b)` the frame [`crate::math::orthonormal_basis`] builds around the normal | `t`, `b` |
//! | rectangle | `p = corner + u edge_u + v edge_v`, `[0, 1]` over the face | `edge_u`, `edge_v` |
//! | disk | pbrt-v4's: `u = phi / (2 pi)` with `phi` measured from `t` towards `b` (the normal's frame), `v = 1 - r / R` (1 at the centre, 0 on the rim); `uv_layout = "radial"`: Mitsuba's ([`super::disk_uv`]) | `2 pi (-y t + x b)`, `-R (p - c) / r` |

use std::sync::Arc;

use super::disk_uv::DiskUv;
use super::{placed, Shape, ShapeKind, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{similarity_scale, Mat4, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `plane`: maps its point and its normal (by the inverse transpose).
pub const PLANE_KIND: ShapeKind = Kind {
    name: "plane",
    summary: "an infinite plane; `normal` is the outward side",
    params: &[Param::new("point", T::Point, "", "", "a point on the plane"), Param::new("normal", T::Vector, "", "", "outward normal")],
    build: |p, m| {
        let (point, normal) = (p.required_vec3("point")?, p.required_vec3("normal")?);
        let normal = if *m == Mat4::IDENTITY { normal } else { m.inverse().transpose().transform_vector3(normal) };
        Ok(vec![Arc::new(Plane::new(m.transform_point3(point), normal).map_err(|e| p.core_error(e))?)])
    },
};

/// `rectangle`: maps its corner and edges.
pub const RECTANGLE_KIND: ShapeKind = Kind {
    name: "rectangle",
    summary: "a parallelogram; outward normal `edge_u x edge_v`",
    params: &[
        Param::new("corner", T::Point, "", "", "a corner"),
        Param::new("edge_u", T::Vector, "", "", "first edge from the corner"),
        Param::new("edge_v", T::Vector, "", "", "second edge from the corner"),
    ],
    build: |p, m| {
        let (c, u, v) = (p.required_vec3("corner")?, p.required_vec3("edge_u")?, p.required_vec3("edge_v")?);
        let r = Rectangle::new(m.transform_point3(c), m.transform_vector3(u), m.transform_vector3(v));
        Ok(vec![Arc::new(r.map_err(|e| p.core_error(e))?)])
    },
};

/// `disk`: stays a disk under a similarity, else becomes an instance.
pub const DISK_KIND: ShapeKind = Kind {
    name: "disk",
    summary: "a disk",
    params: &[
        Param::new("center", T::Point, "", "", "centre"),
        Param::new("normal", T::Vector, "", "", "outward normal"),
        Param::new("radius", T::Number, "", "scene units", "radius"),
        Param::new(
            "uv_layout",
            T::String,
            "\"polar\"",
            "",
            "`\"polar\"`: pbrt's `(phi / 2 pi, 1 - r / R)`; `\"radial\"`: Mitsuba's `(r / R, 1 - phi / 2 pi)` in the disk's own frame",
        ),
    ],
    build: |p, m| {
        let (c, n, r) = (p.required_vec3("center")?, p.required_vec3("normal")?, p.required_number("radius")?);
        let radial = p.choice("uv_layout", &["polar", "radial"])? == "radial";
        let local = |d: Disk| if radial { d.with_radial_uv() } else { d };
        let shape: Result<Arc<dyn Shape>, Error> = match (*m == Mat4::IDENTITY, similarity_scale(m)) {
            (true, _) => Disk::new(c, n, r).map(|d| Arc::new(local(d)) as Arc<dyn Shape>),
            (false, Some(s)) => Disk::new(c, n, r).and_then(|d| local(d).similar(m, s)).map(|d| Arc::new(d) as Arc<dyn Shape>),
            (false, None) => Disk::new(c, n, r).and_then(|d| placed(Arc::new(local(d)), m)),
        };
        Ok(vec![shape.map_err(|e| p.core_error(e))?])
    },
};

/// Ray parameter of the hit with the plane through `point` with unit `normal`,
/// `None` when the ray is parallel to it or the hit is outside `(t_min, t_max)`.
#[inline]
fn plane_t(ray: &Ray, point: Vec3, normal: Vec3, t_min: f64, t_max: f64) -> Option<f64> {
    let denom = ray.dir.dot(normal);
    if denom == 0.0 {
        return None;
    }
    let t = (point - ray.origin).dot(normal) / denom;
    (t > t_min && t < t_max).then_some(t)
}

fn unit_normal(normal: Vec3) -> Result<Vec3, Error> {
    normal.try_normalize().ok_or_else(|| Error::invalid("normal", "must be a non-zero finite vector"))
}

/// The infinite plane through `point` with normal `normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point of the plane.
    pub point: Vec3,
    /// Unit normal (outward side).
    pub normal: Vec3,
}

impl Plane {
    /// A plane; `normal` need not be unit.
    pub fn new(point: Vec3, normal: Vec3) -> Result<Plane, Error> {
        if !point.is_finite() {
            return Err(Error::invalid("point", "must be finite"));
        }
        Ok(Plane { point, normal: unit_normal(normal)? })
    }
}

impl Shape for Plane {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn bounds(&self) -> Aabb {
        Aabb::INFINITE
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        plane_t(ray, self.point, self.normal, t_min, t_max).map(|t| SurfaceHit::new(t, self.normal))
    }

    fn surface_coords(&self, p: Vec3, _n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        let (t, b) = crate::math::orthonormal_basis(self.normal);
        let d = p - self.point;
        SurfaceCoords::new([d.dot(t), d.dot(b)], t, b)
    }
}

/// The parallelogram `corner + u * edge_u + v * edge_v`, `u, v` in `[0, 1]`; a
/// rectangle when the edges are perpendicular. The outward normal is
/// `edge_u x edge_v`, normalized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rectangle {
    /// One corner.
    pub corner: Vec3,
    /// First edge from the corner.
    pub edge_u: Vec3,
    /// Second edge from the corner.
    pub edge_v: Vec3,
    normal: Vec3,
    /// Rows of the inverse of the 2x2 Gram matrix, to get (u, v) of a point.
    dual_u: Vec3,
    dual_v: Vec3,
}

impl Rectangle {
    /// A parallelogram from a corner and two edges, which must not be parallel.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Result<Rectangle, Error> {
        if !(corner.is_finite() && edge_u.is_finite() && edge_v.is_finite()) {
            return Err(Error::invalid("rectangle", "corner and edges must be finite"));
        }
        let cross = edge_u.cross(edge_v);
        let area2 = cross.length_squared();
        if !(area2 > 0.0) {
            return Err(Error::DegenerateGeometry("rectangle edges are parallel or zero".into()));
        }
        // Dual basis: dual_u.edge_u = 1, dual_u.edge_v = 0 (and symmetric).
        let dual_u = edge_v.cross(cross) / area2;
        let dual_v = cross.cross(edge_u) / area2;
        Ok(Rectangle { corner, edge_u, edge_v, normal: cross / area2.sqrt(), dual_u, dual_v })
    }

    /// The axis-aligned rectangle `y = height`, `x0 <= x <= x1`, `z0 <= z <= z1`,
    /// facing +y (a table top or a floor).
    pub fn horizontal(height: f64, x0: f64, x1: f64, z0: f64, z1: f64) -> Result<Rectangle, Error> {
        // edge_u = +z, edge_v = +x gives the normal +z x +x = +y.
        Rectangle::new(Vec3::new(x0, height, z0), Vec3::new(0.0, 0.0, z1 - z0), Vec3::new(x1 - x0, 0.0, 0.0))
    }

    /// Unit outward normal.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// The six faces of the box `[min, max]` placed by the affine `transform`, each
    /// with its normal pointing out of the box, in the order +x, -x, +y, -y, +z, -z.
    pub fn box_faces(min: Vec3, max: Vec3, transform: &crate::math::Mat4) -> Result<[Rectangle; 6], Error> {
        let d = max - min;
        let (dx, dy, dz) = (Vec3::new(d.x, 0.0, 0.0), Vec3::new(0.0, d.y, 0.0), Vec3::new(0.0, 0.0, d.z));
        // (corner, edge_u, edge_v) with edge_u x edge_v pointing out of the box.
        let faces = [
            (Vec3::new(max.x, min.y, min.z), dy, dz),
            (min, dz, dy),
            (Vec3::new(min.x, max.y, min.z), dz, dx),
            (min, dx, dz),
            (Vec3::new(min.x, min.y, max.z), dx, dy),
            (min, dy, dx),
        ];
        let face = |(corner, u, v): (Vec3, Vec3, Vec3)| {
            Rectangle::new(transform.transform_point3(corner), transform.transform_vector3(u), transform.transform_vector3(v))
        };
        Ok([face(faces[0])?, face(faces[1])?, face(faces[2])?, face(faces[3])?, face(faces[4])?, face(faces[5])?])
    }
}

impl Shape for Rectangle {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn inlined(self: std::sync::Arc<Self>) -> Option<super::Inlined> {
        Some(super::Inlined::Rectangle(self))
    }

    fn lane(&self) -> Option<crate::accel::LaneShape> {
        Some(crate::accel::LaneShape::Rectangle(crate::accel::RectangleLane {
            corner: self.corner,
            normal: self.normal,
            dual_u: self.dual_u,
            dual_v: self.dual_v,
            edge_u: self.edge_u,
            edge_v: self.edge_v,
        }))
    }

    fn is_convex(&self) -> bool {
        true
    }

    fn area(&self) -> Option<f64> {
        Some(self.edge_u.cross(self.edge_v).length())
    }

    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        Some((self.corner + self.edge_u * u.0 + self.edge_v * u.1, self.normal))
    }

    fn bounds(&self) -> Aabb {
        let c = self.corner;
        Aabb::from_points([c, c + self.edge_u, c + self.edge_v, c + self.edge_u + self.edge_v])
    }

    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let t = self.hit_t(ray, t_min, t_max)?;
        Some(SurfaceHit::new(t, self.normal))
    }

    /// Shadow rays skip building the hit record (a floor or a wall is tested by
    /// most shadow rays of a scene).
    #[inline(always)]
    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.hit_t(ray, t_min, t_max).is_some()
    }

    fn surface_coords(&self, p: Vec3, _n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        let local = p - self.corner;
        let uv = [local.dot(self.dual_u).clamp(0.0, 1.0), local.dot(self.dual_v).clamp(0.0, 1.0)];
        SurfaceCoords::new(uv, self.edge_u, self.edge_v)
    }
}

impl Rectangle {
    /// The plane's parameter where the point lies inside the parallelogram:
    /// `(u, v)` in `[0, 1]^2` from the dual basis.
    #[inline]
    fn hit_t(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let t = plane_t(ray, self.corner, self.normal, t_min, t_max)?;
        let local = ray.at(t) - self.corner;
        let u = local.dot(self.dual_u);
        let v = local.dot(self.dual_v);
        ((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)).then_some(t)
    }
}

/// The disk of radius `radius` around `center` in the plane with normal `normal`
/// (a cylinder's cap, a lamp's base).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disk {
    /// Centre.
    pub center: Vec3,
    /// Unit normal (outward side).
    pub normal: Vec3,
    /// Radius.
    pub radius: f64,
    /// How its `(u, v)` are laid out.
    pub uv: DiskUv,
}

impl Disk {
    /// A disk; `normal` need not be unit, `radius` must be positive.
    pub fn new(center: Vec3, normal: Vec3, radius: f64) -> Result<Disk, Error> {
        if !center.is_finite() {
            return Err(Error::invalid("center", "must be finite"));
        }
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(Error::invalid("radius", format!("must be a positive number, got {radius}")));
        }
        Ok(Disk { center, normal: unit_normal(normal)?, radius, uv: DiskUv::Polar })
    }

    /// This disk with Mitsuba's radial `(u, v)` in the frame around its normal.
    pub fn with_radial_uv(self) -> Disk {
        let (x, y) = crate::math::orthonormal_basis(self.normal);
        Disk { uv: DiskUv::Radial { x, y }, ..self }
    }

    /// This disk placed by the similarity `m` of scale `s` (its radial frame turns with it).
    pub fn similar(self, m: &Mat4, s: f64) -> Result<Disk, Error> {
        let placed = Disk::new(m.transform_point3(self.center), m.transform_vector3(self.normal), self.radius * s)?;
        let uv = match self.uv {
            DiskUv::Polar => DiskUv::Polar,
            DiskUv::Radial { x, y } => DiskUv::Radial { x: m.transform_vector3(x) / s, y: m.transform_vector3(y) / s },
        };
        Ok(Disk { uv, ..placed })
    }
}

impl Shape for Disk {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn is_convex(&self) -> bool {
        true
    }

    fn area(&self) -> Option<f64> {
        Some(std::f64::consts::PI * self.radius * self.radius)
    }

    /// Uniform on the disk: radius `R sqrt(u0)`, angle `2 pi u1`.
    fn sample_area(&self, u: (f64, f64)) -> Option<(Vec3, Vec3)> {
        let (t, b) = crate::math::orthonormal_basis(self.normal);
        let r = self.radius * u.0.sqrt();
        let phi = 2.0 * std::f64::consts::PI * u.1;
        Some((self.center + (t * phi.cos() + b * phi.sin()) * r, self.normal))
    }

    fn bounds(&self) -> Aabb {
        // Extent along each axis: radius * sqrt(1 - n_axis^2).
        let n = self.normal;
        let half = Vec3::new((1.0 - n.x * n.x).max(0.0).sqrt(), (1.0 - n.y * n.y).max(0.0).sqrt(), (1.0 - n.z * n.z).max(0.0).sqrt())
            * self.radius;
        Aabb::new(self.center - half, self.center + half)
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let t = plane_t(ray, self.center, self.normal, t_min, t_max)?;
        ((ray.at(t) - self.center).length_squared() <= self.radius * self.radius).then(|| SurfaceHit::new(t, self.normal))
    }

    fn surface_coords(&self, p: Vec3, n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        let (t, b) = crate::math::orthonormal_basis(self.normal);
        self.uv.coords(p - self.center, self.radius, t, b, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INF: f64 = f64::INFINITY;

    /// Central difference of `p(u, v)` against the reported tangent.
    fn check_tangent(analytic: Vec3, numeric: Vec3) {
        assert!((analytic - numeric).length() <= 1e-6 * numeric.length().max(1.0), "{analytic} vs {numeric}");
    }

    #[test]
    fn surface_coordinates_of_the_planar_shapes() {
        let r = Rectangle::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -4.0)).unwrap();
        let c = r.surface_coords(Vec3::new(1.5, 0.0, -3.0), r.normal(), None);
        assert_eq!(c.uv, [0.25, 0.75]);
        assert_eq!((c.dpdu, c.dpdv), (r.edge_u, r.edge_v));

        let d = Disk::new(Vec3::new(0.0, 1.0, 0.0), Vec3::Z, 2.0).unwrap();
        let (t, b) = crate::math::orthonormal_basis(Vec3::Z);
        let at = |u: f64, v: f64| {
            let (phi, rad) = (u * std::f64::consts::TAU, (1.0 - v) * 2.0);
            d.center + (t * phi.cos() + b * phi.sin()) * rad
        };
        for (u, v) in [(0.1, 0.2), (0.7, 0.9), (0.45, 0.5)] {
            let c = d.surface_coords(at(u, v), Vec3::Z, None);
            assert!((c.uv[0] - u).abs() < 1e-12 && (c.uv[1] - v).abs() < 1e-12, "{:?}", c.uv);
            let h = 1e-6;
            check_tangent(c.dpdu, (at(u + h, v) - at(u - h, v)) / (2.0 * h));
            check_tangent(c.dpdv, (at(u, v + h) - at(u, v - h)) / (2.0 * h));
        }

        let plane = Plane::new(Vec3::new(0.0, 2.0, 0.0), Vec3::Y).unwrap();
        let c = plane.surface_coords(Vec3::new(3.0, 2.0, -1.0), Vec3::Y, None);
        assert!((plane.point + c.dpdu * c.uv[0] + c.dpdv * c.uv[1] - Vec3::new(3.0, 2.0, -1.0)).length() < 1e-14);
    }

    #[test]
    fn plane_hit_from_either_side_and_parallel_miss() {
        let p = Plane::new(Vec3::ZERO, Vec3::Y).unwrap();
        let down = p.intersect(&Ray::new(Vec3::new(1.0, 2.0, 3.0), -Vec3::Y), 0.0, INF).unwrap();
        assert_eq!(down.t, 2.0);
        assert_eq!(down.normal, Vec3::Y);
        let up = p.intersect(&Ray::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0)), 0.0, INF).unwrap();
        assert!((up.t - 2f64.sqrt()).abs() < 1e-14);
        assert!(p.intersect(&Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X), 0.0, INF).is_none());
        assert!(p.intersect(&Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::Y), 0.0, INF).is_none(), "plane behind the ray");
        assert!(Plane::new(Vec3::ZERO, Vec3::ZERO).is_err());
    }

    #[test]
    fn rectangle_inside_edges_and_outside() {
        let r = Rectangle::horizontal(0.0, -2.5, 2.5, -2.0, 2.0).unwrap();
        assert_eq!(r.normal(), Vec3::Y);
        let at = |x: f64, z: f64| r.intersect(&Ray::new(Vec3::new(x, 1.0, z), -Vec3::Y), 0.0, INF);
        assert_eq!(at(0.0, 0.0).unwrap().t, 1.0);
        assert!(at(2.5, 2.0).is_some(), "corner counts");
        assert!(at(2.5001, 0.0).is_none());
        assert!(at(0.0, -2.0001).is_none());
        let b = r.bounds();
        assert_eq!((b.min, b.max), (Vec3::new(-2.5, 0.0, -2.0), Vec3::new(2.5, 0.0, 2.0)));
        assert!(Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0).is_err());
    }

    #[test]
    fn slanted_parallelogram_uses_its_own_coordinates() {
        let r = Rectangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0)).unwrap();
        let hit = |x: f64, y: f64| r.intersect(&Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z), 0.0, INF).is_some();
        assert!(hit(2.9, 0.95));
        assert!(!hit(0.2, 0.5), "left of the slanted edge");
        assert!(hit(1.0, 0.5));
    }

    #[test]
    fn box_faces_point_outwards() {
        let faces = Rectangle::box_faces(Vec3::splat(-1.0), Vec3::splat(1.0), &crate::math::Mat4::IDENTITY).unwrap();
        for face in faces {
            let centre = face.corner + (face.edge_u + face.edge_v) * 0.5;
            assert!((face.normal() - centre).length() < 1e-12, "face at {centre} points {}", face.normal());
        }
        let placed = crate::math::Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0)) * crate::math::Mat4::from_scale(Vec3::splat(2.0));
        let hit = Rectangle::box_faces(Vec3::splat(-1.0), Vec3::splat(1.0), &placed).unwrap()[1]
            .intersect(&Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::X), 0.0, INF)
            .unwrap();
        assert!((hit.t - 3.0).abs() < 1e-12 && (hit.normal + Vec3::X).length() < 1e-12);
    }

    #[test]
    fn disk_radius_and_bounds() {
        let d = Disk::new(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 0.5).unwrap();
        assert!(d.intersect(&Ray::new(Vec3::new(0.49, 2.0, 0.0), -Vec3::Y), 0.0, INF).is_some());
        assert!(d.intersect(&Ray::new(Vec3::new(0.36, 2.0, 0.36), -Vec3::Y), 0.0, INF).is_none());
        let b = d.bounds();
        assert!((b.max - Vec3::new(0.5, 1.0, 0.5)).length() < 1e-15);
        let tilted = Disk::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), 1.0).unwrap();
        let b = tilted.bounds();
        assert!((b.max.x - 0.5f64.sqrt()).abs() < 1e-12 && (b.max.z - 1.0).abs() < 1e-12);
    }
}
