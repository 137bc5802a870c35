//! `lamplight info`: what a scene or mesh file holds, as plain text: its
//! triangles, bounds, materials, lights, cameras and the importers' warnings.
//!
//! A mesh file (OBJ, PLY, glTF, GLB) is described as the importer read it, so
//! "no camera" and "no lights" say what a render will add
//! ([`crate::instantiate::viewer`]). A scene file (or built-in scene) is built, and
//! described from the built scene and its description.

use std::fmt::Write;
use std::path::Path;

use lamplight_core::accel::Aabb;
use lamplight_core::math::Vec3;
use lamplight_core::params::Value;
use lamplight_core::Scene;

use crate::import::{self, Imported, ImportedLight, ImportedProjection};
use crate::instantiate::SceneFile;
use crate::request::{RequestError, SceneRequest, SceneSpec};

/// The description of the scene `request` names, one `key: value` line each
/// and a `warning:` line per warning. Errors are the loaders' (`file:line:col`).
pub fn describe(request: &SceneRequest) -> Result<String, RequestError> {
    let bad = |e: crate::LoadError| RequestError(e.to_string());
    match &request.spec {
        SceneSpec::Mesh(path) => {
            let mut imported = import::load(path).map_err(bad)?;
            // Described at its first frame, as a render without --frames draws it.
            let clip = request.mesh.animation.unwrap_or(0);
            imported.pose_clip_frame(path, clip, 0).map_err(bad)?;
            Ok(describe_imported(path, &imported, clip))
        }
        SceneSpec::File(file) => {
            let built = file.build_with_warnings().map_err(bad)?;
            Ok(describe_scene(&file.source.path.display().to_string(), "lamplight scene file", Some(file), &built.scene, &built.warnings))
        }
        SceneSpec::Builtin(b) => {
            let scene = request.build()?;
            Ok(describe_scene(b.name, "built-in scene", None, &scene, &[]))
        }
    }
}

/// A number with at most 4 decimals and no trailing zeros: `0.5`, `-1`, `2.3333`.
fn num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

fn rgb(c: lamplight_core::math::Rgb) -> String {
    format!("[{}, {}, {}]", num(c.x), num(c.y), num(c.z))
}

