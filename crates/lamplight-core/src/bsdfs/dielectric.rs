//! Smooth dielectric boundary (glass): Fresnel reflection and refraction.
//!
//! With `eta = n_t / n_i` across the boundary and `F` the dielectric Fresnel
//! reflectance ([`fresnel_dielectric`]), the boundary reflects the mirror
//! direction with weight `F` and transmits the Snell direction with weight
//! `(1 - F) / eta^2` (radiance is compressed into the narrower cone of the denser
//! side). Sampling picks reflection with probability `F`, so each sample's weight
//! is 1 for reflection and `1 / eta^2` for refraction: no light is made or lost
//! at the boundary, which the white furnace test checks.

use super::fresnel::fresnel_dielectric;
use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// One sampled direction of a smooth boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeltaSample {
    /// Direction of the incident light, local frame.
    pub wi: Vec3,
    /// `f cos / pdf` for the branch taken, including the branch's probability.
    pub weight: f64,
    /// True for the refracted branch.
    pub transmitted: bool,
}

/// The mirror direction of `wo` in the local frame.
#[inline]
pub fn reflect_local(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

/// The refracted direction of `wo` (local, `wo.z > 0`) into a medium of relative
/// index `eta = n_t / n_i`, or `None` on total internal reflection.
#[inline]
pub fn refract_local(wo: Vec3, eta: f64) -> Option<Vec3> {
    let cos_i = wo.z;
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-wo / eta + Vec3::new(0.0, 0.0, cos_i / eta - cos_t)).normalize())
}

/// Samples the boundary with one uniform number `u`: reflection when `u < F`.
pub fn sample(wo: Vec3, eta: f64, u: f64) -> DeltaSample {
    let fr = fresnel_dielectric(wo.z, eta);
    if u < fr {
        return DeltaSample { wi: reflect_local(wo), weight: 1.0, transmitted: false };
    }
    match refract_local(wo, eta) {
        Some(wi) => DeltaSample { wi, weight: 1.0 / (eta * eta), transmitted: true },
        // F = 1 under total internal reflection, so u < F above; kept for rounding.
        None => DeltaSample { wi: reflect_local(wo), weight: 1.0, transmitted: false },
    }
}

/// Smooth glass (delta): Fresnel reflection and refraction of relative index
/// `eta = n_t / n_i`, both branches filtered by `tint` (1 for clear glass).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glass {
    /// Relative index across the boundary.
    pub eta: f64,
    /// Colour filter of both branches.
    pub tint: Rgb,
}

impl Scatter for Glass {
    const DELTA: bool = true;

    fn bound(&self) -> Rgb {
        self.tint
    }

    fn scaled(self, s: Rgb) -> Lobe {
        Glass { eta: self.eta, tint: self.tint * s }.into()
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, _u: (f64, f64)) -> Option<Sampled> {
        let s = sample(wo, self.eta, u_choice);
        Some(Sampled::Delta { wi: s.wi, weight: self.tint * s.weight, eta: if s.transmitted { self.eta } else { 1.0 } })
    }
}

/// Smooth refraction only (delta), of relative index `eta`, with a constant
/// weight or, for `None`, the Fresnel weight `1 - F`: the lecture's refraction
/// beside its separate mirror term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refract {
    /// Relative index across the boundary.
    pub eta: f64,
    /// Constant weight, or `None` for the Fresnel weight `1 - F`.
    pub weight: Option<Rgb>,
}

impl Scatter for Refract {
    const DELTA: bool = true;

    fn bound(&self) -> Rgb {
        self.weight.unwrap_or(Rgb::ONE)
    }

    fn scaled(self, s: Rgb) -> Lobe {
        Refract { eta: self.eta, weight: Some(self.weight.unwrap_or(Rgb::ONE) * s) }.into()
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_choice: f64, _u: (f64, f64)) -> Option<Sampled> {
        let eta = self.eta;
        let wi = refract_local(wo, eta)?;
        let w = self.weight.unwrap_or_else(|| Rgb::splat(1.0 - fresnel_dielectric(wo.z, eta)));
        Some(Sampled::Delta { wi, weight: w / (eta * eta), eta })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refraction_obeys_snell_and_total_internal_reflection() {
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let wi = refract_local(wo, 1.5).unwrap();
        assert!((wi.length() - 1.0).abs() < 1e-12 && wi.z < 0.0);
        // sin(theta_t) = sin(theta_i) / eta, on the opposite side of the normal.
        assert!((wi.x + 0.6 / 1.5).abs() < 1e-12);
        let steep = Vec3::new(0.8, 0.0, 0.6);
        assert!(refract_local(steep, 1.0 / 1.5).is_none(), "sin 0.8 > 1/1.5: total internal reflection");
        let s = sample(steep, 1.0 / 1.5, 0.999);
        assert!(!s.transmitted && s.weight == 1.0);
    }

    #[test]
    fn branch_frequencies_follow_fresnel() {
        let wo = Vec3::new(0.8, 0.0, 0.6);
        let fr = fresnel_dielectric(0.6, 1.5);
        let n = 10_000;
        let reflected = (0..n).filter(|i| !sample(wo, 1.5, (*i as f64 + 0.5) / n as f64).transmitted).count();
        assert!((reflected as f64 / n as f64 - fr).abs() < 1e-3);
    }
}
