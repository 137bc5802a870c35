//! The built scene: objects with materials, lights, ambient light, camera, BVH.
//!
//! [`Scene::first_intersect`] is the lecture's `firstIntersect`: the nearest hit
//! over all objects, with its normal turned to face the incoming ray.

use std::borrow::Cow;
use std::sync::Arc;

use crate::accel::{Aabb, Bvh, EyeBuffer, LightBuffer, ObjectLanes};
use crate::bsdfs::Bsdf;
use crate::lights::Light;
use crate::materials::{bsdf_for, Material};
use crate::math::Vec3;
use crate::ray::Ray;
use crate::shapes::Shape;

mod builder;
mod eye;
mod eye_lanes;
mod lanes;
mod leaving;
mod light_set;
mod reach;
mod settings;
mod shading;
mod shadow;

pub use builder::SceneBuilder;
pub use reach::{lit_share, reaches_camera_hits};
pub use settings::{SceneSettings, Sides};
pub use shadow::OccluderHint;

/// A shape placed in the scene with its material.
#[derive(Clone, Debug)]
pub struct Object {
    /// Geometry (shared: a mesh placed twice is stored once).
    pub shape: Arc<dyn Shape>,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// The shape's outward side is turned inward (Mitsuba's `flip_normals`,
    /// pbrt's `ReverseOrientation`): its front face, the side a one-sided
    /// material scatters on and an area light emits from, is the other one.
    pub reversed: bool,
}

/// A ray's nearest hit in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter (distance along the unit direction).
    pub t: f64,
    /// Hit point.
    pub point: Vec3,
    /// Unit shading normal, facing the incoming ray.
    pub normal: Vec3,
    /// Unit geometric normal, facing the incoming ray.
    pub geometric_normal: Vec3,
    /// True when the ray arrived on the shape's outward side: it is outside and
    /// entering (the lecture's `ray.out`, decided per hit from the outward normal).
    pub front_face: bool,
    /// Index of the object hit.
    pub object: usize,
    /// Index of its material.
    pub material: usize,
    /// The shape's absolute error bound for the point (see [`crate::shapes::SurfaceHit::error`]).
    pub error: f64,
    /// Triangle index within a mesh object (see [`crate::shapes::SurfaceHit::primitive`]).
    pub primitive: Option<u32>,
    /// The instant of the ray that found it ([`Ray::time`]).
    pub time: f64,
}

impl Hit {
    /// A ray leaving this hit from `origin` along the unit `dir`, at the
    /// instant of the ray that found it ([`Ray::spawn`]).
    #[inline]
    pub const fn spawn(&self, origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir, time: self.time }
    }
}

/// Everything the integrators need; immutable and shared across threads.
#[derive(Debug)]
pub struct Scene {
    /// Placed shapes.
    pub objects: Vec<Object>,
    /// Materials referenced by objects. Read-only once built: [`Scene::bsdf`]
    /// keeps the path tracer's BSDFs made from them.
    pub materials: Vec<Material>,
    /// Light sources (point, directional).
    pub lights: Vec<Arc<dyn Light>>,
    /// The camera, the ambient and background light, the sky and the
    /// recursion's limits.
    pub settings: SceneSettings,
    /// Per light, a copy of it where it is a [`crate::lights::PointLight`]
    /// ([`Scene::illuminate`]).
    point_lights: Vec<Option<crate::lights::PointLight>>,
    bvh: Bvh,
    /// Objects in the BVH, in BVH primitive order.
    bounded: Vec<PrimRef>,
    /// Some material has a trilinear texture ([`Scene::uses_footprints`]).
    uses_footprints: bool,
    /// Some shape moves during the shutter ([`Scene::shutter`]).
    moves: bool,
    /// Some material has a normal or a bump map ([`Scene::turns_normals`]).
    turns_normals: bool,
    /// Per material: whether [`Scene::shade`] can hand it over as it is (constant,
    /// or a colour of the point alone, and no normal map). One byte each, so the
    /// Whitted tracer's test touches no BSDF.
    plain: Vec<bool>,
    /// Objects with infinite bounds (infinite planes, unclipped quadrics), tested one by one.
    unbounded: Vec<PrimRef>,
    /// Per light, the light buffer of a point source (`scene/shadow.rs`); none in
    /// a scene with partly transparent shadows.
    light_buffers: Vec<Option<LightBuffer>>,
    /// The camera's eye's buffer, for rays that leave the eye (`accel/eye_buffer.rs`).
    eye_buffer: Option<EyeBuffer>,
    /// Per object, the objects near it, for rays that leave its surface back
    /// into it (`scene/leaving.rs`).
    neighbours: leaving::Neighbours,
    /// Every object's test for four rays at once, where the scene is a handful
    /// of rectangles and boxes and nothing else (`scene/lanes.rs`).
    lanes: Option<ObjectLanes>,
    /// The buffer's eye, NaN without one: the queries compare a ray's origin
    /// with it first, one comparison that fails for almost every other ray.
    eye: Vec3,
    /// Some material dims shadow rays without blocking them (transmittance strictly
    /// between 0 and 1), so shadow rays must collect every crossing.
    any_partial_shadow: bool,
    /// Per material of constant colour: its path-tracing BSDF seen from the back
    /// (`[0]`) and from the front (`[1]`), built once (see [`Scene::bsdf`]).
    bsdfs: Vec<Option<[Bsdf; 2]>>,
    /// Per material: the indices of a blend's two components ([`crate::materials::blend`]).
    blend_parts: Vec<Option<[usize; 2]>>,
    names: Names,
}

