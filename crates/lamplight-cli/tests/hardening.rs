//! Issue 12 ("Hardening") end to end: each bad input of the issue with the one
//! line it must print and the exit code, and the files a run leaves.
//! See: issue 12 in the project's tracker.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::Duration;

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

/// The names in `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    names.sort();
    names
}

/// Runs each case in `dir` and collects every mismatch of exit code or of the whole stderr.
fn check(dir: &Path, cases: &[(Vec<&str>, i32, String)]) {
    let mut failures = Vec::new();
    for (args, code, message) in cases {
        let out = lamplight(dir, args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let expected = format!("lamplight: error: {message}\n");
        if out.status.code() != Some(*code) || err != expected {
            failures.push(format!("lamplight {args:?}\n  expected ({code}): {expected}  got ({:?}):      {err}", out.status.code()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

const SMALL: &[&str] = &["render", "spheres", "--width", "8", "--height", "8", "-q"];

fn small<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    [SMALL, extra].concat()
}

#[test]
fn negative_counts_say_the_value_must_be_positive() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let raycast = |flag: &'static str, value: &'static str| {
        vec!["raycast", "--mesh", "m.obj", "--origins", "o.npy", "--directions", "d.npy", "-o", "t.npy", flag, value]
    };
    let cases = vec![
        (vec!["render", "--spp", "-1"], 2, "invalid value '-1' for '--spp <N>': must be a positive number".to_string()),
        (vec!["render", "--threads", "-1"], 2, "invalid value '-1' for '--threads <T>': must be a positive number".into()),
        (vec!["render", "--width", "-5"], 2, "invalid value '-5' for '--width <W>': must be a positive number".into()),
        (vec!["render", "--height", "-5"], 2, "invalid value '-5' for '--height <H>': must be a positive number".into()),
        (vec!["render", "--max-depth", "-2"], 2, "invalid value '-2' for '--max-depth <D>': must be a positive number".into()),
        (vec!["render", "--seed", "-7"], 2, "invalid value '-7' for '--seed <S>': must be a positive number".into()),
        (vec!["render", "--spp", "99999999999"], 2, "invalid value '99999999999' for '--spp <N>': must be at most 4294967295".into()),
        (vec!["render", "--width", "wide"], 2, "invalid value 'wide' for '--width <W>': must be a positive whole number".into()),
        (raycast("--threads", "-1"), 2, "invalid value '-1' for '--threads <N>': must be a positive number".into()),
        (raycast("--repeat", "-1"), 2, "invalid value '-1' for '--repeat <K>': must be a positive number".into()),
        (raycast("--repeat", "0"), 2, "--repeat must be at least 1".into()),
        (small(&["--clamp", "-1"]), 2, "--clamp must be a positive number (a radiance), got -1".into()),
        (small(&["--clamp", "inf"]), 2, "--clamp must be a positive number (a radiance), got inf".into()),
        (
            small(&["--antialias", "-0.3"]),
            2,
            "invalid value '-0.3' for '--antialias <T|on|off>': expected `on`, `off` or a threshold >= 0 (POV-Ray's 0.3), got '-0.3'".into(),
        ),
        (
            small(&["--antialias", "0.3", "--spp", "4"]),
            2,
            "give --spp (fixed supersampling, 4 samples everywhere) or --antialias (adaptive: 16 samples where neighbours differ), not both"
                .into(),
        ),
        (
            small(&["--noise-threshold", "0.01"]),
            2,
            "--noise-threshold is for the path tracer (--integrator path); whitted takes its samples in one pass".into(),
        ),
        (
            small(&["--integrator", "path", "--noise-threshold", "-1"]),
            2,
            "--noise-threshold must be a positive number (a noise level, e.g. 0.01), got -1".into(),
        ),
        (small(&["--integrator", "path", "--min-spp", "-1"]), 2, "invalid value '-1' for '--min-spp <N>': must be a positive number".into()),
    ];
    check(d, &cases);
    assert!(entries(d).is_empty());
}

#[test]
fn two_outputs_may_never_be_the_same_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir(d.join("sub")).unwrap();
    fs::write(d.join("same.exr"), b"old").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink("same.exr", d.join("link.exr")).unwrap();
    fs::hard_link(d.join("same.exr"), d.join("hard.exr")).unwrap();
    let path = ["--integrator", "path", "-o", "same.exr", "--variance-output"];
    let message = |other: &str| format!("-o same.exr and --variance-output {other} are the same file; give each output a file of its own");
    let mut cases = vec![
        (small(&[&path[..], &["same.exr"]].concat()), 2, message("same.exr")),
        (small(&[&path[..], &["sub/../same.exr"]].concat()), 2, message("sub/../same.exr")),
        (small(&[&path[..], &["hard.exr"]].concat()), 2, message("hard.exr")),
    ];
    #[cfg(unix)]
    cases.push((small(&[&path[..], &["link.exr"]].concat()), 2, message("link.exr")));
    let raycast = ["raycast", "--mesh", "m.obj", "--origins", "o.npy", "--directions", "d.npy", "-o", "t.npy", "--prims", "./t.npy"];
    cases.push((raycast.to_vec(), 2, "-o t.npy and --prims ./t.npy are the same file; give each output a file of its own".into()));
    check(d, &cases);
    assert_eq!(fs::read(d.join("same.exr")).unwrap(), b"old", "nothing was written");
    // Two different files are fine.
    let out = lamplight(d, &small(&["--integrator", "path", "-o", "a.exr", "--variance-output", "sub/a.exr"]));
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(d.join("a.exr").exists() && d.join("sub/a.exr").exists());
}

#[test]
fn a_bad_environment_map_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("bad.exr"), b"junk\n").unwrap();
    fs::create_dir(d.join("dir.exr")).unwrap();
    let env = |file: &'static str| small(&["--integrator", "path", "--environment", file]);
    let cases = vec![
        (env("missing.exr"), 2, "cannot read missing.exr: no such file".to_string()),
        (env("bad.exr"), 2, "cannot read bad.exr: invalid: file identifier missing".into()),
        (env("dir.exr"), 2, "cannot read dir.exr: is a directory, expected an image file".into()),
        (env("sky.txt"), 2, "cannot read sky.txt: unknown environment map format \"txt\" (supported: .exr, .hdr)".into()),
    ];
    check(d, &cases);
    assert_eq!(entries(d), ["bad.exr", "dir.exr"]);
}

/// Issue 26: a Mitsuba `sdfgrid` whose grid file is cut short, holds a NaN or
/// is missing is one line at the `filename` that names it, exit code 2.
#[test]
fn a_bad_sdf_grid_is_bad_input() {
    use lamplight_scene::formats::mitsuba::volume::{write, Grid};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let grid = write(&Grid { resolution: [2; 3], values: vec![-1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0] });
    let mut nan = grid.clone();
    nan[48..52].copy_from_slice(&f32::NAN.to_le_bytes());
    fs::write(d.join("short.vol"), &grid[..60]).unwrap();
    fs::write(d.join("nan.vol"), nan).unwrap();
    for file in ["short", "nan", "missing"] {
        let xml = format!(
            "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"/>\n  <shape type=\"sdfgrid\"><string name=\"filename\" value=\"{file}.vol\"/></shape>\n</scene>\n"
        );
        fs::write(d.join(format!("{file}.xml")), xml).unwrap();
    }
    let render = |file: &'static str| vec!["render", file, "-q"];
    let at = "3:56: shape \"sdfgrid\"";
    let cases = vec![
        (render("short.xml"), 2, format!("short.xml:{at}: \"short.vol\": 60 bytes, expected 80 for 2 x 2 x 2 samples")),
        (render("nan.xml"), 2, format!("nan.xml:{at}: \"nan.vol\": sample 0 is NaN, expected a finite number")),
        (render("missing.xml"), 2, "missing.xml:3:56: no such file \"missing.vol\"".into()),
    ];
    check(d, &cases);
    assert_eq!(entries(d), ["missing.xml", "nan.vol", "nan.xml", "short.vol", "short.xml"], "no image written");
}

/// 4 KiB of seeded pseudo-random bytes (the renderer's own generator).
fn random_bytes(seed: u64) -> Vec<u8> {
    let mut rng = lamplight_core::sampling::Rng::for_sample(seed, 0, 0);
    (0..4096).map(|_| (rng.next_u64() >> 56) as u8).collect()
}

#[test]
fn garbage_meshes_are_refused_the_same_way_wherever_they_come_from() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("garbage.obj"), random_bytes(12)).unwrap();
    let scene = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[meshes.m]\nfile = \"garbage.obj\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n";
    fs::write(d.join("s.toml"), scene).unwrap();
    let text = "garbage.obj: has no triangles, expected a mesh";
    let raycast = vec!["raycast", "--mesh", "garbage.obj", "--origins", "o.npy", "--directions", "d.npy", "-o", "t.npy"];
    let cases = vec![
        (vec!["render", "garbage.obj", "-q"], 2, text.to_string()),
        (vec!["render", "s.toml", "-q"], 2, format!("s.toml:6:8: mesh \"m\": {text}")),
        (raycast, 2, text.to_string()),
    ];
    check(d, &cases);
    assert_eq!(entries(d), ["garbage.obj", "s.toml"]);
}

