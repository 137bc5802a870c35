//! The `business-card` scene against Heckbert's own program.
//!
//! `tests/data/heckbert.c` is the restored card (see its header). When a C
//! compiler is found (`cc`, else `gcc`) it is compiled into Cargo's test temp
//! directory at 32x32 and, with the `32`s of its `main` replaced, at 64x64, and
//! its printout is compared with lamplight's render at 1 sample per pixel.
//! Without a compiler the render is compared with `tests/data/heckbert-32.txt`,
//! the card's printout committed beside it (that comparison always runs).
//!
//! Tolerances, per channel of every pixel, no exceptions:
//! - against what the card prints, `round(255 I)` of its double radiance `I`:
//!   `|255 I_lamplight - printed| <= 0.5 + 1e-3`;
//! - against the card with `%.6f` in place of `%.0f` (compiled runs only):
//!   `|255 I_lamplight - 255 I_card| <= 1e-4`. Lamplight differs from the card by
//!   rounding only (offset ray origins, a `1e-10` light threshold, the `f32` film,
//!   whose ulp at 255 is 1.5e-5); the largest difference seen is 8e-6.

use std::path::{Path, PathBuf};
use std::process::Command;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::builtin;

const SOURCE: &str = include_str!("data/heckbert.c");
const REFERENCE_32: &str = include_str!("data/heckbert-32.txt");
/// Against the printed integers.
const ROUNDED: f64 = 0.5 + 1e-3;
/// Against the card printing six decimals.
const PRECISE: f64 = 1e-4;

/// The card's printout: size and one `[r, g, b]` per pixel, top row first.
struct Printout {
    width: u32,
    height: u32,
    pixels: Vec<[f64; 3]>,
}

