use super::*;
use crate::ray::Ray;
use crate::sampling::Rng;
use crate::shapes::{Shape, Sphere};

/// A grid of `n^3` samples of `f` at the grid's corners `(i, j, k) / (n - 1)`.
fn sampled(n: usize, f: impl Fn(Vec3) -> f64) -> SdfGrid {
    let h = 1.0 / (n - 1) as f64;
    let mut values = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(f(Vec3::new(i as f64, j as f64, k as f64) * h) as f32);
            }
        }
    }
    SdfGrid::new([n; 3], values).unwrap()
}

fn unit_vector(rng: &mut Rng) -> Vec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// A plane's signed distance is linear, so the trilinear interpolant is the
/// plane itself (up to the samples' f32 rounding): every ray that meets the
/// plane inside the cube hits it at the analytic distance, grazing rays too,
/// with the plane's normal as geometric and (inside) as smooth shading normal.
#[test]
fn a_plane_grid_is_the_plane() {
    let normal = Vec3::new(0.3, 0.8, -0.5).normalize();
    let offset = normal.dot(Vec3::splat(0.5));
    let grid = sampled(9, |p| normal.dot(p) - offset);
    assert!((grid.lipschitz() - Vec3::new(0.3, 0.8, 0.5).normalize().length()).abs() < 1e-6, "{}", grid.lipschitz());
    let (analytic, smooth) = (grid.clone().into_shape(false), grid.into_shape(true));
    let mut rng = Rng::for_sample(26, 0, 0);
    let mut hits = 0;
    for i in 0..4000 {
        let origin = Vec3::splat(0.5) + unit_vector(&mut rng) * 2.0;
        let target = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        // Every fourth ray grazes: its direction is within 1e-3 of the plane.
        let mut dir = (target - origin).normalize();
        if i % 4 == 0 {
            dir = (dir - normal * (normal.dot(dir) - 1e-3 * (rng.uniform() - 0.5))).normalize();
        }
        let ray = Ray::new(origin, dir);
        let t = (offset - normal.dot(origin)) / normal.dot(dir);
        let inside = t > 0.0 && ray.at(t).cmpge(Vec3::splat(1e-9)).all() && ray.at(t).cmple(Vec3::splat(1.0 - 1e-9)).all();
        for shape in [&analytic, &smooth] {
            let hit = shape.intersect(&ray, 0.0, f64::INFINITY);
            match hit {
                Some(h) => {
                    assert!(inside || t > 0.0, "ray {i}: a hit where the plane is outside the cube");
                    // Distances of the samples are rounded to f32 (6e-8 relative).
                    let tolerance = 1e-6 / normal.dot(dir).abs().max(1e-3);
                    assert!((h.t - t).abs() < tolerance, "ray {i}: t = {} vs {t}", h.t);
                    assert!((h.normal - normal).length() < 1e-6, "ray {i}: {h:?}");
                    // Near the grid's upper faces the smooth blend takes in a voxel
                    // beyond the grid, whose difference along that axis is 0 (as Mitsuba's).
                    let p = ray.at(h.t);
                    if p.cmple(Vec3::splat(1.0 - 2.0 / 8.0)).all() {
                        assert!((h.shading_normal - normal).length() < 1e-6, "ray {i}: {h:?}");
                    }
                    hits += 1;
                }
                None => assert!(!inside, "ray {i} misses the plane at t = {t} ({})", ray.at(t)),
            }
        }
    }
    assert!(hits > 3000, "{hits}");
}

