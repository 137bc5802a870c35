//! The scene-format reference tables, generated from the registry so that
//! `docs/scene-format.md` cannot drift from what the builder reads.

use std::fmt::Write;

use lamplight_core::params::Param;

use super::{CAMERAS, LIGHTS, MATERIALS, NODE_COMMON, SHAPES, SHAPE_COMMON, STRUCTURAL, TEXTURES};
use crate::instantiate::{RENDER_PARAMS, SCENE_PARAMS};

/// Markdown tables of every kind and its parameters, in the order of the
/// reference: top level, `[render]`, cameras, materials, textures, node keys,
/// structural nodes, shapes, lights, meshes.
pub fn reference() -> String {
    let mut out = String::new();
    section(&mut out, "Top level values", "", SCENE_PARAMS);
    section(
        &mut out,
        "`environment`",
        "A sky of a colour or an equirectangular map, at infinity.",
        crate::instantiate::environment::ENVIRONMENT_PARAMS,
    );
    section(&mut out, "`[render]`", "", RENDER_PARAMS);
    section(
        &mut out,
        "`[animation]`",
        "the frame range and rate of an animated scene, and its shutter (see docs/animation.md)",
        crate::description::animation::ANIMATION_PARAMS,
    );
    section(
        &mut out,
        "`animate.KEY` of a node or the camera",
        "keyframes of `KEY`, any key whose value is a number or `[x, y, z]`, or `rotate`; before the first key and after the last the end values hold (glTF)",
        crate::description::animation::TRACK_PARAMS,
    );
    for k in CAMERAS {
        section(&mut out, &format!("Camera `type = \"{}\"`", k.name), k.summary, k.params);
    }
    for k in MATERIALS {
        section(&mut out, &format!("Material `type = \"{}\"`", k.name), k.summary, k.params);
    }
    for k in TEXTURES {
        section(&mut out, &format!("Texture `type = \"{}\"`", k.name), k.summary, k.params);
    }
    section(&mut out, "Keys of every node", "", NODE_COMMON);
    for s in STRUCTURAL {
        section(&mut out, &format!("Node `{}`", s.name), s.summary, s.params);
    }
    for k in SHAPES {
        let params: Vec<Param> = k.params.iter().chain(SHAPE_COMMON).copied().collect();
        section(&mut out, &format!("Shape `{}`", k.name), k.summary, &params);
    }
    for k in LIGHTS {
        section(&mut out, &format!("Light `{}`", k.name), k.summary, k.params);
    }
    section(&mut out, "`[meshes.NAME]`", "give either `file` or `positions` + `indices`", crate::instantiate::MESH_PARAMS);
    out
}

fn section(out: &mut String, title: &str, summary: &str, params: &[Param]) {
    let _ = writeln!(out, "#### {title}\n");
    if !summary.is_empty() {
        let _ = writeln!(out, "{}\n", capitalized(summary));
    }
    let _ = writeln!(out, "| key | type | default | unit / range | meaning |");
    let _ = writeln!(out, "|-----|------|---------|--------------|---------|");
    for p in params {
        let default = if p.default.is_empty() { "required".to_string() } else { format!("`{}`", p.default) };
        let default = if p.default.contains(' ') && !p.default.starts_with('[') { p.default.to_string() } else { default };
        let _ = writeln!(out, "| `{}` | {} | {} | {} | {} |", p.name, p.ty, default, p.unit, p.doc);
    }
    out.push('\n');
}

fn capitalized(s: &str) -> String {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect::<String>() + ".",
        None => String::new(),
    }
}