/// The names a scene file gave objects and materials (for `explain`; nothing renders by them).
#[derive(Clone, Debug, Default)]
struct Names {
    objects: Vec<Option<String>>,
    materials: Vec<Option<String>>,
}

/// Sets `list[i] = name`, growing the list as needed.
fn set_name(list: &mut Vec<Option<String>>, i: usize, name: &str) {
    if list.len() <= i {
        list.resize(i + 1, None);
    }
    list[i] = Some(name.to_string());
}

/// The closest-hit query's test of one bounded object, the nearest hit so far
/// kept: a visitor rather than a closure, so that the object test (with the
/// [`crate::shapes::Inlined`] kinds' tests) is compiled into the BVH walk.
struct Nearest<'a> {
    scene: &'a Scene,
    ray: &'a Ray,
    best: Option<(usize, crate::shapes::SurfaceHit)>,
}

impl crate::accel::Visit for &mut Nearest<'_> {
    #[inline(always)]
    fn visit(&mut self, prim: u32, t_max: f64) -> Option<f64> {
        let prim = &self.scene.bounded[prim as usize];
        let h = self.scene.hit_object(prim, self.ray, t_max)?;
        self.best = Some((prim.object as usize, h));
        Some(h.t)
    }
}

/// An object as the BVH sees it: its index and whether it stops shadow rays, kept
/// side by side so that shadow queries touch no material.
#[derive(Clone, Debug)]
struct PrimRef {
    object: u32,
    opaque: bool,
    /// Its material cuts holes ([`crate::materials::alpha`]).
    masked: bool,
    /// The shape, where its kind is tested without a virtual call
    /// ([`crate::shapes::Inlined`]).
    inlined: Option<crate::shapes::Inlined>,
}

impl Scene {
    /// The name the scene gave object `object`, if any.
    pub fn object_name(&self, object: usize) -> Option<&str> {
        self.names.objects.get(object).and_then(Option::as_deref)
    }

    /// The name the scene gave material `material`, if any.
    pub fn material_name(&self, material: usize) -> Option<&str> {
        self.names.materials.get(material).and_then(Option::as_deref)
    }