/// A sphere's exact distance on a 32^3 grid: the interpolant differs from the
/// distance by `O(h^2)` (`h = 1/31`), so hits lie within 2e-3 of the sphere's
/// (interpolation error over the cosine of the incidence, for rays not within
/// 25 degrees of grazing), and both normals within 0.03 of the sphere's.
#[test]
fn a_sphere_grid_is_the_sphere_to_the_interpolation_error() {
    let (c, r) = (Vec3::new(0.5, 0.45, 0.52), 0.3);
    let grid = sampled(32, |p| (p - c).length() - r);
    let l = grid.lipschitz();
    assert!(l <= 3f64.sqrt() && l > 0.99, "edge differences of a distance are at most h: {l}");
    let sphere = Sphere::new(c, r).unwrap();
    let mut rng = Rng::for_sample(26, 1, 0);
    let mut compared = 0;
    let mut worst = [0.0f64; 4];
    for smooth in [false, true] {
        let shape = grid.clone().into_shape(smooth);
        for i in 0..2000 {
            let origin = c + unit_vector(&mut rng) * 1.5;
            let dir = (c + unit_vector(&mut rng) * r * rng.uniform() - origin).normalize();
            let ray = Ray::new(origin, dir);
            let (got, want) = (shape.intersect(&ray, 0.0, f64::INFINITY), sphere.intersect(&ray, 0.0, f64::INFINITY));
            let want = want.expect("aimed inside the sphere");
            let got = got.unwrap_or_else(|| panic!("ray {i} (smooth {smooth}) misses"));
            let cosine = want.normal.dot(-dir);
            if cosine > 0.42 {
                assert!((got.t - want.t).abs() < 2e-3 / cosine, "ray {i}: t = {} vs {}", got.t, want.t);
                worst[0] = worst[0].max((got.t - want.t).abs() * cosine);
                worst[1] = worst[1].max((got.normal - want.normal).length());
                worst[2 + smooth as usize] = worst[2 + smooth as usize].max((got.shading_normal - want.normal).length());
                compared += 1;
            }
        }
    }
    assert!(compared > 2000, "{compared}");
    eprintln!("worst {worst:?}");
    assert!(worst[0] < 2e-3 && worst[1] < 0.1 && worst[3] < 0.03, "{worst:?}");
}

/// The smooth normal is continuous across a voxel face where the analytic
/// gradient jumps (Mitsuba's reason to make it the default).
#[test]
fn smooth_normals_are_continuous_across_voxels() {
    let grid = sampled(8, |p| (p - Vec3::splat(0.5)).length() - 0.3);
    let face = 3.0 / 7.0;
    let (below, above) = (Vec3::new(face - 1e-9, 0.61, 0.37), Vec3::new(face + 1e-9, 0.61, 0.37));
    let (a, b) = (grid.smooth_normal(below).normalize(), grid.smooth_normal(above).normalize());
    assert!((a - b).length() < 1e-6, "{a} vs {b}");
    let (ga, gb) = (grid.gradient(below).normalize(), grid.gradient(above).normalize());
    assert!((ga - gb).length() > 1e-3, "the analytic gradient does jump there: {ga} vs {gb}");
}

#[test]
fn bad_grids_are_errors() {
    let sphere: Vec<f32> = sampled(4, |p| (p - Vec3::splat(0.5)).length() - 0.3).values;
    let message = |r: Result<SdfGrid, Error>| r.unwrap_err().to_string();
    assert_eq!(message(SdfGrid::new([4, 4, 3], sphere.clone())), "invalid values: has 64 numbers, expected 48");
    assert_eq!(
        message(SdfGrid::new([1, 4, 16], sphere.clone())),
        "invalid resolution: must be at least 2 per axis and at most 4194304 samples, got [1, 4, 16]"
    );
    assert!(message(SdfGrid::new([usize::MAX, 2, 2], sphere.clone())).contains("at most 4194304 samples"));
    let mut nan = sphere.clone();
    nan[5] = f32::NAN;
    assert_eq!(message(SdfGrid::new([4; 3], nan)), "invalid values: values[5] is NaN, expected a finite number");
    assert_eq!(message(SdfGrid::new([4; 3], vec![1.0; 64])), "invalid values: hold no surface: no voxel has corners of both signs");
}
