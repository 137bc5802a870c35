//! The lecture's recursive ray tracer (Whitted 1980), run without recursion.
//!
//! `trace(ray, d)`: the nearest hit's direct light (ambient, emission, the rough
//! model over unshadowed lights) plus the weighted radiance of the reflected and
//! refracted rays, down to the depth limit. The radiance is linear in the radiance
//! of the secondary rays, so instead of recursing the integrator keeps a work list
//! of (ray, weight, depth) and sums `weight * direct light`: the stack cannot
//! overflow whatever the depth limit, and the work is bounded by `2^depth` rays
//! per camera ray (less with the weight cut-off).
//!
//! Emitting objects are area lights here too (POV-Ray's `area_light`): each hit
//! takes [`AREA_SAMPLES`] stratified points on every one, each with its own
//! shadow ray, so they give soft shadows. A sample of density `pdf` (solid
//! angle) stands for `Lin = Le / (pi pdf N)`, the lecture's light term that the
//! rough model multiplies: the same reading of `kd` that makes the path tracer
//! agree ([`crate::lights::DELTA_SCALE`]). Rays that leave the scene see the
//! environment map if there is one, else the background colour.

use std::cell::Cell;
use std::mem::MaybeUninit;
use std::ops::Range;

use super::trace::{LightRef, LightTerm, NoTrace, ReflectionWeight, Trace, Unlit, WhittedTrace};
use super::{sample_row_one_by_one, CameraSample, Integrator, IntegratorEntry, IntegratorSettings, RayCounts, Schedule, View};
use crate::film::PixelSum;
use crate::lights::AreaLight;
use crate::materials::{fresnel_conductor, fresnel_dielectric, Material, Reflection, Refraction};
use crate::math::{max_component, Rgb, Vec3};
use crate::ray::{offset_origin, Ray};
use crate::sampling::{stratified_2d, Cone, Rng};
use crate::scene::{Hit, OccluderHint, Scene};
use crate::Error;

#[cfg(target_arch = "x86_64")]
mod packets;

/// The registry's entry.
pub const ENTRY: IntegratorEntry = IntegratorEntry {
    name: "whitted",
    summary: "recursive (Whitted) ray tracing: the lecture's trace, with shadows, mirror reflection and refraction",
    build: build_whitted,
    schedule: Schedule::OnePass,
    filters: false,
};

fn build_whitted(scene: &Scene, settings: &IntegratorSettings) -> Result<Box<dyn Integrator>, Error> {
    Ok(Box::new(Whitted::new(scene, settings.max_depth, scene.settings.min_weight)))
}

/// Points taken on each area light at each hit (a 4 x 4 grid, jittered).
pub const AREA_SAMPLES: u32 = 16;

/// Lights that keep an [`OccluderHint`] of their own; further lights share them
/// (light `i` uses hint `i % HINTS`, area lights numbered after the delta lights).
const HINTS: usize = 8;

thread_local! {
    /// Per light, the object that last blocked a shadow ray towards it on this
    /// thread, tried first by the next one (`scene/shadow.rs`): neighbouring
    /// pixels mostly share their occluder. Kept per thread because the render
    /// loop hands a sample nothing mutable but its ray counts; no value here
    /// changes an answer, only how soon it is known, so images do not depend
    /// on the thread or the order pixels are traced in.
    static OCCLUDERS: [Cell<OccluderHint>; HINTS] = const { [const { Cell::new(OccluderHint::NONE) }; HINTS] };
}

/// Lights whose `N.L` is at or below this are skipped (POV-Ray's threshold).
const MIN_COSINE: f64 = 1e-10;
/// A light whose unshadowed reflection factor (`kd C (L.N) + ks (H.N)^n`, per unit
/// incident radiance) is below this in every channel is skipped without a shadow
/// ray: 1e-12 is far below what an `f32` film value of a lit pixel can resolve.
const NEGLIGIBLE: f64 = 1e-12;

/// Whitted ray tracing with a depth limit.
#[derive(Clone, Debug)]
pub struct Whitted {
    /// Rays deeper than this return black (camera ray = 1).
    pub max_depth: u32,
    /// Secondary rays with weight at or below this in every channel are dropped.
    pub min_weight: f64,
    /// The scene's emitting objects.
    area_lights: Vec<AreaLight>,
}

