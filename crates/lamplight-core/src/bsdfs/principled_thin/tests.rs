//! The thin principled lobe against Mitsuba 3.9.1's own numbers, in the white
//! furnace, against its pdf (chi-square) and for reciprocity.

use super::*;
use crate::bsdfs::test_support::{chi_square_z, furnace, reciprocity_error, Sampled};
use std::f64::consts::PI;

fn dir(theta: f64, phi: f64) -> Vec3 {
    let t = theta.to_radians();
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// The parameter sets of `bench/mitsuba_bsdf_values.py` (`diff_trans` 0.8 and 1.5 halved).
fn set(name: &str) -> PrincipledThin {
    let d = ThinParams::default();
    match name {
        "thin_leaf" => PrincipledThin::new(
            Rgb::new(0.3, 0.6, 0.2),
            ThinParams { spec_trans: 0.4, diff_trans: 0.4, roughness: 0.4, eta: 1.4, sheen: 0.5, sheen_tint: 0.3, spec_tint: 0.2, ..d },
        ),
        "thin_flat" => PrincipledThin::new(Rgb::new(0.8, 0.5, 0.4), ThinParams { diff_trans: 0.75, flatness: 0.6, roughness: 0.6, ..d }),
        _ => unreachable!("{name}"),
    }
}

/// A parameter set's name, its albedo per channel at four angles, and `eval()` (three channels) and `pdf()` towards five directions.
type Reference = (&'static str, [[f64; 3]; 4], [[f64; 4]; 5]);

/// Mitsuba 3.9.1 `scalar_rgb`, `mi.load_dict({'type': 'principledthin', ...})`, from
/// `bench/mitsuba_bsdf_values.py`: the albedo (per channel) of 200^2 stratified
/// `sample()` calls for `wi` at 0, 30, 60, 80 degrees (azimuth 0.4); then `eval()`
/// (`f cos`, per channel) and `pdf()` from 30 degrees towards five directions (the
/// fourth is straight through the sheet).
const MITSUBA: [Reference; 2] = [
    (
        "thin_leaf",
        [
            [0.3043656, 0.599912, 0.2058502],
            [0.3047516, 0.5998925, 0.2063713],
            [0.3140956, 0.6034053, 0.217659],
            [0.3308046, 0.5846672, 0.2461837],
        ],
        [
            [0.03635382, 0.07053028, 0.02496167, 0.1617028],
            [0.02498368, 0.04741344, 0.01750709, 0.1234007],
            [0.01362046, 0.0253464, 0.00971181, 0.06328834],
            [4.270576, 8.541152, 2.847051, 7.364204],
            [0.01145916, 0.02291831, 0.007639437, 0.03819719],
        ],
    ),
    (
        "thin_flat",
        [
            [0.7711848, 0.4819905, 0.3855924],
            [0.7792421, 0.4870263, 0.389621],
            [0.8114391, 0.5071494, 0.4057196],
            [0.8468268, 0.5292667, 0.4234134],
        ],
        [
            [0.05048392, 0.03155245, 0.02524196, 0.07836851],
            [0.03671376, 0.0229461, 0.01835688, 0.05115141],
            [0.02172624, 0.0135789, 0.01086312, 0.0272171],
            [0.1653987, 0.1033742, 0.08269934, 0.2067483],
            [0.09549297, 0.0596831, 0.04774648, 0.1193662],
        ],
    ),
];

fn directions() -> [Vec3; 5] {
    [dir(10.0, 2.0), dir(50.0, 3.0), dir(70.0, 0.4 + PI), dir(150.0, 0.4 + PI), dir(120.0, 1.0)]
}

fn sampled(p: &PrincipledThin, wo: Vec3, u_choice: f64, u: (f64, f64), channel: usize) -> Option<Sampled> {
    let wi = p.sample(wo, u_choice, u)?;
    let pdf = p.pdf(wo, wi);
    (pdf > 0.0).then(|| Sampled::Smooth(wi, p.f(wo, wi)[channel] * wi.z.abs() / pdf))
}

#[test]
fn eval_pdf_and_albedo_match_mitsuba() {
    for (name, albedos, rows) in MITSUBA {
        let lobe = set(name);
        let wo = dir(30.0, 0.4);
        for (wi, row) in directions().into_iter().zip(rows) {
            let value = lobe.f(wo, wi) * wi.z.abs();
            for (got, expected) in [value.x, value.y, value.z, lobe.pdf(wo, wi)].into_iter().zip(row) {
                assert!((got - expected).abs() <= 1e-4 * expected.abs() + 1e-8, "{name} towards {wi}: {got} vs Mitsuba {expected}");
            }
        }
        for (theta, expected) in [0.0, 30.0, 60.0, 80.0].into_iter().zip(albedos) {
            for (channel, expected) in expected.into_iter().enumerate() {
                let (albedo, _) = furnace(|a, u| sampled(&lobe, dir(theta, 0.4), a, u, channel));
                assert!((albedo / expected - 1.0).abs() < 6e-3, "{name} theta {theta} channel {channel}: {albedo} vs Mitsuba {expected}");
            }
        }
    }
}

#[test]
fn a_white_glossy_sheet_keeps_at_most_what_it_receives() {
    // All glossy (spec_trans 1), or all diffuse transmission (diff_trans 2): no
    // Burley retro-reflection, so the albedo stays at most 1.
    let d = ThinParams::default();
    for params in [ThinParams { spec_trans: 1.0, roughness: 0.3, ..d }, ThinParams { diff_trans: 1.0, ..d }] {
        let lobe = PrincipledThin::new(Rgb::ONE, params);
        for theta in [0.0, 30.0, 60.0, 85.0] {
            let (albedo, _) = furnace(|a, u| sampled(&lobe, dir(theta, 0.2), a, u, 0));
            assert!(albedo <= 1.0 + 2e-3, "{params:?} theta {theta}: {albedo}");
        }
    }
}

#[test]
fn samples_follow_the_pdf_and_reflection_is_reciprocal() {
    for name in ["thin_leaf", "thin_flat"] {
        let lobe = set(name);
        for wo in [dir(35.0, 0.3), dir(75.0, 1.1)] {
            let z = chi_square_z(|wi| lobe.pdf(wo, wi), |a, u| sampled(&lobe, wo, a, u, 0), 300_000, 7);
            assert!(z < 4.0, "{name} from {wo}: z {z:.2}");
        }
        for channel in 0..3 {
            assert!(reciprocity_error(|a, b| lobe.f(a, b)[channel]) < 1e-12, "{name}");
        }
    }
}
