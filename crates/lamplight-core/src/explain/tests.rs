//! The explanation adds up: on a scene with a mirror, glass, a checker-free
//! floor, a point light and an area light, every pixel's recorded contributions
//! sum to its sample's radiance bit for bit, and the pixel to the render's.

use super::summary::luminance;
use super::*;
use crate::integrators::trace::LightRef;
use crate::prelude::*;
use crate::RenderControl;

fn scene() -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 1.5, 6.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y, Fov::VerticalDeg(45.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let floor = b.material(Material::plastic(Rgb::new(0.8, 0.7, 0.6), 0.1, 0.8, 0.2, 20.0)).unwrap();
    let glass = b.material(Material::glass(1.5, 0.5, 60.0)).unwrap();
    let mirror = b.material(Material::metal(Metal::Silver, 0.0, 1.0)).unwrap();
    let lamp = b.material(Material { emission: Rgb::splat(4.0), kd: Rgb::ZERO, ka: Rgb::ZERO, ..Material::default() }).unwrap();
    b.object(Plane::new(Vec3::ZERO, Vec3::Y).unwrap(), floor).unwrap();
    b.object(Sphere::new(Vec3::new(-0.8, 0.7, 0.0), 0.7).unwrap(), glass).unwrap();
    b.object(Sphere::new(Vec3::new(0.9, 0.6, -0.5), 0.6).unwrap(), mirror).unwrap();
    b.object(Rectangle::new(Vec3::new(-0.5, 3.0, -0.5), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0)).unwrap(), lamp).unwrap();
    b.light(PointLight::new(Vec3::new(3.0, 4.0, 3.0), Rgb::splat(30.0)).unwrap());
    b.settings.ambient = Rgb::splat(0.2);
    b.settings.background = Rgb::new(0.1, 0.2, 0.4);
    b.build().unwrap()
}

fn options(integrator: &str, spp: u32) -> RenderOptions {
    RenderOptions { width: 24, height: 16, spp, seed: 7, integrator: integrator.parse().unwrap(), threads: 1, ..RenderOptions::default() }
}

/// The contributions sum to each sample's radiance exactly, and the pixel is the render's.
fn adds_up(integrator: &str, spp: u32) -> (usize, usize) {
    adds_up_with(options(integrator, spp))
}

fn adds_up_with(o: RenderOptions) -> (usize, usize) {
    let integrator = o.integrator.name;
    let scene = scene();
    let (image, _) = crate::render_image(&scene, &o, &RenderControl::default()).unwrap();
    let (mut reflected, mut refracted) = (0, 0);
    for y in 0..o.height {
        for x in 0..o.width {
            let e = explain(&scene, &o, x, y, None).unwrap();
            assert_eq!(e.samples.len(), e.spp as usize);
            for s in &e.samples {
                assert_eq!(s.contribution_sum(), s.radiance, "({x}, {y}) sample {}", s.index);
                if let Record::RayTree(root) = &s.record {
                    let (a, b) = count(root);
                    reflected += a;
                    refracted += b;
                    terms_add_up(root);
                }
            }
            assert_eq!(e.pixel_f32(), image.get(x, y), "{integrator} pixel ({x}, {y})");
        }
    }
    (reflected, refracted)
}

/// Reflected and refracted rays in the tree.
fn count(n: &RayNode) -> (usize, usize) {
    let own = match n.kind {
        RayKind::Reflected => (1, 0),
        RayKind::Refracted => (0, 1),
        RayKind::Camera => (0, 0),
    };
    n.children.iter().map(count).fold(own, |a, b| (a.0 + b.0, a.1 + b.1))
}

/// `Ke + ka C La + the lights' terms`, summed as the tracer sums them (area
/// points first within their light), is each hit's direct light, and the
/// contribution is the weight times it.
fn terms_add_up(n: &RayNode) {
    if let RayOutcome::Hit(s) = &n.outcome {
        let mut direct = s.emission + s.ambient;
        let mut area = Rgb::ZERO;
        for l in &s.lights {
            let r = match &l.outcome {
                LightOutcome::Lit { term, .. } => term.radiance,
                LightOutcome::Unlit(_) => Rgb::ZERO,
            };
            match l.light {
                LightRef::Delta(_) => direct += r,
                LightRef::Area { .. } => area += r,
            }
        }
        if s.lights.iter().any(|l| matches!(l.light, LightRef::Area { .. })) {
            direct += area;
        }
        assert_eq!(direct, s.direct);
        assert_eq!(n.weight * s.direct, s.contribution);
    }
    n.children.iter().for_each(terms_add_up);
}

#[test]
fn whitted_trees_add_up_to_the_render() {
    let (reflected, refracted) = adds_up("whitted", 1);
    assert!(reflected > 20 && refracted > 20, "the image shows mirror and glass: {reflected} {refracted}");
    adds_up("whitted", 4);
}

#[test]
fn paths_add_up_to_the_render() {
    adds_up("path", 1);
    adds_up("path", 6);
}