/// The deepest recursion the integrators accept: the work list lives on the stack
/// and holds at most `max_depth + 1` pending rays. The one statement of the
/// depth limit: scene files and front ends check against it.
pub const MAX_DEPTH_LIMIT: u32 = 64;

#[derive(Clone, Copy)]
struct Pending {
    ray: Ray,
    weight: Rgb,
    depth: u32,
    /// Width of the ray's pixel footprint at its origin ([`Cone`]).
    width: f64,
    /// The object whose surface the ray leaves (`usize::MAX` for the camera
    /// ray): [`Scene::first_intersect_leaving`] looks near it first.
    from: usize,
}

impl Integrator for Whitted {
    /// One sample: a single sample per pixel sits at the camera's pixel offset;
    /// `n > 1` samples are stratified over the pixel ([`stratified_2d`], strata
    /// shifted by `pixel_offset - 0.5`) and jittered by the sample's own generator,
    /// which then draws the lens sample if the camera takes one, and the instant
    /// in the shutter if a shape moves ([`View::shutter`]).
    #[inline(always)]
    fn sample(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts) -> Rgb {
        self.sample_with(view, x, y, index, counts, &mut NoTrace)
    }

    fn sample_traced(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts, trace: &mut dyn Trace) -> Rgb {
        self.sample_with(view, x, y, index, counts, trace)
    }

    fn camera_sample(&self, view: &View, x: u32, y: u32, index: u32) -> CameraSample {
        let mut rng = None;
        let mut uniform = || rng.get_or_insert_with(|| Rng::for_sample(view.seed, view.pixel_index(x, y), index as u64)).uniform();
        camera_sample_from(view, x, y, index, &mut uniform)
    }

    fn schedule(&self) -> Schedule {
        Schedule::OnePass
    }

    /// Four pixels' camera rays at a time where they can share the eye's
    /// search (`whitted/packets.rs`), else each sample on its own: the same values.
    fn sample_row(&self, view: &View, row: (u32, u32), samples: Range<u32>, counts: &mut RayCounts, sums: &mut [PixelSum]) -> u64 {
        #[cfg(target_arch = "x86_64")]
        if packets::apply(view, &samples) && crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { packets::row_avx2(self, view, row, counts, sums) };
        }
        sample_row_one_by_one(self, view, row, samples, counts, sums)
    }
}

/// The camera ray of sample `index` of pixel `(x, y)`, its position and lens
/// point drawn from `uniform` (the sample's generator, which then goes on to
/// the area lights): one function for [`Integrator::sample`] and
/// [`Integrator::camera_sample`], so the feature pass follows exactly the rays
/// the render traced.
#[inline(always)]
fn camera_sample_from(view: &View, x: u32, y: u32, index: u32, uniform: &mut impl FnMut() -> f64) -> CameraSample {
    let offset = view.pixel_offset;
    let (dx, dy) = if view.spp == 1 {
        (offset, offset)
    } else {
        let jitter = (uniform(), uniform());
        let (sx, sy) = stratified_2d(index, view.spp, jitter);
        let shift = offset - 0.5;
        (sx + shift, sy + shift)
    };
    let lens = if view.lens { (uniform(), uniform()) } else { (0.5, 0.5) };
    let (fx, fy) = (x as f64 + dx, y as f64 + dy);
    let mut ray = view.camera.ray(fx, fy, view.width, view.height, lens);
    if let Some(shutter) = view.shutter {
        ray.time = View::instant(shutter, uniform());
    }
    let cone = if view.scene.uses_footprints() { view.pixel_cone(&ray, fx, fy, lens) } else { Cone::default() };
    CameraSample { ray, cone, weight: 1.0 }
}

impl Whitted {
    /// [`Integrator::sample`], telling `trace` what it does.
    #[inline(always)]
    fn sample_with<T: WhittedTrace + ?Sized>(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts, trace: &mut T) -> Rgb {
        self.sample_known(view, (x, y, index), None, counts, trace)
    }

