//! Rough conductor (brushed or sandblasted metal): GGX microfacet reflection whose
//! facets are conductor mirrors, `f = F(wo.h) D(h) G2(wo, wi) / (4 cos(theta_o) cos(theta_i))`,
//! with `F` the conductor Fresnel reflectance of complex index `eta + i k` per channel
//! ([`fresnel_conductor`]) and `D`, `G2` and the visible-normal sampling of
//! [`super::microfacet`], or Beckmann's ([`super::distribution`]) (pbrt-v4's `ConductorBxDF`). Since `F <= 1` and `G2 <= G1`, no
//! direction reflects more than it receives; the single-scattering loss grows with
//! the roughness as for [`super::rough_dielectric`].

use super::distribution::Distribution;
use super::distribution::Microfacet;
use super::fresnel::fresnel_conductor;
use super::microfacet::Glossy;
use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// The BRDF value for `wo`, `wi` above the surface.
pub fn f(eta: Rgb, k: Rgb, m: Microfacet, wo: Vec3, wi: Vec3) -> Rgb {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Rgb::ZERO;
    }
    let Some(h) = (wo + wi).try_normalize() else { return Rgb::ZERO };
    fresnel_conductor(wo.dot(h), eta, k) * m.f(Rgb::ONE, wo, wi)
}

/// Rough metal: microfacet reflection with conductor Fresnel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughConductor {
    /// Real part of the index, per channel.
    pub eta: Rgb,
    /// Extinction coefficient, per channel.
    pub k: Rgb,
    /// Roughness (along local `x`, the surface's `dp/du`, when `alpha_v` differs).
    pub alpha: f64,
    /// Roughness along local `y` ([`super::anisotropic`]); `alpha` when isotropic.
    pub alpha_v: f64,
    /// GGX or Beckmann.
    pub distribution: Distribution,
}

impl RoughConductor {
    /// The distribution of its normals.
    #[inline]
    fn microfacet(&self) -> Microfacet {
        Microfacet::anisotropic(self.distribution, self.alpha, self.alpha_v)
    }
}

impl Scatter for RoughConductor {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        Rgb::ONE
    }

    /// Like the conductor mirror: physics when unscaled, else a
    /// constant-reflectance isotropic GGX lobe (of the geometric mean roughness
    /// when anisotropic: the lecture's Blinn lobe has one).
    fn scaled(self, s: Rgb) -> Lobe {
        if s != Rgb::ONE {
            let alpha = if self.alpha == self.alpha_v { self.alpha } else { (self.alpha * self.alpha_v).sqrt() };
            Glossy { ks: s, alpha }.into()
        } else {
            self.into()
        }
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        f(self.eta, self.k, self.microfacet(), wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        self.microfacet().pdf(wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        self.microfacet().sample(wo, u).map(Sampled::Smooth)
    }

    fn needs_tangent(&self) -> bool {
        self.alpha != self.alpha_v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdfs::microfacet;
    use crate::bsdfs::Metal;

    /// Albedo `E[f cos / pdf]` under visible-normal sampling.
    fn albedo(eta: Rgb, k: Rgb, alpha: f64, wo: Vec3) -> Rgb {
        let n = 200;
        let mut sum = Rgb::ZERO;
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                if let Some(wi) = microfacet::sample(alpha, wo, u) {
                    sum += f(eta, k, Microfacet::ggx(alpha), wo, wi) * wi.z / microfacet::pdf(alpha, wo, wi);
                }
            }
        }
        sum / (n * n) as f64
    }

    #[test]
    fn albedo_stays_below_fresnel_and_reaches_it_when_smooth() {
        let (eta, k) = Metal::Gold.eta_k();
        for theta in [0.0f64, 30.0, 60.0, 80.0] {
            let t = theta.to_radians();
            let wo = Vec3::new(t.sin(), 0.0, t.cos());
            let fr = fresnel_conductor(wo.z, eta, k);
            let smooth = albedo(eta, k, microfacet::MIN_ALPHA, wo);
            assert!((smooth - fr).abs().max_element() < 2e-3, "theta {theta}: {smooth} vs F {fr}");
            let mut previous = smooth;
            for alpha in [0.1, 0.4, 0.8] {
                let a = albedo(eta, k, alpha, wo);
                assert!(a.max_element() <= 1.0 && a.min_element() > 0.0, "theta {theta} alpha {alpha}: {a}");
                // Rougher loses more to the microsurface (a small tolerance for the quadrature).
                assert!(a.max_element() <= previous.max_element() + 2e-3, "theta {theta} alpha {alpha}: {a} above {previous}");
                previous = a;
            }
        }
    }
}
