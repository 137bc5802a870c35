//! Rough dielectric boundary (frosted glass): GGX microfacet reflection and
//! refraction (Walter, Marschner, Li and Torrance 2007, "Microfacet Models for
//! Refraction through Rough Surfaces"; the form of pbrt-v4's `DielectricBxDF`).
//!
//! In the local frame `wo.z > 0` lies on the side of relative index 1 and the far
//! side has `eta = n_t / n_i`. With `G2` the height-correlated Smith term and `F` the
//! dielectric Fresnel reflectance at the microfacet ([`fresnel_dielectric`]):
//!
//! - reflection (`wi.z > 0`), half vector `h = normalize(wo + wi)`:
//!   `f_r = D(h) G2(wo, wi) F(wo.h) / (4 |cos_o| |cos_i|)`;
//! - refraction (`wi.z < 0`), generalized half vector `h = ±normalize(wo + eta wi)`
//!   turned to `+z`: `f_t = D(h) G2 (1 - F(wo.h)) |wi.h| |wo.h| / (|cos_o| |cos_i| (wi.h + wo.h / eta)^2) / eta^2`.
//!
//! The last `1 / eta^2` is the radiance scaling of non-symmetric transport (pbrt's
//! `TransportMode::Radiance`): radiance is compressed into the narrower cone of the
//! denser side, as for smooth glass ([`super::dielectric`]). Microfacets facing away
//! from `wo` or `wi` (`(wo.h) cos_o < 0` or `(wi.h) cos_i < 0`) contribute nothing.
//!
//! Sampling draws `h` from the normals visible from `wo` for GGX
//! ([`super::microfacet::visible_normal`], density `D_wo(h) = G1(wo) (wo.h) D(h) / cos_o`),
//! from `D(h) cos(theta_h)` for Beckmann ([`Microfacet::sample_normal`]), then reflects with probability
//! `F(wo.h)` and refracts otherwise. The solid-angle densities are
//! `pdf_r = D_wo(h) F / (4 wo.h)` and `pdf_t = D_wo(h) (1 - F) |wi.h| / (wi.h + wo.h / eta)^2`,
//! the Jacobians `dh / dwi` of the two half-vector maps. Energy that the
//! single-scattering model leaves on the microsurface (`G2 < G1`) is lost: the
//! lobe's albedo is below 1 and falls with the roughness.

use super::distribution::{Distribution, Microfacet};
use super::fresnel::fresnel_dielectric;
use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// The microfacet normal of the pair `(wo, wi)` (turned to `+z`) and whether it is a
/// reflection; `None` for a degenerate or back-facing configuration.
#[inline]
fn half_vector(eta: f64, wo: Vec3, wi: Vec3) -> Option<(Vec3, bool)> {
    if wo.z <= 0.0 || wi.z == 0.0 {
        return None;
    }
    let reflect = wi.z > 0.0;
    let etap = if reflect { 1.0 } else { eta };
    let h = (wi * etap + wo).try_normalize()?;
    let h = if h.z < 0.0 { -h } else { h };
    if h.dot(wi) * wi.z < 0.0 || h.dot(wo) * wo.z < 0.0 {
        return None;
    }
    Some((h, reflect))
}

/// The BSDF value (one channel; a tint multiplies it) for the distribution `m` and
/// relative index `eta`.
pub fn f(m: Microfacet, eta: f64, wo: Vec3, wi: Vec3) -> f64 {
    let Some((h, reflect)) = half_vector(eta, wo, wi) else { return 0.0 };
    let d = m.d(h);
    let g2 = m.g2(wo, wi);
    let fr = fresnel_dielectric(wo.dot(h), eta);
    let (cos_o, cos_i) = (wo.z, wi.z.abs());
    if reflect {
        return d * g2 * fr / (4.0 * cos_o * cos_i);
    }
    let denom = wi.dot(h) + wo.dot(h) / eta;
    let denom = denom * denom;
    if !(denom > 0.0) {
        return 0.0;
    }
    d * g2 * (1.0 - fr) * (wi.dot(h) * wo.dot(h)).abs() / (cos_o * cos_i * denom) / (eta * eta)
}

