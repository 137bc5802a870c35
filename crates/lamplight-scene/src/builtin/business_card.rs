//! `business-card`: Paul Heckbert's business-card ray tracer ("minray", 1987),
//! the five-sphere program at the end of the lecture, rebuilt from core parts so
//! that lamplight prints what the card prints.
//!
//! # The sphere table
//!
//! Each sphere is 12 numbers: centre `(x, y, z)`, colour `(r, g, b)`, radius, `kd`,
//! `ks`, `kt`, `kl` (emission and light strength), `ir` (index of refraction).
//! The lecture's copy lost decimal points and numbers: it holds 58 values, not 60,
//! and several that are off by a factor of ten (read as a flat C initializer,
//! every sphere after the first would also start in the wrong place). Sphere by
//! sphere, lecture → restored:
//!
//! | # | lecture's text | restored | what was wrong |
//! |---|----------------|----------|----------------|
//! | 0 | `0,6,.5, 1,1,.9, .05,2,85,0,1.7` (11) | `0,6,.5, 1,1,1, .9, .05,.2,.85,0,1.7` | a `1.` of the colour lost; `ks` `.2`, `kt` `.85` lost their points |
//! | 1 | `-1,8,-5, 1,.5,2, 1, .7,.3,0,.05,1.2` | `-1,8,-.5, 1,.5,.2, 1, .7,.3,0,.05,1.2` | `z` `-.5` and blue `.2` lost their points |
//! | 2 | `1,8,-.5, 1,.8,8, 1, .3,7,0,0,1.2` | `1,8,-.5, .1,.8,.8, 1, .3,.7,0,0,1.2` | red `.1`, blue `.8`, `ks` `.7` lost their points |
//! | 3 | `3,-6,15, 1,.8,1, 7, 0,0,.6,1.5` (11) | `3,-6,15, 1,.8,1, 7, 0,0,0,.6,1.5` | one of `kd, ks, kt` lost |
//! | 4 | `-3,-3,12, .8,1,1, .5, 0,0,0,.5,1.5` | `-3,-3,12, .8,1,1, 5, 0,0,0,.5,1.5` | the radius `5.` became `.5` |
//!
//! How it was checked:
//! - **Count.** The restored table has 12 numbers per sphere, 60 in all, and the C
//!   array initializer is exactly `struct sphere[5]` (`sph+5` in the program).
//! - **Published copies.** The restored 60 values agree number for number with
//!   `minray.c` in `tonetheman/wasmchrome70_threads` (a copy of the card),
//!   another stored copy of the card text (found by its exact sphere-table string),
//!   and `examples/simple_scene.rs` and `benches/depth-bench.rs` in
//!   `hukasu/heckbert_renderer` (a Rust port that spells the values out).
//! - **Physical sense.** Colours lie in `[0, 1]`; each weight lies in `[0, 1]`
//!   with `kd + ks + kt <= 1.1` (the glass `0.05 + 0.2 + 0.85`; the lecture's `2`
//!   and `85` break both); the three small spheres (radii `0.9, 1, 1`) sit side by
//!   side 6 to 8 units in front of the eye at `z = ±0.5` (the lecture's `z = -5`
//!   would put sphere 1 below the 25 degree field of view, which reaches
//!   `z = ±1.8` at that distance); the two big spheres behind the eye are the
//!   light sources (`kd = ks = kt = 0`, `kl > 0`), and the lecture's radius `.5`
//!   would make one of them smaller than the spheres it lights.
//! - **The image.** `tests/business_card.rs` compiles the restored card and
//!   compares its printout with this scene pixel by pixel.
//!
//! # What the card computes, in lamplight's terms
//!
//! `trace(level, P, D)` finds the nearest sphere (`t >= 1e-7`), or returns the
//! background `amb = 0.02`. At the hit `P` it takes `N = unit(cen - P)` and
//! `d = -D.N`; when `d < 0` (the ray comes from outside, since this `N` points
//! inwards) it turns `N` round, sets `eta = 1/ir` and `d = -d`, otherwise (leaving)
//! `eta = ir`. So `N` always faces the ray, `d` is the cosine of incidence, and
//!
//! `I = kt T + ks R + kd C (amb + sum_l kl_l (N.L_l) C_l) + kl C`
//!
//! where the sum runs over spheres `l` with `kl_l (N.L_l) > 0` whose surface is
//! the first thing hit from `P` towards `l`'s centre, `R` is the radiance along
//! `D + 2d N`, and `T` along `eta D + (eta d - sqrt(e)) N` with `e = 1 - eta^2 (1 - d^2)`
//! (black when `e <= 0`). `trace(3, ...)`: camera rays and two levels of secondary
//! rays are shaded, deeper ones return black. Mapped onto the core:
//!
//! - each sphere: `color = C`, `ka = kd` with `SceneSettings::ambient = 0.02` (so
//!   `ka C La = kd C amb`), `kd = kd`, no Blinn highlight (`ks = 0`), `emission = kl C`,
//!   `Reflection::Constant(ks)`, `Refraction::Constant { ior: ir, weight: kt }`,
//!   `shadow_transmittance = 0` (every sphere blocks, as `intersect(P,U)==l` demands);
//! - `ior = ir`: the core's `refract` (`integrators/whitted/optics.rs` in lamplight-core)
//!   is the card's formula with `eta = n_i/n_t`, and the integrator passes
//!   `eta = 1/ior` on the front face and `ior` on the back, as the card does with
//!   `ir`: `ir` is the ordinary index of the sphere's inside (1.7 for the glass);
//! - each sphere with `kl > 0` (spheres 1, 3 and 4) is also a [`PointLight`] at its
//!   centre with intensity `kl C`, [`Falloff::None`], and its own sphere as
//!   `own_object`. The core's shadow ray ends where it first meets the light's own
//!   object ([`Scene::transmittance`]), which is the card's test. It matters: the
//!   two big spheres overlap, and from the orange sphere the ray towards sphere 3's
//!   centre enters sphere 3 and then crosses sphere 4 inside it; the card counts
//!   that light as seen (stopping at the centre instead darkens 45 of the
//!   1024 pixels by up to 97/255);
//! - background `0.02`, `max_depth = 3`;
//! - the camera: eye at the origin looking along `+y`, `z` up. The card's pixel
//!   `(col, row)` of an `N x N` image looks along
//!   `U = (col - N/2, (N/2) / tan(25/114.5915590261), N/2 - row)`: a 25 degree
//!   field of view with the sample at the pixel's corner. With `pixel_offset = 0`,
//!   `lookat = (0, 1/tan(..), 0)`, `right = (1, 0, 0)`, `up = (0, 0, 1)` the core camera
//!   gives the direction `U / (N/2)`. For other aspects the horizontal extent is
//!   kept and `up` scaled by `height/width` (the window's [`Fit::Width`]).
//!
//! Remaining differences are rounding: the core moves secondary-ray origins off the
//! surface (`ray::offset_origin`, about `2^-32` of the scene scale) where the card
//! starts them on it and skips hits closer than `1e-7`, and it skips lights with
//! `N.L <= 1e-10` where the card skips `N.L <= 0`.

