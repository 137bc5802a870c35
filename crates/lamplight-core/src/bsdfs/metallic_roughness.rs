//! The glTF 2.0 metallic-roughness BRDF (specification, Appendix B):
//!
//! ```text
//! material = mix(dielectric_brdf, metal_brdf, metallic)
//! metal_brdf      = conductor_fresnel(f0 = C, specular_brdf(alpha))
//! dielectric_brdf = fresnel_mix(ior = 1.5, diffuse_brdf(C), specular_brdf(alpha))
//! ```
//!
//! with Schlick's Fresnel `F(f0) = f0 + (1 - f0)(1 - |v.h|)^5`, `f0 = 0.04` for
//! the dielectric (index 1.5), `diffuse_brdf = C / pi` and `specular_brdf` the
//! GGX lobe `D G2 / (4 |n.l| |n.v|)` of `alpha = roughness^2`
//! ([`super::microfacet`]). Written out, with `s = (1 - |v.h|)^5`:
//!
//! `f = (1 - m)(1 - (0.04 + 0.96 s)) C / pi + (F0 + (1 - F0) s) D G2 / (4 cos_o cos_i)`,
//! `F0 = (1 - m) 0.04 + m C`,
//!
//! since `(1 - m) F(0.04) + m F(C) = F(F0)`. Sampling picks the GGX visible
//! normals with probability `p_s = w_s / (w_s + w_d)`, `w_s = mean(F0)` lifted
//! towards 1 at grazing angles by `s(cos_o)`, `w_d = (1 - m) 0.96 mean(C)`, and
//! the cosine hemisphere otherwise; the density is the mixture of both.
//!
//! Energy: metals and rough surfaces reflect at most what they receive, and
//! lose some at high roughness (single scattering drops the light the
//! microsurface masks). A smooth dielectric reflects more than it receives at
//! grazing angles (1.025 at 60 degrees, 1.35 at 80 for a white base), because
//! the specification weighs the diffuse term by `1 - F(v.h)` per direction
//! rather than by one minus the specular albedo; the measured table is in
//! `bsdfs/tests.rs` (`metallic_roughness_stays_below_one_in_the_furnace`).

use super::{lambertian, microfacet};
use crate::math::{Rgb, Vec3};

/// Schlick's factor `(1 - c)^5`.
#[inline]
fn schlick(c: f64) -> f64 {
    let m = (1.0 - c).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// `F0 = mix(0.04, C, metallic)`.
#[inline]
pub fn f0(base: Rgb, metallic: f64) -> Rgb {
    Rgb::splat(0.04 * (1.0 - metallic)) + base * metallic
}

/// The BRDF for `wo`, `wi` above the surface.
#[inline]
pub fn f(base: Rgb, metallic: f64, alpha: f64, wo: Vec3, wi: Vec3) -> Rgb {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Rgb::ZERO;
    }
    let h = (wo + wi).normalize();
    let s = schlick(wo.dot(h).abs());
    let f0 = f0(base, metallic);
    let fresnel = f0 + (Rgb::ONE - f0) * s;
    let diffuse = base * ((1.0 - metallic) * (1.0 - (0.04 + 0.96 * s)) * std::f64::consts::FRAC_1_PI);
    diffuse + microfacet::f(fresnel, alpha, wo, wi)
}

/// The probability of sampling the specular lobe for `wo`.
#[inline]
fn specular_probability(base: Rgb, metallic: f64, wo: Vec3) -> f64 {
    let f0 = f0(base, metallic);
    let w_s = {
        let s = schlick(wo.z);
        (f0 + (Rgb::ONE - f0) * s).element_sum() / 3.0
    };
    let w_d = (1.0 - metallic) * 0.96 * base.element_sum() / 3.0;
    if w_d <= 0.0 {
        1.0
    } else {
        (w_s / (w_s + w_d)).clamp(0.05, 0.95)
    }
}

/// Density of [`sample`] in solid angle.
#[inline]
pub fn pdf(base: Rgb, metallic: f64, alpha: f64, wo: Vec3, wi: Vec3) -> f64 {
    let p = specular_probability(base, metallic, wo);
    p * microfacet::pdf(alpha, wo, wi) + (1.0 - p) * lambertian::pdf(wo, wi)
}

/// A direction: the specular lobe when `u_choice < p_s`, else the diffuse one.
pub fn sample(base: Rgb, metallic: f64, alpha: f64, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Vec3> {
    if wo.z <= 0.0 {
        return None;
    }
    if u_choice < specular_probability(base, metallic, wo) {
        microfacet::sample(alpha, wo, u)
    } else {
        Some(lambertian::sample(u))
    }
}

/// Per-channel bound of the directional albedo: the diffuse weight plus the
/// Fresnel's largest value, `(1 - m) 0.96 C + F0 + (1 - F0)`, capped at 1.
pub fn bound(base: Rgb, metallic: f64) -> Rgb {
    ((1.0 - metallic) * 0.96 * base + f0(base, metallic)).min(Rgb::ONE)
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
        let metal = f(base, 1.0, alpha, wo, wi);
        let expected = microfacet::f(base + (Rgb::ONE - base) * s, alpha, wo, wi);
        assert!((metal - expected).length() < 1e-12, "{metal} vs {expected}");
        // Dielectric: Lambert weighted by 1 - F plus F times GGX, F0 = 0.04.
        let fd = 0.04 + 0.96 * s;
        let dielectric = f(base, 0.0, alpha, wo, wi);
        let expected = base * ((1.0 - fd) / std::f64::consts::PI) + microfacet::f(Rgb::splat(fd), alpha, wo, wi);
        assert!((dielectric - expected).length() < 1e-12, "{dielectric} vs {expected}");
        // Reciprocity.
        assert!((f(base, 0.4, alpha, wo, wi) - f(base, 0.4, alpha, wi, wo)).length() < 1e-12);
    }

    /// Chi-square-lite: the density integrates to one over the hemisphere and
    /// matches the histogram of the samples in a coarse grid.
    #[test]
    fn sampling_density_matches_the_pdf() {
        let (base, metallic, alpha) = (Rgb::new(0.5, 0.4, 0.3), 0.3, 0.4);
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
                expected[(i / sub) * np + j / sub] += pdf(base, metallic, alpha, wo, wi) * cell_area;
            }
        }
        let total: f64 = expected.iter().sum();
        // Below 1: visible normals that reflect below the horizon return no sample.
        assert!(total > 0.9 && total < 1.01, "the density integrates to {total}");
        let n = 200_000;
        let mut counts = vec![0.0; nt * np];
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        for _ in 0..n {
            if let Some(wi) = sample(base, metallic, alpha, wo, rng.uniform(), (rng.uniform(), rng.uniform())) {
                let i = (((1.0 - wi.z) * nt as f64) as usize).min(nt - 1);
                let phi = super::super::super::shapes::surface::azimuth(wi.x, wi.y);
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
