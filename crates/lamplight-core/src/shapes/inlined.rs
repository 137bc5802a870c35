//! Shapes the scene's queries test without a virtual call.
//!
//! A scene query tests each candidate object through `dyn Shape`. Around that
//! indirect call the query saves and restores every vector register the call
//! may clobber, and the hit comes back through memory: about 60 instructions a
//! test, more than a rectangle's own test (57) and two thirds of a sphere's
//! (about 90; callgrind, issue 24).
//! The most common analytic shapes hand the scene a typed reference of
//! themselves ([`Shape::inlined`]) when it is built; the query matches on it and
//! calls the very `Shape::intersect` the virtual call would reach, compiled into
//! the query. The operations are the same, so every answer is the same bits.
//!
//! Only small tests belong here: each is copied into every place of the
//! queries. Spheres and rectangles made the POV-Ray `spheres` scene 3 % faster;
//! a box's test as well made the Cornell box 2.5 % slower, so boxes keep the
//! virtual call (BENCHMARKS.md, session 28). A kind is added by one variant,
//! one arm in each match and its `Shape::inlined`.

use std::sync::Arc;

use super::{Rectangle, Shape, Sphere, SurfaceHit};
use crate::ray::Ray;

/// A shape of a kind the scene's queries test directly.
#[derive(Clone, Debug)]
pub enum Inlined {
    /// [`Sphere`].
    Sphere(Arc<Sphere>),
    /// [`Rectangle`].
    Rectangle(Arc<Rectangle>),
}

impl Inlined {
    /// [`Shape::intersect`] of the shape, without the virtual call.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        match self {
            Inlined::Sphere(s) => Shape::intersect(&**s, ray, t_min, t_max),
            Inlined::Rectangle(r) => Shape::intersect(&**r, ray, t_min, t_max),
        }
    }

    /// [`Shape::sample_area`] of the shape, without the virtual call (an area
    /// light's point, once per light sample of the path tracer).
    #[inline(always)]
    pub fn sample_area(&self, u: (f64, f64)) -> Option<(crate::math::Vec3, crate::math::Vec3)> {
        match self {
            Inlined::Sphere(s) => Shape::sample_area(&**s, u),
            Inlined::Rectangle(r) => Shape::sample_area(&**r, u),
        }
    }

    /// [`Shape::intersect_p`] of the shape, without the virtual call.
    #[inline(always)]
    pub fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        match self {
            Inlined::Sphere(s) => Shape::intersect_p(&**s, ray, t_min, t_max),
            Inlined::Rectangle(r) => Shape::intersect_p(&**r, ray, t_min, t_max),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Mat4, Vec3};
    use crate::shapes::Cuboid;

    /// The inlined kinds hand themselves over, and the direct tests answer as the
    /// virtual calls do, bit for bit, over rays that hit, graze and miss.
    #[test]
    fn direct_tests_answer_as_the_virtual_calls() {
        let shapes: Vec<Arc<dyn Shape>> = vec![
            Arc::new(Sphere::new(Vec3::new(0.3, -0.2, 0.1), 0.7).unwrap()),
            Arc::new(Rectangle::new(Vec3::new(-1.0, -0.5, 0.2), Vec3::new(2.0, 0.1, 0.0), Vec3::new(0.0, 0.3, 1.5)).unwrap()),
        ];
        let mut rng = crate::sampling::Rng::for_sample(5, 0, 0);
        for shape in &shapes {
            let inlined = Arc::clone(shape).inlined().expect("an inlined kind");
            let mut hits = 0;
            for _ in 0..2000 {
                let origin = Vec3::new(rng.uniform() * 6.0 - 3.0, rng.uniform() * 6.0 - 3.0, rng.uniform() * 6.0 - 3.0);
                let target = Vec3::new(rng.uniform() * 2.0 - 1.0, rng.uniform() * 2.0 - 1.0, rng.uniform() * 2.0 - 1.0);
                let ray = Ray::unit(origin, (target - origin).normalize());
                let t_max = rng.uniform() * 8.0;
                let direct = inlined.intersect(&ray, 0.0, t_max);
                let virtual_call = shape.intersect(&ray, 0.0, t_max);
                assert_eq!(
                    direct.map(|h| (h.t.to_bits(), h.normal.to_array().map(f64::to_bits))),
                    virtual_call.map(|h| (h.t.to_bits(), h.normal.to_array().map(f64::to_bits))),
                    "{shape:?} {ray:?}"
                );
                assert_eq!(inlined.intersect_p(&ray, 0.0, t_max), shape.intersect_p(&ray, 0.0, t_max));
                hits += usize::from(direct.is_some());
                // An area light's point: the same bits as the virtual call.
                let u = (rng.uniform(), rng.uniform());
                let bits = |p: Option<(Vec3, Vec3)>| p.map(|(y, n)| (y.to_array().map(f64::to_bits), n.to_array().map(f64::to_bits)));
                assert_eq!(bits(inlined.sample_area(u)), bits(shape.sample_area(u)), "{shape:?} {u:?}");
            }
            assert!(hits > 200 && hits < 1800, "{shape:?}: {hits} hits of 2000");
        }
        let plane: Arc<dyn Shape> = Arc::new(crate::shapes::Plane::new(Vec3::ZERO, Vec3::Y).unwrap());
        assert!(plane.inlined().is_none(), "other kinds keep the virtual call");
        // A box's test is large: compiled into the queries it made the Cornell
        // box 2.5 % slower (BENCHMARKS.md, session 28).
        let cuboid: Arc<dyn Shape> = Arc::new(Cuboid::new(-Vec3::ONE, Vec3::ONE, Mat4::IDENTITY).unwrap());
        assert!(cuboid.inlined().is_none());
    }
}
