//! Anisotropic microfacets: each distribution is normalized and its masking
//! belongs to it; sampled directions follow the stated densities (chi-square) for
//! reflection, rough glass and the principled lobes; a white conductor (`F = 1`)
//! loses energy only as single scattering does, between its two isotropic
//! bounds; and swapping `alpha_u` and `alpha_v` is turning the tangent by 90 degrees.

use super::*;
use crate::bsdfs::distribution::{Distribution, Microfacet};
use crate::bsdfs::test_support::{chi_square_z, hemisphere_quadrature, stratified_mean, Sampled};
use crate::bsdfs::{Bsdf, Frame, Lobe, RoughConductor, RoughGlass};
use crate::math::Rgb;

const PAIRS: [(f64, f64); 4] = [(0.05, 0.3), (0.3, 0.05), (0.2, 0.6), (0.5, 0.9)];

/// The integral of `g(h)` over the upper hemisphere, midpoint rule in
/// `(cos theta, phi)` with the cosines crowded towards the pole (`c = 1 - s^2`),
/// where narrow lobes live.
fn hemisphere_integral(g: impl Fn(Vec3) -> f64) -> f64 {
    let (ns, np) = (2000, 720);
    let mut sum = 0.0;
    for i in 0..ns {
        let s = (i as f64 + 0.5) / ns as f64;
        let c = 1.0 - s * s;
        let dc = 2.0 * s / ns as f64;
        let sin = (1.0 - c * c).max(0.0).sqrt();
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI;
            sum += g(Vec3::new(sin * phi.cos(), sin * phi.sin(), c)) * dc * 2.0 * PI / np as f64;
        }
    }
    sum
}

#[test]
fn projected_area_of_both_distributions_is_one() {
    // Integral of D(h) cos(theta_h) d(omega) = 1 for every (a_u, a_v).
    for (au, av) in PAIRS {
        let ggx = hemisphere_integral(|h| ggx_d(au, av, h) * h.z);
        let beckmann = hemisphere_integral(|h| beckmann_d(au, av, h) * h.z);
        assert!((ggx - 1.0).abs() < 3e-3, "GGX ({au}, {av}): {ggx}");
        assert!((beckmann - 1.0).abs() < 3e-3, "Beckmann ({au}, {av}): {beckmann}");
    }
}

#[test]
fn equal_roughnesses_are_the_isotropic_forms() {
    let iso = |d| Microfacet::new(d, 0.3);
    for d in [Distribution::Ggx, Distribution::Beckmann] {
        let m = iso(d);
        for v in [Vec3::new(0.3, -0.2, 0.9).normalize(), Vec3::new(-0.8, 0.1, 0.2).normalize()] {
            let (dd, l) = match d {
                Distribution::Ggx => (ggx_d(0.3, 0.3, v), ggx_lambda(0.3, 0.3, v)),
                Distribution::Beckmann => (beckmann_d(0.3, 0.3, v), beckmann_lambda(0.3, 0.3, v)),
            };
            assert!((dd - m.d(v)).abs() <= 1e-12 * dd.max(1.0), "{d:?} D {dd} vs {}", m.d(v));
            assert!((l - m.lambda(v)).abs() <= 1e-12 * l.max(1.0), "{d:?} Lambda {l} vs {}", m.lambda(v));
        }
    }
}

#[test]
fn masking_keeps_the_projected_area_of_the_visible_normals() {
    // Heitz 2014 eq. 8: integral of G1(v) max(0, v.h) D(h) d(omega) = cos(theta_v),
    // which holds only when Lambda belongs to D (exactly for GGX, to the fit's 0.35 % for Beckmann).
    for (au, av) in PAIRS {
        for d in [Distribution::Ggx, Distribution::Beckmann] {
            let m = Microfacet::anisotropic(d, au, av);
            for v in [Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.5, 0.5, 0.5f64.sqrt())] {
                let visible = hemisphere_integral(|h| m.d(h) * v.dot(h).max(0.0)) * m.g1(v);
                let tolerance = if d == Distribution::Ggx { 3e-3 } else { 6e-3 };
                assert!((visible / v.z - 1.0).abs() < tolerance, "{d:?} ({au}, {av}) {v}: {visible} vs {}", v.z);
            }
        }
    }
}

const BOTH: [Distribution; 2] = [Distribution::Ggx, Distribution::Beckmann];

