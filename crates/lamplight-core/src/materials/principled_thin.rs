//! `principled_thin`: Mitsuba 3's `principledthin` BSDF, the principled model of
//! a thin sheet (leaves, paper, cloth; [`crate::bsdfs::principled_thin`]), with
//! Mitsuba's parameters.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `base_color` | colour or texture | 0.5 | the base colour `C` |
//! | `roughness` | number or texture | 0.5 | 0 to 1; GGX `alpha = max(0.001, roughness^2)` (transmission: `(0.65 eta - 0.35) roughness`) |
//! | `anisotropic` | number or texture | 0 | 0 to 1: as `principled`'s, for both the reflection's and the transmission's roughness |
//! | `spec_trans` | number or texture | 0 | 0 to 1: the glossy share (reflection and straight-through transmission) |
//! | `diff_trans` | number or texture | 0 | 0 to 2: the diffuse share that is transmitted (Mitsuba's range) |
//! | `eta` | number or texture | 1.5 | relative index of the sheet (a texture is read at each hit, as Mitsuba's `eval_1`; its values are kept between [`MIN_ETA`] and [`MAX_ETA`]) |
//! | `spec_tint` | number or texture | 0 | 0 to 1: tints the glossy reflection towards `C` |
//! | `sheen`, `sheen_tint` | number or texture | 0, 0 | the sheen lobe's weight and its tint towards `C` |
//! | `flatness` | number or texture | 0 | 0 to 1: blends the diffuse towards Burley's fake subsurface |
//! | `specular_reflectance_sampling_rate`, `specular_transmittance_sampling_rate`, `diffuse_reflectance_sampling_rate`, `diffuse_transmittance_sampling_rate` | number | 1 | the lobes' sampling weights (noise only) |
//! | `emission`, `two_sided` | colour or texture, boolean | 0, false | emitted radiance, from both sides |
//! | `normal_map`, `bump`, `alpha` | | | as for `phong` |
//!
//! The sheet scatters the same from both sides and does not bend light. The
//! Whitted tracer sees `C` as its diffuse term.

use std::sync::Arc;

use super::principled::Scalar;
use super::textured::{scalar_param, Slot};
use super::{Material, MaterialKind, Model, Texture, Textures, ToBsdf};
use crate::bsdfs::principled_thin::{PrincipledThin, ThinParams};
use crate::bsdfs::{Bsdf, Lobe};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// `principled_thin`.
pub const KIND: MaterialKind = Kind {
    name: "principled_thin",
    summary: "Mitsuba's thin principled BSDF (`principledthin`): a sheet with diffuse and glossy transmission",
    params: super::surface_params![
        Param::new("base_color", T::Texture, "0.5", "0 to 1", "the base colour"),
        Param::new("roughness", T::Texture, "0.5", "0 to 1", "GGX `alpha = max(0.001, roughness^2)`"),
        Param::new("anisotropic", T::Texture, "0", "0 to 1", "anisotropy, as `principled`'s"),
        Param::new("spec_trans", T::Texture, "0", "0 to 1", "glossy share"),
        Param::new("diff_trans", T::Texture, "0", "0 to 2", "transmitted diffuse share (Mitsuba's range)"),
        Param::new("eta", T::ScalarTexture, "1.5", "> 0", "relative index of the sheet (a texture: read at each hit)"),
        Param::new("spec_tint", T::Texture, "0", "0 to 1", "tint of the glossy reflection towards the base colour"),
        Param::new("sheen", T::Texture, "0", "0 to 1", "weight of the sheen lobe"),
        Param::new("sheen_tint", T::Texture, "0", "0 to 1", "tint of the sheen towards the base colour"),
        Param::new("flatness", T::Texture, "0", "0 to 1", "blend of the diffuse towards Burley's fake subsurface"),
        Param::new("specular_reflectance_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the glossy reflection"),
        Param::new("specular_transmittance_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the glossy transmission"),
        Param::new("diffuse_reflectance_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the diffuse reflection"),
        Param::new("diffuse_transmittance_sampling_rate", T::Number, "1", ">= 0", "sampling weight of the diffuse transmission"),
        super::EMISSION_PARAM,
        super::TWO_SIDED_PARAM,
    ],
    build,
};