fn bounds(b: Aabb) -> String {
    if b.is_finite() {
        format!("{} to {} (size {})", vec3(b.min), vec3(b.max), vec3(b.max - b.min))
    } else {
        "none".to_string()
    }
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `key: value` lines with the values aligned, then the warnings.
fn lines(head: String, rows: &[(&str, String)], warnings: &[String]) -> String {
    let mut out = head;
    out.push('\n');
    for (key, value) in rows {
        writeln!(out, "{:<11} {value}", format!("{key}:")).unwrap();
    }
    if warnings.is_empty() {
        out.push_str("warnings:   none\n");
    } else {
        writeln!(out, "warnings:   {}", warnings.len()).unwrap();
        for w in warnings {
            writeln!(out, "  {w}").unwrap();
        }
    }
    out
}

fn describe_imported(path: &Path, imported: &Imported, clip: usize) -> String {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or_default().to_ascii_lowercase();
    let format = match ext.as_str() {
        "obj" => "OBJ",
        "ply" => "PLY",
        "gltf" => "glTF",
        _ => "GLB (binary glTF)",
    };
    let triangles: usize = imported.instances.iter().filter_map(|i| imported.meshes.get(i.mesh)).map(|m| m.indices.len()).sum();
    let vertices: usize = imported.meshes.iter().map(|m| m.positions.len()).sum();
    let mut world = Aabb::EMPTY;
    for placed in &imported.instances {
        for p in imported.meshes.get(placed.mesh).map(|m| m.positions.as_slice()).unwrap_or_default() {
            world = world.grow(placed.transform.transform_point3(*p));
        }
    }
    let mut materials = Vec::new();
    let mut unset = 0;
    let mut emitting = 0;
    for placed in &imported.instances {
        match &placed.material {
            Some(m) => {
                emitting += usize::from(m.emission.max_element() > 0.0);
                if !materials.contains(&m) {
                    materials.push(m);
                }
            }
            None => unset += 1,
        }
    }
    let mut material_text = plural(materials.len(), "material", "materials");
    if unset > 0 {
        write!(material_text, "; {} without one (the default grey)", plural(unset, "placed mesh", "placed meshes")).unwrap();
    }
    let cameras = if imported.cameras.is_empty() {
        "none (a render frames the model from a 3/4 view)".to_string()
    } else {
        let list: Vec<String> = imported
            .cameras
            .iter()
            .map(|c| {
                let projection = match c.projection {
                    ImportedProjection::Perspective { vfov_deg } => format!("perspective, vfov {}", num(vfov_deg)),
                    ImportedProjection::Orthographic { xmag, ymag } => format!("orthographic, xmag {}, ymag {}", num(xmag), num(ymag)),
                };
                format!("{projection}, eye {} looking along {}", vec3(c.eye), vec3((c.target - c.eye).normalize_or_zero()))
            })
            .collect();
        format!("{} (a render uses the first): {}", imported.cameras.len(), list.join("; "))
    };
    let mut lights: Vec<String> = imported
        .lights
        .iter()
        .map(|l| match l {
            ImportedLight::Point { position, .. } => format!("point at {}", vec3(*position)),
            ImportedLight::Directional { direction, .. } => format!("directional towards {}", vec3(direction.normalize_or_zero())),
            ImportedLight::Spot { position, direction, .. } => {
                format!("spot at {} towards {}", vec3(*position), vec3(direction.normalize_or_zero()))
            }
        })
        .collect();
    if emitting > 0 {
        lights.push(plural(emitting, "emitting mesh (an area light)", "emitting meshes (area lights)"));
    }
    let lights = if lights.is_empty() {
        "none (a render adds a neutral studio and key, fill and rim lights)".to_string()
    } else {
        lights.join("; ")
    };
    let mut rows = vec![
        (
            "meshes",
            format!(
                "{} ({} placed), {}, {}",
                imported.meshes.len(),
                imported.instances.len(),
                plural(triangles, "triangle", "triangles"),
                plural(vertices, "vertex", "vertices")
            ),
        ),
        ("bounds", bounds(world)),
        ("materials", material_text),
        ("cameras", cameras),
        ("lights", lights),
    ];
    rows.extend(gltf_animation_rows(imported, clip));
    lines(format!("{}: {format} file", path.display()), &rows, &imported.warnings)
}

/// A glTF file's `animation:` (the frames of the animation a render plays,
/// its keys' time span), `animations:` (every animation of the file, when it
/// has several, the one playing marked) and `animated:` (each channel of the
/// one played, on a line of its own).
fn gltf_animation_rows(imported: &Imported, clip: usize) -> Vec<(&'static str, String)> {
    use crate::import::gltf_animation::Clip;
    let Some(clips) = imported.animations.as_ref().map(|a| &a.clips) else { return Vec::new() };
    let Some(first) = clips.get(clip) else { return Vec::new() };
    let name = |c: &Clip| match &c.name {
        Some(n) => format!("animations[{}] {n:?}", c.index),
        None => format!("animations[{}]", c.index),
    };
    let a = first.frames();
    let (t0, t1) = first.time_span();
    let range = format!(
        "frames {} to {} ({} at {} fps; {} plays, keys from {} to {} s; described at frame {})",
        a.start,
        a.end,
        plural(a.frame_count() as usize, "frame", "frames"),
        num(a.fps),
        name(first),
        num(t0),
        num(t1),
        a.start
    );
    let mut listed = Vec::new();
    if clips.len() > 1 {
        let row = |c: &Clip| {
            let (_, end) = c.time_span();
            let title = c.name.as_ref().map_or("(unnamed)".to_string(), |n| format!("{n:?}"));
            let mark = if c.index == first.index { "  (plays)" } else { "" };
            format!("{} {title}, {} s{mark}", c.index, num(end))
        };
        listed.push(("animations", format!("{}\n  {}", clips.len(), clips.iter().map(row).collect::<Vec<_>>().join("\n  "))));
    }
    let mut nodes: Vec<usize> = first.channels.iter().map(|c| c.node).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let channels: Vec<String> = first
        .channels
        .iter()
        .map(|c| {
            let node = c.node_name.as_ref().map_or(format!("nodes[{}]", c.node), |n| format!("nodes[{}] {n:?}", c.node));
            let t = &c.track;
            // glTF's names for the properties.
            let property = match t.key.as_str() {
                "translate" => "translation",
                "rotate" => "rotation",
                _ => "scale",
            };
            let (first, last) = (t.times[0], t.times[t.times.len() - 1]);
            format!(
                "{node}: {property} ({}, {} at {} to {} s)",
                t.interpolation.name(),
                plural(t.times.len(), "key", "keys"),
                num(first),
                num(last)
            )
        })
        .collect();
    let animated = match channels.is_empty() {
        true => "nothing".to_string(),
        false => format!(
            "{} of {}\n  {}",
            plural(channels.len(), "channel", "channels"),
            plural(nodes.len(), "node", "nodes"),
            channels.join("\n  ")
        ),
    };
    let mut rows = vec![("animation", range)];
    rows.extend(listed);
    rows.push(("animated", animated));
    rows
}

/// A scene value as it would be written in a scene file (numbers trimmed).
fn value(v: &Value) -> String {
    match v {
        Value::Bool(b) => b.to_string(),
        Value::Integer(i) => i.to_string(),
        Value::Number(x) => num(*x),
        Value::String(s) => format!("{s:?}"),
        Value::Array(items) => format!("[{}]", items.iter().map(|i| value(&i.value)).collect::<Vec<_>>().join(", ")),
        Value::Table(t) => {
            format!("{{{}}}", t.entries.iter().map(|e| format!("{} = {}", e.key, value(&e.item.value))).collect::<Vec<_>>().join(", "))
        }
    }
}

/// `PointLight { .. }` (a light's `Debug`) to `point light`.
fn light_kind(debug: &str) -> String {
    let name = debug.split(|c: char| !c.is_alphanumeric()).next().unwrap_or_default();
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            out.push(' ');
        }
        out.extend(c.to_lowercase());
    }
    out
}

