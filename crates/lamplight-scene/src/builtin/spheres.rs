//! `spheres`: the POV-Ray comparison scene of `shared/anchors/povray/SCENES.md`.
//!
//! 100 spheres of radius 0.4 on a 10x10 grid over a 12x12 checkered floor: sphere
//! `(i, k)` at `(-4.5 + i, 0.4, -4.5 + k)`, material by `m = (i + 3k) mod 5`:
//! plastic in palette colour `(i + 2k) mod 6` for `m < 3`, a Fresnel mirror for
//! `m = 3`, clear glass for `m = 4`. Two inverse-square point lights, ambient 1,
//! background (0.40, 0.50, 0.65), camera at (0, 6.5, 10.5) looking at (0, 0, 0.8)
//! with a 40 degree vertical field of view; POV-Ray's depth limit 5.

use lamplight_core::prelude::*;
use lamplight_core::Error;

/// Palette of the plastic spheres (linear RGB).
const PALETTE: [[f64; 3]; 6] =
    [[0.80, 0.20, 0.20], [0.20, 0.70, 0.25], [0.20, 0.35, 0.80], [0.85, 0.75, 0.20], [0.70, 0.30, 0.75], [0.90, 0.90, 0.90]];

/// The mirror of both POV-Ray scenes: opaque, reflectance `0.8 + 0.2 F` (ior 1.5),
/// white highlight 0.8 with exponent 300.
pub(crate) fn pov_mirror() -> Material {
    Material {
        color: Texture::Constant(Rgb::ONE),
        ka: Rgb::ZERO,
        kd: Rgb::ZERO,
        ks: Rgb::splat(0.8),
        shininess: 300.0,
        reflection: Reflection::Dielectric { ior: 1.5, min: 0.8, max: 1.0 },
        ..Material::default()
    }
}

/// Builds the scene.
pub fn build() -> Result<Scene, Error> {
    let camera = Perspective::look_at(Vec3::new(0.0, 6.5, 10.5), Vec3::new(0.0, 0.0, 0.8), Vec3::Y, Fov::VerticalDeg(40.0))?;
    let mut scene = SceneBuilder::new(camera);
    scene.settings.ambient = Rgb::ONE;
    scene.settings.background = Rgb::new(0.40, 0.50, 0.65);
    scene.settings.max_depth = 5;

    let floor = scene.material(Material {
        color: Texture::Checker { size: 1.0, even: Rgb::splat(0.75), odd: Rgb::splat(0.25), offset: Vec3::new(0.0, 0.5, 0.0) },
        ka: Rgb::splat(0.1),
        kd: Rgb::splat(0.8),
        ks: Rgb::ZERO,
        ..Material::default()
    })?;
    scene.object(Rectangle::horizontal(0.0, -6.0, 6.0, -6.0, 6.0)?, floor)?;

    let plastics = PALETTE
        .iter()
        .map(|c| scene.material(Material::plastic(Rgb::from_array(*c), 0.1, 0.7, 0.3, 40.0)))
        .collect::<Result<Vec<_>, _>>()?;
    let mirror = scene.material(pov_mirror())?;
    let glass = scene.material(Material::glass(1.5, 0.8, 300.0))?;
    for k in 0..10 {
        for i in 0..10 {
            let center = Vec3::new(-4.5 + i as f64, 0.4, -4.5 + k as f64);
            let material = match (i + 3 * k) % 5 {
                3 => mirror,
                4 => glass,
                _ => plastics[(i + 2 * k) % 6],
            };
            scene.object(Sphere::new(center, 0.4)?, material)?;
        }
    }
    scene.light(PointLight::new(Vec3::new(-6.0, 9.0, 7.0), Rgb::new(160.0, 150.0, 140.0))?);
    scene.light(PointLight::new(Vec3::new(7.0, 6.0, -4.0), Rgb::new(50.0, 55.0, 65.0))?);
    scene.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn has_the_hundred_spheres_and_floor() {
        let scene = build().unwrap();
        assert_eq!(scene.objects.len(), 101);
        assert_eq!(scene.lights.len(), 2);
        // SCENES.md table: row k = 0 reads D0 D1 D2 M G D5 D0 D1 M G.
        let mirror = scene.objects[1 + 3].material;
        let glass = scene.objects[1 + 4].material;
        assert!(matches!(scene.materials[mirror].reflection, Reflection::Dielectric { min, .. } if min == 0.8));
        assert!(matches!(scene.materials[glass].refraction, Refraction::Fresnel { ior } if ior == 1.5));
        assert_eq!(scene.materials[scene.objects[1 + 5].material].color, Texture::Constant(Rgb::new(0.9, 0.9, 0.9)));
    }
}
