//! Denoising through the request layer, as the command line and Python run it:
//! the feature layers of a built-in scene, and a denoised Cornell box measured
//! against a converged one. The denoiser's tests skip, saying so, on a machine
//! without Open Image Denoise, except under CI ([`denoise::for_test`]).

use lamplight_core::film::Image;
use lamplight_core::RenderControl;
use lamplight_scene::denoise;
use lamplight_scene::denoise::Guides;
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
/// both in the values a display shows (clamped to `[0, 1]`) and in linear
/// radiance. Measured 2026-12-05 with OIDN 2.5.1: displayed RMSE noisy 0.0205,
/// denoised 0.0089 (2.3x; the test asks 2x); linear 0.0346 against 0.0289
/// (1.20x; it asks 1.1x). Linear radiance is what the `emitted` split fixed:
/// filtering the whole image, light included, moved the light's edge pixels
/// (radiance up to 18) by up to 2, and its linear RMSE was 0.0795, worse than
/// the noisy image's (docs/denoise.md). What is left of the linear error is
/// mostly those edge pixels' coverage, which the noisy image has too.
#[test]
fn a_denoised_cornell_box_is_closer_to_the_converged_one() {
    if denoise::for_test("a_denoised_cornell_box_is_closer_to_the_converged_one").is_none() {
        return;
    }
    let reference = cornell(64, 1024, 99, false, vec![]).image;
    let denoised = cornell(64, 16, 1, true, vec![Layer::Noisy]);
    let noisy = layer(&denoised, Layer::Noisy);
    let (before, after) = (rmse(&shown(noisy), &shown(&reference)), rmse(&shown(&denoised.image), &shown(&reference)));
    eprintln!("cornell-box 64x64, 16 spp against 1024, displayed: RMSE noisy {before:.4}, denoised {after:.4} ({:.1}x)", before / after);
    assert!(after * 2.0 < before, "displayed: denoised RMSE {after} is not half the noisy {before}");
    let (before, after) = (rmse(noisy, &reference), rmse(&denoised.image, &reference));
    eprintln!("linear: RMSE noisy {before:.4}, denoised {after:.4} ({:.2}x)", before / after);
    assert!(after * 1.1 < before, "linear: denoised RMSE {after} is not 1.1 times below the noisy {before}");
    // The noisy layer is the render without denoising, exactly.
    assert_eq!(noisy, &cornell(64, 16, 1, false, vec![]).image);
}

/// The device and filter are kept between calls (`denoise/oidn.rs`): a call
/// after calls of another size, another thread count, from several threads at
/// once, or after an error, gives the same bytes as the first.
#[test]
fn the_kept_device_and_filter_give_the_same_bytes_every_call() {
    let Some(denoiser) = denoise::for_test("the_kept_device_and_filter_give_the_same_bytes_every_call") else { return };
    let r = cornell(24, 4, 3, false, vec![Layer::Albedo, Layer::Normal, Layer::Emitted]);
    let guides =
        Guides { albedo: Some(layer(&r, Layer::Albedo)), normal: Some(layer(&r, Layer::Normal)), emitted: Some(layer(&r, Layer::Emitted)) };
    let first = denoiser.denoise(&r.image, guides, 2).unwrap();
    let small = cornell(8, 4, 3, false, vec![]).image;
    let small_first = denoiser.denoise(&small, Guides::default(), 2).unwrap();
    assert_eq!(denoiser.denoise(&r.image, guides, 2).unwrap(), first, "after another size");
    assert_eq!(denoiser.denoise(&r.image, guides, 1).unwrap(), first, "on another device's thread count");
    // A size mismatch is refused before the library is called; the next call is unharmed.
    let bad = Guides { albedo: Some(&small), ..guides };
    assert_eq!(denoiser.denoise(&r.image, bad, 2).unwrap_err().0, "the albedo layer is 8x8, the image 24x24");
    let loaded_again = denoise::Denoiser::load(&[]).unwrap();
    std::thread::scope(|s| {
        let calls: Vec<_> = (0..4)
            .map(|i| {
                let (denoiser, first, small, small_first) = (&loaded_again, &first, &small, &small_first);
                let image = &r.image;
                s.spawn(move || {
                    if i % 2 == 0 {
                        assert_eq!(&denoiser.denoise(image, guides, 2).unwrap(), first, "thread {i}");
                    } else {
                        assert_eq!(&denoiser.denoise(small, Guides::default(), 2).unwrap(), small_first, "thread {i}");
                    }
                })
            })
            .collect();
        calls.into_iter().for_each(|c| c.join().unwrap());
    });
}
