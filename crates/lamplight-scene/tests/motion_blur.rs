//! Motion blur (issue 29): `[animation] shutter`. A sphere moving at
//! constant speed smears into the analytic profile; a closed shutter renders
//! the same bytes as no shutter; still shapes are built as without motion
//! blur; the shutter's errors are exact.

use std::path::Path;

use lamplight_core::integrators::{find, View};
use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

/// A sphere of radius 1/2 moving from x = -2 at frame 0 to x = 2 at frame 2
/// (x = 2 t at instant t of frame 1, the frame rendered),
/// seen by an orthographic camera down -z over x in [-1, 3], y in [-1/2, 1/2],
/// against a background (Whitted) or sky (path) of 1. The sphere is black (it
/// reflects nothing), so a pixel is 1 less the fraction of its samples'
/// instants at which the sphere covers them.
fn scene(shutter: Option<&str>, extra: &str) -> String {
    let shutter = shutter.map(|s| format!("shutter = {s}\n")).unwrap_or_default();
    format!(
        "background = 1\n\
         [animation]\nframes = [0, 2]\n{shutter}\
         [camera]\ntype = \"orthographic\"\neye = [1, 0, 5]\nlook_at = [1, 0, 0]\nhalf_width = 2\nhalf_height = 0.5\n\
         [materials.flat]\ncolor = 0\nka = 0\nkd = 0\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.5\nmaterial = \"flat\"\n\
         animate.translate = {{ frames = [0, 2], values = [[-2, 0, 0], [2, 0, 0]] }}\n{extra}"
    )
}

const WIDTH: u32 = 64;
const HEIGHT: u32 = 16;

fn render(text: &str, spp: u32, integrator: &str) -> Vec<[f32; 3]> {
    let file = SceneFile::parse(Path::new("s.toml"), text).unwrap();
    let scene = file.build_frame(Some(1)).unwrap().scene;
    let options =
        RenderOptions { width: WIDTH, height: HEIGHT, spp, threads: 2, integrator: find(integrator).unwrap(), ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

/// The fraction of the shutter `[open, close]` (frames from frame 1) during
/// which the sphere covers the point `(x, y)`: its centre is at `2 t`, and it
/// covers `x` while `|x - 2 t| < sqrt(r^2 - y^2)`.
fn covered(x: f64, y: f64, open: f64, close: f64) -> f64 {
    let h2 = 0.25 - y * y;
    if h2 <= 0.0 {
        return 0.0;
    }
    let h = h2.sqrt();
    let (lo, hi) = (((x - h) / 2.0).max(open), ((x + h) / 2.0).min(close));
    (hi - lo).max(0.0) / (close - open)
}

/// [`covered`] averaged over pixel `(px, py)` (a 64 x 64 grid of points).
fn expected(px: u32, py: u32, open: f64, close: f64) -> f64 {
    let n = 64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -1.0 + 4.0 * (px as f64 + (i as f64 + 0.5) / n as f64) / WIDTH as f64;
            let y = 0.5 - (py as f64 + (j as f64 + 0.5) / n as f64) / HEIGHT as f64;
            sum += covered(x, y, open, close);
        }
    }
    sum / (n * n) as f64
}

#[test]
fn a_sphere_at_constant_speed_smears_into_the_analytic_profile() {
    for (shutter, open, close) in [("[0, 1]", 0.0, 1.0), ("[-0.25, 0.25]", -0.25, 0.25)] {
        for integrator in ["whitted", "path"] {
            let pixels = render(&scene(Some(shutter), ""), 256, integrator);
            let mut sum_error = 0.0;
            for py in [HEIGHT / 2 - 1, HEIGHT / 2, 3] {
                for px in 0..WIDTH {
                    let got = 1.0 - pixels[(py * WIDTH + px) as usize][0] as f64;
                    let want = expected(px, py, open, close);
                    // Each of the 256 samples sees the sphere (1) or not (0), with
                    // probability `want`: its mean has a standard error of at most
                    // sqrt(want (1 - want) / 256) (less where instants are stratified).
                    let sigma = (want * (1.0 - want) / 256.0).sqrt();
                    assert!(
                        (got - want).abs() <= 4.5 * sigma + 1e-3,
                        "{integrator}, shutter {shutter}, pixel ({px}, {py}): {got} against {want} (sigma {sigma})"
                    );
                    sum_error += got - want;
                }
            }
            let bias = sum_error / (3 * WIDTH) as f64;
            assert!(bias.abs() < 0.004, "{integrator}, shutter {shutter}: mean difference {bias}");
        }
    }
    // The smear is the motion's: the middle of the path at x = 1 is covered half the
    // time of the [0, 1] shutter (the sphere spans 1 of the 2 units travelled).
    assert!((expected(WIDTH / 2, HEIGHT / 2, 0.0, 1.0) - 0.5).abs() < 0.02);
}

