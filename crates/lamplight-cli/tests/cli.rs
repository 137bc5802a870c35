//! The `lamplight` binary end to end: each test runs it in a fresh temporary
//! directory with stdout and stderr piped, and checks exit codes, messages and
//! the files it leaves.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};

use lamplight_scene::image_io::{read_exr, read_png_srgb8};

/// Runs `lamplight args...` in `dir`.
fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs and expects success, returning stderr.
fn ok(dir: &Path, args: &[&str]) -> String {
    let out = lamplight(dir, args);
    assert!(out.status.success(), "lamplight {args:?} failed: {}", stderr(&out));
    stderr(&out)
}

/// Runs and expects exit code `code` with one error line containing `needle`.
fn fails(dir: &Path, args: &[&str], code: i32, needle: &str) -> String {
    let out = lamplight(dir, args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(code), "lamplight {args:?}: {err}");
    assert!(err.starts_with("lamplight: error: ") && err.contains(needle), "lamplight {args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "one line: {err}");
    assert!(out.stdout.is_empty());
    err
}

/// The names in `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    names.sort();
    names
}

const SMALL: &[&str] = &["spheres", "--width", "64", "--height", "36"];

fn args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut all = vec!["render"];
    all.extend_from_slice(SMALL);
    all.extend_from_slice(extra);
    all
}

#[test]
fn renders_png_ppm_and_exr() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    ok(dir, &args(&["-o", "a.png"]));
    ok(dir, &args(&["-o", "a.ppm"]));
    ok(dir, &args(&["-o", "a.exr"]));
    assert_eq!(entries(dir), ["a.exr", "a.png", "a.ppm"], "no temporary files are left");

    let png = fs::read(dir.join("a.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png[12..24], b"IHDR\x00\x00\x00\x40\x00\x00\x00\x24", "IHDR says 64x36");
    let (w, h, pixels) = read_png_srgb8(&dir.join("a.png")).unwrap();
    assert_eq!((w, h, pixels.len()), (64, 36, 64 * 36 * 3));
    assert!(pixels.iter().any(|&b| b != pixels[0]), "the image is not blank");

    let ppm = fs::read(dir.join("a.ppm")).unwrap();
    let header = b"P6\n64 36\n255\n";
    assert_eq!(&ppm[..header.len()], header);
    assert_eq!(&ppm[header.len()..], &pixels[..], "PPM and PNG hold the same bytes");

    let exr = read_exr(&dir.join("a.exr")).unwrap();
    assert_eq!((exr.width, exr.height), (64, 36));
    assert_eq!(exr.to_srgb8(), pixels, "the EXR's linear values encode to the PNG's bytes");
}

#[test]
fn thread_count_does_not_change_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    for spp in ["1", "4"] {
        ok(dir, &args(&["--spp", spp, "--threads", "1", "-o", "t1.png"]));
        ok(dir, &args(&["--spp", spp, "--threads", "2", "-o", "t2.png"]));
        let (one, two) = (fs::read(dir.join("t1.png")).unwrap(), fs::read(dir.join("t2.png")).unwrap());
        assert_eq!(one, two, "spp {spp}: 1 and 2 threads differ");
    }
    // ...but the seed and the sample count do change it (so the test above can fail).
    ok(dir, &args(&["--spp", "4", "--seed", "1", "-o", "s1.png"]));
    assert_ne!(fs::read(dir.join("s1.png")).unwrap(), fs::read(dir.join("t1.png")).unwrap());
}

#[test]
fn defaults_render_the_first_scene_to_its_name() {
    let dir = tempfile::tempdir().unwrap();
    let err = ok(dir.path(), &["render", "--width", "32"]);
    assert_eq!(entries(dir.path()), ["luxo.png"]);
    let (w, h, _) = read_png_srgb8(&dir.path().join("luxo.png")).unwrap();
    assert_eq!((w, h), (32, 18), "height follows the scene's 16:9 default");
    // The default render is anti-aliased adaptively (POV-Ray's +A).
    assert!(err.contains("rendered luxo 32x18, ") && err.contains(" spp adaptive (at most 16) in "), "{err}");
    assert!(err.trim_end().ends_with("-> luxo.png"), "{err}");
}

