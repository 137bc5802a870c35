//! `lamplight convert` of mesh files (OBJ with MTL, PLY, glTF): the TOML it
//! writes renders to the same bytes as the file itself, with every material,
//! the camera and the lights written out; what cannot be converted is refused
//! with one exact message.

use crate::common;

use std::path::{Path, PathBuf};

use base64::Engine;
use lamplight_core::RenderControl;
use lamplight_scene::request::{Naming, Request, SceneRequest};

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&path, bytes).unwrap();
    path
}

/// The sRGB bytes of `path` rendered at 24 x 16 by `integrator` with `spp` samples.
fn render(path: &Path, integrator: &str, spp: u32) -> Vec<u8> {
    render_frame(path, None, integrator, spp)
}

/// [`render`] of frame `frame` (`None`: the scene's first).
pub(crate) fn render_frame(path: &Path, frame: Option<i64>, integrator: &str, spp: u32) -> Vec<u8> {
    let scene = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let request = Request {
        width: Some(24),
        height: Some(16),
        spp: Some(spp),
        integrator: Some(integrator.to_string()),
        threads: Some(2),
        frame,
        ..Request::default()
    };
    let job = request.resolve(&scene.defaults, Naming::Flags).unwrap();
    let built = scene.build_frame(job.frame).unwrap().scene;
    job.run(&built, &RenderControl::default()).unwrap().image.to_srgb8()
}

/// Converts `input` to `output` (writing the extracted files too) and returns the TOML.
fn convert(input: &Path, output: &Path) -> String {
    let converted = lamplight_scene::convert::convert(input, output, &[]).unwrap();
    for (path, bytes) in &converted.files {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
    std::fs::write(output, &converted.toml).unwrap();
    converted.toml
}

/// Renders the mesh file and its conversion with both integrators and asserts equal bytes.
fn assert_same_renders(input: &Path, output: &Path) {
    for (integrator, spp) in [("whitted", 1), ("path", 2)] {
        let (a, b) = (render(input, integrator, spp), render(output, integrator, spp));
        assert_eq!(a.len(), 24 * 16 * 3);
        assert!(a == b, "{}: {integrator} renders of the file and of {} differ", input.display(), output.display());
    }
}

fn png(width: u32, height: u32, f: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let image = image::RgbaImage::from_fn(width, height, |x, y| image::Rgba(f(x, y)));
    let mut bytes = Vec::new();
    image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).unwrap();
    bytes
}

fn checker_png() -> Vec<u8> {
    png(4, 4, |x, y| if (x + y) % 2 == 0 { [230, 40, 20, 255] } else { [20, 90, 230, 255] })
}

const OBJ: &str = "mtllib m.mtl
v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1.2 0
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1
usemtl floor
f 1/1 2/2 3/3 4/4
usemtl shiny
f 1 2 5\nf 2 3 5
usemtl glass
f 3 4 5
usemtl rust
f 4 1 5
";

const MTL: &str = "newmtl floor
Kd 0.8 0.7 0.6
map_Kd -clamp on tex/checker.png
map_Ka tex/checker.png
decal rough.png
newmtl shiny
Ka 0.05 0.05 0.05
Kd 0.2 0.3 0.9
Ks 0.6
Ns 80
illum 3
newmtl glass
Ni 1.4
illum 7
newmtl rust
Kd 1 0.5 0.2
Pr 0.4
Pm 0.7
map_Pr rough.png
";

#[test]
fn an_obj_with_an_mtl_and_textures_converts_to_the_same_renders() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tex/checker.png", &checker_png());
    write(dir.path(), "rough.png", &png(2, 2, |x, _| [if x == 0 { 40 } else { 220 }, 0, 0, 255]));
    write(dir.path(), "m.mtl", MTL.as_bytes());
    let obj = write(dir.path(), "model.obj", OBJ.as_bytes());
    let out = dir.path().join("model.toml");
    let toml = convert(&obj, &out);
    // The mesh stays in its file; each part names its material, written out in full.
    assert!(toml.contains("[meshes.model]\nfile = \"model.obj\"\n"), "{toml}");
    assert!(toml.contains("part = 3\nmaterial = \"rust\"\n") && toml.contains("[materials.shiny]\ntype = \"phong\"\n"), "{toml}");
    assert!(toml.contains("b = { type = \"image\", file = \"tex/checker.png\", color_space = \"srgb\", wrap = \"clamp\""), "{toml}");
    assert!(toml.contains("reflection = { type = \"constant\", weight = 0.6 }"), "{toml}");
    assert!(toml.contains("color = { type = \"mix\", a = [0.8, 0.7, 0.6], b = { type = \"image\""), "decal: {toml}");
    assert!(toml.contains("type = \"pbr\""), "{toml}");
    // No lights in the file: the viewer's three, its studio and its camera.
    assert_eq!(toml.matches("type = \"directional_light\"").count(), 3, "{toml}");
    let studio = "ambient = 3.0\nbackground = 0.2\nenvironment = { preset = \"studio\", rotate = 35.0 }\n";
    assert!(toml.contains(studio) && toml.contains("fov = 40.0\n"), "{toml}");
    assert_same_renders(&obj, &out);

    // Written to another folder, the references follow it; editing a material changes the render.
    let other = dir.path().join("out/scene.toml");
    std::fs::create_dir_all(other.parent().unwrap()).unwrap();
    let toml = convert(&obj, &other);
    assert!(toml.contains("file = \"../model.obj\"") && toml.contains("file = \"../tex/checker.png\""), "{toml}");
    assert_same_renders(&obj, &other);
    std::fs::write(&other, toml.replacen("kd = [0.2, 0.3, 0.9]", "kd = [0.9, 0.3, 0.2]", 1)).unwrap();
    assert_ne!(render(&obj, "whitted", 1), render(&other, "whitted", 1), "the TOML's material is the one rendered");
}

