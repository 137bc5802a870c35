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

pub mod conductor;
pub mod dielectric;
pub mod distribution;
mod fresnel;
pub mod lambertian;
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
pub use distribution::{Distribution, Microfacet};
pub use fresnel::{fresnel_conductor, fresnel_conductor_channel, fresnel_dielectric};
pub use metals::Metal;

use crate::math::{orthonormal_basis, Rgb, Vec3};

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
}

/// One lobe of a [`Bsdf`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lobe {
    /// Lambertian reflection of this albedo.
    Diffuse(Rgb),
    /// GGX reflection with constant reflectance `ks` and roughness `alpha`.
    Glossy {
        /// Reflectance.
        ks: Rgb,
        /// GGX roughness.
        alpha: f64,
    },
    /// Smooth mirror (delta).
    Mirror(MirrorFresnel),
    /// Smooth glass: Fresnel reflection and refraction, relative index `eta = n_t / n_i` (delta).
    Glass {
        /// Relative index across the boundary.
        eta: f64,
        /// Colour filter of both branches (1 for clear glass).
        tint: Rgb,
    },
    /// Rough metal: microfacet reflection with conductor Fresnel ([`rough_conductor`]).
    RoughConductor {
        /// Real part of the index, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
        /// Roughness.
        alpha: f64,
        /// GGX or Beckmann.
        distribution: Distribution,
    },
    /// Rough glass: microfacet reflection and refraction ([`rough_dielectric`]).
    RoughGlass {
        /// Relative index across the boundary.
        eta: f64,
        /// Roughness.
        alpha: f64,
        /// Colour filter of both branches (1 for clear glass).
        tint: Rgb,
        /// GGX or Beckmann.
        distribution: Distribution,
    },
    /// Smooth plastic: a delta coating reflection over a diffuse lobe ([`plastic`]).
    Plastic(plastic::Plastic),
    /// Rough plastic: a microfacet coating over a diffuse base ([`rough_plastic`]).
    RoughPlastic(rough_plastic::RoughPlastic),
    /// A thin dielectric sheet: reflection `R'` and straight transmission `1 - R'` ([`thin_dielectric`], delta).
    ThinGlass {
        /// Relative index of the sheet.
        eta: f64,
        /// Colour filter of both branches.
        tint: Rgb,
    },
    /// The glTF metallic-roughness BSDF ([`metallic_roughness`]), with
    /// `KHR_materials_transmission`'s thin-walled transmission.
    MetallicRoughness(metallic_roughness::MetallicRoughness),
    /// Mitsuba's principled BSDF ([`principled`]).
    Principled(principled::Principled),
    /// Mitsuba's thin principled BSDF ([`principled_thin`]).
    PrincipledThin(principled_thin::PrincipledThin),
    /// Smooth refraction only, with weight `Constant` or `1 - F` (delta).
    Refract {
        /// Relative index across the boundary.
        eta: f64,
        /// Constant weight, or `None` for the Fresnel weight `1 - F`.
        weight: Option<Rgb>,
    },
}

impl Lobe {
    /// True for lobes that scatter into single directions.
    pub fn is_delta(&self) -> bool {
        !matches!(
            self,
            Lobe::Diffuse(_)
                | Lobe::Glossy { .. }
                | Lobe::RoughConductor { .. }
                | Lobe::RoughGlass { .. }
                | Lobe::MetallicRoughness(_)
                | Lobe::Plastic(_)
                | Lobe::RoughPlastic(_)
                | Lobe::Principled(_)
                | Lobe::PrincipledThin(_)
        )
    }

    /// Per-channel upper bound of the reflectance (albedo) over all angles.
    pub fn bound(&self) -> Rgb {
        match *self {
            Lobe::Diffuse(a) => a,
            Lobe::Glossy { ks, .. } => ks,
            Lobe::Mirror(m) => m.bound(),
            Lobe::RoughConductor { .. } | Lobe::Plastic(_) | Lobe::RoughPlastic(_) | Lobe::Principled(_) | Lobe::PrincipledThin(_) => {
                Rgb::ONE
            }
            Lobe::Glass { tint, .. } | Lobe::RoughGlass { tint, .. } | Lobe::ThinGlass { tint, .. } => tint,
            Lobe::Refract { weight, .. } => weight.unwrap_or(Rgb::ONE),
            Lobe::MetallicRoughness(lobe) => lobe.bound(),
        }
    }

