//! The lanes against the one-sample loop: the same sums, bit for bit, and the
//! same ray counts, row by row.

use super::*;
use crate::camera::{Fov, Perspective};
use crate::integrators::{sample_row_one_by_one, Integrator};
use crate::lights::PointLight;
use crate::materials::{Material, Texture};
use crate::math::{Mat4, Vec3};
use crate::scene::{Scene, SceneBuilder};
use crate::shapes::{Cuboid, Rectangle};

fn diffuse(c: Rgb) -> Material {
    Material { color: Texture::Constant(c), ka: Rgb::ZERO, kd: Rgb::ONE, ..Material::default() }
}

/// A Cornell box (its tall box standing exactly on the floor, so that some
/// rays tie), and in `variant` 1 a second emitter and a point light, in
/// variant 2 a glass box (a delta BSDF, and shadows that glass lets through),
/// in variant 3 a light that emits from both sides, the back wall turned
/// inside out and Russian roulette from the second segment. Variants 0 and
/// 3 are [`Diffuse`]'s kind of scene, 1 and 2 are not.
fn cornell(variant: u32) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y, Fov::SmallerSideDeg(39.3077)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let white = b.material(diffuse(Rgb::new(0.885809, 0.698859, 0.666422))).unwrap();
    let green = b.material(diffuse(Rgb::new(0.105421, 0.37798, 0.076425))).unwrap();
    let red = b.material(diffuse(Rgb::new(0.570068, 0.0430135, 0.0443706))).unwrap();
    let light =
        b.material(Material { emission: Rgb::new(18.387, 13.9873, 6.75357), two_sided: variant == 3, ..diffuse(Rgb::splat(0.8)) }).unwrap();
    if variant == 3 {
        b.settings.rr_depth = 2;
    }
    let rect = |m: Mat4| {
        let corner = m.transform_point3(Vec3::new(-1.0, -1.0, 0.0));
        Rectangle::new(corner, m.transform_vector3(Vec3::new(2.0, 0.0, 0.0)), m.transform_vector3(Vec3::new(0.0, 2.0, 0.0))).unwrap()
    };
    let t = |x: f64, y: f64, z: f64| Mat4::from_translation(Vec3::new(x, y, z));
    let rx = |deg: f64| Mat4::from_rotation_x(deg.to_radians());
    let ry = |deg: f64| Mat4::from_rotation_y(deg.to_radians());
    b.object(rect(t(0.0, 0.99, 0.01) * rx(90.0) * Mat4::from_scale(Vec3::new(0.23, 0.19, 0.19))), light).unwrap();
    b.object(rect(t(0.0, -1.0, 0.0) * rx(-90.0)), white).unwrap();
    b.object(rect(t(0.0, 1.0, 0.0) * rx(90.0)), white).unwrap();
    let back = b.object(rect(t(0.0, 0.0, -1.0)), white).unwrap();
    if variant == 3 {
        b.reverse_orientation(back);
    }
    b.object(rect(t(1.0, 0.0, 0.0) * ry(-90.0)), green).unwrap();
    b.object(rect(t(-1.0, 0.0, 0.0) * ry(90.0)), red).unwrap();
    b.object(Cuboid::new(-Vec3::ONE, Vec3::ONE, t(0.335, -0.7, 0.38) * ry(-17.0) * Mat4::from_scale(Vec3::splat(0.3))).unwrap(), white)
        .unwrap();
    let tall = if variant == 2 { b.material(Material::glass(1.5, 0.8, 300.0)).unwrap() } else { white };
    let tall_box = t(-0.33, -0.39, -0.28) * ry(18.25) * Mat4::from_scale(Vec3::new(0.3, 0.61, 0.3));
    b.object(Cuboid::new(-Vec3::ONE, Vec3::ONE, tall_box).unwrap(), tall).unwrap();
    if variant == 1 {
        b.object(rect(t(-0.99, 0.3, 0.0) * ry(90.0) * Mat4::from_scale(Vec3::splat(0.2))), light).unwrap();
        b.light(PointLight::new(Vec3::new(0.4, 0.8, 0.6), Rgb::splat(0.6)).unwrap());
    }
    b.build().unwrap()
}

#[test]
fn lanes_add_the_same_sums_as_one_sample_at_a_time() {
    if !crate::cpu::avx2_features() {
        eprintln!("skipped: this CPU lacks AVX2, and the lanes run only there");
        return;
    }
    for variant in 0..4 {
        let scene = cornell(variant);
        let tracer = PathTracer::new(&scene, 8);
        assert_eq!(Diffuse::of(&tracer, &scene).is_some(), variant == 0 || variant == 3, "variant {variant}");
        let camera = scene.settings.camera.for_image(24, 16).unwrap();
        for clamp in [None, Some(0.5)] {
            let view = View::new(&scene, &*camera, 24, 16, 12, 7).with_clamp(clamp);
            assert!(tracer.lanes_fit(&view), "variant {variant}: the lanes should run");
            for y in 0..16 {
                for (x0, width, samples) in [(0, 24, 0..6), (3, 9, 6..12), (20, 4, 5..6)] {
                    let (mut lanes, mut one) = (RayCounts::default(), RayCounts::default());
                    let mut sums = vec![PixelSum::default(); width];
                    let mut expected = sums.clone();
                    let dropped = tracer.sample_row(&view, (x0, y), samples.clone(), &mut lanes, &mut sums);
                    let expected_dropped = sample_row_one_by_one(&tracer, &view, (x0, y), samples, &mut one, &mut expected);
                    assert_eq!(dropped, expected_dropped);
                    assert_eq!((lanes.camera, lanes.secondary, lanes.shadow), (one.camera, one.secondary, one.shadow));
                    let bits = |s: &[PixelSum]| {
                        s.iter().map(|p| (p.sum.to_array().map(f64::to_bits), p.sum_sq.to_array().map(f64::to_bits))).collect::<Vec<_>>()
                    };
                    assert_eq!(bits(&sums), bits(&expected), "variant {variant}, clamp {clamp:?}, row {y} from {x0}");
                }
            }
        }
    }
}

