//! The batch API's meaning, checked on both targets: distances whatever the
//! direction's length, object and triangle ids, misses, thread independence.

use std::sync::Arc;

use super::*;
use crate::camera::{Fov, Perspective};
use crate::materials::Material;
use crate::math::Rgb;
use crate::shapes::{Instance, Sphere, TriangleMesh};
use crate::{Scene, SceneBuilder};

/// The unit square in z = 0 as two triangles (the diagonal from (0,0) to (1,1)).
const SQUARE: ([[f32; 3]; 4], [[u32; 3]; 2]) =
    ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2], [0, 2, 3]]);

/// Object 0: a sphere of radius 1 at (0, 0, -5); object 1: the square moved by
/// (5, 0, 0) through an instance; object 2: the square itself.
fn scene() -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(30.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(Material::plastic(Rgb::splat(0.5), 0.1, 0.8, 0.0, 1.0)).unwrap();
    b.object(Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0).unwrap(), m).unwrap();
    let positions = SQUARE.0.iter().map(|p| Vec3::new(p[0].into(), p[1].into(), p[2].into())).collect();
    let mesh: Arc<dyn crate::shapes::Shape> = Arc::new(TriangleMesh::new(positions, SQUARE.1.to_vec(), None).unwrap());
    b.object(Instance::new(mesh.clone(), crate::math::Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0))).unwrap(), m).unwrap();
    b.shared_object(mesh, m).unwrap();
    b.build().unwrap()
}

type Answers<T> = (Vec<T>, Vec<i64>, Vec<i64>);

fn cast_all<B: BatchTarget, T: Float>(target: &B, origins: &[[T; 3]], dirs: &[[T; 3]], threads: usize) -> Answers<T> {
    let n = origins.len();
    let (mut t, mut object, mut primitive) = (vec![T::from_f64(0.0); n], vec![0; n], vec![0; n]);
    let out = Hits { t: &mut t, object: Some(&mut object), primitive: Some(&mut primitive), normal: None, error: None };
    cast(target, &RaySlices::new(origins, dirs).unwrap(), out, threads).unwrap();
    (t, object, primitive)
}

#[test]
fn t_is_the_distance_whatever_the_direction_length() {
    let s = scene();
    let accel = MeshAccel::new(&SQUARE.0, &SQUARE.1).unwrap();
    // Straight down onto the square from height 2, then along the x axis into the sphere.
    for scale in [1.0, 0.25, 2.0, 1024.0] {
        let origins = [[0.8, 0.2, 2.0], [0.2, 0.8, 2.0], [5.8, 0.2, 2.0], [0.0, 0.0, -2.0]];
        let dirs = [[0.0, 0.0, -scale], [0.0, 0.0, -scale], [0.0, 0.0, -scale], [0.0, 0.0, -scale]];
        let (t, object, primitive) = cast_all(&s, &origins, &dirs, 1);
        assert_eq!(t, [2.0, 2.0, 2.0, 2.0], "scale {scale}");
        assert_eq!(object, [2, 2, 1, 0]);
        assert_eq!(primitive, [0, 1, 0, -1], "triangles of the mesh, kept through the instance; -1 for the sphere");
        let (t, object, primitive) = cast_all(&accel, &origins[..2], &dirs[..2], 1);
        assert_eq!((t, object, primitive), (vec![2.0f32, 2.0], vec![0, 0], vec![0, 1]), "scale {scale}");
    }
}

#[test]
fn misses_and_degenerate_rays_are_inf_and_minus_one() {
    let s = scene();
    let origins = [[0.0, 0.0, 2.0], [f64::NAN, 0.0, 2.0], [0.0, 0.0, 2.0], [0.0, 0.0, 2.0], [0.5, 0.5, 2.0]];
    let dirs = [[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, f64::INFINITY, -1.0], [0.0, 1.0, 0.0], [1e200, 1e200, -1e200]];
    let n = origins.len();
    let (mut t, mut object, mut primitive, mut normal) = (vec![0.0; n], vec![0; n], vec![0; n], vec![[1.0; 3]; n]);
    let out = Hits { t: &mut t, object: Some(&mut object), primitive: Some(&mut primitive), normal: Some(&mut normal), error: None };
    cast(&s, &RaySlices::new(&origins, &dirs).unwrap(), out, 2).unwrap();
    assert_eq!(t, [f64::INFINITY; 5], "the last direction's length overflows: a miss by definition");
    assert_eq!((object, primitive), (vec![-1; 5], vec![-1; 5]));
    assert_eq!(normal, vec![[0.0; 3]; 5]);
    let mut hit = [true; 5];
    occluded(&s, &RaySlices::new(&origins, &dirs).unwrap(), None, &mut hit, 0).unwrap();
    assert_eq!(hit, [false; 5]);
}

