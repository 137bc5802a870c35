//! Fresnel reflectance of smooth dielectrics and conductors, unpolarized light.
//!
//! It lives with the lobes because every smooth and microfacet lobe is built on
//! it; the materials and the Whitted integrator, which sit above the lobes, read
//! it from here.

use crate::math::Rgb;

/// Fresnel reflectance at a smooth boundary between dielectrics, unpolarized:
/// with `c = cos(theta_i)` and `eta = n_t / n_i` (index on the far side over index on
/// the ray's side), `g^2 = eta^2 + c^2 - 1`;
/// `F = 1/2 (g - c)^2 / (g + c)^2 * (1 + (c (g + c) - 1)^2 / (c (g - c) + 1)^2)`
/// (Cook and Torrance 1982, eq. in their appendix), and `F = 1` when `g^2 <= 0`
/// (total internal reflection). Equal to the mean of the s- and p-polarized
/// reflectances of the Fresnel equations.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let c = cos_i.clamp(0.0, 1.0);
    let g2 = eta * eta + c * c - 1.0;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    (0.5 * a * a * (1.0 + b * b)).clamp(0.0, 1.0)
}

/// Fresnel reflectance of a conductor with complex index `eta + i k` (relative to
/// the outside medium) at incidence cosine `cos_i`, unpolarized, one channel.
///
/// With `s2 = sin^2`, `t0 = eta^2 - k^2 - s2`, `a2b2 = sqrt(t0^2 + 4 eta^2 k^2)`,
/// `a = sqrt((a2b2 + t0) / 2)`:
/// `Rs = (a2b2 + c^2 - 2 a c) / (a2b2 + c^2 + 2 a c)`,
/// `Rp = Rs (a2b2 c^2 + s2^2 - 2 a c s2) / (a2b2 c^2 + s2^2 + 2 a c s2)`,
/// `F = (Rs + Rp) / 2` (the exact form as in pbrt-v3, `FrConductor`).
pub fn fresnel_conductor_channel(cos_i: f64, eta: f64, k: f64) -> f64 {
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t1 = a2b2 + c2;
    let t2 = 2.0 * c * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = a2b2 * c2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    let f = 0.5 * (rs + rp);
    if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// [`fresnel_conductor_channel`] for each RGB channel.
pub fn fresnel_conductor(cos_i: f64, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        fresnel_conductor_channel(cos_i, eta.x, k.x),
        fresnel_conductor_channel(cos_i, eta.y, k.y),
        fresnel_conductor_channel(cos_i, eta.z, k.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glass_at_normal_and_grazing_incidence() {
        // ((n - 1) / (n + 1))^2 = 0.04 for n = 1.5.
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-12);
        assert!((fresnel_dielectric(0.0, 1.5) - 1.0).abs() < 1e-12);
        // Brewster's angle: Rp = 0, so F = Rs / 2; at 56.31 deg for n = 1.5, Rs = 0.1479.
        let brewster = 1.5f64.atan();
        assert!((fresnel_dielectric(brewster.cos(), 1.5) - 0.147929 / 2.0).abs() < 1e-5);
        // 45 degrees, n = 1.5: Rs = 0.092013, Rp = 0.008466 (textbook table).
        let f45 = fresnel_dielectric(std::f64::consts::FRAC_1_SQRT_2, 1.5);
        assert!((f45 - (0.092013 + 0.008466) / 2.0).abs() < 1e-5, "{f45}");
    }

    #[test]
    fn total_internal_reflection_beyond_critical_angle() {
        let critical = (1.0f64 / 1.5).asin(); // 41.81 degrees inside glass
        assert_eq!(fresnel_dielectric((critical + 0.01).cos(), 1.0 / 1.5), 1.0);
        assert!(fresnel_dielectric((critical - 0.01).cos(), 1.0 / 1.5) < 1.0);
        // Inside at normal incidence the reflectance is the same 4 %.
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-12);
    }

    #[test]
    fn gold_at_normal_and_grazing_incidence() {
        // Normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
        let (n, k) = (0.18299, 3.4242);
        let expected = ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
        assert!((fresnel_conductor_channel(1.0, n, k) - expected).abs() < 1e-12);
        assert!(expected > 0.9, "gold reflects most red light at normal incidence");
        assert!((fresnel_conductor_channel(0.0, n, k) - 1.0).abs() < 1e-9);
        // A conductor with k = 0 is a dielectric.
        for c in [0.1, 0.5, 0.9] {
            assert!((fresnel_conductor_channel(c, 1.5, 0.0) - fresnel_dielectric(c, 1.5)).abs() < 1e-9);
        }
    }
}
