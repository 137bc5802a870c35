//! `<texture>` to texture tables, and the colour-or-texture parameters of BSDFs.
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `bitmap` `filename`, `filter_type` (`bilinear`, `nearest`), `wrap_mode` (`repeat`, `mirror`, `clamp`), `raw` | `image` `file`, `filter`, `wrap`, `color_space` (`raw = true`: `"linear"`) |
//! | `to_uv` `(u, v) -> (s_u u + t_u, s_v v + t_v)` | `uv_scale = [s_u, s_v]`, `uv_offset = [t_u, 1 - s_v - t_v]` |
//! | `checkerboard` `color0` (0.4), `color1` (0.2), `to_uv` | `uv_checker` `even = color0`, `odd = color1`, `uv_scale = [2 s_u, -2 s_v]`, `uv_offset = [2 t_u, 2 (s_v + t_v)]`; where Mitsuba reads one channel (`blendbsdf`'s `weight`) `even = color1`, `odd = color0`, as its `eval_1` does ([`scalar_texture`]) |
//! | `mesh_attribute` `name` (`vertex_...`, `face_...`), `scale` | `vertex_color` (times `scale`), the shape's `[meshes]` `color = name` (a PLY attribute as Mitsuba names it; one per shape) |
//! | `rawconstant` `value` (a float or a 3D vector) | the constant colour (a float as a grey) |
//!
//! Mitsuba's `v` is lamplight's `1 - v`: Mitsuba flips a mesh file's `v` and
//! reads images from the top row, lamplight keeps the file's `v` and reads
//! images from the bottom row. So an image agrees without a flip and `to_uv`'s
//! offset and the checkerboard's cells are mirrored in `v` (the formulas above
//! follow from `v_mitsuba = 1 - v`). Built-in shapes' own coordinates differ
//! from Mitsuba's (see docs/mitsuba.md).

use lamplight_core::math::{Mat4, Rgb};
use lamplight_core::params::{Item, Loc, ParamError};

use super::properties::{Plugin, PropValue};
use super::xml::El;
use super::{num, pair, table_of, text, vec3, Ctx};

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// Parameter `key` of `p` as a colour (an `<rgb>`, `<spectrum>` or `<float>`) or
/// a nested or referenced texture; `default` when absent.
pub fn colour_or_texture<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, key: &str, default: Rgb) -> Result<Item, ParamError> {
    if let Some(o) = p.object(key) {
        let t = ctx.deref(o)?;
        if t.tag != "texture" {
            return Err(err(&o.loc, format!("{}: {key}: expected a colour or a <texture>, got <{}>", p.label, t.tag)));
        }
        return texture(ctx, t);
    }
    let (c, loc) = p.color(key)?.unwrap_or((default, p.el.loc.clone()));
    Ok(vec3(c, &loc))
}

/// Parameter `key` of `p` as a number or a nested or referenced texture (read
/// by lamplight through its first channel, by Mitsuba through `eval_1`:
/// [`scalar_texture`]); `None` when absent.
pub fn number_or_texture<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, key: &str) -> Result<Option<Item>, ParamError> {
    if let Some(o) = p.object(key) {
        let t = ctx.deref(o)?;
        if t.tag != "texture" {
            return Err(err(&o.loc, format!("{}: {key}: expected a number or a <texture>, got <{}>", p.label, t.tag)));
        }
        return scalar_texture(ctx, t).map(Some);
    }
    Ok(p.number(key)?.map(|(v, loc)| super::num(v, &loc)))
}

/// A `<texture>` read where Mitsuba evaluates one channel (`eval_1`, as
/// `blendbsdf`'s `weight`): as [`texture`], except that a `checkerboard`'s
/// colours trade places, because Mitsuba 3.9's checkerboard `eval_1` returns
/// `color1` where its `eval` returns `color0` (measured: at `uv = (0.1, 0.1)`
/// with `to_uv` scale 3, `eval` gives `color0` and `eval_1` `color1`).
pub fn scalar_texture<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<Item, ParamError> {
    let mut item = texture(ctx, el)?;
    if el.get("type") == Some("checkerboard") {
        if let lamplight_core::params::Value::Table(t) = &mut item.value {
            for e in &mut t.entries {
                match e.key.as_str() {
                    "even" => e.key = "odd".into(),
                    "odd" => e.key = "even".into(),
                    _ => {}
                }
            }
        }
    }
    Ok(item)
}

/// Parameter `key` as a number (a texture is an error: `what` says why).
pub fn number<'a>(p: &mut Plugin<'a>, key: &str, default: f64) -> Result<(f64, Loc), ParamError> {
    if let Some(o) = p.object(key) {
        return Err(err(&o.loc, format!("{}: {key}: a texture here is not supported, expected a number", p.label)));
    }
    p.number_or(key, default)
}

/// A `to_uv`'s scale, offset and place.
type UvTransform = ([f64; 2], [f64; 2], Loc);