    fn scaled(self, s: Rgb) -> Lobe {
        match self {
            Lobe::Diffuse(a) => Lobe::Diffuse(a * s),
            Lobe::Glossy { ks, alpha } => Lobe::Glossy { ks: ks * s, alpha },
            Lobe::Mirror(MirrorFresnel::Constant(w)) => Lobe::Mirror(MirrorFresnel::Constant(w * s)),
            // Fresnel-driven lobes keep their physics; only a scale below 1 changes them,
            // through a constant-weight tint.
            Lobe::Mirror(m) => {
                if s == Rgb::ONE {
                    Lobe::Mirror(m)
                } else {
                    Lobe::Mirror(MirrorFresnel::Constant(m.bound() * s))
                }
            }
            Lobe::Glass { eta, tint } => Lobe::Glass { eta, tint: tint * s },
            Lobe::RoughGlass { eta, alpha, tint, distribution } => Lobe::RoughGlass { eta, alpha, tint: tint * s, distribution },
            Lobe::ThinGlass { eta, tint } => Lobe::ThinGlass { eta, tint: tint * s },
            // Like the conductor mirror: physics when unscaled, else a constant-reflectance GGX lobe.
            Lobe::RoughConductor { alpha, .. } if s != Rgb::ONE => Lobe::Glossy { ks: s, alpha },
            Lobe::RoughConductor { .. } => self,
            Lobe::Refract { eta, weight } => Lobe::Refract { eta, weight: Some(weight.unwrap_or(Rgb::ONE) * s) },
            // Their bounds are at most 1 and their materials use them alone: never scaled.
            Lobe::MetallicRoughness(_) | Lobe::Plastic(_) | Lobe::RoughPlastic(_) | Lobe::Principled(_) | Lobe::PrincipledThin(_) => self,
        }
    }
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
}

impl Bsdf {
    /// A BSDF from lobes, scaled per channel so that the reflectance bounds sum to at most 1.
    pub fn new(lobes: &[Lobe]) -> Bsdf {
        let lobes = &lobes[..lobes.len().min(MAX_LOBES)];
        let total: Rgb = lobes.iter().map(|l| l.bound()).sum();
        let scale = Rgb::ONE / total.max(Rgb::ONE);
        let mut out = Bsdf { lobes: [Lobe::Diffuse(Rgb::ZERO); MAX_LOBES], probs: [0.0; MAX_LOBES], count: 0 };
        let mut sum = 0.0;
        for lobe in lobes {
            let lobe = lobe.scaled(scale);
            let p = lobe.bound().max_element();
            if !(p > 0.0) {
                continue;
            }
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

    /// True when some lobe has a value that a light sample can meet.
    pub fn has_smooth_part(&self) -> bool {
        self.lobes().iter().any(|l| !l.is_delta())
    }

    /// The albedo when the BSDF is one Lambertian lobe (most surfaces of most
    /// scenes): [`Bsdf::f`], [`Bsdf::pdf`] and [`Bsdf::sample`] then skip the lobe
    /// loop (and the sample's weight is the albedo itself, not `f cos / pdf`).
    #[inline(always)]
    fn single_diffuse(&self) -> Option<Rgb> {
        match self.lobes[0] {
            Lobe::Diffuse(albedo) if self.count == 1 => Some(albedo),
            _ => None,
        }
    }

    /// True when [`Bsdf::sample`] reads its `u_lobe` (more than one lobe, or glass
    /// choosing between reflection and refraction).
    #[inline]
    pub fn uses_lobe_sample(&self) -> bool {
        self.single_diffuse().is_none()
    }

    /// Sum of the non-delta lobes' values.
    #[inline]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if let Some(albedo) = self.single_diffuse() {
            return lambertian::f(albedo, wo, wi);
        }
        let mut sum = Rgb::ZERO;
        for lobe in self.lobes() {
            match *lobe {
                Lobe::Diffuse(a) => sum += lambertian::f(a, wo, wi),
                Lobe::Glossy { ks, alpha } => sum += microfacet::f(ks, alpha, wo, wi),
                Lobe::RoughGlass { eta, alpha, tint, distribution } => {
                    sum += tint * rough_dielectric::f(Microfacet::new(distribution, alpha), eta, wo, wi)
                }
                Lobe::RoughConductor { eta, k, alpha, distribution } => {
                    sum += rough_conductor::f(eta, k, Microfacet::new(distribution, alpha), wo, wi)
                }
                Lobe::Plastic(p) => sum += p.f(wo, wi),
                Lobe::RoughPlastic(p) => sum += p.f(wo, wi),
                Lobe::Principled(p) => sum += p.f(wo, wi),
                Lobe::PrincipledThin(p) => sum += p.f(wo, wi),
                Lobe::MetallicRoughness(lobe) => sum += lobe.f(wo, wi),
                _ => {}
            }
        }
        sum
    }

