//! A mesh file (OBJ, PLY, glTF, GLB) as a TOML scene that renders to the same
//! bytes as rendering the file itself ([`crate::instantiate::imported`]):
//!
//! - the geometry stays in the file: one `[meshes.STEM]` entry names it (a
//!   path relative to the TOML), and one `mesh` node per part (`part = i`,
//!   the file's placed meshes in order) gives each its material by name;
//! - every material the importer mapped is written out in full as
//!   `[materials.NAME]` (the file's name for it; `pbr` or `phong`,
//!   [`super::material`]), with its
//!   textures naming their image files (embedded glTF images are extracted
//!   beside the TOML, [`super::images`]);
//! - the camera is the file's first camera, or the viewer's framing camera
//!   written as `perspective` with `fov` (across the shorter side);
//! - the lights are the file's (glTF punctual lights as `point_light`,
//!   `directional_light` and `spot_light` with the glTF profile), and, when the
//!   file has none and nothing emits, or its lights reach too little of the
//!   view ([`crate::instantiate::imported`]), the viewer's key, fill and rim
//!   lights with its `ambient`, `background` and studio `environment`;
//! - an animated glTF file gets `[animation]` (frames 0 to its first
//!   animation's last key at 24 fps, as rendering the file plays it): its
//!   `[meshes]` entry plays that animation at the scene's time, so each frame
//!   renders as the file's own frame; the camera and lights are written where
//!   they stand at frame 0 (the viewer's camera frames everything the
//!   animation reaches, as rendering the file does).

use std::path::Path;

use lamplight_core::materials::Material;
use lamplight_core::params::{Table, Value};

use super::images::{relative_to, Images};
use super::material::{item, material_table, num, read_back, rgb, same_material, table, vec3};
use crate::error::LoadError;
use crate::import::{self, ImportedLight, ImportedProjection};
use crate::instantiate::{imported, studio, viewer};

