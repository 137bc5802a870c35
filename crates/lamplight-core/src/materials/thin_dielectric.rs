//! `thin_dielectric`: a thin dielectric sheet (a window pane), Mitsuba 3's
//! `thindielectric` ([`crate::bsdfs::thin_dielectric`]): it reflects
//! `R' = R + T^2 R / (1 - R^2)` of the light and lets the rest through without bending it.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `int_ior`, `ext_ior` | number | 1.5046, 1.00028 | indices of the sheet and outside (Mitsuba's `bk7` and `air`); `eta = int_ior / ext_ior` |
//! | `emission`, `two_sided` | colour or texture, boolean | 0, false | emitted radiance, from both sides |
//! | `normal_map`, `bump`, `alpha` | | | as for `phong` |
//!
//! Shadow rays stop at the sheet, as they do at glass and in Mitsuba. The Whitted
//! tracer sees a mirror of weight `R'` at normal incidence and a refraction of index 1.

use std::sync::Arc;

use super::plastic::{emission, ior};
use super::{Material, MaterialKind, Model, Reflection, Refraction, Texture, Textures, ToBsdf};
use crate::bsdfs::{Bsdf, Lobe, ThinGlass};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// `thin_dielectric`.
pub const KIND: MaterialKind = Kind {
    name: "thin_dielectric",
    summary:
        "a thin dielectric sheet: Fresnel reflection summed over its two faces, transmission without bending (Mitsuba's `thindielectric`)",
    params: super::surface_params![
        Param::new("int_ior", T::Number, "1.5046", "> 0", "index of refraction of the sheet"),
        Param::new("ext_ior", T::Number, "1.00028", "> 0", "index of refraction outside"),
        super::EMISSION_PARAM,
        super::TWO_SIDED_PARAM,
    ],
    build,
};

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let eta = ior(p, "int_ior", 1.5046)? / ior(p, "ext_ior", 1.00028)?;
    let mut maps = Vec::new();
    let emission = emission(p, textures, &mut maps)?;
    let r = crate::bsdfs::thin_dielectric::reflectance(1.0, eta);
    let m = Material {
        color: Texture::Constant(Rgb::ONE),
        ka: Rgb::ZERO,
        kd: Rgb::ZERO,
        emission,
        reflection: Reflection::Constant(Rgb::splat(r)),
        refraction: Refraction::Constant { ior: 1.0, weight: Rgb::splat(1.0 - r) },
        model: Some(Model::ThinDielectric(ThinSheet { eta })),
        textures: (!maps.is_empty()).then(|| Arc::from(maps)),
        ..Material::default()
    };
    super::finish_emitting(m, p, textures)
}

/// The parameters of a thin dielectric sheet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinSheet {
    /// Relative index of the sheet.
    pub eta: f64,
}

/// The path tracer sees the sheet ([`crate::bsdfs::thin_dielectric`]) as the only lobe.
impl ToBsdf for ThinSheet {
    // The sheet has the same medium on both sides: the face does not matter.
    #[inline]
    fn bsdf(&self, _: &Material, _: Rgb, _: bool) -> Bsdf {
        Bsdf::new(&[Lobe::ThinGlass(ThinGlass { eta: self.eta, tint: Rgb::ONE })])
    }
}