    /// [`Whitted::sample_with`] of sample `index` of pixel `(x, y)`, its
    /// camera sample and that ray's first hit given where the caller has
    /// them (`whitted/packets.rs`), else made here.
    #[inline(always)]
    fn sample_known<T: WhittedTrace + ?Sized>(
        &self,
        view: &View,
        (x, y, index): (u32, u32, u32),
        known: Option<(&CameraSample, &mut Option<Hit>)>,
        counts: &mut RayCounts,
        trace: &mut T,
    ) -> Rgb {
        // Made only when a value is drawn: a single pinhole sample needs none.
        let mut rng = None;
        let mut uniform = || rng.get_or_insert_with(|| Rng::for_sample(view.seed, view.pixel_index(x, y), index as u64)).uniform();
        let (camera, first) = match known {
            Some((camera, hit)) => (*camera, Some(hit)),
            None => (camera_sample_from(view, x, y, index, &mut uniform), None),
        };
        self.trace_traced(view.scene, &camera.ray, camera.cone, first, &mut uniform, counts, trace)
    }

    /// The tracer for `scene` (its area lights are collected here).
    pub fn new(scene: &Scene, max_depth: u32, min_weight: f64) -> Whitted {
        Whitted { max_depth, min_weight, area_lights: scene.light_set().area }
    }

    /// The lecture's `trace`: the radiance arriving along camera ray `ray`.
    /// Area lights draw their points from a fixed generator.
    pub fn trace(&self, scene: &Scene, ray: &Ray, counts: &mut RayCounts) -> Rgb {
        let mut rng = Rng::for_sample(0, 0, 0);
        self.trace_with(scene, ray, &mut || rng.uniform(), counts)
    }

    /// [`Whitted::trace`] with the values of `[0, 1)` for area light points drawn
    /// from `uniform` (called only when the scene has area lights).
    pub fn trace_with(&self, scene: &Scene, ray: &Ray, uniform: &mut dyn FnMut() -> f64, counts: &mut RayCounts) -> Rgb {
        self.trace_cone(scene, ray, Cone::default(), uniform, counts)
    }

    /// [`Whitted::trace_with`] for a camera ray whose pixel footprint is `cone`
    /// (textures are filtered over it; a zero cone reads them unfiltered).
    pub fn trace_cone(&self, scene: &Scene, ray: &Ray, cone: Cone, uniform: &mut dyn FnMut() -> f64, counts: &mut RayCounts) -> Rgb {
        self.trace_traced(scene, ray, cone, None, uniform, counts, &mut NoTrace)
    }

