//! Denoising through the request layer, as the command line and Python run it:
//! the feature layers of a built-in scene, and a denoised Cornell box measured
//! against a converged one. The denoiser's tests skip, saying so, on a machine
//! without Open Image Denoise, except under CI ([`denoise::for_test`]).

use lamplight_core::film::Image;
use lamplight_core::RenderControl;
use lamplight_scene::denoise;
use lamplight_scene::request::{Layer, Naming, Rendered, Request, SceneRequest};

use crate::common::rmse;

fn render(scene: &str, request: Request) -> Rendered {
    let scene = SceneRequest::resolve(scene).unwrap();
    let job = request.resolve(&scene.defaults, Naming::Flags).unwrap();
    let built = scene.instantiate(&job).unwrap();
    job.run(&built.scene, &RenderControl::default()).unwrap()
}

fn cornell(size: u32, spp: u32, seed: u64, denoise: bool, layers: Vec<Layer>) -> Rendered {
    let request = Request {
        width: Some(size),
        height: Some(size),
        spp: Some(spp),
        seed: Some(seed),
        denoise: Some(denoise),
        layers,
        ..Request::default()
    };
    render("cornell-box", request)
}

fn layer(rendered: &Rendered, which: Layer) -> &Image {
    &rendered.layers.iter().find(|(l, _)| *l == which).unwrap().1
}

/// The box's walls are Lambertian: their albedo is their colour (the red
/// wall's, `0.570068, 0.0430135, 0.0443706`) and their normal faces into the
/// box; the light, an emitter, has albedo 0.
#[test]
fn the_cornell_box_walls_have_their_colour_and_normal() {
    let r = cornell(32, 4, 0, false, vec![Layer::Albedo, Layer::Normal]);
    let (albedo, normal) = (layer(&r, Layer::Albedo), layer(&r, Layer::Normal));
    // A pixel in the middle of the left (red) wall.
    let (x, y) = (2, 16);
    let a = albedo.get(x, y);
    assert_eq!(a, [0.570068, 0.0430135, 0.0443706], "red wall albedo");
    let n = normal.get(x, y);
    assert!(n[0] > 0.99 && n[1].abs() < 0.01 && n[2].abs() < 0.01, "the left wall faces +x: {n:?}");
    // The middle of the light, in the ceiling: albedo 0, facing down.
    let (lx, ly) = (16, 4);
    assert_eq!(albedo.get(lx, ly), [0.0; 3], "the light is marked as an emitter");
    let n = normal.get(lx, ly);
    assert!(n[1] == -1.0 && n[0].abs() < 1e-6 && n[2].abs() < 1e-6, "the light faces down: {n:?}");
}

/// Displayed values: radiance clamped to `[0, 1]`, as a PNG shows it.
fn shown(image: &Image) -> Image {
    Image { pixels: image.pixels.iter().map(|p| p.map(|c| c.clamp(0.0, 1.0))).collect(), ..image.clone() }
}

/// The measurement, small: at 64x64 a 16-spp render denoised is
/// closer to a converged one (1024 spp, another seed) than the noisy render,
/// in the values a display shows (clamped to `[0, 1]`). Measured 2026-12 with
/// OIDN 2.5.1: RMSE noisy 0.0205, denoised 0.0076 (2.7x); the test asks for 2x.
/// In linear radiance the denoised image is further off (0.080 against 0.035):
/// the light's anti-aliased edge pixels (radiance up to 18, white on any
/// display) move by up to 2 (docs/denoise.md).
#[test]
fn a_denoised_cornell_box_is_closer_to_the_converged_one() {
    if denoise::for_test("a_denoised_cornell_box_is_closer_to_the_converged_one").is_none() {
        return;
    }
    let reference = shown(&cornell(64, 1024, 99, false, vec![]).image);
    let denoised = cornell(64, 16, 1, true, vec![Layer::Noisy]);
    let noisy = layer(&denoised, Layer::Noisy);
    let (before, after) = (rmse(&shown(noisy), &reference), rmse(&shown(&denoised.image), &reference));
    eprintln!("cornell-box 64x64, 16 spp against 1024, displayed: RMSE noisy {before:.4}, denoised {after:.4} ({:.1}x)", before / after);
    assert!(after * 2.0 < before, "denoised RMSE {after} is not half the noisy {before}");
    // The noisy layer is the render without denoising, exactly.
    assert_eq!(noisy, &cornell(64, 16, 1, false, vec![]).image);
}