fn describe_scene(name: &str, what: &str, file: Option<&SceneFile>, scene: &Scene, warnings: &[String]) -> String {
    let mut triangles = 0;
    let mut meshes = 0;
    let mut world = Aabb::EMPTY;
    let mut unbounded = 0;
    for object in &scene.objects {
        if let Some(t) = object.shape.triangles() {
            meshes += 1;
            triangles += t.len();
        }
        let b = object.shape.bounds();
        if b.is_finite() {
            world = world.union(b);
        } else {
            unbounded += 1;
        }
    }
    let mut objects =
        format!("{}, {} in {}", scene.objects.len(), plural(triangles, "triangle", "triangles"), plural(meshes, "mesh", "meshes"));
    if unbounded > 0 {
        write!(objects, ", {} unbounded (planes)", unbounded).unwrap();
    }
    let materials = match file {
        Some(f) if !f.description.materials.is_empty() => {
            let names: Vec<&str> = f.description.materials.iter().map(|m| m.name.as_str()).collect();
            format!("{} ({})", names.len(), names.join(", "))
        }
        _ => plural(scene.materials.len(), "material", "materials"),
    };
    let cameras = match file.and_then(|f| f.description.camera.as_ref()) {
        Some(camera) => {
            let params: Vec<String> = camera
                .params
                .entries
                .iter()
                .map(|e| if e.key == "animate" { "animated".to_string() } else { format!("{} = {}", e.key, value(&e.item.value)) })
                .collect();
            format!("1: {}, {}", camera.kind, params.join(", "))
        }
        None => "1".to_string(),
    };
    let mut kinds: Vec<(String, usize)> = Vec::new();
    for light in &scene.lights {
        let kind = light_kind(&format!("{light:?}"));
        match kinds.iter_mut().find(|(k, _)| *k == kind) {
            Some((_, n)) => *n += 1,
            None => kinds.push((kind, 1)),
        }
    }
    let mut lights: Vec<String> = kinds.iter().map(|(k, n)| plural(*n, k, &format!("{k}s"))).collect();
    let emitting = scene.objects.iter().filter(|o| scene.materials[o.material].emission.max_element() > 0.0).count();
    if emitting > 0 {
        lights.push(plural(emitting, "emitting object (an area light)", "emitting objects (area lights)"));
    }
    if scene.settings.ambient.max_element() > 0.0 {
        lights.push(format!("ambient {}", rgb(scene.settings.ambient)));
    }
    let lights = if lights.is_empty() { "none".to_string() } else { lights.join(", ") };
    let mut rows = vec![
        ("objects", objects),
        ("bounds", bounds(world)),
        ("materials", materials),
        ("cameras", cameras),
        ("lights", lights),
        ("background", rgb(scene.settings.background)),
    ];
    if let Some(file) = file {
        rows.extend(animation_rows(&file.description));
        rows.extend(gltf_mesh_rows(file));
    }
    lines(format!("{name}: {what}"), &rows, warnings)
}