    /// [`Whitted::trace_cone`], telling `trace` each ray, hit, term and weight.
    /// `first`: the camera ray's first hit, where the caller has found it
    /// already (`whitted/packets.rs`).
    /// Inlined into the render loop, so that the loop's second compilation
    /// ([`crate::cpu`]) covers it (a call of its own cost 0.35 % fewer
    /// instructions in the baseline compilation, `BENCHMARKS.md`).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn trace_traced<T: WhittedTrace + ?Sized>(
        &self,
        scene: &Scene,
        ray: &Ray,
        cone: Cone,
        mut first: Option<&mut Option<Hit>>,
        uniform: &mut dyn FnMut() -> f64,
        counts: &mut RayCounts,
        trace: &mut T,
    ) -> Rgb {
        counts.camera += 1;
        let mut total = Rgb::ZERO;
        // Depth-first: each ray taken off the list adds at most two one level deeper,
        // so the list never holds more than one pending sibling per level plus two.
        // Left uninitialized: filling 4 KB per camera ray cost more than tracing it.
        let mut work = [const { MaybeUninit::<Pending>::uninit() }; MAX_DEPTH_LIMIT as usize + 2];
        let mut pending = 0;
        // The ray pushed last, which is taken next, kept out of the list: read
        // back right after it was written, the list's copy waited for the
        // push's stores (a store-forwarding stall, issue 24).
        let mut next = Some(Pending { ray: *ray, weight: Rgb::ONE, depth: 1, width: cone.width, from: usize::MAX });
        let max_depth = self.max_depth.min(MAX_DEPTH_LIMIT);
        // The hit of the ray in hand, unless the caller holds it (`first`).
        let mut own: Option<Hit>;
        loop {
            let Pending { ray, weight, depth, width, from } = match next.take() {
                Some(p) => p,
                None if pending > 0 => {
                    pending -= 1;
                    // SAFETY: entries below `pending` were written before (each push
                    // writes `work[pending]` and then increments it).
                    unsafe { work[pending].assume_init_read() }
                }
                None => break,
            };
            trace.ray(&ray, weight, depth);
            // Mitsuba's `hide_emitters`: the camera sees through emitters, and black sky.
            let hidden = depth == 1 && scene.settings.hide_emitters;
            let found: &mut Option<Hit> = if hidden {
                own = scene.first_camera_hit(&ray);
                &mut own
            } else if depth > 1 {
                own = scene.first_intersect_leaving(&ray, from);
                &mut own
            } else {
                // The camera ray's hit, where the caller has found it already
                // (`whitted/packets.rs`): the query's answer, used where the
                // query stored it. Copied out, its wide loads waited on the
                // query's narrower stores (issue 24).
                match first.take() {
                    Some(found) => found,
                    None => {
                        own = scene.first_intersect(&ray, f64::INFINITY);
                        &mut own
                    }
                }
            };
            // Used in place, by reference, as the path tracer does: moving the
            // hit out of `found` copied it with wide loads over the query's
            // narrow stores, a store-forwarding stall on every hit (issue 24).
            let Some(hit) = found.as_mut() else {
                let sky = if hidden {
                    Rgb::ZERO
                } else {
                    // Read back a coordinate at a time: the map's lookup (out
                    // of line) returns through memory, and the wide loads of
                    // the sum below stalled on its stores (issue 24).
                    scene
                        .settings
                        .environment
                        .as_ref()
                        .map_or(scene.settings.background, |env| crate::math::read_forwarded(&env.radiance(ray.dir)))
                };
                let contribution = weight * sky;
                trace.miss(sky, contribution);
                total += contribution;
                continue;
            };
            let width = width + cone.spread * hit.t;
            // Shaded first, so the tree shows the normal the lighting used (a normal map's).
            let material = &*scene.shade(hit, -ray.dir, width);
            trace.hit(scene, hit);
            let direct = direct_light(scene, &self.area_lights, &ray, hit, material, uniform, counts, trace);
            let contribution = weight * direct;
            trace.direct(direct, contribution);
            total += contribution;
            if depth >= max_depth {
                trace.depth_cutoff();
                continue;
            }
            if !material.scatters_at(hit.front_face) {
                continue;
            }
            for (dir, w) in smooth_directions(&ray, hit, material, trace) {
                let w = weight * w;
                if max_component(w) <= self.min_weight {
                    trace.branch(&hit.spawn(hit.point, dir), w, depth + 1, false);
                    continue;
                }
                counts.secondary += 1;
                let origin = offset_origin(hit.point, hit.geometric_normal, dir, hit.t, hit.error);
                trace.branch(&hit.spawn(origin, dir), w, depth + 1, true);
                if let Some(earlier) = next.replace(Pending {
                    ray: hit.spawn(origin, dir),
                    weight: w,
                    depth: depth + 1,
                    width,
                    from: scene.leaving_into(hit, dir),
                }) {
                    work[pending].write(earlier);
                    pending += 1;
                }
            }
        }
        total
    }
}

/// The lecture's `DirectLight`: `Ke + ka*C*La + sum over visible lights of
/// Lin * (kd*C (L.N) + ks (H.N)^shine)`, skipping lights with `L.N <= 1e-10`.
/// `Ke` counts on the side the surface emits from ([`Material::emits_towards`]).
/// The lights are the scene's delta lights and the area lights `area_lights`,
/// whose points are drawn from `uniform` (16 per light, see the module doc).
/// Each term is told to `trace`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn direct_light<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    area_lights: &[AreaLight],
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    uniform: &mut dyn FnMut() -> f64,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    // The material as evaluated at the hit (`Scene::material_at`): its colour is
    // a constant or the 3D checker, worked out here from the point; any other
    // colour `Texture::evaluate` (not inlined) returns through memory is read
    // back a coordinate at a time (issue 24: `BENCHMARKS.md`, session 34, has
    // the variants measured).
    let color = match material.color.of_point(hit.point) {
        Some(c) => c,
        None => crate::math::read_forwarded(&material.color.evaluate(&crate::materials::ShadingPoint::at(hit.point))),
    };
    let emission = if material.emits_towards(hit.front_face) { material.emission } else { Rgb::ZERO };
    // The back of a one-sided surface scatters nothing, not even the ambient light.
    let scatters = material.scatters_at(hit.front_face);
    let ambient = if scatters { material.ka * color * scene.settings.ambient } else { Rgb::ZERO };
    trace.surface(color, emission, ambient);
    let mut radiance = emission + ambient;
    if !material.is_lit() || !scatters {
        return radiance;
    }
    for i in 0..scene.lights.len() {
        trace.light(LightRef::Delta(i));
        let (Some(sample), own) = scene.illuminate(i, hit.point) else {
            trace.unlit(Unlit::NotReached);
            continue;
        };
        let incident = Incident { wi: sample.wi, distance: sample.distance, lin: sample.radiance, own, light: i };
        radiance += lit_by(scene, ray, hit, material, color, &incident, counts, trace);
    }
    if !area_lights.is_empty() {
        radiance += area_light(scene, area_lights, ray, hit, material, color, uniform, counts, trace);
    }
    radiance
}

