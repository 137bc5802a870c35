//! Physically based scattering for the path tracer: a [`Bsdf`] is a weighted sum
//! of lobes (one file each), evaluated and sampled in a local shading frame whose
//! `z` axis is the shading normal on the side the ray arrived from.
//!
//! Non-delta lobes (Lambertian, GGX reflection, rough glass) have a value `f(wo, wi)` and a density; delta
//! lobes (mirrors, smooth glass) are only sampled. Sampling picks a lobe with
//! probability proportional to its reflectance bound; for a non-delta lobe the
//! returned weight uses the mixture value and density of all non-delta lobes
//! (`f cos / sum_j p_j pdf_j`), which is what multiple importance sampling with
//! light samples needs. [`Bsdf::new`] scales the lobes so that their reflectance
//! bounds sum to at most 1 per channel: no material reflects more than it receives.
//!
//! The lobes are physics only: they import math and sampling, never the materials
//! or the scene above them. Which lobes a material is, is decided by the material
//! kinds, each in its own file.
//!
//! Each lobe is a type in its own file that implements [`Scatter`] (its bound,
//! value, density, sampling and scaling); the `lobes!` registry below gives it
//! its [`Lobe`] variant and dispatch in one line. A new lobe is its file, its
//! `pub mod` line and its registry line.

pub mod anisotropic;
pub mod conductor;
pub mod dielectric;
pub mod distribution;
mod fresnel;
pub mod lambertian;
mod lobe;
pub mod metallic_roughness;
mod metals;
pub mod microfacet;
pub mod plastic;
pub mod principled;
pub mod principled_thin;
pub mod rough_conductor;
pub mod rough_dielectric;
pub mod rough_plastic;
#[cfg(test)]
pub(crate) mod test_support;
pub mod thin_dielectric;

pub use conductor::MirrorFresnel;
pub use dielectric::{Glass, Refract};
pub use distribution::{Distribution, Microfacet};
pub use fresnel::{fresnel_conductor, fresnel_conductor_channel, fresnel_dielectric};
pub use lambertian::Lambertian;
pub use lobe::{Sampled, Scatter};
pub use metals::Metal;
pub use microfacet::Glossy;
pub use rough_conductor::RoughConductor;
pub use rough_dielectric::RoughGlass;
pub use thin_dielectric::ThinGlass;

use crate::math::{orthonormal_basis, Rgb, Vec3};
use lobe::lobes;

/// An orthonormal frame around a unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub t: Vec3,
    /// Second tangent.
    pub b: Vec3,
    /// The normal (local `z`).
    pub n: Vec3,
}

impl Frame {
    /// The frame of unit normal `n`.
    pub fn new(n: Vec3) -> Frame {
        let (t, b) = orthonormal_basis(n);
        Frame { t, b, n }
    }

    /// World to local coordinates.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }

    /// Local to world coordinates.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }

    /// The frame of unit normal `n` whose first tangent follows the surface's
    /// `dpdu`, as Mitsuba 3 builds its shading frame (`initialize_sh_frame`):
    /// `t = normalize(dpdu - n (n.dpdu))` (Gram-Schmidt), `b = n x t`. Where
    /// `dpdu` is zero or along `n`, `t` is the first tangent of the basis
    /// around `outward` (Mitsuba's `coordinate_system` of its outward shading
    /// normal; `n` or `-n`). Anisotropic lobes need it: their roughness is
    /// measured along `t` and `b`.
    pub fn from_tangent(n: Vec3, dpdu: Vec3, outward: Vec3) -> Frame {
        let t = match (dpdu - n * n.dot(dpdu)).try_normalize() {
            Some(t) => t,
            None => orthonormal_basis(outward).0,
        };
        Frame { t, b: n.cross(t), n }
    }
}