/// Solid-angle density with which [`sample`] returns `wi`.
pub fn pdf(m: Microfacet, eta: f64, wo: Vec3, wi: Vec3) -> f64 {
    let Some((h, reflect)) = half_vector(eta, wo, wi) else { return 0.0 };
    let wo_h = wo.dot(h);
    // Density of the sampled normal h (for GGX, among the visible normals).
    let d_vis = m.normal_pdf(wo, h);
    let fr = fresnel_dielectric(wo_h, eta);
    if reflect {
        return d_vis * fr / (4.0 * wo_h);
    }
    let denom = wi.dot(h) + wo_h / eta;
    let denom = denom * denom;
    if !(denom > 0.0) {
        return 0.0;
    }
    d_vis * (1.0 - fr) * wi.dot(h).abs() / denom
}

/// Refraction of `wo` through a facet of normal `h` (`wo.h > 0`) into relative index
/// `eta`: `wi = -wo / eta + (c / eta - sqrt(1 - (1 - c^2) / eta^2)) h`, `c = wo.h`;
/// `None` on total internal reflection.
#[inline]
pub fn refract(wo: Vec3, h: Vec3, eta: f64) -> Option<Vec3> {
    let c = wo.dot(h);
    let sin2_t = (1.0 - c * c).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    (-wo / eta + h * (c / eta - cos_t)).try_normalize()
}

/// An incident direction for `wo` (`wo.z > 0`): a visible normal from `u`, then
/// reflection when `u_branch < F(wo.h)`, else refraction. `None` when the direction
/// ends on the wrong side of the macro-surface (the single-scattering loss).
pub fn sample(m: Microfacet, eta: f64, wo: Vec3, u_branch: f64, u: (f64, f64)) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    let h = m.sample_normal(wo, u);
    let wo_h = wo.dot(h);
    if wo_h <= 0.0 {
        return None;
    }
    if u_branch < fresnel_dielectric(wo_h, eta) {
        let wi = h * (2.0 * wo_h) - wo;
        return (wi.z > 0.0).then_some(wi);
    }
    let wi = refract(wo, h, eta)?;
    (wi.z < 0.0).then_some(wi)
}

/// Rough glass: microfacet reflection and refraction of relative index `eta`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughGlass {
    /// Relative index across the boundary.
    pub eta: f64,
    /// Roughness (along local `x`, the surface's `dp/du`, when `alpha_v` differs).
    pub alpha: f64,
    /// Roughness along local `y` ([`super::anisotropic`]); `alpha` when isotropic.
    pub alpha_v: f64,
    /// Colour filter of both branches (1 for clear glass).
    pub tint: Rgb,
    /// GGX or Beckmann.
    pub distribution: Distribution,
}

impl RoughGlass {
    /// The distribution of its normals.
    #[inline]
    fn microfacet(&self) -> Microfacet {
        Microfacet::anisotropic(self.distribution, self.alpha, self.alpha_v)
    }
}

impl Scatter for RoughGlass {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        self.tint
    }

    fn scaled(self, s: Rgb) -> Lobe {
        RoughGlass { tint: self.tint * s, ..self }.into()
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.tint * f(self.microfacet(), self.eta, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        pdf(self.microfacet(), self.eta, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        sample(self.microfacet(), self.eta, wo, u_choice, u).map(Sampled::Smooth)
    }

    fn needs_tangent(&self) -> bool {
        self.alpha != self.alpha_v
    }

    /// A transmitted direction (below the surface) crossed the boundary.
    fn eta_towards(&self, wi: Vec3) -> f64 {
        if wi.z < 0.0 {
            self.eta
        } else {
            1.0
        }
    }
}

#[cfg(test)]
mod tests;
