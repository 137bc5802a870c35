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

/// A material field a texture can drive: a name (for comparisons and debug
/// output) and the function that writes a texture's value into the field.
///
/// The lecture's fields, which every material has, have their slots here
/// ([`Slot::KA`] ... [`Slot::ROUGHNESS`]); a kind with fields of its own states
/// their slots in its own file ([`super::pbr::METALLIC`],
/// [`super::principled::slot`]), so that a new texturable parameter touches
/// only its kind's file. Two slots are equal when their names are: each name is
/// given once (a test lists them all).
#[derive(Clone, Copy)]
pub struct Slot {
    name: &'static str,
    set: fn(&mut Material, Rgb),
}

impl PartialEq for Slot {
    fn eq(&self, other: &Slot) -> bool {
        self.name == other.name
    }
}

impl Eq for Slot {}

impl std::fmt::Debug for Slot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Slot({})", self.name)
    }
}

impl Slot {
    /// The slot `name` whose texture values `set` writes into a material.
    pub const fn new(name: &'static str, set: fn(&mut Material, Rgb)) -> Slot {
        Slot { name, set }
    }

    /// Its name (`"kd"`, `"pbr.metallic"`).
    pub fn name(self) -> &'static str {
        self.name
    }

    /// Writes `value` into the slot's field of `m`.
    #[inline]
    pub fn apply(self, m: &mut Material, value: Rgb) {
        (self.set)(m, value)
    }

    /// `ka`.
    pub const KA: Slot = Slot::new("ka", |m, v| m.ka = v.max(Rgb::ZERO));
    /// `kd`.
    pub const KD: Slot = Slot::new("kd", |m, v| m.kd = v.max(Rgb::ZERO));
    /// `ks`.
    pub const KS: Slot = Slot::new("ks", |m, v| m.ks = v.max(Rgb::ZERO));
    /// `shininess`.
    pub const SHININESS: Slot = Slot::new("shininess", |m, v| m.shininess = v.x.max(0.0));
    /// `emission`.
    pub const EMISSION: Slot = Slot::new("emission", |m, v| m.emission = v.max(Rgb::ZERO));
    /// `shadow_transmittance`.
    pub const SHADOW_TRANSMITTANCE: Slot = Slot::new("shadow_transmittance", |m, v| m.shadow_transmittance = v.max(Rgb::ZERO));
    /// `roughness` (the lecture's, which the metallic-roughness model reads too).
    pub const ROUGHNESS: Slot = Slot::new("roughness", |m, v| m.roughness = v.x.clamp(0.0, 1.0));
    /// `roughness_v`, the anisotropic roughness along the second tangent.
    pub const ROUGHNESS_V: Slot = Slot::new("roughness_v", |m, v| m.roughness_v = Some(v.x.clamp(0.0, 1.0)));
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
        let maps = [Slot::KA, Slot::KD, Slot::KS, Slot::SHININESS, Slot::EMISSION, Slot::SHADOW_TRANSMITTANCE, Slot::ROUGHNESS];
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

    /// Slots compare by name, so no two may share one: every slot of every kind.
    #[test]
    fn every_slot_has_its_own_name() {
        use super::super::{pbr, principled, principled_thin};
        let mut all = vec![
            Slot::KA,
            Slot::KD,
            Slot::KS,
            Slot::SHININESS,
            Slot::EMISSION,
            Slot::SHADOW_TRANSMITTANCE,
            Slot::ROUGHNESS,
            Slot::ROUGHNESS_V,
        ];
        all.extend([pbr::METALLIC, pbr::SPECULAR, pbr::SPECULAR_COLOR, pbr::TRANSMISSION]);
        all.extend(principled::Scalar::ALL.map(principled::slot));
        all.push(principled_thin::ETA);
        let mut names: Vec<&str> = all.iter().map(|s| s.name()).collect();
        names.sort_unstable();
        let count = names.len();
        names.dedup();
        assert_eq!(names.len(), count, "{names:?}");
    }
}
