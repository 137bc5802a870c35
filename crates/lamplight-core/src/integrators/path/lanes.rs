//! The path tracer on four paths at once, for scenes the scene's lanes test
//! (a handful of rectangles and boxes: a Cornell box; [`Scene::object_lanes`]).
//!
//! Four paths of a row step in lockstep, one vertex each per round: their
//! four rays go through one closest-hit query in SIMD lanes, each path is
//! shaded on its own by the scalar code, then their light samples' shadow
//! rays go through one shadow query. A path that ends hands its lane to the
//! row's next sample. About 40 % of a Cornell sample went to the two queries
//! one ray at a time (issue 24).
//!
//! **The same image, bit for bit.** Each path draws the same sample values
//! and computes what [`PathTracer::li`] computes, in the same order; the
//! queries answer as the one-ray queries do (`scene/lanes.rs`); each pixel's
//! samples are kept apart and added in sample order at the end of the row, as
//! [`super::super::Integrator::sample_row`] adds them. The one difference in
//! what is computed: a light sample's value is worked out before its shadow
//! ray is answered, and dropped where the ray is blocked.
//!
//! Scenes with normal or bump maps, footprints (trilinear textures) or
//! `hide_emitters` keep the one-path loop, and so does a sample's trace
//! (`explain`).
//!
//! [`PathTracer::vertex`] and `diffuse.rs` repeat the body of `li`'s loop for
//! their scenes; a test (`lanes/tests.rs`) renders rows of both kinds both
//! ways and compares the bits, so a change to one that the others do not
//! follow fails there.
//!
//! **Two kinds of shading.** A scene of the Cornell box's kind (Lambertian
//! surfaces of constant colour, one emitting rectangle, no sky: `diffuse.rs`)
//! keeps the four paths' state lane by lane and shades each vertex with that
//! case's operations written out, building no `Hit`, `Bsdf` or material:
//! 0.80-0.82x the time of one sample at a time, 20 % fewer instructions.
//! Other scenes of rectangles and boxes keep each path's state as the
//! one-path loop does and shade it with the general code ([`PathTracer::vertex`]):
//! the queries take 35 % of the time instead of 46 %, but the state goes
//! through memory between rounds, and the whole is 2-5 % faster
//! (BENCHMARKS.md, session 32).

use std::ops::Range;

use super::PathTracer;
use crate::accel::Nearest4;
use crate::film::PixelSum;
use crate::integrators::{RayCounts, View};
use crate::math::Rgb;
use crate::ray::Ray;
use crate::sampling::{peek_2d_lanes, PixelSampler};
pub(super) use diffuse::Diffuse;
use diffuse::{Hits, Paths, Shadows};

/// Most sample values the lanes keep at once before adding them to their
/// pixels' sums (96 KB).
const MAX_VALUES: usize = 4096;

/// Adds each pixel's `per_pixel` values in `values` to its sum in `sums`, in
/// sample order, as the one-sample loop does; the number dropped.
fn add_in_order(values: &[Rgb], per_pixel: usize, clamp: f64, sums: &mut [PixelSum]) -> u64 {
    let mut nonfinite = 0;
    for (sum, pixel) in sums.iter_mut().zip(values.chunks_exact(per_pixel.max(1))) {
        for &l in pixel {
            nonfinite += crate::integrators::add_sample(sum, l, clamp);
        }
    }
    nonfinite
}

impl PathTracer {
    /// Whether this scene's rows run in lanes (module doc).
    pub(super) fn lanes_fit(&self, view: &View) -> bool {
        let scene = view.scene;
        scene.object_lanes().is_some() && !scene.settings.hide_emitters && !scene.turns_normals() && !scene.uses_footprints()
    }

