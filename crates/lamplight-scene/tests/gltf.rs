//! glTF importer: a scene the test writes (embedded buffer, then the same as
//! `.glb` and with an external `.bin`), the shared sample models, and a table
//! of malformed files with the exact error each gives.

use crate::common;

use base64::Engine;
use common::{error_of, shared_data, triangles, write_and_load};
use lamplight_core::materials::{Reflection, Refraction};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_scene::import::{self, ImportedLight, ImportedProjection};

/// One triangle: 3 float positions (36 bytes), then 3 `u16` indices and 2 bytes of padding.
fn triangle_buffer(indices: [u16; 3], y1: f32) -> Vec<u8> {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, y1, 0.0, 0.0, 1.0, 0.0] {
        b.extend(v.to_le_bytes());
    }
    for i in indices {
        b.extend(i.to_le_bytes());
    }
    b.extend([0, 0]);
    b
}

/// A scene of two instances of the triangle, a camera and three lights; `uri` is the buffer's URI (or none for GLB).
fn scene_json(uri: Option<&str>, position_count: usize, extra_nodes: &str) -> String {
    let uri = uri.map_or(String::new(), |u| format!(r#""uri": "{u}", "#));
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior"],
  "scene": 0,
  "scenes": [{{"nodes": [0, 3]}}],
  "nodes": [
    {{"mesh": 0, "translation": [0, 0, 5], "children": [1, 2]}},
    {{"mesh": 0, "matrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 1,0,0,1]}},
    {{"camera": 0, "translation": [0, 1, 10]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [0, 4, 0],
      "children": [4, 5]}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
    {{"extensions": {{"KHR_lights_punctual": {{"light": 2}}}}}}{extra_nodes}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.5, "znear": 0.1}}}}],
  "meshes": [{{"name": "tri", "primitives": [
    {{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}},
    {{"attributes": {{"POSITION": 0}}, "material": 1}},
    {{"attributes": {{"POSITION": 0}}, "mode": 1}}
  ]}}],
  "materials": [
    {{"pbrMetallicRoughness": {{"baseColorFactor": [1, 0.5, 0.25, 1], "metallicFactor": 1, "roughnessFactor": 0.5}}}},
    {{"extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}, "KHR_materials_ior": {{"ior": 1.33}}}}}}
  ],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "color": [1, 1, 1], "intensity": 20}},
    {{"type": "directional", "intensity": 2}},
    {{"type": "spot", "intensity": 3, "spot": {{"innerConeAngle": 0.25, "outerConeAngle": 0.5}}}}
  ]}}}},
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {position_count}, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
    {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 6}}
  ],
  "buffers": [{{{uri}"byteLength": 44}}]
}}"#
    )
}

fn data_uri(buffer: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(buffer))
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(bin);
    out
}

fn check_scene(imported: &import::Imported) {
    // Two triangle primitives per mesh instance (mode 1 skipped with a warning), two nodes with the mesh.
    assert_eq!(imported.meshes.len(), 2);
    assert_eq!(imported.meshes[0].indices, vec![[0, 1, 2]]);
    assert_eq!(imported.meshes[0].name.as_deref(), Some("tri.0"));
    assert_eq!(imported.instances.len(), 4);
    let child = &imported.instances[2];
    assert_eq!(child.transform.transform_point3(Vec3::new(1.0, 0.0, 0.0)), Vec3::new(3.0, 0.0, 5.0), "parent translation * child matrix");
    let metal = imported.instances[0].material.as_ref().unwrap();
    assert_eq!(metal.kd, Rgb::ZERO);
    assert_eq!(metal.shininess, 30.0);
    assert_eq!(metal.reflection, Reflection::Constant(Rgb::new(0.5, 0.25, 0.125)));
    // KHR_materials_transmission: the pbr material's thin-walled transmission,
    // KHR_materials_ior its Fresnel. glTF's default metallicFactor 1 makes it a
    // metal, which transmits nothing (the specification's mix by metallic).
    let glass = imported.instances[1].material.as_ref().unwrap();
    let pbr = glass.pbr.as_ref().unwrap();
    assert_eq!((pbr.transmission, pbr.ior, pbr.metallic), (1.0, 1.33f32 as f64, 1.0));
    assert_eq!(glass.refraction, Refraction::None);
    // glTF's default roughnessFactor 1 (GGX alpha 1 in the path tracer).
    assert_eq!(glass.roughness, 1.0);
    let camera = &imported.cameras[0];
    assert_eq!(
        (camera.eye, camera.target, camera.up),
        (Vec3::new(0.0, 1.0, 15.0), Vec3::new(0.0, 1.0, 14.0), Vec3::Y),
        "the camera is a child of the translated node"
    );
    assert!(matches!(camera.projection, ImportedProjection::Perspective { vfov_deg } if (vfov_deg - 0.5f64.to_degrees()).abs() < 1e-5));
    assert_eq!(imported.lights.len(), 3);
    // candela and lux over pi: see the importer's module doc.
    use std::f64::consts::PI;
    match &imported.lights[0] {
        ImportedLight::Point { position, intensity } => {
            assert_eq!((*position, *intensity), (Vec3::new(0.0, 4.0, 0.0), Rgb::splat(20.0 / PI)))
        }
        other => panic!("expected a point light, got {other:?}"),
    }
    match &imported.lights[1] {
        ImportedLight::Directional { direction, radiance } => assert_eq!((*direction, *radiance), (-Vec3::Z, Rgb::splat(2.0 / PI))),
        other => panic!("expected a directional light, got {other:?}"),
    }
    match &imported.lights[2] {
        ImportedLight::Spot { intensity, direction, inner_deg, outer_deg, .. } => {
            assert_eq!((*intensity, *direction), (Rgb::splat(3.0 / PI), -Vec3::Z));
            assert!((inner_deg - 0.25f64.to_degrees()).abs() < 1e-5 && (outer_deg - 0.5f64.to_degrees()).abs() < 1e-5);
        }
        other => panic!("expected a spot light, got {other:?}"),
    }
    assert_eq!(imported.warnings, vec!["glTF primitives of mode Lines ignored: only triangles (mode 4) are read".to_string(),]);
}

