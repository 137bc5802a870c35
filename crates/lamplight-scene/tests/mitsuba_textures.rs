//! Mitsuba's texture coordinates and texture lookups, read as a user's file is:
//! the `uv` of its rectangle and disk (so a checkerboard has Mitsuba's phase),
//! bitmaps at texel borders, `rawconstant`, textured area emitters and PLY
//! attributes read by `mesh_attribute` (per vertex and per face), with the
//! exact errors of bad ones. Expected values are Mitsuba 3.9.1's (measured
//! with its Python API; the numbers are quoted where they are used).

use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::ray::Ray;
use lamplight_core::Scene;
use lamplight_scene::request::SceneRequest;

/// The built scene of `text`, written as `s.xml` beside the `files` (name, bytes).
fn build(text: &str, files: &[(&str, &[u8])]) -> Scene {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    SceneRequest::resolve(path.to_str().unwrap()).and_then(|r| r.build()).unwrap_or_else(|e| panic!("{e}"))
}

/// The error of `text` beside `files`, the folder left out.
fn error(text: &str, files: &[(&str, &[u8])]) -> String {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    match SceneRequest::resolve(path.to_str().unwrap()).and_then(|r| r.build()) {
        Ok(_) => panic!("read but should fail:\n{text}"),
        Err(e) => e.to_string().replace(&format!("{}/", dir.path().display()), ""),
    }
}

fn scene(shapes: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <sensor type="orthographic"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
{shapes}
</scene>
"#
    )
}

/// The first hit of the ray straight down `-z` from `(x, y, 5)`: whether it
/// hit the front face, and the material there (its colour and emission).
fn down(scene: &Scene, x: f64, y: f64) -> (bool, Rgb, Rgb, [f64; 2]) {
    let ray = Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z);
    let mut hit = scene.first_intersect(&ray, f64::INFINITY).unwrap_or_else(|| panic!("no hit at ({x}, {y})"));
    let uv = scene.objects[hit.object].shape.surface_coords(hit.point, hit.geometric_normal, hit.primitive).uv;
    let front = hit.front_face;
    let m = scene.shade(&mut hit, Vec3::Z, 0.0);
    (front, m.color.constant().expect("evaluated at the hit"), m.emission, uv)
}

const RED: Rgb = Rgb::new(0.8, 0.1, 0.1);
const BLUE: Rgb = Rgb::new(0.1, 0.1, 0.8);

fn checker(to_uv: &str) -> String {
    format!(
        r#"<bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <rgb name="color0" value="0.8, 0.1, 0.1"/><rgb name="color1" value="0.1, 0.1, 0.8"/>{to_uv}</texture></bsdf>"#
    )
}

fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
}

