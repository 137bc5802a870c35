//! Axis-aligned bounding boxes and the ray slab test.

use crate::math::Vec3;
use crate::ray::Ray;

/// An axis-aligned box `[min, max]`. The empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box that contains nothing; the identity of `union`.
    pub const EMPTY: Aabb = Aabb { min: Vec3::INFINITY, max: Vec3::NEG_INFINITY };
    /// The box that contains everything (unbounded shapes such as an infinite plane).
    pub const INFINITE: Aabb = Aabb { min: Vec3::NEG_INFINITY, max: Vec3::INFINITY };

    /// The box spanned by two corners, in any order.
    pub fn new(a: Vec3, b: Vec3) -> Aabb {
        Aabb { min: a.min(b), max: a.max(b) }
    }

    /// The smallest box holding every point of `points`.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| b.grow(p))
    }

    /// This box enlarged to hold `p`.
    #[inline]
    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    /// The smallest box holding both.
    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// The common part of both (possibly empty).
    #[inline]
    pub fn intersection(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.max(other.min), max: self.max.min(other.max) }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// True when every bound is a finite number.
    pub fn is_finite(&self) -> bool {
        !self.is_empty() && self.min.is_finite() && self.max.is_finite()
    }

    /// Centre point.
    #[inline]
    pub fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Edge lengths.
    #[inline]
    pub fn extent(&self) -> Vec3 {
        self.max - self.min
    }

    /// Surface area `2 (xy + yz + zx)`, 0 for an empty box; the SAH cost weight.
    #[inline]
    pub fn surface_area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// True when `p` lies in the closed box.
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Slab test (Kay and Kajiya 1986): the parameter interval where `ray` is inside
    /// the box, clipped to `[t_min, t_max]`, or `None`. `inv_dir` is `1 / ray.dir`
    /// (infinite components are fine: IEEE arithmetic gives the right slabs). A ray
    /// parallel to a slab and lying exactly in one of its planes gives `0 * inf = NaN`;
    /// it is inside the closed slab, so that axis then puts no bound on the interval.
    #[inline]
    pub fn hit_interval(&self, origin: Vec3, inv_dir: Vec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let in_plane = t0.cmpne(t0) | t1.cmpne(t1);
        let near = Vec3::select(in_plane, Vec3::NEG_INFINITY, t0.min(t1));
        let far = Vec3::select(in_plane, Vec3::INFINITY, t0.max(t1));
        let enter = t_min.max(near.x).max(near.y).max(near.z);
        // Robust far bound (Ize 2013): one ulp-scale widening so that a ray grazing a
        // face or an edge still enters the box.
        let exit = t_max.min(far.x).min(far.y).min(far.z) * (1.0 + 4.0 * f64::EPSILON);
        (enter <= exit).then_some((enter, exit))
    }

    /// Convenience form of [`Aabb::hit_interval`] for one ray.
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        self.hit_interval(ray.origin, ray.dir.recip(), t_min, t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_test_hits_misses_and_grazes() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let r = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        let (t0, t1) = b.hit(&r, 0.0, f64::INFINITY).unwrap();
        assert!((t0 - 4.0).abs() < 1e-12 && (t1 - 6.0).abs() < 1e-9);
        assert!(b.hit(&Ray::new(Vec3::new(0.0, 2.0, -5.0), Vec3::Z), 0.0, f64::INFINITY).is_none());
        // Parallel to a face, just inside it (direction has zero components: infinite inverses).
        assert!(b.hit(&Ray::new(Vec3::new(1.0 - 1e-12, 0.0, -5.0), Vec3::Z), 0.0, f64::INFINITY).is_some());
        assert!(b.hit(&Ray::new(Vec3::new(1.0 + 1e-12, 0.0, -5.0), Vec3::Z), 0.0, f64::INFINITY).is_none());
        assert!(b.hit(&r, 0.0, 3.0).is_none());
        // Lying exactly in a face plane (0 * inf = NaN), either direction sign.
        for dir in [Vec3::Z, -Vec3::Z, Vec3::new(0.0, -0.0, 1.0)] {
            let on_face = Ray::new(Vec3::new(1.0, 0.0, -5.0 * dir.z), dir);
            assert!(b.hit(&on_face, 0.0, f64::INFINITY).is_some(), "{dir}");
            let on_edge = Ray::new(Vec3::new(-1.0, 1.0, -5.0 * dir.z), dir);
            assert!(b.hit(&on_edge, 0.0, f64::INFINITY).is_some(), "{dir}");
        }
        let flat = Aabb::new(Vec3::new(0.0, -1.0, -1.0), Vec3::new(0.0, 1.0, 1.0));
        assert!(flat.hit(&Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), 0.0, f64::INFINITY).is_some());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        assert!((b.surface_area() - 24.0).abs() < 1e-12);
    }
}