/// Ctrl-C at any moment of a render, the final write included: exit code 130,
/// no temporary file, and the output either absent or whole. The signal is sent
/// after a range of delays across the run (the write itself is deterministic in
/// `lamplight_scene::atomic`'s own test, which interrupts in the middle of it).
#[cfg(unix)]
#[test]
fn an_interrupt_at_any_moment_leaves_no_temporary_file() {
    let mut interrupted = 0;
    for delay_ms in [150u64, 250, 350, 450, 550, 650, 750, 850, 950] {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let child = Command::new(env!("CARGO_BIN_EXE_lamplight"))
            .args(["render", "spheres", "--width", "1000", "--height", "1000", "--max-depth", "1", "-o", "big.exr", "-q"])
            .current_dir(d)
            .stdin(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        // Fails harmlessly when the render has already ended.
        let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).stderr(Stdio::null()).status();
        let out = child.wait_with_output().unwrap();
        let names = entries(d);
        assert!(names.is_empty() || names == ["big.exr"], "after {delay_ms} ms: {names:?}");
        if names == ["big.exr"] {
            assert_eq!(lamplight_scene::image_io::read_exr(&d.join("big.exr")).unwrap().width, 1000, "renamed whole");
        }
        if !out.status.success() {
            assert_eq!(out.status.code(), Some(130), "after {delay_ms} ms");
            assert_eq!(String::from_utf8_lossy(&out.stderr), "lamplight: error: interrupted\n");
            interrupted += 1;
        }
    }
    assert!(interrupted > 0, "no render lasted 150 ms: the signal was never handled");
}

