//! `explain` on every built-in scene: each pixel's recorded contributions add up
//! to the rendered pixel, bit for bit (the tree is computed by the render's own
//! code and summed in its order, so equality is exact, not within a tolerance).

use lamplight_core::explain::{RayKind, RayNode, Record};
use lamplight_core::RenderControl;
use lamplight_scene::builtin::BUILTINS;
use lamplight_scene::explain::explain;
use lamplight_scene::request::{Naming, Request, SceneRequest};

/// Reflected and refracted rays below `n`.
fn secondary(n: &RayNode) -> (usize, usize) {
    let own = match n.kind {
        RayKind::Reflected => (1, 0),
        RayKind::Refracted => (0, 1),
        RayKind::Camera => (0, 0),
    };
    n.children.iter().map(secondary).fold(own, |a, b| (a.0 + b.0, a.1 + b.1))
}

/// Explains every `stride`-th pixel of a small render of `name`; returns the
/// reflected and refracted rays seen.
fn check(name: &str, integrator: &str, spp: u32, stride: u32) -> (usize, usize) {
    check_request(name, Request { spp: Some(spp), integrator: Some(integrator.into()), ..Request::default() }, stride)
}

/// [`check`] for any request (adaptive sampling when it asks for it).
fn check_request(name: &str, request: Request, stride: u32) -> (usize, usize) {
    let integrator = request.integrator.clone().unwrap_or_default();
    let integrator = integrator.as_str();
    let scene = SceneRequest::resolve(name).unwrap();
    let width = if name == "business-card" { 32 } else { 40 };
    let request = Request { width: Some(width), threads: Some(1), ..request };
    let job = request.resolve(&scene.defaults, Naming::Flags).unwrap();
    let built = scene.build().unwrap();
    let rendered = job.run(&built, &RenderControl::default()).unwrap();
    let (w, h) = (job.options.width, job.options.height);
    let mut seen = (0, 0);
    for i in (0..w * h).step_by(stride as usize) {
        let (x, y) = (i % w, i / w);
        let e = explain(&built, &job, (x, y), None, Naming::Flags).unwrap();
        for s in &e.samples {
            assert_eq!(s.contribution_sum(), s.radiance, "{name} {integrator} ({x}, {y}) sample {}", s.index);
            if let Record::RayTree(root) = &s.record {
                let (a, b) = secondary(root);
                seen = (seen.0 + a, seen.1 + b);
            }
        }
        assert_eq!(e.pixel_f32(), rendered.image.get(x, y), "{name} {integrator} ({x}, {y})");
    }
    seen
}

#[test]
fn whitted_trees_add_up_on_every_builtin() {
    for b in BUILTINS {
        let (reflected, refracted) = check(b.name, "whitted", 1, 1);
        match b.name {
            "luxo" => assert!(reflected > 0 && refracted > 0, "luxo's mirror and glass: {reflected} {refracted}"),
            "spheres" | "business-card" => assert!(reflected > 0, "{}: {reflected}", b.name),
            _ => {}
        }
    }
}

#[test]
fn stratified_whitted_samples_add_up() {
    for b in BUILTINS {
        check(b.name, "whitted", 4, 7);
    }
}

#[test]
fn adaptive_sampling_is_explained_as_rendered() {
    for b in BUILTINS {
        // Whitted's default: anti-aliased where neighbours differ.
        let whitted = Request { integrator: Some("whitted".into()), ..Request::default() };
        check_request(b.name, whitted, 3);
        let path =
            Request { integrator: Some("path".into()), spp: Some(32), noise_threshold: Some(0.1), min_spp: Some(4), ..Request::default() };
        check_request(b.name, path, 13);
    }
}

#[test]
fn paths_add_up_on_every_builtin() {
    for b in BUILTINS {
        check(b.name, "path", 1, 5);
        check(b.name, "path", 4, 11);
    }
}
