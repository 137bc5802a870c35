//! `<bsdf>` to `[materials]`. lamplight's `phong` material is read by the path
//! tracer as physically based lobes (`lecture_bsdf` in `crates/lamplight-core/src/materials/phong.rs`),
//! so each Mitsuba BSDF becomes the `phong` table of the same lobes:
//!
//! | Mitsuba | lamplight `phong` |
//! |---|---|
//! | `diffuse` `reflectance` (0.5, colour or texture) | `color = reflectance`, `kd = 1`, `ka = ks = 0` |
//! | none (Mitsuba's default) | diffuse 0.5; on an emitting shape diffuse 0 (black), as Mitsuba |
//! | `conductor` `material` (`none`: a perfect mirror) or `eta`, `k` | `kd = 0`, `reflection = { type = "conductor", eta, k }` ([`super::conductors`]: Mitsuba's table, as `scalar_rgb` reduces it) |
//! | `roughconductor` `alpha` (0.1) or `alpha_u` and `alpha_v` (numbers or textures), `distribution` (`beckmann`) | the same with `roughness = alpha`, or `roughness_u = alpha_u`, `roughness_v = alpha_v` (along and across the surface's `dp/du`, Mitsuba's shading frame; a texture is evaluated at each hit), `distribution` |
//! | `dielectric` `int_ior` (`bk7`), `ext_ior` (`air`): numbers or names | `reflection = { type = "dielectric", ior }`, `refraction = { type = "fresnel", ior }`, `ior = int_ior / ext_ior` |
//! | `roughdielectric` `alpha` or `alpha_u` and `alpha_v` (numbers or textures), `distribution` | the same with `roughness = alpha` or `roughness_u`, `roughness_v`, `distribution` |
//! | `plastic` `diffuse_reflectance` (0.5), `specular_reflectance` (1), `int_ior` (`polypropylene`), `ext_ior` (`air`), `nonlinear` | `plastic` of the same parameters |
//! | `roughplastic` (the same and `alpha` (a number: a texture is an error), `distribution`) | `plastic` with `roughness = alpha`, `distribution` |
//! | `thindielectric` `int_ior` (`bk7`), `ext_ior` (`air`) | `thin_dielectric` |
//! | `twosided` | its nested BSDF; every other one-sided BSDF gets `sided = "front"` ([`super::sided`]) |
//! | `null` | `alpha = 0`: cut out |
//! | `mask` `opacity` | the nested BSDF with `alpha = opacity`, `alpha_mode = "blend"` (there with probability `opacity`, as Mitsuba) |
//! | `normalmap` `normalmap` (a bitmap), `use_shadowing_function` (true), `flip_invalid_normals` | the nested BSDF with `normal_map`, `map_shadowing` |
//! | `bumpmap` (`scale`, one nested height `<texture>`, `use_shadowing_function`, `flip_invalid_normals`) | the nested BSDF with `bump`, `bump_scale`, `map_shadowing` |
//! | `principled` (every parameter, `anisotropic` a number or texture; `eta`, `specular` numbers: a texture there is an error, as in Mitsuba) | `principled` of the same parameters (Mitsuba's own BSDF, `crates/lamplight-core/src/bsdfs/principled.rs`) |
//! | `principledthin` (every parameter, `anisotropic` and `eta` numbers or textures) | `principled_thin` of the same parameters (`crates/lamplight-core/src/bsdfs/principled_thin.rs`) |
//!
//! | `blendbsdf` `weight` (0.5, number or texture), two nested BSDFs | `blend` with `a`, `b` the nested BSDFs as material tables, each one-sided as Mitsuba's (both sides inside a `twosided`) |

use lamplight_core::math::Rgb;
use lamplight_core::params::{Entry, Item, Loc, ParamError, Value};

use super::properties::{Plugin, PropValue};
use super::rough::rough;
use super::textures::{colour_or_texture, number, number_or_texture, scalar_texture, texture};
use super::xml::El;
use super::{conductors::CONDUCTORS, entry, num, table, table_of, text, vec3, Ctx};

