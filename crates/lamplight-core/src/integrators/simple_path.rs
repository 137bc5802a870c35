//! The plainest path tracer: BSDF sampling only, emitters and sky counted where
//! paths happen to hit them. Slow to converge but with nothing to get wrong in
//! light sampling or MIS weights, it is the oracle [`super::PathTracer`] is tested
//! against. No Russian roulette: paths end at the depth limit.

use crate::lights::LightSet;
use crate::math::Rgb;
use crate::ray::{offset_origin, Ray};
use crate::sampling::PixelSampler;
use crate::scene::Scene;

/// BSDF-sampling-only path tracing to a depth limit (segments, camera ray = 1).
#[derive(Debug)]
pub struct SimplePath {
    /// Longest path in segments.
    pub max_depth: u32,
    lights: LightSet,
}

impl SimplePath {
    /// For `scene`.
    pub fn new(scene: &Scene, max_depth: u32) -> SimplePath {
        SimplePath { max_depth, lights: scene.light_set() }
    }

    /// Radiance along `ray`.
    pub fn li(&self, scene: &Scene, camera_ray: &Ray, sampler: &mut PixelSampler) -> Rgb {
        let mut radiance = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        let mut ray = *camera_ray;
        for depth in 1..=self.max_depth {
            let Some(mut hit) = scene.first_intersect(&ray, f64::INFINITY) else {
                if let Some(env) = &self.lights.environment {
                    radiance += beta * env.radiance(ray.dir);
                }
                break;
            };
            let material = &*scene.shade(&mut hit, -ray.dir, 0.0);
            if material.emits_towards(hit.front_face) {
                radiance += beta * material.emission;
            }
            if depth >= self.max_depth {
                break;
            }
            let bsdf = scene.bsdf(&hit, material);
            let frame = scene.shading_frame(&hit, &bsdf);
            let wo = frame.to_local(-ray.dir);
            let u_lobe = sampler.get_1d();
            let Some(s) = bsdf.sample(wo, u_lobe, sampler.get_2d()) else { break };
            let wi = frame.to_world(s.wi);
            if (wi.dot(hit.geometric_normal) > 0.0) != (s.wi.z > 0.0) {
                break;
            }
            beta *= s.weight;
            ray = hit.spawn(offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error), wi);
        }
        radiance
    }
}
