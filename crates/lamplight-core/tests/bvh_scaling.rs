//! The BVH must never degrade into a linear scan: as the number of spheres grows
//! a thousandfold, the primitive tests per ray stay bounded (a count, not a
//! timing; timings are in `benches/scaling.rs` and BENCHMARKS.md).

use lamplight_core::accel::{Aabb, Bvh};
use lamplight_core::math::Vec3;
use lamplight_core::ray::Ray;
use lamplight_core::shapes::{Shape, Sphere};

fn rand(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E3779B97F4A7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Spheres of constant density (so the expected hit distance stays put): radius 0.6
/// and 1/8 per unit volume give a mean free path of about 7, well inside the
/// smallest scene (side 20).
fn spheres(n: usize, seed: u64) -> Vec<Sphere> {
    let side = (n as f64).cbrt() * 2.0;
    let mut s = seed;
    (0..n).map(|_| Sphere::new(Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * side, 0.6).unwrap()).collect()
}

fn tests_per_ray(n: usize) -> f64 {
    let shapes = spheres(n, 42);
    let boxes: Vec<Aabb> = shapes.iter().map(|s| s.bounds()).collect();
    let bvh = Bvh::build(&boxes);
    let side = (n as f64).cbrt() * 2.0;
    let mut s = 7u64;
    let (mut tests, rays) = (0usize, 2000);
    for _ in 0..rays {
        // Origins in the central part, so that (at constant density) rays of every
        // scene size meet the same surroundings before they hit.
        let origin = (Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 0.2 + 0.4) * side;
        let dir = (Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) - 0.5).normalize();
        let ray = Ray::new(origin, dir);
        let found = bvh.traverse(origin, ray.dir, 0.0, f64::INFINITY, |i, t_max| {
            tests += 1;
            shapes[i as usize].intersect(&ray, 0.0, t_max).map(|h| h.t)
        });
        // Cross-check the nearest hit against brute force on the smaller sets.
        if n <= 1000 {
            let brute = shapes.iter().filter_map(|sp| sp.intersect(&ray, 0.0, f64::INFINITY)).map(|h| h.t).fold(f64::INFINITY, f64::min);
            assert_eq!(found, brute);
        }
    }
    tests as f64 / rays as f64
}

#[test]
fn primitive_tests_per_ray_stay_bounded_as_the_scene_grows() {
    let counts: Vec<(usize, f64)> = [1_000, 10_000, 100_000].into_iter().map(|n| (n, tests_per_ray(n))).collect();
    println!("primitive tests per ray: {counts:?}");
    // A scan would multiply the count by 100 from the first size to the last.
    let (first, last) = (counts[0].1, counts[2].1);
    assert!(last < 2.5 * first, "{first} -> {last}: the BVH scales badly");
    assert!(counts.iter().all(|&(_, t)| t < 12.0), "close to a scan: {counts:?}");
}