/// `gltf anim:`, one line per `[meshes]` glTF file with animations: the one
/// that plays at the scene's time (`[meshes.NAME] animation`), or the rest
/// pose, and the file's animations.
fn gltf_mesh_rows(file: &SceneFile) -> Vec<(&'static str, String)> {
    use crate::import::gltf_choice::{self, AnimationChoice};
    let mut lines = Vec::new();
    for mesh in &file.description.meshes {
        let Some(Value::String(name)) = mesh.value.get("file").map(|e| &e.item.value) else { continue };
        let path = file.source.dir().join(name);
        let Some(clips) = gltf_choice::file_clips(&path).ok().filter(|c| !c.is_empty() && gltf_choice::is_gltf(&path)) else { continue };
        let choice = match mesh.value.get("animation").map(|e| &e.item.value) {
            Some(Value::Bool(false)) => None,
            Some(Value::String(n)) => Some(AnimationChoice::Name(n.clone())),
            Some(Value::Integer(i)) => Some(AnimationChoice::Index(*i as usize)),
            _ => Some(AnimationChoice::Index(0)),
        };
        let plays = match choice.map(|c| gltf_choice::resolve(&path, &c, "animation")) {
            None => "the rest pose (animation = false)".to_string(),
            Some(Ok(i)) => {
                let end = gltf_choice::file_clip_end(&path, i).map_or(String::new(), |e| format!(", keys to {} s", num(e)));
                format!("animations[{i}]{} plays{end}", clips[i].name.as_ref().map_or(String::new(), |n| format!(" {n:?}")))
            }
            Some(Err(_)) => continue,
        };
        lines.push(format!("mesh {:?} ({name}): {plays}; the file has {}", mesh.name, gltf_choice::listing(&clips)));
    }
    match lines.is_empty() {
        true => Vec::new(),
        false => vec![("gltf anim", lines.join("\n  "))],
    }
}

/// `animation:` (the range, the rate and the length; the scene as built above
/// is its first frame) and `animated:` (how many keys move, then each animated
/// node and its keys on a line of its own).
fn animation_rows(desc: &crate::description::SceneDescription) -> Vec<(&'static str, String)> {
    use crate::description::animation::TimeUnit;
    let Some(a) = &desc.animation else { return Vec::new() };
    let count = a.frame_count();
    let range = format!(
        "frames {} to {} ({} at {} fps, {} s; described at frame {})",
        a.start,
        a.end,
        plural(count as usize, "frame", "frames"),
        num(a.fps),
        num(count as f64 / a.fps),
        a.start
    );
    // The description was checked when it was read.
    let animated = desc.animated().unwrap_or_default();
    let nodes: Vec<String> = animated
        .iter()
        .map(|node| {
            let name = node.name.as_ref().map(|n| format!(" {n:?}")).unwrap_or_default();
            let what = if node.path == "camera" { "camera".to_string() } else { format!("{} ({}{name})", node.path, node.label) };
            let tracks: Vec<String> = node
                .tracks
                .iter()
                .map(|t| {
                    let (first, last) = (t.times[0], t.times[t.times.len() - 1]);
                    let when = match t.unit {
                        TimeUnit::Frames => format!("frames {} to {}", num(first), num(last)),
                        TimeUnit::Seconds => format!("{} to {} s", num(first), num(last)),
                    };
                    format!("{} ({}, {} at {when})", t.key, t.interpolation.name(), plural(t.times.len(), "key", "keys"))
                })
                .collect();
            format!("{what}: {}", tracks.join(", "))
        })
        .collect();
    let keys: usize = animated.iter().map(|n| n.tracks.len()).sum();
    let animated = match nodes.is_empty() {
        true => "nothing".to_string(),
        // One line per node, indented as the warnings are.
        false => format!("{} of {}\n  {}", plural(keys, "key", "keys"), plural(nodes.len(), "node", "nodes"), nodes.join("\n  ")),
    };
    let mut rows = vec![("animation", range), ("animated", animated)];
    let (open, close) = a.shutter;
    if close > open {
        rows.push(("shutter", format!("[{}, {}] frames around each frame: moving shapes are motion-blurred", num(open), num(close))));
    }
    rows
}