    /// The nearest hit with `0 < t < t_max`, normal turned against the ray.
    ///
    /// Inlined into its callers, so that the render loop goes straight to the
    /// compilation for this CPU: an out-of-line choice cost about 60
    /// instructions a ray, the baseline query's stack frame set up and torn
    /// down before the jump (issue 24).
    #[inline]
    pub fn first_intersect(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.first_intersect_avx2(ray, t_max) };
        }
        self.first_intersect_baseline(ray, t_max)
    }

    /// [`Scene::first_intersect`] for baseline x86-64, out of line.
    #[inline(never)]
    fn first_intersect_baseline(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        if let Some(eye) = self.eye_buffer_of(ray) {
            return self.first_intersect_from_eye_baseline(eye, ray, t_max);
        }
        self.first_intersect_in::<false>(ray, t_max)
    }

    /// [`Scene::first_intersect`] compiled whole for [`crate::cpu::AVX2_FEATURES`]
    /// (the attribute takes a literal; a test keeps the two equal), the BVH walk
    /// inlined into it. Calling the walk's own AVX2 compilation from a baseline
    /// query instead cost 7 % of a path-traced Cornell box (`BENCHMARKS.md`).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn first_intersect_avx2(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        // A ray from the eye goes to the eye's buffer, out of line: with the
        // search compiled in here, or its answer handed back through here, the
        // path-traced Cornell box (which has no buffer) took 6-9 % longer.
        if let Some(eye) = self.eye_buffer_of(ray) {
            return self.first_intersect_from_eye_avx2(eye, ray, t_max);
        }
        self.first_intersect_in::<true>(ray, t_max)
    }

    /// The eye's buffer, where `ray` leaves its eye.
    #[inline(always)]
    fn eye_buffer_of(&self, ray: &Ray) -> Option<&EyeBuffer> {
        if ray.origin.x == self.eye.x && ray.origin == self.eye {
            self.eye_buffer.as_ref()
        } else {
            None
        }
    }

    /// [`Scene::first_intersect`] with the BVH's box test chosen by `AVX2`.
    #[inline(always)]
    fn first_intersect_in<const AVX2: bool>(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        let mut best: Option<(usize, crate::shapes::SurfaceHit)> = None;
        let mut closest = t_max;
        for prim in &self.unbounded {
            let i = prim.object as usize;
            if let Some(h) = self.hit_object(prim, ray, closest) {
                closest = h.t;
                best = Some((i, h));
            }
        }
        let mut nearest = Nearest { scene: self, ray, best };
        self.bvh.traverse_in::<AVX2>(ray.origin, ray.dir, 0.0, closest, &mut nearest);
        let (object, h) = nearest.best?;
        Some(self.hit_record(ray, object, h))
    }

    /// The [`Hit`] of `ray` on object `object`, whose shape reported `h`.
    #[inline(always)]
    fn hit_record(&self, ray: &Ray, object: usize, h: crate::shapes::SurfaceHit) -> Hit {
        let faces_ray = ray.dir.dot(h.normal) < 0.0;
        let (geometric_normal, mut normal) = if faces_ray { (h.normal, h.shading_normal) } else { (-h.normal, -h.shading_normal) };
        let mut front_face = faces_ray != self.objects[object].reversed;
        // A shading normal must face the ray too, or the lighting would see the back side.
        if normal.dot(ray.dir) >= 0.0 {
            match self.settings.sides {
                Sides::Geometric => normal = geometric_normal,
                // The shading normal says the ray arrived on the other side.
                Sides::Shading => {
                    normal = -normal;
                    front_face = !front_face;
                }
            }
        }
        Hit {
            t: h.t,
            point: ray.at(h.t),
            normal,
            geometric_normal,
            front_face,
            object,
            material: self.objects[object].material,
            error: h.error,
            primitive: h.primitive(),
            time: ray.time,
        }
    }

    /// The first hit of a camera ray `ray` (depth 1): [`Scene::first_intersect`],
    /// or under [`SceneSettings::hide_emitters`] the first hit past every emitting
    /// surface, which a camera ray then goes through as Mitsuba's does (the
    /// surface still casts shadows and is seen by later segments).
    pub fn first_camera_hit(&self, ray: &Ray) -> Option<Hit> {
        let mut ray = *ray;
        // Each pass moves past one emitting surface; a bound keeps pathological stacks finite.
        for _ in 0..64 {
            let hit = self.first_intersect(&ray, f64::INFINITY)?;
            if !self.settings.hide_emitters || !self.materials[hit.material].emits() {
                return Some(hit);
            }
            ray = ray.spawn(crate::ray::offset_origin(hit.point, hit.geometric_normal, ray.dir, hit.t, hit.error), ray.dir);
        }
        None
    }

    /// The shutter interval camera samples draw their instant from
    /// ([`SceneSettings::shutter`]): `None` when no shape moves, so that a still
    /// scene draws no time and renders as it did without motion blur.
    pub fn shutter(&self) -> Option<(f64, f64)> {
        let (open, close) = self.settings.shutter;
        (self.moves && close > open).then_some((open, close))
    }

    /// Whether some material reads a footprint (a trilinear image texture), so
    /// that the Whitted tracer follows its camera rays' cones.
    pub fn uses_footprints(&self) -> bool {
        self.uses_footprints
    }

    /// Whether some material turns shading normals (a normal or bump map), so
    /// that the path tracer keeps what the map leaves of the unmapped surface
    /// ([`crate::materials::map_shadowing`]); scenes without maps skip it.
    #[inline]
    pub fn turns_normals(&self) -> bool {
        self.turns_normals
    }

    /// The nearest hit of one object in `(0, t_max)`, past its cut-outs.
    #[inline(always)]
    fn hit_object(&self, prim: &PrimRef, ray: &Ray, t_max: f64) -> Option<crate::shapes::SurfaceHit> {
        // The flag first: unmasked objects never load their material here.
        if prim.masked {
            return self.hit_masked(prim, ray, t_max);
        }
        match &prim.inlined {
            Some(shape) => shape.intersect(ray, 0.0, t_max),
            None => self.objects[prim.object as usize].shape.intersect(ray, 0.0, t_max),
        }
    }

    /// [`Scene::hit_object`] of an object whose material may cut holes, kept out
    /// of line so that the usual case inlines into the BVH walk.
    #[inline(never)]
    fn hit_masked(&self, prim: &PrimRef, ray: &Ray, t_max: f64) -> Option<crate::shapes::SurfaceHit> {
        let object = &self.objects[prim.object as usize];
        match &self.materials[object.material].alpha {
            Some(mask) => crate::materials::alpha::first_covered(&*object.shape, mask, ray, 0.0, t_max),
            None => object.shape.intersect(ray, 0.0, t_max),
        }
    }

    /// [`Light::illuminate`] of light `i` of [`Scene::lights`] at `point`, and
    /// its [`Light::own_object`]: a point light (the lecture's and POV-Ray's
    /// usual light) by a direct call compiled into the Whitted tracer's loop,
    /// the others through `dyn Light`; the same values either way.
    #[inline(always)]
    pub fn illuminate(&self, i: usize, point: Vec3) -> (Option<crate::lights::LightSample>, Option<usize>) {
        match self.point_lights.get(i) {
            Some(Some(light)) => (Light::illuminate(light, point), light.own_object),
            _ => {
                let light = &self.lights[i];
                (light.illuminate(point), light.own_object())
            }
        }
    }

    /// The surface coordinates of `hit` ([`Shape::surface_coords`]), computed
    /// now: only materials that read them ask.
    pub fn surface_coords(&self, hit: &Hit) -> crate::shapes::SurfaceCoords {
        self.objects[hit.object].shape.surface_coords_at(hit.point, self.shape_outward(hit), hit.primitive, hit.time)
    }

    /// The shape's own outward geometric normal at `hit` (before any
    /// [`Object::reversed`]), which the shape's other questions are asked with.
    pub fn shape_outward(&self, hit: &Hit) -> Vec3 {
        if hit.front_face != self.objects[hit.object].reversed {
            hit.geometric_normal
        } else {
            -hit.geometric_normal
        }
    }

    /// What the shapes noticed while rendering ([`crate::shapes::Shape::warnings`]:
    /// an implicit surface's Lipschitz bound exceeded), each text once, in object order.
    pub fn shape_warnings(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for object in &self.objects {
            for w in object.shape.warnings() {
                if !out.contains(&w) {
                    out.push(w);
                }
            }
        }
        out
    }

    /// The path tracer's BSDF at `hit`, whose material evaluated there
    /// ([`Scene::material_at`]) is `material` ([`surface_bsdf`]). Constant materials
    /// have it built once with the scene: making it per hit (scaling the lobes so
    /// they conserve energy) was an eighth of the path tracer's time.
    #[inline]
    pub fn bsdf(&self, hit: &Hit, material: &Material) -> Cow<'_, Bsdf> {
        match self.prebuilt_bsdf(hit.material, hit.front_face) {
            Some(bsdf) => Cow::Borrowed(bsdf),
            None => Cow::Owned(surface_bsdf(material, hit.point, hit.front_face)),
        }
    }

    /// The BSDF built with the scene for a material of one colour, `None` for a
    /// textured one. The path tracer's inner loop takes this reference instead of a
    /// [`Cow`], whose every use tests which variant it holds.
    #[inline]
    pub fn prebuilt_bsdf(&self, material: usize, front_face: bool) -> Option<&Bsdf> {
        match self.bsdfs.get(material) {
            Some(Some(both)) => Some(&both[front_face as usize]),
            _ => None,
        }
    }

    /// Bounds of all bounded objects.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// Total primitives (triangles count one each).
    pub fn primitive_count(&self) -> usize {
        self.objects.iter().map(|o| o.shape.primitive_count()).sum()
    }
}

