//! The denoiser's feature layers, `albedo` and `normal`, and the radiance it
//! must leave alone, `emitted`, from a pass of their own.
//!
//! A denoiser (Open Image Denoise's `RT` filter) keeps edges and textures
//! sharp when it is given, beside the noisy image, the colour of the surfaces
//! and their normals. Computing them inside the integrators would add work to
//! their inner loops, which are the program's speed; this pass is separate and
//! cheap instead (no light, no shadow rays): for every sample of a finished
//! render it takes the very camera ray the integrator traced
//! ([`Integrator::camera_sample`]: same position, lens point, footprint and
//! filter weight), so the layers are anti-aliased as the image is, and
//! follows it as Open Image Denoise's documentation recommends ("Albedos",
//! "Normals" in its API manual):
//!
//! - through perfect specular (delta) surfaces, mirrors and smooth glass, to
//!   the first diffuse or glossy hit, each bounce chosen by the BSDF's own
//!   sampling and weighted by its reflectance or transmittance, so that the
//!   average over a pixel's samples is the Fresnel blend of what is seen in
//!   the reflection and through the glass;
//! - at that hit, `albedo` is the BSDF's directional-hemispherical reflectance
//!   `ρ(wo) = ∫ f cos dwi`, exact for a Lambertian surface (its colour) and
//!   estimated from [`REFLECTANCE_SAMPLES`] stratified BSDF samples otherwise;
//!   `normal` is the world-space shading normal (normal maps included), on
//!   the side the ray arrived from;
//! - a ray that leaves the scene gives albedo 0 and normal 0; a surface that
//!   only emits gives albedo 0 and its normal; a delta chain that reaches the
//!   depth limit ends with the last delta surface's reflectance and normal.
//!
//! `emitted` is what the integrators add where the camera ray itself ends: an
//! emitter's emission seen directly, or the sky (environment or background)
//! where the ray leaves the scene; 0 where it hits anything else. It is the
//! very value both integrators add for that sample at depth 1 (same ray, same
//! shading footprint), so `image - emitted` is the rest of the light, the part
//! with Monte Carlo noise. The denoiser filters only that and adds `emitted`
//! back (the split of Cycles' `path_radiance_split_denoising`, whose "clean"
//! part was emission and background at the first bounce): `emitted` has no
//! noise but the pixel's coverage, which stratification keeps small, while a
//! denoiser moves the pixels at a light's edge, whose radiance is many times
//! that of their neighbours (`BENCHMARKS.md`, "Denoising").
//!
//! Each pixel averages its samples in index order (the film's count for it:
//! adaptive renders too) with the filter weight, the samples' random numbers
//! are seeded by (seed, pixel, sample), so the layers are the same bytes for
//! any number of threads. Albedo is clamped to `[0, 1]` and the normal to
//! `[-1, 1]`, the ranges the denoiser takes.

use rayon::prelude::*;

use super::{integrator_for, thread_pool, view_of, RenderOptions};
use crate::bsdfs::Bsdf;
use crate::film::{Film, Image};
use crate::integrators::{CameraSample, Integrator, Schedule, View};
use crate::math::{Rgb, Vec3};
use crate::ray::offset_origin;
use crate::sampling::Rng;
use crate::scene::Scene;
use crate::Error;

/// BSDF samples that estimate the reflectance of a surface that is not one
/// Lambertian lobe (whose reflectance is its colour, taken as it is). Each
/// pixel averages them over its samples too. Two denoise DamagedHelmet (PBR,
/// textured) as well as eight (displayed RMSE at 128x128, 1/4/16 spp: 0.0333,
/// 0.0255, 0.0183 against 0.0332, 0.0255, 0.0183) and cut the pass's time there
/// by a third (BENCHMARKS.md, "Denoising").
pub const REFLECTANCE_SAMPLES: u32 = 2;

/// Mixed into the render seed, so that the feature pass's random numbers are
/// not those the integrator drew for the same sample.
const FEATURE_SEED: u64 = 0xA1BE_D0C0_FEA7_0125;