#[test]
fn embedded_external_and_binary_buffers_give_the_same_scene() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer([0, 1, 2], 0.0);
    check_scene(&write_and_load(dir.path(), "embedded.gltf", scene_json(Some(&data_uri(&buffer)), 3, "").as_bytes()).unwrap());
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    check_scene(&write_and_load(dir.path(), "external.gltf", scene_json(Some("tri.bin"), 3, "").as_bytes()).unwrap());
    check_scene(&write_and_load(dir.path(), "binary.glb", &glb(&scene_json(None, 3, ""), &buffer)).unwrap());
    // load_mesh: every triangle in node order, in world space.
    let merged = import::load_mesh(&dir.path().join("binary.glb")).unwrap();
    assert_eq!(merged.indices.len(), 4);
    assert_eq!(merged.positions[1], Vec3::new(1.0, 0.0, 5.0));
}

#[test]
fn malformed_files_give_one_exact_error() {
    let dir = tempfile::tempdir().unwrap();
    let good = triangle_buffer([0, 1, 2], 0.0);
    let uri = data_uri(&good);
    let cycle = ",\n    {\"children\": [7]}, {\"children\": [6]}";
    let cyclic = scene_json(Some(&uri), 3, cycle).replace("\"children\": [4, 5]", "\"children\": [4, 5, 6]");
    let cases: Vec<(&str, String, Vec<u8>, &str)> = vec![
        ("empty", "a.gltf".into(), Vec::new(), "a.gltf: the file is empty"),
        (
            "bad json",
            "a.gltf".into(),
            b"{\n  \"asset\": [\n".to_vec(),
            "a.gltf:3:1: invalid glTF JSON: EOF while parsing a list at line 3 column 0",
        ),
        (
            "accessor out of bounds",
            "a.gltf".into(),
            scene_json(Some(&uri), 100, "").into_bytes(),
            "a.gltf: at accessors[0]: needs bytes 0..1200 of bufferView 0, which has 36 bytes",
        ),
        (
            "missing bin",
            "a.gltf".into(),
            scene_json(Some("missing.bin"), 3, "").into_bytes(),
            "a.gltf: at buffers[0].uri: cannot read buffer `missing.bin`: file not found",
        ),
        (
            "index out of range",
            "a.gltf".into(),
            scene_json(Some(&data_uri(&triangle_buffer([0, 1, 5], 0.0))), 3, "").into_bytes(),
            "a.gltf: at accessors[1]: index 5 of triangle 0 out of range: POSITION has 3 vertices",
        ),
        (
            "nan",
            "a.gltf".into(),
            scene_json(Some(&data_uri(&triangle_buffer([0, 1, 2], f32::NAN))), 3, "").into_bytes(),
            "a.gltf: at accessors[0]: item 1 is [1, NaN, 0], expected finite numbers",
        ),
        (
            "cycle",
            "a.gltf".into(),
            cyclic.into_bytes(),
            "a.gltf: at nodes[7].children[0]: node 6 is reached twice (a cycle or a shared child): glTF nodes must form trees",
        ),
        (
            "image in a buffer view without a mimeType (gltf 1.4.1 unwrapped it: fuzz finding)",
            "a.gltf".into(),
            with_images(&scene_json(Some(&uri), 3, ""), r#"[{"bufferView": 0}]"#),
            "a.gltf: at images[0].mimeType: an image in a bufferView needs a mimeType",
        ),
        (
            "image with neither uri nor bufferView",
            "a.gltf".into(),
            with_images(&scene_json(Some(&uri), 3, ""), r#"[{"mimeType": "image/png"}]"#),
            "a.gltf: at images[0]: expected a uri or a bufferView",
        ),
        (
            "image in a missing buffer view",
            "a.gltf".into(),
            with_images(&scene_json(Some(&uri), 3, ""), r#"[{"bufferView": 9, "mimeType": "image/png"}]"#),
            "a.gltf: at images[0].bufferView: buffer view 9 does not exist (2 views)",
        ),
        (
            "glb without bin",
            "a.glb".into(),
            glb(&scene_json(None, 3, ""), &[]),
            "a.glb: at buffers[0].byteLength: claims 44 bytes but the data has 0",
        ),
        (
            "truncated glb",
            "a.glb".into(),
            glb(&scene_json(None, 3, ""), &good)[..100].to_vec(),
            "a.glb: invalid GLB container: could not completely read the object",
        ),
    ];
    let mut fails = Vec::new();
    for (what, name, bytes, expected) in cases {
        let got = error_of(dir.path(), &name, &bytes);
        if got != expected {
            fails.push(format!("{what}: got {got:?}, expected {expected:?}"));
        }
    }
    assert!(fails.is_empty(), "{fails:#?}");
}

#[test]
fn shared_gltf_models_load_with_the_readme_counts() {
    let Some(data) = shared_data("shared_gltf_models_load_with_the_readme_counts") else { return };
    for (file, count) in [
        ("gltf/Box/Box.gltf", 12),
        ("gltf/BoxTextured.glb", 12),
        ("gltf/Duck.glb", 4_212),
        ("gltf/DamagedHelmet.glb", 15_452),
        ("gltf/Suzanne/Suzanne.gltf", 3_936),
    ] {
        let imported = import::load(&data.join(file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(triangles(&imported), count, "{file}");
        println!("{file}: {count} triangles, warnings {:?}", imported.warnings);
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 128, rng_seed: proptest::test_runner::RngSeed::Fixed(0x1a3f), ..Default::default() })]

    /// Random bytes, as `.gltf` and as `.glb`, give a scene or a `LoadError`, never a panic.
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..512)) {
        let _ = import::load_bytes(&common::fake_path("x.gltf"), &bytes);
        let mut with_magic = b"glTF\x02\0\0\0".to_vec();
        with_magic.extend(&bytes);
        let _ = import::load_bytes(&common::fake_path("x.glb"), &with_magic);
    }

    /// Mutations of a valid `.gltf` and `.glb` give a scene or a `LoadError`, never a panic.
    #[test]
    fn mutated_files_never_panic(edits in common::edits(), cut in proptest::prelude::any::<usize>()) {
        let buffer = triangle_buffer([0, 1, 2], 0.0);
        let text = scene_json(Some(&data_uri(&buffer)), 3, "").into_bytes();
        let _ = import::load_bytes(&common::fake_path("x.gltf"), &common::mutate(&text, &edits, cut));
        let binary = glb(&scene_json(None, 3, ""), &buffer);
        let _ = import::load_bytes(&common::fake_path("x.glb"), &common::mutate(&binary, &edits, cut));
    }
}

/// `json` with an `images` array added.
fn with_images(json: &str, images: &str) -> Vec<u8> {
    json.replacen("\"materials\"", &format!("\"images\": {images},\n  \"materials\""), 1).into_bytes()
}

/// The test scene with its camera made orthographic with half-extents `xmag x ymag`.
fn orthographic_scene(xmag: f64, ymag: f64) -> Vec<u8> {
    let buffer = triangle_buffer([0, 1, 2], 0.0);
    let perspective = r#"{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}"#;
    let orthographic =
        format!(r#"{{"type": "orthographic", "orthographic": {{"xmag": {xmag}, "ymag": {ymag}, "znear": 0.1, "zfar": 100}}}}"#);
    let json = scene_json(Some(&data_uri(&buffer)), 3, "");
    assert!(json.contains(perspective));
    json.replace(perspective, &orthographic).into_bytes()
}

#[test]
fn orthographic_cameras_see_their_window_at_every_aspect() {
    let dir = tempfile::tempdir().unwrap();
    let imported = write_and_load(dir.path(), "ortho.gltf", &orthographic_scene(3.0, 1.5)).unwrap();
    assert_eq!(imported.cameras[0].projection, ImportedProjection::Orthographic { xmag: 3.0, ymag: 1.5 });
    assert!(!imported.warnings.iter().any(|w| w.contains("orthographic")), "{:?}", imported.warnings);
    let scene = lamplight_scene::instantiate::imported::build(&dir.path().join("ortho.gltf"), &imported).unwrap();
    let eye = Vec3::new(0.0, 1.0, 15.0);
    // xmag and ymag are half-extents; an image of another aspect than 3 : 1.5
    // widens the window along one side, never crops or stretches it.
    for ((w, h), (half_w, half_h)) in [((40, 20), (3.0, 1.5)), ((80, 20), (6.0, 1.5)), ((20, 20), (3.0, 3.0))] {
        let top_left = scene.settings.camera.ray(0.0, 0.0, w, h, (0.5, 0.5));
        let bottom_right = scene.settings.camera.ray(w as f64, h as f64, w, h, (0.5, 0.5));
        assert_eq!((top_left.dir, bottom_right.dir), (-Vec3::Z, -Vec3::Z), "parallel rays down the node's -z");
        assert!((top_left.origin - (eye + Vec3::new(-half_w, half_h, 0.0))).length() < 1e-12, "{w}x{h}: {}", top_left.origin);
        assert!((bottom_right.origin - (eye + Vec3::new(half_w, -half_h, 0.0))).length() < 1e-12, "{w}x{h}");
    }
    assert_eq!(
        error_of(dir.path(), "a.gltf", &orthographic_scene(0.0, 1.0)),
        "a.gltf: at cameras[0].orthographic.xmag: expected a positive half-extent"
    );
}

#[test]
fn a_metallic_roughness_texture_drives_metallic_and_roughness() {
    // glTF assets leave metallicFactor at 1 and paint the metal in the texture
    // (blue: metallic, green: roughness, linear); the factors multiply it.
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_fn(2, 1, |x, _| image::Rgb(if x == 0 { [0, 128, 0] } else { [0, 64, 255] }))
        .save(dir.path().join("mr.png"))
        .unwrap();
    let metal = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "metallicFactor": 1, "roughnessFactor": 0.5}}"#;
    let textured = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "roughnessFactor": 0.5,
        "metallicRoughnessTexture": {"index": 0}}}"#;
    let json = scene_json(Some(&data_uri(&triangle_buffer([0, 1, 2], 0.0))), 3, "");
    assert!(json.contains(metal));
    let json = json
        .replace(metal, textured)
        .replace(r#""accessors""#, r#""textures": [{"source": 0}], "images": [{"uri": "mr.png"}], "accessors""#);
    let imported = write_and_load(dir.path(), "mr.gltf", json.as_bytes()).unwrap();
    let m = imported.instances[0].material.as_ref().unwrap();
    assert!(!imported.warnings.iter().any(|w| w.contains("metallicRoughnessTexture")), "{:?}", imported.warnings);
    let at = |u: f64| {
        m.at(&lamplight_core::materials::ShadingPoint { uv: [u, 0.5], ..lamplight_core::materials::ShadingPoint::at(Vec3::ZERO) })
            .into_owned()
    };
    let (dielectric, metallic) = (at(0.25), at(0.75));
    assert_eq!(dielectric.pbr.as_ref().unwrap().metallic, 0.0);
    assert!((dielectric.roughness - 0.5 * 128.0 / 255.0).abs() < 1e-6, "{}", dielectric.roughness);
    assert_eq!((dielectric.kd, dielectric.ks, &dielectric.reflection), (Rgb::ONE, Rgb::splat(0.04), &Reflection::None));
    assert_eq!(metallic.pbr.as_ref().unwrap().metallic, 1.0);
    assert_eq!((metallic.kd, metallic.ks), (Rgb::ZERO, Rgb::new(1.0, 0.5, 0.25)));
    // A missing image is an error at its JSON path.
    std::fs::remove_file(dir.path().join("mr.png")).unwrap();
    assert_eq!(error_of(dir.path(), "mr.gltf", json.as_bytes()), "mr.gltf: at images[0].uri: cannot read image `mr.png`: no such file");
}