use lamplight_core::camera::Fit;
use lamplight_core::prelude::*;
use lamplight_core::Error;

/// One row of Heckbert's sphere table, in the card's order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CardSphere {
    /// Centre.
    pub center: [f64; 3],
    /// Colour `C`.
    pub color: [f64; 3],
    /// Radius.
    pub radius: f64,
    /// Diffuse weight (also the ambient weight).
    pub kd: f64,
    /// Mirror reflection weight.
    pub ks: f64,
    /// Transmission weight.
    pub kt: f64,
    /// Emission and light-source strength.
    pub kl: f64,
    /// Index of refraction of the inside (lamplight's `ior`).
    pub ir: f64,
}

const fn card(center: [f64; 3], color: [f64; 3], radius: f64, [kd, ks, kt, kl, ir]: [f64; 5]) -> CardSphere {
    CardSphere { center, color, radius, kd, ks, kt, kl, ir }
}

/// The card's sphere table, restored (see the module doc).
pub const SPHERES: [CardSphere; 5] = [
    card([0.0, 6.0, 0.5], [1.0, 1.0, 1.0], 0.9, [0.05, 0.2, 0.85, 0.0, 1.7]),
    card([-1.0, 8.0, -0.5], [1.0, 0.5, 0.2], 1.0, [0.7, 0.3, 0.0, 0.05, 1.2]),
    card([1.0, 8.0, -0.5], [0.1, 0.8, 0.8], 1.0, [0.3, 0.7, 0.0, 0.0, 1.2]),
    card([3.0, -6.0, 15.0], [1.0, 0.8, 1.0], 7.0, [0.0, 0.0, 0.0, 0.6, 1.5]),
    card([-3.0, -3.0, 12.0], [0.8, 1.0, 1.0], 5.0, [0.0, 0.0, 0.0, 0.5, 1.5]),
];

/// The card's ambient light and background, `amb`.
pub const AMBIENT: f64 = 0.02;

/// The card's `trace(3, ...)`.
pub const MAX_DEPTH: u32 = 3;

/// Half the field of view in radians, exactly as the card writes it:
/// `25 / 114.5915590261` (114.59... = 360/pi, so 12.5 degrees).
pub const HALF_FOV: f64 = 25.0 / 114.5915590261;

