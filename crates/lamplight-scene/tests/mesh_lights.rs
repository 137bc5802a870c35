//! Emitting meshes from every source become area lights of the path tracer: an
//! OBJ with an emissive MTL, a glTF mesh with `emissiveFactor`, and a native
//! `mesh` node with an emitting material (the last two placed by a transform, so
//! through an instance).

use std::path::Path;

use lamplight_scene::instantiate::{imported, SceneFile};

#[test]
fn obj_with_an_emissive_mtl_is_an_area_light_and_needs_no_default_light() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lamp.mtl"), "newmtl glow\nKd 0 0 0\nKe 4 4 4\nnewmtl grey\nKd 0.5 0.5 0.5\n").unwrap();
    let obj = "mtllib lamp.mtl\no lamp\nv 0 2 0\nv 0 2 1\nv 1 2 1\nv 1 2 0\nusemtl glow\nf 1 4 3 2\n\
               o floor\nv -2 0 -2\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nusemtl grey\nf 5 6 7 8\n";
    let path = dir.path().join("lamp.obj");
    std::fs::write(&path, obj).unwrap();
    let scene = imported::load(&path).unwrap();
    assert!(scene.lights.is_empty(), "the emitting mesh lights the scene: no default point light");
    let lights = scene.light_set();
    assert_eq!(lights.area.len(), 1);
    assert!((lights.area[0].area() - 1.0).abs() < 1e-12, "the unit quad");
    // The quad faces -y (counter-clockwise seen from below): a point below receives light.
    let s = lights.area[0].sample(lamplight_core::math::Vec3::new(0.5, 0.0, 0.5), (0.3, 0.6)).unwrap();
    assert!(s.wi.y > 0.0 && s.pdf > 0.0 && s.radiance.x == 4.0);
}

#[test]
fn a_native_mesh_node_with_an_emitting_material_is_an_area_light() {
    let text = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
                [materials.lamp]\nkd = 0\nemission = 2\n\
                [meshes.quad]\npositions = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]\nindices = [[0, 1, 2], [0, 2, 3]]\n\
                [[objects]]\ntype = \"group\"\nscale = [2, 3, 1]\nchildren = [{ type = \"mesh\", mesh = \"quad\", material = \"lamp\" }]\n";
    let file = SceneFile::parse(Path::new("t.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    let scene = file.build().unwrap_or_else(|e| panic!("{e}"));
    let lights = scene.light_set();
    assert_eq!(lights.area.len(), 1);
    assert!((lights.area[0].area() - 6.0).abs() < 1e-12, "scaled by 2 x 3");
}

#[test]
fn a_gltf_mesh_with_an_emissive_factor_is_an_area_light() {
    use base64::Engine;
    // One triangle (0,0,0), (1,0,0), (0,1,0) of area 1/2, placed by a node scaled 2x.
    let mut buffer = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        buffer.extend(v.to_le_bytes());
    }
    let uri = format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&buffer));
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0, "scale": [2, 2, 2]}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
  "materials": [{{"emissiveFactor": [1, 0.5, 0.25]}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}],
  "buffers": [{{"uri": "{uri}", "byteLength": 36}}]}}"#
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("glow.gltf");
    std::fs::write(&path, json).unwrap();
    let scene = imported::load(&path).unwrap();
    let lights = scene.light_set();
    assert_eq!(lights.area.len(), 1);
    assert!((lights.area[0].area() - 2.0).abs() < 1e-12, "area 1/2 scaled by 2 x 2");
    assert_eq!(lights.area[0].radiance, lamplight_core::math::Rgb::new(1.0, 0.5, 0.25));
    assert!(scene.lights.is_empty(), "no default point light");
}