#[test]
fn specular_ior_and_blend_extensions_reach_the_pbr_material() {
    // KHR_materials_specular with KHR_materials_ior, and alphaMode BLEND with a
    // base colour alpha of 0.4: stochastic transparency of coverage 0.4.
    let dir = tempfile::tempdir().unwrap();
    let metal = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "metallicFactor": 1, "roughnessFactor": 0.5}}"#;
    let extended = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 0.4], "metallicFactor": 0, "roughnessFactor": 0.5},
        "alphaMode": "BLEND",
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 4]},
                       "KHR_materials_ior": {"ior": 2.0}}}"#;
    let json = scene_json(Some(&data_uri(&triangle_buffer([0, 1, 2], 0.0))), 3, "").replace(metal, extended);
    let imported = write_and_load(dir.path(), "spec.gltf", json.as_bytes()).unwrap();
    assert!(!imported.warnings.iter().any(|w| w.contains("BLEND")), "{:?}", imported.warnings);
    let m = imported.instances[0].material.as_ref().unwrap();
    let pbr = m.pbr.as_ref().unwrap();
    assert_eq!((pbr.ior, pbr.specular, pbr.specular_color), (2.0, 0.5, Rgb::new(1.0, 0.5, 4.0)));
    // The Whitted tracer's ks is the dielectric's f0: min(((2 - 1) / (2 + 1))^2 color, 1) x 0.5.
    let f0 = 1.0 / 9.0;
    assert!((m.ks - Rgb::new(f0, 0.5 * f0, 4.0 * f0) * 0.5).length() < 1e-12, "{}", m.ks);
    let alpha = m.alpha.as_ref().unwrap();
    assert!(alpha.blend);
    assert_eq!(alpha.texture, lamplight_core::materials::Texture::Constant(Rgb::splat(f64::from(0.4f32))));
}