/// Light arriving at a hit from one light (or one point of an area light).
struct Incident {
    /// Unit direction towards the light.
    wi: Vec3,
    /// Distance to the light.
    distance: f64,
    /// Radiance arriving if nothing blocks it.
    lin: Rgb,
    /// The light's own body, which does not block it.
    own: Option<usize>,
    /// The light's number, delta lights first, which picks its [`OccluderHint`].
    light: usize,
}

/// What the rough model reflects towards `-ray.dir` of light `lin` arriving
/// from `wi` over `distance` if nothing blocks it: `Lin (kd C (L.N) + ks
/// (H.N)^shine)` times the shadow ray's transmittance (`own` does not block).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn lit_by<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    color: Rgb,
    incident: &Incident,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    let Incident { wi, distance, lin, own, light } = *incident;
    // A light point that sends nothing (a black texel of a textured emitter)
    // adds `0 * visible * reflected = 0` whatever blocks it: no shadow ray.
    if lin == Rgb::ZERO {
        trace.unlit(Unlit::NotReached);
        return Rgb::ZERO;
    }
    let n = hit.normal;
    let cos_light = n.dot(wi);
    if cos_light <= MIN_COSINE || hit.geometric_normal.dot(wi) <= 0.0 {
        trace.unlit(Unlit::Below(cos_light));
        return Rgb::ZERO;
    }
    // The unshadowed reflection first: a light whose contribution could not
    // show (a highlight of a material without diffuse term, far from its peak)
    // costs no shadow ray.
    let diffuse = material.kd * color * cos_light;
    let cos_half = n.dot((wi - ray.dir).normalize());
    let specular =
        if cos_half > 0.0 && material.ks != Rgb::ZERO { material.ks * blinn_power(cos_half, material.shininess) } else { Rgb::ZERO };
    let reflected = diffuse + specular;
    if max_component(reflected) < NEGLIGIBLE {
        trace.unlit(Unlit::Negligible);
        return Rgb::ZERO;
    }
    counts.shadow += 1;
    let origin = offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error);
    let remaining = distance - (origin - hit.point).length();
    // The query stays outside `with`'s closure, which the compiler may keep out of line.
    let mut hint = OCCLUDERS.with(|hints| hints[light % HINTS].get()).towards(light);
    // Read back one component at a time: the first test of the query's
    // answer below stalled on its stores (issue 24, `read_forwarded`).
    let visible = crate::math::read_forwarded(&scene.transmittance_hinted(&hit.spawn(origin, wi), remaining, own, &mut hint));
    // Only the object is read back (the query writes that alone): loading the
    // whole hint spanned the query's narrower store, a store-forwarding stall
    // on every shadow ray (issue 24).
    OCCLUDERS.with(|hints| hints[light % HINTS].set(hint.towards(light)));
    let mut told = |radiance: Rgb| {
        let shadow = hit.spawn(origin, wi);
        let term = LightTerm {
            wi,
            distance,
            lin,
            cos_light,
            cos_half,
            diffuse,
            specular,
            shadow,
            shadow_length: remaining,
            own,
            visible,
            radiance,
        };
        trace.lit(scene, &term);
    };
    if visible == Rgb::ZERO {
        told(Rgb::ZERO);
        return Rgb::ZERO;
    }
    let radiance = lin * visible * reflected;
    told(radiance);
    radiance
}