#[test]
fn a_window_renders_exactly_those_pixels_of_the_whole_image() {
    let dir = tempfile::tempdir().unwrap();
    ok(dir.path(), &args(&["-o", "full.png"]));
    ok(dir.path(), &args(&["--window", "8,4,16,8", "-o", "part.png"]));
    let (w, h, full) = read_png_srgb8(&dir.path().join("full.png")).unwrap();
    let (pw, ph, part) = read_png_srgb8(&dir.path().join("part.png")).unwrap();
    assert_eq!((w, h, pw, ph), (64, 36, 16, 8));
    for y in 0..8usize {
        let row = |x0: usize, width: usize, stride: usize, y: usize| (y * stride + x0) * 3..(y * stride + x0 + width) * 3;
        assert_eq!(part[row(0, 16, 16, y)], full[row(8, 16, 64, y + 4)], "row {y}");
    }
}

#[test]
fn the_path_tracer_without_spp_samples_to_a_noise_level_and_the_cornell_box_to_its_own_count() {
    let dir = tempfile::tempdir().unwrap();
    // A scene that gives no sample count: 16 to 1024 samples a pixel, to noise 0.05.
    let err = ok(dir.path(), &["render", "spheres", "--integrator", "path", "--width", "16", "-o", "p.exr"]);
    assert!(err.contains("rendered spheres 16x9, ") && err.contains(" spp adaptive (at most 1024) in "), "{err}");
    let mean: f64 = err.split(", ").nth(1).and_then(|s| s.split(' ').next()).and_then(|s| s.parse().ok()).unwrap();
    assert!((16.0..=1024.0).contains(&mean), "{err}");
    // The built-in Cornell box and its example file say 128.
    let err = ok(dir.path(), &["render", "cornell-box", "--width", "8", "-o", "c.exr"]);
    assert!(err.contains("rendered cornell-box 8x8, 128 spp in "), "{err}");
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/cornell-box.toml");
    let err = ok(dir.path(), &["render", example, "--width", "8", "-o", "e.exr"]);
    assert!(err.contains("8x8, 128 spp in "), "{err}");
}

#[test]
fn piped_stderr_gets_the_summary_and_no_progress_bar() {
    let dir = tempfile::tempdir().unwrap();
    let err = ok(dir.path(), &args(&["--threads", "2"]));
    assert!(!err.contains('\x1b') && !err.contains('\r'), "no terminal control codes: {err:?}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("rendered spheres 64x36, ") && err.contains(" spp adaptive (at most 16) in "), "{err}");
    assert!(err.contains(" camera, ") && err.contains(" shadow), ") && err.contains("2 threads -> spheres.png"), "{err}");

    let out = lamplight(dir.path(), &args(&["--quiet"]));
    assert!(out.status.success() && out.stderr.is_empty() && out.stdout.is_empty());
}

#[test]
fn bad_input_exits_with_2() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fails(dir, &["render", "foo"], 2, "unknown scene \"foo\" (built-in scenes: luxo, business-card, cornell-box, spheres)");
    // clap's own errors are one line too, with the nearest flag and the usage.
    fails(
        dir,
        &["render", "--bogus"],
        2,
        "unexpected argument '--bogus' found; usage: lamplight render [OPTIONS] [SCENE] (more with --help)",
    );
    fails(dir, &["render", "--widht", "3"], 2, "unexpected argument '--widht' found (a similar argument exists: '--width'); usage: ");
    fails(dir, &["frob"], 2, "unrecognized subcommand 'frob'; usage: lamplight <COMMAND> (more with --help)");
    fails(
        dir,
        &["render", "--window", "1,2,3"],
        2,
        "invalid value '1,2,3' for '--window <X,Y,W,H>': must be the window's corner and size as X,Y,W,H",
    );
    fails(
        dir,
        &["render", "spheres", "--width", "64", "--window", "60,0,16,8"],
        2,
        "--window (x0=60, y0=0, width=16, height=8) must be non-empty and inside the 64x36 image",
    );
    fails(
        dir,
        &["render", "spheres", "--filter", "gaussian"],
        2,
        "--filter is for the path tracer (--integrator path); whitted averages its samples over the pixel square (a box)",
    );
    fails(dir, &["render", "--width", "0"], 2, "--width must be at least 1");
    fails(dir, &["render", "--spp", "0"], 2, "--spp must be between 1 and 1048576, got 0");
    fails(dir, &["render", "--spp", "4294967295"], 2, "--spp must be between 1 and 1048576, got 4294967295");
    fails(dir, &["render", "--max-depth", "65"], 2, "--max-depth must be between 1 and 64");
    fails(dir, &["render", "--threads", "100000"], 2, "--threads must be at most 1024");
    fails(dir, &["render", "-o", "x.jpg"], 2, "unknown image format \"jpg\" (supported: .png, .ppm, .exr)");
    // clap's own errors: several lines, but exit code 2 too.
    assert_eq!(lamplight(dir, &["render", "--bogus"]).status.code(), Some(2));
    assert_eq!(lamplight(dir, &["render", "--width", "-3"]).status.code(), Some(2));
    assert_eq!(lamplight(dir, &["paint"]).status.code(), Some(2));
    assert!(entries(dir).is_empty());
}

