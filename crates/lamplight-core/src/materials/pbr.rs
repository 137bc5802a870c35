//! `pbr`: the glTF 2.0 metallic-roughness material, as a scene kind and as
//! what the glTF importer maps its materials to.
//!
//! The path tracer's BSDF is the specification's (Appendix B,
//! [`crate::bsdfs::metallic_roughness`]). The Whitted tracer has no glossy
//! lobes; it sees the lecture's terms derived from the same numbers
//! ([`derive_lecture_terms`]): with base colour `C`, metallic `m`, roughness `r`,
//!
//! | lecture | from |
//! |---|---|
//! | `kd` (times `C`) | `1 - m` |
//! | `ks` | `(1 - m) f0_d + m C`, the specular colour at normal incidence (`f0_d = 0.04` without `ior`, `specular`) |
//! | `shininess` | `clamp(2 / max(r^4, 1e-4) - 2, 1, 10000)`: the Blinn exponent of GGX `alpha = r^2` |
//! | mirror | `m C (1 - r)`: a metal mirrors its base colour, fading as it roughens |
//! | `ka` (times `C`) | `0.1 ((1 - m) + m r)`: the diffuse part, and the part of a metal's reflection its roughness spreads, both under the ambient light (the importers' `ka = 0.1 kd` convention), so that under a uniform surround the terms add to `C` |
//! | with transmission `t > 0` | `kd = (1 - m)(1 - t)`, `ka` likewise, and a straight refraction (index 1) of weight `(1 - m) t C`, which shadow rays pass too |
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `base_color` | colour or texture | 1 | `C` (glTF `baseColorFactor x baseColorTexture`) |
//! | `metallic` | number or texture | 0 | `m`, 0 to 1 (glTF's metallicRoughness texture's blue channel) |
//! | `roughness` | number or texture | 0.5 | perceptual `r`, 0 to 1; GGX `alpha = r^2` (the texture's green channel) |
//! | `ior` | number | 1.5 | the dielectric's index (`KHR_materials_ior`): `f0_d = ((ior - 1) / (ior + 1))^2` |
//! | `specular` | number or texture | 1 | `KHR_materials_specular`'s `specularFactor` x `specularTexture.a`: scales `f0_d` and sets `f90_d` |
//! | `specular_color` | colour or texture | 1 | `specularColorFactor` x `specularColorTexture`: tints `f0_d` (capped at 1) |
//! | `transmission` | number or texture | 0 | `KHR_materials_transmission`'s `transmissionFactor` x `transmissionTexture.r`: the share of the dielectric's diffuse base that is thin-walled microfacet transmission, tinted by `C` |
//! | `emission` | colour or texture | 0 | emitted radiance |
//! | `emission_strength` | number | 1 | multiplies `emission` (`KHR_materials_emissive_strength`) |
//! | `two_sided` | boolean | false | emit from both sides |
//! | `normal_map`, `normal_scale` | texture, number | none, 1 | a tangent-space normal map ([`super::normal_map`]) |
//! | `alpha`, `alpha_cutoff` | number or texture, number | none, 0.5 | a cut-out mask ([`super::alpha`]) |
//!
//! Occlusion textures are not read: a path tracer computes the occlusion they
//! approximate.

use std::sync::Arc;

use super::textured::{scalar_param, Slot};
use super::{Material, MaterialKind, Reflection, Refraction, Texture, Textures, ToBsdf};
use crate::bsdfs::metallic_roughness::MetallicRoughness;
use crate::bsdfs::{microfacet, Bsdf, Lobe};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// The metallic-roughness model's own numbers; the base colour is the
/// material's `color`, the roughness its `roughness`.
#[derive(Clone, Debug, PartialEq)]
pub struct Pbr {
    /// Metallic `m`, 0 to 1.
    pub metallic: f64,
    /// The dielectric's index of refraction (`KHR_materials_ior`), 1.5 by default.
    pub ior: f64,
    /// `KHR_materials_specular`'s strength, 0 to 1 (1 by default).
    pub specular: f64,
    /// `KHR_materials_specular`'s colour (1 by default).
    pub specular_color: Rgb,
    /// `KHR_materials_transmission`'s transmission `t`, 0 to 1 (0 by default):
    /// the share of the dielectric's diffuse base that is a thin-walled
    /// microfacet BTDF ([`crate::bsdfs::metallic_roughness`]).
    pub transmission: f64,
}

impl Pbr {
    /// Metallic `metallic` and glTF's dielectric (no extensions).
    pub fn new(metallic: f64) -> Pbr {
        Pbr { metallic: metallic.clamp(0.0, 1.0), ior: 1.5, specular: 1.0, specular_color: Rgb::ONE, transmission: 0.0 }
    }