#[test]
fn a_lamp_facing_away_is_reported_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A floor under a square lamp whose front faces up, away from it.
    let scene = |two_sided: bool| {
        format!(
            "[camera]\neye = [0, 4, 4]\nlook_at = [0, 0, 0]\nvfov = 40\n[materials.lamp]\nemission = 5\nkd = 0\nka = 0\ntwo_sided = {two_sided}\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-5, 0, 5]\nedge_u = [10, 0, 0]\nedge_v = [0, 0, -10]\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-0.5, 2, 5.5]\nedge_u = [0, 0, 1]\nedge_v = [1, 0, 0]\nmaterial = \"lamp\"\n"
        )
    };
    let warning =
        "lamplight: warning: no light reaches anything the camera sees: emitters send light from their front (outward) side only \
                   (set `two_sided = true` on the material to emit from both), and point, spot and directional lights light only the side \
                   of a surface that faces them\n";
    for (two_sided, expected) in [(false, warning), (true, "")] {
        fs::write(d.join("s.toml"), scene(two_sided)).unwrap();
        let out = lamplight(d, &["render", "s.toml", "--width", "16", "--height", "12", "-q", "-o", "s.png"]);
        assert_eq!(out.status.code(), Some(0));
        assert_eq!(String::from_utf8_lossy(&out.stderr), expected, "two_sided = {two_sided}");
    }
}

#[test]
fn a_scene_without_lights_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(
        d.join("dark.toml"),
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n",
    )
    .unwrap();
    let out = lamplight(d, &["render", "dark.toml", "--width", "8", "--height", "8", "-q", "-o", "dark.png"]);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "lamplight: warning: the scene has no lights: add a light, an emitting material, a background or an ambient term\n"
    );
}

/// The first Ctrl-C of a long path-traced render writes the passes already
/// complete, whole, says so and exits with code 130.
#[cfg(unix)]
#[test]
fn a_first_interrupt_writes_the_last_complete_pass() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 2^20 samples would take hours: only the interrupt ends it.
    let child = Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .args(["render", "cornell-box", "--width", "32", "--height", "32", "--spp", "1048576", "-o", "out.exr", "-q"])
        .current_dir(d)
        .stdin(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    let spp: u32 = err
        .strip_prefix("lamplight: interrupted: wrote the last complete pass (")
        .and_then(|rest| rest.strip_suffix(" of 1048576 samples per pixel) to out.exr\n"))
        .unwrap_or_else(|| panic!("stderr: {err}"))
        .parse()
        .unwrap();
    assert!(spp.is_power_of_two(), "complete doubling passes: {spp}");
    assert_eq!(entries(d), ["out.exr"], "the output and no temporary file");
    let image = lamplight_scene::image_io::read_exr(&d.join("out.exr")).unwrap();
    assert_eq!((image.width, image.height), (32, 32));
    assert!(image.pixels.iter().flatten().any(|&c| c > 0.0), "a rendered image");
}

#[test]
fn an_implicit_surface_steeper_than_its_bound_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = |lipschitz: f64| {
        format!(
            "ambient = 0.2\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
             [[objects]]\ntype = \"implicit\"\nexpression = \"10 * (sqrt(x*x + y*y + z*z) - 1)\"\nmin = [-1.5, -1.5, -1.5]\nmax = [1.5, 1.5, 1.5]\nlipschitz = {lipschitz}\n"
        )
    };
    fs::write(d.join("loose.toml"), scene(2.0)).unwrap();
    let out = lamplight(d, &["render", "loose.toml", "--width", "24", "--height", "24", "-q", "-o", "loose.png"]);
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(err.starts_with("lamplight: warning: implicit surface: f changed by ") && err.lines().count() == 1, "{err}");
    assert!(err.contains(" per unit of distance between samples, above its lipschitz = 2: rays may miss parts of the surface; set lipschitz to at least "), "{err}");
    fs::write(d.join("safe.toml"), scene(10.5)).unwrap();
    let out = lamplight(d, &["render", "safe.toml", "--width", "24", "--height", "24", "-q", "-o", "safe.png"]);
    assert_eq!((out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned()), (Some(0), String::new()));
}