#[test]
fn unwritable_output_fails_and_leaves_files_alone() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::write(dir.join("file"), b"a file").unwrap();
    fs::write(dir.join("keep.png"), b"old image").unwrap();

    // The parent is a regular file: refused before rendering, for root too.
    fails(dir, &args(&["-o", "file/out.png"]), 1, "cannot write file/out.png: not a directory");
    fails(dir, &args(&["-o", "missing/out.exr"]), 1, "cannot write missing/out.exr: no such file or directory");
    assert!(!dir.join("missing").exists());

    // The target is a non-empty directory: the render runs and the final rename fails.
    fs::create_dir(dir.join("busy.png")).unwrap();
    fs::write(dir.join("busy.png/inside"), b"x").unwrap();
    fails(dir, &args(&["-o", "busy.png"]), 1, "cannot write busy.png: ");
    assert_eq!(fs::read(dir.join("busy.png/inside")).unwrap(), b"x");

    // A rejected run leaves an existing output as it was.
    fails(dir, &args(&["--spp", "0", "-o", "keep.png"]), 2, "--spp");
    assert_eq!(fs::read(dir.join("keep.png")).unwrap(), b"old image");
    assert_eq!(entries(dir), ["busy.png", "file", "keep.png"], "no temporary files are left");

    // And a good run replaces it whole.
    ok(dir, &args(&["-o", "keep.png"]));
    assert_eq!(read_png_srgb8(&dir.join("keep.png")).unwrap().0, 64);
}

#[test]
fn list_names_every_builtin() {
    let dir = tempfile::tempdir().unwrap();
    let out = lamplight(dir.path(), &["list"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let names: Vec<&str> = text.lines().map(|l| l.split_whitespace().next().unwrap()).collect();
    assert_eq!(names, ["luxo", "business-card", "cornell-box", "spheres"]);
    assert!(text.contains("1280x720") && text.contains("32x32"), "{text}");
}

#[test]
fn renders_a_scene_file_and_flags_override_its_settings() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    fs::copy(examples.join("business-card.toml"), dir.join("card.toml")).unwrap();
    // The file asks for 32x32; the flag makes it 16 wide (square aspect kept).
    let err = ok(dir, &["render", "card.toml", "--width", "16", "-q"]);
    assert!(err.is_empty(), "{err}");
    let (w, h, _) = read_png_srgb8(&dir.join("card.png")).unwrap();
    assert_eq!((w, h), (16, 16));
    // A name with an extension is a file even when it matches nothing built in.
    fails(dir, &["render", "luxo.toml"], 2, "luxo.toml: no such file");
}

#[test]
fn a_malformed_scene_file_is_one_line_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::write(dir.join("bad.toml"), "[camera]\neye = [0, 0, 0\n").unwrap();
    let err = fails(dir, &["render", "bad.toml"], 2, "bad.toml:2:");
    assert!(err.contains("expected"), "{err}");
    fs::write(dir.join("cycle.toml"), CYCLE).unwrap();
    fails(dir, &["render", "cycle.toml"], 2, "cycle.toml:8:1: instance: cyclic instance: a -> b -> a");
    fs::create_dir(dir.join("dir.toml")).unwrap();
    fails(dir, &["render", "dir.toml"], 2, "dir.toml: is a directory, expected a scene file");
    fs::write(dir.join("empty.toml"), "").unwrap();
    fails(dir, &["render", "empty.toml"], 2, "empty.toml: is empty");
    assert_eq!(entries(dir), ["bad.toml", "cycle.toml", "dir.toml", "empty.toml"], "no image written");
}