/// The rough model under the area lights `lights`: [`AREA_SAMPLES`] points on
/// each, stratified on a 4 x 4 grid of the light's sample square and jittered by
/// `uniform`, each standing for `Lin = Le / (pi pdf N)`; `color` is `C` at the hit.
#[allow(clippy::too_many_arguments)]
fn area_light<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    lights: &[AreaLight],
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    color: Rgb,
    uniform: &mut dyn FnMut() -> f64,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    let mut radiance = Rgb::ZERO;
    let side = (AREA_SAMPLES as f64).sqrt() as u32;
    let scale = 1.0 / (std::f64::consts::PI * AREA_SAMPLES as f64);
    for (j, light) in lights.iter().enumerate() {
        for k in 0..AREA_SAMPLES {
            let (jx, jy) = (uniform(), uniform());
            let u = (((k % side) as f64 + jx) / side as f64, ((k / side) as f64 + jy) / side as f64);
            trace.light(LightRef::Area { object: light.object, sample: k });
            let Some(s) = light.sample(hit.point, u) else {
                trace.unlit(Unlit::NotReached);
                continue;
            };
            let lin = s.radiance * (scale / s.pdf);
            let incident = Incident { wi: s.wi, distance: s.distance, lin, own: Some(light.object), light: scene.lights.len() + j };
            radiance += lit_by(scene, ray, hit, material, color, &incident, counts, trace);
        }
    }
    radiance
}

/// `x^n` for the Blinn lobe; integer exponents (the usual case) by repeated
/// squaring, which is several times faster than `powf`. Written out rather than
/// `powi`, which calls a runtime routine; the multiplications are the same, in
/// the same order, so the value is the same.
#[inline]
fn blinn_power(x: f64, n: f64) -> f64 {
    // `(n as u32) as f64 == n` tests for an integer without the libm call that
    // `fract` is on baseline x86-64.
    if (0.0..=4096.0).contains(&n) && (n as u32) as f64 == n {
        let (mut base, mut exponent, mut result) = (x, n as u32, 1.0);
        loop {
            if exponent & 1 != 0 {
                result *= base;
            }
            exponent >>= 1;
            if exponent == 0 {
                return result;
            }
            base *= base;
        }
    } else {
        x.powf(n)
    }
}

/// Mirror direction of unit `d` about unit `n`: `d - 2 (d.n) n`.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - n * (2.0 * d.dot(n))
}

/// Refracted direction of unit `d` through a surface with unit normal `n` facing
/// the ray, `eta = n_i / n_t` (Heckbert's form): with `c = -d.n` and
/// `k = 1 - eta^2 (1 - c^2)`, `T = eta d + (eta c - sqrt(k)) n`; `None` when `k < 0`
/// (total internal reflection). Snell's law `n_i sin(i) = n_t sin(t)` holds for `T`.
#[inline]
pub fn refract(d: Vec3, n: Vec3, eta: f64) -> Option<Vec3> {
    let c = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - c * c);
    if k < 0.0 {
        return None;
    }
    Some((d * eta + n * (eta * c - k.sqrt())).normalize())
}

