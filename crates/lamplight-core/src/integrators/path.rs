//! Unidirectional path tracing with next-event estimation and multiple
//! importance sampling (Veach 1997, ch. 9; pbrt's `PathIntegrator`).
//!
//! At each vertex the path adds one light sample (a light picked uniformly, a
//! point or direction on it) and continues along a BSDF sample. Light that both
//! strategies can find (area lights, the sky, through non-delta lobes) is
//! weighted by the power heuristic `w_a = p_a^2 / (p_a^2 + p_b^2)`; delta lights
//! only by light sampling, delta lobes only by BSDF sampling (weight 1). After
//! [`PathTracer::rr_depth`] segments a path survives with probability
//! `min(1, max(throughput))` and is reweighted (Russian roulette), which keeps
//! the estimate unbiased. Depth counts segments: 1 sees emitters only, 2 adds
//! direct light, `max_depth` ends the path (the Whitted convention).
//!
//! Shadow rays must reach the light without meeting anything: unlike the
//! lecture's shadows, glass blocks them (light through glass arrives along
//! refracted BSDF paths), so nothing is counted twice.

use super::trace::{NeeMiss, NeeSample, NoTrace, PathEnd, PathTrace, Trace};
use super::{CameraSample, Integrator, IntegratorEntry, IntegratorSettings, RayCounts, Schedule, View};
use crate::bsdfs::{Bsdf, Frame};
use crate::film::{Filter, FilterSampler, PixelSum};
use crate::lights::LightSet;
use crate::materials::map_shadowing::Perturbed;
use crate::materials::{Reflection, Refraction};
use crate::math::{Rgb, Vec3};
use crate::ray::{offset_origin, Ray};
use crate::sampling::{Cone, PixelSampler};
use crate::scene::{Hit, Scene, Sides};
use crate::Error;

// The lanes run on AVX2 (`accel/ray_lanes.rs`); elsewhere every row takes one sample at a time.
#[cfg(target_arch = "x86_64")]
mod lanes;

/// What a map left of the unmapped normal `unmapped` where it turned the
/// shading normal to `mapped` ([`Perturbed`]); `None` where it did not. Kept
/// out of the path loop: only scenes with maps call it.
#[cold]
#[inline(never)]
fn perturbation(unmapped: Vec3, mapped: Vec3, shadowing: bool) -> Option<Perturbed> {
    (mapped != unmapped).then(|| Perturbed::new(unmapped, mapped, shadowing))
}

/// The registry's entry.
pub const ENTRY: IntegratorEntry = IntegratorEntry {
    name: "path",
    summary: "unidirectional path tracing with next-event estimation, MIS and Russian roulette",
    build: build_path,
    schedule: Schedule::Doubling,
    filters: true,
};

fn build_path(scene: &Scene, settings: &IntegratorSettings) -> Result<Box<dyn Integrator>, Error> {
    Ok(Box::new(PathTracer::new(scene, settings.max_depth).with_filter(settings.filter)))
}

/// Path tracing with NEE, MIS and Russian roulette.
#[derive(Debug)]
pub struct PathTracer {
    /// Longest path in segments (camera ray = 1).
    pub max_depth: u32,
    /// Segments before Russian roulette starts: the scene's [`crate::scene::SceneSettings::rr_depth`]
    /// (4 unless it says), the same counting as Mitsuba's `rr_depth`.
    pub rr_depth: u32,
    lights: LightSet,
    /// Every material stops shadow rays: visibility can use the BVH's any-hit query.
    all_opaque: bool,
    /// Where in and around its pixel a sample's film position falls (with a
    /// filter with negative lobes, its table).
    filter: FilterSampler,
    /// The tables of the lanes' shading for the Cornell box's kind of scene
    /// (`path/lanes/diffuse.rs`), worked out once here for the scene the
    /// tracer is built for (asked per tile row, they were 1.1 % of a render).
    #[cfg(target_arch = "x86_64")]
    diffuse: Option<lanes::Diffuse>,
}

/// The power heuristic with exponent 2 for one sample of each strategy.
#[inline]
pub fn power_heuristic(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 {
        a2 / (a2 + b2)
    } else {
        0.0
    }
}

