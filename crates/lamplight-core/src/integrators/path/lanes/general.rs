//! The lanes for scenes of rectangles and boxes other than the Cornell box's
//! kind (`diffuse.rs`): each path's state kept as the one-path loop keeps it,
//! each vertex shaded by the general code ([`PathTracer::vertex`], the body of
//! [`PathTracer::li`]'s loop for a scene without maps or footprints), the
//! queries in lanes (module doc of `lanes.rs`).

use std::ops::Range;

use super::super::{power_heuristic, unoccluded, PathTracer};
use super::add_in_order;
use crate::film::PixelSum;
use crate::integrators::{RayCounts, View};
use crate::lights::LiSample;
use crate::math::{Rgb, Vec3};
use crate::ray::{offset_origin, Ray};
use crate::sampling::{peek_2d_lanes, PixelSampler};
use crate::scene::{Hit, Scene, Sides};

/// One lane's path.
#[derive(Clone, Debug)]
struct Path {
    /// Its sample's index in the row's list, `u32::MAX` while the lane is idle.
    item: u32,
    ray: Ray,
    beta: Rgb,
    radiance: Rgb,
    prev_pdf: f64,
    prev_delta: bool,
    depth: u32,
    sampler: PixelSampler,
    /// The filter weight of its sample.
    weight: f64,
}

/// A light sample waiting for its shadow ray: its value where the ray is
/// clear, and the throughput it is added with.
#[derive(Clone, Copy, Debug)]
struct Pending {
    beta: Rgb,
    value: Rgb,
}

/// What a vertex leaves for the round's shadow query.
#[derive(Clone, Copy, Debug)]
enum Shadow {
    /// No light sample (a delta BSDF), or one the path's own code answered.
    None,
    /// `beta * value` is added whatever the shadow ray finds (zero where the
    /// sample gave nothing, or visibility known already).
    Known(Pending),
    /// The ray, its length and the object it may end on, for the lanes.
    Ray(Pending, Ray, f64, u32),
}
impl PathTracer {
    /// [`PathTracer::row_lanes`] for scenes that are not of the Cornell box's
    /// kind: the row's samples taken by four lanes as they free up, their
    /// values added to `sums` in sample order.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub(super) unsafe fn row_general(
        &self,
        view: &View,
        (x0, y): (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        let scene = view.scene;
        let per_pixel = samples.len();
        let total = sums.len() * per_pixel;
        let mut values = vec![Rgb::ZERO; total];
        let idle = Path {
            item: u32::MAX,
            ray: Ray::unit(Vec3::ZERO, Vec3::Z),
            beta: Rgb::ONE,
            radiance: Rgb::ZERO,
            prev_pdf: 0.0,
            prev_delta: true,
            depth: 1,
            sampler: PixelSampler::new(0, 0, 0),
            weight: 1.0,
        };
        let mut paths = [idle.clone(), idle.clone(), idle.clone(), idle];
        let mut next = 0;
        let mut hits: [Option<Hit>; 4] = [None; 4];
        loop {
            let mut active = 0u8;
            for (lane, path) in paths.iter_mut().enumerate() {
                if path.item == u32::MAX && next < total {
                    let (x, s) = (x0 + (next / per_pixel) as u32, samples.start + (next % per_pixel) as u32);
                    let (camera, sampler) = self.camera_sample_with(view, x, y, s);
                    counts.camera += 1;
                    *path = Path {
                        item: next as u32,
                        ray: camera.ray,
                        beta: Rgb::ONE,
                        radiance: Rgb::ZERO,
                        prev_pdf: 0.0,
                        prev_delta: true,
                        depth: 1,
                        sampler,
                        weight: camera.weight,
                    };
                    next += 1;
                }
                if path.item != u32::MAX {
                    active |= 1 << lane;
                }
            }
            if active == 0 {
                break;
            }
            // Each vertex's light and BSDF points, drawn before its ray is traced (as `li`).
            let [lights, bsdfs] = peek_2d_lanes([&paths[0].sampler, &paths[1].sampler, &paths[2].sampler, &paths[3].sampler], (1, 3));
            let rays = [paths[0].ray, paths[1].ray, paths[2].ray, paths[3].ray];
            scene.closest_hits4(&rays, active, &mut hits);
            let mut shadows = [Shadow::None; 4];
            let mut ended = 0u8;
            for lane in 0..4 {
                if active & (1 << lane) != 0 {
                    let (end, shadow) = self.vertex(scene, &mut paths[lane], hits[lane].as_mut(), (lights[lane], bsdfs[lane]), counts);
                    shadows[lane] = shadow;
                    ended |= u8::from(end) << lane;
                }
            }
            let mut shadow_rays = rays;
            let mut distance = [0.0; 4];
            let mut ignore = [u32::MAX; 4];
            let mut asked = 0u8;
            for (lane, shadow) in shadows.iter().enumerate() {
                if let Shadow::Ray(_, ray, d, own) = *shadow {
                    shadow_rays[lane] = ray;
                    distance[lane] = d;
                    ignore[lane] = own;
                    asked |= 1 << lane;
                }
            }
            let blocked = if asked != 0 { scene.blocked4(&shadow_rays, &distance, &ignore, asked) } else { 0 };
            for (lane, path) in paths.iter_mut().enumerate() {
                match shadows[lane] {
                    Shadow::None => {}
                    Shadow::Known(p) => path.radiance += p.beta * p.value,
                    Shadow::Ray(p, ..) => path.radiance += p.beta * if blocked & (1 << lane) != 0 { Rgb::ZERO } else { p.value },
                }
                if ended & (1 << lane) != 0 {
                    // As `sample_with`: the box and the tent keep the radiance as it is.
                    values[path.item as usize] = if path.weight == 1.0 { path.radiance } else { path.radiance * path.weight };
                    path.item = u32::MAX;
                }
            }
        }
        add_in_order(&values, per_pixel, view.clamp, sums)
    }

