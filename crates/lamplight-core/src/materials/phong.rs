//! `phong`: the lecture's material as a scene kind (the default material type).
//!
//! `L = Ke + ka C La + sum_l Lin_l (kd C (N.L)+ + ks ((H.N)+)^shininess) + R L(refl) + T L(refr)`,
//! with `C` the colour (or texture) and `R`, `T` the weights of `reflection` and
//! `refraction`:
//!
//! | `reflection` | meaning |
//! |--------------|---------|
//! | `{ type = "constant", weight = COLOUR }` | constant mirror weight |
//! | `{ type = "dielectric", ior = N, min = 0, max = 1 }` | dielectric Fresnel `F` at index `ior`, rescaled to `min + (max - min) F` |
//! | `{ type = "conductor", metal = "gold" }` | conductor Fresnel of `"gold"`, `"silver"`, `"copper"`, `"aluminium"` |
//! | `{ type = "conductor", eta = COLOUR, k = COLOUR }` | conductor Fresnel with complex index `eta + i k` |
//!
//! | `refraction` | meaning |
//! |--------------|---------|
//! | `{ type = "fresnel", ior = N }` | refraction weighted `1 - F` |
//! | `{ type = "constant", ior = N, weight = COLOUR }` | refraction with a constant weight |

use super::normal_map;
use super::textured::{color_param, scalar_param, Slot};
use super::{Material, MaterialKind, Metal, Reflection, Refraction};
use crate::bsdfs::{microfacet, Bsdf, Glass, Glossy, Lambertian, Lobe, MirrorFresnel, Refract, RoughConductor, RoughGlass};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// `phong`.
pub const KIND: MaterialKind = Kind {
    name: "phong",
    summary: "the lecture's model: ambient, diffuse and Blinn terms, emission, mirror reflection and refraction",
    params: super::surface_params![
        Param::new("color", T::Texture, "0.5", "", "surface colour `C`"),
        Param::new(
            "checker",
            T::Table,
            "none",
            "",
            "a 3D checker instead of `color`: `{ size, even, odd, offset }`, as the `checker` texture",
        ),
        Param::new("ka", T::Texture, "0.1", "", "ambient factor"),
        Param::new("kd", T::Texture, "0.9", "", "diffuse factor"),
        Param::new("ks", T::Texture, "0", "", "Blinn highlight factor (not multiplied by `C`)"),
        Param::new("shininess", T::ScalarTexture, "1", ">= 0", "Blinn exponent"),
        Param::new(
            "emission",
            T::Texture,
            "0",
            "radiance",
            "emitted radiance, from the front side; an emitting shape of constant emission is an area light",
        ),
        super::TWO_SIDED_PARAM,
        super::sided::SIDED_PARAM,
        // Said in full: the reference table sits below the forms' own tables (issue 27).
        Param::new(
            "reflection",
            T::Table,
            "none",
            "",
            "mirror reflection: `{ type = \"constant\", weight }`, `{ type = \"dielectric\", ior, min, max }` or `{ type = \"conductor\", metal }` / `{ type = \"conductor\", eta, k }`",
        ),
        Param::new("refraction", T::Table, "none", "", "refraction: `{ type = \"fresnel\", ior }` or `{ type = \"constant\", ior, weight }`"),
        Param::new(
            "shadow_transmittance",
            T::Texture,
            "0",
            "",
            "fraction of light a shadow ray keeps crossing this surface (clear glass: 1; a texture applies where the surface is shaded, not to shadow rays)",
        ),
        Param::new("roughness", T::ScalarTexture, "0", "0 to 1", "microfacet roughness of Fresnel glass and conductors in the path tracer"),
        Param::new(
            "roughness_u",
            T::ScalarTexture,
            "none",
            "0 to 1",
            "anisotropic roughness along the surface's `dp/du`, with `roughness_v` and instead of `roughness`",
        ),
        Param::new("roughness_v", T::ScalarTexture, "none", "0 to 1", "anisotropic roughness along the other tangent, with `roughness_u`"),
        Param::new("distribution", T::String, "ggx", "ggx, beckmann", "microfacet distribution of rough glass and conductors"),
    ],
    build,
};

