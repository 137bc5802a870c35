//! Area lights: scene objects whose material emits (`emission > 0`).
//!
//! An emitting surface sends radiance `Le` from its outward side only (as area
//! lights in pbrt and Mitsuba do), or from both when its material is
//! [two-sided](crate::materials::Material::two_sided). Light sampling picks a point `y` uniformly on
//! the shape's area `A`; seen from `x`, its density in solid angle is
//! `pdf = |x - y|^2 / (|cos(theta_y)| A)`, where `theta_y` is between the light's
//! normal and the direction back to `x`. Shapes that only know their area as
//! triangles (meshes, placed meshes) are sampled by a [`TriangleSampler`].
//!
//! A textured emission (a Mitsuba `area` emitter whose `radiance` is a
//! texture) is evaluated at each sampled point, at the shape's surface
//! coordinates there, so light sampling finds the light a BSDF-sampled ray
//! would see there; the density stays uniform in area.

use std::sync::Arc;

use super::mesh::TriangleSampler;
use super::{LiSample, Light, LightSample};
use crate::materials::{ShadingPoint, Texture};
use crate::math::{Rgb, Vec3};
use crate::shapes::{Inlined, Shape};

/// An emitting object that can be sampled.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Index of the scene object.
    pub object: usize,
    /// Its shape.
    pub shape: Arc<dyn Shape>,
    /// Emitted radiance on the outward side.
    pub radiance: Rgb,
    /// The emission's texture, where it varies over the surface (then it, not
    /// `radiance`, is what a sampled point emits).
    pub texture: Option<Texture>,
    /// The inward side emits `radiance` too.
    pub two_sided: bool,
    /// The shape's orientation is reversed ([`crate::scene::Object::reversed`]):
    /// it emits from the side its normals point away from.
    pub reversed: bool,
    area: f64,
    /// The shape is convex ([`Shape::is_convex`]): a sampled point is where a
    /// shadow ray towards it first meets the light.
    pub convex: bool,
    /// The triangles of a mesh emitter (`None`: the shape samples itself).
    triangles: Option<Arc<TriangleSampler>>,
    /// The shape, where its kind samples itself without a virtual call
    /// ([`crate::shapes::Inlined`]): the call and its answer through memory were
    /// a few percent of a path-traced Cornell box.
    inlined: Option<Inlined>,
}

/// A point sampled on an area light, as seen from a receiving point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaSample {
    /// Unit direction from the receiver to the light point.
    pub wi: Vec3,
    /// Distance to the light point.
    pub distance: f64,
    /// Radiance arriving along `-wi` (0 from the light's back side).
    pub radiance: Rgb,
    /// Density in solid angle at the receiver.
    pub pdf: f64,
}

impl AreaLight {
    /// The area light of object `object`, or `None` when the shape cannot be sampled
    /// (neither [`Shape::area`] nor [`Shape::triangles`]) or has no area.
    pub fn new(object: usize, shape: Arc<dyn Shape>, radiance: Rgb) -> Option<AreaLight> {
        let (area, triangles) = match shape.area() {
            Some(area) => (area, None),
            None => {
                let sampler = TriangleSampler::new(shape.triangles()?)?;
                (sampler.area(), Some(Arc::new(sampler)))
            }
        };
        let convex = triangles.is_none() && shape.is_convex();
        let inlined = shape.clone().inlined();
        (area > 0.0 && area.is_finite()).then_some(AreaLight {
            object,
            shape,
            radiance,
            texture: None,
            two_sided: false,
            reversed: false,
            area,
            convex,
            triangles,
            inlined,
        })
    }

    /// The same light emitting from both sides when `two_sided`.
    pub fn with_two_sided(self, two_sided: bool) -> AreaLight {
        AreaLight { two_sided, ..self }
    }

    /// The same light emitting `texture`'s value at each point where it is `Some`.
    pub fn with_texture(self, texture: Option<Texture>) -> AreaLight {
        AreaLight { texture, ..self }
    }

    /// The same light with its shape's orientation reversed when `reversed`.
    pub fn with_reversed(self, reversed: bool) -> AreaLight {
        AreaLight { reversed, ..self }
    }

