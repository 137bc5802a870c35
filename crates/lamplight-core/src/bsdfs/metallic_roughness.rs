//! The glTF 2.0 metallic-roughness BRDF (specification, Appendix B), with the
//! dielectric's reflectance of `KHR_materials_ior` and `KHR_materials_specular`:
//!
//! ```text
//! material = mix(dielectric_brdf, metal_brdf, metallic)
//! metal_brdf      = specular_brdf(alpha) * (C + (1 - C) s)
//! dielectric_brdf = mix(diffuse_brdf(C), specular_brdf(alpha), F_d)
//! F_d = f0_d + (f90_d - f0_d) s
//! ```
//!
//! with Schlick's weight `s = (1 - |v.h|)^5`, `diffuse_brdf = C / pi` and
//! `specular_brdf` the GGX lobe `D G2 / (4 |n.l| |n.v|)` of `alpha =
//! roughness^2` ([`super::microfacet`]). Without the extensions `f0_d = 0.04`
//! (index 1.5) and `f90_d = 1`; [`Specular`] gives them from the index and the
//! specular factor and colour. Written out:
//!
//! `f = (1 - m)(1 - F_d) C / pi + ((1 - m) F_d + m (C + (1 - C) s)) D G2 / (4 cos_o cos_i)`,
//!
//! which for the defaults is `F0 + (1 - F0) s` with `F0 = (1 - m) 0.04 + m C`.
//! Sampling picks the GGX visible normals with probability `p_s = w_s / (w_s +
//! w_d)`, `w_s` the mean of the specular Fresnel at `cos_o`, `w_d = (1 - m)
//! mean(C (1 - f0_d))`, and the cosine hemisphere otherwise; the density is the
//! mixture of both.
//!
//! Energy: metals and rough surfaces reflect at most what they receive, and
//! lose some at high roughness (single scattering drops the light the
//! microsurface masks). A smooth dielectric reflects more than it receives at
//! grazing angles (1.025 at 60 degrees, 1.35 at 80 for a white base), because
//! the specification weighs the diffuse term by `1 - F(v.h)` per direction
//! rather than by one minus the specular albedo; the measured table is in
//! `bsdfs/tests.rs` (`metallic_roughness_stays_below_one_in_the_furnace`).

use super::{lambertian, microfacet, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// Schlick's factor `(1 - c)^5`.
#[inline]
fn schlick(c: f64) -> f64 {
    let m = (1.0 - c).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// The dielectric's Fresnel at normal and grazing incidence, `f0_d` and `f90_d`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Specular {
    /// `f0_d`, per channel.
    pub f0: Rgb,
    /// `f90_d`.
    pub f90: f64,
}

impl Specular {
    /// glTF's dielectric without extensions: index 1.5, `f0 = 0.04`, `f90 = 1`.
    pub const GLTF: Specular = Specular { f0: Rgb::splat(0.04), f90: 1.0 };

    /// `KHR_materials_specular` over `KHR_materials_ior`: `f0 = min(((ior - 1) /
    /// (ior + 1))^2 color, 1) factor`, `f90 = factor`.
    pub fn khr(ior: f64, factor: f64, color: Rgb) -> Specular {
        let r = (ior - 1.0) / (ior + 1.0);
        // Index 1.5 is exactly glTF's 0.04 (0.2^2 rounds to 0.04000000000000001).
        let f0_ior = if ior == 1.5 { 0.04 } else { r * r };
        let factor = factor.clamp(0.0, 1.0);
        Specular { f0: (f0_ior * color.max(Rgb::ZERO)).min(Rgb::ONE) * factor, f90: factor }
    }

    /// `F_d` at Schlick weight `s`.
    #[inline]
    fn fresnel(self, s: f64) -> Rgb {
        self.f0 + (Rgb::splat(self.f90) - self.f0) * s
    }
}

/// The specular lobe's Fresnel at Schlick weight `s`: `(1 - m) F_d + m (C + (1 - C) s)`.
#[inline]
fn specular_fresnel(base: Rgb, metallic: f64, spec: Specular, s: f64) -> Rgb {
    (1.0 - metallic) * spec.fresnel(s) + metallic * (base + (Rgb::ONE - base) * s)
}

/// The specular colour at normal incidence, `(1 - m) f0_d + m C`.
#[inline]
pub fn f0(base: Rgb, metallic: f64, spec: Specular) -> Rgb {
    specular_fresnel(base, metallic, spec, 0.0)
}

/// The lobe: base colour `C`, metallic `m`, the dielectric's Fresnel, GGX
/// `alpha` and `KHR_materials_transmission`'s transmission `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicRoughness {
    /// Base colour `C`.
    pub base: Rgb,
    /// Metallic, 0 to 1.
    pub metallic: f64,
    /// The dielectric's Fresnel (`KHR_materials_ior`, `KHR_materials_specular`).
    pub spec: Specular,
    /// GGX roughness (glTF's `roughness^2`).
    pub alpha: f64,
    /// Transmission `t`, 0 to 1: the share of the dielectric's diffuse base
    /// replaced by the thin-walled microfacet BTDF.
    pub transmission: f64,
}

