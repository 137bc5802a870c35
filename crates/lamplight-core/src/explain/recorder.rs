//! The recorder `explain` passes to an integrator: it forwards the Whitted
//! events to a [`RayTree`] and the path tracer's to a [`PathRecord`], so one
//! recorder serves whichever integrator the render uses.

use super::{PathRecord, RayTree, Record};
use crate::integrators::trace::{PathTrace, WhittedTrace};
use crate::math::{Rgb, Vec3};
use crate::scene::{Hit, Scene};

/// Records whichever integrator calls it.
#[derive(Default)]
pub(super) struct Recorder {
    tree: RayTree,
    path: PathRecord,
}

impl Recorder {
    /// The contributions in the integrator's order and what was recorded.
    pub(super) fn finish(self) -> (Vec<Rgb>, Record) {
        if let Some((root, contributions)) = self.tree.finish() {
            return (contributions, Record::RayTree(root));
        }
        if !self.path.vertices.is_empty() {
            let contributions = self.path.contributions.clone();
            return (contributions, Record::Path(self.path));
        }
        (Vec::new(), Record::Nothing)
    }
}

/// Forwards the Whitted events to the ray tree.
impl WhittedTrace for Recorder {
    fn ray(&mut self, ray: &crate::ray::Ray, weight: Rgb, depth: u32) {
        self.tree.ray(ray, weight, depth)
    }
    fn miss(&mut self, radiance: Rgb, contribution: Rgb) {
        self.tree.miss(radiance, contribution)
    }
    fn hit(&mut self, scene: &Scene, hit: &Hit) {
        WhittedTrace::hit(&mut self.tree, scene, hit)
    }
    fn surface(&mut self, color: Rgb, emission: Rgb, ambient: Rgb) {
        self.tree.surface(color, emission, ambient)
    }
    fn light(&mut self, light: crate::integrators::trace::LightRef) {
        self.tree.light(light)
    }
    fn unlit(&mut self, why: crate::integrators::trace::Unlit) {
        self.tree.unlit(why)
    }
    fn lit(&mut self, scene: &Scene, term: &crate::integrators::trace::LightTerm) {
        self.tree.lit(scene, term)
    }
    fn direct(&mut self, direct: Rgb, contribution: Rgb) {
        self.tree.direct(direct, contribution)
    }
    fn depth_cutoff(&mut self) {
        self.tree.depth_cutoff()
    }
    fn reflection(&mut self, how: crate::integrators::trace::ReflectionWeight, weight: Rgb) {
        self.tree.reflection(how, weight)
    }
    fn refraction(&mut self, fresnel: Option<f64>, weight: Option<Rgb>) {
        self.tree.refraction(fresnel, weight)
    }
    fn branch(&mut self, ray: &crate::ray::Ray, weight: Rgb, depth: u32, traced: bool) {
        self.tree.branch(ray, weight, depth, traced)
    }
}

/// Forwards the path events to the path record.
impl PathTrace for Recorder {
    fn segment(&mut self, depth: u32, ray: &crate::ray::Ray, beta: Rgb) {
        self.path.segment(depth, ray, beta)
    }
    fn path_hit(&mut self, scene: &Scene, hit: &Hit) {
        self.path.path_hit(scene, hit)
    }
    fn emitted(&mut self, le: Rgb, weight: f64, contribution: Rgb) {
        self.path.emitted(le, weight, contribution)
    }
    fn nee_miss(&mut self, why: crate::integrators::trace::NeeMiss) {
        self.path.nee_miss(why)
    }
    fn nee(&mut self, sample: &crate::integrators::trace::NeeSample) {
        self.path.nee(sample)
    }
    fn nee_contribution(&mut self, contribution: Rgb) {
        self.path.nee_contribution(contribution)
    }
    fn bsdf_sample(&mut self, sample: &crate::bsdfs::BsdfSample, wi: Vec3, beta: Rgb) {
        self.path.bsdf_sample(sample, wi, beta)
    }
    fn survived(&mut self, survive: f64, beta: Rgb) {
        self.path.survived(survive, beta)
    }
    fn end(&mut self, why: crate::integrators::trace::PathEnd) {
        self.path.end(why)
    }
}