#[test]
fn adaptive_anti_aliasing_is_explained_as_rendered() {
    let o = RenderOptions { adaptive: Some(crate::Adaptive::Antialias(crate::Antialias::default())), ..options("whitted", 1) };
    adds_up_with(o.clone());
    let scene = scene();
    let counts: Vec<u32> = (0..o.width).map(|x| plan(&scene, &o, x, 8).unwrap().samples).collect();
    assert!(counts.contains(&16) && counts.contains(&1), "{counts:?}");
}

#[test]
fn the_noise_threshold_is_explained_as_rendered() {
    let noise = crate::NoiseThreshold { threshold: 0.3, min_samples: 4 };
    let o = RenderOptions { adaptive: Some(crate::Adaptive::NoiseThreshold(noise)), ..options("path", 64) };
    adds_up_with(o.clone());
    let scene = scene();
    let counts: Vec<u32> = (0..o.width * o.height).map(|i| plan(&scene, &o, i % o.width, i / o.width).unwrap().samples).collect();
    assert!(counts.iter().any(|n| *n < 64) && counts.iter().all(|n| *n >= 4), "{counts:?}");
}

#[test]
fn one_sample_is_the_renders_sample() {
    let scene = scene();
    let o = options("path", 8);
    let all = explain(&scene, &o, 10, 9, None).unwrap();
    let one = explain(&scene, &o, 10, 9, Some(5)).unwrap();
    assert_eq!(one.samples, all.samples[5..6]);
    assert_eq!(one.pixel, all.pixel);
}

#[test]
fn glass_hit_shows_fresnel_and_both_rays() {
    let scene = scene();
    let o = options("whitted", 1);
    // Find a camera ray that hits the glass sphere (object 1).
    let tree = (0..o.width)
        .flat_map(|x| (0..o.height).map(move |y| (x, y)))
        .find_map(|(x, y)| match explain(&scene, &o, x, y, None).unwrap().samples.remove(0).record {
            Record::RayTree(root) => match &root.outcome {
                RayOutcome::Hit(s) if s.hit.object == 1 => Some(root),
                _ => None,
            },
            _ => None,
        })
        .expect("some pixel sees the glass");
    let RayOutcome::Hit(s) = &tree.outcome else { unreachable!() };
    assert!(s.hit.front_face && !s.hit.flipped);
    let Some((crate::integrators::trace::ReflectionWeight::Dielectric { fresnel }, w)) = s.reflection else { panic!("{:?}", s.reflection) };
    assert!(fresnel > 0.0 && fresnel < 1.0);
    assert_eq!(s.refraction.unwrap().1.unwrap(), Rgb::splat(1.0 - fresnel));
    assert_eq!(w.x, fresnel, "min 0, max 1");
    let kinds: Vec<RayKind> = tree.children.iter().map(|c| c.kind).collect();
    assert_eq!(kinds, [RayKind::Reflected, RayKind::Refracted]);
    assert!(!tree.children[0].inside && tree.children[1].inside, "the refracted ray is inside the glass");
    let text = explain(&scene, &o, 0, 0, None).unwrap().to_string();
    assert!(text.starts_with("pixel (0, 0) of 24x16, whitted integrator, 1 sample here"), "{text}");
}

#[test]
fn bad_pixels_and_samples_are_refused() {
    let scene = scene();
    let o = options("whitted", 2);
    assert_eq!(explain(&scene, &o, 24, 0, None).unwrap_err().to_string(), "invalid pixel: (24, 0) is outside the 24x16 image");
    assert_eq!(
        explain(&scene, &o, 0, 0, Some(2)).unwrap_err().to_string(),
        "invalid sample: 2 does not exist: the pixel takes 2 samples (0 to 1)"
    );
}

#[test]
fn kind_names_come_from_the_debug_text() {
    assert_eq!(kind_name(&Sphere::new(Vec3::ZERO, 1.0).unwrap()), "Sphere");
    let placed =
        crate::shapes::placed(std::sync::Arc::new(Sphere::new(Vec3::ZERO, 1.0).unwrap()), &Mat4::from_scale(Vec3::splat(2.0))).unwrap();
    assert_eq!(kind_name(&*placed), "Sphere (instance)");
}

