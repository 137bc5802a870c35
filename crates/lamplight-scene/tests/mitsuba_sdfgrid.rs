//! Issue 26: Mitsuba's `sdfgrid` read from a `.vol` file: the grid lands on
//! the unit cube under `to_world`, its surface is where the distances say, and
//! every bad grid is one error at the `filename` that names it, never a panic
//! (exit code 2 from the command line: `lamplight-cli`'s `tests/hardening.rs`).

use lamplight_core::math::Vec3;
use lamplight_core::ray::Ray;
use lamplight_scene::formats::mitsuba::volume::{self, Grid};
use lamplight_scene::request::SceneRequest;

/// A sphere of radius `r` at the cube's centre, sampled at the `n^3` corners.
fn sphere_grid(n: usize, r: f64) -> Grid {
    let h = 1.0 / (n - 1) as f64;
    let mut values = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(((Vec3::new(i as f64, j as f64, k as f64) * h - Vec3::splat(0.5)).length() - r) as f32);
            }
        }
    }
    Grid { resolution: [n; 3], values }
}

/// A scene of one sdfgrid reading `grid.vol`, with `extra` inside the shape;
/// the `filename` value is at line 4, column 40.
fn scene(extra: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    <shape type="sdfgrid">
        <string name="filename" value="grid.vol"/>{extra}
        <transform name="to_world"><scale value="2"/><translate x="-1" y="-1" z="-1"/></transform>
    </shape>
</scene>
"#
    )
}

/// Reads `text` as `s.xml` next to `grid.vol` holding `bytes` (none: no file)
/// and builds it; the error has the folder left out.
fn build(text: &str, bytes: Option<&[u8]>) -> Result<lamplight_core::Scene, String> {
    let dir = tempfile::tempdir().unwrap();
    if let Some(bytes) = bytes {
        std::fs::write(dir.path().join("grid.vol"), bytes).unwrap();
    }
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    SceneRequest::resolve_with(path.to_str().unwrap(), &[])
        .and_then(|r| r.build())
        .map_err(|e| e.to_string().replace(&format!("{}/", dir.path().display()), ""))
}

#[test]
fn a_grid_file_is_the_surface_it_samples() {
    let bytes = volume::write(&sphere_grid(16, 0.4));
    for normals in ["", "<string name=\"normals\" value=\"analytic\"/>"] {
        let scene = build(&scene(normals), Some(&bytes)).unwrap();
        // The cube [-1, 1]^3: a sphere of radius 0.8 at the origin, along each
        // axis, to the interpolation error of a 16^3 grid (its voxels are 0.13 wide).
        for dir in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X] {
            let hit = scene.first_intersect(&Ray::new(dir * -5.0, dir), f64::INFINITY).expect("hits the sphere");
            assert!((hit.point.length() - 0.8).abs() < 1e-2, "{normals}: {} from {dir}", hit.point);
            assert!((hit.normal + dir).length() < 1e-2, "{normals}: {} from {dir}", hit.normal);
        }
        assert!(scene.first_intersect(&Ray::new(Vec3::new(0.85, 0.0, -5.0), Vec3::Z), f64::INFINITY).is_none());
    }
}

#[test]
fn bad_grids_are_one_error_at_the_filename() {
    let good = volume::write(&sphere_grid(4, 0.4));
    let mut short = good.clone();
    short.truncate(good.len() - 4);
    let mut nan = good.clone();
    nan[48 + 4 * 7..48 + 4 * 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let empty = volume::write(&Grid { resolution: [4; 3], values: vec![1.0; 64] });
    let at = "s.xml:4:40: shape \"sdfgrid\"";
    let cases: [(&str, Option<&[u8]>, String); 6] = [
        ("", Some(&short), format!("{at}: \"grid.vol\": 300 bytes, expected 304 for 4 x 4 x 4 samples")),
        ("", Some(&nan), format!("{at}: \"grid.vol\": sample 7 is NaN, expected a finite number")),
        ("", Some(b"VOL\x03 not a grid"), format!("{at}: \"grid.vol\": not a Mitsuba .vol grid file (no \"VOL\" header)")),
        ("", None, "s.xml:4:40: no such file \"grid.vol\"".into()),
        ("", Some(&empty), "s.xml:4:40: sdfgrid: invalid values: hold no surface: no voxel has corners of both signs".into()),
        (
            "<string name=\"normals\" value=\"falcao\"/>",
            Some(&good),
            "s.xml:4:81: sdfgrid: normals: unknown value \"falcao\" (values: smooth, analytic)".into(),
        ),
    ];
    for (extra, bytes, expected) in cases {
        assert_eq!(build(&scene(extra), bytes).err().as_deref(), Some(expected.as_str()));
    }
    let no_file = scene("").replace(r#"<string name="filename" value="grid.vol"/>"#, "");
    assert_eq!(
        build(&no_file, Some(&good)).err().as_deref(),
        Some("s.xml:3:5: shape \"sdfgrid\": needs filename (a .vol grid; a `grid` tensor can only be given from Python)")
    );
}
