//! [`PathRecord`]: the recorder of one path-traced sample, vertex by vertex.

use super::HitInfo;
use crate::bsdfs::BsdfSample;
use crate::integrators::trace::{NeeMiss, NeeSample, PathEnd, PathTrace};
use crate::math::{Rgb, Vec3};
use crate::ray::Ray;
use crate::scene::{Hit, Scene};

/// One path: its vertices, why it ended, and every term it added in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathRecord {
    /// The segments, camera ray first.
    pub vertices: Vec<PathVertex>,
    /// Why it ended.
    pub end: Option<PathEnd>,
    /// What it added to the sample, in the tracer's order (emission and light samples).
    pub contributions: Vec<Rgb>,
}

/// One segment of a path and what happened where it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct PathVertex {
    /// Segment number (camera ray = 1).
    pub depth: u32,
    /// The ray.
    pub ray: Ray,
    /// Throughput `beta` carried along it.
    pub beta: Rgb,
    /// Its hit (`None`: it left the scene).
    pub hit: Option<HitInfo>,
    /// Emission found along it: `(Le, MIS weight, beta Le w)`.
    pub emitted: Option<(Rgb, f64, Rgb)>,
    /// The light sample at the hit.
    pub nee: Option<NeeRecord>,
    /// What the light sample added: `beta * value`.
    pub nee_contribution: Option<Rgb>,
    /// The BSDF sample that continues the path: `(sample, wi in world space, throughput after it)`.
    pub bsdf: Option<(BsdfSample, Vec3, Rgb)>,
    /// Russian roulette survived: `(probability, throughput after reweighting)`.
    pub survived: Option<(f64, Rgb)>,
}

/// A vertex's next-event estimate.
#[derive(Clone, Debug, PartialEq)]
pub enum NeeRecord {
    /// Nothing, and why.
    Miss(NeeMiss),
    /// The light sample.
    Sample {
        /// The light picked (`PointLight`, `AreaLight`, `Environment`, ...).
        light: String,
        /// Its pick probability.
        pick_probability: f64,
        /// Unit direction to it.
        wi: Vec3,
        /// Distance to it.
        distance: f64,
        /// `Li`.
        li: Rgb,
        /// Solid-angle density (`None`: a delta light).
        light_pdf: Option<f64>,
        /// BSDF value.
        f: Rgb,
        /// `|cos theta_i|`.
        cos: f64,
        /// BSDF density of `wi`.
        bsdf_pdf: f64,
        /// MIS weight.
        mis_weight: f64,
        /// The estimate before `beta`.
        value: Rgb,
    },
}

impl PathRecord {
    fn vertex(&mut self) -> &mut PathVertex {
        self.vertices.last_mut().expect("events follow a segment")
    }
}

impl PathTrace for PathRecord {
    fn segment(&mut self, depth: u32, ray: &Ray, beta: Rgb) {
        self.vertices.push(PathVertex {
            depth,
            ray: *ray,
            beta,
            hit: None,
            emitted: None,
            nee: None,
            nee_contribution: None,
            bsdf: None,
            survived: None,
        });
    }

    fn path_hit(&mut self, scene: &Scene, hit: &Hit) {
        self.vertex().hit = Some(HitInfo::new(scene, hit));
    }

    fn emitted(&mut self, le: Rgb, weight: f64, contribution: Rgb) {
        self.vertex().emitted = Some((le, weight, contribution));
        self.contributions.push(contribution);
    }

    fn nee_miss(&mut self, why: NeeMiss) {
        self.vertex().nee = Some(NeeRecord::Miss(why));
    }

    fn nee(&mut self, s: &NeeSample) {
        self.vertex().nee = Some(NeeRecord::Sample {
            light: super::kind_name(s.light),
            pick_probability: s.pick_probability,
            wi: s.wi,
            distance: s.distance,
            li: s.li,
            light_pdf: s.light_pdf,
            f: s.f,
            cos: s.cos,
            bsdf_pdf: s.bsdf_pdf,
            mis_weight: s.mis_weight,
            value: s.value,
        });
    }

    fn nee_contribution(&mut self, contribution: Rgb) {
        self.vertex().nee_contribution = Some(contribution);
        self.contributions.push(contribution);
    }

    fn bsdf_sample(&mut self, sample: &BsdfSample, wi: Vec3, beta: Rgb) {
        self.vertex().bsdf = Some((*sample, wi, beta));
    }

    fn survived(&mut self, survive: f64, beta: Rgb) {
        self.vertex().survived = Some((survive, beta));
    }

    fn end(&mut self, why: PathEnd) {
        self.end = Some(why);
    }
}