#[test]
fn a_ply_converts_to_the_same_renders() {
    let dir = tempfile::tempdir().unwrap();
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
               element face 2\nproperty list uchar int vertex_indices\nend_header\n\
               0 0 0\n1 0 0\n1 1 0.3\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    let input = write(dir.path(), "quad.ply", ply.as_bytes());
    let out = dir.path().join("quad.toml");
    let toml = convert(&input, &out);
    assert!(toml.contains("[materials.default]\ntype = \"phong\"\ncolor = 0.5\nka = 0.1\nkd = 0.9\n"), "{toml}");
    assert!(!toml.contains("part ="), "one part: no part key\n{toml}");
    assert_same_renders(&input, &out);
}

/// A quad with UVs, two materials (textured metallic-roughness with KHR
/// extensions, and transmission), a camera and three lights.
fn gltf_scene(texture_transform: &str) -> String {
    let mut buffer = Vec::new();
    let positions = [[-1.0f32, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
    for p in positions.iter().flatten() {
        buffer.extend(p.to_le_bytes());
    }
    for uv in [0.0f32, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0] {
        buffer.extend(uv.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        buffer.extend(i.to_le_bytes());
    }
    let data = |bytes: &[u8], mime: &str| format!("data:{mime};base64,{}", base64::engine::general_purpose::STANDARD.encode(bytes));
    let mr = png(2, 2, |x, y| [0, 60 + 100 * x as u8, 255 * y as u8, 255]);
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_specular",
                     "KHR_materials_emissive_strength", "KHR_texture_transform"],
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2, 3, 4, 5]}}],
  "nodes": [
    {{"mesh": 0}},
    {{"mesh": 1, "translation": [0.5, 0.2, -1], "rotation": [0, 0.3826834, 0, 0.9238795]}},
    {{"camera": 0, "translation": [0.3, 0.4, 4]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [0, 2, 2]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 1}}}}, "rotation": [-0.3826834, 0, 0, 0.9238795]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 2}}}}, "translation": [0, 0, 3]}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.7, "znear": 0.1}}}}],
  "meshes": [
    {{"name": "front", "primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}}]}},
    {{"name": "back", "primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 1}}]}}
  ],
  "materials": [
    {{"pbrMetallicRoughness": {{"baseColorFactor": [1, 0.8, 0.6, 1], "baseColorTexture": {{"index": 0{texture_transform}}},
        "metallicFactor": 0.9, "roughnessFactor": 0.6, "metallicRoughnessTexture": {{"index": 1}}}},
      "emissiveFactor": [0.2, 0.1, 0], "emissiveTexture": {{"index": 0}},
      "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": 2}},
                     "KHR_materials_specular": {{"specularFactor": 0.7}}, "KHR_materials_ior": {{"ior": 1.7}}}}}},
    {{"name": "Glass", "pbrMetallicRoughness": {{"baseColorFactor": [0.9, 1, 0.9, 1], "metallicFactor": 0, "roughnessFactor": 0.2}},
      "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 0.8}}}}}}
  ],
  "textures": [{{"source": 0, "sampler": 0}}, {{"source": 1}}],
  "samplers": [{{"magFilter": 9728, "minFilter": 9728, "wrapS": 33071}}],
  "images": [{{"uri": "checker.png"}}, {{"uri": "{mr}"}}],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "color": [1, 0.9, 0.8], "intensity": 30}},
    {{"type": "directional", "intensity": 2}},
    {{"type": "spot", "intensity": 40, "spot": {{"innerConeAngle": 0.2, "outerConeAngle": 0.6}}}}
  ]}}}},
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1,-1,0], "max": [1,1,0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 12}}
  ],
  "buffers": [{{"uri": "{}", "byteLength": 92}}]
}}"#,
        data(&buffer, "application/octet-stream"),
        mr = data(&mr, "image/png"),
    )
}