fn build(p: &mut Params<'_>, textures: &super::Textures<'_>) -> ParamResult<Material> {
    let d = Material::default();
    let color = match (p.has("color"), p.has("checker")) {
        (true, true) => return Err(p.error("takes color or checker, not both")),
        (false, true) => {
            let checker = &super::texture::CHECKER;
            p.table("checker")?.expect("present").read(checker.params, &[], |t| (checker.build)(t, textures))?
        }
        _ => textures.read(p, "color")?.unwrap_or(d.color.clone()),
    };
    let mut maps = Vec::new();
    let (roughness, roughness_v) = roughness(p, textures, &mut maps)?;
    let material = Material {
        color,
        ka: color_param(p, textures, "ka", d.ka, Slot::KA, &mut maps)?,
        kd: color_param(p, textures, "kd", d.kd, Slot::KD, &mut maps)?,
        ks: color_param(p, textures, "ks", d.ks, Slot::KS, &mut maps)?,
        shininess: scalar_param(p, textures, "shininess", d.shininess, Slot::SHININESS, &mut maps)?,
        emission: color_param(p, textures, "emission", d.emission, Slot::EMISSION, &mut maps)?,
        two_sided: p.boolean("two_sided")?.unwrap_or(d.two_sided),
        one_sided: super::sided::read(p)?,
        reflection: reflection(p)?,
        refraction: refraction(p)?,
        shadow_transmittance: color_param(
            p,
            textures,
            "shadow_transmittance",
            d.shadow_transmittance,
            Slot::SHADOW_TRANSMITTANCE,
            &mut maps,
        )?,
        roughness,
        roughness_v,
        distribution: match p.choice("distribution", &["ggx", "beckmann"])? {
            "beckmann" => crate::bsdfs::Distribution::Beckmann,
            _ => crate::bsdfs::Distribution::Ggx,
        },
        model: None,
        textures: None,
        pbr: None,
        normal_map: normal_map::read(p, textures)?,
        bump: super::bump::read(p, textures)?,
        map_shadowing: super::map_shadowing::read(p)?,
        alpha: super::alpha::read(p, textures)?,
        blend: None,
    };
    let material = Material { textures: (!maps.is_empty()).then(|| maps.into()), ..material };
    material.validate().map_err(|e| p.core_error(e))?;
    Ok(material)
}

/// `roughness`, or the anisotropic pair `roughness_u` (along `dp/du`, stored as
/// the roughness) and `roughness_v`: both or neither, and not with `roughness`
/// (Mitsuba's rule for `alpha`, `alpha_u`, `alpha_v`).
fn roughness(
    p: &mut Params<'_>,
    textures: &super::Textures<'_>,
    maps: &mut Vec<(Slot, super::Texture)>,
) -> ParamResult<(f64, Option<f64>)> {
    let pair = "anisotropic roughness takes both `roughness_u` and `roughness_v`";
    match (p.has("roughness_u"), p.has("roughness_v")) {
        (false, false) => Ok((scalar_param(p, textures, "roughness", 0.0, Slot::ROUGHNESS, maps)?, None)),
        (true, false) => Err(p.key_error("roughness_u", format!("needs `roughness_v` too ({pair})"))),
        (false, true) => Err(p.key_error("roughness_v", format!("needs `roughness_u` too ({pair})"))),
        (true, true) if p.has("roughness") => {
            Err(p.key_error("roughness", "give either `roughness` or `roughness_u` and `roughness_v`, not both"))
        }
        (true, true) => {
            let u = scalar_param(p, textures, "roughness_u", 0.0, Slot::ROUGHNESS, maps)?;
            let v = scalar_param(p, textures, "roughness_v", 0.0, Slot::ROUGHNESS_V, maps)?;
            for (key, x) in [("roughness_u", u), ("roughness_v", v)] {
                if !(0.0..=1.0).contains(&x) {
                    return Err(p.key_error(key, format!("must be between 0 and 1, got {x}")));
                }
            }
            Ok((u, Some(v)))
        }
    }
}

