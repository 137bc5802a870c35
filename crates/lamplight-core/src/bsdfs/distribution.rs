//! The microfacet distribution of a rough lobe: GGX ([`super::microfacet`]) or
//! Beckmann, of roughness `alpha` (or `alpha_u`, `alpha_v` along the two tangents:
//! [`super::anisotropic`]), with the sampling of its normals.
//!
//! Beckmann (Walter et al. 2007, Mitsuba's `beckmann`):
//! `D(h) = exp(-tan^2(theta_h) / a^2) / (pi a^2 cos^4(theta_h))`, and Smith's
//! `Lambda(v)` through Walter's rational fit in `b = 1 / (a tan(theta_v))`:
//! `Lambda = (1 - 1.259 b + 0.396 b^2) / (3.535 b + 2.181 b^2)` for `b < 1.6`, else 0
//! (so `G1 = 1 / (1 + Lambda) = (3.535 b + 2.181 b^2) / (1 + 2.276 b + 2.577 b^2)`,
//! Mitsuba's form, within 0.35 % of the exact erf expression).
//!
//! GGX normals are drawn from the visible normals (density
//! `G1(wo) max(0, wo.h) D(h) / cos(theta_o)`); Beckmann normals from `D(h) cos(theta_h)`
//! itself (`tan^2(theta_h) = -a^2 ln(1 - u_1)`, `phi = 2 pi u_2`), whose density is
//! exact and needs no `erf` inversion. A reflection through `h` has the density
//! `p(h) / (4 wo.h)` either way.

use std::f64::consts::PI;

use super::{anisotropic, microfacet};
use crate::math::{Rgb, Vec3};

/// Which normal distribution a rough surface has.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Distribution {
    /// Trowbridge-Reitz (GGX), lamplight's default.
    #[default]
    Ggx,
    /// Beckmann (Gaussian slopes), Mitsuba's default.
    Beckmann,
}

impl Distribution {
    /// The distribution called `name` (`"ggx"` or `"beckmann"`).
    pub fn from_name(name: &str) -> Option<Distribution> {
        match name {
            "ggx" => Some(Distribution::Ggx),
            "beckmann" => Some(Distribution::Beckmann),
            _ => None,
        }
    }
}

/// A distribution of a given roughness: `alpha_u` along the shading frame's
/// first tangent (local `x`), `alpha_v` along the second (local `y`); equal for
/// an isotropic surface, which then takes the isotropic forms above (the
/// anisotropic ones, [`super::anisotropic`], are only for `alpha_u != alpha_v`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// GGX or Beckmann.
    pub distribution: Distribution,
    /// Roughness `a_u` along local `x`.
    pub alpha_u: f64,
    /// Roughness `a_v` along local `y`.
    pub alpha_v: f64,
}

impl Microfacet {
    /// GGX of roughness `alpha`.
    pub fn ggx(alpha: f64) -> Microfacet {
        Microfacet::new(Distribution::Ggx, alpha)
    }

    /// `distribution` of roughness `alpha`.
    pub fn new(distribution: Distribution, alpha: f64) -> Microfacet {
        Microfacet { distribution, alpha_u: alpha, alpha_v: alpha }
    }

    /// `distribution` of roughness `alpha_u` along local `x` and `alpha_v` along `y`.
    pub fn anisotropic(distribution: Distribution, alpha_u: f64, alpha_v: f64) -> Microfacet {
        Microfacet { distribution, alpha_u, alpha_v }
    }

    /// True when the roughness is the same in every direction.
    #[inline]
    pub fn is_isotropic(&self) -> bool {
        self.alpha_u == self.alpha_v
    }