/// The feature layers of a render, of the film's size.
#[derive(Clone, Debug, PartialEq)]
pub struct Features {
    /// Reflectance at the first non-specular hit, each channel in `[0, 1]`.
    pub albedo: Image,
    /// World-space shading normal there, averaged (not renormalized), in `[-1, 1]`.
    pub normal: Image,
    /// Radiance of the emitters and the sky the camera rays see directly
    /// (see the module doc): the part of the image a denoiser leaves alone.
    pub emitted: Image,
}

/// What one camera sample gives each feature layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleFeatures {
    /// Reflectance at the first non-specular hit.
    pub albedo: Rgb,
    /// Shading normal there.
    pub normal: Vec3,
    /// Radiance the integrators add where the camera ray ends on an emitter or leaves the scene.
    pub emitted: Rgb,
}

impl SampleFeatures {
    const NOTHING: SampleFeatures = SampleFeatures { albedo: Rgb::ZERO, normal: Vec3::ZERO, emitted: Rgb::ZERO };
}

/// The feature layers of the render of `scene` with `options` that made
/// `film`: per pixel, the film's own sample count of the same camera rays.
/// Errors as [`crate::render()`] does on bad options.
pub fn render_features(scene: &Scene, options: &RenderOptions, film: &Film) -> Result<Features, Error> {
    let integrator = integrator_for(scene, options)?;
    let max_depth = options.max_depth.unwrap_or(scene.settings.max_depth);
    let window = options.pixel_window();
    if (film.width(), film.height()) != (window.width, window.height) {
        return Err(Error::invalid("features", "the film is not of the render's window"));
    }
    let sized = scene.settings.camera.for_image(options.width, options.height);
    let camera = sized.as_deref().unwrap_or(scene.settings.camera.as_ref());
    let view = view_of(scene, camera, options);
    let one_pass = integrator.schedule() == Schedule::OnePass;
    let pixels = window.width as usize * window.height as usize;
    let mut albedo = Image::new(window.width, window.height);
    let mut normal = Image::new(window.width, window.height);
    let mut emitted = Image::new(window.width, window.height);
    let pool = thread_pool(options.threads)?;
    let row = window.width as usize;
    let rows = albedo.pixels.par_chunks_mut(row).zip(normal.pixels.par_chunks_mut(row)).zip(emitted.pixels.par_chunks_mut(row));
    pool.install(|| {
        rows.enumerate().for_each(|(j, ((albedo, normal), emitted))| {
            let fy = j as u32;
            for (i, ((a, n), e)) in albedo.iter_mut().zip(normal.iter_mut()).zip(emitted.iter_mut()).enumerate() {
                let fx = i as u32;
                let count = film.samples_at(fx, fy);
                // A one-pass integrator stratifies over the pixel's own count:
                // adaptive anti-aliasing renders a refined pixel as a render of
                // that many samples ([`crate::Antialias`]).
                let view = if one_pass { View { spp: count.max(1), ..view } } else { view };
                let (x, y) = (window.x0 + fx, window.y0 + fy);
                let sum = pixel_features(integrator.as_ref(), &view, max_depth, (x, y), count);
                let inv = if count > 0 { 1.0 / count as f64 } else { 0.0 };
                *a = (sum.albedo * inv).clamp(Rgb::ZERO, Rgb::ONE).as_vec3().to_array();
                *n = (sum.normal * inv).clamp(Vec3::splat(-1.0), Vec3::ONE).as_vec3().to_array();
                // The film's mean is its sum divided by its count in f64, then f32: the same here.
                *e = (sum.emitted / count.max(1) as f64).as_vec3().to_array();
            }
        });
    });
    debug_assert_eq!(albedo.pixels.len(), pixels);
    Ok(Features { albedo, normal, emitted })
}

/// The sums over samples `0..count` of pixel `(x, y)` of each feature, each
/// sample weighted by its filter weight; `emitted` kept as the film keeps a
/// sample ([`crate::film::kept`]: the render's clamp, nothing non-finite).
fn pixel_features(integrator: &dyn Integrator, view: &View, max_depth: u32, (x, y): (u32, u32), count: u32) -> SampleFeatures {
    let mut sum = SampleFeatures::NOTHING;
    for index in 0..count {
        let camera = integrator.camera_sample(view, x, y, index);
        let mut rng = Rng::for_sample(view.seed ^ FEATURE_SEED, view.pixel_index(x, y), index as u64);
        let f = sample_features(view.scene, &camera, max_depth, &mut rng);
        sum.albedo += f.albedo * camera.weight;
        sum.normal += f.normal * camera.weight;
        sum.emitted += crate::film::kept(f.emitted * camera.weight, view.clamp).unwrap_or(Rgb::ZERO);
    }
    sum
}

