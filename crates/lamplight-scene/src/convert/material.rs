//! An imported [`Material`] written as the `[materials.NAME]` table of the
//! kind that builds it back: `pbr` for glTF's metallic-roughness materials and
//! MTL's PBR extension (glTF's transmission included), `phong` for the rest
//! (MTL's lecture model), every field written out, so that the user edits
//! numbers and texture files in the TOML.
//!
//! A material is written from what the importer built, then read back through
//! the registry's kind and compared with the original ([`same_material`]);
//! one that does not come back the same is refused with what differs, never
//! written approximately. Textures name their image files
//! ([`super::images::Images`]); a fixed UV transform is written as
//! `uv_scale`, `uv_rotate` and `uv_offset` when those give the same matrix.

use std::sync::Arc;

use lamplight_core::materials::image::{Channel, Filter, Wrap};
use lamplight_core::materials::{self, Material, Reflection, Refraction, Slot, Texture, Textures, UvTransform};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::params::{Entry, Item, Kind, Loc, Params, Table, Value};

use super::images::Images;
use crate::registry;

/// A table of `(key, value)` pairs in order.
pub(super) fn table(entries: Vec<(&str, Value)>) -> Table {
    Table {
        entries: entries.into_iter().map(|(k, v)| Entry { key: k.to_string(), key_loc: Loc::Unknown, item: item(v) }).collect(),
        loc: Loc::Unknown,
    }
}

pub(super) fn item(value: Value) -> Item {
    Item { value, loc: Loc::Unknown }
}

/// A number.
pub(super) fn num(x: f64) -> Value {
    Value::Number(x)
}

/// `[x, y, z]`.
pub(super) fn vec3(v: Vec3) -> Value {
    Value::Array(vec![item(num(v.x)), item(num(v.y)), item(num(v.z))])
}

/// A colour: one number when grey, else `[r, g, b]`.
pub(super) fn rgb(c: Rgb) -> Value {
    if c.x == c.y && c.y == c.z {
        num(c.x)
    } else {
        vec3(c)
    }
}

fn string(s: &str) -> Value {
    Value::String(s.to_string())
}

/// The material's table (with its `type`), or why it has none.
pub(super) fn material_table(m: &Material, images: &mut Images) -> Result<Table, String> {
    let mut out: Vec<(&str, Value)> = Vec::new();
    let slot = |s: Slot| m.textures.as_ref().and_then(|t| t.iter().find(|(k, _)| *k == s).map(|(_, t)| t.clone()));
    let slot_or = |s: Slot, constant: Value, images: &mut Images| -> Result<Value, String> {
        match slot(s) {
            Some(t) => texture(&t, images),
            None => Ok(constant),
        }
    };
    match &m.pbr {
        Some(pbr) => {
            out.push(("type", string("pbr")));
            out.push(("base_color", texture(&m.color, images)?));
            out.push(("metallic", slot_or(materials::pbr::METALLIC, num(pbr.metallic), images)?));
            out.push(("roughness", slot_or(Slot::ROUGHNESS, num(m.roughness), images)?));
            out.push(("ior", num(pbr.ior)));
            out.push(("specular", slot_or(materials::pbr::SPECULAR, num(pbr.specular), images)?));
            out.push(("specular_color", slot_or(materials::pbr::SPECULAR_COLOR, rgb(pbr.specular_color), images)?));
            out.push(("transmission", slot_or(materials::pbr::TRANSMISSION, num(pbr.transmission), images)?));
            out.push(("emission", slot_or(Slot::EMISSION, rgb(m.emission), images)?));
        }
        None => {
            out.push(("type", string("phong")));
            out.push(("color", texture(&m.color, images)?));
            out.push(("ka", slot_or(Slot::KA, rgb(m.ka), images)?));
            out.push(("kd", slot_or(Slot::KD, rgb(m.kd), images)?));
            out.push(("ks", slot_or(Slot::KS, rgb(m.ks), images)?));
            out.push(("shininess", slot_or(Slot::SHININESS, num(m.shininess), images)?));
            out.push(("emission", slot_or(Slot::EMISSION, rgb(m.emission), images)?));
            if let Some(r) = reflection(&m.reflection) {
                out.push(("reflection", r));
            }
            if let Some(r) = refraction(&m.refraction) {
                out.push(("refraction", r));
            }
            out.push(("shadow_transmittance", slot_or(Slot::SHADOW_TRANSMITTANCE, rgb(m.shadow_transmittance), images)?));
            out.push(("roughness", slot_or(Slot::ROUGHNESS, num(m.roughness), images)?));
        }
    }
    out.push(("two_sided", Value::Bool(m.two_sided)));
    if let Some(n) = &m.normal_map {
        out.push(("normal_map", texture(&n.texture, images)?));
        out.push(("normal_scale", num(n.scale)));
    }
    if let Some(b) = &m.bump {
        out.push(("bump", texture(&b.texture, images)?));
        out.push(("bump_scale", num(b.scale)));
    }
    if let Some(a) = &m.alpha {
        out.push(("alpha", texture(&a.texture, images)?));
        out.push(("alpha_cutoff", num(a.cutoff)));
        out.push(("alpha_mode", string(if a.blend { "blend" } else { "mask" })));
    }
    Ok(table(out))
}