    /// The dielectric's Fresnel for the BSDF.
    pub fn specular(&self) -> crate::bsdfs::metallic_roughness::Specular {
        crate::bsdfs::metallic_roughness::Specular::khr(self.ior, self.specular, self.specular_color)
    }

    /// Whether nothing of its own varies over the surface.
    pub fn is_constant(&self) -> bool {
        true
    }

    /// Whether it reads surface coordinates.
    pub fn needs_coords(&self) -> bool {
        false
    }
}

/// The Blinn exponent whose lobe matches GGX of `alpha = r^2` (`n = 2 / alpha^2 - 2`), clamped.
pub fn shininess(roughness: f64) -> f64 {
    (2.0 / roughness.powi(4).max(1e-4) - 2.0).clamp(1.0, 10_000.0)
}

/// Sets the lecture's terms of a metallic-roughness material `m` (module
/// documentation) from its constant colour, `metallic` and `roughness`.
pub fn derive_lecture_terms(m: &mut Material) {
    let Some(pbr) = &m.pbr else { return };
    let metal = pbr.metallic.clamp(0.0, 1.0);
    let base = m.color.constant().unwrap_or(Rgb::ONE).clamp(Rgb::ZERO, Rgb::ONE);
    let r = m.roughness.clamp(0.0, 1.0);
    m.kd = Rgb::splat(1.0 - metal);
    m.ka = Rgb::splat(0.1 * ((1.0 - metal) + metal * r));
    m.ks = crate::bsdfs::metallic_roughness::f0(base, metal, pbr.specular());
    m.shininess = shininess(r);
    m.reflection = if metal > 0.0 { Reflection::Constant(metal * base * (1.0 - r)) } else { Reflection::None };
    // The thin wall: what the diffuse base gives up goes straight through. (Set
    // at every point: a transmission texture varies it from the material's.)
    let t = pbr.transmission.clamp(0.0, 1.0);
    let through = (1.0 - metal) * t * base;
    if t > 0.0 {
        m.kd = Rgb::splat((1.0 - metal) * (1.0 - t));
        m.ka = Rgb::splat(0.1 * ((1.0 - metal) * (1.0 - t) + metal * r));
    }
    (m.refraction, m.shadow_transmittance) =
        if through != Rgb::ZERO { (Refraction::Constant { ior: 1.0, weight: through }, through) } else { (Refraction::None, Rgb::ZERO) };
}

/// The texture slot of `metallic` (first channel, clamped to `[0, 1]`).
pub const METALLIC: Slot = Slot::new("pbr.metallic", |m, v| {
    if let Some(pbr) = &mut m.pbr {
        pbr.metallic = v.x.clamp(0.0, 1.0);
    }
});
/// The texture slot of `specular` (first channel, clamped to `[0, 1]`).
pub const SPECULAR: Slot = Slot::new("pbr.specular", |m, v| {
    if let Some(pbr) = &mut m.pbr {
        pbr.specular = v.x.clamp(0.0, 1.0);
    }
});
/// The texture slot of `specular_color` (clamped to `>= 0`).
pub const SPECULAR_COLOR: Slot = Slot::new("pbr.specular_color", |m, v| {
    if let Some(pbr) = &mut m.pbr {
        pbr.specular_color = v.max(Rgb::ZERO);
    }
});
/// The texture slot of `transmission` (first channel, clamped to `[0, 1]`).
pub const TRANSMISSION: Slot = Slot::new("pbr.transmission", |m, v| {
    if let Some(pbr) = &mut m.pbr {
        pbr.transmission = v.x.clamp(0.0, 1.0);
    }
});

/// A metallic-roughness material: base colour `base`, `metallic`, perceptual
/// `roughness`, emission, and textures for any of them in `textures`.
pub fn material(base: Texture, metallic: f64, roughness: f64, emission: Rgb, textures: Vec<(Slot, Texture)>) -> Material {
    let mut m = Material {
        color: base,
        roughness: roughness.clamp(0.0, 1.0),
        emission,
        textures: (!textures.is_empty()).then(|| Arc::from(textures)),
        pbr: Some(Pbr::new(metallic)),
        ..Material::default()
    };
    derive_lecture_terms(&mut m);
    m
}

