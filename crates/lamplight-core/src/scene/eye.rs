//! Camera rays through the eye's buffer ([`EyeBuffer`], `accel/eye_buffer.rs`):
//! a ray that leaves the eye tests the unbounded objects, then the objects
//! listed in its cell of directions, nearest box first, instead of walking
//! the BVH.
//!
//! The answer is the walk's, bit for bit. Every listed object's test
//! ignores `t_max` ([`crate::shapes::Shape::hit_ignores_t_max`]), so the
//! object hit nearest reports the same hit here as in the walk; where two
//! objects are hit at exactly the same distance, the walk's order decides
//! which one counts, so such a ray is handed to the walk. So is a ray whose
//! cell lists too many objects.
//!
//! The search is compiled out of line, reached from the top of
//! [`Scene::first_intersect`]'s compilations: with it compiled into the walk's
//! query, or its answer handed back through the query, the path-traced
//! Cornell box (which has no buffer) took 6-9 % longer (`BENCHMARKS.md`,
//! session 29).

use super::{Hit, Scene};
use crate::accel::EyeBuffer;
use crate::ray::Ray;
use crate::shapes::SurfaceHit;

impl Scene {
    /// [`Scene::first_intersect`] of a ray from the eye, by the eye's buffer
    /// where it answers, by the walk where it does not.
    #[inline(never)]
    pub(super) fn first_intersect_from_eye_baseline(&self, eye: &EyeBuffer, ray: &Ray, t_max: f64) -> Option<Hit> {
        match self.first_intersect_listed(eye, ray, t_max) {
            Some(found) => found,
            None => self.first_intersect_walk_baseline(ray, t_max),
        }
    }

    /// The walk of [`Scene::first_intersect`] for baseline x86-64, without
    /// its look at the eye ([`Scene::first_intersect_walk_avx2`]).
    #[inline(never)]
    fn first_intersect_walk_baseline(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        self.first_intersect_in::<false>(ray, t_max)
    }

