//! `plastic`: a diffuse base under a smooth or rough dielectric coating, Mitsuba 3's
//! `plastic` and `roughplastic` ([`crate::bsdfs::plastic`], [`crate::bsdfs::rough_plastic`]).
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `diffuse_reflectance` | colour or texture | 0.5 | albedo `d` of the base |
//! | `specular_reflectance` | colour | 1 | scales the coating's reflection (1 for a physical coating) |
//! | `int_ior`, `ext_ior` | number | 1.49, 1.00028 | indices inside the coating and outside; `eta = int_ior / ext_ior` |
//! | `nonlinear` | boolean | false | the internal bounces shift the colour: `d / (1 - d F_dr)` instead of `d / (1 - F_dr)` |
//! | `roughness` | number | 0 | the coating's microfacet roughness `alpha`; 0 is the smooth coating |
//! | `distribution` | string | `"ggx"` | `"ggx"` or `"beckmann"` (a rough coating's normal distribution) |
//! | `emission`, `two_sided` | colour or texture, boolean | 0, false | emitted radiance, from both sides |
//! | `sided` | string | `"both"` | `"front"`: scatters only on the front side, black from the back (Mitsuba's plastic is) |
//! | `normal_map`, `bump`, `alpha` | | | as for `phong` |
//!
//! The Whitted tracer sees the base as its diffuse term and the coating as a
//! Fresnel mirror (smooth) or a Blinn highlight of the matching exponent (rough).

use std::sync::Arc;

use super::textured::Slot;
use super::{Material, MaterialKind, Model, Reflection, Texture, Textures, ToBsdf};
use crate::bsdfs::plastic::{Coating, Plastic};
use crate::bsdfs::rough_plastic::{self, RoughPlastic};
use crate::bsdfs::{Bsdf, Distribution, Lobe, Microfacet};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// `plastic`.
pub const KIND: MaterialKind = Kind {
    name: "plastic",
    summary: "a diffuse base under a smooth or rough dielectric coating (Mitsuba's `plastic` and `roughplastic`)",
    params: super::surface_params![
        Param::new("diffuse_reflectance", T::Texture, "0.5", "0 to 1", "albedo of the diffuse base"),
        Param::new("specular_reflectance", T::Color, "1", "0 to 1", "scales the coating's reflection"),
        Param::new("int_ior", T::Number, "1.49", "> 0", "index of refraction of the coating"),
        Param::new("ext_ior", T::Number, "1.00028", "> 0", "index of refraction outside"),
        Param::new("nonlinear", T::Bool, "false", "", "let the internal bounces shift the colour (`d / (1 - d F_dr)`)"),
        Param::new("roughness", T::Number, "0", "0 to 1", "microfacet roughness `alpha` of the coating; 0: smooth"),
        Param::new("distribution", T::String, "ggx", "ggx, beckmann", "normal distribution of a rough coating"),
        super::EMISSION_PARAM,
        super::TWO_SIDED_PARAM,
        super::sided::SIDED_PARAM,
    ],
    build,
};

/// An index of refraction parameter, positive and finite.
pub fn ior(p: &mut Params<'_>, key: &str, default: f64) -> ParamResult<f64> {
    let v = p.number_or(key, default)?;
    if !(v.is_finite() && v > 0.0) {
        return Err(p.key_error(key, format!("must be a positive number, got {v}")));
    }
    Ok(v)
}

/// The emission parameter: a constant, or a texture in `maps`.
pub fn emission(p: &mut Params<'_>, textures: &Textures<'_>, maps: &mut Vec<(Slot, Texture)>) -> ParamResult<Rgb> {
    Ok(match textures.read(p, "emission")? {
        None => Rgb::ZERO,
        Some(Texture::Constant(c)) => c,
        Some(t) => {
            maps.push((Slot::EMISSION, t));
            Rgb::ZERO
        }
    })
}

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let base = textures.read(p, "diffuse_reflectance")?.unwrap_or(Texture::Constant(Rgb::splat(0.5)));
    let specular = p.color_or("specular_reflectance", Rgb::ONE)?;
    if !(specular.min_element() >= 0.0 && specular.max_element() <= 1.0) {
        return Err(p.key_error("specular_reflectance", format!("must be between 0 and 1, got {specular}")));
    }
    let eta = ior(p, "int_ior", 1.49)? / ior(p, "ext_ior", 1.00028)?;
    let nonlinear = p.boolean("nonlinear")?.unwrap_or(false);
    let alpha = p.number_or("roughness", 0.0)?;
    if !(0.0..=1.0).contains(&alpha) {
        return Err(p.key_error("roughness", format!("must be between 0 and 1, got {alpha}")));
    }
    let distribution = match p.choice("distribution", &["ggx", "beckmann"])? {
        "beckmann" => Distribution::Beckmann,
        _ => Distribution::Ggx,
    };
    // Mitsuba weighs the sampling by the base's mean albedo; a textured base takes
    // 0.5 (the weight changes only the noise, not the image).
    let mean = base.constant().map_or(0.5, |c| c.element_sum() / 3.0);
    let mut coating = Coating::new(eta, specular, nonlinear, mean);
    if alpha > 0.0 {
        // Mitsuba clamps the roughness at 1e-4 as well.
        let m = Microfacet::new(distribution, alpha.max(1e-4));
        coating.rough = Some((m, rough_plastic::table(m, eta)));
    }
    let mut maps = Vec::new();
    let emission = emission(p, textures, &mut maps)?;
    let f0 = crate::materials::fresnel_dielectric(1.0, eta);
    let mut m = Material {
        color: base,
        ka: Rgb::splat(0.1),
        kd: Rgb::ONE,
        emission,
        model: Some(Model::Plastic(coating)),
        distribution,
        textures: (!maps.is_empty()).then(|| Arc::from(maps)),
        ..Material::default()
    };
    if alpha > 0.0 {
        (m.ks, m.shininess) = (specular * f0, (2.0 / (alpha * alpha) - 2.0).clamp(1.0, 10_000.0));
    } else {
        m.reflection = Reflection::Dielectric { ior: eta, min: 0.0, max: specular.max_element() };
    }
    m.one_sided = super::sided::read(p)?;
    super::finish_emitting(m, p, textures)
}

/// The path tracer sees the coating over a diffuse base of albedo `C` (capped at
/// 1), smooth ([`crate::bsdfs::plastic`]) or rough ([`crate::bsdfs::rough_plastic`]),
/// as the only lobe: the lecture's terms are the Whitted tracer's alone.
impl ToBsdf for Coating {
    #[inline]
    fn bsdf(&self, _: &Material, color: Rgb, _: bool) -> Bsdf {
        let base = color.clamp(Rgb::ZERO, Rgb::ONE);
        let lobe = match self.rough {
            Some((m, table)) => Lobe::RoughPlastic(RoughPlastic::new(base, self, m, table)),
            None => Lobe::Plastic(Plastic::new(base, self)),
        };
        Bsdf::new(&[lobe])
    }
}
