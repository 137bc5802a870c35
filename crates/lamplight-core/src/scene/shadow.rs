//! Shadow queries: how much light reaches a point from a light, through the
//! scene's objects ([`Scene::transmittance`]).
//!
//! A shadow ray is blocked as soon as any opaque object lies on its segment, so
//! the order objects are tried in cannot change the answer, only how soon it is
//! known. [`OccluderHint`] uses that: the object that blocked the previous
//! shadow ray towards the same light is tried before the BVH is walked.
//! Neighbouring pixels usually lie in the same object's shadow, so most blocked
//! rays end after one shape test (POV-Ray keeps the same cache per light).
//! A ray that nothing blocks clears the hint: its neighbours are then likely
//! lit too, and would test the object for nothing.
//!
//! A hint also names its light. For a light that leaves one point the scene
//! keeps a [`LightBuffer`]: the objects that may lie in each cell of directions
//! around the light. A shadow ray towards it tests its cell's objects instead of
//! walking the BVH; the buffer checks that the ray really ends at its light.
//!
//! The answer is the same for any hint, bit for bit: a hinted object that does
//! not block is skipped by the search that follows, and the cell lists every
//! object that can lie on the ray. Scenes with partly transparent shadows
//! (which multiply every crossing, in the walk's order) keep the walk.

use super::{PrimRef, Scene};
use crate::accel::{LightBuffer, Occlude};
use crate::math::{max_abs, Rgb};
use crate::ray::{Ray, OFFSET_SCALE};

/// The object that last blocked a shadow ray towards a light, and that light's
/// index in [`Scene::lights`], kept by the caller per light and handed to
/// [`Scene::transmittance_hinted`], which tries the object first and updates it
/// (to the blocker found, or to no object when none blocks).
/// It only decides which objects are tested and in what order; any value
/// (another scene's, or [`OccluderHint::NONE`]) gives the same answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OccluderHint {
    /// Index into the scene's bounded objects, or `u32::MAX`.
    prim: u32,
    /// Index into the scene's lights, or `u32::MAX`.
    light: u32,
}

impl OccluderHint {
    /// No object and no light known: the BVH is walked as usual.
    pub const NONE: OccluderHint = OccluderHint { prim: u32::MAX, light: u32::MAX };

    /// This hint for a shadow ray towards light `light` of [`Scene::lights`].
    pub fn towards(self, light: usize) -> OccluderHint {
        OccluderHint { light: u32::try_from(light).unwrap_or(u32::MAX), ..self }
    }
}

impl Default for OccluderHint {
    fn default() -> Self {
        OccluderHint::NONE
    }
}

/// The shadow query's test of one bounded object for the walk and the light
/// buffer's lists: the hinted object `tried` is skipped (it was tested first),
/// and the blocker found is kept for the hint.
struct Blocker<'a> {
    scene: &'a Scene,
    ray: &'a Ray,
    distance: f64,
    ignore: u32,
    tried: u32,
    /// The object that blocked, or `u32::MAX`.
    found: u32,
}

impl crate::accel::Occlude for &mut Blocker<'_> {
    #[inline(always)]
    fn occluded(&mut self, prim: u32) -> bool {
        let blocked = prim != self.tried && self.scene.blocks(&self.scene.bounded[prim as usize], self.ray, self.distance, self.ignore);
        if blocked {
            self.found = prim;
        }
        blocked
    }
}

impl Scene {
    /// Fraction of light that travels from `ray.origin` a distance `distance` along the
    /// unit `ray.dir` (a shadow ray, at `ray.time`): 0 if an opaque object lies in between, the product
    /// of the crossed surfaces' `shadow_transmittance` otherwise.
    ///
    /// Object `ignore` is a light's own body (a bulb, or Heckbert's emitting
    /// spheres): the light is seen where the ray first meets that object, so the
    /// ray ends there. Neither the object nor anything inside it or behind its
    /// near surface shadows the light, as in Heckbert's test "the first sphere hit
    /// towards the light is the light".
    #[inline]
    pub fn transmittance(&self, ray: &Ray, distance: f64, ignore: Option<usize>) -> Rgb {
        self.transmittance_hinted(ray, distance, ignore, &mut OccluderHint::default())
    }