#[test]
fn past_the_first_64_samples_are_summarised_not_recorded() {
    // See: issue 30 (131,072 samples recorded in full took 3.2 GB).
    let scene = scene();
    let o = options("path", 200);
    let e = explain(&scene, &o, 10, 9, None).unwrap();
    assert_eq!(MAX_RECORDED_SAMPLES, 64);
    assert_eq!(e.samples.iter().map(|s| s.index).collect::<Vec<_>>(), (0..64).collect::<Vec<_>>());
    let u = e.unrecorded.unwrap();
    assert_eq!((u.first, u.count, u.dropped), (64, 136, 0));
    // The summary is of the render's own samples: each one explained alone.
    let (mut sum, mut brightest) = (Rgb::ZERO, (0, Rgb::ZERO));
    for k in 64..200 {
        let l = explain(&scene, &o, 10, 9, Some(k)).unwrap().samples[0].film_value.unwrap();
        sum += l;
        if luminance(l) > luminance(brightest.1) {
            brightest = (k, l);
        }
    }
    assert_eq!(u.film_sum, sum);
    assert_eq!(u.mean, sum / 136.0);
    assert_eq!(u.brightest, Some(brightest));
    let (image, _) = crate::render_image(&scene, &o, &RenderControl::default()).unwrap();
    assert_eq!(e.pixel_f32(), image.get(10, 9), "the pixel is still the render's");
    let text = e.to_string();
    let (k, l) = brightest;
    let line = |c: Rgb| format!("({:.4}, {:.4}, {:.4})", c.x, c.y, c.z);
    let expected = format!(
        "\nsamples 64 to 199: traced, not recorded (an explanation records the first 64 of a pixel; --sample K shows any one)\n  \
         136 samples, mean film value {}; the brightest is sample {k}, film value {}\n",
        line(u.mean),
        line(l)
    );
    assert!(text.contains(&expected), "{text}");
    assert!(text.ends_with(&format!("pixel = sum of the 200 samples' film values / 200 = {}\n", line(Rgb::from(e.pixel.map(f64::from))))));
    let json = e.to_json();
    assert_eq!(json["samples"].as_array().unwrap().len(), 64);
    assert_eq!(json["unrecorded"]["count"], 136);
    assert_eq!(json["unrecorded"]["brightest"]["index"], k);
    // At 64 samples or fewer, every sample is recorded and nothing summarised.
    assert_eq!(explain(&scene, &options("path", 64), 10, 9, None).unwrap().unrecorded, None);
    assert_eq!(explain(&scene, &o, 10, 9, Some(150)).unwrap().unrecorded, None, "one sample asked for");
}

#[test]
fn a_cancelled_plan_stops() {
    let scene = scene();
    let cancel = Arc::new(AtomicBool::new(true));
    let err = plan_cancellable(&scene, &options("path", 1 << 20), 10, 9, Some(cancel)).err().unwrap();
    assert_eq!(err.to_string(), Error::Render("cancelled".into()).to_string());
    let cancel = Arc::new(AtomicBool::new(false));
    let plan = plan_cancellable(&scene, &options("path", 8), 10, 9, Some(cancel.clone())).unwrap();
    cancel.store(true, Ordering::Relaxed);
    assert!(plan.explain(&scene, None).is_err(), "the plan's explanation stops too");
}

#[test]
fn recording_stops_at_the_memory_allowance() {
    // See: issue 30 (the recorder draws on the memory budget; one Whitted
    // sample of a deep glass scene can hold millions of rays).
    let scene = scene();
    let o = options("path", 20);
    let plan = plan(&scene, &o, 10, 9).unwrap();
    let full = plan.explain(&scene, None).unwrap();
    assert_eq!((full.samples.len(), full.unrecorded), (20, None));
    // Allowances from 1 KiB up, doubling: each records a prefix of the samples,
    // the same records as with room for all, and summarises the rest.
    let mut stopped_part_way = 0;
    let mut last = 0;
    for allowance in (10..24).map(|b| 1usize << b) {
        let e = plan.explain_within(&scene, None, allowance).unwrap();
        let m = e.samples.len();
        assert!(m >= last, "a larger allowance records no fewer samples");
        last = m;
        assert_eq!(e.samples[..], full.samples[..m], "allowance {allowance}");
        assert_eq!(e.pixel, full.pixel, "the pixel is still the render's");
        if m == 20 {
            assert_eq!(e.unrecorded, None);
            continue;
        }
        let u = e.unrecorded.unwrap();
        assert_eq!((u.first, u.count, u.why), (m as u32, 20 - m as u32, Unrecorded::Memory { allowance }));
        let rest = full.samples[m..].iter().fold(Rgb::ZERO, |s, x| s + x.film_value.unwrap());
        assert_eq!(u.film_sum, rest);
        stopped_part_way += usize::from(m > 0);
        let text = e.to_string();
        let mib = allowance as f64 / (1 << 20) as f64;
        let line = format!(
            "samples {m} to 19: traced, not recorded: their records would pass the explanation's memory allowance of {mib:.1} MiB \
             (a larger memory budget records more)"
        );
        assert!(text.contains(&line), "{text}");
        assert_eq!(e.to_json()["unrecorded"]["why"]["memory_allowance"], allowance);
    }
    assert_eq!(last, 20, "16 MiB holds them all");
    assert!(stopped_part_way > 0, "some allowance stops after some samples");
    // Nothing fits: a sample asked for alone is summarised, not recorded.
    let alone = plan.explain_within(&scene, Some(7), 0).unwrap();
    assert!(alone.samples.is_empty());
    let u = alone.unrecorded.unwrap();
    assert_eq!((u.first, u.count, u.why), (7, 1, Unrecorded::Memory { allowance: 0 }));
    assert_eq!(u.film_sum, full.samples[7].film_value.unwrap());
}
