//! `principled`: Mitsuba 3's principled BSDF (Burley's Disney BSDF as Mitsuba
//! defines it, [`crate::bsdfs::principled`]), with Mitsuba's parameters.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `base_color` | colour or texture | 0.5 | the base colour `C` |
//! | `roughness` | number or texture | 0.5 | 0 to 1; GGX `alpha = max(0.001, roughness^2)` |
//! | `anisotropic` | number or texture | 0 | 0 to 1: GGX `alpha_u = max(0.001, roughness^2 / aspect)` along the surface's `dp/du`, `alpha_v = max(0.001, roughness^2 aspect)` across it, `aspect = sqrt(1 - 0.9 anisotropic)` |
//! | `metallic` | number or texture | 0 | 0 to 1: blends the dielectric towards a Schlick metal of colour `C` |
//! | `spec_trans` | number or texture | 0 | 0 to 1: the share of the dielectric that transmits (rough glass tinted `sqrt(C)`) |
//! | `specular` | number | 0.5 | Fresnel strength: `eta = 2 / (1 - sqrt(0.08 specular)) - 1`; not with `eta` |
//! | `eta` | number | 1.5 | relative index `n_int / n_ext`, instead of `specular` |
//! | `spec_tint` | number or texture | 0 | 0 to 1: tints the dielectric's reflection towards `C` |
//! | `sheen`, `sheen_tint` | number or texture | 0, 0 | the sheen lobe's weight and its tint towards `C` |
//! | `clearcoat`, `clearcoat_gloss` | number or texture | 0, 0 | the clearcoat lobe's weight and gloss (GTR1 `alpha = lerp(0.1, 0.001, gloss)`) |
//! | `flatness` | number or texture | 0 | 0 to 1: blends the diffuse towards Burley's fake subsurface |
//! | `diffuse_reflectance_sampling_rate`, `main_specular_sampling_rate`, `clearcoat_sampling_rate` | number | 1, 1, 1 | the lobes' sampling weights (noise only, not the image) |
//! | `emission`, `two_sided` | colour or texture, boolean | 0, false | emitted radiance, from both sides |
//! | `normal_map`, `bump`, `alpha` | | | as for `phong` |
//!
//! As in Mitsuba, `spec_trans` above 0 turns a zero `specular` into 0.001 and an
//! `eta` of 1 into 1.001 (transmission needs a boundary). The surface has two
//! sides of its own: from inside only the transmitting part scatters. The Whitted
//! tracer sees `C` as its diffuse term and the reflection as a Blinn highlight.

use std::sync::Arc;

use super::textured::{scalar_param, Slot};
use super::{Material, MaterialKind, Model, Texture, Textures, ToBsdf};
use crate::bsdfs::principled::{eta_from_specular, Principled, PrincipledParams};
use crate::bsdfs::principled_thin::ThinParams;
use crate::bsdfs::{Bsdf, Lobe};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params, Value};

/// `principled`.
pub const KIND: MaterialKind = Kind {
    name: "principled",
    summary: "Mitsuba's principled (Disney) BSDF: diffuse, metal, rough glass, sheen and clearcoat",
    params: super::surface_params![
        Param::new("base_color", T::Texture, "0.5", "0 to 1", "the base colour"),
        Param::new("roughness", T::Texture, "0.5", "0 to 1", "GGX `alpha = max(0.001, roughness^2)`"),
        Param::new(
            "anisotropic",
            T::Texture,
            "0",
            "0 to 1",
            "anisotropy: GGX `alpha = roughness^2 / aspect` along `dp/du` and `roughness^2 aspect` across, `aspect = sqrt(1 - 0.9 anisotropic)`",
        ),
        Param::new("metallic", T::Texture, "0", "0 to 1", "blend towards a metal of the base colour"),
        Param::new("spec_trans", T::Texture, "0", "0 to 1", "share of the dielectric that transmits"),
        Param::new("specular", T::Number, "0.5", "0 to 1", "Fresnel strength, `eta = 2 / (1 - sqrt(0.08 specular)) - 1`"),
        Param::new("eta", T::Number, "1.5", "> 0", "relative index of refraction, instead of `specular`"),
        Param::new("spec_tint", T::Texture, "0", "0 to 1", "tint of the dielectric reflection towards the base colour"),
        Param::new("sheen", T::Texture, "0", "0 to 1", "weight of the sheen lobe"),
        Param::new("sheen_tint", T::Texture, "0", "0 to 1", "tint of the sheen towards the base colour"),
        Param::new("clearcoat", T::Texture, "0", "0 to 1", "weight of the clearcoat lobe"),
        Param::new("clearcoat_gloss", T::Texture, "0", "0 to 1", "gloss of the clearcoat"),
        Param::new("flatness", T::Texture, "0", "0 to 1", "blend of the diffuse towards Burley's fake subsurface"),
        Param::new("diffuse_reflectance_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the diffuse lobe"),
        Param::new("main_specular_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the main specular lobes"),
        Param::new("clearcoat_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the clearcoat"),
        super::EMISSION_PARAM,
        super::TWO_SIDED_PARAM,
    ],
    build,
};