fn reflection(p: &mut Params<'_>) -> ParamResult<Reflection> {
    let Some(mut r) = p.table("reflection")? else { return Ok(Reflection::None) };
    let out = match r.required_choice("type", &["constant", "dielectric", "conductor"])? {
        "constant" => Reflection::Constant(r.color("weight")?.ok_or_else(|| r.error("needs `weight` (a colour)"))?),
        "dielectric" => {
            let ior = r.required_number("ior")?;
            let (min, max) = (r.number_or("min", 0.0)?, r.number_or("max", 1.0)?);
            // A weight of Fresnel reflectance: outside [0, 1], or reversed, it
            // would reflect more light than arrives (or less than none).
            if !(0.0..=1.0).contains(&min) {
                return Err(r.key_error("min", format!("must be between 0 and 1, got {min}")));
            }
            if !(min..=1.0).contains(&max) {
                return Err(r.key_error("max", format!("must be between min ({min}) and 1, got {max}")));
            }
            Reflection::Dielectric { ior, min, max }
        }
        _ => match (r.string("metal")?, r.color("eta")?, r.color("k")?) {
            (Some(name), None, None) => {
                let metal =
                    Metal::from_name(name).ok_or_else(|| r.key_error("metal", crate::params::unknown("metal", name, &Metal::NAMES)))?;
                let (eta, k) = metal.eta_k();
                Reflection::Conductor { eta, k }
            }
            (None, Some(eta), Some(k)) => Reflection::Conductor { eta, k },
            _ => return Err(r.error("takes either metal or both eta and k")),
        },
    };
    r.finish()?;
    Ok(out)
}

fn refraction(p: &mut Params<'_>) -> ParamResult<Refraction> {
    let Some(mut r) = p.table("refraction")? else { return Ok(Refraction::None) };
    let out = match r.required_choice("type", &["fresnel", "constant"])? {
        "fresnel" => Refraction::Fresnel { ior: r.required_number("ior")? },
        _ => Refraction::Constant {
            ior: r.required_number("ior")?,
            weight: r.color("weight")?.ok_or_else(|| r.error("needs `weight` (a colour)"))?,
        },
    };
    r.finish()?;
    Ok(out)
}

