//! `lamplight render --denoise` and `lamplight denoise`: the errors a machine
//! without Open Image Denoise and a bad file give, word for word, and, where
//! the library is (always under CI: `scripts/test.sh` installs it), that the
//! layers and the denoised files are what the command line promises.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use lamplight_scene::denoise;
use lamplight_scene::exr_layers::read_exr_channels;
use lamplight_scene::image_io::read_exr;

/// `lamplight args...` in `dir`, with the variables `env` sets (`None`: removed).
fn lamplight(dir: &Path, args: &[&str], env: &[(&str, Option<&str>)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_lamplight"));
    command.args(args).current_dir(dir).stdin(Stdio::null());
    for (name, value) in env {
        match value {
            Some(v) => command.env(name, v),
            None => command.env_remove(name),
        };
    }
    command.output().expect("the binary runs")
}

/// Expects exit code 2 and exactly `message` as the one error line.
fn usage_error(out: &Output, message: &str) {
    assert_eq!(String::from_utf8_lossy(&out.stderr), format!("lamplight: error: {message}\n"));
    assert_eq!(out.status.code(), Some(2));
}

/// A machine with no library anywhere: no variable, no Python on `PATH`, no
/// virtual environment, no loader path.
fn without_oidn(bin: &str) -> [(&str, Option<&str>); 4] {
    [("LAMPLIGHT_OIDN", None), ("VIRTUAL_ENV", None), ("PATH", Some(bin)), ("LD_LIBRARY_PATH", None)]
}

#[test]
fn denoise_without_the_library_stops_before_rendering_and_says_how_to_get_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bin = d.join("bin");
    std::fs::create_dir(&bin).unwrap();
    let start = Instant::now();
    // A render of minutes: the error must come before it.
    let big = ["render", "cornell-box", "--width", "2000", "--height", "2000", "--spp", "4096", "--denoise", "-o", "out.exr"];
    let out = lamplight(d, &big, &without_oidn(bin.to_str().unwrap()));
    usage_error(
        &out,
        "denoising needs Intel Open Image Denoise 2.x, which was not found: install it with `pip install pyoidn` \
         (into the python3 on PATH or the active virtual environment), or set LAMPLIGHT_OIDN to libOpenImageDenoise.so.2 or its folder",
    );
    assert!(start.elapsed() < Duration::from_secs(10), "failed before rendering");
    assert!(!d.join("out.exr").exists());
    // A scene file's `[render] denoise = true` asks the same, and is told the same.
    let scene =
        "[render]\nwidth = 2000\nheight = 2000\nspp = 4096\ndenoise = true\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    let out = lamplight(d, &["render", "scene.toml", "-o", "out.exr"], &without_oidn(bin.to_str().unwrap()));
    assert!(String::from_utf8_lossy(&out.stderr)
        .starts_with("lamplight: error: denoising needs Intel Open Image Denoise 2.x, which was not found"));
    assert_eq!(out.status.code(), Some(2));
    // A variable naming something that is not the library says so, with the loader's reason.
    std::fs::write(d.join("notlib.so"), "not a library").unwrap();
    let out = lamplight(d, &big, &[("LAMPLIGHT_OIDN", Some("notlib.so"))]);
    let err = String::from_utf8_lossy(&out.stderr);
    let expected =
        format!("lamplight: error: LAMPLIGHT_OIDN=notlib.so: cannot load Open Image Denoise: {}: ", d.join("notlib.so").display());
    assert!(err.starts_with(&expected) && err.lines().count() == 1, "{err}");
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn bad_denoise_requests_and_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = lamplight(d, &["render", "cornell-box", "--width", "8", "--height", "8", "--exr-layers", "noisy", "-o", "x.exr"], &[]);
    usage_error(&out, "the noisy layer is the image before denoising: it needs --denoise");
    std::fs::write(d.join("bad.exr"), "not an image").unwrap();
    usage_error(&lamplight(d, &["denoise", "bad.exr", "-o", "out.exr"], &[]), "cannot read bad.exr: invalid: file identifier missing");
    usage_error(
        &lamplight(d, &["denoise", "missing.exr", "-o", "out.exr"], &[]),
        "cannot read missing.exr: No such file or directory (os error 2)",
    );
    // A good file, but no library: the same line as render's.
    let out = lamplight(d, &["render", "cornell-box", "--width", "8", "--height", "8", "--spp", "1", "-q", "-o", "in.exr"], &[]);
    assert!(out.status.success());
    let bin = d.join("bin");
    std::fs::create_dir(&bin).unwrap();
    let out = lamplight(d, &["denoise", "in.exr", "-o", "out.exr"], &without_oidn(bin.to_str().unwrap()));
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("lamplight: error: denoising needs Intel Open Image Denoise 2.x"));
    assert!(!d.join("out.exr").exists());
}

#[test]
fn denoised_renders_keep_their_layers_and_denoise_again_to_the_same_image() {
    if denoise::for_test("denoised_renders_keep_their_layers_and_denoise_again_to_the_same_image").is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let render = |extra: &[&str]| {
        let mut args = vec!["render", "cornell-box", "--width", "32", "--height", "32", "--spp", "8", "--threads", "2", "-q"];
        args.extend_from_slice(extra);
        let out = lamplight(d, &args, &[]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    };
    render(&["--denoise", "--exr-layers", "albedo,normal,noisy", "-o", "denoised.exr"]);
    render(&["--exr-layers", "albedo,normal,emitted", "-o", "noisy.exr"]);
    let (_, _, channels) = read_exr_channels(&d.join("denoised.exr")).unwrap();
    let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        ["B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "noisy.B", "noisy.G", "noisy.R", "normal.X", "normal.Y", "normal.Z"]
    );
    let get = |channels: &[(String, Vec<f32>)], name: &str| channels.iter().find(|(n, _)| n == name).unwrap().1.clone();
    let (_, _, plain) = read_exr_channels(&d.join("noisy.exr")).unwrap();
    for c in ["R", "G", "B"] {
        assert_eq!(get(&channels, &format!("noisy.{c}")), get(&plain, c), "the noisy layer is the render without --denoise");
    }
    // `lamplight denoise` on the noisy file with its layers gives the render's
    // denoised image (its `emitted` layer, the light seen directly, left out of the filter).
    let out = lamplight(d, &["denoise", "noisy.exr", "-o", "again.exr", "--threads", "2"], &[]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let told = String::from_utf8_lossy(&out.stderr);
    assert!(told.starts_with("32x32 denoised with albedo, normal and emitted in "), "{told}");
    let (again, denoised) = (read_exr(&d.join("again.exr")).unwrap(), read_exr(&d.join("denoised.exr")).unwrap());
    assert_eq!(again.pixels, denoised.pixels);
    assert_ne!(get(&channels, "R"), get(&plain, "R"), "denoising changed the image");
}
