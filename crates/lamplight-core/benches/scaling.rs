//! Time per ray as the scene grows: spheres at constant density, rays from the
//! centre region (the same setting as `tests/bvh_scaling.rs`). With a BVH the time
//! grows about with the logarithm of the sphere count; a scan would grow linearly.
//!
//! `cargo bench -p lamplight-core --bench scaling`

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
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

fn scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("nearest_hit_vs_sphere_count");
    const RAYS: usize = 10_000;
    group.throughput(Throughput::Elements(RAYS as u64));
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let side = (n as f64).cbrt() * 2.0;
        let mut s = 42u64;
        let spheres: Vec<Sphere> =
            (0..n).map(|_| Sphere::new(Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * side, 0.6).unwrap()).collect();
        let boxes: Vec<Aabb> = spheres.iter().map(|sp| sp.bounds()).collect();
        let bvh = Bvh::build(&boxes);
        let rays: Vec<Ray> = (0..RAYS)
            .map(|_| {
                let origin = (Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 0.2 + 0.4) * side;
                Ray::new(origin, Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) - 0.5)
            })
            .collect();
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                let mut sum = 0.0;
                for ray in &rays {
                    let t = bvh.traverse(ray.origin, ray.dir, 0.0, f64::INFINITY, |i, t_max| {
                        spheres[i as usize].intersect(ray, 0.0, t_max).map(|h| h.t)
                    });
                    sum += t.min(1e9);
                }
                black_box(sum)
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = scaling
}
criterion_main!(benches);