/// True when nothing lies on the segment from `ray.origin` along `ray.dir` before
/// `distance` (at `ray.time`), except object `own` (the light's own body), where the ray may end.
/// Surfaces that scatter nothing and let shadows through (a bulb's glow around its
/// point light) are passed; every other surface blocks, glass included.
pub fn unoccluded(scene: &Scene, ray: &Ray, distance: f64, own: Option<usize>) -> bool {
    let (mut origin, dir) = (ray.origin, ray.dir);
    let mut remaining = distance;
    // Each pass moves past one surface; a bound keeps pathological stacks finite.
    for _ in 0..64 {
        let Some(h) = scene.first_intersect(&ray.spawn(origin, dir), remaining) else { return true };
        if Some(h.object) == own {
            return true;
        }
        let m = &scene.materials[h.material];
        let clear =
            m.shadow_transmittance == Rgb::ONE && !m.is_lit() && m.reflection == Reflection::None && m.refraction == Refraction::None;
        if !clear {
            return false;
        }
        let next = offset_origin(h.point, h.geometric_normal, dir, h.t, h.error);
        remaining -= (next - origin).length();
        origin = next;
        if remaining <= 0.0 {
            return true;
        }
    }
    false
}

impl PathTracer {
    /// A path tracer for `scene` (its lights are collected here).
    pub fn new(scene: &Scene, max_depth: u32) -> PathTracer {
        let all_opaque = scene.materials.iter().all(|m| m.shadow_transmittance == Rgb::ZERO);
        #[cfg_attr(not(target_arch = "x86_64"), allow(unused_mut))]
        let mut tracer = PathTracer {
            max_depth,
            rr_depth: scene.settings.rr_depth,
            lights: scene.light_set(),
            all_opaque,
            filter: FilterSampler::new(Filter::Box),
            #[cfg(target_arch = "x86_64")]
            diffuse: None,
        };
        #[cfg(target_arch = "x86_64")]
        {
            tracer.diffuse = lanes::Diffuse::of(&tracer, scene);
        }
        tracer
    }

    /// The same tracer with film positions drawn from `filter` (default: the box).
    pub fn with_filter(self, filter: Filter) -> PathTracer {
        PathTracer { filter: FilterSampler::new(filter), ..self }
    }

    /// The lights it samples.
    pub fn lights(&self) -> &LightSet {
        &self.lights
    }

    /// Radiance along camera ray `ray`, drawing sample values from `sampler`.
    pub fn li(&self, scene: &Scene, camera_ray: &Ray, sampler: &mut PixelSampler, counts: &mut RayCounts) -> Rgb {
        if scene.turns_normals() {
            self.li_traced::<true, _>(scene, camera_ray, Cone::default(), sampler, counts, &mut NoTrace)
        } else {
            self.li_traced::<false, _>(scene, camera_ray, Cone::default(), sampler, counts, &mut NoTrace)
        }
    }