/// `pbr`.
pub const KIND: MaterialKind = Kind {
    name: "pbr",
    summary: "the glTF 2.0 metallic-roughness material: Lambert diffuse and GGX specular mixed by `metallic`, Schlick Fresnel",
    params: super::surface_params![
        Param::new("base_color", T::Texture, "1", "", "base colour `C`"),
        Param::new("metallic", T::ScalarTexture, "0", "0 to 1", "metalness `m`"),
        Param::new("roughness", T::ScalarTexture, "0.5", "0 to 1", "perceptual roughness `r`; GGX `alpha = r^2`"),
        Param::new("ior", T::Number, "1.5", "> 0", "the dielectric's index of refraction (`KHR_materials_ior`)"),
        Param::new("specular", T::ScalarTexture, "1", "0 to 1", "strength of the dielectric's reflection (`KHR_materials_specular`)"),
        Param::new(
            "specular_color",
            T::Texture,
            "1",
            "",
            "tint of the dielectric's reflection at normal incidence (`KHR_materials_specular`)",
        ),
        Param::new(
            "transmission",
            T::ScalarTexture,
            "0",
            "0 to 1",
            "share of the dielectric's diffuse base that is thin-walled GGX transmission tinted by the base colour (`KHR_materials_transmission`)",
        ),
        super::EMISSION_PARAM,
        Param::new("emission_strength", T::Number, "1", ">= 0", "multiplies `emission` (`KHR_materials_emissive_strength`)"),
        super::TWO_SIDED_PARAM,
        super::sided::SIDED_PARAM,
    ],
    build,
};

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let base = textures.read(p, "base_color")?.unwrap_or(Texture::Constant(Rgb::ONE));
    let mut maps = Vec::new();
    let metallic = scalar_param(p, textures, "metallic", 0.0, METALLIC, &mut maps)?;
    let roughness = scalar_param(p, textures, "roughness", 0.5, Slot::ROUGHNESS, &mut maps)?;
    for (key, x) in [("metallic", metallic), ("roughness", roughness)] {
        if !(0.0..=1.0).contains(&x) {
            return Err(p.key_error(key, format!("must be between 0 and 1, got {x}")));
        }
    }
    let ior = p.number_or("ior", 1.5)?;
    if !(ior.is_finite() && ior > 0.0) {
        return Err(p.key_error("ior", format!("must be a positive number, got {ior}")));
    }
    let specular = scalar_param(p, textures, "specular", 1.0, SPECULAR, &mut maps)?;
    if !(0.0..=1.0).contains(&specular) {
        return Err(p.key_error("specular", format!("must be between 0 and 1, got {specular}")));
    }
    let specular_color = super::textured::color_param(p, textures, "specular_color", Rgb::ONE, SPECULAR_COLOR, &mut maps)?;
    let transmission = scalar_param(p, textures, "transmission", 0.0, TRANSMISSION, &mut maps)?;
    if !(0.0..=1.0).contains(&transmission) {
        return Err(p.key_error("transmission", format!("must be between 0 and 1, got {transmission}")));
    }
    let strength = p.number_or("emission_strength", 1.0)?;
    if !(strength.is_finite() && strength >= 0.0) {
        return Err(p.key_error("emission_strength", format!("must be a non-negative number, got {strength}")));
    }
    let emission = match textures.read(p, "emission")? {
        None => Rgb::ZERO,
        Some(Texture::Constant(c)) => c * strength,
        Some(t) => {
            let scaled = if strength == 1.0 { t } else { Texture::Scale(Arc::new([t, Texture::Constant(Rgb::splat(strength))])) };
            maps.push((Slot::EMISSION, scaled));
            Rgb::ZERO
        }
    };
    let mut m = material(base, metallic, roughness, emission, maps);
    if let Some(pbr) = &mut m.pbr {
        (pbr.ior, pbr.specular, pbr.specular_color, pbr.transmission) = (ior, specular, specular_color, transmission);
    }
    derive_lecture_terms(&mut m);
    m.one_sided = super::sided::read(p)?;
    super::finish_emitting(m, p, textures)
}

/// The path tracer sees the glTF BRDF ([`crate::bsdfs::metallic_roughness`]) of base
/// colour `C`, `metallic` and `alpha = max(roughness^2, 0.001)` as the only lobe.
impl ToBsdf for Pbr {
    #[inline]
    fn bsdf(&self, material: &Material, color: Rgb, _: bool) -> Bsdf {
        let alpha = (material.roughness * material.roughness).max(microfacet::MIN_ALPHA);
        let lobe = MetallicRoughness {
            base: color.min(Rgb::ONE),
            metallic: self.metallic,
            spec: self.specular(),
            alpha,
            transmission: self.transmission,
        };
        Bsdf::new(&[Lobe::MetallicRoughness(lobe)])
    }
}