    /// One vertex of `path` at its query's answer `found`: [`PathTracer::li`]'s
    /// loop body for a scene without maps or footprints, telling whether the
    /// path ends here and what its light sample waits for.
    #[inline(always)]
    fn vertex(
        &self,
        scene: &Scene,
        path: &mut Path,
        found: Option<&mut Hit>,
        (u_light, u_bsdf): ((f64, f64), (f64, f64)),
        counts: &mut RayCounts,
    ) -> (bool, Shadow) {
        let p_pick = self.lights.pick_probability();
        let single_light = self.lights.count() <= 1;
        let geometric_sides = scene.settings.sides == Sides::Geometric;
        let ray = path.ray;
        let depth = path.depth;
        let sampler = &mut path.sampler;
        let Some(hit) = found else {
            if let Some(env) = self.lights.environment.as_ref() {
                let w = if path.prev_delta { 1.0 } else { power_heuristic(path.prev_pdf, p_pick * env.pdf(ray.dir)) };
                let le = env.radiance(ray.dir);
                path.radiance += path.beta * le * w;
            }
            return (true, Shadow::None);
        };
        let material = &*scene.shade(hit, -ray.dir, 0.0);
        if material.emits_towards(hit.front_face) {
            let w = match self.lights.area_light_of(hit.object) {
                Some(light) if !path.prev_delta => power_heuristic(path.prev_pdf, p_pick * light.pdf(ray.dir, hit.t, hit.geometric_normal)),
                _ if !path.prev_delta && self.lights.is_bulb(hit.object) => 0.0,
                _ => 1.0,
            };
            path.radiance += path.beta * material.emission * w;
        }
        if depth >= self.max_depth {
            return (true, Shadow::None);
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
            return (true, Shadow::None);
        }
        let frame = scene.shading_frame(hit, bsdf);
        let wo = frame.to_local(-ray.dir);
        let smooth = bsdf.has_smooth_part();
        let light_values = if smooth {
            let u_pick = if single_light { sampler.skip_value() } else { sampler.get_1d() };
            sampler.skip();
            Some((u_pick, u_light))
        } else {
            sampler.skip();
            sampler.skip();
            None
        };
        let u_lobe = if bsdf.uses_lobe_sample() { sampler.get_1d() } else { sampler.skip_value() };
        sampler.skip();
        let u_rr = if depth >= self.rr_depth { sampler.get_1d() } else { sampler.skip_value() };
        let sampled = bsdf.sample(wo, u_lobe, u_bsdf);
        let shadow = match light_values {
            Some((u_pick, u)) => self.light_sample(scene, hit, bsdf, &frame, wo, u_pick, u, counts, path.beta),
            None => Shadow::None,
        };
        let next = sampled.map(|s| {
            let wi = frame.to_world(s.wi);
            (s, wi, offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error))
        });
        let Some((s, wi, origin)) = next else { return (true, shadow) };
        if (geometric_sides && (wi.dot(hit.geometric_normal) > 0.0) != (s.wi.z > 0.0)) || s.weight == Rgb::ZERO {
            return (true, shadow);
        }
        path.beta *= s.weight;
        path.prev_pdf = s.pdf;
        path.prev_delta = s.delta;
        if depth >= self.rr_depth {
            let survive = path.beta.max_element().min(1.0);
            if !(u_rr < survive) {
                return (true, shadow);
            }
            path.beta *= 1.0 / survive;
        }
        counts.secondary += 1;
        path.ray = hit.spawn(origin, wi);
        path.depth += 1;
        (false, shadow)
    }

    /// [`PathTracer::sample_light`]'s light sample at `hit`, its value worked
    /// out before its shadow ray is answered; the ray goes to the lanes where
    /// the scene's one-ray query would ignore only the light's own object.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn light_sample(
        &self,
        scene: &Scene,
        hit: &Hit,
        bsdf: &crate::bsdfs::Bsdf,
        frame: &crate::bsdfs::Frame,
        wo: Vec3,
        u_pick: f64,
        u: (f64, f64),
        counts: &mut RayCounts,
        beta: Rgb,
    ) -> Shadow {
        let nothing = Shadow::Known(Pending { beta, value: Rgb::ZERO });
        let Some((_, Some(LiSample { wi, distance, radiance: li, pdf: light_pdf, own_object: own, ends_on_own }))) =
            self.lights.pick_and_sample(u_pick, hit.point, u)
        else {
            return nothing;
        };
        let p_pick = self.lights.pick_probability();
        if li == Rgb::ZERO {
            return nothing;
        }
        let wi_local = frame.to_local(wi);
        if scene.settings.sides == Sides::Geometric && (wi.dot(hit.geometric_normal) > 0.0) != (wi_local.z > 0.0) {
            return nothing;
        }
        let f = bsdf.f(wo, wi_local);
        if f == Rgb::ZERO {
            return nothing;
        }
        counts.shadow += 1;
        let origin = offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error);
        let remaining = distance - (origin - hit.point).length();
        let cos = wi_local.z.abs();
        let value = match light_pdf {
            None => f * li * (cos / p_pick),
            Some(pdf) => {
                let pl = p_pick * pdf;
                let bsdf_pdf = bsdf.pdf(wo, wi_local);
                let w = power_heuristic(pl, bsdf_pdf);
                f * li * (cos * w / pl)
            }
        };
        let pending = Pending { beta, value };
        let ray = hit.spawn(origin, wi);
        match own {
            // Any hit blocks but the light's own object, where the ray ends.
            _ if !self.all_opaque => {
                let visible = unoccluded(scene, &ray, remaining, own);
                Shadow::Known(Pending { beta, value: if visible { value } else { Rgb::ZERO } })
            }
            Some(own) if ends_on_own => Shadow::Ray(pending, ray, remaining, own as u32),
            None => Shadow::Ray(pending, ray, remaining, u32::MAX),
            Some(_) => {
                let visible = scene.transmittance(&ray, remaining, own) != Rgb::ZERO;
                Shadow::Known(Pending { beta, value: if visible { value } else { Rgb::ZERO } })
            }
        }
    }
}
