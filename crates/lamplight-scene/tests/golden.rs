//! Golden images: each built-in scene rendered small must match its stored reference.
//!
//! References are 8-bit sRGB PNGs in `tests/golden/`. Tolerance: the mean absolute
//! difference must stay below 0.05 levels, at most 0.1 % of the channel values may
//! differ by more than one level, and none by more than 24. The renderer is
//! deterministic, so on the machine that made the references the images are equal;
//! the tolerance admits last-bit differences of `tan`/`powf` between C libraries,
//! which can move a value across a rounding boundary or, rarely, a silhouette pixel.
//!
//! To regenerate after an intended change: `LAMPLIGHT_BLESS=1 cargo test -p lamplight-scene --test all golden::`,
//! then look at the new images before committing them. On failure the rendered image
//! and a difference mask are written next to the test binary's target directory.

use std::path::PathBuf;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::builtin;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests").join("golden")
}

fn check(name: &str, width: u32, height: u32, spp: u32) {
    let scene = (builtin::find(name).unwrap().build)().unwrap();
    let options = RenderOptions { width, height, spp, ..RenderOptions::default() };
    let (image, stats) = render_image(&scene, &options, &RenderControl::default()).unwrap();
    assert_eq!(stats.nonfinite_samples, 0, "{name}: NaN or infinite samples");
    let actual = image.to_srgb8();
    let reference_path = golden_dir().join(format!("{name}-{width}x{height}-{spp}spp.png"));
    if std::env::var_os("LAMPLIGHT_BLESS").is_some() {
        image::save_buffer(&reference_path, &actual, width, height, image::ExtendedColorType::Rgb8).unwrap();
        eprintln!("wrote {}", reference_path.display());
        return;
    }
    let reference = image::open(&reference_path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with LAMPLIGHT_BLESS=1 to create it)", reference_path.display()))
        .to_rgb8();
    assert_eq!((reference.width(), reference.height()), (width, height), "{name}: reference size");
    let reference = reference.into_raw();
    let diffs: Vec<u8> = actual.iter().zip(&reference).map(|(a, b)| a.abs_diff(*b)).collect();
    let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let over_one = diffs.iter().filter(|&&d| d > 1).count();
    let worst = diffs.iter().copied().max().unwrap_or(0);
    let ok = mean < 0.05 && over_one as f64 <= 0.001 * diffs.len() as f64 && worst <= 24;
    if !ok {
        let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        let img_path = out.join(format!("{name}-actual.png"));
        image::save_buffer(&img_path, &actual, width, height, image::ExtendedColorType::Rgb8).unwrap();
        let mask: Vec<u8> = diffs.chunks(3).map(|c| if c.iter().any(|&d| d > 1) { 255 } else { 0 }).collect();
        image::save_buffer(out.join(format!("{name}-diff.png")), &mask, width, height, image::ExtendedColorType::L8).unwrap();
        panic!(
            "{name}: differs from {}: mean {mean:.4} levels, {over_one} values off by more than 1, worst {worst}; actual image in {}",
            reference_path.display(),
            img_path.display()
        );
    }
}

#[test]
fn luxo_matches_its_reference() {
    check("luxo", 192, 108, 4);
}

#[test]
fn spheres_matches_its_reference() {
    check("spheres", 192, 108, 1);
}

#[test]
fn business_card_matches_its_reference() {
    check("business-card", 64, 64, 1);
}