lobes! {
    /// Lambertian reflection ([`lambertian`]).
    Diffuse(Lambertian),
    /// GGX reflection with a constant reflectance ([`microfacet`]).
    Glossy(Glossy),
    /// Smooth mirror (delta, [`conductor`]).
    Mirror(MirrorFresnel),
    /// Smooth glass: Fresnel reflection and refraction (delta, [`dielectric`]).
    Glass(Glass),
    /// Rough metal: microfacet reflection with conductor Fresnel ([`rough_conductor`]).
    RoughConductor(RoughConductor),
    /// Rough glass: microfacet reflection and refraction ([`rough_dielectric`]).
    RoughGlass(RoughGlass),
    /// Smooth plastic: a delta coating reflection over a diffuse lobe ([`plastic`]).
    Plastic(plastic::Plastic),
    /// Rough plastic: a microfacet coating over a diffuse base ([`rough_plastic`]).
    RoughPlastic(rough_plastic::RoughPlastic),
    /// A thin dielectric sheet: reflection and straight transmission (delta, [`thin_dielectric`]).
    ThinGlass(ThinGlass),
    /// The glTF metallic-roughness BSDF ([`metallic_roughness`]), with
    /// `KHR_materials_transmission`'s thin-walled transmission.
    MetallicRoughness(metallic_roughness::MetallicRoughness),
    /// Mitsuba's principled BSDF ([`principled`]).
    Principled(principled::Principled),
    /// Mitsuba's thin principled BSDF ([`principled_thin`]).
    PrincipledThin(principled_thin::PrincipledThin),
    /// Smooth refraction only, with a constant or a Fresnel weight (delta, [`dielectric`]).
    Refract(Refract),
}

/// Most lobes a material maps to.
pub const MAX_LOBES: usize = 4;

/// A sampled incident direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Incident direction, local frame.
    pub wi: Vec3,
    /// `f |cos| / pdf`: the factor the path throughput is multiplied by.
    pub weight: Rgb,
    /// Solid-angle density of the sample (the mixture over non-delta lobes); 0 for a delta lobe.
    pub pdf: f64,
    /// True when a delta lobe produced it (no light sample could have).
    pub delta: bool,
    /// Relative index `n_t / n_i` of a refraction (1 for reflection): the weight
    /// carries the radiance factor `1 / eta^2`, the power is `weight * eta^2`.
    pub eta: f64,
}

/// A weighted sum of lobes with their sampling probabilities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bsdf {
    lobes: [Lobe; MAX_LOBES],
    probs: [f64; MAX_LOBES],
    count: usize,
    /// Some lobe is anisotropic ([`Bsdf::needs_tangent`]).
    tangent: bool,
}

impl Bsdf {
    /// A BSDF from lobes, scaled per channel so that the reflectance bounds sum to at most 1.
    pub fn new(lobes: &[Lobe]) -> Bsdf {
        let lobes = &lobes[..lobes.len().min(MAX_LOBES)];
        let total: Rgb = lobes.iter().map(|l| l.bound()).sum();
        let scale = Rgb::ONE / total.max(Rgb::ONE);
        let mut out = Bsdf { lobes: [Lobe::Diffuse(Lambertian(Rgb::ZERO)); MAX_LOBES], probs: [0.0; MAX_LOBES], count: 0, tangent: false };
        let mut sum = 0.0;
        for lobe in lobes {
            let lobe = lobe.scaled(scale);
            let p = lobe.bound().max_element();
            if !(p > 0.0) {
                continue;
            }
            out.tangent |= lobe.needs_tangent();
            out.lobes[out.count] = lobe;
            out.probs[out.count] = p;
            out.count += 1;
            sum += p;
        }
        for p in &mut out.probs[..out.count] {
            *p /= sum;
        }
        out
    }

    /// The lobes, after scaling.
    pub fn lobes(&self) -> &[Lobe] {
        &self.lobes[..self.count]
    }

    /// True when nothing scatters (a black or purely emitting surface).
    pub fn is_black(&self) -> bool {
        self.count == 0
    }

    /// True when some lobe is anisotropic: the local frame's first tangent must
    /// then be the surface's `dp/du` ([`Frame::from_tangent`]); any frame around
    /// the normal serves the others.
    #[inline]
    pub fn needs_tangent(&self) -> bool {
        self.tangent
    }

    /// True when some lobe has a value that a light sample can meet.
    pub fn has_smooth_part(&self) -> bool {
        self.lobes().iter().any(|l| !l.is_delta())
    }

    /// The albedo when the BSDF is one Lambertian lobe (most surfaces of most
    /// scenes): [`Bsdf::f`], [`Bsdf::pdf`] and [`Bsdf::sample`] then skip the lobe
    /// loop (and the sample's weight is the albedo itself, not `f cos / pdf`).
    #[inline(always)]
    pub(crate) fn single_diffuse(&self) -> Option<Rgb> {
        match self.lobes[0] {
            Lobe::Diffuse(Lambertian(albedo)) if self.count == 1 => Some(albedo),
            _ => None,
        }
    }