/// A texturable scalar of the principled model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    /// `roughness`.
    Roughness,
    /// `anisotropic`.
    Anisotropic,
    /// `metallic`.
    Metallic,
    /// `spec_trans`.
    SpecTrans,
    /// `spec_tint`.
    SpecTint,
    /// `sheen`.
    Sheen,
    /// `sheen_tint`.
    SheenTint,
    /// `clearcoat`.
    Clearcoat,
    /// `clearcoat_gloss`.
    ClearcoatGloss,
    /// `flatness`.
    Flatness,
    /// `principled_thin`'s `diff_trans` (0 to 2, stored halved as Mitsuba does).
    DiffTrans,
}

impl Scalar {
    /// Writes `value` into its field of `p`.
    pub fn set(self, p: &mut PrincipledParams, value: f64) {
        let field = match self {
            Scalar::Roughness => &mut p.roughness,
            Scalar::Anisotropic => &mut p.anisotropic,
            Scalar::Metallic => &mut p.metallic,
            Scalar::SpecTrans => &mut p.spec_trans,
            Scalar::SpecTint => &mut p.spec_tint,
            Scalar::Sheen => &mut p.sheen,
            Scalar::SheenTint => &mut p.sheen_tint,
            Scalar::Clearcoat => &mut p.clearcoat,
            Scalar::ClearcoatGloss => &mut p.clearcoat_gloss,
            Scalar::Flatness => &mut p.flatness,
            Scalar::DiffTrans => return,
        };
        *field = value;
    }

    /// Writes `value` into its field of the thin model's `p` (`diff_trans` halved).
    pub fn set_thin(self, p: &mut ThinParams, value: f64) {
        let field = match self {
            Scalar::Roughness => &mut p.roughness,
            Scalar::Anisotropic => &mut p.anisotropic,
            Scalar::SpecTrans => &mut p.spec_trans,
            Scalar::SpecTint => &mut p.spec_tint,
            Scalar::Sheen => &mut p.sheen,
            Scalar::SheenTint => &mut p.sheen_tint,
            Scalar::Flatness => &mut p.flatness,
            Scalar::DiffTrans => {
                p.diff_trans = value / 2.0;
                return;
            }
            Scalar::Metallic | Scalar::Clearcoat | Scalar::ClearcoatGloss => return,
        };
        *field = value;
    }
}

impl Scalar {
    /// Every scalar, in declaration order.
    pub const ALL: [Scalar; 11] = [
        Scalar::Roughness,
        Scalar::Anisotropic,
        Scalar::Metallic,
        Scalar::SpecTrans,
        Scalar::SpecTint,
        Scalar::Sheen,
        Scalar::SheenTint,
        Scalar::Clearcoat,
        Scalar::ClearcoatGloss,
        Scalar::Flatness,
        Scalar::DiffTrans,
    ];
}

/// Writes a texture's value into `scalar`'s field of a principled or thin
/// principled material, clamped to the field's range (`diff_trans` 0 to 2, the
/// others 0 to 1).
fn set_scalar(m: &mut Material, scalar: Scalar, value: Rgb) {
    match &mut m.model {
        Some(Model::Principled(p)) => scalar.set(p, value.x.clamp(0.0, 1.0)),
        Some(Model::PrincipledThin(p)) => {
            let max = if scalar == Scalar::DiffTrans { 2.0 } else { 1.0 };
            scalar.set_thin(p, value.x.clamp(0.0, max))
        }
        _ => {}
    }
}