/// The lecture's terms as the path tracer's lobes:
///
/// | lecture term | path tracer |
/// |---|---|
/// | `kd * C` | Lambertian albedo (`f = kd C / pi`) |
/// | `ks`, `shininess` | GGX reflection of reflectance `ks`, roughness `sqrt(2 / (shine + 2))` |
/// | `Reflection::Constant(w)` | mirror of weight `w` |
/// | `Reflection::Dielectric` + `Refraction::Fresnel` of one index, `min 0 max 1` | smooth glass; rough glass (GGX, [`crate::bsdfs::rough_dielectric`]) of `alpha = roughness` when `roughness >= 0.001` |
/// | `Reflection::Dielectric {min, max}` otherwise | mirror of weight `min + (max - min) F` |
/// | `Reflection::Conductor {eta, k}` | conductor mirror with complex Fresnel; rough metal (GGX, [`crate::bsdfs::rough_conductor`]) of `alpha = roughness` when `roughness >= 0.001` |
/// | [`Material::roughness_v`] | the rough glass and metal lobes anisotropic: `alpha = roughness` along `dp/du`, `alpha_v = roughness_v` along the other tangent, each at least 0.001 |
/// | `Refraction::Fresnel` alone | refraction of weight `1 - F` |
/// | `Refraction::Constant(w)` | refraction of weight `w` |
/// | `emission` | area light radiance (see [`crate::lights::area`]) |
/// | [`Material::distribution`] | the distribution of the rough glass and metal lobes (GGX or Beckmann, [`crate::bsdfs::distribution`]) |
/// | `ka` | nothing: it stands for the indirect light the path tracer computes (the background is the sky, [`crate::lights::LightSet`]) |
///
/// With lights read as [`crate::lights::DELTA_SCALE`] says, the Lambertian lobe
/// gives exactly the lecture's diffuse term under point, directional and spot
/// lights; the GGX lobe only approximates the Blinn highlight.
///
/// On a conductor or on Fresnel glass the Blinn highlight is dropped: it stands for
/// the light source's own reflection, which the path tracer computes from the
/// mirror (a point light's reflection in a perfect mirror is invisible in both).
/// Then every lobe is scaled per channel so that the reflectance bounds sum to at
/// most 1 ([`Bsdf::new`]): the lecture lets `kd + ks + kr` exceed 1, physics does not.
#[inline]
pub fn lecture_bsdf(material: &Material, color: Rgb, front_face: bool) -> Bsdf {
    let relative = |ior: f64| if front_face { ior } else { 1.0 / ior };
    let mut lobes: [Lobe; 4] = [Lobe::Diffuse(Lambertian(Rgb::ZERO)); 4];
    let mut n = 0;
    let mut push = |lobe: Lobe| {
        lobes[n] = lobe;
        n += 1;
    };
    if material.kd != Rgb::ZERO {
        push(Lobe::Diffuse(Lambertian(material.kd * color)));
    }
    let glass = match (&material.reflection, &material.refraction) {
        (Reflection::Dielectric { ior, min, max }, Refraction::Fresnel { ior: t }) => *ior == *t && *min == 0.0 && *max == 1.0,
        _ => false,
    };
    let conductor = matches!(material.reflection, Reflection::Conductor { .. });
    if material.ks != Rgb::ZERO && !glass && !conductor {
        push(Lobe::Glossy(Glossy { ks: material.ks, alpha: microfacet::alpha_from_shininess(material.shininess) }));
    }
    // Below the smallest GGX roughness the lobe is a mirror that f64 cannot
    // sample; an anisotropic lobe is rough when either roughness is, each
    // clamped to the smallest (as Mitsuba clamps to 1e-4).
    let (rough, alpha, alpha_v) = match material.roughness_v {
        None => (material.roughness >= microfacet::MIN_ALPHA, material.roughness, material.roughness),
        Some(v) => {
            let u = material.roughness;
            (u.max(v) >= microfacet::MIN_ALPHA, u.max(microfacet::MIN_ALPHA), v.max(microfacet::MIN_ALPHA))
        }
    };
    if glass {
        if let Refraction::Fresnel { ior } = material.refraction {
            if rough {
                push(Lobe::RoughGlass(RoughGlass {
                    eta: relative(ior),
                    alpha,
                    alpha_v,
                    tint: Rgb::ONE,
                    distribution: material.distribution,
                }));
            } else {
                push(Lobe::Glass(Glass { eta: relative(ior), tint: Rgb::ONE }));
            }
        }
    } else {
        match material.reflection {
            Reflection::None => {}
            Reflection::Constant(w) => push(Lobe::Mirror(MirrorFresnel::Constant(w))),
            Reflection::Dielectric { ior, min, max } => push(Lobe::Mirror(MirrorFresnel::Dielectric { eta: relative(ior), min, max })),
            Reflection::Conductor { eta, k } if rough => {
                push(Lobe::RoughConductor(RoughConductor { eta, k, alpha, alpha_v, distribution: material.distribution }))
            }
            Reflection::Conductor { eta, k } => push(Lobe::Mirror(MirrorFresnel::Conductor { eta, k })),
        }
        match material.refraction {
            Refraction::None => {}
            Refraction::Fresnel { ior } => push(Lobe::Refract(Refract { eta: relative(ior), weight: None })),
            Refraction::Constant { ior, weight } => push(Lobe::Refract(Refract { eta: relative(ior), weight: Some(weight) })),
        }
    }
    Bsdf::new(&lobes[..n])
}
