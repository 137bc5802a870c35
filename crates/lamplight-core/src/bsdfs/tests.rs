//! Energy and consistency checks over lobes and their mixtures.

use super::test_support::albedo;
use super::*;

#[test]
fn lossless_lobes_conserve_energy_exactly() {
    // A white Lambertian and clear glass entered from outside keep all energy
    // (glass gives 1/eta^2 on refraction, which the radiance compression explains;
    // its power, weight * eta^2, is 1).
    let white = Bsdf::new(&[Lobe::Diffuse(Lambertian(Rgb::ONE))]);
    for k in 0..8 {
        let theta = (k as f64 * 11.0).to_radians();
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        assert!((albedo(&white, wo).x - 1.0).abs() < 1e-9);
    }
    let glass = Bsdf::new(&[Lobe::Glass(Glass { eta: 1.0, tint: Rgb::ONE })]);
    assert!((albedo(&glass, Vec3::new(0.6, 0.0, 0.8)).x - 1.0).abs() < 1e-9);
}

#[test]
fn glossy_pdf_integrates_to_one_over_the_sphere() {
    // Quadrature of the mixture pdf over the hemisphere (the lobe cannot leave it):
    // the sampled density is a density (integral <= 1, equal for the diffuse part).
    let bsdf = Bsdf::new(&[Lobe::Diffuse(Lambertian(Rgb::splat(0.5))), Lobe::Glossy(Glossy { ks: Rgb::splat(0.5), alpha: 0.3 })]);
    let wo = Vec3::new(0.5, 0.0, 0.75f64.sqrt());
    let (nt, np) = (400, 400);
    let mut integral = 0.0;
    for i in 0..nt {
        let c = (i as f64 + 0.5) / nt as f64; // cos(theta), d(omega) = dc dphi
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * std::f64::consts::PI;
            let s = (1.0 - c * c).sqrt();
            let wi = Vec3::new(s * phi.cos(), s * phi.sin(), c);
            integral += bsdf.pdf(wo, wi) / nt as f64 * 2.0 * std::f64::consts::PI / np as f64;
        }
    }
    // The GGX visible-normal sampler loses the samples reflected below the horizon:
    // the integral equals the fraction of samples that survive.
    let n = 256;
    let mut kept = 0;
    for i in 0..n {
        for j in 0..n {
            let u = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            kept += usize::from(bsdf.sample(wo, ((i * n + j) as f64 * 0.618_033_988_749_895).fract(), u).is_some());
        }
    }
    let survived = kept as f64 / (n * n) as f64;
    assert!((integral - survived).abs() < 5e-3, "{integral} vs {survived}");
}

/// `KHR_materials_transmission` (thin-walled): the dielectric's diffuse base
/// replaced by a GGX lobe mirrored below the surface.
mod transmission {
    use super::*;
    use metallic_roughness::{MetallicRoughness, Specular};
    use test_support::{chi_square_z, Sampled};

    fn lobe(base: Rgb, metallic: f64, roughness: f64, t: f64) -> Bsdf {
        let alpha = (roughness * roughness).max(microfacet::MIN_ALPHA);
        Bsdf::new(&[Lobe::MetallicRoughness(MetallicRoughness { base, metallic, spec: Specular::GLTF, alpha, transmission: t })])
    }

    fn dir(theta_deg: f64) -> Vec3 {
        let t = theta_deg.to_radians();
        Vec3::new(t.sin(), 0.0, t.cos())
    }

    #[test]
    fn full_transmission_of_white_keeps_at_most_what_arrives() {
        // Reflection F and transmission 1 - F share one GGX lobe: together its
        // single-scattering albedo, at most 1 and all of it when smooth.
        for roughness in [0.0, 0.05, 0.5, 1.0] {
            let bsdf = lobe(Rgb::ONE, 0.0, roughness, 1.0);
            for k in 0..=8 {
                let a = albedo(&bsdf, dir(k as f64 * 10.0));
                assert!(a.max_element() <= 1.0 + 2e-3, "r {roughness} at {} deg: {a}", k * 10);
                if roughness <= 0.05 && k <= 7 {
                    assert!(a.min_element() > 0.99, "smooth: nothing lost, r {roughness} at {} deg: {a}", k * 10);
                }
            }
        }
        // Partly transmitting, coloured, partly metallic: below 1 up to 45 degrees (as without transmission).
        let bsdf = lobe(Rgb::new(0.9, 0.5, 0.2), 0.3, 0.4, 0.6);
        for k in 0..=4 {
            assert!(albedo(&bsdf, dir(k as f64 * 10.0)).max_element() <= 1.0 + 2e-3);
        }
    }