const SCALARS: [(&str, Scalar, f64, f64); 8] = [
    ("roughness", Scalar::Roughness, 0.5, 1.0),
    ("anisotropic", Scalar::Anisotropic, 0.0, 1.0),
    ("spec_trans", Scalar::SpecTrans, 0.0, 1.0),
    ("diff_trans", Scalar::DiffTrans, 0.0, 2.0),
    ("spec_tint", Scalar::SpecTint, 0.0, 1.0),
    ("sheen", Scalar::Sheen, 0.0, 1.0),
    ("sheen_tint", Scalar::SheenTint, 0.0, 1.0),
    ("flatness", Scalar::Flatness, 0.0, 1.0),
];

/// The smallest index a texture gives the sheet: Mitsuba reads any value;
/// at 0 or below Fresnel's equations have no meaning, so the slot keeps it here
/// (and at most [`MAX_ETA`], so that an infinite texel stays finite).
pub const MIN_ETA: f64 = 1e-3;
/// The largest index a texture gives the sheet.
pub const MAX_ETA: f64 = 1e3;

/// The texture slot of `eta` (Mitsuba's `principledthin` reads its `eta`
/// texture per hit, `m_eta_thin->eval_1`).
pub const ETA: Slot = Slot::new("principled_thin.eta", |m, v| {
    if let Some(Model::PrincipledThin(p)) = &mut m.model {
        // A NaN texel becomes MIN_ETA too (`clamp` would keep the NaN).
        p.eta = if v.x.is_nan() { MIN_ETA } else { v.x.clamp(MIN_ETA, MAX_ETA) };
    }
});

const RATES: [&str; 4] = [
    "specular_reflectance_sampling_rate",
    "specular_transmittance_sampling_rate",
    "diffuse_reflectance_sampling_rate",
    "diffuse_transmittance_sampling_rate",
];

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let base = textures.read(p, "base_color")?.unwrap_or(Texture::Constant(Rgb::splat(0.5)));
    let mut maps = Vec::new();
    let mut params = ThinParams::default();
    for (key, scalar, default, max) in SCALARS {
        let v = scalar_param(p, textures, key, default, super::principled::slot(scalar), &mut maps)?;
        if !(0.0..=max).contains(&v) {
            return Err(p.key_error(key, format!("must be between 0 and {max}, got {v}")));
        }
        scalar.set_thin(&mut params, v);
    }
    params.eta = scalar_param(p, textures, "eta", 1.5, ETA, &mut maps)?;
    if !(params.eta.is_finite() && params.eta > 0.0) {
        return Err(p.key_error("eta", format!("must be a positive number, got {}", params.eta)));
    }
    for (rate, key) in params.rates.iter_mut().zip(RATES) {
        *rate = p.number_or(key, 1.0)?;
        if !(rate.is_finite() && *rate >= 0.0) {
            return Err(p.key_error(key, format!("must be a non-negative number, got {rate}")));
        }
    }
    let emission = super::plastic::emission(p, textures, &mut maps)?;
    let diffuse = (1.0 - params.spec_trans) * (1.0 - params.diff_trans);
    let m = Material {
        color: base,
        ka: Rgb::splat(0.1 * diffuse),
        kd: Rgb::splat(diffuse),
        emission,
        model: Some(Model::PrincipledThin(params)),
        textures: (!maps.is_empty()).then(|| Arc::from(maps)),
        ..Material::default()
    };
    super::finish_emitting(m, p, textures)
}

/// The path tracer sees Mitsuba's `principledthin` ([`crate::bsdfs::principled_thin`])
/// of base colour `C` as the only lobe.
impl ToBsdf for ThinParams {
    // A sheet has the same medium on both sides: the face does not matter.
    #[inline]
    fn bsdf(&self, _: &Material, color: Rgb, _: bool) -> Bsdf {
        Bsdf::new(&[Lobe::PrincipledThin(PrincipledThin::new(color.max(Rgb::ZERO), *self))])
    }
}