#[test]
fn normals_are_outward_and_occlusion_uses_distances() {
    let s = scene();
    // Into the sphere from inside (its centre) and from outside, and up at the square from below.
    let origins = [[0.0, 0.0, -5.0], [-3.0, 0.0, -5.0], [0.5, 0.25, -0.5]];
    let dirs = [[0.0, 3.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 4.0]];
    let (mut t, mut normal) = (vec![0.0f32; 3], vec![[0.0f32; 3]; 3]);
    let out = Hits { t: &mut t, object: None, primitive: None, normal: Some(&mut normal), error: None };
    cast(&s, &RaySlices::new(&origins, &dirs).unwrap(), out, 1).unwrap();
    assert_eq!(t, [1.0, 2.0, 0.5]);
    assert_eq!(normal, [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], "outward, not turned to the ray");
    let mut hit = [false; 3];
    occluded(&s, &RaySlices::new(&origins, &dirs).unwrap(), Some(&[1.5, 1.5, 0.75]), &mut hit, 1).unwrap();
    assert_eq!(hit, [true, false, true]);
}

#[test]
fn answers_do_not_depend_on_threads_or_chunks() {
    let s = scene();
    let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
    let mut r = |a: f64| (rng.uniform() * 2.0 - 1.0) * a;
    let n = 3 * CHUNK + 17;
    let origins: Vec<[f64; 3]> = (0..n).map(|_| [r(8.0), r(8.0), r(8.0)]).collect();
    // Aimed at points of the box around the objects, x in [-1, 6], y in [-1, 1], z in [-6, 0].
    let dirs: Vec<[f64; 3]> = origins.iter().map(|o| [2.5 + r(3.5) - o[0], r(1.0) - o[1], -3.0 + r(3.0) - o[2]]).collect();
    let one = cast_all(&s, &origins, &dirs, 1);
    let hits = one.1.iter().filter(|&&o| o >= 0).count();
    assert!(hits > n / 20 && hits < n, "{hits} of {n} rays hit");
    for threads in [2, 3, 0] {
        let other = cast_all(&s, &origins, &dirs, threads);
        assert_eq!(one.0.iter().map(|t| t.to_bits()).collect::<Vec<_>>(), other.0.iter().map(|t| t.to_bits()).collect::<Vec<_>>());
        assert_eq!((&one.1, &one.2), (&other.1, &other.2), "{threads} threads");
    }
}

#[test]
fn bad_lengths_and_thread_counts_are_errors() {
    let s = scene();
    assert_eq!(RaySlices::new(&[[0.0f64; 3]; 2], &[[0.0; 3]; 3]).unwrap_err().to_string(), "invalid rays: 2 origins but 3 directions");
    let rays = RaySlices::new(&[[0.0f64; 3]; 2], &[[0.0; 3]; 2]).unwrap();
    let (mut t, mut object) = ([0.0f64; 2], [0i64; 1]);
    let err = cast(&s, &rays, Hits { t: &mut t, object: Some(&mut object), primitive: None, normal: None, error: None }, 1).unwrap_err();
    assert_eq!(err.to_string(), "invalid object: 1 outputs for 2 rays: lengths must agree");
    let err = cast(&s, &rays, Hits { t: &mut t, object: None, primitive: None, normal: None, error: None }, MAX_THREADS + 1).unwrap_err();
    assert_eq!(err.to_string(), "invalid threads: 1025: at most 1024 (0 uses the current pool)");
    let err = occluded(&s, &rays, Some(&[1.0]), &mut [false; 2], 1).unwrap_err();
    assert!(err.to_string().contains("lengths must agree"), "{err}");
    let empty = RaySlices::<f32>::new(&[], &[]).unwrap();
    assert!(empty.is_empty());
    cast(&s, &empty, Hits { t: &mut [0.0f32; 0], object: None, primitive: None, normal: None, error: None }, 0).unwrap();
}

/// `t` and its error bound for each ray against `target`, in `f64`.
fn distances_and_errors<T: Float>(target: &Scene, origins: &[[T; 3]], dirs: &[[T; 3]]) -> (Vec<T>, Vec<T>) {
    let n = origins.len();
    let (mut t, mut error) = (vec![T::from_f64(0.0); n], vec![T::from_f64(0.0); n]);
    let out = Hits { error: Some(&mut error), ..Hits::distances(&mut t) };
    cast(target, &RaySlices::new(origins, dirs).unwrap(), out, 1).unwrap();
    (t, error)
}