/// The card's camera (see the module doc).
pub fn camera() -> Result<Perspective, Error> {
    Perspective::window(Vec3::ZERO, Vec3::new(0.0, 1.0 / HALF_FOV.tan(), 0.0), Vec3::X, Vec3::Z, Fit::Width)?.with_pixel_offset(0.0)
}

/// Builds the scene.
pub fn build() -> Result<Scene, Error> {
    let mut scene = SceneBuilder::new(camera()?);
    scene.settings.ambient = Rgb::splat(AMBIENT);
    scene.settings.background = Rgb::splat(AMBIENT);
    scene.settings.max_depth = MAX_DEPTH;
    for s in &SPHERES {
        let color = Rgb::from_array(s.color);
        let material = scene.material(Material {
            color: Texture::Constant(color),
            ka: Rgb::splat(s.kd),
            kd: Rgb::splat(s.kd),
            ks: Rgb::ZERO,
            shininess: 1.0,
            emission: color * s.kl,
            two_sided: false,
            one_sided: false,
            reflection: Reflection::Constant(Rgb::splat(s.ks)),
            refraction: Refraction::Constant { ior: s.ir, weight: Rgb::splat(s.kt) },
            shadow_transmittance: Rgb::ZERO,
            roughness: 0.0,
            roughness_v: None,
            distribution: Default::default(),
            model: None,
            textures: None,
            pbr: None,
            normal_map: None,
            bump: None,
            map_shadowing: false,
            alpha: None,
            blend: None,
        })?;
        let center = Vec3::from_array(s.center);
        let index = scene.object(Sphere::new(center, s.radius)?, material)?;
        if s.kl > 0.0 {
            let mut light = PointLight::new(center, color * s.kl)?.with_falloff(Falloff::None);
            light.own_object = Some(index);
            scene.light(light);
        }
    }
    scene.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_physically_plausible() {
        assert_eq!(SPHERES.len() * 12, 60);
        for s in &SPHERES {
            assert!(s.color.iter().all(|c| (0.0..=1.0).contains(c)), "{s:?}");
            for k in [s.kd, s.ks, s.kt, s.kl] {
                assert!((0.0..=1.0).contains(&k), "{s:?}");
            }
            assert!(s.kd + s.ks + s.kt <= 1.1 + 1e-12, "{s:?}");
            assert!(s.radius > 0.0 && s.ir > 1.0);
        }
    }

    #[test]
    fn lights_are_the_emitting_spheres() {
        let scene = build().unwrap();
        assert_eq!(scene.objects.len(), 5);
        assert_eq!(scene.lights.len(), 3, "spheres 1, 3 and 4 have kl > 0");
        let owners: Vec<_> = scene.lights.iter().map(|l| l.own_object()).collect();
        assert_eq!(owners, [Some(1), Some(3), Some(4)]);
        // A constant light: the same radiance near and far.
        let near = scene.lights[1].illuminate(Vec3::new(3.0, -6.0, 7.0)).unwrap();
        let far = scene.lights[1].illuminate(Vec3::new(3.0, 60.0, 15.0)).unwrap();
        assert_eq!(near.radiance, far.radiance);
        assert_eq!(near.radiance, Rgb::new(0.6, 0.48, 0.6));
        let glass = &scene.materials[scene.objects[0].material];
        assert!(matches!(glass.refraction, Refraction::Constant { ior, .. } if ior == 1.7));
        assert_eq!(scene.settings.max_depth, 3);
    }

    #[test]
    fn camera_rays_match_the_cards_pixel_directions() {
        let cam = camera().unwrap();
        for n in [32u32, 64, 100] {
            let half = (n / 2) as f64;
            for (col, row) in [(0, 0), (n / 2, n / 2), (n - 1, 3), (5, n - 1)] {
                let u = Vec3::new(col as f64 - half, half / HALF_FOV.tan(), half - row as f64).normalize();
                let ray = cam.ray(col as f64, row as f64, n, n, (0.5, 0.5));
                assert!((ray.dir - u).length() < 1e-15, "n {n} pixel ({col}, {row})");
                assert_eq!(ray.origin, Vec3::ZERO);
            }
        }
    }

    #[test]
    fn wide_images_keep_the_horizontal_field() {
        let cam = camera().unwrap();
        let left = cam.ray(0.0, 32.0, 128, 64, (0.5, 0.5)).dir;
        let top = cam.ray(64.0, 0.0, 128, 64, (0.5, 0.5)).dir;
        assert!((left.x / left.y + HALF_FOV.tan()).abs() < 1e-14);
        assert!((top.z / top.y - HALF_FOV.tan() / 2.0).abs() < 1e-14);
    }
}