    /// [`Scene::transmittance`], trying the object `hint` names first, then the
    /// light buffer of the light it names (module doc). When the search finds
    /// an object that blocks the ray, `hint` becomes that object; otherwise it
    /// is left as it was.
    #[inline]
    pub fn transmittance_hinted(&self, ray: &Ray, distance: f64, ignore: Option<usize>, hint: &mut OccluderHint) -> Rgb {
        // The light is seen where the ray first meets its own object: the ray ends there.
        let distance = ignore.and_then(|i| self.first_meeting(i, ray, distance)).unwrap_or(distance);
        // A ray its caller has just built goes to the query that copies it
        // first (`transmittance_fresh_avx2`): in `spheres` the plain query's
        // first, wide loads of the ray waited on the caller's stores, 16 % of
        // the query's time (issue 24).
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.transmittance_fresh_avx2(ray, distance, ignore, hint) };
        }
        self.transmittance_to(ray, distance, ignore, hint)
    }

    /// Where `ray` first meets object `object` within `distance` (its
    /// parameter alone, [`crate::shapes::Shape::first_t`]). Out of line: the
    /// Whitted loop, which inlines the shadow query's entry, stays as it was
    /// for scenes whose lights have no body (`spheres` took 1.4 % more
    /// instructions with it inlined).
    #[inline(never)]
    fn first_meeting(&self, object: usize, ray: &Ray, distance: f64) -> Option<f64> {
        self.objects.get(object)?.shape.first_t(ray, 0.0, distance)
    }

    /// [`Scene::transmittance`] along a segment already known to end where it first
    /// meets object `own`: a point sampled on the facing side of a convex emitter
    /// ([`crate::shapes::Shape::is_convex`]) is that first meeting, so the search is skipped.
    #[inline]
    pub fn transmittance_to_surface(&self, ray: &Ray, distance: f64, own: usize) -> Rgb {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.transmittance_fresh_avx2(ray, distance, Some(own), &mut OccluderHint::default()) };
        }
        self.transmittance_to(ray, distance, Some(own), &mut OccluderHint::default())
    }

    /// Transmittance over `(0, distance)`, object `ignore` left out (inlined,
    /// as [`Scene::first_intersect`] is).
    #[inline]
    fn transmittance_to(&self, ray: &Ray, distance: f64, ignore: Option<usize>, hint: &mut OccluderHint) -> Rgb {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.transmittance_avx2(ray, distance, ignore, hint) };
        }
        self.transmittance_baseline(ray, distance, ignore, hint)
    }

    /// [`Scene::transmittance_to`] for baseline x86-64, out of line.
    #[inline(never)]
    fn transmittance_baseline(&self, ray: &Ray, distance: f64, ignore: Option<usize>, hint: &mut OccluderHint) -> Rgb {
        self.transmittance_in::<false>(ray, distance, ignore, hint)
    }

    /// [`Scene::transmittance_to`] compiled whole for [`crate::cpu::AVX2_FEATURES`],
    /// as [`Scene::first_intersect_avx2`] is.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub(super) unsafe fn transmittance_avx2(&self, ray: &Ray, distance: f64, ignore: Option<usize>, hint: &mut OccluderHint) -> Rgb {
        self.transmittance_in::<true>(ray, distance, ignore, hint)
    }

    /// [`Scene::transmittance_avx2`] of a ray its caller has just built
    /// ([`Scene::transmittance_to_surface`], the path tracer's light samples,
    /// the Whitted tracer's rays towards point lights), read one coordinate
    /// at a time into a copy whose later reads each lie within one store
    /// ([`Ray::copy_forwarded_avx2`]): the path-traced Cornell box took 4 %
    /// less time reading it a coordinate at a time, and `spheres` 2-4 % less
    /// again with the copy. Rays towards a light with a body of its own (the
    /// bulb of `luxo`) took the plain query while the copy was read back in
    /// pieces (it cost `luxo` 3-4 %); with the copy whole, they take this one
    /// too (`luxo` 0.98-0.995 of the time).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    pub(super) unsafe fn transmittance_fresh_avx2(&self, ray: &Ray, distance: f64, ignore: Option<usize>, hint: &mut OccluderHint) -> Rgb {
        let mut copy = std::mem::MaybeUninit::uninit();
        ray.copy_forwarded_avx2(&mut copy);
        // Kept in memory as stored: values the compiler carried over in
        // registers would be spilled and read back in its own widths.
        let copy = std::hint::black_box(&mut copy).assume_init_ref();
        self.transmittance_in::<true>(copy, distance, ignore, hint)
    }

    /// [`Scene::transmittance_to`] with the BVH's box test chosen by `AVX2`.
    #[inline(always)]
    pub(super) fn transmittance_in<const AVX2: bool>(
        &self,
        ray: &Ray,
        distance: f64,
        ignore: Option<usize>,
        hint: &mut OccluderHint,
    ) -> Rgb {
        let (origin, dir) = (ray.origin, ray.dir);
        let ignore = ignore.map_or(u32::MAX, |i| i as u32);
        // Any blocking object gives the same answer, the hinted one included;
        // one that does not block is not tested again by the walk.
        let tried = hint.prim;
        if self.bounded.get(tried as usize).is_some_and(|prim| self.blocks(prim, ray, distance, ignore)) {
            return Rgb::ZERO;
        }
        for prim in &self.unbounded {
            if self.blocks(prim, ray, distance, ignore) {
                return Rgb::ZERO;
            }
        }
        let mut walk = Blocker { scene: self, ray, distance, ignore, tried, found: u32::MAX };
        if let Some((near, cell)) = self.light_cell(hint.light, ray, distance) {
            for &prim in near.iter().chain(cell) {
                if (&mut walk).occluded(prim) {
                    hint.prim = prim;
                    return Rgb::ZERO;
                }
            }
            hint.prim = u32::MAX;
            return Rgb::ONE;
        }
        if self.bvh.any_in::<AVX2>(origin, dir, 0.0, distance, &mut walk) {
            hint.prim = walk.found;
            return Rgb::ZERO;
        }
        hint.prim = u32::MAX;
        if !self.any_partial_shadow {
            return Rgb::ONE;
        }
        // Only partly transparent surfaces lie on the segment: multiply their
        // transmittance once per crossing.
        let mut result = Rgb::ONE;
        let mut crossing = |prim: &PrimRef| {
            let i = prim.object as usize;
            let filter = self.materials[self.objects[i].material].shadow_transmittance;
            if prim.object == ignore || filter == Rgb::ZERO || filter == Rgb::ONE {
                return;
            }
            let mut t_min = 0.0;
            // Each crossing moves t_min forward by at least the relative offset, so the loop ends.
            while let Some(h) = self.objects[i].shape.intersect(ray, t_min, distance) {
                result *= filter;
                t_min = h.t + OFFSET_SCALE * (max_abs(ray.at(h.t)) + h.t) + 4.0 * h.error;
                if result == Rgb::ZERO {
                    return;
                }
            }
        };
        for prim in &self.unbounded {
            crossing(prim);
        }
        self.bvh.traverse_in::<AVX2>(origin, dir, 0.0, distance, |prim, _| {
            crossing(&self.bounded[prim as usize]);
            None
        });
        result
    }

    /// Whether object `prim` blocks the shadow ray `ray` over `(0, distance)`:
    /// opaque, not the light's own object `ignore`, and hit. A method compiled
    /// into each of the query's three places rather than a closure, which LLVM
    /// kept out of line once the [`crate::shapes::Inlined`] tests made it large.
    #[inline(always)]
    fn blocks(&self, prim: &PrimRef, ray: &Ray, distance: f64, ignore: u32) -> bool {
        prim.opaque
            && prim.object != ignore
            && if prim.masked {
                self.hit_object(prim, ray, distance).is_some()
            } else {
                match &prim.inlined {
                    Some(shape) => shape.intersect_p(ray, 0.0, distance),
                    None => self.objects[prim.object as usize].shape.intersect_p(ray, 0.0, distance),
                }
            }
    }

    /// The objects a shadow ray towards light `light` over `(0, distance)` may
    /// meet, from the light's buffer (module doc): those near the light, then
    /// those of the ray's cell. `None` where the walk must answer: no buffer
    /// (the builder makes none for scenes with partly transparent shadows), or a
    /// ray that does not end at the light.
    #[inline(always)]
    fn light_cell(&self, light: u32, ray: &Ray, distance: f64) -> Option<(&[u32], &[u32])> {
        let buffer: &LightBuffer = self.light_buffers.get(light as usize)?.as_ref()?;
        let cell = buffer.cell_of(ray.origin, ray.dir, distance)?;
        Some((buffer.always(), cell))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::materials::Material;
    use crate::math::Vec3;
    use crate::scene::SceneBuilder;
    use crate::shapes::Sphere;

    /// 40 random balls, a quarter of them tinted glass that dims shadows
    /// (transmittance 0.5) instead of blocking them.
    fn balls() -> (Scene, Vec<Vec3>) {
        let mut rng = crate::sampling::Rng::for_sample(11, 0, 0);
        let mut rand = move || rng.uniform();
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut builder = SceneBuilder::new(camera);
        let opaque = builder.material(Material::default()).unwrap();
        let dim = builder.material(Material { shadow_transmittance: Rgb::splat(0.5), ..Material::default() }).unwrap();
        let mut centres = Vec::new();
        for k in 0..40 {
            let centre = Vec3::new(rand() * 8.0 - 4.0, rand() * 8.0 - 4.0, rand() * 8.0 - 4.0);
            let material = if k % 4 == 0 { dim } else { opaque };
            builder.object(Sphere::new(centre, 0.2 + rand() * 0.6).unwrap(), material).unwrap();
            centres.push(centre);
        }
        (builder.build().unwrap(), centres)
    }

    /// Every hint, each object's, none and one past the last, gives the answer of
    /// the plain query bit for bit, with and without a light's own object; a
    /// walk that finds a blocker leaves the hint naming an object that blocks,
    /// and a ray that nothing blocks leaves it naming none.
    #[test]
    fn no_hint_changes_the_answer() {
        let (scene, centres) = balls();
        let mut rng = crate::sampling::Rng::for_sample(12, 0, 0);
        let mut rand = move || rng.uniform();
        let hints: Vec<OccluderHint> =
            (0..=scene.bounded.len() as u32).map(|prim| OccluderHint { prim, light: u32::MAX }).chain([OccluderHint::NONE]).collect();
        let (mut blocked, mut dimmed, mut clear) = (0, 0, 0);
        for _ in 0..600 {
            let origin = Vec3::new(rand() * 12.0 - 6.0, rand() * 12.0 - 6.0, rand() * 12.0 - 6.0);
            let target = centres[(rand() * centres.len() as f64) as usize] + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5);
            let ray = Ray::unit(origin, (target - origin).normalize());
            let distance = rand() * 12.0;
            let own = (rand() < 0.3).then(|| (rand() * centres.len() as f64) as usize);
            let plain = scene.transmittance(&ray, distance, own);
            for &start in &hints {
                let mut hint = start;
                assert_eq!(scene.transmittance_hinted(&ray, distance, own, &mut hint), plain, "ray {ray:?}, hint {start:?}");
                if plain != Rgb::ZERO {
                    assert_eq!(hint.prim, u32::MAX, "a ray that nothing blocks clears the hint");
                } else if hint != start {
                    let mut again = hint;
                    assert_eq!(scene.transmittance_hinted(&ray, distance, own, &mut again), Rgb::ZERO);
                    assert_eq!(again, hint, "the new hint blocks the ray itself, so it stays");
                }
            }
            match plain {
                p if p == Rgb::ZERO => blocked += 1,
                p if p == Rgb::ONE => clear += 1,
                _ => dimmed += 1,
            }
        }
        assert!(blocked > 100 && clear > 100 && dimmed > 20, "{blocked} blocked, {dimmed} dimmed, {clear} clear: too few of a kind");
    }

    /// Shadow rays as the Whitted tracer makes them (from a hit, its origin
    /// pushed off the surface, towards a point light) get the walk's answer
    /// from the light's buffer, for lights inside, beside and far above the
    /// balls and at scene sizes from 1e-4 to 1e6; so do rays that do not end at
    /// the light, which the buffer hands back to the walk.
    #[test]
    fn the_light_buffer_answers_as_the_walk() {
        use crate::lights::PointLight;
        use crate::ray::offset_origin;
        let mut rng = crate::sampling::Rng::for_sample(13, 0, 0);
        let mut rand = move || rng.uniform();
        for scale in [1e-4, 1.0, 1e6] {
            let (mut shadow_rays, mut from_buffer, mut blocked) = (0, 0, 0);
            let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
            let mut builder = SceneBuilder::new(camera);
            let opaque = builder.material(Material::default()).unwrap();
            let clear = builder.material(Material { shadow_transmittance: Rgb::ONE, ..Material::default() }).unwrap();
            let mut centres = Vec::new();
            for i in 0..60 {
                let centre = Vec3::new(rand() * 8.0 - 4.0, rand() * 8.0 - 4.0, rand() * 8.0 - 4.0) * scale;
                let material = if i % 5 == 0 { clear } else { opaque };
                builder.object(Sphere::new(centre, (0.2 + rand() * 0.6) * scale).unwrap(), material).unwrap();
                centres.push(centre);
            }
            let lights = [Vec3::ZERO, Vec3::new(5.0, 1.0, -2.0), Vec3::new(3.0, 40.0, 7.0)];
            for p in lights {
                builder.light(PointLight::new(p * scale, Rgb::ONE).unwrap());
            }
            let scene = builder.build().unwrap();
            assert!(scene.light_buffers.iter().all(Option::is_some), "every point light has a buffer");
            for _ in 0..3000 {
                // Aimed near a ball, so that most rays hit one.
                let origin = Vec3::new(rand() * 16.0 - 8.0, rand() * 16.0 - 8.0, rand() * 16.0 - 8.0) * scale;
                let target = centres[(rand() * 60.0) as usize] + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * scale;
                let dir = (target - origin).normalize();
                let Some(hit) = scene.first_intersect(&Ray::unit(origin, dir), f64::INFINITY) else {
                    continue;
                };
                let light = (rand() * 3.0) as usize;
                let sample = scene.lights[light].illuminate(hit.point).unwrap();
                let start = offset_origin(hit.point, hit.geometric_normal, sample.wi, hit.t, hit.error);
                let shadow = Ray::unit(start, sample.wi);
                let remaining = sample.distance - (start - hit.point).length();
                // Some rays treat a ball as the light's own body, which does not block it.
                let own = (rand() < 0.3).then(|| (rand() * 60.0) as usize);
                let walk = scene.transmittance(&shadow, remaining, own);
                let mut hint = OccluderHint::NONE.towards(light);
                assert_eq!(scene.transmittance_hinted(&shadow, remaining, own, &mut hint), walk, "scale {scale}, {shadow:?}, own {own:?}");
                shadow_rays += 1;
                blocked += usize::from(walk == Rgb::ZERO);
                from_buffer += usize::from(scene.light_cell(light as u32, &shadow, remaining).is_some());
                // The same ray past the light, and a ray that misses it.
                let past = remaining * (1.0 + rand());
                let mut hint = OccluderHint::NONE.towards(light);
                assert_eq!(scene.transmittance_hinted(&shadow, past, None, &mut hint), scene.transmittance(&shadow, past, None));
                let mut hint = OccluderHint::NONE.towards(light);
                assert_eq!(
                    scene.transmittance_hinted(&hit.spawn(start, dir), remaining, None, &mut hint),
                    scene.transmittance(&hit.spawn(start, dir), remaining, None)
                );
            }
            assert!(shadow_rays > 1500 && from_buffer == shadow_rays, "scale {scale}: {from_buffer} of {shadow_rays} used the buffer");
            assert!(blocked > 300 && shadow_rays - blocked > 300, "scale {scale}: {blocked} of {shadow_rays} blocked, too few of a kind");
        }
    }

    /// A lamp shade around its light (`luxo`): the light's buffer lists the
    /// shade only where its surface is, not on the list every ray tests, so a
    /// ray through the mouth tests nothing; and every shadow ray, from hits
    /// inside the shade, on its back and on the balls and floor around it,
    /// gets the walk's answer, at scene sizes from 1e-3 to 1e5 and for a
    /// shade turned so that its box is not aligned with its axis.
    #[test]
    fn a_shade_around_its_light_is_listed_only_where_its_surface_is() {
        use crate::lights::PointLight;
        use crate::ray::offset_origin;
        use crate::shapes::Quadric;
        let mut rng = crate::sampling::Rng::for_sample(14, 0, 0);
        let mut rand = move || rng.uniform();
        for (scale, axis) in [(1e-3, Vec3::new(0.55, -1.35, 0.30)), (1.0, -Vec3::Y), (1e5, Vec3::new(-0.2, -1.0, 0.7))] {
            let axis = axis.normalize();
            let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
            let mut builder = SceneBuilder::new(camera);
            let opaque = builder.material(Material::default()).unwrap();
            let apex = Vec3::new(-0.45, 1.35, -0.25) * scale;
            let focus = apex + axis * 0.1 * scale;
            let shade = builder.object(Quadric::paraboloid_cup(apex, axis, 0.1 * scale, 0.25 * scale).unwrap(), opaque).unwrap();
            builder.object(Sphere::new(Vec3::new(0.0, -10.0, 0.0) * scale, 9.0 * scale).unwrap(), opaque).unwrap();
            let mut centres = vec![focus + axis * 0.6 * scale];
            for _ in 0..12 {
                centres.push(focus + Vec3::new(rand() - 0.5, rand() - 0.9, rand() - 0.5) * 2.0 * scale);
            }
            for &c in &centres {
                builder.object(Sphere::new(c, (0.05 + 0.1 * rand()) * scale).unwrap(), opaque).unwrap();
            }
            builder.light(PointLight::new(focus, Rgb::ONE).unwrap());
            builder.light(PointLight::new(Vec3::new(2.0, 3.0, 1.0) * scale, Rgb::ONE).unwrap());
            let scene = builder.build().unwrap();
            let buffer = scene.light_buffers[0].as_ref().expect("the shade's light has a buffer");
            let shade_prim = scene.bounded.iter().position(|p| p.object as usize == shade).unwrap() as u32;
            assert!(!buffer.always().contains(&shade_prim), "scale {scale}: the shade is tested by every ray");
            // Straight out of the mouth: no list; straight out of the back: the shade.
            let below = focus + axis * 3.0 * scale;
            let (near, cell) = scene.light_cell(0, &Ray::unit(below, -axis), 3.0 * scale).expect("a cell");
            assert!(near.is_empty() && !cell.contains(&shade_prim), "scale {scale}: {near:?} {cell:?}");
            let behind = focus - axis * 3.0 * scale;
            assert!(scene.light_cell(0, &Ray::unit(behind, axis), 3.0 * scale).unwrap().1.contains(&shade_prim));
            let (mut shadow_rays, mut from_buffer, mut blocked, mut inside) = (0, 0, 0, 0);
            for k in 0..4000 {
                let origin = focus + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 8.0 * scale;
                // A third aimed into the shade, the rest at a ball or the floor.
                let target = match k % 3 {
                    0 => apex + (axis * 0.25 + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 0.4) * scale,
                    1 => {
                        centres[(rand() * centres.len() as f64) as usize]
                            + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 0.2 * scale
                    }
                    _ => focus + Vec3::new(rand() - 0.5, -1.0, rand() - 0.5) * 2.0 * scale,
                };
                let Some(hit) = scene.first_intersect(&Ray::unit(origin, (target - origin).normalize()), f64::INFINITY) else {
                    continue;
                };
                for light in 0..2 {
                    let sample = scene.lights[light].illuminate(hit.point).unwrap();
                    let start = offset_origin(hit.point, hit.geometric_normal, sample.wi, hit.t, hit.error);
                    let shadow = Ray::unit(start, sample.wi);
                    let remaining = sample.distance - (start - hit.point).length();
                    let walk = scene.transmittance(&shadow, remaining, None);
                    let mut hint = OccluderHint::NONE.towards(light);
                    assert_eq!(scene.transmittance_hinted(&shadow, remaining, None, &mut hint), walk, "scale {scale}, {shadow:?}");
                    if light == 0 {
                        shadow_rays += 1;
                        blocked += usize::from(walk == Rgb::ZERO);
                        inside += usize::from(hit.object == shade && walk == Rgb::ONE);
                        from_buffer += usize::from(scene.light_cell(0, &shadow, remaining).is_some());
                    }
                }
            }
            assert!(from_buffer == shadow_rays, "scale {scale}: {from_buffer} of {shadow_rays} used the buffer");
            assert!(
                blocked > 500 && shadow_rays - blocked > 500 && inside > 100,
                "scale {scale}: {blocked} of {shadow_rays} blocked, {inside} lit inside the shade"
            );
        }
    }

    /// A walk that finds the blocker leaves the hint naming it, for the next ray.
    #[test]
    fn the_hint_names_the_blocker() {
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut builder = SceneBuilder::new(camera);
        let opaque = builder.material(Material::default()).unwrap();
        for x in 0..20 {
            builder.object(Sphere::new(Vec3::new(x as f64 * 3.0, 0.0, 0.0), 1.0).unwrap(), opaque).unwrap();
        }
        let scene = builder.build().unwrap();
        let mut hint = OccluderHint::NONE;
        let ray = Ray::unit(Vec3::new(30.0, 5.0, 0.0), -Vec3::Y);
        assert_eq!(scene.transmittance_hinted(&ray, 10.0, None, &mut hint), Rgb::ZERO);
        let prim = &scene.bounded[hint.prim as usize];
        assert_eq!(prim.object, 10, "the ball at x = 30 blocks");
    }
}