const CYCLE: &str = "[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
vfov = 40
[definitions.a]
type = \"instance\"
of = \"b\"
[definitions.b]
type = \"instance\"
of = \"a\"
[[objects]]
type = \"instance\"
of = \"a\"
";

#[test]
fn path_traces_the_cornell_box_with_an_environment_map() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cb = ["render", "cornell-box", "--integrator", "path", "--width", "16", "--height", "16", "--spp", "4", "-o", "cb.exr"];
    ok(d, &[&cb[..], &["--variance-output", "var.exr"]].concat());
    let image = read_exr(&d.join("cb.exr")).unwrap();
    let variance = read_exr(&d.join("var.exr")).unwrap();
    assert!(variance.pixels.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)));
    assert!(variance.pixels.iter().any(|p| p[0] > 0.0), "4 samples of a noisy image have some variance");
    // The light in the ceiling is seen near the top centre; its radiance is (18.387, 13.9873, 6.75357).
    let top = image.get(8, 3);
    assert!(image.pixels.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)));
    assert!(top[0] > top[2], "{top:?}");
    // A sky map through --environment: the spheres scene lit by a 4x2 EXR.
    let sky = lamplight_core::film::Image { width: 4, height: 2, pixels: vec![[2.0, 2.0, 2.0]; 8] };
    lamplight_scene::image_io::write_image(&d.join("sky.exr"), &sky).unwrap();
    let args =
        ["render", "spheres", "--integrator", "path", "--environment", "sky.exr", "--width", "16", "--height", "9", "--tonemap", "filmic"];
    ok(d, &args);
    assert!(d.join("spheres.png").exists());
}

#[test]
fn exr_layers_hold_the_variance_and_sample_count_of_the_same_render() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cb = ["render", "cornell-box", "--integrator", "path", "--width", "16", "--height", "16", "--spp", "4"];
    // One render writes the layered file and the separate variance file from one accumulator.
    ok(d, &[&cb[..], &["-o", "layered.exr", "--exr-layers", "variance,samples", "--variance-output", "var.exr"]].concat());
    ok(d, &[&cb[..], &["-o", "plain.exr"]].concat());
    let (w, h, channels) = lamplight_scene::exr_layers::read_exr_channels(&d.join("layered.exr")).unwrap();
    assert_eq!((w, h), (16, 16));
    let get = |n: &str| channels.iter().find(|(name, _)| name == n).unwrap_or_else(|| panic!("no channel {n}")).1.clone();
    let variance = read_exr(&d.join("var.exr")).unwrap();
    for (c, name) in ["variance.R", "variance.G", "variance.B"].iter().enumerate() {
        assert_eq!(get(name), variance.pixels.iter().map(|p| p[c]).collect::<Vec<_>>(), "{name}");
    }
    assert!(get("variance.R").iter().any(|v| *v > 0.0));
    assert_eq!(get("samples.Y"), vec![4.0; 256]);
    // The image channels are the plain render's, bit for bit.
    assert_eq!(read_exr(&d.join("layered.exr")).unwrap().pixels, read_exr(&d.join("plain.exr")).unwrap().pixels);
    fails(d, &[&cb[..], &["-o", "x.png", "--exr-layers", "variance"]].concat(), 2, "--exr-layers needs an .exr output file");
    // Every integrator fills the same film, so Whitted renders have the layers too.
    let whitted = ["render", "spheres", "--width", "8", "--height", "8", "--spp", "4", "-o", "w.exr", "--exr-layers", "samples,variance"];
    ok(d, &whitted);
    let (_, _, channels) = lamplight_scene::exr_layers::read_exr_channels(&d.join("w.exr")).unwrap();
    let get = |n: &str| channels.iter().find(|(name, _)| name == n).unwrap_or_else(|| panic!("no channel {n}")).1.clone();
    assert_eq!(get("samples.Y"), vec![4.0; 64]);
    assert!(get("variance.R").iter().any(|v| *v > 0.0), "jittered samples vary at edges");
}