/// The reflected and refracted directions with their weights (at most two),
/// announced to `trace` in that order.
#[inline(always)]
fn smooth_directions<T: WhittedTrace + ?Sized>(
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    trace: &mut T,
) -> impl Iterator<Item = (Vec3, Rgb)> {
    let n = hit.normal;
    let cos_i = (-ray.dir.dot(n)).clamp(0.0, 1.0);
    // Relative index n_t / n_i for a boundary of index `ior`, entered from outside
    // when the ray is on the front face.
    let relative = |ior: f64| if hit.front_face { ior } else { 1.0 / ior };
    // Whether the weight is nonzero is decided from the value it is made of:
    // comparing the splatted `Rgb` read it back with a load across two of the
    // splat's stores, a store-forwarding stall on every mirror hit (issue 24).
    let (reflection, how, reflects) = match &material.reflection {
        Reflection::None => (Rgb::ZERO, ReflectionWeight::Constant, false),
        Reflection::Constant(w) => (*w, ReflectionWeight::Constant, *w != Rgb::ZERO),
        Reflection::Dielectric { ior, min, max } => {
            let fresnel = fresnel_dielectric(cos_i, relative(*ior));
            let w = min + (max - min) * fresnel;
            (Rgb::splat(w), ReflectionWeight::Dielectric { fresnel }, w != 0.0)
        }
        Reflection::Conductor { eta, k } => {
            let w = fresnel_conductor(cos_i, *eta, *k);
            (w, ReflectionWeight::Conductor, w != Rgb::ZERO)
        }
    };
    if reflects {
        trace.reflection(how, reflection);
    }
    let refraction = match &material.refraction {
        Refraction::None => None,
        Refraction::Fresnel { ior } => {
            let eta = relative(*ior);
            match refract(ray.dir, n, 1.0 / eta) {
                Some(t) => {
                    let fresnel = fresnel_dielectric(cos_i, eta);
                    trace.refraction(Some(fresnel), Some(Rgb::splat(1.0 - fresnel)));
                    // Tested as the scalar, as the reflection's weight above.
                    (1.0 - fresnel != 0.0).then_some((t, Rgb::splat(1.0 - fresnel)))
                }
                None => {
                    trace.refraction(None, None);
                    None
                }
            }
        }
        Refraction::Constant { ior, weight } => {
            let refracted = refract(ray.dir, n, 1.0 / relative(*ior)).map(|t| (t, *weight));
            trace.refraction(None, refracted.map(|(_, w)| w));
            refracted.filter(|(_, w)| *w != Rgb::ZERO)
        }
    };
    let reflected = reflects.then(|| (reflect(ray.dir, n), reflection));
    reflected.into_iter().chain(refraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A light point of zero radiance adds nothing and traces no shadow ray; the
    /// same point with radiance traces one, blocked or not.
    #[test]
    fn a_light_point_that_sends_nothing_costs_no_shadow_ray() {
        use crate::camera::{Fov, Perspective};
        use crate::scene::SceneBuilder;
        use crate::shapes::Sphere;
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut builder = SceneBuilder::new(camera);
        let matte = builder.material(Material::default()).unwrap();
        builder.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), matte).unwrap();
        builder.object(Sphere::new(Vec3::new(0.0, 0.0, 3.0), 0.5).unwrap(), matte).unwrap();
        let scene = builder.build().unwrap();
        let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z);
        let mut hit = scene.first_intersect(&Ray::new(Vec3::new(0.0, 0.0, 2.0), -Vec3::Z), f64::INFINITY).unwrap();
        let material = &*scene.shade(&mut hit, Vec3::Z, 0.0);
        let towards = |z: f64, lin: Rgb| {
            let to = Vec3::new(0.0, 0.0, z) - hit.point;
            Incident { wi: to.normalize(), distance: to.length(), lin, own: None, light: 0 }
        };
        let lit = |incident: Incident| {
            let mut counts = RayCounts::default();
            let value = lit_by(&scene, &ray, &hit, material, Rgb::ONE, &incident, &mut counts, &mut NoTrace);
            (value, counts.shadow)
        };
        // Towards z = 6 the small ball at z = 3 blocks; towards z = 2 nothing does.
        assert_eq!(lit(towards(6.0, Rgb::ZERO)), (Rgb::ZERO, 0));
        assert_eq!(lit(towards(2.0, Rgb::ZERO)), (Rgb::ZERO, 0));
        assert_eq!(lit(towards(6.0, Rgb::ONE)), (Rgb::ZERO, 1));
        let (value, shadow) = lit(towards(2.0, Rgb::ONE));
        assert!(value.x > 0.0 && shadow == 1, "{value:?}");
    }

    #[test]
    fn snells_law_holds() {
        let n = Vec3::Y;
        for deg in [0.0f64, 10.0, 30.0, 60.0, 85.0] {
            let th = deg.to_radians();
            let d = Vec3::new(th.sin(), -th.cos(), 0.0);
            let t = refract(d, n, 1.0 / 1.5).unwrap();
            let sin_t = t.x;
            assert!((th.sin() - 1.5 * sin_t).abs() < 1e-12, "{deg} deg");
            assert!((t.length() - 1.0).abs() < 1e-12 && t.y < 0.0);
        }
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        let critical = (1.0f64 / 1.5).asin();
        let n = Vec3::Y;
        let dir = |th: f64| Vec3::new(th.sin(), -th.cos(), 0.0);
        assert!(refract(dir(critical + 1e-6), n, 1.5).is_none());
        let grazing = refract(dir(critical - 1e-6), n, 1.5).unwrap();
        assert!(grazing.y.abs() < 0.01, "refracted ray leaves almost along the surface");
    }

    #[test]
    fn blinn_power_equals_powi() {
        for x in [0.0, 0.3, 0.5, 0.99, 1.0] {
            for n in [0u32, 1, 2, 7, 40, 255, 4096] {
                assert_eq!(blinn_power(x, n as f64), x.powi(n as i32), "{x}^{n}");
            }
        }
        assert_eq!(blinn_power(0.5, 2.5), 0.5f64.powf(2.5));
    }

    #[test]
    fn reflection_keeps_the_angle() {
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        assert!((reflect(d, Vec3::Y) - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
    }
}