    /// Solid-angle density with which [`Bsdf::sample`] returns `wi` from a non-delta lobe
    /// (`wi.z < 0`: transmitted).
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        if self.single_diffuse().is_some() {
            // The single lobe's probability is exactly 1.
            return lambertian::pdf(wo, wi);
        }
        let mut pdf = 0.0;
        for (lobe, p) in self.lobes().iter().zip(self.probs) {
            match *lobe {
                Lobe::Diffuse(_) => pdf += p * lambertian::pdf(wo, wi),
                Lobe::Glossy { alpha, .. } => pdf += p * microfacet::pdf(alpha, wo, wi),
                Lobe::RoughConductor { alpha, distribution, .. } => pdf += p * Microfacet::new(distribution, alpha).pdf(wo, wi),
                Lobe::RoughGlass { eta, alpha, distribution, .. } => {
                    pdf += p * rough_dielectric::pdf(Microfacet::new(distribution, alpha), eta, wo, wi)
                }
                Lobe::Plastic(lobe) => pdf += p * lobe.pdf(wo, wi),
                Lobe::RoughPlastic(lobe) => pdf += p * lobe.pdf(wo, wi),
                Lobe::Principled(lobe) => pdf += p * lobe.pdf(wo, wi),
                Lobe::PrincipledThin(lobe) => pdf += p * lobe.pdf(wo, wi),
                Lobe::MetallicRoughness(lobe) => pdf += p * lobe.pdf(wo, wi),
                _ => {}
            }
        }
        pdf
    }

    /// Samples an incident direction for outgoing `wo` (local, `wo.z > 0`): `u_lobe`
    /// picks the lobe (and, rescaled, the glass branch), `u` the direction.
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
        let delta = |wi: Vec3, weight: Rgb, eta: f64| Some(BsdfSample { wi, weight: weight / p, pdf: 0.0, delta: true, eta });
        let wi = match self.lobes[chosen] {
            Lobe::Diffuse(_) => lambertian::sample(u),
            Lobe::Glossy { alpha, .. } => microfacet::sample(alpha, wo, u)?,
            Lobe::RoughConductor { alpha, distribution, .. } => Microfacet::new(distribution, alpha).sample(wo, u)?,
            Lobe::RoughGlass { eta, alpha, distribution, .. } => {
                rough_dielectric::sample(Microfacet::new(distribution, alpha), eta, wo, u_rest, u)?
            }
            Lobe::Plastic(lobe) => match lobe.sample(wo, u_rest, u)? {
                plastic::PlasticSample::Specular(wi, weight) => return delta(wi, weight, 1.0),
                plastic::PlasticSample::Diffuse(wi) => wi,
            },
            Lobe::RoughPlastic(lobe) => lobe.sample(wo, u_rest, u)?,
            Lobe::Principled(lobe) => lobe.sample(wo, u_rest, u)?,
            Lobe::PrincipledThin(lobe) => lobe.sample(wo, u_rest, u)?,
            Lobe::ThinGlass { eta, tint } => return delta(thin_dielectric::sample(wo, eta, u_rest).0, tint, 1.0),
            Lobe::MetallicRoughness(lobe) => lobe.sample(wo, u_rest, u)?,
            Lobe::Mirror(m) => return delta(dielectric::reflect_local(wo), m.reflectance(wo.z), 1.0),
            Lobe::Glass { eta, tint } => {
                let s = dielectric::sample(wo, eta, u_rest);
                return delta(s.wi, tint * s.weight, if s.transmitted { eta } else { 1.0 });
            }
            Lobe::Refract { eta, weight } => {
                let wi = dielectric::refract_local(wo, eta)?;
                let w = weight.unwrap_or_else(|| Rgb::splat(1.0 - fresnel::fresnel_dielectric(wo.z, eta)));
                return delta(wi, w / (eta * eta), eta);
            }
        };
        let pdf = self.pdf(wo, wi);
        if !(pdf > 0.0) {
            return None;
        }
        // Only rough glass and principled lobes transmit and bend among the
        // non-delta lobes (a thin sheet does not, nor the metallic-roughness
        // transmission, which is thin-walled: `eta = 1`).
        let eta = match self.lobes[chosen] {
            Lobe::RoughGlass { eta, .. } if wi.z < 0.0 => eta,
            Lobe::Principled(lobe) => lobe.eta_towards(wi),
            _ => 1.0,
        };
        Some(BsdfSample { wi, weight: self.f(wo, wi) * wi.z.abs() / pdf, pdf, delta: false, eta })
    }
}

#[cfg(test)]
mod tests;