/// Rows whose values would not fit the lanes' buffer at once (many pixels
/// of hundreds of samples, or one pixel of thousands) are taken in parts,
/// with the same sums.
#[test]
fn long_rows_add_the_same_sums() {
    if !crate::cpu::avx2_features() {
        eprintln!("skipped: this CPU lacks AVX2, and the lanes run only there");
        return;
    }
    for variant in [0, 2] {
        let scene = cornell(variant);
        let tracer = PathTracer::new(&scene, 8);
        let camera = scene.settings.camera.for_image(24, 16).unwrap();
        let view = View::new(&scene, &*camera, 24, 16, 8192, 3);
        for (x0, width, samples) in [(0, 24, 0..300), (5, 2, 100..(100 + 2 * MAX_VALUES as u32 + 7))] {
            let (mut lanes, mut one) = (RayCounts::default(), RayCounts::default());
            let mut sums = vec![PixelSum::default(); width];
            let mut expected = sums.clone();
            tracer.sample_row(&view, (x0, 9), samples.clone(), &mut lanes, &mut sums);
            sample_row_one_by_one(&tracer, &view, (x0, 9), samples, &mut one, &mut expected);
            assert_eq!((lanes.camera, lanes.secondary, lanes.shadow), (one.camera, one.secondary, one.shadow));
            assert_eq!(sums, expected, "variant {variant}, from {x0}");
        }
    }
}

/// Scenes the lanes do not cover keep the one-sample loop.
#[test]
fn other_scenes_keep_one_sample_at_a_time() {
    let mut scene = cornell(0);
    scene.settings.hide_emitters = true;
    let camera = scene.settings.camera.for_image(8, 8).unwrap();
    let tracer = PathTracer::new(&scene, 8);
    assert!(!tracer.lanes_fit(&View::new(&scene, &*camera, 8, 8, 4, 1)), "hide_emitters");
    let mut b = SceneBuilder::new(Perspective::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap());
    let m = b.material(Material::default()).unwrap();
    b.object(crate::shapes::Sphere::new(Vec3::ZERO, 1.0).unwrap(), m).unwrap();
    let spheres = b.build().unwrap();
    assert!(spheres.object_lanes().is_none(), "a sphere has no lane test yet");
}

/// Each compilation of the lanes this CPU can run (AVX-512, AVX2 with GFNI,
/// AVX2) adds the same sums as the one-sample loop: the dispatch picks one,
/// and the others would otherwise go untested here.
#[test]
fn every_compilation_adds_the_same_sums() {
    let compiled: [(&str, bool, RowFn); 3] = [
        ("avx512", crate::cpu::avx512_features(), |t, v, r, s, c, sums| unsafe { t.row_lanes_avx512(v, r, s, c, sums) }),
        ("render", crate::cpu::render_features(), |t, v, r, s, c, sums| unsafe { t.row_lanes_features(v, r, s, c, sums) }),
        ("avx2", crate::cpu::avx2_features(), |t, v, r, s, c, sums| unsafe { t.row_lanes_avx2(v, r, s, c, sums) }),
    ];
    for (name, available, row) in compiled {
        if !available {
            eprintln!("skipped the {name} compilation: this CPU lacks its features");
            continue;
        }
        for variant in 0..4 {
            let scene = cornell(variant);
            let tracer = PathTracer::new(&scene, 8);
            let camera = scene.settings.camera.for_image(24, 16).unwrap();
            let view = View::new(&scene, &*camera, 24, 16, 12, 7);
            for y in [0, 7, 15] {
                let (mut lanes, mut one) = (RayCounts::default(), RayCounts::default());
                let mut sums = vec![PixelSum::default(); 24];
                let mut expected = sums.clone();
                row(&tracer, &view, (0, y), 2..9, &mut lanes, &mut sums);
                sample_row_one_by_one(&tracer, &view, (0, y), 2..9, &mut one, &mut expected);
                assert_eq!((lanes.camera, lanes.secondary, lanes.shadow), (one.camera, one.secondary, one.shadow));
                assert_eq!(sums, expected, "{name}, variant {variant}, row {y}");
            }
        }
    }
}

/// A compilation of [`PathTracer::row_lanes`].
type RowFn = fn(&PathTracer, &View, (u32, u32), Range<u32>, &mut RayCounts, &mut [PixelSum]) -> u64;

/// The compilations' attributes name the feature lists of `cpu.rs` (the
/// attribute takes a literal).
#[test]
fn the_compilations_name_the_detected_features() {
    let source = include_str!("../lanes.rs");
    for (features, name) in [
        (crate::cpu::AVX512_FEATURES, "row_lanes_avx512"),
        (crate::cpu::RENDER_FEATURES, "row_lanes_features"),
        (crate::cpu::AVX2_FEATURES, "row_lanes_avx2"),
    ] {
        let attribute = format!("#[target_feature(enable = \"{features}\")]\n    unsafe fn {name}(");
        assert!(source.contains(&attribute), "{name} must be compiled for {features}");
    }
}