#[test]
fn a_transmission_texture_drives_transmission() {
    // transmissionFactor x transmissionTexture.r (linear): 0.8 x 0 and 0.8 x 1
    // on the two texels; the warning of old is gone.
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_fn(2, 1, |x, _| image::Rgb(if x == 0 { [0, 255, 255] } else { [255, 0, 0] }))
        .save(dir.path().join("t.png"))
        .unwrap();
    let metal = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "metallicFactor": 1, "roughnessFactor": 0.5}}"#;
    let transmitting = r#"{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "metallicFactor": 0, "roughnessFactor": 0.2},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.8, "transmissionTexture": {"index": 0}}}}"#;
    let json = scene_json(Some(&data_uri(&triangle_buffer([0, 1, 2], 0.0))), 3, "")
        .replace(metal, transmitting)
        .replace(r#""accessors""#, r#""textures": [{"source": 0}], "images": [{"uri": "t.png"}], "accessors""#);
    let imported = write_and_load(dir.path(), "t.gltf", json.as_bytes()).unwrap();
    assert!(!imported.warnings.iter().any(|w| w.contains("transmission")), "{:?}", imported.warnings);
    let m = imported.instances[0].material.as_ref().unwrap();
    let at = |u: f64| {
        m.at(&lamplight_core::materials::ShadingPoint { uv: [u, 0.5], ..lamplight_core::materials::ShadingPoint::at(Vec3::ZERO) })
            .into_owned()
    };
    let (opaque, clear) = (at(0.25), at(0.75));
    assert_eq!(opaque.pbr.as_ref().unwrap().transmission, 0.0);
    assert_eq!((opaque.refraction.clone(), opaque.kd), (Refraction::None, Rgb::ONE));
    let t = 0.8f32 as f64;
    assert!((clear.pbr.as_ref().unwrap().transmission - t).abs() < 1e-12);
    assert_eq!(clear.refraction, Refraction::Constant { ior: 1.0, weight: t * Rgb::new(1.0, 0.5, 0.25) });
    // The path tracer's BSDF transmits only where the texture says.
    let below = Vec3::new(0.1, 0.0, -1.0).normalize();
    let wo = Vec3::new(0.0, 0.1, 1.0).normalize();
    let f = |m: &lamplight_core::materials::Material| lamplight_core::materials::bsdf_for(m, Vec3::ZERO, true).f(wo, below);
    assert_eq!(f(&opaque), Rgb::ZERO);
    assert!(f(&clear).min_element() > 0.0, "{}", f(&clear));
}
