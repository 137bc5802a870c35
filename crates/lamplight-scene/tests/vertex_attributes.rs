//! Texture coordinates, colours and tangents read from OBJ, PLY and glTF files
//! the test writes, and the messages of broken ones.

use crate::common;

use base64::Engine;
use common::{error_of, write_and_load};
use lamplight_core::math::Rgb;

#[test]
fn obj_vt_are_kept_per_corner() {
    let dir = tempfile::tempdir().unwrap();
    // Two faces share vertex 1 and 3 but give them different texture coordinates: a seam.
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\nf 1/1 2/2 3/3\nf 1/5 3/3 4/4\n";
    let imported = write_and_load(dir.path(), "quad.obj", obj.as_bytes()).unwrap();
    let mesh = &imported.meshes[0];
    let uvs = mesh.attributes.uvs.as_ref().expect("every corner has a vt");
    assert_eq!(mesh.positions.len(), 5, "vertex 1 with two texture coordinates is two vertices");
    for (t, expected) in mesh.indices.iter().zip([[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], [[0.5, 0.5], [1.0, 1.0], [0.0, 1.0]]]) {
        assert_eq!(t.map(|i| uvs[i as usize]), expected);
    }
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    // A corner without vt: no texture coordinates for the mesh.
    let partial = write_and_load(dir.path(), "p.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n").unwrap();
    assert_eq!(partial.meshes[0].attributes.uvs, None);
    assert_eq!(
        error_of(dir.path(), "bad.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n"),
        "bad.obj:5:7: face corner `2/2`: texture coordinate index 2 out of range (1 texture coordinates defined so far)"
    );
}

#[test]
fn ply_reads_each_spelling_of_texture_coordinates_and_8_bit_colours() {
    let dir = tempfile::tempdir().unwrap();
    for (u, v) in [("u", "v"), ("s", "t"), ("texture_u", "texture_v")] {
        let ply = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
             property float {u}\nproperty float {v}\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n\
             0 0 0 0 0 255 0 0\n1 0 0 1 0 0 255 0\n0 1 0 0.25 1 0 0 188\n3 0 1 2\n"
        );
        let imported = write_and_load(dir.path(), "t.ply", ply.as_bytes()).unwrap();
        let a = &imported.meshes[0].attributes;
        assert_eq!(a.uvs.as_deref(), Some(&[[0.0, 0.0], [1.0, 0.0], [0.25, 1.0]][..]), "{u} {v}");
        let colors = a.colors.as_ref().unwrap();
        assert_eq!(colors[0], Rgb::new(1.0, 0.0, 0.0));
        // 188 / 255 is sRGB-encoded 0.5 (to 0.3 %).
        assert!((colors[2].z - 0.5).abs() < 3e-3, "{}", colors[2]);
        assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    }
}

/// One triangle with float positions, `u16` normalized texture coordinates,
/// float RGBA colours and tangents.
#[test]
fn gltf_texcoord_color_and_tangent() {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend(v.to_le_bytes());
    }
    for v in [0u16, 0, 65535, 0, 0, 65535] {
        b.extend(v.to_le_bytes());
    }
    for v in [1.0f32, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0] {
        b.extend(v.to_le_bytes());
    }
    for _ in 0..3 {
        for v in [1.0f32, 0.0, 0.0, -1.0] {
            b.extend(v.to_le_bytes());
        }
    }
    let data = base64::engine::general_purpose::STANDARD.encode(&b);
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1, "COLOR_0": 2, "TANGENT": 3}}}}]}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
    {{"bufferView": 1, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}},
    {{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 12}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 96, "byteLength": 48}}],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{data}"}}]}}"#,
        b.len()
    );
    let dir = tempfile::tempdir().unwrap();
    let imported = write_and_load(dir.path(), "t.gltf", gltf.as_bytes()).unwrap();
    let a = &imported.meshes[0].attributes;
    // glTF's v runs down the image; lamplight's up: v' = 1 - v.
    assert_eq!(a.uvs.as_deref(), Some(&[[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]][..]));
    assert_eq!(a.colors.as_ref().unwrap()[1], Rgb::new(0.0, 1.0, 0.0));
    assert_eq!(a.tangents.as_ref().unwrap()[2], [1.0, 0.0, 0.0, -1.0]);
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    // Integer texture coordinates that are not normalized are refused, at their key.
    let bad = gltf.replace(r#""componentType": 5123, "normalized": true"#, r#""componentType": 5123"#);
    assert_eq!(
        error_of(dir.path(), "bad.gltf", bad.as_bytes()),
        "bad.gltf: at meshes[0].primitives[0].attributes.TEXCOORD_0: expected floats or normalized integers, found U16 that are not normalized"
    );
}

#[test]
fn gltf_texcoord_1_is_read_and_chosen_by_a_texture_info() {
    let mut b = Vec::new();
    // Positions, TEXCOORD_0 all (0.25, 0.5), TEXCOORD_1 all (0.75, 0.5).
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend(v.to_le_bytes());
    }
    for uv in [[0.25f32, 0.5], [0.75, 0.5]] {
        for _ in 0..3 {
            b.extend(uv[0].to_le_bytes());
            b.extend(uv[1].to_le_bytes());
        }
    }
    let data = base64::engine::general_purpose::STANDARD.encode(&b);
    let dir = tempfile::tempdir().unwrap();
    // Left texel red, right texel green.
    image::RgbImage::from_fn(2, 1, |x, _| image::Rgb(if x == 0 { [255, 0, 0] } else { [0, 255, 0] }))
        .save(dir.path().join("rg.png"))
        .unwrap();
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2}}, "material": 0}}]}}],
  "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0, "texCoord": 1}}}}}}],
  "textures": [{{"source": 0}}], "images": [{{"uri": "rg.png"}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": 60, "byteLength": 24}}],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{data}"}}]}}"#,
        b.len()
    );
    let imported = write_and_load(dir.path(), "t.gltf", gltf.as_bytes()).unwrap();
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    let a = &imported.meshes[0].attributes;
    assert_eq!(a.uvs1.as_deref(), Some(&[[0.75, 0.5]; 3][..]), "v flipped as for TEXCOORD_0");
    let base = &imported.instances[0].material.as_ref().unwrap().color;
    assert!(matches!(base, lamplight_core::materials::Texture::SecondUv(_)), "{base:?}");
    // Read at the second set: the green texel; at the first: red.
    use lamplight_core::materials::ShadingPoint;
    let at = ShadingPoint {
        uv: [0.25, 0.5],
        second: Some([[0.75, 0.5], [0.0; 2], [0.0; 2]]),
        ..ShadingPoint::at(lamplight_core::math::Vec3::ZERO)
    };
    assert_eq!(base.evaluate(&at), Rgb::new(0.0, 1.0, 0.0));
    // texCoord 2 is read with TEXCOORD_0, with a warning.
    let two = gltf.replace(r#""texCoord": 1"#, r#""texCoord": 2"#);
    let imported = write_and_load(dir.path(), "two.gltf", two.as_bytes()).unwrap();
    assert_eq!(imported.warnings, ["glTF textures on TEXCOORD_2 and above are read with TEXCOORD_0"]);
}
