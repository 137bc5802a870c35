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
        Param::new("two_sided", T::Bool, "false", "", "emit from both sides of the surface, not only the front"),
        super::sided::SIDED_PARAM,
        Param::new("reflection", T::Table, "none", "", "mirror reflection (see below)"),
        Param::new("refraction", T::Table, "none", "", "refraction (see below)"),
        Param::new(
            "shadow_transmittance",
            T::Texture,
            "0",
            "",
            "fraction of light a shadow ray keeps crossing this surface (clear glass: 1; a texture applies where the surface is shaded, not to shadow rays)",
        ),
        Param::new("roughness", T::ScalarTexture, "0", "0 to 1", "microfacet roughness of Fresnel glass and conductors in the path tracer"),
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
    let material = Material {
        color,
        ka: color_param(p, textures, "ka", d.ka, Slot::Ka, &mut maps)?,
        kd: color_param(p, textures, "kd", d.kd, Slot::Kd, &mut maps)?,
        ks: color_param(p, textures, "ks", d.ks, Slot::Ks, &mut maps)?,
        shininess: scalar_param(p, textures, "shininess", d.shininess, Slot::Shininess, &mut maps)?,
        emission: color_param(p, textures, "emission", d.emission, Slot::Emission, &mut maps)?,
        two_sided: p.boolean("two_sided")?.unwrap_or(d.two_sided),
        one_sided: super::sided::read(p)?,
        reflection: reflection(p)?,
        refraction: refraction(p)?,
        shadow_transmittance: color_param(
            p,
            textures,
            "shadow_transmittance",
            d.shadow_transmittance,
            Slot::ShadowTransmittance,
            &mut maps,
        )?,
        roughness: scalar_param(p, textures, "roughness", d.roughness, Slot::Roughness, &mut maps)?,
        distribution: match p.choice("distribution", &["ggx", "beckmann"])? {
            "beckmann" => crate::bsdfs::Distribution::Beckmann,
            _ => crate::bsdfs::Distribution::Ggx,
        },
        model: None,
        textures: None,
        pbr: None,
        normal_map: normal_map::read(p, textures)?,
        bump: super::bump::read(p, textures)?,
        alpha: super::alpha::read(p, textures)?,
        blend: None,
    };
    let material = Material { textures: (!maps.is_empty()).then(|| maps.into()), ..material };
    material.validate().map_err(|e| p.core_error(e))?;
    Ok(material)
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
                let metal = Metal::from_name(name).ok_or_else(|| {
                    r.key_error("metal", format!("unknown metal \"{name}\", expected \"gold\", \"silver\", \"copper\" or \"aluminium\""))
                })?;
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