fn reflection(r: &Reflection) -> Option<Value> {
    Some(Value::Table(match r {
        Reflection::None => return None,
        Reflection::Constant(c) => table(vec![("type", string("constant")), ("weight", rgb(*c))]),
        Reflection::Dielectric { ior, min, max } => {
            table(vec![("type", string("dielectric")), ("ior", num(*ior)), ("min", num(*min)), ("max", num(*max))])
        }
        Reflection::Conductor { eta, k } => table(vec![("type", string("conductor")), ("eta", vec3(*eta)), ("k", vec3(*k))]),
    }))
}

fn refraction(r: &Refraction) -> Option<Value> {
    Some(Value::Table(match r {
        Refraction::None => return None,
        Refraction::Fresnel { ior } => table(vec![("type", string("fresnel")), ("ior", num(*ior))]),
        Refraction::Constant { ior, weight } => table(vec![("type", string("constant")), ("ior", num(*ior)), ("weight", rgb(*weight))]),
    }))
}

/// A texturable value: a colour, or the table of the texture kind that builds `t`.
fn texture(t: &Texture, images: &mut Images) -> Result<Value, String> {
    Ok(Value::Table(match t {
        Texture::Constant(c) => return Ok(rgb(*c)),
        Texture::Checker { size, even, odd, offset } => table(vec![
            ("type", string("checker")),
            ("size", num(*size)),
            ("even", rgb(*even)),
            ("odd", rgb(*odd)),
            ("offset", vec3(*offset)),
        ]),
        Texture::UvChecker(c) => {
            let mut entries = vec![("type", string("uv_checker")), ("even", rgb(c.even)), ("odd", rgb(c.odd))];
            entries.extend(uv_transform(&c.transform)?);
            table(entries)
        }
        Texture::Image(i) => {
            let (file, srgb) = images.name(&i.image)?;
            let wrap = match i.wrap {
                Wrap::Repeat => "repeat",
                Wrap::Mirror => "mirror",
                Wrap::Clamp => "clamp",
            };
            let filter = match i.filter {
                Filter::Nearest => "nearest",
                Filter::Bilinear => "bilinear",
                Filter::Trilinear => "trilinear",
            };
            let channel = match i.channel {
                Channel::Rgb => "rgb",
                Channel::One(0) => "r",
                Channel::One(1) => "g",
                Channel::One(2) => "b",
                Channel::One(_) => "a",
            };
            let mut entries = vec![
                ("type", string("image")),
                ("file", Value::String(file)),
                ("color_space", string(if srgb { "srgb" } else { "linear" })),
                ("wrap", string(wrap)),
                ("filter", string(filter)),
                ("channel", string(channel)),
            ];
            entries.extend(uv_transform(&i.transform)?);
            table(entries)
        }
        Texture::Scale(f) => {
            table(vec![("type", string("scale")), ("texture", texture(&f[0], images)?), ("scale", texture(&f[1], images)?)])
        }
        Texture::Mix(f) => table(vec![
            ("type", string("mix")),
            ("a", texture(&f[0], images)?),
            ("b", texture(&f[1], images)?),
            ("amount", texture(&f[2], images)?),
        ]),
        Texture::VertexColor => table(vec![("type", string("vertex_color"))]),
        Texture::SecondUv(t) => table(vec![("type", string("uv_set")), ("set", Value::Integer(1)), ("texture", texture(t, images)?)]),
    }))
}