    /// Surface area.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// A light point for receiver `x` from `u`.
    #[inline(always)]
    pub fn sample(&self, x: Vec3, u: (f64, f64)) -> Option<AreaSample> {
        let (y, n, face) = match &self.triangles {
            Some(t) => t.sample(u).map(|(y, n, k)| (y, n, Some(k)))?,
            None => match &self.inlined {
                Some(shape) => shape.sample_area(u).map(|(y, n)| (y, n, None))?,
                None => self.shape.sample_area(u).map(|(y, n)| (y, n, None))?,
            },
        };
        let to = y - x;
        let d2 = to.length_squared();
        if !(d2 > 0.0) {
            return None;
        }
        let distance = d2.sqrt();
        // One division for the three components (divisions are the slow part here).
        let wi = to * (1.0 / distance);
        let facing = if self.reversed { wi.dot(n) } else { -wi.dot(n) };
        let cos_y = if self.two_sided { facing.abs() } else { facing };
        if cos_y <= 0.0 {
            return None; // the back side does not emit
        }
        let pdf = d2 / (cos_y * self.area);
        let radiance = match &self.texture {
            None => self.radiance,
            Some(t) => t.evaluate(&ShadingPoint::with_coords(y, &self.shape.surface_coords(y, n, face))),
        };
        pdf.is_finite().then_some(AreaSample { wi, distance, radiance, pdf })
    }

    /// Solid-angle density with which [`AreaLight::sample`] returns the point at
    /// distance `distance` along `wi`, where the light's outward normal is `normal`.
    pub fn pdf(&self, wi: Vec3, distance: f64, normal: Vec3) -> f64 {
        let cos_y = wi.dot(normal).abs();
        if cos_y <= 0.0 {
            return 0.0;
        }
        distance * distance / (cos_y * self.area)
    }
}

impl Light for AreaLight {
    /// Not a delta light: the Whitted integrator does not see it this way.
    fn illuminate(&self, _point: Vec3) -> Option<LightSample> {
        None
    }

    fn own_object(&self) -> Option<usize> {
        Some(self.object)
    }

    /// A point on the surface ([`AreaLight::sample`]).
    fn sample_li(&self, point: Vec3, u: (f64, f64)) -> Option<LiSample> {
        self.sample_li_direct(point, u)
    }
}

impl AreaLight {
    /// [`Light::sample_li`], for callers that know the light's type
    /// ([`crate::lights::LightSet::pick_and_sample`]) and compile it in.
    #[inline(always)]
    pub fn sample_li_direct(&self, point: Vec3, u: (f64, f64)) -> Option<LiSample> {
        let s = self.sample(point, u)?;
        Some(LiSample {
            wi: s.wi,
            distance: s.distance,
            radiance: s.radiance,
            pdf: Some(s.pdf),
            own_object: Some(self.object),
            ends_on_own: self.convex,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Mat4;
    use crate::ray::Ray;
    use crate::shapes::{Cuboid, Disk, Rectangle, Sphere, Triangle};

    /// What `Shape::is_convex` promises the path tracer: from a point outside, a
    /// sampled light point whose normal faces it is where the segment first meets
    /// the shape, so the shadow ray need not search for it.
    #[test]
    fn convex_emitters_are_first_met_at_their_sampled_points() {
        let placed =
            Mat4::from_translation(Vec3::new(0.3, -0.2, 0.1)) * Mat4::from_rotation_y(0.4) * Mat4::from_scale(Vec3::new(0.5, 1.0, 0.7));
        let shapes: Vec<Arc<dyn Shape>> = vec![
            Arc::new(Rectangle::new(Vec3::new(-0.5, 1.0, -0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)).unwrap()),
            Arc::new(Disk::new(Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.2, -1.0, 0.1), 0.6).unwrap()),
            Arc::new(Triangle::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.2, 0.0), Vec3::new(0.0, 0.1, 1.0)).unwrap()),
            Arc::new(Sphere::new(Vec3::new(0.1, 0.2, -0.1), 0.8).unwrap()),
            Arc::new(Cuboid::new(-Vec3::ONE, Vec3::ONE, placed).unwrap()),
        ];
        let mut state = 1u32;
        let mut uniform = || {
            state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            (state >> 8) as f64 / (1u32 << 24) as f64
        };
        for shape in shapes {
            assert!(shape.is_convex());
            let light = AreaLight::new(0, shape.clone(), Rgb::ONE).unwrap();
            assert!(light.convex);
            let mut checked = 0;
            for _ in 0..4000 {
                let x = Vec3::new(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5) * 8.0;
                let inside = Ray::new(x, Vec3::new(0.0, 1.0, 0.0));
                // Points inside the sphere or box (odd crossings upwards) are not outside.
                let mut crossings = 0;
                let mut t = 0.0;
                while let Some(h) = shape.intersect(&inside, t, f64::INFINITY) {
                    crossings += 1;
                    t = h.t * (1.0 + 1e-9) + 1e-9;
                }
                if crossings % 2 == 1 {
                    continue;
                }
                let Some(s) = light.sample(x, (uniform(), uniform())) else { continue };
                let first = shape.intersect(&Ray::new(x, s.wi), 0.0, f64::INFINITY).expect("the sampled point is on the ray");
                assert!((first.t - s.distance).abs() <= 1e-9 * s.distance, "{shape:?}: first hit {} before {}", first.t, s.distance);
                checked += 1;
            }
            assert!(checked > 500, "{shape:?}: only {checked} samples checked");
        }
    }