/// A `<texture>` element as a texture table.
pub fn texture<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<Item, ParamError> {
    let mut p = Plugin::new(el)?;
    let loc = el.loc.clone();
    let uv = |p: &mut Plugin<'_>| -> Result<Option<UvTransform>, ParamError> {
        let Some((m, mloc)) = p.transform("to_uv")? else { return Ok(None) };
        scale_offset(&m).map(|(s, o)| Some((s, o, mloc.clone()))).ok_or_else(|| {
            err(&mloc, format!("{}: to_uv: only a scale and a translation are supported (lamplight's uv_scale and uv_offset)", p.label))
        })
    };
    let table = match p.kind.as_str() {
        "bitmap" => {
            let (f, floc) = p.string("filename")?.ok_or_else(|| err(&loc, "texture \"bitmap\": needs filename"))?;
            let file = ctx.file(&f, &floc)?;
            let mut pairs = vec![("type", text("image", &loc)), ("file", text(&file, &floc))];
            if let Some((filter, l)) = p.string("filter_type")? {
                let v = match filter.as_str() {
                    "bilinear" => "bilinear",
                    "nearest" => "nearest",
                    _ => return Err(err(&l, format!("texture \"bitmap\": filter_type: expected bilinear or nearest, got \"{filter}\""))),
                };
                pairs.push(("filter", text(v, &l)));
            }
            if let Some((wrap, l)) = p.string("wrap_mode")? {
                let v = match wrap.as_str() {
                    "repeat" => "repeat",
                    "mirror" => "mirror",
                    "clamp" => "clamp",
                    _ => return Err(err(&l, format!("texture \"bitmap\": wrap_mode: expected repeat, mirror or clamp, got \"{wrap}\""))),
                };
                pairs.push(("wrap", text(v, &l)));
            }
            let hdr = ["exr", "hdr"].iter().any(|e| file.to_ascii_lowercase().ends_with(e));
            if let Some((true, l)) = p.boolean("raw")? {
                if !hdr {
                    pairs.push(("color_space", text("linear", &l)));
                }
            }
            if let Some((s, o, l)) = uv(&mut p)? {
                pairs.push(("uv_scale", pair(s[0], s[1], &l)));
                pairs.push(("uv_offset", pair(o[0], 1.0 - s[1] - o[1], &l)));
            }
            let _ = p.string("format")?;
            table_of(pairs, &loc)
        }
        "checkerboard" => {
            let even = colour_or_texture(ctx, &mut p, "color0", Rgb::splat(0.4))?;
            let odd = colour_or_texture(ctx, &mut p, "color1", Rgb::splat(0.2))?;
            let (s, o, l) = uv(&mut p)?.unwrap_or(([1.0, 1.0], [0.0, 0.0], loc.clone()));
            table_of(
                vec![
                    ("type", text("uv_checker", &loc)),
                    ("even", even),
                    ("odd", odd),
                    ("uv_scale", pair(2.0 * s[0], -2.0 * s[1], &l)),
                    ("uv_offset", pair(2.0 * o[0], 2.0 * (s[1] + o[1]), &l)),
                ],
                &loc,
            )
        }
        "mesh_attribute" => {
            // The mesh's colour (lamplight's `vertex_color` texture); the shape
            // it is placed on takes its values from the attribute `name`
            // (`[meshes] color`, set by [`super::shapes`]).
            let (name, l) = p.string("name")?.ok_or_else(|| err(&loc, "texture \"mesh_attribute\": needs name"))?;
            if !(name.starts_with("vertex_") || name.starts_with("face_")) {
                return Err(err(&l, format!("texture \"mesh_attribute\": name: expected \"vertex_...\" or \"face_...\", got \"{name}\"")));
            }
            ctx.attribute_reads.push((name, l.clone()));
            if let Some((s, sl)) = p.number("scale")? {
                return Ok(table_of(
                    vec![
                        ("type", text("scale", &loc)),
                        ("texture", table_of(vec![("type", text("vertex_color", &loc))], &loc)),
                        ("scale", num(s, &sl)),
                    ],
                    &loc,
                ));
            }
            table_of(vec![("type", text("vertex_color", &l))], &loc)
        }
        "rawconstant" => {
            // Mitsuba's raw value: a float or a 3D vector, used as it is (no
            // spectral upsampling, which scalar_rgb does not do to an <rgb> either).
            let value = p.take("value").ok_or_else(|| err(&loc, "texture \"rawconstant\": needs value (a float or a vector)"))?;
            match value.value {
                PropValue::Float(v) => vec3(Rgb::splat(v), &value.loc),
                PropValue::Integer(v) => vec3(Rgb::splat(v as f64), &value.loc),
                PropValue::Vec3(v) => vec3(v, &value.loc),
                other => {
                    return Err(err(
                        &value.loc,
                        format!("texture \"rawconstant\": value: expected a float or a 3D vector, got {}", other.describe()),
                    ))
                }
            }
        }
        other => {
            return Err(err(
                &p.el.require("type")?.loc,
                format!("texture \"{other}\": not supported (lamplight reads bitmap, checkerboard, mesh_attribute, rawconstant)"),
            ))
        }
    };
    ctx.finish(p);
    Ok(table)
}

/// `uv' = s uv + o` when `m` (Mitsuba's 2D `to_uv`, written as a 4x4) is only that.
fn scale_offset(m: &Mat4) -> Option<([f64; 2], [f64; 2])> {
    let c = m.to_cols_array_2d();
    (c[1][0] == 0.0 && c[0][1] == 0.0).then_some(([c[0][0], c[1][1]], [c[3][0], c[3][1]]))
}