/// Mitsuba's named indices of refraction (`include/mitsuba/render/ior.h`).
pub const IORS: &[(&str, f64)] = &[
    ("vacuum", 1.0),
    ("helium", 1.00004),
    ("hydrogen", 1.00013),
    ("air", 1.00028),
    ("carbon dioxide", 1.00045),
    ("water", 1.333),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.47),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.575),
    ("diamond", 2.419),
];

/// The name of Mitsuba's default BSDF (diffuse 0.5) as a material.
pub const DEFAULT_MATERIAL: &str = "mitsuba_default_diffuse";
/// The name of the BSDF Mitsuba gives an emitting shape without one (diffuse 0: black).
pub const DEFAULT_EMITTER_MATERIAL: &str = "mitsuba_default_emitter";

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// The material name of the `<bsdf>` `el`, made on first use.
pub fn material_name<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<String, ParamError> {
    if let Some(id) = el.get("id") {
        if let Some(name) = ctx.material_ids.get(id) {
            return Ok(name.clone());
        }
    }
    let reads = ctx.attribute_reads.len();
    let entries = material(ctx, el)?;
    let entries = super::sided::mark(ctx, el, entries)?;
    let name = match el.get("id") {
        Some(id) if !ctx.materials.iter().any(|m| m.key == id) => id.to_string(),
        _ => ctx.fresh("bsdf"),
    };
    if let Some(id) = el.get("id") {
        ctx.material_ids.insert(id.to_string(), name.clone());
    }
    ctx.materials.push(entry(&name, table(entries, el.loc.clone())));
    let used = ctx.attribute_reads[reads..].to_vec();
    ctx.material_attributes.insert(name.clone(), used);
    Ok(name)
}

/// Mitsuba's default BSDF, made once: diffuse 0.5, or 0 (black) on an emitting shape.
pub fn default_material(ctx: &mut Ctx<'_>, emitting: bool) -> String {
    let (name, albedo) = if emitting { (DEFAULT_EMITTER_MATERIAL, 0.0) } else { (DEFAULT_MATERIAL, 0.5) };
    if !ctx.materials.iter().any(|m| m.key == name) {
        let loc = Loc::Unknown;
        // Mitsuba's default diffuse is one-sided, as every diffuse ([`super::sided`]).
        let mut e = diffuse(vec3(Rgb::splat(albedo), &loc), &loc);
        e.push(entry("sided", text("front", &loc)));
        let t = table(e, loc.clone());
        ctx.materials.push(entry(name, t));
    }
    name.to_string()
}

fn diffuse(color: Item, loc: &Loc) -> Vec<Entry> {
    vec![
        entry("type", text("phong", loc)),
        entry("color", color),
        entry("kd", num(1.0, loc)),
        entry("ka", num(0.0, loc)),
        entry("ks", num(0.0, loc)),
    ]
}

fn black(loc: &Loc) -> Vec<Entry> {
    vec![entry("type", text("phong", loc)), entry("kd", num(0.0, loc)), entry("ka", num(0.0, loc)), entry("ks", num(0.0, loc))]
}

/// The nested BSDF of a wrapper (`twosided`, `mask`, `normalmap`, `bumpmap`).
fn nested<'a>(ctx: &mut Ctx<'a>, p: &Plugin<'a>) -> Result<Vec<Entry>, ParamError> {
    let mut found = None;
    for &o in &p.objects {
        let t = ctx.deref(o)?;
        if t.tag == "bsdf" {
            if found.is_some() {
                ctx.warn(&o.loc, format!("{}: a second nested BSDF is not supported, the first is used", p.label));
                continue;
            }
            found = Some(t);
        }
    }
    let inner = found.ok_or_else(|| err(&p.el.loc, format!("{}: needs a nested <bsdf>", p.label)))?;
    material(ctx, inner)
}