    /// [`PathTracer::li`], telling `trace` each vertex, light sample and BSDF sample.
    ///
    /// Textures are filtered over the pixel footprint `cone` of the camera ray
    /// (zero: point lookups): at the first hit the cone's width there; at later
    /// hits the width the camera's cone has at that point's distance from the
    /// camera, pbrt-v4's approximation (`Camera::Approximate_dp_dxy`) of ray
    /// differentials through diffuse and glossy bounces, which keeps a far
    /// texture seen in a mirror or through a bounce filtered as if seen directly.
    ///
    /// `MAPS` is [`Scene::turns_normals`]: compiled twice, so that a scene
    /// without normal or bump maps carries none of their bookkeeping through
    /// the loop (with one compilation it cost 17 instructions a vertex and
    /// perturbed the loop's code: +3.4 % on the guard's Cornell box).
    #[inline(always)]
    fn li_traced<const MAPS: bool, T: PathTrace + ?Sized>(
        &self,
        scene: &Scene,
        camera_ray: &Ray,
        cone: Cone,
        sampler: &mut PixelSampler,
        counts: &mut RayCounts,
        trace: &mut T,
    ) -> Rgb {
        counts.camera += 1;
        let mut radiance = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        let mut ray = *camera_ray;
        // Density of the BSDF sample that made `ray`; a delta lobe or the camera count as delta.
        let mut prev_pdf = 0.0;
        let mut prev_delta = true;
        let p_pick = self.lights.pick_probability();
        let single_light = self.lights.count() <= 1;
        let geometric_sides = scene.settings.sides == Sides::Geometric;
        for depth in 1..=self.max_depth {
            // This vertex's light and BSDF points (dimensions 1 and 3 of its five),
            // drawn before the ray is traced: the hashing needs no hit and overlaps
            // the intersection's latency. Unused if the path ends here.
            let (u_light, u_bsdf) = (sampler.peek_2d(1), sampler.peek_2d(3));
            trace.segment(depth, &ray, beta);
            // Mitsuba's `hide_emitters`: the camera sees through emitters, and black sky.
            let hidden = depth == 1 && scene.settings.hide_emitters;
            let mut found = if hidden { scene.first_camera_hit(&ray) } else { scene.first_intersect(&ray, f64::INFINITY) };
            // Used in place, by reference: moving the hit out of `found` copied it
            // with wide loads over the query's narrow stores, a store-forwarding
            // stall on every vertex (issue 24).
            let Some(hit) = found.as_mut() else {
                if let Some(env) = self.lights.environment.as_ref().filter(|_| !hidden) {
                    let w = if prev_delta { 1.0 } else { power_heuristic(prev_pdf, p_pick * env.pdf(ray.dir)) };
                    let le = env.radiance(ray.dir);
                    let contribution = beta * le * w;
                    trace.emitted(le, w, contribution);
                    radiance += contribution;
                }
                trace.end(PathEnd::Escaped);
                break;
            };
            let footprint = if cone.spread == 0.0 && cone.width == 0.0 {
                0.0
            } else if depth == 1 {
                cone.width + cone.spread * hit.t
            } else {
                cone.width + cone.spread * (hit.point - camera_ray.origin).length()
            };
            let unmapped = hit.normal;
            let material = &*scene.shade(hit, -ray.dir, footprint);
            trace.path_hit(scene, hit);
            if material.emits_towards(hit.front_face) {
                let w = match self.lights.area_light_of(hit.object) {
                    Some(light) if !prev_delta => {
                        // Outward normal: the geometric normal faces the ray on the front face.
                        power_heuristic(prev_pdf, p_pick * light.pdf(ray.dir, hit.t, hit.geometric_normal))
                    }
                    // A bulb's light comes through its delta light, which BSDF
                    // samples cannot find: only delta paths see the bulb itself.
                    _ if !prev_delta && self.lights.is_bulb(hit.object) => 0.0,
                    // Delta paths, and emitters that light sampling cannot reach.
                    _ => 1.0,
                };
                let contribution = beta * material.emission * w;
                trace.emitted(material.emission, w, contribution);
                radiance += contribution;
            }
            if depth >= self.max_depth {
                trace.end(PathEnd::MaxDepth);
                break;
            }
            let textured;
            let bsdf = match scene.prebuilt_bsdf(hit.material, hit.front_face) {
                Some(bsdf) => bsdf,
                None => {
                    textured = crate::scene::surface_bsdf(material, hit.point, hit.front_face);
                    &textured
                }
            };
            if bsdf.is_black() {
                trace.end(PathEnd::BlackBsdf);
                break;
            }
            let frame = scene.shading_frame(hit, bsdf);
            let wo = frame.to_local(-ray.dir);
            // A normal or bump map turned the normal: Mitsuba's sides and
            // shadowing term ([`crate::materials::map_shadowing`]).
            let perturbed = if MAPS { perturbation(unmapped, hit.normal, material.map_shadowing) } else { None };
            // Every vertex owns the same five dimensions, so that every sample of a
            // pixel uses dimension k for the same decision; values a vertex does not
            // need are skipped, not computed.
            let smooth = bsdf.has_smooth_part();
            let light_values = if smooth {
                let u_pick = if single_light { sampler.skip_value() } else { sampler.get_1d() };
                sampler.skip(); // u_light
                Some((u_pick, u_light))
            } else {
                sampler.skip();
                sampler.skip();
                None
            };
            let u_lobe = if bsdf.uses_lobe_sample() { sampler.get_1d() } else { sampler.skip_value() };
            sampler.skip(); // u_bsdf
            let u_rr = if depth >= self.rr_depth { sampler.get_1d() } else { sampler.skip_value() };
            // The continuation does not depend on the light sample: sampling it first
            // lets its division and square roots overlap the shadow ray's work.
            let sampled = bsdf.sample(wo, u_lobe, u_bsdf);
            if let Some((u_pick, u_light)) = light_values {
                let contribution =
                    beta * self.sample_light(scene, hit, bsdf, &frame, perturbed.as_ref(), wo, u_pick, u_light, counts, trace);
                trace.nee_contribution(contribution);
                radiance += contribution;
            }
            // Read only now: right after `sample` returned, its result was still in
            // the store buffer, and the wide loads of a Vec3 cannot be forwarded
            // from the narrow stores that wrote it (a stall per vertex, issue 24).
            let next = sampled.map(|s| {
                let wi = frame.to_world(s.wi);
                (s, wi, offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error))
            });
            let Some((s, wi, origin)) = next else {
                trace.end(PathEnd::NoSample);
                break;
            };
            // The shading normal may disagree with the geometry: keep the side the
            // geometric normal says, or light would leak through the surface
            // (unless the scene follows the shading normal's sides, `Sides::Shading`).
            if (geometric_sides && (wi.dot(hit.geometric_normal) > 0.0) != (s.wi.z > 0.0)) || s.weight == Rgb::ZERO {
                trace.end(PathEnd::WrongSide);
                break;
            }
            if let Some(p) = &perturbed {
                let w = p.weight(wi, s.wi.z > 0.0, !geometric_sides);
                if w == 0.0 {
                    trace.end(PathEnd::WrongSide);
                    break;
                }
                beta *= w;
            }
            beta *= s.weight;
            trace.bsdf_sample(&s, wi, beta);
            prev_pdf = s.pdf;
            prev_delta = s.delta;
            if depth >= self.rr_depth {
                let survive = beta.max_element().min(1.0);
                if !(u_rr < survive) {
                    trace.end(PathEnd::Roulette { survive, u: u_rr });
                    break;
                }
                beta *= 1.0 / survive;
                trace.survived(survive, beta);
            }
            counts.secondary += 1;
            ray = hit.spawn(origin, wi);
        }
        radiance
    }

    /// One light sample at `hit`, MIS-weighted against the BSDF.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample_light<T: PathTrace + ?Sized>(
        &self,
        scene: &Scene,
        hit: &Hit,
        bsdf: &Bsdf,
        frame: &Frame,
        perturbed: Option<&Perturbed>,
        wo: Vec3,
        u_pick: f64,
        u: (f64, f64),
        counts: &mut RayCounts,
        trace: &mut T,
    ) -> Rgb {
        let Some((picked, sample)) = self.lights.pick_and_sample(u_pick, hit.point, u) else {
            trace.nee_miss(NeeMiss::NoLight);
            return Rgb::ZERO;
        };
        let p_pick = self.lights.pick_probability();
        let Some(crate::lights::LiSample { wi, distance, radiance: li, pdf: light_pdf, own_object: own, ends_on_own }) = sample else {
            trace.nee_miss(NeeMiss::NoSample);
            return Rgb::ZERO;
        };
        if li == Rgb::ZERO {
            trace.nee_miss(NeeMiss::NoSample);
            return Rgb::ZERO;
        }
        let wi_local = frame.to_local(wi);
        if scene.settings.sides == Sides::Geometric && (wi.dot(hit.geometric_normal) > 0.0) != (wi_local.z > 0.0) {
            trace.nee_miss(NeeMiss::WrongSide);
            return Rgb::ZERO;
        }
        let mut f = bsdf.f(wo, wi_local);
        if let Some(p) = perturbed {
            f *= p.weight(wi, wi_local.z > 0.0, scene.settings.sides == Sides::Shading);
        }
        if f == Rgb::ZERO {
            trace.nee_miss(NeeMiss::BlackBsdf);
            return Rgb::ZERO;
        }
        counts.shadow += 1;
        let origin = offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error);
        let remaining = distance - (origin - hit.point).length();
        let visible = if self.all_opaque {
            // Any hit blocks; the scene's query ends the ray at the light's own object.
            let transmittance = match own {
                Some(own) if ends_on_own => scene.transmittance_to_surface(&hit.spawn(origin, wi), remaining, own),
                _ => scene.transmittance(&hit.spawn(origin, wi), remaining, own),
            };
            transmittance != Rgb::ZERO
        } else {
            unoccluded(scene, &hit.spawn(origin, wi), remaining, own)
        };
        if !visible {
            trace.nee_miss(NeeMiss::Blocked);
            return Rgb::ZERO;
        }
        let cos = wi_local.z.abs();
        let (value, bsdf_pdf, mis_weight) = match light_pdf {
            // Scalars first: one division instead of one per channel.
            None => (f * li * (cos / p_pick), 0.0, 1.0),
            Some(pdf) => {
                let pl = p_pick * pdf;
                let bsdf_pdf = bsdf.pdf(wo, wi_local);
                let w = power_heuristic(pl, bsdf_pdf);
                (f * li * (cos * w / pl), bsdf_pdf, w)
            }
        };
        trace.nee(&NeeSample { light: picked, pick_probability: p_pick, wi, distance, li, light_pdf, f, cos, bsdf_pdf, mis_weight, value });
        value
    }
}

