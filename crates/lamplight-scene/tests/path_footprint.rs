//! Texture filtering in the path tracer: camera rays carry their pixel
//! footprint (ray cones, pbrt-v4's camera approximation after a bounce), so a
//! minified texture is MIP-mapped as in the Whitted tracer.

use std::path::Path;

use lamplight_core::film::Image;
use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

/// A 64 x 64 linear checker of one-texel cells, black and white: mean 0.5.
fn write_checker(dir: &Path) {
    let img = image::GrayImage::from_fn(64, 64, |x, y| image::Luma([if (x + y) % 2 == 0 { 255 } else { 0 }]));
    img.save(dir.join("fine.png")).unwrap();
}

/// The checker, repeated 256 x 256 times, as the emission of a quad that fills
/// an 8 x 4 orthographic view: about 2000 texels per pixel.
fn render(dir: &Path, integrator: &str, filter: &str, spp: u32) -> Image {
    let text = format!(
        "[camera]\ntype = \"orthographic\"\neye = [2, 1, 10]\nlook_at = [2, 1, 0]\nhalf_width = 2\nhalf_height = 1\n\
         [materials.m]\nkd = 0\nka = 0\nemission = {{ type = \"image\", file = \"fine.png\", color_space = \"linear\", filter = \"{filter}\", uv_scale = [256, 256] }}\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [4, 0, 0]\nedge_v = [0, 2, 0]\nmaterial = \"m\"\n"
    );
    let path = dir.join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let built = SceneFile::read(&path).unwrap_or_else(|e| panic!("{e}")).build_with_warnings().unwrap_or_else(|e| panic!("{e}"));
    let integrator = integrators::find(integrator).unwrap();
    let options = RenderOptions { width: 8, height: 4, spp, threads: 1, integrator, ..RenderOptions::default() };
    render_image(&built.scene, &options, &RenderControl::default()).unwrap().0
}

/// Mean and variance of the pixels' green channel.
fn stats(image: &Image) -> (f64, f64) {
    let values: Vec<f64> = image.pixels.iter().map(|p| f64::from(p[1])).collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    (mean, values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64)
}

#[test]
fn a_minified_texture_is_filtered_to_its_mean_in_the_path_tracer() {
    let dir = tempfile::tempdir().unwrap();
    write_checker(dir.path());
    for spp in [1, 4] {
        let (mean, variance) = stats(&render(dir.path(), "path", "trilinear", spp));
        // Every lookup reads the 1 x 1 top of the pyramid, the box mean 0.5
        // (kept in 8 bits: 127 / 255).
        assert!((mean - 0.5).abs() < 3e-3 && variance < 1e-6, "path {spp} spp: mean {mean} variance {variance}");
    }
    // The same as the Whitted tracer's.
    let (whitted_mean, _) = stats(&render(dir.path(), "whitted", "trilinear", 1));
    assert!((whitted_mean - 0.5).abs() < 3e-3, "{whitted_mean}");
    // Point lookups alias: each pixel reads a few texels of 0 and 1 (variance 0.03, not 0).
    let (_, aliased) = stats(&render(dir.path(), "path", "bilinear", 1));
    assert!(aliased > 0.01, "unfiltered variance {aliased}");
}