/// The texturable scalars of `principled`, with lamplight's names (the same).
const PRINCIPLED_SCALARS: [&str; 10] =
    ["roughness", "anisotropic", "metallic", "spec_trans", "spec_tint", "sheen", "sheen_tint", "clearcoat", "clearcoat_gloss", "flatness"];

/// The texturable scalars of `principledthin` (lamplight's `principled_thin`,
/// the same names); `eta` too, read per hit as Mitsuba's `eval_1` reads it.
const THIN_SCALARS: [&str; 9] =
    ["roughness", "anisotropic", "spec_trans", "diff_trans", "eta", "spec_tint", "sheen", "sheen_tint", "flatness"];

/// `principledthin`: lamplight's `principled_thin` material of the same parameters.
fn principled_thin<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, loc: &Loc) -> Result<Vec<Entry>, ParamError> {
    let mut e =
        vec![entry("type", text("principled_thin", loc)), entry("base_color", colour_or_texture(ctx, p, "base_color", Rgb::splat(0.5))?)];
    for key in THIN_SCALARS {
        if let Some(item) = number_or_texture(ctx, p, key)? {
            e.push(entry(key, item));
        }
    }
    for key in [
        "specular_reflectance_sampling_rate",
        "specular_transmittance_sampling_rate",
        "diffuse_reflectance_sampling_rate",
        "diffuse_transmittance_sampling_rate",
    ] {
        if let Some((v, vloc)) = p.number(key)? {
            e.push(entry(key, num(v, &vloc)));
        }
    }
    Ok(e)
}

/// `principled`: lamplight's `principled` material of the same parameters.
fn principled<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, loc: &Loc) -> Result<Vec<Entry>, ParamError> {
    let mut e =
        vec![entry("type", text("principled", loc)), entry("base_color", colour_or_texture(ctx, p, "base_color", Rgb::splat(0.5))?)];
    for key in PRINCIPLED_SCALARS {
        if let Some(item) = number_or_texture(ctx, p, key)? {
            e.push(entry(key, item));
        }
    }
    if p.has("eta") && p.has("specular") {
        return Err(err(loc, format!("{}: give either eta or specular, not both (as Mitsuba)", p.label)));
    }
    // Mitsuba refuses a texture in these two ("expected float, got object").
    for key in ["eta", "specular"] {
        if let Some(o) = p.object(key) {
            return Err(err(&o.loc, format!("{}: {key}: expected a float, got a <{}> (Mitsuba takes no texture here)", p.label, o.tag)));
        }
    }
    for key in ["eta", "specular", "diffuse_reflectance_sampling_rate", "main_specular_sampling_rate", "clearcoat_sampling_rate"] {
        if let Some((v, vloc)) = p.number(key)? {
            e.push(entry(key, num(v, &vloc)));
        }
    }
    Ok(e)
}

/// An index of refraction: a number or one of [`IORS`].
fn ior(p: &mut Plugin<'_>, key: &str, default: &str) -> Result<(f64, Loc), ParamError> {
    let label = p.label.clone();
    let named = |name: &str, loc: &Loc| -> Result<f64, ParamError> {
        IORS.iter().find(|(n, _)| *n == name.to_ascii_lowercase()).map(|(_, v)| *v).ok_or_else(|| {
            err(
                loc,
                format!(
                    "{label}: {key}: unknown material \"{name}\" (expected a number or {})",
                    IORS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                ),
            )
        })
    };
    match p.take(key) {
        None => Ok((named(default, &p.el.loc)?, p.el.loc.clone())),
        Some(prop) => match prop.value {
            PropValue::Float(v) if v > 0.0 => Ok((v, prop.loc)),
            PropValue::Str(s) => Ok((named(&s, &prop.loc)?, prop.loc)),
            _ => Err(err(&prop.loc, format!("{label}: {key}: expected a positive number or a material name"))),
        },
    }
}

