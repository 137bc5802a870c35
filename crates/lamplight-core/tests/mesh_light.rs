//! Emitting triangle meshes are area lights: the irradiance under an emissive
//! mesh square matches the closed form, and a mesh quad light renders the same
//! image as the analytic quad light of the same size and radiance.

use std::sync::Arc;

use lamplight_core::integrators::{self, PathTracer, RayCounts};
use lamplight_core::prelude::*;
use lamplight_core::ray::Ray;
use lamplight_core::sampling::PixelSampler;

fn white() -> Material {
    Material { color: Texture::Constant(Rgb::ONE), ka: Rgb::ZERO, kd: Rgb::ONE, ..Material::default() }
}

fn emitter(radiance: f64) -> Material {
    Material { kd: Rgb::ZERO, ka: Rgb::ZERO, emission: Rgb::splat(radiance), ..Material::default() }
}

/// The square `|x|, |z| <= a` at height 0, as two triangles facing -y.
fn square_mesh(a: f64) -> TriangleMesh {
    let p = vec![Vec3::new(-a, 0.0, -a), Vec3::new(a, 0.0, -a), Vec3::new(a, 0.0, a), Vec3::new(-a, 0.0, a)];
    TriangleMesh::new(p, vec![[0, 1, 2], [0, 2, 3]], None).unwrap()
}

fn dark_builder(camera: Perspective) -> SceneBuilder {
    let mut b = SceneBuilder::new(camera);
    b.settings.ambient = Rgb::ZERO;
    b.settings.background = Rgb::ZERO;
    b
}

#[test]
fn irradiance_under_an_emissive_mesh_square_matches_the_form_factor() {
    // A square of side 2a at height h above a point, facing it, of radiance L: the
    // point's irradiance is E = pi L F with the form factor of four corner rectangles,
    // F = 4 * 1/(2 pi) * 2 * A / sqrt(1 + A^2) * atan(A / sqrt(1 + A^2)), A = a / h.
    // A white Lambertian floor there reflects L_o = E / pi = L F. The mesh is placed by
    // a rotation about the vertical and a translation (an instance).
    let (a, h, radiance) = (1.0, 1.0, 3.0);
    let camera = Perspective::look_at(Vec3::new(0.0, 0.5, 0.0), Vec3::ZERO, Vec3::Z, Fov::VerticalDeg(10.0)).unwrap();
    let mut b = dark_builder(camera);
    let floor = b.material(white()).unwrap();
    let lamp = b.material(emitter(radiance)).unwrap();
    b.object(Rectangle::horizontal(0.0, -20.0, 20.0, -20.0, 20.0).unwrap(), floor).unwrap();
    let placed = Mat4::from_translation(Vec3::new(0.0, h, 0.0)) * Mat4::from_rotation_y(0.5);
    b.shared_object(Arc::new(Instance::new(Arc::new(square_mesh(a)), placed).unwrap()), lamp).unwrap();
    let scene = b.build().unwrap();
    let lights = scene.light_set();
    assert_eq!(lights.area.len(), 1, "the mesh is an area light");
    assert!((lights.area[0].area() - 4.0 * a * a).abs() < 1e-12);

    let big_a: f64 = a / h;
    let s = (1.0 + big_a * big_a).sqrt();
    let form_factor = 4.0 / std::f64::consts::PI * big_a / s * (big_a / s).atan();
    let expected = radiance * form_factor;
    let tracer = PathTracer::new(&scene, 2);
    let ray = Ray::new(Vec3::new(0.0, 0.5, 0.0), -Vec3::Y);
    let mut counts = RayCounts::default();
    let n = 1 << 14;
    let sum: f64 = (0..n).map(|i| tracer.li(&scene, &ray, &mut PixelSampler::new(9, 0, i), &mut counts).x).sum();
    let estimate = sum / n as f64;
    eprintln!("mesh square: L_o {estimate:.5}, closed form {expected:.5}");
    assert!((estimate / expected - 1.0).abs() < 2e-3, "{estimate} vs {expected}");
}

/// A floor, a diffuse ball and a square light of side 1 at height 2, facing down,
/// built as an analytic rectangle or as a two-triangle mesh.
fn lit_room(mesh_light: bool) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 1.5, 4.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y, Fov::VerticalDeg(50.0)).unwrap();
    let mut b = dark_builder(camera);
    let floor = b.material(Material { kd: Rgb::splat(0.8), ..white() }).unwrap();
    let ball = b.material(Material::plastic(Rgb::new(0.8, 0.4, 0.2), 0.0, 0.8, 0.2, 20.0)).unwrap();
    let lamp = b.material(emitter(8.0)).unwrap();
    b.object(Rectangle::horizontal(0.0, -3.0, 3.0, -3.0, 3.0).unwrap(), floor).unwrap();
    b.object(Sphere::new(Vec3::new(0.3, 0.5, 0.0), 0.5).unwrap(), ball).unwrap();
    if mesh_light {
        let placed = Mat4::from_translation(Vec3::new(0.0, 2.0, 0.0));
        b.shared_object(Arc::new(Instance::new(Arc::new(square_mesh(0.5)), placed).unwrap()), lamp).unwrap();
    } else {
        // Edges +x and +z: normal +x cross +z = -y.
        b.object(Rectangle::new(Vec3::new(-0.5, 2.0, -0.5), Vec3::X, Vec3::Z).unwrap(), lamp).unwrap();
    }
    b.settings.max_depth = 5;
    b.build().unwrap()
}

#[test]
fn mesh_quad_light_renders_like_the_analytic_quad_light() {
    // Same geometry and radiance, sampled differently (two triangles by area
    // against the rectangle's own parameterization): the images agree within their
    // noise. Per pixel |a - b| <= 5 sigma (sigma^2 = var_a + var_b, the variances of
    // the pixel means), and the image means within 0.5 %.
    let options =
        RenderOptions { width: 16, height: 16, spp: 1024, integrator: integrators::find("path").unwrap(), ..RenderOptions::default() };
    let (a, _) = render(&lit_room(false), &options, &RenderControl::default()).unwrap();
    let (b, _) = render(&lit_room(true), &options, &RenderControl::default()).unwrap();
    let (mean_a, mean_b) = (a.mean(), b.mean());
    let (var_a, var_b) = (a.variance(), b.variance());
    let (mut sum_a, mut sum_b, mut worst) = (0.0, 0.0, 0.0f64);
    for i in 0..mean_a.pixels.len() {
        for c in 0..3 {
            let (pa, pb) = (mean_a.pixels[i][c] as f64, mean_b.pixels[i][c] as f64);
            let sigma = (var_a.pixels[i][c] as f64 + var_b.pixels[i][c] as f64).sqrt();
            sum_a += pa;
            sum_b += pb;
            if sigma > 0.0 {
                worst = worst.max((pa - pb).abs() / sigma);
            } else {
                assert_eq!(pa, pb, "pixel {i}: noiseless pixels must match");
            }
        }
    }
    let relative = (sum_b / sum_a - 1.0).abs();
    eprintln!("mesh vs analytic quad light: worst pixel {worst:.2} sigma, image means differ by {:.3} %", relative * 100.0);
    assert!(worst < 5.0, "worst pixel differs by {worst} sigma");
    assert!(relative < 5e-3, "image means differ by {relative}");
    assert!(sum_a > 1.0, "the room is lit");
}