impl Integrator for PathTracer {
    /// Sample `index` of a pixel uses the Sobol point `index` scrambled for that
    /// pixel ([`PixelSampler`]): its first 2D dimension places the sample by the
    /// filter around the pixel centre, the next one is the lens sample (only for a
    /// camera that takes one), then the instant in the shutter (only when a shape
    /// moves, [`View::shutter`]), and the path's vertices use the rest. Its passes
    /// double, so a render of `2N` samples continues one of `N`.
    #[inline(always)]
    fn sample(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts) -> Rgb {
        self.sample_with(view, x, y, index, counts, &mut NoTrace)
    }

    fn sample_traced(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts, trace: &mut dyn Trace) -> Rgb {
        self.sample_with(view, x, y, index, counts, trace)
    }

    fn camera_sample(&self, view: &View, x: u32, y: u32, index: u32) -> CameraSample {
        self.camera_sample_with(view, x, y, index).0
    }

    fn schedule(&self) -> Schedule {
        Schedule::Doubling
    }

    /// Four paths at a time where the scene's lanes test its objects
    /// (`path/lanes.rs`; the same values), else one sample at a time.
    fn sample_row(
        &self,
        view: &View,
        row: (u32, u32),
        samples: std::ops::Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        #[cfg(target_arch = "x86_64")]
        if self.lanes_fit(view) && sums.len().saturating_mul(samples.len()) < u32::MAX as usize {
            // SAFETY: the lanes fit this view.
            return unsafe { self.sample_row_lanes(view, row, samples, counts, sums) };
        }
        super::sample_row_one_by_one(self, view, row, samples, counts, sums)
    }
}