/// Albedo and normal of one camera sample, delta surfaces followed to the
/// first diffuse or glossy hit, and the emission or sky its camera ray sees
/// (see the module doc).
pub fn sample_features(scene: &Scene, camera: &CameraSample, max_depth: u32, rng: &mut Rng) -> SampleFeatures {
    let mut ray = camera.ray;
    let mut throughput = Rgb::ONE;
    let mut emitted = Rgb::ZERO;
    for depth in 1..=max_depth.max(1) {
        // Mitsuba's `hide_emitters`, as the integrators see it.
        let hidden = depth == 1 && scene.settings.hide_emitters;
        let found = if hidden { scene.first_camera_hit(&ray) } else { scene.first_intersect(&ray, f64::INFINITY) };
        let Some(mut hit) = found else {
            // The sky both integrators add for a camera ray that leaves the scene.
            if depth == 1 && !hidden {
                emitted = scene.settings.environment.as_ref().map_or(scene.settings.background, |env| env.radiance(ray.dir));
            }
            return SampleFeatures { emitted, ..SampleFeatures::NOTHING };
        };
        // The footprint the integrators filter textures over (the path tracer's rule).
        let footprint = if depth == 1 {
            camera.cone.width + camera.cone.spread * hit.t
        } else {
            camera.cone.width + camera.cone.spread * (hit.point - camera.ray.origin).length()
        };
        let material = &*scene.shade(&mut hit, -ray.dir, footprint);
        let emits = material.emits_towards(hit.front_face);
        if depth == 1 && emits {
            // The emission both integrators add at the camera ray's hit (weight 1).
            emitted = material.emission;
        }
        let bsdf: &Bsdf = &scene.bsdf(&hit, material);
        let normal = hit.normal;
        // An emitter's pixels are its emission, not reflected light: albedo 0
        // marks them, so the denoiser keeps the edge of a light against a
        // ceiling of its own colour and normal.
        if bsdf.is_black() || emits {
            return SampleFeatures { albedo: Rgb::ZERO, normal, emitted };
        }
        let frame = scene.shading_frame(&hit, bsdf);
        let wo = frame.to_local(-ray.dir);
        if bsdf.has_smooth_part() || depth == max_depth {
            return SampleFeatures { albedo: throughput * reflectance(bsdf, wo, rng), normal, emitted };
        }
        let Some(s) = bsdf.sample(wo, rng.uniform(), (rng.uniform(), rng.uniform())) else {
            return SampleFeatures { albedo: Rgb::ZERO, normal, emitted };
        };
        // The power the bounce carries: a refraction's weight holds the
        // radiance factor 1 / eta^2, which is not reflectance.
        throughput *= s.weight * (s.eta * s.eta);
        let wi = frame.to_world(s.wi);
        ray = hit.spawn(offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error), wi);
    }
    SampleFeatures { emitted, ..SampleFeatures::NOTHING }
}

