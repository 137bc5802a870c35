//! A thin dielectric sheet (a window pane, a soap film), Mitsuba 3's `thindielectric`.
//!
//! Light meets two parallel smooth boundaries of relative index `eta` and bounces
//! between them any number of times. With `R = F(cos_o)` the Fresnel reflectance of
//! one boundary ([`fresnel_dielectric`]) and `T = 1 - R`, the reflected series sums to
//! `R' = R + T^2 R / (1 - R^2)` (`= 2 R / (1 + R)`), and the rest `T' = 1 - R'` leaves
//! the far side along the incident direction: the two refractions cancel, so the
//! sheet does not bend light (and, both sides being the same medium, no `1 / eta^2`).
//! Sampling reflects with probability `R'`: each branch's weight is 1 (times a tint).

use super::dielectric::reflect_local;
use super::fresnel::fresnel_dielectric;
use super::{Lobe, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// `R'`, the sheet's reflectance at `cos_o` (1 under total internal reflection).
#[inline]
pub fn reflectance(cos_o: f64, eta: f64) -> f64 {
    let r = fresnel_dielectric(cos_o, eta);
    if r >= 1.0 {
        return 1.0;
    }
    let t = 1.0 - r;
    r + t * t * r / (1.0 - r * r)
}

/// A direction for `wo` (local, `wo.z > 0`) and whether it went through the sheet:
/// the mirror direction when `u < R'`, else straight through (`-wo`).
#[inline]
pub fn sample(wo: Vec3, eta: f64, u: f64) -> (Vec3, bool) {
    if u < reflectance(wo.z, eta) {
        (reflect_local(wo), false)
    } else {
        (-wo, true)
    }
}

/// A thin dielectric sheet (delta) of relative index `eta`: reflection `R'`
/// and straight transmission `1 - R'`, both filtered by `tint`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinGlass {
    /// Relative index of the sheet.
    pub eta: f64,
    /// Colour filter of both branches.
    pub tint: Rgb,
}

impl Scatter for ThinGlass {
    const DELTA: bool = true;

    fn bound(&self) -> Rgb {
        self.tint
    }

    fn scaled(self, s: Rgb) -> Lobe {
        ThinGlass { eta: self.eta, tint: self.tint * s }.into()
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, _u: (f64, f64)) -> Option<Sampled> {
        Some(Sampled::Delta { wi: sample(wo, self.eta, u_choice).0, weight: self.tint, eta: 1.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflectance_is_the_summed_series_and_stays_below_one() {
        // Sum the bounces explicitly: R + T R T + T R R R T + ...
        for eta in [1.33, 1.5, 2.4] {
            for k in 0..=10 {
                let c = k as f64 / 10.0;
                let r = fresnel_dielectric(c, eta);
                let t = 1.0 - r;
                let series: f64 = r + (0..200).map(|n| t * t * r * r.powi(2 * n)).sum::<f64>();
                let closed = reflectance(c, eta);
                assert!((closed - series).abs() < 1e-12 || r > 0.99, "eta {eta} cos {c}: {closed} vs {series}");
                assert!((closed - 2.0 * r / (1.0 + r)).abs() < 1e-12 && (0.0..=1.0).contains(&closed));
            }
        }
        // At normal incidence on glass: R = 0.04, R' = 0.08 / 1.04.
        assert!((reflectance(1.0, 1.5) - 0.08 / 1.04).abs() < 1e-12);
    }

    #[test]
    fn matches_mitsuba() {
        // Mitsuba 3.9.1 `scalar_rgb` `thindielectric` (bk7 in air), fraction of 20000
        // stratified samples reflected for `wi` at 0, 30, 60, 80 degrees (`bench/mitsuba_bsdf_values.py`).
        let eta = 1.5046 / 1.00028;
        for (theta, expected) in [(0.0f64, 0.07790), (30.0, 0.08075), (60.0, 0.16495), (80.0, 0.55950)] {
            let r = reflectance(theta.to_radians().cos(), eta);
            assert!((r - expected).abs() < 1e-4, "theta {theta}: {r} vs Mitsuba {expected}");
        }
    }

    #[test]
    fn branches_follow_the_reflectance_and_transmission_does_not_bend() {
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let n = 100_000;
        let mut reflected = 0;
        for i in 0..n {
            let (wi, through) = sample(wo, 1.5, (i as f64 + 0.5) / n as f64);
            if through {
                assert_eq!(wi, -wo);
            } else {
                assert_eq!(wi, Vec3::new(-0.6, 0.0, 0.8));
                reflected += 1;
            }
        }
        assert!((reflected as f64 / n as f64 - reflectance(0.8, 1.5)).abs() < 1e-4);
    }
}