    /// `D(h)` for a unit half vector in the local frame (0 below the surface).
    #[inline]
    pub fn d(&self, h: Vec3) -> f64 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx if au == av => microfacet::d(au, h),
            Distribution::Ggx => anisotropic::ggx_d(au, av, h),
            Distribution::Beckmann if au == av => {
                if h.z <= 0.0 {
                    return 0.0;
                }
                let c2 = h.z * h.z;
                let a2 = au * au;
                let tan2 = ((1.0 - c2) / c2).max(0.0);
                (-tan2 / a2).exp() / (PI * a2 * c2 * c2)
            }
            Distribution::Beckmann => anisotropic::beckmann_d(au, av, h),
        }
    }

    /// Smith's `Lambda(v)`, even in `v.z`.
    #[inline]
    pub fn lambda(&self, v: Vec3) -> f64 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx if au == av => microfacet::lambda(au, v),
            Distribution::Ggx => anisotropic::ggx_lambda(au, av, v),
            Distribution::Beckmann if au == av => {
                let c2 = v.z * v.z;
                if c2 <= 0.0 {
                    return f64::INFINITY;
                }
                let tan = ((1.0 - c2) / c2).max(0.0).sqrt();
                if tan == 0.0 {
                    return 0.0;
                }
                let b = 1.0 / (au * tan);
                if b >= 1.6 {
                    return 0.0;
                }
                (1.0 - 1.259 * b + 0.396 * b * b) / (3.535 * b + 2.181 * b * b)
            }
            Distribution::Beckmann => anisotropic::beckmann_lambda(au, av, v),
        }
    }

    /// Masking `G1(v) = 1 / (1 + Lambda(v))`.
    #[inline]
    pub fn g1(&self, v: Vec3) -> f64 {
        1.0 / (1.0 + self.lambda(v))
    }

    /// Height-correlated masking-shadowing `G2 = 1 / (1 + Lambda(wo) + Lambda(wi))`.
    #[inline]
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f64 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// True for isotropic GGX, whose value, density and sampling are
    /// [`super::microfacet`]'s own functions.
    #[inline]
    fn is_isotropic_ggx(&self) -> bool {
        self.distribution == Distribution::Ggx && self.alpha_u == self.alpha_v
    }

    /// A microfacet normal for outgoing `wo` (`wo.z > 0`), density [`Microfacet::normal_pdf`].
    #[inline]
    pub fn sample_normal(&self, wo: Vec3, u: (f64, f64)) -> Vec3 {
        let (au, av) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx => microfacet::visible_normal_stretched(au, av, wo, u),
            Distribution::Beckmann if au == av => {
                let tan2 = -au * au * (1.0 - u.0).ln();
                let cos = 1.0 / (1.0 + tan2).sqrt();
                let sin = (1.0 - cos * cos).max(0.0).sqrt();
                let phi = 2.0 * PI * u.1;
                Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
            }
            Distribution::Beckmann => anisotropic::beckmann_normal(au, av, u),
        }
    }

    /// Solid-angle density of [`Microfacet::sample_normal`] at `h`.
    #[inline]
    pub fn normal_pdf(&self, wo: Vec3, h: Vec3) -> f64 {
        match self.distribution {
            // The form rough glass has always used: its images stay the same.
            Distribution::Ggx if self.is_isotropic() => {
                let alpha = self.alpha_u;
                microfacet::g1(alpha, wo) * wo.dot(h).max(0.0) * microfacet::d(alpha, h) / wo.z
            }
            Distribution::Ggx => self.g1(wo) * wo.dot(h).max(0.0) * self.d(h) / wo.z,
            Distribution::Beckmann => self.d(h) * h.z.max(0.0),
        }
    }

    /// Reflection of constant reflectance `ks`: `ks D(h) G2 / (4 cos_o cos_i)`.
    #[inline]
    pub fn f(&self, ks: Rgb, wo: Vec3, wi: Vec3) -> Rgb {
        if self.is_isotropic_ggx() {
            return microfacet::f(ks, self.alpha_u, wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let h = (wo + wi).normalize();
        ks * (self.d(h) * self.g2(wo, wi) / (4.0 * wo.z * wi.z))
    }

    /// Density of [`Microfacet::sample`]: `p(h) / (4 wo.h)`.
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        if self.is_isotropic_ggx() {
            return microfacet::pdf(self.alpha_u, wo, wi);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize();
        let wo_h = wo.dot(h);
        if wo_h <= 0.0 {
            return 0.0;
        }
        self.normal_pdf(wo, h) / (4.0 * wo_h)
    }

    /// A reflected direction through a sampled normal; `None` below the surface.
    pub fn sample(&self, wo: Vec3, u: (f64, f64)) -> Option<Vec3> {
        if self.is_isotropic_ggx() {
            return microfacet::sample(self.alpha_u, wo, u);
        }
        if wo.z <= 0.0 {
            return None;
        }
        let h = self.sample_normal(wo, u);
        let wo_h = wo.dot(h);
        if wo_h <= 0.0 {
            return None;
        }
        let wi = h * (2.0 * wo_h) - wo;
        (wi.z > 0.0).then_some(wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdfs::test_support::{hemisphere_quadrature, projected_area, stratified_mean};

    fn beckmann(alpha: f64) -> Microfacet {
        Microfacet::new(Distribution::Beckmann, alpha)
    }

    #[test]
    fn beckmann_is_normalized_over_projected_area() {
        for alpha in [0.05, 0.2, 0.5, 1.0] {
            let sum = projected_area(400_000, |h| beckmann(alpha).d(h));
            assert!((sum - 1.0).abs() < 2e-3, "alpha {alpha}: {sum}");
        }
    }

    #[test]
    fn beckmann_masking_matches_the_exact_erf_form() {
        // Exact Lambda = (erf(b) - 1) / 2 + exp(-b^2) / (2 b sqrt(pi)); the fit is within 0.35 % in G1.
        fn erf(x: f64) -> f64 {
            // Abramowitz and Stegun 7.1.26 is too coarse here: integrate exp(-t^2) instead.
            let n = 20_000;
            let h = x / n as f64;
            (0..n).map(|i| (-((i as f64 + 0.5) * h).powi(2)).exp() * h).sum::<f64>() * 2.0 / PI.sqrt()
        }
        for alpha in [0.1, 0.3, 0.7] {
            for theta in [10.0f64, 40.0, 70.0, 85.0] {
                let t = theta.to_radians();
                let v = Vec3::new(t.sin(), 0.0, t.cos());
                let b = 1.0 / (alpha * t.tan());
                let exact = 1.0 / (1.0 + (erf(b) - 1.0) / 2.0 + (-b * b).exp() / (2.0 * b * PI.sqrt()));
                let fit = beckmann(alpha).g1(v);
                assert!((fit - exact).abs() / exact < 4e-3, "alpha {alpha} theta {theta}: {fit} vs {exact}");
            }
        }
    }

    #[test]
    fn beckmann_samples_follow_their_density() {
        // E[g(h) / p(h)] = integral of g: with g = D(h) cos(h) the integral is 1, and
        // the sampled reflections' E[f cos / pdf] is the albedo computed by quadrature.
        for alpha in [0.1, 0.4, 0.9] {
            let m = beckmann(alpha);
            let wo = Vec3::new(0.5, 0.0, 0.75f64.sqrt());
            let albedo = stratified_mean(300, |u| {
                let h = m.sample_normal(wo, u);
                assert!((h.length() - 1.0).abs() < 1e-12 && h.z > 0.0);
                m.sample(wo, u).map_or(0.0, |wi| m.f(Rgb::ONE, wo, wi).x * wi.z / m.pdf(wo, wi))
            });
            let quadrature = hemisphere_quadrature(|wi| m.f(Rgb::ONE, wo, wi).x);
            assert!((albedo - quadrature).abs() < 0.01, "alpha {alpha}: sampled {albedo}, quadrature {quadrature}");
            assert!(albedo <= 1.0 + 1e-3, "alpha {alpha}: {albedo}");
        }
    }

    #[test]
    fn ggx_delegates_to_the_ggx_module() {
        let m = Microfacet::ggx(0.3);
        let (wo, wi) = (Vec3::new(0.3, 0.1, 0.9).normalize(), Vec3::new(-0.5, 0.2, 0.7).normalize());
        assert_eq!(m.f(Rgb::ONE, wo, wi), microfacet::f(Rgb::ONE, 0.3, wo, wi));
        assert_eq!(m.pdf(wo, wi), microfacet::pdf(0.3, wo, wi));
    }
}