/// A scene of one sphere.
fn sphere_scene(center: Vec3, radius: f64) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(30.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(Material::plastic(Rgb::splat(0.5), 0.1, 0.8, 0.0, 1.0)).unwrap();
    b.object(Sphere::new(center, radius).unwrap(), m).unwrap();
    b.build().unwrap()
}

#[test]
fn error_bounds_hold_and_flag_far_hits() {
    let s = sphere_scene(Vec3::new(0.0, 0.0, -5.0), 1.0);
    // Down the z axis onto the sphere at (0, 0, -5): exactly t = z + 4. `t - z`
    // is exact (Sterbenz), so the true error `(t - z) - 4` is too.
    for z in [5.0f64, 1e3, 1e8, 1e12, 1e15, 1e17, 1e20] {
        let (t, error) = distances_and_errors(&s, &[[0.0, 0.0, z]], &[[0.0, 0.0, -1.0]]);
        let true_error = ((t[0] - z) - 4.0).abs();
        assert!(true_error <= error[0], "z = {z}: t = {}, off by {true_error}, bound {}", t[0], error[0]);
        assert!(error[0] <= 1e-13 * (z + 10.0), "z = {z}: the bound {} is a few ulps, not vacuous", error[0]);
    }
    // Far away the bound exceeds the sphere itself: the caller can tell that
    // the distance no longer resolves it.
    let (_, error) = distances_and_errors(&s, &[[0.0, 0.0, 1e17]], &[[0.0, 0.0, -1.0]]);
    assert!(error[0] > 2.0, "bound {}", error[0]);
    // f32 answers add their own rounding, half an ulp of t at least.
    let (t, error) = distances_and_errors(&s, &[[0.0f32, 0.0, 1e3]], &[[0.0, 0.0, -1.0]]);
    assert_eq!(t[0], 1004.0);
    assert!(error[0] >= f32::EPSILON * 1004.0 / 2.0);
    // A miss has an infinite bound.
    let (t, error) = distances_and_errors(&s, &[[0.0, 10.0, 0.0]], &[[0.0, 1.0, 0.0]]);
    assert_eq!((t[0], error[0]), (f64::INFINITY, f64::INFINITY));
}

#[test]
fn error_bounds_cover_a_large_shape_seen_from_close_by() {
    // A sphere of radius 1e6 whose top is at z = 0, hit from z = 1: t is about
    // 1, but it is computed from magnitudes of 1e12, which the bound must count.
    let s = sphere_scene(Vec3::new(0.0, 0.0, -1e6), 1e6);
    for x in [0.0f64, 0.5, 3.0, 100.0] {
        // Exactly 1 + (1e6 - sqrt(1e12 - x^2)), written without cancellation.
        let exact = 1.0 + x * x / (1e6 + (1e12 - x * x).sqrt());
        let (t, error) = distances_and_errors(&s, &[[x, 0.0, 1.0]], &[[0.0, 0.0, -1.0]]);
        assert!((t[0] - exact).abs() <= error[0], "x = {x}: t = {}, exact {exact}, bound {}", t[0], error[0]);
    }
}

#[test]
fn a_mesh_target_does_not_claim_error_bounds() {
    let accel = MeshAccel::new(&SQUARE.0, &SQUARE.1).unwrap();
    let (mut t, mut error) = (vec![0.0f32], vec![0.0f32]);
    let out = Hits { error: Some(&mut error), ..Hits::distances(&mut t) };
    let err = cast(&accel, &RaySlices::new(&[[0.5, 0.5, 1.0]], &[[0.0, 0.0, -1.0]]).unwrap(), out, 1).unwrap_err();
    assert_eq!(err.to_string(), "invalid error: this target does not bound its errors");
}

/// The `f32` shortcut of [`Float::usable_ray`] refuses exactly the rays the
/// `f64` definition refuses, on the values at the edges: zeros, the smallest
/// subnormal, the largest finite, infinities and NaN.
#[test]
fn f32_usable_rays_are_those_of_the_f64_definition() {
    let values =
        [0.0f32, -0.0, f32::from_bits(1), -f32::from_bits(1), 1.0, -3.5, f32::MAX, f32::MIN, f32::INFINITY, f32::NEG_INFINITY, f32::NAN];
    let mut checked = 0;
    for &a in &values {
        for &b in &values {
            for &c in &values {
                for (origin, dir) in [([a, b, c], [1.0, 0.0, 0.0]), ([0.0, 1.0, 2.0], [a, b, c])] {
                    let wide = <f64 as Float>::usable_ray(origin.map(f64::from), dir.map(f64::from));
                    assert_eq!(<f32 as Float>::usable_ray(origin, dir), wide, "origin {origin:?} dir {dir:?}");
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 2 * 11 * 11 * 11);
}