/// `v` mirrored through the surface plane (`z -> -z`).
#[inline]
fn mirrored(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

impl MetallicRoughness {
    /// The lobe without transmission (the core specification's model).
    pub fn new(base: Rgb, metallic: f64, spec: Specular, alpha: f64) -> MetallicRoughness {
        MetallicRoughness { base, metallic, spec, alpha, transmission: 0.0 }
    }

    /// The BSDF for `wo` above the surface: the BRDF for `wi` above, the
    /// thin-walled BTDF `(1 - m) t C (1 - F_d) D G2 / (4 cos_o |cos_i|)`, at
    /// the half vector of `wo` and `wi` mirrored back above, for `wi` below.
    #[inline]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let MetallicRoughness { base, metallic, spec, alpha, transmission: t } = *self;
        if wo.z <= 0.0 || wi.z == 0.0 {
            return Rgb::ZERO;
        }
        if wi.z < 0.0 {
            if t <= 0.0 {
                return Rgb::ZERO;
            }
            let up = mirrored(wi);
            let s = schlick(wo.dot((wo + up).normalize()).abs());
            return microfacet::f(base * (Rgb::ONE - spec.fresnel(s)) * ((1.0 - metallic) * t), alpha, wo, up);
        }
        let h = (wo + wi).normalize();
        let s = schlick(wo.dot(h).abs());
        // `(1 - m)(1 - t)`: exactly `1 - m` without transmission.
        let diffuse = base * (Rgb::ONE - spec.fresnel(s)) * ((1.0 - metallic) * (1.0 - t) * std::f64::consts::FRAC_1_PI);
        diffuse + microfacet::f(specular_fresnel(base, metallic, spec, s), alpha, wo, wi)
    }

    /// The probability of sampling the specular reflection for `wo`; the rest
    /// goes to the diffuse lobe (`1 - t` of it) and the transmission (`t`).
    #[inline]
    fn specular_probability(&self, wo: Vec3) -> f64 {
        let MetallicRoughness { base, metallic, spec, .. } = *self;
        let w_s = specular_fresnel(base, metallic, spec, schlick(wo.z)).element_sum() / 3.0;
        let w_d = (1.0 - metallic) * (base * (Rgb::ONE - spec.f0)).element_sum() / 3.0;
        if w_d <= 0.0 {
            1.0
        } else if w_s <= 0.0 {
            0.0
        } else {
            (w_s / (w_s + w_d)).clamp(0.05, 0.95)
        }
    }

    /// Density of [`MetallicRoughness::sample`] in solid angle.
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        let p = self.specular_probability(wo);
        if wi.z < 0.0 {
            return if self.transmission > 0.0 && wo.z > 0.0 {
                (1.0 - p) * self.transmission * microfacet::pdf(self.alpha, wo, mirrored(wi))
            } else {
                0.0
            };
        }
        p * microfacet::pdf(self.alpha, wo, wi) + (1.0 - p) * (1.0 - self.transmission) * lambertian::pdf(wo, wi)
    }

    /// A direction: the specular lobe when `u_choice < p_s`; else the
    /// transmission with probability `t` (a GGX reflection mirrored below the
    /// surface: a thin wall bends no ray), and the diffuse lobe otherwise.
    pub fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Vec3> {
        if wo.z <= 0.0 {
            return None;
        }
        let p = self.specular_probability(wo);
        if u_choice < p {
            return microfacet::sample(self.alpha, wo, u);
        }
        let t = self.transmission;
        if t > 0.0 && (u_choice - p) < (1.0 - p) * t {
            return microfacet::sample(self.alpha, wo, u).map(mirrored);
        }
        Some(lambertian::sample(u))
    }

    /// Per-channel bound of the directional albedo: the diffuse weight (shared
    /// with the transmission) plus the specular Fresnel's largest value, `(1 -
    /// m) C (1 - min(f0_d, f90_d)) + (1 - m) max(f0_d, f90_d) + m`, capped at 1.
    pub fn bound(&self) -> Rgb {
        let MetallicRoughness { base, metallic, spec, .. } = *self;
        let lo = spec.f0.min(Rgb::splat(spec.f90));
        let hi = spec.f0.max(Rgb::splat(spec.f90));
        ((1.0 - metallic) * (base * (Rgb::ONE - lo) + hi) + Rgb::splat(metallic)).min(Rgb::ONE)
    }
}