    /// True when [`Bsdf::sample`] reads its `u_lobe` (more than one lobe, or glass
    /// choosing between reflection and refraction).
    #[inline]
    pub fn uses_lobe_sample(&self) -> bool {
        self.single_diffuse().is_none()
    }

    /// Sum of the non-delta lobes' values (the single Lambertian lobe compiled
    /// into the caller, as in [`Bsdf::sample`]).
    #[inline(always)]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if let Some(albedo) = self.single_diffuse() {
            return lambertian::f(albedo, wo, wi);
        }
        self.f_lobes(wo, wi)
    }

    /// [`Bsdf::f`] of any other BSDF.
    #[inline(never)]
    fn f_lobes(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let mut sum = Rgb::ZERO;
        for lobe in self.lobes() {
            lobe.add_f(&mut sum, wo, wi);
        }
        sum
    }

    /// Solid-angle density with which [`Bsdf::sample`] returns `wi` from a non-delta lobe
    /// (`wi.z < 0`: transmitted).
    #[inline(always)]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        if self.single_diffuse().is_some() {
            // The single lobe's probability is exactly 1.
            return lambertian::pdf(wo, wi);
        }
        self.pdf_lobes(wo, wi)
    }

    /// [`Bsdf::pdf`] of any other BSDF.
    #[inline(never)]
    fn pdf_lobes(&self, wo: Vec3, wi: Vec3) -> f64 {
        let mut pdf = 0.0;
        for (lobe, p) in self.lobes().iter().zip(self.probs) {
            lobe.add_pdf(&mut pdf, p, wo, wi);
        }
        pdf
    }

    /// Samples an incident direction for outgoing `wo` (local, `wo.z > 0`): `u_lobe`
    /// picks the lobe (and, rescaled, the glass branch), `u` the direction.
    ///
    /// The single Lambertian lobe is compiled into the caller (the path
    /// tracer's loop, in its AVX2 compilation); other BSDFs go out of line.
    #[inline(always)]
    pub fn sample(&self, wo: Vec3, u_lobe: f64, u: (f64, f64)) -> Option<BsdfSample> {
        if let Some(albedo) = self.single_diffuse() {
            let wi = lambertian::sample(u);
            let pdf = lambertian::pdf(wo, wi);
            if !(pdf > 0.0) {
                return None;
            }
            // f cos / pdf = (albedo / pi) cos / (cos / pi), both directions above
            // the surface (pdf > 0): exactly the albedo.
            return Some(BsdfSample { wi, weight: albedo, pdf, delta: false, eta: 1.0 });
        }
        self.sample_lobes(wo, u_lobe, u)
    }

    /// [`Bsdf::sample`] of any other BSDF: a lobe picked by `u_lobe`, then sampled.
    #[inline(never)]
    fn sample_lobes(&self, wo: Vec3, u_lobe: f64, u: (f64, f64)) -> Option<BsdfSample> {
        let mut start = 0.0;
        let mut chosen = self.count.checked_sub(1)?;
        for i in 0..self.count {
            if u_lobe < start + self.probs[i] {
                chosen = i;
                break;
            }
            start += self.probs[i];
        }
        let p = self.probs[chosen];
        let u_rest = ((u_lobe - start) / p).clamp(0.0, 1.0 - f64::EPSILON);
        let chosen = &self.lobes[chosen];
        let wi = match chosen.sample(wo, u_rest, u)? {
            Sampled::Smooth(wi) => wi,
            Sampled::Delta { wi, weight, eta } => return Some(BsdfSample { wi, weight: weight / p, pdf: 0.0, delta: true, eta }),
        };
        let pdf = self.pdf(wo, wi);
        if !(pdf > 0.0) {
            return None;
        }
        // Among the non-delta lobes only rough glass and the principled lobe
        // refract ([`Scatter::eta_towards`]).
        let eta = chosen.eta_towards(wi);
        Some(BsdfSample { wi, weight: self.f(wo, wi) * wi.z.abs() / pdf, pdf, delta: false, eta })
    }
}

#[cfg(test)]
mod tests;