#[test]
fn a_gltf_with_textures_a_camera_and_lights_converts_to_the_same_renders() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "checker.png", &checker_png());
    let transform = r#", "extensions": {"KHR_texture_transform": {"scale": [2, 0.5], "offset": [0.25, 0.125], "rotation": 0.3}}"#;
    let input = write(dir.path(), "scene.gltf", gltf_scene(transform).as_bytes());
    let out = dir.path().join("scene.toml");
    let toml = convert(&input, &out);
    // The file's camera and lights, and no viewer lights.
    assert!(toml.contains("[camera]\ntype = \"perspective\"\neye = [0.30000001192092896, 0.4000000059604645, 4.0]\n"), "{toml}");
    for kind in ["point_light", "directional_light", "spot_light"] {
        assert_eq!(toml.matches(&format!("type = \"{kind}\"")).count(), 1, "{kind}\n{toml}");
    }
    assert!(toml.contains("profile = \"gltf\""), "{toml}");
    // The embedded metallic-roughness image is extracted beside the TOML.
    assert!(toml.contains("file = \"scene_textures/image1.png\", color_space = \"linear\""), "{toml}");
    assert!(dir.path().join("scene_textures/image1.png").is_file());
    assert!(toml.contains("uv_scale = [2.0, 0.5], uv_rotate = -17.188734536943613"), "{toml}");
    // Transmission is the pbr material's; materials keep the file's names.
    assert!(toml.contains("transmission = 0.800000011920929\n"), "{toml}");
    assert!(toml.contains("[materials.Glass]\n") && toml.contains("part = 1\nmaterial = \"Glass\"\n"), "{toml}");
    assert!(toml.contains("part = 0\nmaterial = \"material_0\"\n"), "{toml}");
    assert_same_renders(&input, &out);
}

#[test]
fn what_cannot_be_converted_is_refused_with_one_message() {
    let dir = tempfile::tempdir().unwrap();
    let stl = write(dir.path(), "model.stl", b"solid x\nendsolid x\n");
    let err = |input: &Path, output: &str, defines: &[(String, String)]| {
        let e = lamplight_scene::convert::convert(input, &dir.path().join(output), defines).unwrap_err().to_string();
        e.replace(&format!("{}/", dir.path().display()), "")
    };
    assert_eq!(
        err(&stl, "x.toml", &[]),
        "model.stl: convert reads Mitsuba scenes (.xml) and mesh files (obj, ply, gltf, glb), not .stl files"
    );
    let ply = write(dir.path(), "t.ply", b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    assert_eq!(err(&ply, "x.obj", &[]), "x.obj: convert writes a lamplight scene file, expected a name ending in .toml");
    let d = vec![("a".to_string(), "1".to_string())];
    assert_eq!(err(&ply, "x.toml", &d), "t.ply: -D sets parameters of Mitsuba scenes; a mesh file has none");
    // A mesh node's part that the file does not have.
    let toml = write(
        dir.path(),
        "p.toml",
        b"[camera]\neye = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 40\n\n[meshes.t]\nfile = \"t.ply\"\n\n[[objects]]\ntype = \"mesh\"\nmesh = \"t\"\npart = 1\n",
    );
    let e = SceneRequest::resolve(toml.to_str().unwrap()).unwrap().build().unwrap_err().to_string();
    assert_eq!(
        e.replace(&format!("{}/", dir.path().display()), ""),
        "p.toml:12:8: mesh: part: part 1 does not exist: mesh \"t\" has 1 part"
    );
}

#[test]
fn the_shared_gltf_models_convert_to_the_same_renders() {
    let Some(data) = common::shared_data("the_shared_gltf_models_convert_to_the_same_renders") else { return };
    let files = ["gltf/Box/Box.gltf", "gltf/BoxTextured.glb", "gltf/Duck.glb", "gltf/Suzanne/Suzanne.gltf", "gltf/DamagedHelmet.glb"];
    let dir = tempfile::tempdir().unwrap();
    for file in files {
        let input = data.join(file);
        if !input.is_file() {
            println!("SKIPPED {file}: not in {}", data.display());
            continue;
        }
        let out = dir.path().join(format!("{}.toml", input.file_stem().unwrap().to_string_lossy()));
        convert(&input, &out);
        let (a, b) = (render(&input, "whitted", 1), render(&out, "whitted", 1));
        assert!(a == b, "{file}: the renders of the file and of its conversion differ");
    }
}