    #[test]
    fn a_reversed_emitter_lights_the_other_side_with_the_same_density() {
        // A square at y = 1 facing +y: it lights points above it, reversed those below.
        let square = Arc::new(Rectangle::new(Vec3::new(-0.5, 1.0, -0.5), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0)).unwrap());
        let light = AreaLight::new(0, square, Rgb::ONE).unwrap();
        let reversed = light.clone().with_reversed(true);
        let (above, below) = (Vec3::new(0.1, 3.0, 0.2), Vec3::new(0.1, -1.0, 0.2));
        for u in [(0.2, 0.7), (0.9, 0.1), (0.5, 0.5)] {
            assert!(light.sample(above, u).is_some() && light.sample(below, u).is_none(), "{u:?}");
            assert!(reversed.sample(above, u).is_none(), "{u:?}");
            let (s, r) = (light.sample(above, u).unwrap(), reversed.sample(below, u).unwrap());
            // Both points are 2 from the square: the same distance and density.
            assert!((s.distance - r.distance).abs() < 1e-12 && (s.pdf - r.pdf).abs() < 1e-9 * s.pdf, "{u:?}");
        }
    }

    #[test]
    fn solid_angle_of_a_sphere_from_its_samples() {
        // E[1{front} / pdf] over area samples = solid angle subtended by the visible cap,
        // 2 pi (1 - sqrt(1 - (r/d)^2)) for a sphere of radius r at distance d.
        let light = AreaLight::new(0, Arc::new(Sphere::new(Vec3::new(0.0, 0.0, 3.0), 1.0).unwrap()), Rgb::ONE).unwrap();
        let n = 400;
        let mut omega = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                if let Some(s) = light.sample(Vec3::ZERO, u) {
                    // Only points seen from x (the near cap) count: they are the ones
                    // whose direction back to x is within the visible cap.
                    let hit = light.shape.intersect(&crate::ray::Ray::unit(Vec3::ZERO, s.wi), 0.0, f64::INFINITY).unwrap();
                    if (hit.t - s.distance).abs() < 1e-9 {
                        omega += 1.0 / s.pdf;
                    }
                }
            }
        }
        omega /= (n * n) as f64;
        let expected = 2.0 * std::f64::consts::PI * (1.0 - (1.0f64 - 1.0 / 9.0).sqrt());
        assert!((omega - expected).abs() / expected < 2e-3, "{omega} vs {expected}");
    }

    #[test]
    fn mesh_light_pdf_of_the_hit_agrees_with_sample() {
        // What MIS needs: a BSDF ray that hits the mesh where a light sample landed
        // gets the sample's density from the hit's distance and normal alone.
        let positions = vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(3.0, 0.0, 3.0)];
        let mesh = crate::shapes::TriangleMesh::new(positions, vec![[0, 2, 1], [1, 2, 3]], None).unwrap(); // both face +y
        let light = AreaLight::new(0, Arc::new(mesh), Rgb::ONE).unwrap();
        assert!((light.area() - 4.5).abs() < 1e-12, "areas 1 and 3.5");
        let x = Vec3::new(0.7, 1.5, 0.9);
        for i in 0..20 {
            let s = light.sample(x, ((i as f64 * 0.37).fract(), (i as f64 * 0.61).fract())).unwrap();
            let hit = light.shape.intersect(&crate::ray::Ray::unit(x, s.wi), 0.0, f64::INFINITY).unwrap();
            assert!((hit.t - s.distance).abs() < 1e-9);
            assert!(
                (light.pdf(s.wi, hit.t, hit.normal) - s.pdf).abs() < 1e-9 * s.pdf,
                "{} vs {}",
                light.pdf(s.wi, hit.t, hit.normal),
                s.pdf
            );
        }
        assert!(light.sample(Vec3::new(0.7, -1.5, 0.9), (0.3, 0.3)).is_none(), "back side is dark");
    }

    #[test]
    fn a_textured_light_emits_its_texture_at_each_sampled_point() {
        // The unit square at z = 0 facing +z, uv = (x, y), a checker of 2 x 2 cells:
        // light sampling must see the colour of the cell the point lies in, with
        // the density of the untextured light.
        use crate::materials::texture::UvChecker;
        use crate::materials::{ShadingPoint, UvTransform};
        let square = Arc::new(Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap());
        let (even, odd) = (Rgb::new(1.0, 0.5, 0.25), Rgb::new(0.2, 0.4, 0.6));
        let checker = Texture::UvChecker(Arc::new(UvChecker { transform: UvTransform::new([2.0, 2.0], 0.0, [0.0, 0.0]), even, odd }));
        let plain = AreaLight::new(0, square, Rgb::splat(7.0)).unwrap();
        let textured = plain.clone().with_texture(Some(checker.clone()));
        let x = Vec3::new(0.4, 0.3, 2.0);
        let mut seen = [0, 0];
        for i in 0..64 {
            // Stratum centres, none on a cell border (where the point's rounding would decide).
            let u = (((i % 8) as f64 + 0.5) / 8.0, ((i / 8) as f64 + 0.5) / 8.0);
            let (s, p) = (textured.sample(x, u).unwrap(), plain.sample(x, u).unwrap());
            assert_eq!((s.wi, s.pdf), (p.wi, p.pdf), "the texture leaves the density alone");
            assert_eq!(p.radiance, Rgb::splat(7.0));
            let y = x + s.wi * s.distance;
            let cell = ((2.0 * y.x).floor() + (2.0 * y.y).floor()) as i64 % 2;
            assert_eq!(s.radiance, if cell == 0 { even } else { odd }, "at {y}");
            assert_eq!(s.radiance, checker.evaluate(&ShadingPoint { uv: [y.x, y.y], ..ShadingPoint::at(y) }));
            seen[cell as usize] += 1;
        }
        assert!(seen[0] > 10 && seen[1] > 10, "both cells sampled: {seen:?}");
    }

    #[test]
    fn rectangle_pdf_agrees_with_sample() {
        let rect = Rectangle::new(Vec3::new(-0.5, 2.0, -0.5), Vec3::X, Vec3::Z).unwrap(); // normal X x Z = -Y
        let light = AreaLight::new(3, Arc::new(rect), Rgb::splat(5.0)).unwrap();
        let s = light.sample(Vec3::ZERO, (0.3, 0.8)).unwrap();
        assert!((light.pdf(s.wi, s.distance, -Vec3::Y) - s.pdf).abs() < 1e-12);
        assert!(light.sample(Vec3::new(0.0, 4.0, 0.0), (0.3, 0.8)).is_none(), "back side is dark");
    }
}
