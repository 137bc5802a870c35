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

use std::mem::MaybeUninit;
use std::ops::Range;

use super::trace::{NoTrace, Trace, WhittedTrace};
use super::{sample_row_one_by_one, CameraSample, Integrator, IntegratorEntry, IntegratorSettings, RayCounts, Schedule, View};
use crate::film::PixelSum;
use crate::lights::AreaLight;
use crate::math::{max_component, Rgb};
use crate::ray::{offset_origin, Ray};
use crate::sampling::{stratified_2d, Cone, Rng};
use crate::scene::{Hit, Scene};
use crate::Error;

mod direct;
mod optics;
#[cfg(target_arch = "x86_64")]
mod packets;

use direct::direct_light;
use optics::smooth_directions;

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