// `MetallicRoughness::f` and the like name the inherent methods (which come before a trait's).
impl Scatter for MetallicRoughness {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        MetallicRoughness::bound(self)
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        MetallicRoughness::f(self, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        MetallicRoughness::pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        MetallicRoughness::sample(self, wo, u_choice, u).map(Sampled::Smooth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta_deg: f64, phi_deg: f64) -> Vec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    #[test]
    fn metal_and_dielectric_limits_match_the_formulas() {
        let (wo, wi) = (dir(30.0, 0.0), dir(50.0, 170.0));
        let alpha = 0.3;
        let base = Rgb::new(0.9, 0.6, 0.2);
        let h = (wo + wi).normalize();
        let s = (1.0 - wo.dot(h)).powi(5);
        // Metal: Schlick with f0 = C times the GGX lobe, no diffuse term.
        let lobe = |m: f64, spec: Specular| MetallicRoughness::new(base, m, spec, alpha);
        let metal = lobe(1.0, Specular::GLTF).f(wo, wi);
        let expected = microfacet::f(base + (Rgb::ONE - base) * s, alpha, wo, wi);
        assert!((metal - expected).length() < 1e-12, "{metal} vs {expected}");
        // Dielectric: Lambert weighted by 1 - F plus F times GGX, F0 = 0.04.
        let fd = 0.04 + 0.96 * s;
        let dielectric = lobe(0.0, Specular::GLTF).f(wo, wi);
        let expected = base * ((1.0 - fd) / std::f64::consts::PI) + microfacet::f(Rgb::splat(fd), alpha, wo, wi);
        assert!((dielectric - expected).length() < 1e-12, "{dielectric} vs {expected}");
        // Reciprocity.
        assert!((lobe(0.4, Specular::GLTF).f(wo, wi) - lobe(0.4, Specular::GLTF).f(wi, wo)).length() < 1e-12);
        // KHR_materials_specular: f0 = min(F0(ior) color, 1) factor, f90 = factor, and
        // F_d = f0 + (f90 - f0) s weighs the lobes (the extension's formulas).
        let spec = Specular::khr(2.0, 0.5, Rgb::new(1.0, 2.0, 20.0));
        let f0_ior = (1.0_f64 / 3.0).powi(2);
        assert_eq!(spec, Specular { f0: Rgb::new(f0_ior, 2.0 * f0_ior, 1.0) * 0.5, f90: 0.5 });
        let fd = spec.f0 + (Rgb::splat(0.5) - spec.f0) * s;
        let expected = base * (Rgb::ONE - fd) / std::f64::consts::PI + microfacet::f(fd, alpha, wo, wi);
        let got = lobe(0.0, spec).f(wo, wi);
        assert!((got - expected).length() < 1e-12, "{got} vs {expected}");
        assert!((lobe(0.4, spec).f(wo, wi) - lobe(0.4, spec).f(wi, wo)).length() < 1e-12);
        // Index 1.5, factor 1, white: the extension-free model.
        let plain = Specular::khr(1.5, 1.0, Rgb::ONE);
        assert_eq!(plain, Specular::GLTF);
        // Factor 0: a Lambert surface.
        let lambert = lobe(0.0, Specular::khr(1.5, 0.0, Rgb::ONE)).f(wo, wi);
        assert!((lambert - base / std::f64::consts::PI).length() < 1e-12);
    }

    /// Chi-square-lite: the density integrates to one over the hemisphere and
    /// matches the histogram of the samples in a coarse grid.
    #[test]
    fn sampling_density_matches_the_pdf() {
        for spec in [Specular::GLTF, Specular::khr(1.8, 0.7, Rgb::new(1.0, 0.5, 2.0))] {
            sampling_density_matches_the_pdf_for(spec);
        }
    }

    fn sampling_density_matches_the_pdf_for(spec: Specular) {
        let lobe = MetallicRoughness::new(Rgb::new(0.5, 0.4, 0.3), 0.3, spec, 0.4);
        let wo = dir(40.0, 20.0);
        let (nt, np) = (16, 32);
        let mut expected = vec![0.0; nt * np];
        let sub = 8;
        for i in 0..nt * sub {
            for j in 0..np * sub {
                let cos_t = 1.0 - (i as f64 + 0.5) / (nt * sub) as f64;
                let phi = (j as f64 + 0.5) / (np * sub) as f64 * std::f64::consts::TAU;
                let sin_t = (1.0 - cos_t * cos_t).sqrt();
                let wi = Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t);
                let cell_area = std::f64::consts::TAU / (nt * np * sub * sub) as f64;
                expected[(i / sub) * np + j / sub] += lobe.pdf(wo, wi) * cell_area;
            }
        }
        let total: f64 = expected.iter().sum();
        // Below 1: visible normals that reflect below the horizon return no sample.
        assert!(total > 0.9 && total < 1.01, "the density integrates to {total}");
        let n = 200_000;
        let mut counts = vec![0.0; nt * np];
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        for _ in 0..n {
            if let Some(wi) = lobe.sample(wo, rng.uniform(), (rng.uniform(), rng.uniform())) {
                let i = (((1.0 - wi.z) * nt as f64) as usize).min(nt - 1);
                let phi = wi.y.atan2(wi.x).rem_euclid(std::f64::consts::TAU);
                let j = ((phi / std::f64::consts::TAU * np as f64) as usize).min(np - 1);
                counts[i * np + j] += 1.0;
            }
        }
        let mut chi2 = 0.0;
        let mut cells = 0;
        for (c, e) in counts.iter().zip(&expected) {
            let e = e * n as f64;
            if e > 5.0 {
                chi2 += (c - e) * (c - e) / e;
                cells += 1;
            }
        }
        // For ~500 degrees of freedom the 99.9 % quantile is about 1.2 dof.
        assert!(chi2 < 1.25 * cells as f64, "chi2 {chi2} over {cells} cells");
    }
}