/// The `map_shadowing` entry of a `normalmap` or `bumpmap`: Mitsuba's
/// `use_shadowing_function` (on by default). Its `flip_invalid_normals` is read
/// and has no counterpart: lamplight bends a mapped normal that faces away
/// from the viewer back towards it ([`lamplight_core::materials::normal_map::facing`]).
fn map_shadowing(p: &mut Plugin<'_>) -> Result<Vec<Entry>, ParamError> {
    let _ = p.boolean("flip_invalid_normals")?;
    let (on, loc) = p.boolean("use_shadowing_function")?.unwrap_or((true, p.el.loc.clone()));
    Ok(vec![entry("map_shadowing", super::boolean(on, &loc))])
}

/// Warns when the optional `key` (a colour factor lamplight does not have) is not 1.
fn unit_factor(ctx: &mut Ctx<'_>, p: &mut Plugin<'_>, key: &str) -> Result<(), ParamError> {
    if let Some(o) = p.object(key) {
        return Err(err(&o.loc, format!("{}: {key}: a texture here is not supported", p.label)));
    }
    if let Some((c, loc)) = p.color(key)? {
        if c != Rgb::ONE {
            return Err(err(&loc, format!("{}: {key}: only 1 is supported, got {c}", p.label)));
        }
    }
    let _ = ctx;
    Ok(())
}

/// `blendbsdf`: lamplight's `blend` of its two nested BSDFs (material tables
/// in place, each one-sided as Mitsuba's), by `weight` (a number or a
/// texture, 0.5 by default).
fn blend<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>) -> Result<Vec<Entry>, ParamError> {
    let loc = p.el.loc.clone();
    let weight = match p.object("weight") {
        Some(o) => {
            let t = ctx.deref(o)?;
            super::textures::scalar_texture(ctx, t)?
        }
        None => {
            let (w, wloc) = p.number_or("weight", 0.5)?;
            if !(0.0..=1.0).contains(&w) {
                return Err(err(&wloc, format!("{}: weight: must be between 0 and 1, got {w}", p.label)));
            }
            num(w, &wloc)
        }
    };
    let mut parts = Vec::new();
    for &o in &p.objects {
        let t = ctx.deref(o)?;
        if t.tag != "bsdf" {
            continue;
        }
        // In place even when referenced: a `twosided` around the blend must
        // reach its components ([`super::sided::both_sides`]).
        let entries = material(ctx, t)?;
        let entries = super::sided::mark(ctx, t, entries)?;
        parts.push(table(entries, o.loc.clone()));
    }
    let [a, b]: [Item; 2] =
        parts.try_into().map_err(|parts: Vec<Item>| err(&loc, format!("{}: needs two nested BSDFs, got {}", p.label, parts.len())))?;
    Ok(vec![entry("type", text("blend", &loc)), entry("weight", weight), entry("a", a), entry("b", b)])
}