fn parse(text: &str) -> Printout {
    let mut lines = text.lines();
    let size: Vec<u32> = lines.next().expect("size line").split_whitespace().map(|v| v.parse().unwrap()).collect();
    let pixels: Vec<[f64; 3]> = lines
        .map(|line| {
            let v: Vec<f64> = line.split_whitespace().map(|v| v.parse().unwrap()).collect();
            assert_eq!(v.len(), 3, "pixel line {line:?}");
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(size.len(), 2);
    assert_eq!(pixels.len(), (size[0] * size[1]) as usize, "one line per pixel");
    Printout { width: size[0], height: size[1], pixels }
}

/// The card's source for an `n x n` image: every `32` of `main` becomes `n`;
/// `decimals` replaces the `%.0f` of its printout by `%.{decimals}f`.
fn source_for(n: u32, decimals: u32) -> String {
    let main = SOURCE.find("main(){").expect("the card's main");
    let (head, body) = SOURCE.split_at(main);
    let body = body.replace("32", &n.to_string()).replace("%.0f", &format!("%.{decimals}f"));
    format!("{head}{body}")
}

/// Compiles and runs the card at `n x n` printing `decimals` decimals; `None`
/// when no C compiler is installed.
fn run_card(n: u32, decimals: u32) -> Option<Printout> {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("heckbert-{}-{n}-{decimals}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = dir.join("heckbert.c");
    std::fs::write(&source, source_for(n, decimals)).unwrap();
    let binary = dir.join("heckbert");
    let compiled = ["cc", "gcc"].iter().find_map(|cc| compile(cc, &source, &binary))?;
    assert!(compiled, "the card must compile (see the build line in tests/data/heckbert.c)");
    // The card's `main` returns no value, so its exit status is arbitrary.
    let out = Command::new(&binary).output().expect("run the compiled card");
    Some(parse(std::str::from_utf8(&out.stdout).unwrap()))
}

/// `Some(success)` if compiler `cc` exists, `None` if it does not.
fn compile(cc: &str, source: &Path, binary: &Path) -> Option<bool> {
    let status = Command::new(cc)
        .args(["-std=gnu89", "-ffp-contract=off", "-w", "-O1"])
        .arg(source)
        .arg("-o")
        .arg(binary)
        .arg("-lm")
        .status()
        .ok()?;
    Some(status.success())
}

/// Lamplight's `business-card` at the printout's size, as `255 * radiance`.
fn render_card(width: u32, height: u32) -> Vec<[f64; 3]> {
    let card = builtin::find("business-card").expect("registered");
    let scene = (card.build)().unwrap();
    let options = RenderOptions { width, height, spp: 1, ..RenderOptions::default() };
    let (image, stats) = render_image(&scene, &options, &RenderControl::default()).unwrap();
    assert_eq!(stats.nonfinite_samples, 0);
    image.pixels.iter().map(|p| p.map(|c| 255.0 * c as f64)).collect()
}

/// Asserts every channel of every pixel within `tolerance` of the printout.
fn assert_matches(card: &Printout, tolerance: f64, what: &str) {
    let ours = render_card(card.width, card.height);
    let mut worst = (0.0f64, 0usize, 0usize);
    for (i, (a, b)) in ours.iter().zip(&card.pixels).enumerate() {
        for c in 0..3 {
            let diff = (a[c] - b[c]).abs();
            if diff > worst.0 {
                worst = (diff, i, c);
            }
        }
    }
    let (diff, i, c) = worst;
    let (x, y) = (i as u32 % card.width, i as u32 / card.width);
    assert!(
        diff <= tolerance,
        "{what}: pixel ({x}, {y}) channel {c}: lamplight {:.4} vs card {} (|diff| {diff:.4})",
        ours[i][c],
        card.pixels[i][c]
    );
}

#[test]
fn matches_the_stored_printout() {
    let card = parse(REFERENCE_32);
    assert_eq!((card.width, card.height), (32, 32));
    assert_matches(&card, ROUNDED, "heckbert-32.txt");
}

#[test]
fn matches_the_compiled_card_at_32_and_64() {
    let Some(card32) = run_card(32, 0) else {
        eprintln!("no C compiler (cc, gcc): only the stored printout is compared");
        return;
    };
    assert_eq!(card32.pixels, parse(REFERENCE_32).pixels, "the stored printout is the card's");
    assert_matches(&card32, ROUNDED, "compiled card 32x32");
    let card64 = run_card(64, 0).unwrap();
    assert_eq!((card64.width, card64.height), (64, 64));
    assert_matches(&card64, ROUNDED, "compiled card 64x64");
    for n in [32, 64] {
        let precise = run_card(n, 6).unwrap();
        assert!(precise.pixels.iter().flatten().any(|c| c.fract() != 0.0), "six decimals printed");
        assert_matches(&precise, PRECISE, &format!("compiled card {n}x{n}, six decimals"));
    }
}

#[test]
fn glass_in_the_centre_and_ambient_corners() {
    let card = parse(REFERENCE_32);
    let ours = render_card(32, 32);
    // Rays through the corners miss everything: background 0.02 * 255 = 5.1.
    for (x, y) in [(0, 0), (31, 0), (0, 31), (31, 31)] {
        let i = (y * 32 + x) as usize;
        assert_eq!(card.pixels[i], [5.0; 3]);
        for c in ours[i] {
            assert!((c - 5.1).abs() < 1e-4, "corner ({x}, {y}): {c}");
        }
    }
    // The centre pixel's ray (0, 1/tan 12.5deg, 0) hits the glass sphere at
    // (0, 6, 0.5), radius 0.9; the render agrees with a direct intersection.
    let scene = (builtin::find("business-card").unwrap().build)().unwrap();
    let ray = scene.settings.camera.ray(16.0, 16.0, 32, 32, (0.5, 0.5));
    let hit = scene.first_intersect(&ray, f64::INFINITY).expect("the centre ray hits");
    assert_eq!(hit.object, 0, "the glass sphere");
    // It is mostly refraction (kt = 0.85) of the two spheres behind and the
    // background, so it is neither black nor background.
    let centre = ours[16 * 32 + 16];
    assert!(centre.iter().all(|&c| c > 5.5), "{centre:?}");
    // Below the glass, the orange sphere (centre pixel about (7, 20.5)) is redder
    // than blue, the cyan one (about (25, 20.5)) the reverse.
    let left = ours[24 * 32 + 10];
    let right = ours[24 * 32 + 22];
    assert!(left[0] > left[2] && right[2] > right[0], "orange {left:?}, cyan {right:?}");
}

/// The built-in rendered at `n x n` the way `lamplight render business-card -o
/// card.png` does, its PNG read back as bytes.
fn card_png(n: u32) -> Vec<u8> {
    use lamplight_core::film::tonemap::ToneMap;
    use lamplight_scene::request::{self, DisplayTransform, Naming, Request, SceneRequest};
    let scene_request = SceneRequest::resolve("business-card").unwrap();
    let job = Request { width: Some(n), height: Some(n), ..Request::default() }.resolve(&scene_request.defaults, Naming::Flags).unwrap();
    let rendered = job.run(&scene_request.build().unwrap(), &RenderControl::default()).unwrap();
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("card-{}-{n}.png", std::process::id()));
    let display = DisplayTransform { exposure: 0.0, tonemap: ToneMap::Clamp, transfer: scene_request.defaults.transfer };
    request::write(&path, &rendered, display).unwrap();
    let (w, h, bytes) = lamplight_scene::image_io::read_png_srgb8(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!((w, h), (n, n));
    bytes
}

/// Every byte of the PNG against the card's printed integer (clamped to 255):
/// the largest and the mean difference.
fn png_against(card: &Printout) -> (f64, f64) {
    let bytes = card_png(card.width);
    let printed = card.pixels.iter().flatten().map(|&v| v.clamp(0.0, 255.0));
    let diffs: Vec<f64> = bytes.iter().zip(printed).map(|(&b, p)| (f64::from(b) - p).abs()).collect();
    (diffs.iter().fold(0.0f64, |a, &b| a.max(b)), diffs.iter().sum::<f64>() / diffs.len() as f64)
}

#[test]
fn the_png_holds_the_cards_own_numbers() {
    // The card's output is display values; the built-in's `transfer` is linear,
    // so its PNG stores round(255 I), what the card prints (sRGB encoding made
    // the mean byte 45.7 brighter at 256x256). Ties of the rounding may differ by one.
    let (worst, mean) = png_against(&parse(REFERENCE_32));
    assert!(worst <= 1.0 && mean < 0.01, "32x32: worst {worst}, mean {mean}");
    let Some(card256) = run_card(256, 0) else {
        eprintln!("no C compiler (cc, gcc): the 256x256 printout is not compared");
        return;
    };
    let (worst, mean) = png_against(&card256);
    assert!(worst <= 1.0 && mean < 0.01, "256x256: worst {worst}, mean {mean}");
}