    /// [`Scene::first_intersect_from_eye_baseline`] compiled for [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[inline(never)]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub(super) unsafe fn first_intersect_from_eye_avx2(&self, eye: &EyeBuffer, ray: &Ray, t_max: f64) -> Option<Hit> {
        match self.first_intersect_listed(eye, ray, t_max) {
            Some(found) => found,
            None => self.first_intersect_walk_avx2(ray, t_max),
        }
    }

    /// The walk of [`Scene::first_intersect_avx2`] without its look at the
    /// eye, for the rays the buffer hands back; out of line, so that the
    /// search's own frame stays small.
    #[cfg(target_arch = "x86_64")]
    #[inline(never)]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub(super) unsafe fn first_intersect_walk_avx2(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        self.first_intersect_in::<true>(ray, t_max)
    }

    /// The unbounded objects, then those the eye's buffer lists for `ray`;
    /// `None` where the walk must answer ([`Scene::nearest_listed`]).
    #[inline(always)]
    fn first_intersect_listed(&self, eye: &EyeBuffer, ray: &Ray, t_max: f64) -> Option<Option<Hit>> {
        let mut best: Option<(usize, SurfaceHit)> = None;
        let mut closest = t_max;
        for prim in &self.unbounded {
            if let Some(h) = self.hit_object(prim, ray, closest) {
                closest = h.t;
                best = Some((prim.object as usize, h));
            }
        }
        let found = self.nearest_listed(eye, ray, best, closest)?;
        Some(found.map(|(object, h)| self.hit_record(ray, object, h)))
    }

    /// The nearest hit of a ray from the eye among the objects of its cell of
    /// the eye's buffer, after `best` at `closest` (the unbounded objects'):
    /// `Some` answer, or `None` where the walk must answer (no list for the
    /// ray, or two objects hit at exactly the same distance, whose order the
    /// walk decides; `accel/eye_buffer.rs`).
    #[inline(always)]
    fn nearest_listed(
        &self,
        eye: &EyeBuffer,
        ray: &Ray,
        mut best: Option<(usize, SurfaceHit)>,
        mut closest: f64,
    ) -> Option<Option<(usize, SurfaceHit)>> {
        let (always, cell) = eye.lists(ray.dir)?;
        // Each object is asked up to the float past `closest`, so that a hit at
        // exactly `closest` shows: a tie, left to the walk.
        let mut limit = closest.next_up();
        let mut tie = false;
        for (k, &i) in always.iter().chain(cell).enumerate() {
            // The cell's list is sorted by reach: nothing further on can be nearer.
            if k >= always.len() && eye.reach(i) > closest {
                break;
            }
            let prim = &self.bounded[i as usize];
            let Some(h) = self.hit_object(prim, ray, limit) else { continue };
            if h.t < closest {
                closest = h.t;
                limit = h.t.next_up();
                best = Some((prim.object as usize, h));
                // A tie further away no longer matters.
                tie = false;
            } else if best.is_some() {
                tie = true;
            }
        }
        if tie {
            return None;
        }
        Some(best)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective, ThinLens};
    use crate::materials::Material;
    use crate::math::{Mat4, Vec3};
    use crate::scene::SceneBuilder;
    use crate::shapes::{Cuboid, Implicit, Plane, Quadric, Rectangle, Sphere, TriangleMesh};

    pub(in crate::scene) const EYE: Vec3 = Vec3::new(0.5, 3.0, 12.0);

    /// Thirty balls, boxes, ellipsoids and a small mesh over a floor, seen from
    /// `EYE`, with an infinite plane behind them, a ball placed twice and two
    /// rectangles in one plane (exact ties, which the walk must decide).
    fn mixed_scene(camera: impl crate::camera::Camera + 'static) -> Scene {
        mixed_scene_with(camera, true)
    }

    /// [`mixed_scene`], with the infinite plane behind only when `plane`.
    pub(in crate::scene) fn mixed_scene_with(camera: impl crate::camera::Camera + 'static, plane: bool) -> Scene {
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        let mut rand = move || rng.uniform();
        let mut builder = SceneBuilder::new(camera);
        let m = builder.material(Material::default()).unwrap();
        builder.object(Rectangle::horizontal(0.0, -8.0, 8.0, -8.0, 8.0).unwrap(), m).unwrap();
        if plane {
            builder.object(Plane::new(Vec3::new(0.0, 0.0, -20.0), Vec3::Z).unwrap(), m).unwrap();
        }
        for k in 0..30 {
            let c = Vec3::new(rand() * 10.0 - 5.0, 0.3 + rand() * 3.0, rand() * 10.0 - 5.0);
            match k % 3 {
                0 => builder.object(Sphere::new(c, 0.2 + rand() * 0.6).unwrap(), m).unwrap(),
                1 => builder
                    .object(Cuboid::new(c - Vec3::splat(0.3), c + Vec3::splat(0.4), Mat4::from_rotation_y(rand())).unwrap(), m)
                    .unwrap(),
                _ => builder.object(Quadric::ellipsoid(c, Vec3::new(0.5, 0.3, 0.4)).unwrap(), m).unwrap(),
            };
        }
        let twice = Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.8).unwrap();
        builder.object(twice, m).unwrap();
        builder.object(twice, m).unwrap();
        let corner = Vec3::new(-2.0, 0.5, 3.0);
        builder.object(Rectangle::new(corner, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap(), m).unwrap();
        builder.object(Rectangle::new(corner, Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)).unwrap(), m).unwrap();
        let tetrahedron = TriangleMesh::new(
            vec![Vec3::new(3.0, 0.0, 4.0), Vec3::new(4.0, 0.0, 4.0), Vec3::new(3.5, 0.0, 3.0), Vec3::new(3.5, 1.0, 3.7)],
            vec![[0, 1, 3], [1, 2, 3], [2, 0, 3], [0, 2, 1]],
            None,
        )
        .unwrap();
        builder.object(tetrahedron, m).unwrap();
        builder.build().unwrap()
    }

    pub(in crate::scene) fn pinhole() -> Perspective {
        Perspective::look_at(EYE, Vec3::new(0.0, 1.0, 0.0), Vec3::Y, Fov::VerticalDeg(50.0)).unwrap()
    }

    /// Rays from the eye in every direction, most towards the objects: the
    /// buffer's answer is the walk's, bit for bit, ties included, and the
    /// buffer answers most rays itself.
    #[test]
    fn rays_from_the_eye_get_the_walks_answer() {
        let scene = mixed_scene(pinhole());
        let eye = scene.eye_buffer.as_ref().expect("a pinhole over 36 objects has an eye's buffer");
        assert_eq!(eye.eye(), EYE);
        let mut rng = crate::sampling::Rng::for_sample(4, 0, 0);
        let mut rand = move || rng.uniform();
        let (mut listed, mut ties, mut hits) = (0, 0, 0);
        for k in 0..20_000 {
            let target = if k % 10 == 0 {
                Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 100.0
            } else if k % 10 == 1 {
                // The ball placed twice, and the two rectangles in one plane.
                [Vec3::new(0.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 3.0)][k % 20 / 10] + Vec3::new(rand() - 0.5, rand() - 0.5, 0.0) * 0.8
            } else {
                Vec3::new(rand() * 12.0 - 6.0, rand() * 4.0, rand() * 12.0 - 6.0)
            };
            let ray = Ray::unit(EYE, (target - EYE).normalize());
            let walk = scene.first_intersect_in::<false>(&ray, f64::INFINITY);
            assert_eq!(scene.first_intersect(&ray, f64::INFINITY), walk, "ray {ray:?}");
            assert_eq!(scene.first_intersect_from_eye_baseline(eye, &ray, f64::INFINITY), walk, "ray {ray:?}");
            match scene.first_intersect_listed(eye, &ray, f64::INFINITY) {
                Some(found) => {
                    assert_eq!(found, walk, "ray {ray:?}");
                    listed += 1;
                }
                None => ties += 1,
            }
            hits += usize::from(walk.is_some());
            // A shorter reach answers alike.
            let t_max = rand() * 15.0;
            assert_eq!(scene.first_intersect(&ray, t_max), scene.first_intersect_in::<false>(&ray, t_max), "ray {ray:?} to {t_max}");
        }
        assert!(listed > 17_000, "the buffer answered only {listed} rays");
        assert!(ties > 100, "only {ties} rays were handed to the walk: the ties were not met");
        assert!(hits > 15_000, "only {hits} hits");
    }

    /// No buffer where its answer could differ or it would not pay: a camera
    /// whose rays leave a lens, a surface found by marching (whose hit
    /// depends on `t_max`), a handful of objects (the flat walk).
    #[test]
    fn no_eye_buffer_where_it_cannot_answer_or_pay() {
        assert!(mixed_scene(pinhole()).eye_buffer.is_some());
        assert!(mixed_scene(ThinLens::new(pinhole(), 0.1, 10.0).unwrap()).eye_buffer.is_none(), "a lens");
        let with_marching = |marching: bool| {
            let mut builder = SceneBuilder::new(pinhole());
            let m = builder.material(Material::default()).unwrap();
            for k in 0..20 {
                builder.object(Sphere::new(Vec3::new(k as f64, 0.0, 0.0), 0.3).unwrap(), m).unwrap();
            }
            if marching {
                let f: crate::shapes::ImplicitFn = std::sync::Arc::new(|p: Vec3| p.length() - 0.5);
                let ball = Implicit::new(f, crate::accel::Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0)), 1.0).unwrap();
                builder.object(ball, m).unwrap();
            }
            builder.build().unwrap()
        };
        assert!(with_marching(false).eye_buffer.is_some());
        assert!(with_marching(true).eye_buffer.is_none(), "an implicit surface");
        let mut builder = SceneBuilder::new(pinhole());
        let m = builder.material(Material::default()).unwrap();
        for k in 0..crate::accel::FLAT_MAX {
            builder.object(Sphere::new(Vec3::new(k as f64, 0.0, 0.0), 0.3).unwrap(), m).unwrap();
        }
        assert!(builder.build().unwrap().eye_buffer.is_none(), "a flat scene");
    }
}
