//! Which sampling each combination of request and scene settings gives, and the
//! exact refusals.

use std::path::Path;

use lamplight_core::{Adaptive, Antialias, NoiseThreshold};

use crate::instantiate::SceneFile;
use crate::request::{AntialiasRequest, Naming, Request, SceneRequest};

fn scene(render: &str) -> SceneRequest {
    let text = format!("[render]\n{render}\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n");
    SceneRequest::file(SceneFile::parse(Path::new("s.toml"), &text).unwrap(), "s".into()).unwrap()
}

fn resolved(request: Request, scene: &SceneRequest) -> Result<(u32, Option<Adaptive>), String> {
    request.resolve(&scene.defaults, Naming::Flags).map(|j| (j.options.spp, j.options.adaptive)).map_err(|e| e.0)
}

fn aa(threshold: f64) -> Option<Adaptive> {
    Some(Adaptive::Antialias(Antialias { threshold, samples: 16 }))
}

fn noise_at(threshold: f64, min_samples: u32) -> Option<Adaptive> {
    Some(Adaptive::NoiseThreshold(NoiseThreshold { threshold, min_samples }))
}

fn on(threshold: f64) -> Option<AntialiasRequest> {
    Some(AntialiasRequest::On { threshold })
}

#[test]
fn whitted_without_spp_anti_aliases_and_spp_is_fixed_supersampling() {
    let plain = scene("");
    assert_eq!(resolved(Request::default(), &plain), Ok((1, aa(0.3))));
    assert_eq!(resolved(Request { spp: Some(4), ..Request::default() }, &plain), Ok((4, None)));
    assert_eq!(resolved(Request { spp: Some(1), ..Request::default() }, &plain), Ok((1, None)));
    assert_eq!(resolved(Request { antialias: Some(AntialiasRequest::Off), ..Request::default() }, &plain), Ok((1, None)));
    assert_eq!(resolved(Request { antialias: on(0.1), ..Request::default() }, &plain), Ok((1, aa(0.1))));
    // The scene's choice, unless the request makes its own.
    let fixed = scene("spp = 4");
    assert_eq!(resolved(Request::default(), &fixed), Ok((4, None)));
    assert_eq!(resolved(Request { antialias: on(0.3), ..Request::default() }, &fixed), Ok((1, aa(0.3))));
    let file_aa = scene("antialias_threshold = 0.05");
    assert_eq!(resolved(Request::default(), &file_aa), Ok((1, aa(0.05))));
    assert_eq!(resolved(Request { spp: Some(2), ..Request::default() }, &file_aa), Ok((2, None)));
    assert_eq!(resolved(Request::default(), &scene("antialias = false")), Ok((1, None)));
    // The path tracer takes its spp; without one, it samples to the default
    // noise level (0.05, 16 to 1024 samples a pixel).
    let path = Request { integrator: Some("path".into()), ..Request::default() };
    let default_noise = Some(Adaptive::NoiseThreshold(NoiseThreshold { threshold: 0.05, min_samples: 16 }));
    assert_eq!(resolved(path.clone(), &plain), Ok((1024, default_noise)));
    assert_eq!(resolved(Request { spp: Some(1), ..path.clone() }, &plain), Ok((1, None)));
    assert_eq!(resolved(Request { min_spp: Some(4), ..path.clone() }, &plain), Ok((1024, noise_at(0.05, 4))));
    assert_eq!(resolved(path.clone(), &fixed), Ok((4, None)), "the scene's spp is fixed supersampling");
    assert_eq!(resolved(path, &file_aa), Ok((1024, default_noise)), "a scene's antialias has nothing to refine under path");
}

#[test]
fn a_noise_threshold_makes_spp_the_most_a_pixel_takes() {
    let path = || Request { integrator: Some("path".into()), noise_threshold: Some(0.01), ..Request::default() };
    let noise = |threshold, min_samples| Some(Adaptive::NoiseThreshold(NoiseThreshold { threshold, min_samples }));
    let plain = scene("");
    assert_eq!(resolved(path(), &plain), Ok((1024, noise(0.01, 16))));
    assert_eq!(resolved(Request { spp: Some(256), min_spp: Some(32), ..path() }, &plain), Ok((256, noise(0.01, 32))));
    assert_eq!(resolved(Request { spp: Some(8), ..path() }, &plain), Ok((8, noise(0.01, 8))), "min_spp 16 capped by spp 8");
    let file = scene("integrator = \"path\"\nspp = 512\nnoise_threshold = 0.02\nmin_spp = 4");
    assert_eq!(resolved(Request::default(), &file), Ok((512, noise(0.02, 4))));
    assert_eq!(resolved(Request { noise_threshold: Some(0.1), ..Request::default() }, &file), Ok((512, noise(0.1, 4))));
}

