//! `lamplight info FILE`: the exact text for a small scene file and mesh file
//! written by the test, and the usual one-line error with exit code 2.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

fn info(dir: &Path, file: &str) -> String {
    let out = lamplight(dir, &["info", file]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// Two OBJ objects, one with an MTL material, the other naming a material no library defines (a warning).
fn write_mesh(dir: &Path) {
    fs::write(dir.join("two.mtl"), "newmtl red\nKd 0.8 0.1 0.1\n").unwrap();
    let obj = "mtllib two.mtl\no quad\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nvt 0 0\nusemtl red\nf 1 2 3 4\n\
               o tri\nv 0 0 -3\nv 1 0 -3\nv 0 1 -3\nusemtl none\nf 5 6 7\n";
    fs::write(dir.join("two.obj"), obj).unwrap();
}

#[test]
fn a_mesh_file_lists_its_meshes_bounds_materials_and_warnings() {
    let dir = tempfile::tempdir().unwrap();
    write_mesh(dir.path());
    assert_eq!(
        info(dir.path(), "two.obj"),
        "two.obj: OBJ file\n\
         meshes:     2 (2 placed), 3 triangles, 7 vertices\n\
         bounds:     [0, 0, -3] to [2, 1, 0] (size [2, 1, 3])\n\
         materials:  1 material; 1 placed mesh without one (the default grey)\n\
         cameras:    none (a render frames the model from a 3/4 view)\n\
         lights:     none (a render adds a neutral studio and key, fill and rim lights)\n\
         warnings:   1\n  \
           OBJ material `none` is defined by no `mtllib` read so far: no material used\n"
    );
}

#[test]
fn a_scene_file_lists_its_objects_materials_camera_and_lights() {
    let dir = tempfile::tempdir().unwrap();
    write_mesh(dir.path());
    let scene = "background = [0.1, 0.2, 0.3]\nambient = 0.5\n\
                 [camera]\neye = [0, 1, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
                 [materials.gold]\ncolor = [1, 0.8, 0.2]\n[materials.lamp]\nemission = 4\n\
                 [meshes.two]\nfile = \"two.obj\"\n\
                 [[objects]]\ntype = \"sphere\"\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"gold\"\n\
                 [[objects]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n\
                 [[objects]]\ntype = \"mesh\"\nmesh = \"two\"\nmaterial = \"lamp\"\n\
                 [[objects]]\ntype = \"point_light\"\nposition = [0, 5, 0]\nintensity = 10\n\
                 [[objects]]\ntype = \"point_light\"\nposition = [0, 5, 5]\nintensity = 10\n";
    fs::write(dir.path().join("s.toml"), scene).unwrap();
    assert_eq!(
        info(dir.path(), "s.toml"),
        "s.toml: lamplight scene file\n\
         objects:    4, 3 triangles in 2 meshes, 1 unbounded (planes)\n\
         bounds:     [-1, 0, -3] to [2, 2, 1] (size [3, 2, 4])\n\
         materials:  2 (gold, lamp)\n\
         cameras:    1: perspective, eye = [0, 1, 5], look_at = [0, 0, 0], vfov = 40\n\
         lights:     2 point lights, 2 emitting objects (area lights), ambient [0.5, 0.5, 0.5]\n\
         background: [0.1, 0.2, 0.3]\n\
         warnings:   1\n  \
           two.obj: OBJ material `none` is defined by no `mtllib` read so far: no material used\n"
    );
}

#[test]
fn bad_input_is_one_line_with_its_place_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("bad.obj"), "v 0 0 0\nv 1 x 0\n").unwrap();
    fs::write(dir.path().join("bad.toml"), "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = \"wide\"\n").unwrap();
    for (file, expected) in [
        ("bad.obj", "lamplight: error: bad.obj:2:5: expected a number (y), found `x`\n"),
        ("missing.ply", "lamplight: error: missing.ply: file not found\n"),
        ("bad.toml", "lamplight: error: bad.toml:4:8: camera: vfov: expected a number, got a string \"wide\"\n"),
    ] {
        let out = lamplight(dir.path(), &["info", file]);
        assert_eq!(out.status.code(), Some(2), "{file}");
        assert_eq!(String::from_utf8_lossy(&out.stderr), expected);
        assert!(out.stdout.is_empty());
    }
}