    #[test]
    fn sampling_matches_the_density_on_both_sides() {
        let wo = Vec3::new(0.5, 0.2, 0.8).normalize();
        for (roughness, t) in [(0.4, 1.0), (0.6, 0.5), (0.3, 0.2)] {
            let bsdf = lobe(Rgb::new(0.8, 0.6, 0.4), 0.2, roughness, t);
            let z =
                chi_square_z(|wi| bsdf.pdf(wo, wi), |a, u| bsdf.sample(wo, a, u).map(|s| Sampled::Smooth(s.wi, s.weight.x)), 200_000, 11);
            assert!(z < 4.0, "r {roughness} t {t}: z {z:.2}");
            let below = (0..2000).filter_map(|i| bsdf.sample(wo, (i as f64 + 0.5) / 2000.0, (0.3, 0.7))).filter(|s| s.wi.z < 0.0);
            for s in below {
                // A thin wall: no bending, no radiance scaling.
                assert_eq!(s.eta, 1.0);
                assert!(!s.delta);
            }
        }
    }

    #[test]
    fn the_wall_is_reciprocal_seen_from_either_side() {
        // f(wo, wi) with wi below equals f with the two swapped and mirrored
        // (the same wall seen from the other side), and reflection is reciprocal.
        let bsdf = lobe(Rgb::new(0.8, 0.6, 0.4), 0.1, 0.5, 0.7);
        let mirror = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
        // f(a, b') against f(b, a') with ' the mirror: the wall seen from its other side.
        let through = test_support::reciprocity_error(|a, b| bsdf.f(a, mirror(b)).x);
        assert!(through < 1e-12 && test_support::reciprocity_error(|a, b| bsdf.f(a, b).x) < 1e-12, "{through}");
    }

    #[test]
    fn smooth_transmission_goes_straight_through_as_the_thin_dielectric() {
        // Roughness 0 (GGX at its least alpha): the transmitted rays leave
        // along -wo, where the thin dielectric sends its own, carrying 1 - F of
        // Schlick's Fresnel of index 1.5 (glTF's single interface).
        for theta in [0.0, 30.0, 60.0] {
            let wo = dir(theta);
            let bsdf = lobe(Rgb::ONE, 0.0, 0.0, 1.0);
            let (straight, _) = thin_dielectric::sample(wo, 1.5, 0.999);
            let (mut through, mut n, mut mean) = (0.0, 0, Vec3::ZERO);
            for i in 0..64 {
                for j in 0..64 {
                    let u = ((i as f64 + 0.5) / 64.0, (j as f64 + 0.5) / 64.0);
                    let u_lobe = ((i * 64 + j) as f64 * 0.618_033_988_749_895).fract();
                    if let Some(s) = bsdf.sample(wo, u_lobe, u) {
                        if s.wi.z < 0.0 {
                            // GGX's long tail, even at its least alpha.
                            assert!((s.wi - straight).length() < 0.1, "{} vs {straight}", s.wi);
                            through += s.weight.x;
                            mean += s.wi * s.weight.x;
                        }
                    }
                    n += 1;
                }
            }
            let f = 0.04 + 0.96 * (1.0 - wo.z).powi(5);
            assert!((mean / through - straight).length() < 2e-3, "{theta} deg: mean direction {}", mean / through);
            let through = through / n as f64;
            assert!((through - (1.0 - f)).abs() < 2e-3, "{theta} deg: {through} vs {}", 1.0 - f);
        }
    }
}