    /// [`crate::integrators::Integrator::sample_row`] in lanes.
    ///
    /// # Safety
    /// [`PathTracer::lanes_fit`] must be true for `view`.
    #[cfg(target_arch = "x86_64")]
    pub(super) unsafe fn sample_row_lanes(
        &self,
        view: &View,
        row: (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        // The values wait for their pixel's sum in a buffer of at most
        // `MAX_VALUES`: a row's pixels in groups, or one pixel's samples in
        // runs (in order, so the sums are the same), never a buffer that
        // grows with the sample count (a pass of 2^19 samples of 16 pixels
        // would have held 200 MB a thread).
        let (x0, y) = row;
        let per_pixel = samples.len();
        let mut dropped = 0;
        if per_pixel <= MAX_VALUES {
            let group = (MAX_VALUES / per_pixel.max(1)).max(1);
            for (k, chunk) in sums.chunks_mut(group).enumerate() {
                dropped += self.row_lanes_compiled(view, (x0 + (k * group) as u32, y), samples.clone(), counts, chunk);
            }
        } else {
            for (i, sum) in sums.iter_mut().enumerate() {
                let mut start = samples.start;
                while start < samples.end {
                    let end = samples.end.min(start + MAX_VALUES as u32);
                    dropped += self.row_lanes_compiled(view, (x0 + i as u32, y), start..end, counts, std::slice::from_mut(sum));
                    start = end;
                }
            }
        }
        dropped
    }

    /// [`PathTracer::row_lanes`] through its compilation for this CPU.
    #[cfg(target_arch = "x86_64")]
    unsafe fn row_lanes_compiled(
        &self,
        view: &View,
        row: (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        if crate::cpu::avx512_features() {
            self.row_lanes_avx512(view, row, samples, counts, sums)
        } else if crate::cpu::render_features() {
            self.row_lanes_features(view, row, samples, counts, sums)
        } else {
            self.row_lanes_avx2(view, row, samples, counts, sums)
        }
    }

    /// [`PathTracer::row_lanes`] compiled for [`crate::cpu::AVX512_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni,avx512f,avx512dq,avx512vl,avx512bw")]
    unsafe fn row_lanes_avx512(
        &self,
        view: &View,
        row: (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        self.row_lanes(view, row, samples, counts, sums)
    }

    /// [`PathTracer::row_lanes`] compiled for [`crate::cpu::RENDER_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni")]
    unsafe fn row_lanes_features(
        &self,
        view: &View,
        row: (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        self.row_lanes(view, row, samples, counts, sums)
    }

    /// [`PathTracer::row_lanes`] compiled for [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn row_lanes_avx2(
        &self,
        view: &View,
        row: (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        self.row_lanes(view, row, samples, counts, sums)
    }

    /// The row's samples, pixel by pixel and each pixel's in order, taken by
    /// four lanes as they free up; their values added to `sums` in sample order.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn row_lanes(
        &self,
        view: &View,
        (x0, y): (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        let scene = view.scene;
        if let Some(diffuse) = self.diffuse.as_ref().filter(|d| d.fits(scene)) {
            return self.row_diffuse(diffuse, view, (x0, y), samples, counts, sums);
        }
        self.row_general(view, (x0, y), samples, counts, sums)
    }

    /// [`PathTracer::row_lanes`] for a scene of [`Diffuse`]'s kind: the
    /// paths' state lane by lane, each vertex shaded by `diffuse`.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    // The lanes index several arrays side by side (structure of arrays).
    #[allow(clippy::needless_range_loop)]
    unsafe fn row_diffuse(
        &self,
        diffuse: &Diffuse,
        view: &View,
        (x0, y): (u32, u32),
        samples: Range<u32>,
        counts: &mut RayCounts,
        sums: &mut [PixelSum],
    ) -> u64 {
        let scene = view.scene;
        let Some(lanes) = scene.object_lanes() else { return 0 };
        let per_pixel = samples.len();
        let total = sums.len() * per_pixel;
        let mut values = vec![Rgb::ZERO; total];
        let mut item = [u32::MAX; 4];
        let mut weight = [1.0; 4];
        let fresh = PixelSampler::new(0, 0, 0);
        let mut samplers = [fresh.clone(), fresh.clone(), fresh.clone(), fresh];
        let mut paths = Paths::default();
        let mut next = 0;
        let mut shadows = Shadows::default();
        let own = [diffuse.light_object(); 4];
        // Kept across rounds and written lane by lane: a lane that hits
        // nothing keeps its last hit, which the vertex does not use.
        let mut nearest = Nearest4::default();
        let mut hits = Hits::default();
        loop {
            let mut active = 0u8;
            for l in 0..4 {
                if item[l] == u32::MAX && next < total {
                    let (x, s) = (x0 + (next / per_pixel) as u32, samples.start + (next % per_pixel) as u32);
                    let (camera, sampler) = self.camera_sample_with(view, x, y, s);
                    counts.camera += 1;
                    item[l] = next as u32;
                    next += 1;
                    paths.origin.set(l, camera.ray.origin);
                    paths.dir.set(l, camera.ray.dir);
                    paths.beta.set(l, Rgb::ONE);
                    paths.radiance.set(l, Rgb::ZERO);
                    paths.prev_pdf[l] = 0.0;
                    paths.prev_delta[l] = true;
                    paths.depth[l] = 1;
                    samplers[l] = sampler;
                    weight[l] = camera.weight;
                }
                if item[l] != u32::MAX {
                    active |= 1 << l;
                }
            }
            if active == 0 {
                break;
            }
            let [u_light, u_bsdf] = peek_2d_lanes([&samplers[0], &samplers[1], &samplers[2], &samplers[3]], (1, 3));
            let (o, d) = (&paths.origin, &paths.dir);
            lanes.closest_coordinates([&o.x, &o.y, &o.z], [&d.x, &d.y, &d.z], f64::INFINITY, active, &mut nearest);
            let mut live = [false; 4];
            let mut u_rr = [0.5; 4];
            for l in 0..4 {
                let bit = 1 << l;
                if active & bit == 0 {
                    continue;
                }
                let hit = if nearest.tie & bit != 0 {
                    let ray = Ray::unit(paths.origin.get(l), paths.dir.get(l));
                    scene.first_intersect(&ray, f64::INFINITY).map(|h| diffuse.walked(&h))
                } else if nearest.hit & bit != 0 {
                    let slot = nearest.slot[l];
                    Some((nearest.t[l], slot, lanes.shape(slot).normal(nearest.face[l] as usize)))
                } else {
                    None
                };
                if let Some((t, slot, normal)) = hit {
                    (hits.t[l], hits.slot[l]) = (t, slot);
                    hits.normal.set(l, normal);
                    live[l] = true;
                }
                if paths.depth[l] >= self.rr_depth {
                    u_rr[l] = samplers[l].peek_2d(4).0;
                }
                // The vertex's five dimensions (`li` skips those it does not use).
                for _ in 0..5 {
                    samplers[l].skip();
                }
            }
            let on = diffuse.vertex(self, &mut paths, live, &hits, &u_light, &u_bsdf, &u_rr, &mut shadows, counts);
            let mut asked = 0u8;
            for l in 0..4 {
                asked |= u8::from(shadows.ray[l]) << l;
            }
            let (o, d) = (&shadows.origin, &shadows.dir);
            let blocked = if asked != 0 {
                lanes.blocked_coordinates([&o.x, &o.y, &o.z], [&d.x, &d.y, &d.z], &shadows.distance, &own, asked)
            } else {
                0
            };
            for l in 0..4 {
                if shadows.nee[l] {
                    let clear = asked & !blocked & (1 << l) != 0;
                    let value = if clear { shadows.value.get(l) } else { Rgb::ZERO };
                    paths.radiance.set(l, paths.radiance.get(l) + shadows.beta.get(l) * value);
                }
                if active & (1 << l) != 0 && !on[l] {
                    let r = paths.radiance.get(l);
                    values[item[l] as usize] = if weight[l] == 1.0 { r } else { r * weight[l] };
                    item[l] = u32::MAX;
                }
            }
        }
        add_in_order(&values, per_pixel, view.clamp, sums)
    }
}

mod diffuse;
mod general;
#[cfg(test)]
mod tests;
