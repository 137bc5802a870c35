//! Rough glass: the sampled directions follow the stated density (chi-square over
//! the sphere), the density integrates to the fraction of samples kept, no angle or
//! roughness gains energy, transport is reciprocal, and the smooth limit is glass.

use std::f64::consts::PI;

use super::*;

// The GGX tests below name the roughness; Beckmann's are in `bsdfs::coated_tests`.
fn f(alpha: f64, eta: f64, wo: Vec3, wi: Vec3) -> f64 {
    super::f(Microfacet::ggx(alpha), eta, wo, wi)
}
fn pdf(alpha: f64, eta: f64, wo: Vec3, wi: Vec3) -> f64 {
    super::pdf(Microfacet::ggx(alpha), eta, wo, wi)
}
fn sample(alpha: f64, eta: f64, wo: Vec3, u_branch: f64, u: (f64, f64)) -> Option<Vec3> {
    super::sample(Microfacet::ggx(alpha), eta, wo, u_branch, u)
}
use crate::bsdfs::dielectric::refract_local;
use crate::sampling::Rng;

fn dir(theta_deg: f64, phi: f64) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// The direction at fractions `(xf, pf)` of a grid over the sphere that is uniform in
/// `x` and in the angle `phi` around the x axis (equal solid angle per cell). Its
/// poles lie on the x axis, away from the peaks of the lobes tested (the normal,
/// the mirror and the refracted directions of a `wo` at azimuth [`AZIMUTH`]), where
/// a midpoint rule over the cells is accurate.
fn cell_dir(xf: f64, pf: f64) -> Vec3 {
    let x = -1.0 + 2.0 * xf;
    let s = (1.0 - x * x).max(0.0).sqrt();
    let phi = 2.0 * PI * pf;
    Vec3::new(x, s * phi.cos(), s * phi.sin())
}

/// The cell fractions of a direction (inverse of [`cell_dir`]).
fn cell_of(v: Vec3) -> (usize, usize) {
    let xf = ((v.x + 1.0) / 2.0 * NZ as f64) as usize;
    let phi = v.z.atan2(v.y).rem_euclid(2.0 * PI);
    let pf = (phi / (2.0 * PI) * NP as f64) as usize;
    (xf.min(NZ - 1), pf.min(NP - 1))
}

/// Azimuth of the outgoing directions tested.
const AZIMUTH: f64 = 1.3;

const NZ: usize = 40;
const NP: usize = 80;
const SUB: usize = 6;

/// Integral of the pdf over each cell of the `NZ x NP` grid (midpoint rule on a `SUB x SUB` subgrid).
fn cell_integrals(alpha: f64, eta: f64, wo: Vec3) -> Vec<f64> {
    let d_omega = 4.0 * PI / (NZ * NP * SUB * SUB) as f64;
    let mut cells = vec![0.0; NZ * NP];
    for i in 0..NZ * SUB {
        for j in 0..NP * SUB {
            let wi = cell_dir((i as f64 + 0.5) / (NZ * SUB) as f64, (j as f64 + 0.5) / (NP * SUB) as f64);
            cells[(i / SUB) * NP + j / SUB] += pdf(alpha, eta, wo, wi) * d_omega;
        }
    }
    cells
}

/// Chi-square statistic of `n` samples against the pdf, cells with fewer than 5
/// expected samples pooled; returns (statistic, degrees of freedom, fraction kept).
fn chi_square(alpha: f64, eta: f64, wo: Vec3, n: usize, seed: u64) -> (f64, usize, f64) {
    let mut observed = vec![0.0; NZ * NP];
    let mut rng = Rng::for_sample(seed, 0, 0);
    let mut kept = 0;
    for _ in 0..n {
        let (a, b, c) = (rng.uniform(), rng.uniform(), rng.uniform());
        if let Some(wi) = sample(alpha, eta, wo, a, (b, c)) {
            let (zf, pf) = cell_of(wi);
            observed[zf * NP + pf] += 1.0;
            kept += 1;
        }
    }
    let expected: Vec<f64> = cell_integrals(alpha, eta, wo).iter().map(|p| p * n as f64).collect();
    let (chi2, cells) = crate::bsdfs::test_support::pooled_chi_square(&observed, &expected);
    (chi2, cells - 1, kept as f64 / n as f64)
}

#[test]
fn sampled_directions_follow_the_pdf() {
    // Chi-square of the sample histogram against the integrated pdf. Under the null
    // hypothesis chi2 ~ dof +- sqrt(2 dof); the Wilson-Hilferty transform makes it a
    // standard normal, which must stay below 4 (fixed seeds: no flakiness).
    for (alpha, eta, theta) in [(0.3, 1.5, 30.0), (0.6, 1.5, 70.0), (0.3, 1.0 / 1.5, 20.0), (0.5, 1.0 / 1.5, 60.0), (0.15, 1.33, 45.0)] {
        let wo = dir(theta, AZIMUTH);
        let (chi2, dof, _) = chi_square(alpha, eta, wo, 400_000, 7);
        let k = dof as f64;
        let z = ((chi2 / k).cbrt() - (1.0 - 2.0 / (9.0 * k))) / (2.0 / (9.0 * k)).sqrt();
        eprintln!("alpha {alpha} eta {eta:.3} theta {theta}: chi2 {chi2:.0} dof {dof} z {z:.2}");
        assert!(z < 4.0, "alpha {alpha} eta {eta} theta {theta}: chi2 {chi2:.1} for {dof} dof (z {z:.2})");
    }
}

