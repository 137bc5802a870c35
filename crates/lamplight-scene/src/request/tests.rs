//! The request layer's precedence, limits and messages.

use super::*;

fn luxo() -> SceneRequest {
    SceneRequest::resolve("luxo").unwrap()
}

#[test]
fn a_misspelt_scene_or_layer_names_the_nearest() {
    let err = SceneRequest::resolve("sphere").unwrap_err().0;
    assert!(err.starts_with("unknown scene \"sphere\" (did you mean 'spheres'? built-in scenes: luxo, "), "{err}");
    assert_eq!(
        "varience".parse::<Layer>().unwrap_err(),
        "unknown layer \"varience\" (did you mean 'variance'? layers: variance, samples, albedo, normal, noisy, emitted)"
    );
}

#[test]
fn one_side_keeps_the_default_aspect() {
    let n = Naming::Flags;
    assert_eq!(image_size(Some(640), None, (1280, 720), n).unwrap(), (640, 360));
    assert_eq!(image_size(None, Some(36), (1280, 720), n).unwrap(), (64, 36));
    assert_eq!(image_size(Some(1), None, (1280, 720), n).unwrap(), (1, 1), "never rounds to 0");
    assert_eq!(image_size(Some(7), Some(3), (1280, 720), n).unwrap(), (7, 3));
}

#[test]
fn limits_are_the_same_for_every_front_end_and_spelled_its_way() {
    let r = Request { spp: Some(u32::MAX), ..Request::default() };
    assert_eq!(r.resolve(&luxo().defaults, Naming::Flags).unwrap_err().0, "--spp must be between 1 and 1048576, got 4294967295");
    assert_eq!(r.resolve(&luxo().defaults, Naming::Keywords).unwrap_err().0, "spp must be between 1 and 1048576, got 4294967295");
    let r = Request { threads: Some(100_000), ..Request::default() };
    assert_eq!(r.resolve(&luxo().defaults, Naming::Keywords).unwrap_err().0, "threads must be at most 1024 (0 uses all cores), got 100000");
    let r = Request { max_depth: Some(65), ..Request::default() };
    assert_eq!(
        r.resolve(&luxo().defaults, Naming::Flags).unwrap_err().0,
        "--max-depth must be between 1 and 64 (work grows as 2^depth), got 65"
    );
    let r = Request { integrator: Some("photon".into()), ..Request::default() };
    assert_eq!(r.resolve(&luxo().defaults, Naming::Flags).unwrap_err().0, "--integrator must be \"whitted\" or \"path\", got \"photon\"");
}

#[test]
fn the_request_wins_over_the_scene_which_wins_over_the_defaults() {
    let text = "[render]\nwidth = 100\nheight = 50\nspp = 8\nseed = 3\nintegrator = \"path\"\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";
    let file = SceneFile::parse(Path::new("s.toml"), text).unwrap();
    let scene = SceneRequest::file(file, "s".into()).unwrap();
    let job = Request::default().resolve(&scene.defaults, Naming::Flags).unwrap();
    let o = &job.options;
    assert_eq!((o.width, o.height, o.spp, o.seed, o.integrator.name), (100, 50, 8, 3, "path"));
    let job = Request { width: Some(40), spp: Some(2), integrator: Some("whitted".into()), ..Request::default() }
        .resolve(&scene.defaults, Naming::Flags)
        .unwrap();
    let o = &job.options;
    assert_eq!((o.width, o.height, o.spp, o.seed, o.integrator.name), (40, 20, 2, 3, "whitted"));
    let o = Request::default().resolve(&luxo().defaults, Naming::Flags).unwrap().options;
    assert_eq!((o.width, o.height, o.spp, o.seed, o.integrator.name), (1280, 720, 1, 0, "whitted"));
}