/// The `phong` or `pbr` entries of the `<bsdf>` `el`.
pub fn material<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<Vec<Entry>, ParamError> {
    let el = ctx.deref(el)?;
    if el.tag != "bsdf" {
        return Err(err(&el.loc, format!("expected a <bsdf>, got <{}>", el.tag)));
    }
    let mut p = Plugin::new(el)?;
    let loc = el.loc.clone();
    let entries = match p.kind.as_str() {
        "diffuse" => {
            let c = colour_or_texture(ctx, &mut p, "reflectance", Rgb::splat(0.5))?;
            diffuse(c, &loc)
        }
        "conductor" | "roughconductor" => {
            let (eta, k, eloc) = match (p.color("eta")?, p.color("k")?) {
                (Some((eta, l)), Some((k, _))) => (eta, k, l),
                (None, None) => {
                    let (name, l) = p.string("material")?.unwrap_or(("none".into(), loc.clone()));
                    let (_, eta, k) = CONDUCTORS.iter().find(|(n, _, _)| *n == name).ok_or_else(|| {
                        err(
                            &l,
                            format!(
                                "{}: material: unknown conductor \"{name}\" (expected one of {})",
                                p.label,
                                CONDUCTORS.iter().map(|c| c.0).collect::<Vec<_>>().join(", ")
                            ),
                        )
                    })?;
                    (Rgb::from_array(*eta), Rgb::from_array(*k), l)
                }
                _ => return Err(err(&loc, format!("{}: give both eta and k, or material", p.label))),
            };
            let _ = ior(&mut p, "ext_eta", "air").ok();
            unit_factor(ctx, &mut p, "specular_reflectance")?;
            let mut e = black(&loc);
            e.push(entry(
                "reflection",
                table_of(vec![("type", text("conductor", &eloc)), ("eta", vec3(eta, &eloc)), ("k", vec3(k, &eloc))], &eloc),
            ));
            if p.kind == "roughconductor" {
                e.extend(rough(ctx, &mut p, true, true)?);
            }
            e
        }
        "dielectric" | "roughdielectric" => {
            let (int, iloc) = ior(&mut p, "int_ior", "bk7")?;
            let (ext, _) = ior(&mut p, "ext_ior", "air")?;
            unit_factor(ctx, &mut p, "specular_reflectance")?;
            unit_factor(ctx, &mut p, "specular_transmittance")?;
            let eta = int / ext;
            let mut e = black(&loc);
            e.push(entry("reflection", table_of(vec![("type", text("dielectric", &iloc)), ("ior", num(eta, &iloc))], &iloc)));
            e.push(entry("refraction", table_of(vec![("type", text("fresnel", &iloc)), ("ior", num(eta, &iloc))], &iloc)));
            if p.kind == "roughdielectric" {
                e.extend(rough(ctx, &mut p, true, true)?);
            }
            e
        }
        "plastic" | "roughplastic" => {
            let base = colour_or_texture(ctx, &mut p, "diffuse_reflectance", Rgb::splat(0.5))?;
            let (int, iloc) = ior(&mut p, "int_ior", "polypropylene")?;
            let (ext, eloc) = ior(&mut p, "ext_ior", "air")?;
            if p.kind == "roughplastic" && int == ext {
                return Err(err(&iloc, format!("{}: int_ior and ext_ior must differ", p.label)));
            }
            let mut e = vec![
                entry("type", text("plastic", &loc)),
                entry("diffuse_reflectance", base),
                entry("int_ior", num(int, &iloc)),
                entry("ext_ior", num(ext, &eloc)),
            ];
            if let Some(o) = p.object("specular_reflectance") {
                return Err(err(&o.loc, format!("{}: specular_reflectance: a texture here is not supported", p.label)));
            }
            if let Some((c, cloc)) = p.color("specular_reflectance")? {
                e.push(entry("specular_reflectance", vec3(c, &cloc)));
            }
            if let Some((b, bloc)) = p.boolean("nonlinear")? {
                e.push(entry("nonlinear", super::boolean(b, &bloc)));
            }
            if p.kind == "roughplastic" {
                // Mitsuba's `roughplastic` is isotropic: `alpha` only.
                e.extend(rough(ctx, &mut p, false, false)?);
                if e.iter().any(|x| x.key == "roughness" && matches!(x.item.value, Value::Number(a) if a == 0.0)) {
                    // lamplight's roughness 0 is the smooth coating; Mitsuba clamps to 1e-4.
                    e.retain(|x| x.key != "roughness");
                    e.push(entry("roughness", num(1e-4, &loc)));
                }
            }
            e
        }
        "thindielectric" => {
            let (int, iloc) = ior(&mut p, "int_ior", "bk7")?;
            let (ext, eloc) = ior(&mut p, "ext_ior", "air")?;
            unit_factor(ctx, &mut p, "specular_reflectance")?;
            unit_factor(ctx, &mut p, "specular_transmittance")?;
            vec![entry("type", text("thin_dielectric", &loc)), entry("int_ior", num(int, &iloc)), entry("ext_ior", num(ext, &eloc))]
        }
        "twosided" => super::sided::both_sides(nested(ctx, &p)?),
        "null" => {
            let mut e = black(&loc);
            e.push(entry("alpha", num(0.0, &loc)));
            e
        }
        "mask" => {
            let opacity = match p.object("opacity") {
                // Mitsuba reads the opacity through `eval_1`.
                Some(o) => {
                    let t = ctx.deref(o)?;
                    scalar_texture(ctx, t)?
                }
                None => {
                    let (a, aloc) = p.number_or("opacity", 0.5)?;
                    num(a, &aloc)
                }
            };
            let mut e = nested(ctx, &p)?;
            e.retain(|x| x.key != "alpha" && x.key != "alpha_mode" && x.key != "alpha_cutoff");
            e.push(entry("alpha", opacity));
            // Mitsuba keeps the surface with probability `opacity`: lamplight's blend.
            e.push(entry("alpha_mode", text("blend", &loc)));
            e
        }
        "normalmap" => {
            let o = p.object("normalmap").ok_or_else(|| err(&loc, "bsdf \"normalmap\": needs a nested <texture name=\"normalmap\">"))?;
            let t = ctx.deref(o)?;
            let mut map = texture(ctx, t)?;
            if let Value::Table(tt) = &mut map.value {
                tt.entries.retain(|x| x.key != "color_space");
                tt.entries.push(entry("color_space", text("linear", &t.loc)));
            }
            let mut e = nested(ctx, &p)?;
            e.retain(|x| x.key != "normal_map" && x.key != "map_shadowing");
            e.push(entry("normal_map", map));
            e.extend(map_shadowing(&mut p)?);
            e
        }
        "bumpmap" => {
            // Mitsuba names the height texture freely; it is the one nested <texture>.
            let mut height = None;
            for &o in &p.objects {
                let t = ctx.deref(o)?;
                if t.tag == "texture" && height.replace(t).is_some() {
                    return Err(err(&o.loc, "bsdf \"bumpmap\": expected one nested <texture> (the height)"));
                }
            }
            let t = height.ok_or_else(|| err(&loc, "bsdf \"bumpmap\": needs a nested <texture> (the height)"))?;
            let mut map = texture(ctx, t)?;
            // A bitmap's heights are raw values, as Mitsuba reads them.
            if let Value::Table(tt) = &mut map.value {
                if tt.entries.iter().any(|x| x.key == "file") {
                    tt.entries.retain(|x| x.key != "color_space");
                    tt.entries.push(entry("color_space", text("linear", &t.loc)));
                }
            }
            let (scale, sloc) = number(&mut p, "scale", 1.0)?;
            let mut e = nested(ctx, &p)?;
            e.retain(|x| x.key != "bump" && x.key != "bump_scale" && x.key != "map_shadowing");
            e.push(entry("bump", map));
            e.push(entry("bump_scale", num(scale, &sloc)));
            e.extend(map_shadowing(&mut p)?);
            e
        }
        "principled" => principled(ctx, &mut p, &loc)?,
        "principledthin" => principled_thin(ctx, &mut p, &loc)?,
        "blendbsdf" => blend(ctx, &mut p)?,
        "hair" | "measured" | "polarizer" | "retarder" | "pplastic" => {
            return Err(err(&p.el.require("type")?.loc, format!("{}: not yet supported (no lamplight material gives its image)", p.label)))
        }
        other => return Err(err(&p.el.require("type")?.loc, format!("bsdf \"{other}\": unknown BSDF"))),
    };
    for o in p.objects.clone() {
        let t = ctx.deref(o)?;
        if !matches!(t.tag.as_str(), "bsdf" | "texture") {
            ctx.warn(&o.loc, format!("{}: nested <{}> is not supported, ignored", p.label, t.tag));
        }
    }
    ctx.finish(p);
    Ok(entries)
}