/// A direction at polar angle `theta_deg` and azimuth `phi`.
fn dir(theta_deg: f64, phi: f64) -> Vec3 {
    let t = theta_deg.to_radians();
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

#[test]
fn sampled_reflections_follow_the_pdf() {
    for d in BOTH {
        for (au, av) in PAIRS {
            let m = Microfacet::anisotropic(d, au, av);
            for wo in [dir(30.0, 0.4), dir(70.0, 2.0)] {
                let z = chi_square_z(|wi| m.pdf(wo, wi), |_, u| m.sample(wo, u).map(|wi| Sampled::Smooth(wi, 1.0)), 200_000, 3);
                assert!(z < 4.0, "{d:?} ({au}, {av}) wo {wo}: z {z}");
            }
        }
    }
}

#[test]
fn sampled_rough_glass_follows_the_pdf() {
    for d in BOTH {
        for (au, av) in [(0.1, 0.4), (0.5, 0.2)] {
            for eta in [1.5, 1.0 / 1.5] {
                let glass = Bsdf::new(&[Lobe::RoughGlass(RoughGlass { eta, alpha: au, alpha_v: av, tint: Rgb::ONE, distribution: d })]);
                assert!(glass.needs_tangent());
                let wo = dir(40.0, 1.1);
                let z = chi_square_z(
                    |wi| glass.pdf(wo, wi),
                    |a, u| glass.sample(wo, a, u).map(|s| Sampled::Smooth(s.wi, s.weight.x)),
                    200_000,
                    7,
                );
                assert!(z < 4.0, "{d:?} ({au}, {av}) eta {eta}: z {z}");
            }
        }
    }
}

#[test]
fn sampled_principled_lobes_follow_the_pdf() {
    use crate::bsdfs::principled::{Principled, PrincipledParams};
    use crate::bsdfs::principled_thin::{PrincipledThin, ThinParams};
    let params = PrincipledParams { roughness: 0.5, anisotropic: 0.8, spec_trans: 0.5, ..PrincipledParams::default() };
    let thin = ThinParams { roughness: 0.4, anisotropic: 0.6, spec_trans: 0.7, ..ThinParams::default() };
    let base = Rgb::new(0.8, 0.5, 0.3);
    let lobes = [
        Lobe::Principled(Principled::new(base, params, true)),
        Lobe::Principled(Principled::new(base, params, false)),
        Lobe::PrincipledThin(PrincipledThin::new(base, thin)),
    ];
    for lobe in lobes {
        let bsdf = Bsdf::new(&[lobe]);
        assert!(bsdf.needs_tangent(), "{lobe:?}");
        let wo = dir(50.0, 0.7);
        let z = chi_square_z(|wi| bsdf.pdf(wo, wi), |a, u| bsdf.sample(wo, a, u).map(|s| Sampled::Smooth(s.wi, s.weight.x)), 200_000, 9);
        assert!(z < 4.0, "{lobe:?}: z {z}");
    }
}

/// The directional albedo `E[f cos / pdf]` of a white conductor (`F = 1`).
fn white_albedo(m: Microfacet, wo: Vec3) -> f64 {
    stratified_mean(300, |u| m.sample(wo, u).map_or(0.0, |wi| m.f(Rgb::ONE, wo, wi).x * wi.z / m.pdf(wo, wi)))
}

#[test]
fn a_white_conductor_loses_only_what_single_scattering_loses() {
    // With F = 1 the only loss is the light the microsurface masks after one
    // bounce: nearly none when smooth, more with roughness. The anisotropic
    // albedo lies between those of its two roughnesses taken isotropically (up
    // to 45 degrees; GGX (0.1, 0.6) at normal incidence: 0.755 between 0.592 and 0.989), and
    // the sampled albedo is the quadrature of f cos (samples and pdf agree).
    for d in BOTH {
        for wo in [dir(0.0, 0.0), dir(45.0, 0.0), dir(45.0, PI / 2.0), dir(75.0, 0.9)] {
            let smooth = white_albedo(Microfacet::anisotropic(d, 0.01, 0.03), wo);
            assert!(smooth > 0.985 && smooth <= 1.0 + 1e-9, "{d:?} smooth {wo}: {smooth}");
            for (au, av) in [(0.1, 0.6), (0.6, 0.1), (0.3, 0.9)] {
                let m = Microfacet::anisotropic(d, au, av);
                let a = white_albedo(m, wo);
                let quadrature = hemisphere_quadrature(|wi| m.f(Rgb::ONE, wo, wi).x);
                assert!((a - quadrature).abs() < 0.01, "{d:?} ({au}, {av}) {wo}: sampled {a}, quadrature {quadrature}");
                let low = white_albedo(Microfacet::new(d, au.max(av)), wo);
                let high = white_albedo(Microfacet::new(d, au.min(av)), wo);
                assert!(a <= 1.0 + 1e-9, "{d:?} ({au}, {av}) {wo}: {a}");
                // Not a theorem at grazing angles (Beckmann's albedo is not monotonic in
                // the roughness there): a sanity check up to 45 degrees.
                if wo.z >= 0.7 {
                    assert!(a >= low - 3e-3 && a <= high + 3e-3, "{d:?} ({au}, {av}) {wo}: {a} not in [{low}, {high}]");
                }
            }
        }
    }
}

#[test]
fn swapping_the_roughnesses_is_turning_the_tangent_by_90_degrees() {
    // The same world directions over a surface whose dp/du is x (roughness
    // (a_u, a_v)) and one whose dp/du is y (roughness (a_v, a_u)): the same value
    // and density, through Frame::from_tangent.
    let n = Vec3::new(0.2, -0.1, 1.0).normalize();
    let x = Frame::from_tangent(n, Vec3::X, n);
    // A quarter turn: the second surface's dp/du is the first frame's bitangent.
    let y = Frame::from_tangent(n, x.b, n);
    for d in BOTH {
        for (au, av) in [(0.05, 0.4), (0.3, 0.7)] {
            let along = RoughConductor { eta: Rgb::splat(0.2), k: Rgb::splat(3.0), alpha: au, alpha_v: av, distribution: d };
            let across = RoughConductor { alpha: av, alpha_v: au, ..along };
            let (fa, fb) = (Bsdf::new(&[along.into()]), Bsdf::new(&[across.into()]));
            for (wo, wi) in [(dir(30.0, 0.3), dir(50.0, 2.5)), (dir(60.0, 1.7), dir(20.0, -0.6)), (dir(10.0, 0.0), dir(80.0, 1.0))] {
                let (wo, wi) = (x.to_world(wo), x.to_world(wi));
                let (va, vb) = (fa.f(x.to_local(wo), x.to_local(wi)), fb.f(y.to_local(wo), y.to_local(wi)));
                let (pa, pb) = (fa.pdf(x.to_local(wo), x.to_local(wi)), fb.pdf(y.to_local(wo), y.to_local(wi)));
                assert!((va - vb).abs().max_element() <= 1e-9 * va.max_element().max(1.0), "{d:?}: {va} vs {vb}");
                assert!((pa - pb).abs() <= 1e-9 * pa.max(1.0), "{d:?}: {pa} vs {pb}");
                // And the lobe is anisotropic: without the turn the values differ.
                let unturned = fb.f(x.to_local(wo), x.to_local(wi));
                assert!(va.max_element() < 1e-3 || (va - unturned).abs().max_element() > 1e-3 * va.max_element(), "{d:?}");
            }
        }
    }
}

#[test]
fn the_tangent_frame_follows_dpdu_projected_on_the_normal() {
    let n = Vec3::new(0.0, 0.6, 0.8);
    let f = Frame::from_tangent(n, Vec3::new(2.0, 1.0, 0.0), n);
    // dp/du minus its normal part, normalized; b = n x t (a right-handed frame).
    let expected = (Vec3::new(2.0, 1.0, 0.0) - n * 0.6).normalize();
    assert!((f.t - expected).length() < 1e-15 && (f.b - n.cross(expected)).length() < 1e-15, "{f:?}");
    assert!((f.t.cross(f.b) - n).length() < 1e-15);
    // Degenerate dp/du (zero, or along the normal): the basis around the outward normal, as Mitsuba's.
    for dpdu in [Vec3::ZERO, n * 3.0] {
        let g = Frame::from_tangent(-n, dpdu, n);
        assert_eq!(g.t, crate::math::orthonormal_basis(n).0);
        assert!((g.t.cross(g.b) + n).length() < 1e-15, "z is the ray's side, -n");
    }
}
