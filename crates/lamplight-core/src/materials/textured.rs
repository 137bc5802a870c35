//! Texturable material parameters, one mechanism for all of them.
//!
//! A material kind reads each texturable parameter through [`color_param`] or
//! [`scalar_param`]: a constant lands in the material's field as before, a
//! texture in [`super::Material::textures`] as a `(Slot, Texture)` pair. At a hit,
//! [`super::Material::at`] evaluates every pair and writes the value into its
//! slot's field, so the integrators and the BSDF mapping read plain numbers and
//! need no per-parameter code. A material without textures is borrowed as it is.
//!
//! Values from textures are clamped where the field requires it: colours to
//! `>= 0`, `shininess` to `>= 0`, `roughness`, `metallic`, `specular`, `transmission` and the principled model's weights to `[0, 1]`. A
//! scalar slot reads the texture's first channel (an image's `channel` chooses it).

use super::{Material, Texture, Textures};
use crate::math::Rgb;
use crate::params::{ParamResult, Params};

/// A material field a texture can drive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// `ka`.
    Ka,
    /// `kd`.
    Kd,
    /// `ks`.
    Ks,
    /// `shininess`.
    Shininess,
    /// `emission`.
    Emission,
    /// `shadow_transmittance`.
    ShadowTransmittance,
    /// `roughness`.
    Roughness,
    /// The metallic-roughness model's `metallic` ([`super::pbr`]).
    Metallic,
    /// Its `specular` strength (`KHR_materials_specular`).
    Specular,
    /// Its `specular_color`.
    SpecularColor,
    /// A scalar of the principled model ([`super::principled`]).
    Principled(super::principled::Scalar),
    /// Its `transmission` (`KHR_materials_transmission`).
    Transmission,
}

impl Slot {
    /// Writes `value` into the slot's field of `m`.
    #[inline]
    pub fn apply(self, m: &mut Material, value: Rgb) {
        let colour = value.max(Rgb::ZERO);
        match self {
            Slot::Ka => m.ka = colour,
            Slot::Kd => m.kd = colour,
            Slot::Ks => m.ks = colour,
            Slot::Emission => m.emission = colour,
            Slot::ShadowTransmittance => m.shadow_transmittance = colour,
            Slot::Shininess => m.shininess = value.x.max(0.0),
            Slot::Roughness => m.roughness = value.x.clamp(0.0, 1.0),
            Slot::Metallic => {
                if let Some(pbr) = &mut m.pbr {
                    pbr.metallic = value.x.clamp(0.0, 1.0);
                }
            }
            Slot::Specular => {
                if let Some(pbr) = &mut m.pbr {
                    pbr.specular = value.x.clamp(0.0, 1.0);
                }
            }
            Slot::SpecularColor => {
                if let Some(pbr) = &mut m.pbr {
                    pbr.specular_color = colour;
                }
            }
            Slot::Principled(scalar) => {
                match &mut m.model {
                    Some(super::Model::Principled(p)) => scalar.set(p, value.x.clamp(0.0, 1.0)),
                    // `diff_trans` runs from 0 to 2.
                    Some(super::Model::PrincipledThin(p)) => {
                        let max = if scalar == super::principled::Scalar::DiffTrans { 2.0 } else { 1.0 };
                        scalar.set_thin(p, value.x.clamp(0.0, max))
                    }
                    _ => {}
                }
            }
            Slot::Transmission => {
                if let Some(pbr) = &mut m.pbr {
                    pbr.transmission = value.x.clamp(0.0, 1.0);
                }
            }
        }
    }
}

/// A colour parameter that may be a texture: the constant (or `default`), with
/// a texture pushed to `maps` for `slot`.
pub fn color_param(
    p: &mut Params<'_>,
    textures: &Textures<'_>,
    key: &str,
    default: Rgb,
    slot: Slot,
    maps: &mut Vec<(Slot, Texture)>,
) -> ParamResult<Rgb> {
    Ok(constant_or_map(textures.read(p, key)?, default, slot, maps))
}

/// A scalar parameter that may be a texture (see [`color_param`]).
pub fn scalar_param(
    p: &mut Params<'_>,
    textures: &Textures<'_>,
    key: &str,
    default: f64,
    slot: Slot,
    maps: &mut Vec<(Slot, Texture)>,
) -> ParamResult<f64> {
    Ok(constant_or_map(textures.read_scalar(p, key)?, Rgb::splat(default), slot, maps).x)
}

fn constant_or_map(t: Option<Texture>, default: Rgb, slot: Slot, maps: &mut Vec<(Slot, Texture)>) -> Rgb {
    match t {
        None => default,
        Some(Texture::Constant(c)) => c,
        Some(t) => {
            maps.push((slot, t));
            default
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ShadingPoint;
    use super::*;
    use crate::math::Vec3;

    #[test]
    fn every_slot_takes_its_textures_value_at_the_point() {
        let checker = Texture::Checker { size: 1.0, even: Rgb::splat(0.25), odd: Rgb::splat(0.75), offset: Vec3::ZERO };
        let maps = [Slot::Ka, Slot::Kd, Slot::Ks, Slot::Shininess, Slot::Emission, Slot::ShadowTransmittance, Slot::Roughness];
        let m = Material { textures: Some(maps.iter().map(|&s| (s, checker.clone())).collect()), ..Material::default() };
        let even = m.at(&ShadingPoint::at(Vec3::new(0.5, 0.5, 0.5)));
        assert_eq!((even.ka, even.kd, even.ks, even.emission), (Rgb::splat(0.25), Rgb::splat(0.25), Rgb::splat(0.25), Rgb::splat(0.25)));
        assert_eq!((even.shininess, even.roughness, even.shadow_transmittance), (0.25, 0.25, Rgb::splat(0.25)));
        assert!(even.textures.is_none(), "the evaluated material is constant");
        let odd = m.at(&ShadingPoint::at(Vec3::new(1.5, 0.5, 0.5)));
        assert_eq!(odd.kd, Rgb::splat(0.75));
        let plain = Material::default();
        assert!(matches!(plain.at(&ShadingPoint::at(Vec3::ZERO)), std::borrow::Cow::Borrowed(_)));
    }
}
