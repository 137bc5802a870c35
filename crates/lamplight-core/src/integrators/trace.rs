//! What an integrator tells a recorder while it computes one sample, so that
//! `lamplight explain` can show the ray tree of a pixel computed by the very code
//! that renders it (no second Whitted tracer that could disagree).
//!
//! The integrators are generic over a recorder. Ordinary renders pass
//! [`NoTrace`], whose methods are the traits' empty default bodies, marked
//! `#[inline(always)]`: monomorphized, every call and every value built only for
//! it vanish, and the render compiles to the code it had before recording
//! existed (checked by instruction counts, `BENCHMARKS.md`). `explain` passes a
//! `&mut dyn Trace` (the recorders of [`crate::explain`]).
//!
//! Each event states the values the integrator has just used, so a recorder
//! never recomputes them; where it reports a sum (`contribution`) that is the
//! very term the integrator adds to its radiance, in the integrator's order.

use crate::bsdfs::BsdfSample;
use crate::lights::Light;
use crate::math::{Rgb, Vec3};
use crate::ray::Ray;
use crate::scene::{Hit, Scene};

/// Which light the next [`WhittedTrace::lit`] or [`WhittedTrace::unlit`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightRef {
    /// `scene.lights[i]`, a delta light (point, directional, spot).
    Delta(usize),
    /// Point `sample` of the area light of scene object `object`.
    Area {
        /// The emitting object.
        object: usize,
        /// Index of the stratified point (0 to [`super::Whitted`]'s 16 area samples - 1).
        sample: u32,
    },
}

/// Why a light adds nothing at a hit without a shadow ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unlit {
    /// The light sends nothing to the point (outside a spot's cone, a light point seen from behind).
    NotReached,
    /// The light is below the surface: `L.N` at or below 1e-10 (the value), or behind the geometric surface.
    Below(f64),
    /// The unshadowed reflection `kd C (L.N) + ks (H.N)^n` is below 1e-12 in every channel.
    Negligible,
}

/// One light at one Whitted hit, with its shadow ray traced: the lecture's terms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightTerm {
    /// Unit direction to the light `L`.
    pub wi: Vec3,
    /// Distance to the light (infinite for a directional light).
    pub distance: f64,
    /// Incident radiance `Lin` (for an area light point: `Le / (pi pdf N)`).
    pub lin: Rgb,
    /// `L.N` with the shading normal (positive here).
    pub cos_light: f64,
    /// `H.N`, `H` the half vector of `L` and the view direction.
    pub cos_half: f64,
    /// `kd C (L.N)+`.
    pub diffuse: Rgb,
    /// `ks ((H.N)+)^shine`.
    pub specular: Rgb,
    /// The shadow ray: from the offset origin along `wi`.
    pub shadow: Ray,
    /// Its length (to the light, less the offset).
    pub shadow_length: f64,
    /// The object the shadow ray may end on (the light's own body).
    pub own: Option<usize>,
    /// Transmittance of the shadow ray (0: blocked, 1: clear).
    pub visible: Rgb,
    /// What the light adds to the hit's direct light: `Lin visible (diffuse + specular)`.
    pub radiance: Rgb,
}

/// How a Whitted hit's reflection weight was found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReflectionWeight {
    /// The material's constant weight.
    Constant,
    /// `min + (max - min) F`, `F` the dielectric Fresnel reflectance.
    Dielectric {
        /// Fresnel reflectance `F`.
        fresnel: f64,
    },
    /// Conductor Fresnel reflectance per channel (the weight itself).
    Conductor,
}

/// Events of the Whitted tracer ([`super::Whitted`]), all no-ops by default.
#[allow(unused_variables)]
pub trait WhittedTrace {
    /// A ray is taken off the work list (the camera ray first, then depth first).
    #[inline(always)]
    fn ray(&mut self, ray: &Ray, weight: Rgb, depth: u32) {}
    /// The ray left the scene: the sky's `radiance`; `contribution = weight * radiance` is added to the pixel.
    #[inline(always)]
    fn miss(&mut self, radiance: Rgb, contribution: Rgb) {}
    /// The ray's nearest hit.
    #[inline(always)]
    fn hit(&mut self, scene: &Scene, hit: &Hit) {}
    /// The hit's colour `C`, its emission `Ke` towards the ray (0 if none) and the ambient term `ka C La`.
    #[inline(always)]
    fn surface(&mut self, color: Rgb, emission: Rgb, ambient: Rgb) {}
    /// The next event is about `light`.
    #[inline(always)]
    fn light(&mut self, light: LightRef) {}
    /// The light adds nothing, and no shadow ray was traced.
    #[inline(always)]
    fn unlit(&mut self, why: Unlit) {}
    /// The light's shadow ray was traced (`scene` to find what blocked it).
    #[inline(always)]
    fn lit(&mut self, scene: &Scene, term: &LightTerm) {}
    /// All the hit's direct light, and `contribution = weight * direct`, added to the pixel.
    #[inline(always)]
    fn direct(&mut self, direct: Rgb, contribution: Rgb) {}
    /// The ray is at the depth limit: no reflected or refracted ray leaves the hit.
    #[inline(always)]
    fn depth_cutoff(&mut self) {}
    /// The hit reflects with local weight `weight` (nonzero), found as `how` says.
    #[inline(always)]
    fn reflection(&mut self, how: ReflectionWeight, weight: Rgb) {}
    /// The hit refracts: `fresnel` is `F` for Fresnel glass (`None`: constant
    /// weight); `weight` the local weight (`1 - F`), `None` for total internal reflection.
    #[inline(always)]
    fn refraction(&mut self, fresnel: Option<f64>, weight: Option<Rgb>) {}
    /// The next of the announced reflected/refracted rays, with its weight
    /// product `weight`; `traced` is false when the weight cut-off dropped it.
    #[inline(always)]
    fn branch(&mut self, ray: &Ray, weight: Rgb, depth: u32, traced: bool) {}
}

