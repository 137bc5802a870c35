//! glTF metallic-roughness materials mapped onto the nearest lamplight
//! [`Material`] (a Whitted tracer has no glossy lobes, so the mapping keeps
//! the colours and turns roughness into a Blinn exponent).
//!
//! With base colour `B` (`baseColorFactor` rgb), metallic `m` and roughness `r`:
//!
//! | glTF | lamplight |
//! |---|---|
//! | `B`, `m` | `color = 1`, `kd = (1 - m) B`, `ka = 0.1 kd` |
//! | highlight | `ks = (1 - m) 0.04 + m B` (the glTF specular colour at normal incidence) |
//! | `r` | `shininess = clamp(2 / max(r^4, 1e-4) - 2, 1, 10000)`: the Blinn exponent whose lobe matches a GGX lobe of `alpha = r^2` (`n = 2 / alpha^2 - 2`) |
//! | `m > 0` | mirror `Reflection::Constant(m B (1 - r))`: a conductor tinted by its base colour, fading as it roughens since a sharp mirror of a rough metal would look wrong |
//! | `metallicRoughnessTexture` | `m = 0`: the texture is unsupported, and the factor alone (1 by default, as such assets leave it) would make the whole surface bare metal, black where no light is mirrored |
//! | `emissiveFactor` | `emission`; 0 when an `emissiveTexture` modulates it (textures are unsupported, and the factor alone would make the whole surface glow: glTF assets set it to 1 and paint the glowing parts in the texture) |
//! | `KHR_materials_transmission` `t > 0` | `Material::glass(ior, ..)` (index from `KHR_materials_ior`, default 1.5) with `kd`, `ka` scaled by `1 - t`, shadow rays passing `t B`, and GGX `roughness = r^2` (glTF's `alpha`; rough glass in the path tracer) |
//!
//! `KHR_materials_ior` without transmission changes only the dielectric F0,
//! which the fixed 0.04 above already stands for, so it is read but unused.
//! Textures (base colour, metallic-roughness, normal, occlusion, emissive,
//! transmission) and alpha blending/masking are unsupported: each kind is
//! reported once as a warning. Numbers are clamped to their valid range
//! (non-finite ones become 0) so no NaN reaches the renderer.

use lamplight_core::materials::{Material, Reflection, Texture};
use lamplight_core::math::Rgb;

use super::Warnings;

/// A finite, non-negative number from an `f32` of the file.
fn clean(x: f32) -> f64 {
    if x.is_finite() {
        f64::from(x.max(0.0))
    } else {
        0.0
    }
}

fn rgb(c: [f32; 3]) -> Rgb {
    Rgb::new(clean(c[0]), clean(c[1]), clean(c[2]))
}

/// The Blinn exponent of roughness `r` (module doc).
pub(super) fn shininess(roughness: f64) -> f64 {
    (2.0 / roughness.powi(4).max(1e-4) - 2.0).clamp(1.0, 10_000.0)
}

/// Maps one glTF material (module doc), adding a warning per unsupported kind.
pub(super) fn map(m: &gltf::Material, warnings: &mut Warnings) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let textures = [
        ("baseColorTexture", pbr.base_color_texture().is_some()),
        ("metallicRoughnessTexture", pbr.metallic_roughness_texture().is_some()),
        ("normalTexture", m.normal_texture().is_some()),
        ("occlusionTexture", m.occlusion_texture().is_some()),
        ("emissiveTexture", m.emissive_texture().is_some()),
        ("transmissionTexture", m.transmission().is_some_and(|t| t.transmission_texture().is_some())),
    ];
    for (kind, present) in textures {
        if present {
            warnings.once(format!("glTF {kind} ignored: textures are not supported"));
        }
    }
    if m.alpha_mode() != gltf::material::AlphaMode::Opaque {
        warnings.once("glTF alphaMode BLEND/MASK ignored: surfaces are opaque".to_string());
    }
    let [r, g, b, _alpha] = pbr.base_color_factor();
    let base = rgb([r, g, b]).min(Rgb::ONE);
    let metal = if pbr.metallic_roughness_texture().is_some() {
        warnings.once(
            "glTF metallicFactor read as 0 where a metallicRoughnessTexture modulates it: without the texture the whole surface \
             would be bare metal"
                .to_string(),
        );
        0.0
    } else {
        clean(pbr.metallic_factor()).min(1.0)
    };
    let rough = clean(pbr.roughness_factor()).min(1.0);
    let kd = (1.0 - metal) * base;
    let ks = Rgb::splat(0.04 * (1.0 - metal)) + metal * base;
    let shine = shininess(rough);
    let emission = if m.emissive_texture().is_some() {
        warnings.once(
            "glTF emissiveFactor ignored where an emissiveTexture modulates it: without the texture the whole surface would glow"
                .to_string(),
        );
        Rgb::ZERO
    } else {
        rgb(m.emissive_factor())
    };
    let transmission = m.transmission().map_or(0.0, |t| clean(t.transmission_factor()).min(1.0));
    if transmission > 0.0 {
        let ior = m.ior().map(f64::from).filter(|i| i.is_finite() && *i > 0.0).unwrap_or(1.5);
        let glass = Material::glass(ior, ks.max_element(), shine);
        return Material {
            kd: (1.0 - transmission) * kd,
            ka: 0.1 * (1.0 - transmission) * kd,
            emission,
            shadow_transmittance: transmission * base,
            roughness: rough * rough,
            ..glass
        };
    }
    Material {
        color: Texture::Constant(Rgb::ONE),
        ka: 0.1 * kd,
        kd,
        ks,
        shininess: shine,
        emission,
        reflection: if metal > 0.0 { Reflection::Constant(metal * base * (1.0 - rough)) } else { Reflection::None },
        ..Material::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_maps_to_the_ggx_matched_exponent() {
        assert_eq!(shininess(1.0), 1.0);
        assert_eq!(shininess(0.5), 30.0);
        assert_eq!(shininess(0.0), 10_000.0);
    }
}