#[test]
fn pdf_integrates_to_the_fraction_of_samples_kept() {
    // Samples that land on the wrong side of the macro-surface are dropped; the rest
    // have density pdf, so its integral over the sphere is the fraction kept (<= 1).
    for (alpha, eta, theta) in [(0.1, 1.5, 0.0), (0.3, 1.5, 50.0), (0.8, 1.5, 80.0), (0.2, 1.0 / 1.5, 35.0), (0.7, 1.0 / 1.5, 60.0)] {
        let wo = dir(theta, AZIMUTH);
        let integral: f64 = cell_integrals(alpha, eta, wo).iter().sum();
        let (_, _, kept) = chi_square(alpha, eta, wo, 100_000, 3);
        eprintln!("alpha {alpha} eta {eta:.3} theta {theta}: integral {integral:.4}, kept {kept:.4}");
        assert!(integral <= 1.0 + 2e-3, "{integral}");
        assert!((integral - kept).abs() < 5e-3, "alpha {alpha} eta {eta} theta {theta}: integral {integral} vs kept {kept}");
    }
}

#[test]
fn transport_is_reciprocal() {
    // Reflection is symmetric, f(wo, wi) = f(wi, wo). Refraction swaps the sides:
    // seen from the other side (z flipped, index 1 / eta) the radiance BSDF is
    // eta^2 times larger, f(wi', wo', 1/eta) = eta^2 f(wo, wi, eta).
    let flip = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
    let mut rng = Rng::for_sample(11, 0, 0);
    for _ in 0..200 {
        let alpha = 0.05 + 0.9 * rng.uniform();
        let eta = if rng.uniform() < 0.5 { 1.5 } else { 1.0 / 1.33 };
        let wo = dir(85.0 * rng.uniform(), 6.0 * rng.uniform());
        let a = dir(85.0 * rng.uniform(), 6.0 * rng.uniform());
        let r = f(alpha, eta, wo, a);
        assert!((r - f(alpha, eta, a, wo)).abs() <= 1e-9 * r.max(1.0), "reflection");
        let wi = flip(a);
        let t = f(alpha, eta, wo, wi);
        let back = f(alpha, 1.0 / eta, flip(wi), flip(wo));
        assert!((back - eta * eta * t).abs() <= 1e-9 * back.max(1.0), "refraction: {back} vs {}", eta * eta * t);
    }
}

/// Power albedo `E[f |cos| / pdf * (eta^2 on refraction)]` and its reflected part.
fn albedo(alpha: f64, eta: f64, wo: Vec3) -> (f64, f64) {
    let n = 256;
    let (mut total, mut reflected) = (0.0, 0.0);
    crate::bsdfs::test_support::stratified_grid(n, |u_branch, u| {
        let Some(wi) = sample(alpha, eta, wo, u_branch, u) else { return };
        let w = f(alpha, eta, wo, wi) * wi.z.abs() / pdf(alpha, eta, wo, wi);
        if wi.z > 0.0 {
            reflected += w;
            total += w;
        } else {
            total += w * eta * eta;
        }
    });
    (total / (n * n) as f64, reflected / (n * n) as f64)
}

#[test]
fn no_angle_or_roughness_gains_energy() {
    // Power albedo <= 1 everywhere; nearly 1 for nearly smooth glass; and falling
    // as the roughness grows (more light stays on the microsurface, which the
    // single-scattering model drops: from inside at alpha 1, more than half).
    for eta in [1.5, 1.0 / 1.5] {
        let mut previous = [1.0 + 1e-3; 9];
        for alpha in [0.01, 0.1, 0.3, 0.6, 1.0] {
            let mut line = String::new();
            for (k, prev) in previous.iter_mut().enumerate() {
                let theta = k as f64 * 10.0 + if k == 8 { 5.0 } else { 0.0 };
                let (a, _) = albedo(alpha, eta, dir(theta, 0.0));
                line += &format!(" {a:.3}");
                assert!(a <= *prev + 1e-3, "eta {eta} alpha {alpha} theta {theta}: albedo {a} above {prev} of a smoother lobe");
                assert!(a > 0.3, "eta {eta} alpha {alpha} theta {theta}: albedo {a}");
                if alpha <= 0.01 {
                    assert!(a > 0.99, "eta {eta} alpha {alpha} theta {theta}: albedo {a}");
                }
                *prev = a;
            }
            eprintln!("eta {eta:.3} alpha {alpha}:{line}");
        }
    }
}

#[test]
fn smooth_limit_is_fresnel_glass() {
    // At the smallest roughness the lobe reflects F of the power, transmits 1 - F,
    // and sends the refracted light along Snell's direction.
    for (eta, theta) in [(1.5, 30.0), (1.5, 70.0), (1.0 / 1.5, 15.0), (1.0 / 1.5, 30.0)] {
        let wo = dir(theta, 0.0);
        let alpha = crate::bsdfs::microfacet::MIN_ALPHA;
        let (total, reflected) = albedo(alpha, eta, wo);
        let fr = fresnel_dielectric(wo.z, eta);
        assert!((reflected - fr).abs() < 2e-3, "eta {eta} theta {theta}: reflected {reflected} vs F {fr}");
        assert!((total - 1.0).abs() < 2e-3, "eta {eta} theta {theta}: total {total}");
        if let Some(snell) = refract_local(wo, eta) {
            let mut rng = Rng::for_sample(5, 0, 0);
            for _ in 0..100 {
                if let Some(wi) = sample(alpha, eta, wo, 0.999_999, (rng.uniform(), rng.uniform())) {
                    assert!(wi.dot(snell) > 0.999, "{wi} vs {snell}");
                }
            }
        }
    }
}