/// The scene table of the mesh file `input` for a TOML written to `output`,
/// the warnings, and the image files to extract (absolute path, bytes);
/// `clip` is the glTF animation chosen (`None`: the first).
pub(super) fn convert(input: &Path, output: &Path, clip: Option<usize>) -> Result<super::Converted, LoadError> {
    let mut imported = import::load(input)?;
    let fail = |m: String| LoadError::file(input, format!("cannot convert: {m}"));
    // An animated glTF file: written at frame 0 of its first animation, which
    // its `[meshes]` entry plays at the scene's time (`[animation]`, 24 fps).
    let index = clip.unwrap_or(0);
    let framing = imported::animation_sphere(input, &mut imported, index)?;
    let animation = imported.clip_frames(index);
    imported.pose_clip_frame(input, index, 0)?;
    let out_dir = super::absolute(output.parent().unwrap_or(Path::new("")));
    let stem = output.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let mesh_name = input.file_stem().map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    let mut images = Images::new(&imported.images, out_dir.clone(), &stem);
    let mut root: Vec<(&str, Value)> = Vec::new();
    if let Some(a) = &animation {
        let frames = Value::Array(vec![item(Value::Integer(a.start)), item(Value::Integer(a.end))]);
        let fps = if a.fps.fract() == 0.0 { Value::Integer(a.fps as i64) } else { num(a.fps) };
        root.push(("animation", Value::Table(table(vec![("frames", frames), ("fps", fps)]))));
    }

    // Lights first (they decide the globals), written after the meshes.
    let sphere = framing.or_else(|| imported::world_sphere(&imported)).ok_or_else(|| fail("the file has no geometry to render".into()))?;
    let (eye, target, camera) = match imported.cameras.first() {
        Some(c) => {
            let projection = match c.projection {
                ImportedProjection::Perspective { vfov_deg } => vec![("type", string("perspective")), ("vfov", num(vfov_deg))],
                ImportedProjection::Orthographic { xmag, ymag } => {
                    vec![("type", string("orthographic")), ("half_width", num(xmag)), ("half_height", num(ymag))]
                }
            };
            let mut entries = vec![projection[0].clone(), ("eye", vec3(c.eye)), ("look_at", vec3(c.target)), ("up", vec3(c.up))];
            entries.extend(projection.into_iter().skip(1));
            (c.eye, c.target, table(entries))
        }
        None => {
            let (eye, _) = viewer::camera(sphere).map_err(|e| fail(e.to_string()))?;
            let entries = vec![
                ("type", string("perspective")),
                ("eye", vec3(eye)),
                ("look_at", vec3(sphere.center)),
                ("up", vec3(lamplight_core::math::Vec3::Y)),
                ("fov", num(viewer::VFOV_DEG)),
            ];
            (eye, sphere.center, table(entries))
        }
    };
    let mut lights = Vec::new();
    // The same choice as rendering the file (`--keep-auto-lights auto`).
    let (viewer_lights, note) = imported::viewer_lights(input, &imported, imported::AutoLights::Auto)?;
    if !viewer_lights {
        root.push(("ambient", num(imported::AMBIENT)));
        root.push(("background", num(0.0)));
    } else {
        root.push(("ambient", num(viewer::AMBIENT)));
        root.push(("background", num(studio::FLOOR)));
        let rotate = studio::rotation_towards(eye, target);
        root.push(("environment", Value::Table(table(vec![("preset", string("studio")), ("rotate", num(rotate))]))));
        for (direction, irradiance) in viewer::light_directions(eye, target) {
            lights.push(table(vec![("type", string("directional_light")), ("direction", vec3(direction)), ("radiance", num(irradiance))]));
        }
    }
    for light in &imported.lights {
        lights.push(light_table(light));
    }
    root.push(("camera", Value::Table(camera)));

    // Materials, one table per distinct one, in order of first use.
    let mut materials: Vec<(String, String, Table)> = Vec::new(); // (name, written text, table)
    let mut objects = Vec::new();
    let parts = imported.instances.len();
    let default = Material::default();
    for (i, placed) in imported.instances.iter().enumerate() {
        let m = placed.material.as_ref().unwrap_or(&default);
        let what = |reason: String| match imported.meshes.get(placed.mesh).and_then(|d| d.name.as_deref()) {
            Some(name) => fail(format!("the material of part {i} (\"{name}\"): {reason}")),
            None => fail(format!("the material of part {i}: {reason}")),
        };
        let t = material_table(m, &mut images).map_err(what)?;
        let back = read_back(&t, &images).map_err(|e| what(format!("its TOML form does not read back: {e}")))?;
        if !same_material(&back, m) {
            return Err(what("its TOML form builds a different material".into()));
        }
        let text = crate::formats::native_writer::write(&t, "");
        let name = match materials.iter().find(|(_, written, _)| *written == text) {
            Some((name, _, _)) => name.clone(),
            None => {
                let name = material_name(placed, &materials);
                materials.push((name.clone(), text, t));
                name
            }
        };
        let mut node = vec![("type", string("mesh")), ("mesh", string(&mesh_name))];
        if parts > 1 {
            node.push(("part", Value::Integer(i as i64)));
        }
        node.push(("material", string(&name)));
        objects.push(item(Value::Table(table(node))));
    }
    objects.extend(lights.into_iter().map(|t| item(Value::Table(t))));
    let materials = Table {
        entries: materials
            .into_iter()
            .map(|(name, _, t)| lamplight_core::params::Entry { key: name, key_loc: Default::default(), item: item(Value::Table(t)) })
            .collect(),
        loc: Default::default(),
    };
    root.push(("materials", Value::Table(materials)));
    let file = relative_to(&out_dir, &super::absolute_file(input));
    let mut mesh = vec![("file", Value::String(file))];
    if let Some(i) = clip.filter(|&i| i > 0) {
        mesh.push(("animation", Value::Integer(i as i64)));
    }
    let mesh = table(mesh);
    root.push(("meshes", Value::Table(table(vec![(mesh_name.as_str(), Value::Table(mesh))]))));
    root.push(("objects", Value::Array(objects)));

    let header = format!(
        "Converted from {} by `lamplight convert`.\nThe meshes stay in that file; materials, camera and lights are written out to edit.",
        input.display()
    );
    let toml = crate::formats::native_writer::write(&table(root), &header);
    let mut warnings = imported.warnings_of(input);
    warnings.extend(note);
    if clip.is_none() {
        warnings.extend(imported.several_animations_note());
    }
    if imported.animations.as_ref().is_some_and(|a| a.moves_cameras_or_lights(index)) {
        let m = "its animation moves a camera or a light, which the scene file places where they stand at frame 0 (only the meshes play)";
        warnings.push(format!("{}: {m}", input.display()));
    }
    Ok(super::Converted { toml, warnings, files: images.extracted })
}

/// The file's name of the part's material (or `default`, or `material_N`),
/// made unique among `taken` (a glTF material with and without vertex colours
/// is two materials of one name).
fn material_name(placed: &import::ImportedMesh, taken: &[(String, String, Table)]) -> String {
    let base = match (&placed.material, &placed.material_name) {
        (None, _) => "default".to_string(),
        (Some(_), Some(name)) if !name.trim().is_empty() => name.clone(),
        (Some(_), _) => format!("material_{}", taken.len()),
    };
    let free = |n: &str| !taken.iter().any(|(t, _, _)| t == n);
    if free(&base) {
        return base;
    }
    (2..).map(|i| format!("{base}_{i}")).find(|n| free(n)).expect("some suffix is free")
}

fn string(s: &str) -> Value {
    Value::String(s.to_string())
}

fn light_table(light: &ImportedLight) -> Table {
    match *light {
        ImportedLight::Point { position, intensity } => {
            table(vec![("type", string("point_light")), ("position", vec3(position)), ("intensity", rgb(intensity))])
        }
        ImportedLight::Directional { direction, radiance } => {
            table(vec![("type", string("directional_light")), ("direction", vec3(direction)), ("radiance", rgb(radiance))])
        }
        ImportedLight::Spot { position, direction, intensity, inner_deg, outer_deg } => table(vec![
            ("type", string("spot_light")),
            ("position", vec3(position)),
            ("direction", vec3(direction)),
            ("intensity", rgb(intensity)),
            ("inner_angle", num(inner_deg)),
            ("outer_angle", num(outer_deg)),
            ("profile", string("gltf")),
        ]),
    }
}
