//! The recorder `explain` passes to an integrator: it forwards the Whitted
//! events to a [`RayTree`] and the path tracer's to a [`PathRecord`], so one
//! recorder serves whichever integrator the render uses.
//!
//! It keeps an estimate of the bytes it holds (the size of each node, light,
//! vertex and term it records) and stops recording once that would pass its
//! allowance: every later event of the sample is ignored, and the caller
//! drops the sample's record ([`super::RECORD_BYTES`]).

use std::mem::size_of;

use super::{LightRecord, NeeRecord, PathRecord, PathVertex, RayKind, RayNode, RayTree, Record, ShadingRecord};
use crate::integrators::trace::{PathTrace, WhittedTrace};
use crate::math::{Rgb, Vec3};
use crate::scene::{Hit, Scene};

/// Records whichever integrator calls it.
pub(super) struct Recorder {
    tree: RayTree,
    path: PathRecord,
    /// Estimated bytes held.
    bytes: usize,
    /// The most it may hold.
    allowance: usize,
}

/// Bytes of a name or kind string recorded with a hit or a light (an
/// estimate: most names are short).
const NAME: usize = 48;

impl Recorder {
    /// A recorder that may hold about `allowance` bytes.
    pub(super) fn within(allowance: usize) -> Recorder {
        Recorder { tree: RayTree::default(), path: PathRecord::default(), bytes: 0, allowance }
    }

    /// Whether recording stopped at the allowance (the record is incomplete).
    pub(super) fn overflowed(&self) -> bool {
        self.bytes > self.allowance
    }

    /// The estimated bytes held.
    pub(super) fn bytes(&self) -> usize {
        self.bytes
    }

    /// Counts `bytes` more; false once over the allowance (from then on, for
    /// every event: the count only grows).
    fn take(&mut self, bytes: usize) -> bool {
        self.bytes = self.bytes.saturating_add(bytes);
        self.bytes <= self.allowance
    }

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
        // The camera ray makes the root; the later ones were counted as branches.
        let root = if self.bytes == 0 { size_of::<RayNode>() + 2 * size_of::<usize>() } else { 0 };
        if self.take(root) {
            self.tree.ray(ray, weight, depth)
        }
    }
    fn miss(&mut self, radiance: Rgb, contribution: Rgb) {
        if self.take(size_of::<Rgb>()) {
            self.tree.miss(radiance, contribution)
        }
    }
    fn hit(&mut self, scene: &Scene, hit: &Hit) {
        if self.take(size_of::<ShadingRecord>() + 2 * NAME) {
            WhittedTrace::hit(&mut self.tree, scene, hit)
        }
    }
    fn surface(&mut self, color: Rgb, emission: Rgb, ambient: Rgb) {
        if self.take(0) {
            self.tree.surface(color, emission, ambient)
        }
    }
    fn light(&mut self, light: crate::integrators::trace::LightRef) {
        if self.take(0) {
            self.tree.light(light)
        }
    }
    fn unlit(&mut self, why: crate::integrators::trace::Unlit) {
        if self.take(size_of::<LightRecord>()) {
            self.tree.unlit(why)
        }
    }
    fn lit(&mut self, scene: &Scene, term: &crate::integrators::trace::LightTerm) {
        if self.take(size_of::<LightRecord>() + size_of::<crate::integrators::trace::LightTerm>() + NAME) {
            self.tree.lit(scene, term)
        }
    }
    fn direct(&mut self, direct: Rgb, contribution: Rgb) {
        if self.take(size_of::<Rgb>()) {
            self.tree.direct(direct, contribution)
        }
    }
    fn depth_cutoff(&mut self) {
        if self.take(0) {
            self.tree.depth_cutoff()
        }
    }
    fn reflection(&mut self, how: crate::integrators::trace::ReflectionWeight, weight: Rgb) {
        if self.take(size_of::<RayKind>()) {
            self.tree.reflection(how, weight)
        }
    }
    fn refraction(&mut self, fresnel: Option<f64>, weight: Option<Rgb>) {
        if self.take(size_of::<RayKind>()) {
            self.tree.refraction(fresnel, weight)
        }
    }
    fn branch(&mut self, ray: &crate::ray::Ray, weight: Rgb, depth: u32, traced: bool) {
        if self.take(size_of::<RayNode>() + 3 * size_of::<usize>()) {
            self.tree.branch(ray, weight, depth, traced)
        }
    }
}

/// Forwards the path events to the path record.
impl PathTrace for Recorder {
    fn segment(&mut self, depth: u32, ray: &crate::ray::Ray, beta: Rgb) {
        if self.take(size_of::<PathVertex>()) {
            self.path.segment(depth, ray, beta)
        }
    }
    fn path_hit(&mut self, scene: &Scene, hit: &Hit) {
        if self.take(2 * NAME) {
            self.path.path_hit(scene, hit)
        }
    }
    fn emitted(&mut self, le: Rgb, weight: f64, contribution: Rgb) {
        if self.take(size_of::<Rgb>()) {
            self.path.emitted(le, weight, contribution)
        }
    }
    fn nee_miss(&mut self, why: crate::integrators::trace::NeeMiss) {
        if self.take(0) {
            self.path.nee_miss(why)
        }
    }
    fn nee(&mut self, sample: &crate::integrators::trace::NeeSample) {
        if self.take(size_of::<NeeRecord>() + NAME) {
            self.path.nee(sample)
        }
    }
    fn nee_contribution(&mut self, contribution: Rgb) {
        if self.take(size_of::<Rgb>()) {
            self.path.nee_contribution(contribution)
        }
    }
    fn bsdf_sample(&mut self, sample: &crate::bsdfs::BsdfSample, wi: Vec3, beta: Rgb) {
        if self.take(0) {
            self.path.bsdf_sample(sample, wi, beta)
        }
    }
    fn survived(&mut self, survive: f64, beta: Rgb) {
        if self.take(0) {
            self.path.survived(survive, beta)
        }
    }
    fn end(&mut self, why: crate::integrators::trace::PathEnd) {
        if self.take(0) {
            self.path.end(why)
        }
    }
}
