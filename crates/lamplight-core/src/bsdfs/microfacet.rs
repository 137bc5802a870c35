//! GGX (Trowbridge-Reitz) microfacet reflection with a constant reflectance: the
//! physical form of the lecture's Blinn highlight `ks (N.H)^shine`.
//!
//! `f = ks D(h) G2(wo, wi) / (4 cos(theta_o) cos(theta_i))` with
//! `D(h) = a^2 / (pi ((a^2 - 1) cos^2(theta_h) + 1)^2)`, the height-correlated
//! Smith masking-shadowing `G2 = 1 / (1 + Lambda(wo) + Lambda(wi))`,
//! `Lambda(v) = (sqrt(1 + a^2 tan^2(theta_v)) - 1) / 2` (Heitz 2014). Directions are
//! sampled from the visible normals (Heitz 2018), `pdf = G1(wo) D(h) / (4 cos(theta_o))`.
//! The lobe never reflects more than `ks`: `G2 <= 1` removes the light the
//! microsurface masks (a little energy is lost at high roughness).
//!
//! The Blinn exponent maps to the roughness `a = sqrt(2 / (shine + 2))`, the
//! Beckmann/Phong correspondence of Walter et al. 2007, which GGX shares near the peak.

use std::f64::consts::PI;

use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// Smallest roughness: narrower lobes would be a mirror that f64 cannot sample.
pub const MIN_ALPHA: f64 = 1e-3;

/// GGX roughness `a` for a Blinn exponent.
pub fn alpha_from_shininess(shininess: f64) -> f64 {
    (2.0 / (shininess.max(0.0) + 2.0)).sqrt().max(MIN_ALPHA)
}

/// The normal distribution `D(h)` for a unit half vector in the local frame.
#[inline]
pub fn d(alpha: f64, h: Vec3) -> f64 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let c2 = h.z * h.z;
    let denom = (a2 - 1.0) * c2 + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's `Lambda(v)` (even in `v.z`: the same on both sides of the surface).
#[inline]
pub fn lambda(alpha: f64, v: Vec3) -> f64 {
    let c2 = v.z * v.z;
    if c2 <= 0.0 {
        return f64::INFINITY;
    }
    let tan2 = ((1.0 - c2) / c2).max(0.0);
    0.5 * ((1.0 + alpha * alpha * tan2).sqrt() - 1.0)
}

/// Masking `G1(v) = 1 / (1 + Lambda(v))`.
#[inline]
pub fn g1(alpha: f64, v: Vec3) -> f64 {
    1.0 / (1.0 + lambda(alpha, v))
}

/// The BRDF value for `wo`, `wi` above the surface.
#[inline]
pub fn f(ks: Rgb, alpha: f64, wo: Vec3, wi: Vec3) -> Rgb {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Rgb::ZERO;
    }
    let h = (wo + wi).normalize();
    let g2 = 1.0 / (1.0 + lambda(alpha, wo) + lambda(alpha, wi));
    ks * (d(alpha, h) * g2 / (4.0 * wo.z * wi.z))
}

/// Density of [`sample`] in solid angle.
#[inline]
pub fn pdf(alpha: f64, wo: Vec3, wi: Vec3) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let h = (wo + wi).normalize();
    g1(alpha, wo) * d(alpha, h) / (4.0 * wo.z)
}

/// A reflected direction: a visible normal `h` ([`visible_normal`]), then
/// `wi = reflect(wo, h)`; `None` when it falls below the surface.
pub fn sample(alpha: f64, wo: Vec3, u: (f64, f64)) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    let h = visible_normal(alpha, wo, u);
    let wi = h * (2.0 * wo.dot(h)) - wo;
    (wi.z > 0.0).then_some(wi)
}

/// A microfacet normal distributed as the normals visible from `wo` (`wo.z > 0`),
/// density `D_wo(h) = G1(wo) max(0, wo.h) D(h) / cos(theta_o)` (Heitz 2018,
/// "Sampling the GGX Distribution of Visible Normals").
#[inline]
pub fn visible_normal(alpha: f64, wo: Vec3, u: (f64, f64)) -> Vec3 {
    visible_normal_stretched(alpha, alpha, wo, u)
}

/// [`visible_normal`] of anisotropic GGX, roughness `alpha_u` along local `x`
/// and `alpha_v` along `y` ([`super::anisotropic`]): Heitz's algorithm is a
/// stretch of `wo` to unit roughness and back, so one routine serves both.
#[inline]
pub fn visible_normal_stretched(alpha_u: f64, alpha_v: f64, wo: Vec3, u: (f64, f64)) -> Vec3 {
    // Stretch to the unit-roughness configuration.
    let vh = Vec3::new(alpha_u * wo.x, alpha_v * wo.y, wo.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
    let t2 = vh.cross(t1);
    let r = u.0.sqrt();
    let phi = 2.0 * PI * u.1;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    Vec3::new(alpha_u * nh.x, alpha_v * nh.y, nh.z.max(1e-9)).normalize()
}

/// GGX reflection with constant reflectance `ks` and roughness `alpha` (the
/// lecture's Blinn highlight read as a microfacet lobe).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glossy {
    /// Reflectance.
    pub ks: Rgb,
    /// GGX roughness.
    pub alpha: f64,
}

impl Scatter for Glossy {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        self.ks
    }

    fn scaled(self, s: Rgb) -> Lobe {
        Glossy { ks: self.ks * s, alpha: self.alpha }.into()
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        f(self.ks, self.alpha, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        pdf(self.alpha, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        sample(self.alpha, wo, u).map(Sampled::Smooth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdfs::test_support::{hemisphere_quadrature, projected_area, stratified_mean};

    #[test]
    fn distribution_is_normalized_over_projected_area() {
        // Integral of D(h) cos(theta_h) over the hemisphere is 1, for every roughness.
        for alpha in [0.05, 0.2, 0.5, 1.0] {
            let sum = projected_area(200_000, |h| d(alpha, h));
            assert!((sum - 1.0).abs() < 2e-3, "alpha {alpha}: {sum}");
        }
    }

    #[test]
    fn sampled_albedo_matches_quadrature_and_stays_below_one() {
        // E[f cos / pdf] over samples and the quadrature of f cos over the hemisphere
        // are both the directional albedo: they agree when the pdf is the samples' density.
        for alpha in [0.1, 0.4, 0.9] {
            let wo = Vec3::new(0.5, 0.0, 0.75f64.sqrt());
            let albedo = stratified_mean(200, |u| {
                sample(alpha, wo, u).map_or(0.0, |wi| {
                    let p = pdf(alpha, wo, wi);
                    assert!(p > 0.0);
                    f(Rgb::ONE, alpha, wo, wi).x * wi.z / p
                })
            });
            let quadrature = hemisphere_quadrature(|wi| f(Rgb::ONE, alpha, wo, wi).x);
            assert!((albedo - quadrature).abs() < 0.01, "alpha {alpha}: sampled {albedo}, quadrature {quadrature}");
            assert!(albedo <= 1.0, "alpha {alpha}: albedo {albedo}");
        }
    }
}
