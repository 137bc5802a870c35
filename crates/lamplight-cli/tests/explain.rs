//! `lamplight explain` end to end: the tree as text and JSON, the JSON's pixel
//! equal to the rendered EXR's, and bad input as one line with exit code 2.

use std::path::Path;
use std::process::{Command, Output, Stdio};

use lamplight_scene::image_io::read_exr;

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

fn stdout_of(dir: &Path, args: &[&str]) -> String {
    let out = lamplight(dir, args);
    assert!(out.status.success(), "lamplight {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_json_pixel_is_the_rendered_pixel_and_the_contributions_add_up() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    // No --spp: Whitted anti-aliases adaptively, 16 samples where neighbours differ.
    for (integrator, spp) in [("whitted", None), ("whitted", Some("1")), ("whitted", Some("4")), ("path", Some("4"))] {
        let mut size = vec!["--width", "48", "--height", "27", "--integrator", integrator];
        if let Some(spp) = spp {
            size.extend(["--spp", spp]);
        }
        let size = size.as_slice();
        let mut render = vec!["render", "luxo", "-q", "-o", "a.exr"];
        render.extend_from_slice(size);
        stdout_of(dir, &render);
        let image = read_exr(&dir.join("a.exr")).unwrap();
        for (x, y) in [(20, 14), (21, 18), (30, 10), (0, 0)] {
            let pixel = format!("{x},{y}");
            let mut args = vec!["explain", "luxo", "--pixel", &pixel, "--json"];
            args.extend_from_slice(size);
            let json: serde_json::Value = serde_json::from_str(&stdout_of(dir, &args)).unwrap();
            let value: Vec<f32> = json["value"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect();
            assert_eq!(value, image.get(x, y), "{integrator} {spp:?} ({x}, {y})");
            for sample in json["samples"].as_array().unwrap() {
                let mut sum = [0.0f64; 3];
                for c in sample["contributions"].as_array().unwrap() {
                    for (s, v) in sum.iter_mut().zip(c.as_array().unwrap()) {
                        *s += v.as_f64().unwrap();
                    }
                }
                let radiance: Vec<f64> = sample["radiance"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
                assert_eq!(sum.to_vec(), radiance, "JSON numbers round-trip, so the sum is exact");
            }
        }
    }
}

#[test]
fn text_shows_the_tree() {
    let dir = tempfile::tempdir().unwrap();
    let text = stdout_of(dir.path(), &["explain", "luxo", "--width", "64", "--pixel", "28,24"]);
    assert!(text.starts_with("pixel (28, 24) of 64x36, whitted integrator, 1 sample here, max depth 5, seed 0\n"), "{text}");
    for needle in ["- camera ray, depth 1, outside", "reflection: Fresnel F = ", "- refracted ray, depth 2, inside", "depth limit reached"]
    {
        assert!(text.contains(needle), "{needle}: {text}");
    }
    let one = stdout_of(dir.path(), &["explain", "cornell-box", "--width", "32", "--spp", "4", "--sample", "2", "--pixel", "16,16"]);
    assert!(one.contains("path integrator, 4 samples here") && one.contains("\nsample 2: ") && !one.contains("\nsample 1: "), "{one}");
    assert!(one.contains("light sample: "), "{one}");
}

#[test]
fn bad_input_is_one_line_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--pixel", "64,0"], "--pixel 64,0 is outside the 64x36 image (x from 0 to 63, y from 0 to 35)"),
        (
            &["--pixel", "3"],
            "invalid value '3' for '--pixel <X,Y>': must be the pixel's column and row as X,Y, two whole numbers such as 320,180",
        ),
        (
            &["--pixel", "a,b"],
            "invalid value 'a,b' for '--pixel <X,Y>': must be the pixel's column and row as X,Y, two whole numbers such as 320,180",
        ),
        (&["--pixel", "1,1", "--sample", "1"], "--sample 1 does not exist: the render takes 1 sample at pixel (1, 1), numbered 0 to 0"),
        (&["--pixel", "1,1", "--sample", "-1"], "invalid value '-1' for '--sample <K>': must be a positive number"),
        (&["--pixel", "1,1", "--max-depth", "0"], "--max-depth must be between 1 and 64 (work grows as 2^depth), got 0"),
    ];
    for (extra, message) in cases {
        let mut args = vec!["explain", "spheres", "--width", "64"];
        args.extend_from_slice(extra);
        let out = lamplight(dir.path(), &args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8_lossy(&out.stderr), format!("lamplight: error: {message}\n"), "{args:?}");
        assert!(out.stdout.is_empty());
    }
    let out = lamplight(dir.path(), &["explain", "nowhere", "--pixel", "1,1"]);
    assert_eq!(out.status.code(), Some(2));
}

/// See: issue 30: 131,072 samples recorded in full took 3.2 GB and aborted.
/// The first 64 are recorded and the rest summarised.
#[test]
fn a_pixel_of_131072_samples_records_64_and_summarises_the_rest() {
    let start = std::time::Instant::now();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .args(["explain", "spheres", "--pixel", "20,10", "--width", "40", "--spp", "131072", "--json"])
        .output()
        .unwrap();
    let elapsed = start.elapsed();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(elapsed < std::time::Duration::from_secs(5), "{elapsed:?}");
    assert!(out.stdout.len() < 1 << 20, "{} bytes of JSON", out.stdout.len());
    let tree: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(tree["spp"], 131072);
    assert_eq!(tree["samples"].as_array().unwrap().len(), 64);
    let u = &tree["unrecorded"];
    assert_eq!((u["first"].as_u64(), u["count"].as_u64(), u["dropped"].as_u64()), (Some(64), Some(131008), Some(0)));
    // The summary is of the render's samples: the recorded ones' film values
    // and the rest's sum make the pixel (within the f32 it is stored as).
    let mut sum = [0.0; 3];
    for s in tree["samples"].as_array().unwrap() {
        for (k, c) in sum.iter_mut().enumerate() {
            *c += s["film_value"][k].as_f64().unwrap();
        }
    }
    for (k, c) in sum.iter().enumerate() {
        let pixel = (c + u["film_sum"][k].as_f64().unwrap()) / 131072.0;
        assert!((pixel - tree["value"][k].as_f64().unwrap()).abs() < 1e-6, "channel {k}: {pixel}");
    }
}