#[test]
fn radiance_hdr_files_light_the_scene_like_the_same_exr() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A uniform sky of 2 is exact in RGBE (mantissa 128, exponent 130), so both maps give the same image.
    let sky = lamplight_core::film::Image { width: 4, height: 2, pixels: vec![[2.0, 2.0, 2.0]; 8] };
    lamplight_scene::image_io::write_image(&d.join("sky.exr"), &sky).unwrap();
    // Rows of 4 pixels are too short for run-length encoding: flat RGBE quadruples.
    let mut hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n".to_vec();
    for _ in 0..8 {
        hdr.extend([128, 128, 128, 130]);
    }
    std::fs::write(d.join("sky.hdr"), hdr).unwrap();
    let base = ["render", "spheres", "--integrator", "path", "--width", "12", "--height", "8", "--spp", "4"];
    ok(d, &[&base[..], &["--environment", "sky.exr", "-o", "a.exr"]].concat());
    ok(d, &[&base[..], &["--environment", "sky.hdr", "-o", "b.exr"]].concat());
    assert_eq!(read_exr(&d.join("a.exr")).unwrap().pixels, read_exr(&d.join("b.exr")).unwrap().pixels);
    std::fs::write(d.join("bad.hdr"), b"#?RADIANCE\nnot really").unwrap();
    // A bad input file is the user's input: exit code 2, as for a bad scene file.
    let message = fails(d, &[&base[..], &["--environment", "bad.hdr", "-o", "c.exr"]].concat(), 2, "bad.hdr");
    assert!(message.contains("not a valid Radiance .hdr file"), "{message}");
}

/// An OBJ quad with line and point elements, both unsupported.
const WARNED_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nl 1 3\nl 2 4\np 1\np 2\n";

#[test]
fn importer_warnings_are_printed_once_each_to_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    fs::write(dir.join("quad.obj"), WARNED_OBJ).unwrap();
    let expected = "lamplight: warning: quad.obj: OBJ line elements ignored\n\
                    lamplight: warning: quad.obj: OBJ point elements ignored\n";
    let err = ok(dir, &["render", "quad.obj", "--width", "16", "--height", "9", "-q"]);
    assert_eq!(err, expected, "-q keeps the warnings");
    let err = ok(dir, &["render", "quad.obj", "--width", "16", "--height", "9"]);
    assert!(err.starts_with(expected) && err.lines().nth(2).is_some_and(|l| l.starts_with("rendered quad 16x9")), "{err}");
    // A scene file placing the mesh twice reads it once: each warning once.
    let scene = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[meshes.quad]\nfile = \"quad.obj\"\n\
                 [[objects]]\ntype = \"mesh\"\nmesh = \"quad\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"quad\"\ntranslate = [1, 0, 0]\n\
                 [[objects]]\ntype = \"point_light\"\nposition = [0, 0, 5]\nintensity = 1\n";
    fs::write(dir.join("twice.toml"), scene).unwrap();
    assert_eq!(ok(dir, &["render", "twice.toml", "--width", "16", "--height", "9", "-q"]), expected);
}

#[test]
fn convert_writes_a_mesh_file_as_toml_and_refuses_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
               element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    fs::write(dir.join("t.ply"), ply).unwrap();
    ok(dir, &["convert", "t.ply", "-o", "t.toml"]);
    let toml = fs::read_to_string(dir.join("t.toml")).unwrap();
    assert!(toml.contains("[meshes.t]\nfile = \"t.ply\"\n"), "{toml}");
    let small = ["--width", "16", "--height", "12"];
    ok(dir, &[&["render", "t.ply", "-o", "a.png"][..], &small].concat());
    ok(dir, &[&["render", "t.toml", "-o", "b.png"][..], &small].concat());
    assert_eq!(read_png_srgb8(&dir.join("a.png")).unwrap(), read_png_srgb8(&dir.join("b.png")).unwrap());
    fs::write(dir.join("m.stl"), "solid m\nendsolid m\n").unwrap();
    fails(
        dir,
        &["convert", "m.stl", "-o", "m.toml"],
        2,
        "m.stl: convert reads Mitsuba scenes (.xml) and mesh files (obj, ply, gltf, glb), not .stl files",
    );
    fails(dir, &["convert", "t.ply", "-o", "t.obj"], 2, "t.obj: convert writes a lamplight scene file, expected a name ending in .toml");
    assert_eq!(fs::read_to_string(dir.join("t.ply")).unwrap(), ply, "the mesh file is left alone");
}

#[test]
fn quiet_drops_the_summary_but_keeps_warnings() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("m.obj"), "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let err = ok(dir.path(), &["render", "m.obj", "--width", "8", "--height", "8", "-q", "-o", "m.png"]);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("lamplight: warning: ") && err.contains("material library `") && !err.contains("rendered"), "{err}");
}