#[test]
fn a_closed_shutter_is_the_same_bytes_as_none() {
    let none = render(&scene(None, ""), 16, "path");
    for closed in ["[0, 0]", "[0.5, 0.5]"] {
        assert_eq!(render(&scene(Some(closed), ""), 16, "path"), none, "shutter {closed}");
    }
    assert_eq!(render(&scene(Some("[0, 0]"), ""), 4, "whitted"), render(&scene(None, ""), 4, "whitted"));
    // An open shutter does blur, and the image is not all one value.
    assert_ne!(render(&scene(Some("[0, 1]"), ""), 16, "path"), none);
    assert!(none.iter().any(|p| p[0] == 0.0) && none.iter().any(|p| p[0] == 1.0));
}

#[test]
fn still_shapes_are_built_as_without_motion_blur() {
    // A second, still sphere: the scene with an open shutter draws instants (it
    // has a moving shape), but the still sphere is not wrapped, and a scene of
    // still shapes alone draws none and renders as without a shutter.
    let still = "[[objects]]\ntype = \"sphere\"\ncenter = [2, 0, -2]\nradius = 0.3\nmaterial = \"flat\"\n";
    let file = SceneFile::parse(Path::new("s.toml"), &scene(Some("[0, 1]"), still)).unwrap();
    let scene_built = file.build_frame(Some(1)).unwrap().scene;
    let moving: Vec<bool> = scene_built.objects.iter().map(|o| o.shape.moves()).collect();
    assert_eq!(moving, [true, false]);
    assert_eq!(scene_built.shutter(), Some((0.0, 1.0)));
    let view = View::new(&scene_built, &*scene_built.settings.camera, 8, 8, 1, 0);
    assert_eq!(view.shutter, Some((0.0, 1.0)));

    let only_still = format!(
        "background = 1\n[animation]\nframes = [1, 2]\nshutter = [0, 1]\n\
         [camera]\ntype = \"orthographic\"\neye = [1, 0, 5]\nlook_at = [1, 0, 0]\nhalf_width = 2\nhalf_height = 0.5\n\
         [materials.flat]\ncolor = 0\nka = 0\nkd = 0\n{still}"
    );
    let file = SceneFile::parse(Path::new("s.toml"), &only_still).unwrap();
    assert_eq!(file.build_frame(Some(1)).unwrap().scene.shutter(), None);
    assert_eq!(render(&only_still, 16, "path"), render(&only_still.replace("shutter = [0, 1]\n", ""), 16, "path"));

    // An unbounded shape has no box to sweep: a moving plane stands as at the frame.
    let plane = "[[objects]]\ntype = \"plane\"\npoint = [0, 0, -3]\nnormal = [0, 0, 1]\nmaterial = \"flat\"\n\
                 animate.translate = { frames = [0, 2], values = [[0, 0, 0], [0, 0, 1]] }\n";
    let file = SceneFile::parse(Path::new("s.toml"), &scene(Some("[0, 1]"), plane)).unwrap();
    let built = file.build_frame(Some(1)).unwrap().scene;
    assert_eq!(built.objects.iter().map(|o| o.shape.moves()).collect::<Vec<_>>(), [true, false]);
}

#[test]
fn bad_shutters_give_their_exact_errors() {
    let error = |shutter: &str| {
        let text = scene(Some(shutter), "");
        match SceneFile::parse(Path::new("s.toml"), &text).and_then(|f| f.build()) {
            Ok(_) => panic!("expected an error for shutter {shutter}"),
            Err(e) => e.to_string(),
        }
    };
    assert_eq!(error("[1, 0]"), "s.toml:4:11: animation: shutter: [1, 0] must have open <= close, both within ±1000 frames");
    assert_eq!(error("[0, 5000]"), "s.toml:4:11: animation: shutter: [0, 5000] must have open <= close, both within ±1000 frames");
    assert!(error("[0]").starts_with("s.toml:4:11: animation: shutter:"), "{}", error("[0]"));
}