/// The texture slot of `scalar`, for both principled kinds.
pub fn slot(scalar: Scalar) -> Slot {
    macro_rules! slot {
        ($name:literal, $scalar:ident) => {
            Slot::new($name, |m, v| set_scalar(m, Scalar::$scalar, v))
        };
    }
    match scalar {
        Scalar::Roughness => slot!("principled.roughness", Roughness),
        Scalar::Anisotropic => slot!("principled.anisotropic", Anisotropic),
        Scalar::Metallic => slot!("principled.metallic", Metallic),
        Scalar::SpecTrans => slot!("principled.spec_trans", SpecTrans),
        Scalar::SpecTint => slot!("principled.spec_tint", SpecTint),
        Scalar::Sheen => slot!("principled.sheen", Sheen),
        Scalar::SheenTint => slot!("principled.sheen_tint", SheenTint),
        Scalar::Clearcoat => slot!("principled.clearcoat", Clearcoat),
        Scalar::ClearcoatGloss => slot!("principled.clearcoat_gloss", ClearcoatGloss),
        Scalar::Flatness => slot!("principled.flatness", Flatness),
        Scalar::DiffTrans => slot!("principled.diff_trans", DiffTrans),
    }
}

const SCALARS: [(&str, Scalar, f64); 10] = [
    ("roughness", Scalar::Roughness, 0.5),
    ("anisotropic", Scalar::Anisotropic, 0.0),
    ("metallic", Scalar::Metallic, 0.0),
    ("spec_trans", Scalar::SpecTrans, 0.0),
    ("spec_tint", Scalar::SpecTint, 0.0),
    ("sheen", Scalar::Sheen, 0.0),
    ("sheen_tint", Scalar::SheenTint, 0.0),
    ("clearcoat", Scalar::Clearcoat, 0.0),
    ("clearcoat_gloss", Scalar::ClearcoatGloss, 0.0),
    ("flatness", Scalar::Flatness, 0.0),
];

fn rate(p: &mut Params<'_>, key: &str) -> ParamResult<f64> {
    let v = p.number_or(key, 1.0)?;
    if !(v.is_finite() && v >= 0.0) {
        return Err(p.key_error(key, format!("must be a non-negative number, got {v}")));
    }
    Ok(v)
}

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let base = textures.read(p, "base_color")?.unwrap_or(Texture::Constant(Rgb::splat(0.5)));
    let mut maps = Vec::new();
    let mut params = PrincipledParams::default();
    // Mitsuba's rule: transmission is on when `spec_trans` is given and is not the number 0.
    let transmits =
        p.item("spec_trans").is_some_and(|i| !matches!(i.value, Value::Number(x) if x == 0.0) && !matches!(i.value, Value::Integer(0)));
    for (key, scalar, default) in SCALARS {
        let v = scalar_param(p, textures, key, default, slot(scalar), &mut maps)?;
        if !(0.0..=1.0).contains(&v) {
            return Err(p.key_error(key, format!("must be between 0 and 1, got {v}")));
        }
        scalar.set(&mut params, v);
    }
    params.eta = match (p.has("eta"), p.has("specular")) {
        (true, true) => return Err(p.key_error("eta", "give either `eta` or `specular`, not both")),
        (true, false) => {
            let eta = super::plastic::ior(p, "eta", 1.5)?;
            if transmits && eta == 1.0 {
                1.001
            } else {
                eta
            }
        }
        (false, _) => {
            let s = p.number_or("specular", 0.5)?;
            if !(0.0..=1.0).contains(&s) {
                return Err(p.key_error("specular", format!("must be between 0 and 1, got {s}")));
            }
            eta_from_specular(if transmits && s == 0.0 { 1e-3 } else { s })
        }
    };
    params.diffuse_rate = rate(p, "diffuse_reflectance_sampling_rate")?;
    params.specular_rate = rate(p, "main_specular_sampling_rate")?;
    params.clearcoat_rate = rate(p, "clearcoat_sampling_rate")?;
    let emission = super::plastic::emission(p, textures, &mut maps)?;
    let dielectric = (1.0 - params.metallic) * (1.0 - params.spec_trans);
    let f0 = crate::materials::fresnel_dielectric(1.0, params.eta);
    let m = Material {
        color: base,
        ka: Rgb::splat(0.1 * dielectric),
        kd: Rgb::splat(dielectric),
        ks: Rgb::splat(f0 + params.metallic * (1.0 - f0)),
        shininess: super::pbr::shininess(params.roughness),
        emission,
        model: Some(Model::Principled(params)),
        textures: (!maps.is_empty()).then(|| Arc::from(maps)),
        ..Material::default()
    };
    super::finish_emitting(m, p, textures)
}

/// The path tracer sees Mitsuba's principled BSDF ([`crate::bsdfs::principled`]) of
/// base colour `C` as the only lobe.
impl ToBsdf for PrincipledParams {
    // It tells the two sides apart itself, as Mitsuba's does.
    #[inline]
    fn bsdf(&self, _: &Material, color: Rgb, front_face: bool) -> Bsdf {
        Bsdf::new(&[Lobe::Principled(Principled::new(color.max(Rgb::ZERO), *self, front_face))])
    }
}