/// The directional-hemispherical reflectance of `bsdf` seen from `wo`
/// (local): the BSDF sample weight `f |cos| / pdf` averaged over
/// [`REFLECTANCE_SAMPLES`] stratified samples (exactly the colour for one
/// Lambertian lobe, whose every sample weight is its colour).
fn reflectance(bsdf: &Bsdf, wo: Vec3, rng: &mut Rng) -> Rgb {
    if let [crate::bsdfs::Lobe::Diffuse(crate::bsdfs::Lambertian(albedo))] = bsdf.lobes() {
        return *albedo;
    }
    let mut sum = Rgb::ZERO;
    let n = REFLECTANCE_SAMPLES;
    for i in 0..n {
        let u_lobe = (i as f64 + rng.uniform()) / n as f64;
        if let Some(s) = bsdf.sample(wo, u_lobe, (rng.uniform(), rng.uniform())) {
            sum += s.weight * (s.eta * s.eta);
        }
    }
    sum / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::materials::Material;
    use crate::ray::Ray;
    use crate::shapes::Plane;
    use crate::{RenderControl, SceneBuilder};

    /// A plane `z = 0` of colour `color` filling the view of a camera above it, looking down.
    fn plane_scene(color: Rgb) -> Scene {
        let camera = Perspective::look_at(Vec3::new(0.3, -0.2, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let m = b.material(Material::plastic(color, 0.0, 1.0, 0.0, 1.0)).unwrap();
        b.object(Plane::new(Vec3::ZERO, Vec3::Z).unwrap(), m).unwrap();
        b.build().unwrap()
    }

    #[test]
    fn a_diffuse_plane_has_its_colour_as_albedo_and_its_normal() {
        let color = Rgb::new(0.8, 0.25, 0.05);
        let scene = plane_scene(color);
        for integrator in ["whitted", "path"] {
            let options = RenderOptions { width: 9, height: 7, spp: 4, integrator: integrator.parse().unwrap(), ..Default::default() };
            let (film, _) = crate::render(&scene, &options, &RenderControl::default()).unwrap();
            let f = render_features(&scene, &options, &film).unwrap();
            for (a, n) in f.albedo.pixels.iter().zip(&f.normal.pixels) {
                let expected = [0.8f32, 0.25, 0.05];
                for c in 0..3 {
                    assert!((a[c] - expected[c]).abs() < 1e-6, "{integrator}: albedo {a:?}");
                }
                assert_eq!(*n, [0.0, 0.0, 1.0], "{integrator}: normal");
            }
        }
    }

    #[test]
    fn layers_are_the_same_bytes_for_any_number_of_threads() {
        // A glossy floor, a glass and a gold sphere: reflectance estimates and delta chains.
        let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(50.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let floor = b.material(Material::plastic(Rgb::new(0.7, 0.6, 0.5), 0.1, 0.7, 0.3, 20.0)).unwrap();
        b.object(Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y).unwrap(), floor).unwrap();
        let glass = b.material(Material::glass(1.5, 0.0, 1.0)).unwrap();
        b.object(crate::shapes::Sphere::new(Vec3::new(-0.6, 0.0, 0.0), 0.6).unwrap(), glass).unwrap();
        let gold = b.material(Material::metal(crate::materials::Metal::Gold, 0.0, 1.0)).unwrap();
        b.object(crate::shapes::Sphere::new(Vec3::new(0.7, -0.3, 0.3), 0.5).unwrap(), gold).unwrap();
        b.light(crate::lights::PointLight::new(Vec3::new(1.0, 3.0, 2.0), Rgb::splat(10.0)).unwrap());
        let scene = b.build().unwrap();
        for integrator in ["whitted", "path"] {
            let options = RenderOptions { width: 24, height: 20, spp: 3, integrator: integrator.parse().unwrap(), ..Default::default() };
            let features = |threads: usize| {
                let options = RenderOptions { threads, ..options.clone() };
                let (film, _) = crate::render(&scene, &options, &RenderControl::default()).unwrap();
                render_features(&scene, &options, &film).unwrap()
            };
            let one = features(1);
            assert_eq!(one, features(3), "{integrator}");
            assert!(one.albedo.pixels.iter().any(|p| p[0] > 0.0), "{integrator}: something is seen");
        }
        // Adaptive renders: each pixel averages its own count of samples.
        let adaptive = [
            ("whitted", crate::Adaptive::Antialias(crate::Antialias::default()), 1),
            ("path", crate::Adaptive::NoiseThreshold(crate::NoiseThreshold { threshold: 0.2, min_samples: 4 }), 32),
        ];
        for (integrator, adaptive, spp) in adaptive {
            let options = RenderOptions {
                width: 24,
                height: 20,
                spp,
                adaptive: Some(adaptive),
                integrator: integrator.parse().unwrap(),
                ..Default::default()
            };
            let features = |threads: usize| {
                let options = RenderOptions { threads, ..options.clone() };
                let (film, _) = crate::render(&scene, &options, &RenderControl::default()).unwrap();
                assert!(film.is_adaptive(), "{integrator}: pixels took different counts");
                render_features(&scene, &options, &film).unwrap()
            };
            assert_eq!(features(1), features(2), "{integrator}, adaptive");
        }
    }

    /// `emitted` is, sample for sample, what the integrators add where the
    /// camera ray ends. A path tracer of depth 1 sees emitters and sky only:
    /// its render is `emitted` bit for bit (a lamp, a lit grey floor, the sky).
    /// The Whitted integrator's render of the same scene with a black floor
    /// (no ambient, nothing reflected) is too.
    #[test]
    fn emitted_is_what_the_camera_rays_see_of_emitters_and_sky() {
        let scene = |floor: Rgb| {
            let camera = Perspective::look_at(Vec3::new(0.0, 0.5, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(60.0)).unwrap();
            let mut b = SceneBuilder::new(camera);
            b.settings.background = Rgb::new(0.2, 0.3, 0.9);
            let floor = b.material(Material::plastic(floor, 0.0, 1.0, 0.0, 1.0)).unwrap();
            b.object(Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y).unwrap(), floor).unwrap();
            let mut lamp = Material::plastic(Rgb::ZERO, 0.0, 0.0, 0.0, 1.0);
            lamp.emission = Rgb::new(18.0, 12.0, 6.0);
            let lamp = b.material(lamp).unwrap();
            b.object(crate::shapes::Sphere::new(Vec3::new(0.3, 0.2, 0.0), 0.7).unwrap(), lamp).unwrap();
            b.build().unwrap()
        };
        for (integrator, floor, max_depth) in [("path", Rgb::splat(0.6), Some(1)), ("whitted", Rgb::ZERO, None)] {
            let scene = scene(floor);
            let options = RenderOptions { width: 16, height: 12, spp: 5, integrator: integrator.parse().unwrap(), ..Default::default() };
            let (film, _) = crate::render(&scene, &options, &RenderControl::default()).unwrap();
            let emitted = render_features(&scene, &options, &film).unwrap().emitted;
            let seeing = RenderOptions { max_depth, ..options.clone() };
            let (seen, _) = crate::render(&scene, &seeing, &RenderControl::default()).unwrap();
            assert_eq!(emitted, seen.mean(), "{integrator}");
            let lamp = emitted.pixels.iter().filter(|p| **p == [18.0, 12.0, 6.0]).count();
            let sky = emitted.pixels.iter().filter(|p| **p == [0.2, 0.3, 0.9]).count();
            let floor = emitted.pixels.iter().filter(|p| **p == [0.0; 3]).count();
            assert!(lamp > 0 && sky > 0 && floor > 0, "{integrator}: lamp {lamp}, sky {sky}, floor {floor} pixels");
        }
    }

    /// Records the camera ray an integrator traces (the first ray of a sample).
    #[derive(Default)]
    struct FirstRay(Option<Ray>);

    impl crate::integrators::trace::WhittedTrace for FirstRay {
        fn ray(&mut self, ray: &Ray, _weight: Rgb, depth: u32) {
            if depth == 1 {
                self.0.get_or_insert(*ray);
            }
        }
    }

    impl crate::integrators::trace::PathTrace for FirstRay {
        fn segment(&mut self, depth: u32, ray: &Ray, _beta: Rgb) {
            if depth == 1 {
                self.0.get_or_insert(*ray);
            }
        }
    }

    #[test]
    fn the_pass_follows_the_very_rays_the_integrators_trace() {
        let scene = plane_scene(Rgb::splat(0.5));
        for (integrator, filter) in [("whitted", crate::film::Filter::Box), ("path", "lanczos".parse::<crate::film::Filter>().unwrap())] {
            for spp in [1, 5] {
                let options =
                    RenderOptions { width: 7, height: 5, spp, filter, integrator: integrator.parse().unwrap(), ..Default::default() };
                let built = integrator_for(&scene, &options).unwrap();
                let view = view_of(&scene, scene.settings.camera.as_ref(), &options);
                for (x, y, index) in [(0, 0, 0), (3, 2, spp - 1), (6, 4, spp / 2)] {
                    let mut first = FirstRay::default();
                    built.sample_traced(&view, x, y, index, &mut Default::default(), &mut first);
                    assert_eq!(Some(built.camera_sample(&view, x, y, index).ray), first.0, "{integrator}, {spp} spp, ({x}, {y}) #{index}");
                }
            }
        }
    }
}