#[test]
fn contradictions_are_refused_with_what_to_do() {
    let plain = scene("");
    let both = Request { spp: Some(4), antialias: on(0.3), ..Request::default() };
    assert_eq!(
        resolved(both, &plain).unwrap_err(),
        "give --spp (fixed supersampling, 4 samples everywhere) or --antialias (adaptive: 16 samples where neighbours differ), not both"
    );
    assert_eq!(
        resolved(Request::default(), &scene("spp = 4\nantialias = true")).unwrap_err(),
        "the scene's [render] gives both spp = 4 (fixed supersampling) and antialias (adaptive); keep one"
    );
    let path_aa = Request { integrator: Some("path".into()), antialias: on(0.3), ..Request::default() };
    assert_eq!(
        resolved(path_aa, &plain).unwrap_err(),
        "--antialias is for the Whitted tracer; the path integrator takes --spp samples per pixel (or --noise-threshold)"
    );
    let whitted_noise = Request { noise_threshold: Some(0.01), ..Request::default() };
    assert_eq!(
        resolved(whitted_noise, &plain).unwrap_err(),
        "--noise-threshold is for the path tracer (--integrator path); whitted takes its samples in one pass"
    );
    let path = || Request { integrator: Some("path".into()), ..Request::default() };
    assert_eq!(
        resolved(Request { noise_threshold: Some(0.0), ..path() }, &plain).unwrap_err(),
        "--noise-threshold must be a positive number (a noise level, e.g. 0.01), got 0"
    );
    assert_eq!(
        resolved(Request { noise_threshold: Some(0.01), spp: Some(64), min_spp: Some(128), ..path() }, &plain).unwrap_err(),
        "--min-spp must be between 1 and --spp (64), got 128"
    );
    assert_eq!(
        resolved(Request { min_spp: Some(8), spp: Some(64), ..path() }, &plain).unwrap_err(),
        "--min-spp takes effect only with --noise-threshold"
    );
    // Python spells them as keywords.
    let keywords = Request { spp: Some(4), antialias: on(0.3), ..Request::default() }.resolve(&plain.defaults, Naming::Keywords);
    assert_eq!(
        keywords.unwrap_err().0,
        "give spp (fixed supersampling, 4 samples everywhere) or antialias (adaptive: 16 samples where neighbours differ), not both"
    );
}

#[test]
fn antialias_flags_parse_as_povray_users_write_them() {
    assert_eq!("on".parse::<AntialiasRequest>(), Ok(AntialiasRequest::On { threshold: 0.3 }));
    assert_eq!("off".parse::<AntialiasRequest>(), Ok(AntialiasRequest::Off));
    assert_eq!("0.1".parse::<AntialiasRequest>(), Ok(AntialiasRequest::On { threshold: 0.1 }));
    assert_eq!("-1".parse::<AntialiasRequest>().unwrap_err(), "expected `on`, `off` or a threshold >= 0 (POV-Ray's 0.3), got '-1'");
}

#[test]
fn file_settings_are_checked_at_their_keys() {
    let err = |render: &str| {
        let text = format!("[render]\n{render}\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n");
        SceneFile::parse(Path::new("s.toml"), &text).unwrap().settings().unwrap_err().to_string()
    };
    assert_eq!(err("noise_threshold = -1"), "s.toml:2:19: render: noise_threshold: must be a positive number, got -1");
    assert_eq!(err("antialias_threshold = -0.5"), "s.toml:2:23: render: antialias_threshold: must be a non-negative number, got -0.5");
    assert!(err("antialias = 0.3").starts_with("s.toml:2:13: render: antialias: expected"), "{}", err("antialias = 0.3"));
}

#[test]
fn a_filter_is_refused_by_an_integrator_that_does_not_place_samples_by_it() {
    let plain = scene("");
    let filtered = |integrator: &str, filter: &str| {
        let request = Request { integrator: Some(integrator.into()), filter: Some(filter.into()), spp: Some(4), ..Request::default() };
        request.resolve(&plain.defaults, Naming::Flags).map(|j| j.options.filter).map_err(|e| e.0)
    };
    assert_eq!(
        filtered("whitted", "gaussian"),
        Err("--filter is for the path tracer (--integrator path); whitted averages its samples over the pixel square (a box)".into())
    );
    assert_eq!(filtered("whitted", "box"), Ok(lamplight_core::film::Filter::Box), "the box is what Whitted does");
    assert_eq!(filtered("path", "gaussian"), Ok(lamplight_core::film::Filter::Gaussian { sigma: 0.5 }));
}