/// Why a path ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathEnd {
    /// It left the scene.
    Escaped,
    /// The depth limit.
    MaxDepth,
    /// The surface scatters nothing (a pure emitter).
    BlackBsdf,
    /// The BSDF sample failed (no direction).
    NoSample,
    /// The sampled direction is on the side the geometric normal forbids, or has zero weight.
    WrongSide,
    /// Russian roulette: `u >= survive`.
    Roulette {
        /// The survival probability `min(1, max(throughput))`.
        survive: f64,
        /// The sample value drawn.
        u: f64,
    },
}

/// Why a path vertex's light sample adds nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NeeMiss {
    /// The scene has no light to pick.
    NoLight,
    /// The picked light sends nothing to the point.
    NoSample,
    /// The light's direction is on the wrong side of the geometric surface.
    WrongSide,
    /// The BSDF reflects nothing in the light's direction.
    BlackBsdf,
    /// The shadow ray is blocked.
    Blocked,
}

/// A path vertex's next-event estimate that reached the light (or was blocked).
#[derive(Clone, Copy, Debug)]
pub struct NeeSample<'a> {
    /// The light picked.
    pub light: &'a dyn Light,
    /// Its pick probability.
    pub pick_probability: f64,
    /// Unit direction to the light point.
    pub wi: Vec3,
    /// Distance to it.
    pub distance: f64,
    /// Radiance arriving from it, `Li`.
    pub li: Rgb,
    /// Solid-angle density of the light sample (`None`: a delta light).
    pub light_pdf: Option<f64>,
    /// The BSDF value `f(wo, wi)`.
    pub f: Rgb,
    /// `|cos theta_i|`.
    pub cos: f64,
    /// The BSDF's density of `wi` (0 for a delta light: not used).
    pub bsdf_pdf: f64,
    /// The power-heuristic MIS weight (1 for a delta light).
    pub mis_weight: f64,
    /// The estimate `f Li |cos| w / (p_pick pdf)` (0 when blocked).
    pub value: Rgb,
}

/// Events of the path tracer ([`super::PathTracer`]), all no-ops by default.
#[allow(unused_variables)]
pub trait PathTrace {
    /// Vertex `depth` starts: `ray` with throughput `beta`.
    #[inline(always)]
    fn segment(&mut self, depth: u32, ray: &Ray, beta: Rgb) {}
    /// The ray's hit.
    #[inline(always)]
    fn path_hit(&mut self, scene: &Scene, hit: &Hit) {}
    /// Emitted light found along the ray (`le` from a surface or the sky), MIS
    /// weight `weight`, adding `contribution = beta * le * weight`.
    #[inline(always)]
    fn emitted(&mut self, le: Rgb, weight: f64, contribution: Rgb) {}
    /// The vertex's light sample added nothing.
    #[inline(always)]
    fn nee_miss(&mut self, why: NeeMiss) {}
    /// The vertex's light sample (its value before `beta`).
    #[inline(always)]
    fn nee(&mut self, sample: &NeeSample) {}
    /// `contribution = beta * nee` is added to the pixel.
    #[inline(always)]
    fn nee_contribution(&mut self, contribution: Rgb) {}
    /// The BSDF sample that continues the path (`wi` in world space) and the throughput after it (before roulette).
    #[inline(always)]
    fn bsdf_sample(&mut self, sample: &BsdfSample, wi: Vec3, beta: Rgb) {}
    /// The path survived Russian roulette with probability `survive`; throughput now `beta`.
    #[inline(always)]
    fn survived(&mut self, survive: f64, beta: Rgb) {}
    /// The path ends.
    #[inline(always)]
    fn end(&mut self, why: PathEnd) {}
}

/// A recorder for any integrator.
pub trait Trace: WhittedTrace + PathTrace {}

impl<T: WhittedTrace + PathTrace + ?Sized> Trace for T {}

/// Records nothing: what ordinary renders pass.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoTrace;

impl WhittedTrace for NoTrace {}
impl PathTrace for NoTrace {}