/// `uv_scale`, `uv_rotate` (degrees) and `uv_offset` giving exactly `t`
/// (nothing for the identity), or why there are none.
fn uv_transform(t: &UvTransform) -> Result<Vec<(&'static str, Value)>, String> {
    if *t == UvTransform::IDENTITY {
        return Ok(Vec::new());
    }
    let [[a, b, c], [d, e, f]] = t.0;
    // t = T(offset) R(angle) S(scale): the first column is R (sx, 0), the second R (0, sy).
    let angle = d.atan2(a);
    let (sx, sy) = (a.hypot(d), b.hypot(e) * if (-b * angle.sin() + e * angle.cos()) < 0.0 { -1.0 } else { 1.0 });
    let degrees = angle.to_degrees();
    if UvTransform::new([sx, sy], degrees.to_radians(), [c, f]) != *t {
        return Err(format!("its UV transform {:?} has no exact uv_scale/uv_rotate/uv_offset form", t.0));
    }
    let pair = |x: f64, y: f64| Value::Array(vec![item(num(x)), item(num(y))]);
    Ok(vec![("uv_scale", pair(sx, sy)), ("uv_rotate", num(degrees)), ("uv_offset", pair(c, f))])
}

/// Builds the material `table` through the registry, as a scene file would,
/// with the images `images` names.
pub(super) fn read_back(table_: &Table, images: &Images) -> Result<Material, String> {
    let node = crate::description::Node::from_table(table_.clone(), "material", Some("phong"), false).map_err(|e| e.message)?;
    let kind = Kind::find(registry::MATERIALS, &node.kind).ok_or("unknown material kind")?;
    let textures = Textures { kinds: registry::TEXTURES, images: Some(images), materials: None };
    let p = Params::new("material", &node.params);
    p.read(kind.params, &[], |p| (kind.build)(p, &textures)).map_err(|e| e.message)
}

/// Whether two materials render the same: equal, except for the order of
/// their textured parameters and the constants a texture replaces (which a
/// material kind sets to its default while an importer keeps the factor; a
/// textured field is overwritten at every shading point, and the lecture
/// terms derived from it with it).
pub(super) fn same_material(a: &Material, b: &Material) -> bool {
    canonical(a) == canonical(b)
}

fn canonical(m: &Material) -> Material {
    let mut m = m.clone();
    if let Some(maps) = m.textures.take() {
        let mut maps: Vec<(Slot, Texture)> = maps.to_vec();
        maps.sort_by_key(|(s, _)| format!("{s:?}"));
        for (s, _) in &maps {
            s.apply(&mut m, Rgb::ZERO);
        }
        m.textures = Some(Arc::from(maps));
    }
    lamplight_core::materials::pbr::derive_lecture_terms(&mut m);
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_transforms_are_written_exactly_or_refused() {
        let t = UvTransform::new([2.0, -0.5], 0.3, [0.25, 0.125]);
        let written = uv_transform(&t).unwrap();
        let Value::Number(degrees) = written[1].1 else { panic!("{written:?}") };
        assert_eq!(UvTransform::new([2.0, -0.5], degrees.to_radians(), [0.25, 0.125]), t);
        assert!(uv_transform(&UvTransform::IDENTITY).unwrap().is_empty());
        // A shear is no scale, rotation and offset.
        let shear = UvTransform([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(
            uv_transform(&shear).unwrap_err(),
            "its UV transform [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0]] has no exact uv_scale/uv_rotate/uv_offset form"
        );
    }
}