impl PathTracer {
    /// [`Integrator::sample`], telling `trace` what it does.
    #[inline(always)]
    fn sample_with<T: PathTrace + ?Sized>(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts, trace: &mut T) -> Rgb {
        let (camera, mut sampler) = self.camera_sample_with(view, x, y, index);
        let l = if view.scene.turns_normals() {
            self.li_traced::<true, T>(view.scene, &camera.ray, camera.cone, &mut sampler, counts, trace)
        } else {
            self.li_traced::<false, T>(view.scene, &camera.ray, camera.cone, &mut sampler, counts, trace)
        };
        // The box and the tent weigh every sample 1: their radiance is kept as it
        // is. Filters with negative lobes weigh some samples below 0.
        if camera.weight == 1.0 {
            l
        } else {
            l * camera.weight
        }
    }

    /// The camera ray of a sample and the sampler positioned after the values
    /// it drew (the film position, then the lens): one function for
    /// [`Integrator::sample`] and [`Integrator::camera_sample`], so the feature
    /// pass follows exactly the rays the render traced.
    #[inline(always)]
    fn camera_sample_with(&self, view: &View, x: u32, y: u32, index: u32) -> (CameraSample, PixelSampler) {
        let mut sampler = PixelSampler::new(view.seed, view.pixel_index(x, y), index);
        let (lo, hi) = view.offset_bounds(x, y);
        let ((dx, dy), weight) = self.filter.sample_in(sampler.get_2d(), lo, hi);
        let lens = if view.lens { sampler.get_2d() } else { (0.5, 0.5) };
        let (fx, fy) = (x as f64 + 0.5 + dx, y as f64 + 0.5 + dy);
        let mut ray = view.camera.ray(fx, fy, view.width, view.height, lens);
        if let Some(shutter) = view.shutter {
            ray.time = View::instant(shutter, sampler.get_1d());
        }
        let cone = if view.scene.uses_footprints() { view.pixel_cone(&ray, fx, fy, lens) } else { Cone::default() };
        (CameraSample { ray, cone, weight }, sampler)
    }
}