#[test]
fn a_rectangle_has_mitsubas_uv_and_front_so_a_checkerboard_has_its_phase() {
    let s = build(&scene(&format!(r#"<shape type="rectangle">{}</shape>"#, checker(""))), &[]);
    // Mitsuba: uv = ((x + 1) / 2, (y + 1) / 2) (at (0.3, 0.5): (0.65, 0.75)); lamplight's v is 1 - that.
    let (front, _, _, uv) = down(&s, 0.3, 0.5);
    assert!(front, "Mitsuba's rectangle faces +z");
    assert!(close(uv, [0.65, 0.25]), "{uv:?}");
    // color0 where both halves of (u, v) agree: the lower left and upper right quarters.
    for (x, y, colour) in [(-0.5, -0.5, RED), (0.5, -0.5, BLUE), (0.5, 0.5, RED), (-0.5, 0.5, BLUE)] {
        assert_eq!(down(&s, x, y).1, colour, "({x}, {y})");
    }
    // flip_normals turns it to face -z.
    let flipped = build(&scene(r#"<shape type="rectangle"><boolean name="flip_normals" value="true"/></shape>"#), &[]);
    assert!(!down(&flipped, 0.3, 0.5).0);
}

#[test]
fn a_disk_has_mitsubas_radial_uv_which_turns_with_it() {
    // Mitsuba: uv = (r, phi / 2 pi) in the local frame (at (0.3, 0.5): (0.583095, 0.163989)).
    let s = build(&scene(r#"<shape type="disk"/>"#), &[]);
    let (front, _, _, uv) = down(&s, 0.3, 0.5);
    assert!(front);
    assert!((uv[0] - 0.583095).abs() < 1e-6 && (uv[1] - (1.0 - 0.163989)).abs() < 1e-6, "{uv:?}");
    // Turned by 90 degrees about z and scaled by 2: world (0, 1) is local (0.5, 0) (phi = 0),
    // world (-1, 0) is local (0, 0.5) (phi = 90 degrees, Mitsuba's v = 0.25).
    let turned = build(
        &scene(r#"<shape type="disk"><transform name="to_world"><rotate z="1" angle="90"/><scale value="2"/></transform></shape>"#),
        &[],
    );
    assert!(close(down(&turned, 0.0, 1.0).3, [0.5, 1.0]), "{:?}", down(&turned, 0.0, 1.0).3);
    assert!(close(down(&turned, -1.0, 0.0).3, [0.5, 0.75]), "{:?}", down(&turned, -1.0, 0.0).3);
    // A checkerboard of 2 x 2 cells per unit: r < 0.5 and phi < 180 degrees is color0.
    let s = build(&scene(&format!(r#"<shape type="disk">{}</shape>"#, checker(""))), &[]);
    for (x, y, colour) in [(0.2, 0.1, RED), (0.7, 0.1, BLUE), (0.2, -0.1, BLUE), (-0.7, -0.1, RED)] {
        assert_eq!(down(&s, x, y).1, colour, "({x}, {y})");
    }
}

/// A 4 x 2 PNG (8-bit, linear values through `raw`): column `x` of row `y` is `(60 x + 10, 200 y + 20, 7)`.
fn png() -> Vec<u8> {
    let img = image::RgbImage::from_fn(4, 2, |x, y| image::Rgb([60 * x as u8 + 10, 200 * y as u8 + 20, 7]));
    let mut bytes = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).unwrap();
    bytes
}

fn texel(x: u32, y: u32) -> Rgb {
    Rgb::new(f64::from(60 * x + 10) / 255.0, f64::from(200 * y + 20) / 255.0, 7.0 / 255.0)
}

fn bitmap(filter: &str, wrap: &str) -> String {
    scene(&format!(
        r#"<shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
            <string name="filename" value="t.png"/><boolean name="raw" value="true"/>
            <string name="filter_type" value="{filter}"/><string name="wrap_mode" value="{wrap}"/>
            <transform name="to_uv"><scale x="2" y="1"/></transform></texture></bsdf></shape>"#
    ))
}

#[test]
fn bitmap_lookups_are_mitsubas_at_texel_borders_and_centres() {
    let png = png();
    // Mitsuba's uv on the rectangle is ((x + 1) / 2, (y + 1) / 2), scaled by 2 in u: s = x + 1,
    // so texel column i spans x in [i / 4 - 1, (i + 1) / 4 - 1) of the first copy; v = (y + 1) / 2
    // picks row 0 (the image's top) below y = 0. Mitsuba 3.9.1 on this image: nearest at
    // uv (0.5, 0.25) gives texel 2 (red 130), at (0.4999999, 0.25) texel 1 (70), at v = 0.5
    // row 1; bilinear at (0.125, 0.25) texel 0 exactly, at (0.25, 0.25) the mean 40 of 10 and 70.
    let nearest = build(&bitmap("nearest", "repeat"), &[("t.png", &png)]);
    let c = |s: &Scene, x: f64, y: f64| down(s, x, y).1;
    // Texels are kept as f32.
    let near = |a: Rgb, b: Rgb| (a - b).abs().max_element() < 1e-6;
    let same = |a: Rgb, b: Rgb| assert!(near(a, b), "{a} vs {b}");
    same(c(&nearest, -0.9, -0.5), texel(0, 0));
    same(c(&nearest, -0.5, -0.5), texel(2, 0)); // a texel border belongs to the texel after it
    same(c(&nearest, -0.5 - 1e-9, -0.5), texel(1, 0));
    same(c(&nearest, -0.6, 0.5), texel(1, 1));
    same(c(&nearest, 0.1, 0.5), texel(0, 1)); // repeat: the second copy
                                              // Bilinear: exact at texel centres (s = (i + 0.5) / 4), the mean of two at a border.
    let bilinear = build(&bitmap("bilinear", "clamp"), &[("t.png", &png)]);
    assert!(near(c(&bilinear, -0.875, -0.5), texel(0, 0)), "{}", c(&bilinear, -0.875, -0.5));
    assert!(near(c(&bilinear, -0.75, -0.5), (texel(0, 0) + texel(1, 0)) * 0.5));
    // Clamp: beyond the image the border texels; mirror: the image reflected.
    assert!(near(c(&bilinear, 0.5, -0.5), texel(3, 0)));
    let mirror = build(&bitmap("nearest", "mirror"), &[("t.png", &png)]);
    same(c(&mirror, 0.1, -0.5), texel(3, 0));
}

#[test]
fn rawconstant_is_its_value_as_it_is() {
    let s = build(
        &scene(
            r#"<shape type="rectangle"><bsdf type="diffuse"><texture type="rawconstant" name="reflectance">
            <vector name="value" value="0.2, 0.5, 0.7"/></texture></bsdf></shape>"#,
        ),
        &[],
    );
    assert_eq!(down(&s, 0.0, 0.0).1, Rgb::new(0.2, 0.5, 0.7));
    let grey = build(
        &scene(
            r#"<shape type="rectangle"><bsdf type="diffuse"><texture type="rawconstant" name="reflectance"><float name="value" value="0.4"/></texture></bsdf></shape>"#,
        ),
        &[],
    );
    assert_eq!(down(&grey, 0.0, 0.0).1, Rgb::splat(0.4));
}

#[test]
fn an_area_emitter_takes_a_texture_as_its_radiance() {
    let s = build(
        &scene(
            r#"<shape type="rectangle"><emitter type="area"><texture type="checkerboard" name="radiance">
            <rgb name="color0" value="1, 0.5, 0.25"/><rgb name="color1" value="0.2, 0.4, 0.6"/></texture></emitter></shape>"#,
        ),
        &[],
    );
    assert_eq!(down(&s, -0.5, -0.5).2, Rgb::new(1.0, 0.5, 0.25));
    assert_eq!(down(&s, 0.5, -0.5).2, Rgb::new(0.2, 0.4, 0.6));
    // It is a light, and light sampling sees the same colours: from above, a
    // sample where x and y have the same sign is color0, else color1.
    let lights = s.light_set();
    assert_eq!(lights.area.len(), 1);
    let from = Vec3::new(0.0, 0.0, 3.0);
    let mut seen = [false, false];
    for i in 0..16 {
        let u = (((i % 4) as f64 + 0.5) / 4.0, ((i / 4) as f64 + 0.5) / 4.0);
        let sample = lights.area[0].sample(from, u).expect("the front faces +z");
        let y = from + sample.wi * sample.distance;
        let same_sign = (y.x > 0.0) == (y.y > 0.0);
        seen[usize::from(same_sign)] = true;
        let expected = if same_sign { Rgb::new(1.0, 0.5, 0.25) } else { Rgb::new(0.2, 0.4, 0.6) };
        assert_eq!(sample.radiance, expected, "sample {u:?} at {y}");
    }
    assert_eq!(seen, [true, true]);
}

/// One quad over [-1, 1]^2 (two triangles by the fan) with per-vertex colours
/// `color_0..2` and a per-face `weight_0` and `color_0..2`, and a triangle
/// beside it, as Mitsuba's `write_ply` names them.
const PLY: &str = "ply
format ascii 1.0
element vertex 7
property float x
property float y
property float z
property float color_0
property float color_1
property float color_2
element face 2
property list uchar int vertex_indices
property float weight_0
property float color_0
property float color_1
property float color_2
end_header
-1 -1 0 1 0 0
1 -1 0 0 1 0
1 1 0 0 0 1
-1 1 0 1 1 1
2 -1 0 0.5 0.5 0.5
3 -1 0 0.5 0.5 0.5
2 1 0 0.5 0.5 0.5
4 0 1 2 3 0.25 0.1 0.2 0.3
3 4 5 6 0.75 0.4 0.5 0.6
";

fn attribute_scene(name: &str) -> String {
    scene(&format!(
        r#"<shape type="ply"><string name="filename" value="m.ply"/>
        <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="{name}"/></texture></bsdf></shape>"#
    ))
}

#[test]
fn mesh_attribute_reads_plys_vertex_and_face_attributes_as_mitsuba_names_them() {
    let files: &[(&str, &[u8])] = &[("m.ply", PLY.as_bytes())];
    let near = |a: Rgb, b: Rgb| (a - b).abs().max_element() < 1e-9;
    // Per vertex, interpolated: the quad's centre is on the diagonal from vertex 0 to 2.
    let vertex = build(&attribute_scene("vertex_color"), files);
    assert!(near(down(&vertex, 0.0, 0.0).1, Rgb::new(0.5, 0.0, 0.5)), "{}", down(&vertex, 0.0, 0.0).1);
    assert!(near(down(&vertex, 2.5, -0.5).1, Rgb::splat(0.5)));
    // Per face, constant over both triangles of the quad.
    let weight = build(&attribute_scene("face_weight"), files);
    for (x, y) in [(0.9, -0.9), (-0.9, 0.9), (0.0, 0.0)] {
        assert_eq!(down(&weight, x, y).1, Rgb::splat(0.25), "({x}, {y})");
    }
    assert_eq!(down(&weight, 2.5, -0.5).1, Rgb::splat(0.75));
    let colour = build(&attribute_scene("face_color"), files);
    assert_eq!(down(&colour, -0.9, 0.9).1, Rgb::new(0.1, 0.2, 0.3));
    assert_eq!(down(&colour, 2.2, 0.0).1, Rgb::new(0.4, 0.5, 0.6));
}

#[test]
fn bad_mesh_attributes_and_rawconstants_are_one_clear_error() {
    let files: &[(&str, &[u8])] = &[("m.ply", PLY.as_bytes()), ("q.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")];
    assert_eq!(
        error(&attribute_scene("colour"), files),
        "s.xml:4:107: texture \"mesh_attribute\": name: expected \"vertex_...\" or \"face_...\", got \"colour\""
    );
    let missing = error(&attribute_scene("face_foo"), files);
    assert!(
        missing
            == "s.xml:3:50: mesh \"mesh_1\": file \"m.ply\" has no attribute \"face_foo\" (it has: vertex_color, face_weight, face_color)",
        "{missing}"
    );
    let two = scene(
        r#"<shape type="ply"><string name="filename" value="m.ply"/>
        <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="face_weight"/></texture></bsdf>
        <emitter type="area"><texture type="mesh_attribute" name="radiance"><string name="name" value="vertex_color"/></texture></emitter></shape>"#,
    );
    assert_eq!(
        error(&two, files),
        "s.xml:5:104: shape \"ply\": its textures read the mesh attributes \"face_weight\" and \"vertex_color\"; lamplight reads one per shape"
    );
    let obj = scene(
        r#"<shape type="obj"><string name="filename" value="q.obj"/>
        <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="face_weight"/></texture></bsdf></shape>"#,
    );
    assert_eq!(
        error(&obj, files),
        "s.xml:4:107: shape \"obj\": mesh_attribute \"face_weight\": face attributes are read from PLY files only"
    );
    let raw = scene(
        r#"<shape type="rectangle"><bsdf type="diffuse"><texture type="rawconstant" name="reflectance"><string name="value" value="red"/></texture></bsdf></shape>"#,
    );
    assert_eq!(error(&raw, &[]), "s.xml:3:121: texture \"rawconstant\": value: expected a float or a 3D vector, got a string");
}