/// The path tracer's BSDF of `material` at `point` seen from the front face
/// (`front_face`) or the back: [`bsdf_for`], or no lobe at all (black, and no
/// light from the back arrives through it) on the back of a
/// [`Material::one_sided`] surface.
pub fn surface_bsdf(material: &Material, point: Vec3, front_face: bool) -> Bsdf {
    if material.scatters_at(front_face) {
        bsdf_for(material, point, front_face)
    } else {
        Bsdf::new(&[])
    }
}

#[cfg(test)]
mod sides_tests;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::math::Rgb;
    use crate::shapes::Sphere;

    /// `Scene::illuminate` answers as `dyn Light` does, point lights (called
    /// directly) and other kinds alike, bit for bit.
    #[test]
    fn lights_illuminate_as_through_dyn_light() {
        use crate::lights::{DirectionalLight, Falloff, PointLight, SpotLight, SpotProfile};
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        b.light(PointLight::new(Vec3::new(1.0, 3.0, -2.0), Rgb::new(9.0, 8.0, 7.0)).unwrap());
        b.light(PointLight::new(Vec3::new(-2.0, 1.0, 0.5), Rgb::splat(3.0)).unwrap().with_falloff(Falloff::None));
        b.light(SpotLight::new(Vec3::new(0.0, 3.0, 0.0), -Vec3::Y, Rgb::splat(9.0), 10.0, 20.0, SpotProfile::Smoothstep).unwrap());
        b.light(DirectionalLight::new(Vec3::new(0.3, -1.0, 0.2), Rgb::splat(2.0)).unwrap());
        let scene = b.build().unwrap();
        assert_eq!(scene.point_lights.iter().map(Option::is_some).collect::<Vec<_>>(), [true, true, false, false]);
        let mut rng = crate::sampling::Rng::for_sample(9, 0, 0);
        for _ in 0..200 {
            let point = Vec3::new(rng.uniform() * 6.0 - 3.0, rng.uniform() * 6.0 - 3.0, rng.uniform() * 6.0 - 3.0);
            for (i, light) in scene.lights.iter().enumerate() {
                let direct = scene.illuminate(i, point);
                assert_eq!(direct, (light.illuminate(point), light.own_object()), "light {i} at {point}");
            }
        }
    }

    /// A bulb of radius 2 around the origin with a small opaque ball inside it,
    /// off centre towards +x, and an opaque ball outside it on the -x side.
    fn bulb_scene() -> Scene {
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut builder = SceneBuilder::new(camera);
        let opaque = builder.material(Material::default()).unwrap();
        builder.object(Sphere::new(Vec3::ZERO, 2.0).unwrap(), opaque).unwrap();
        builder.object(Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.5).unwrap(), opaque).unwrap();
        builder.object(Sphere::new(Vec3::new(-4.0, 0.0, 0.0), 0.5).unwrap(), opaque).unwrap();
        builder.build().unwrap()
    }

    #[test]
    fn shadow_rays_end_at_the_lights_own_object() {
        let scene = bulb_scene();
        // From (5, 0, 0) towards the centre: the bulb's surface at distance 3 comes
        // before the inner ball (distance 3.5 to 4.5): the light is seen.
        let from_right = Vec3::new(5.0, 0.0, 0.0);
        assert_eq!(scene.transmittance(&Ray::unit(from_right, -Vec3::X), 5.0, Some(0)), Rgb::ONE);
        // Without an own object, the bulb itself blocks.
        assert_eq!(scene.transmittance(&Ray::unit(from_right, -Vec3::X), 5.0, None), Rgb::ZERO);
        // Outside the bulb, occluders still count: the ball at x = -4 blocks from x = -6.
        assert_eq!(scene.transmittance(&Ray::unit(Vec3::new(-6.0, 0.0, 0.0), Vec3::X), 6.0, Some(0)), Rgb::ZERO);
        // A ray that starts inside the bulb meets it only beyond the light: it is not
        // cut short, so the inner ball still shadows a point behind it.
        assert_eq!(scene.transmittance(&Ray::unit(Vec3::new(1.8, 0.0, 0.0), -Vec3::X), 1.8, Some(0)), Rgb::ZERO);
        assert_eq!(scene.transmittance(&Ray::unit(Vec3::new(0.0, 1.5, 0.0), -Vec3::Y), 1.5, Some(0)), Rgb::ONE);
    }

    /// The attributes of the AVX2 queries name [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_queries_are_compiled_for_the_detected_features() {
        let source = [include_str!("mod.rs"), include_str!("shadow.rs"), include_str!("eye.rs")].concat();
        for (name, prefix) in [
            ("first_intersect_avx2", ""),
            ("transmittance_avx2", "pub(super) "),
            ("transmittance_fresh_avx2", "pub(super) "),
            ("first_intersect_from_eye_avx2", "pub(super) "),
        ] {
            let attribute = format!("#[target_feature(enable = \"{}\")]\n    {prefix}unsafe fn {name}", crate::cpu::AVX2_FEATURES);
            assert!(source.contains(&attribute), "{name} must be compiled for AVX2_FEATURES");
        }
    }

    /// The baseline and the AVX2 compilation of the queries answer alike, bit
    /// for bit: the same hit (distance, point, normals, object) and the same
    /// shadow answer, on a tree of 60 balls and on a flat set of 6.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn both_compilations_of_the_queries_agree() {
        if !crate::cpu::avx2_features() {
            eprintln!("skipped: this CPU lacks AVX2, so only the baseline compilation runs");
            return;
        }
        let mut rng = crate::sampling::Rng::for_sample(7, 0, 0);
        let mut rand = move || rng.uniform();
        for balls in [60, 6] {
            let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
            let mut builder = SceneBuilder::new(camera);
            let opaque = builder.material(Material::default()).unwrap();
            let mut centres = Vec::new();
            for _ in 0..balls {
                let centre = Vec3::new(rand() * 8.0 - 4.0, rand() * 8.0 - 4.0, rand() * 8.0 - 4.0);
                builder.object(Sphere::new(centre, 0.2 + rand() * 0.6).unwrap(), opaque).unwrap();
                centres.push(centre);
            }
            let scene = builder.build().unwrap();
            let mut hits = 0;
            for _ in 0..4000 {
                // Aimed near a ball, so that about half the rays hit something.
                let origin = Vec3::new(rand() * 12.0 - 6.0, rand() * 12.0 - 6.0, rand() * 12.0 - 6.0);
                let target = centres[(rand() * balls as f64) as usize] + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5);
                let dir = (target - origin).normalize();
                let ray = Ray::unit(origin, dir);
                let base = scene.first_intersect_in::<false>(&ray, f64::INFINITY);
                // SAFETY: the CPU has the features (checked above).
                let avx2 = unsafe { scene.first_intersect_avx2(&ray, f64::INFINITY) };
                let key = |h: &Option<Hit>| {
                    h.map(|h| (h.t.to_bits(), h.point.to_array().map(f64::to_bits), h.normal.to_array().map(f64::to_bits), h.object))
                };
                assert_eq!(key(&base), key(&avx2), "ray {ray:?}");
                hits += usize::from(base.is_some());
                let distance = rand() * 10.0;
                let shadow = scene.transmittance_in::<false>(&ray, distance, None, &mut OccluderHint::default());
                // SAFETY: as above.
                assert_eq!(
                    shadow,
                    unsafe { scene.transmittance_avx2(&ray, distance, None, &mut OccluderHint::default()) },
                    "ray {ray:?} to {distance}"
                );
                let own = (rand() * balls as f64) as usize;
                // SAFETY: as above.
                let fresh = unsafe { scene.transmittance_fresh_avx2(&ray, distance, Some(own), &mut OccluderHint::default()) };
                assert_eq!(scene.transmittance_in::<false>(&ray, distance, Some(own), &mut OccluderHint::default()), fresh);
                // The public query, which sends a ray without a light's body to the fresh compilation.
                assert_eq!(scene.transmittance(&ray, distance, None), shadow, "ray {ray:?} to {distance}");
            }
            assert!(hits > 400, "{balls} balls: only {hits} of 4000 rays hit, too few to compare");
        }
    }
}
