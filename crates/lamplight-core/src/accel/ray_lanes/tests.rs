//! The lanes against each shape's own scalar test, bit for bit.

use std::sync::Arc;

use super::*;
use crate::math::Mat4;
use crate::ray::Ray;
use crate::shapes::{Cuboid, Rectangle, Shape};

/// A Cornell box (six walls and the light as rectangles, two turned boxes,
/// the tall one standing exactly on the floor) and `extra` random rectangles
/// and boxes.
fn shapes(extra: usize, seed: u64) -> Vec<Arc<dyn Shape>> {
    let mut rng = crate::sampling::Rng::for_sample(seed, 0, 0);
    let mut rand = move || rng.uniform();
    let rect = |m: Mat4| -> Arc<dyn Shape> {
        let corner = m.transform_point3(Vec3::new(-1.0, -1.0, 0.0));
        Arc::new(
            Rectangle::new(corner, m.transform_vector3(Vec3::new(2.0, 0.0, 0.0)), m.transform_vector3(Vec3::new(0.0, 2.0, 0.0))).unwrap(),
        )
    };
    let t = |x: f64, y: f64, z: f64| Mat4::from_translation(Vec3::new(x, y, z));
    let rx = |deg: f64| Mat4::from_rotation_x(deg.to_radians());
    let ry = |deg: f64| Mat4::from_rotation_y(deg.to_radians());
    let mut list: Vec<Arc<dyn Shape>> = vec![
        rect(t(0.0, 0.99, 0.01) * rx(90.0) * Mat4::from_scale(Vec3::new(0.23, 0.19, 0.19))),
        rect(t(0.0, -1.0, 0.0) * rx(-90.0)),
        rect(t(0.0, 1.0, 0.0) * rx(90.0)),
        rect(t(0.0, 0.0, -1.0)),
        rect(t(1.0, 0.0, 0.0) * ry(-90.0)),
        rect(t(-1.0, 0.0, 0.0) * ry(90.0)),
        Arc::new(Cuboid::new(-Vec3::ONE, Vec3::ONE, t(0.335, -0.7, 0.38) * ry(-17.0) * Mat4::from_scale(Vec3::splat(0.3))).unwrap()),
        // Its bottom face lies in the floor's plane: rays there tie.
        Arc::new(
            Cuboid::new(-Vec3::ONE, Vec3::ONE, t(-0.33, -0.39, -0.28) * ry(18.25) * Mat4::from_scale(Vec3::new(0.3, 0.61, 0.3))).unwrap(),
        ),
    ];
    for k in 0..extra {
        let centre = Vec3::new(rand() * 1.6 - 0.8, rand() * 1.6 - 0.8, rand() * 1.6 - 0.8);
        let turn = Mat4::from_rotation_y(rand() * 6.0) * Mat4::from_rotation_x(rand() * 6.0);
        let scale = Vec3::new(0.05 + rand() * 0.3, 0.05 + rand() * 0.3, 0.05 + rand() * 0.3);
        let m = Mat4::from_translation(centre) * turn * Mat4::from_scale(scale);
        list.push(if k % 2 == 0 { rect(m) } else { Arc::new(Cuboid::new(-Vec3::ONE, Vec3::ONE, m).unwrap()) });
    }
    list
}

/// The scalar answer: each object's own test, the nearest kept (`None` for
/// a miss), and whether another object is hit at the same distance.
fn scalar_nearest(list: &[Arc<dyn Shape>], ray: &Ray, t_max: f64) -> (Option<(usize, crate::shapes::SurfaceHit)>, bool) {
    let hits: Vec<(usize, crate::shapes::SurfaceHit)> =
        list.iter().enumerate().filter_map(|(i, s)| s.intersect(ray, 0.0, t_max).map(|h| (i, h))).collect();
    let Some(&(slot, h)) = hits.iter().min_by(|a, b| a.1.t.total_cmp(&b.1.t)) else { return (None, false) };
    (Some((slot, h)), hits.iter().filter(|x| x.1.t == h.t).count() > 1)
}

/// Random rays through the room, from inside and outside, and rays leaving
/// the points they hit (as a path's next segment, from the hit point itself:
/// where the walk is most delicate), four at a time with some lanes idle;
/// and both compilations of the queries (AVX2, AVX-512) answer alike.
#[test]
fn lanes_answer_as_each_shape_does() {
    if !crate::cpu::avx2_features() {
        eprintln!("skipped: this CPU lacks AVX2, and the lanes run only there");
        return;
    }
    let (mut hits, mut ties, mut misses, mut blocked) = (0, 0, 0, 0);
    for (extra, seed) in [(0, 1), (2, 2), (3, 3), (4, 4)] {
        let list = shapes(extra, seed);
        let built: Vec<(LaneShape, bool, u32)> =
            list.iter().enumerate().map(|(i, s)| (s.lane().expect("a lane kind"), i % 3 != 2, 100 + i as u32)).collect();
        let lanes = ObjectLanes::build(&built).expect("few enough objects");
        assert_eq!(lanes.len(), list.len());
        let mut rng = crate::sampling::Rng::for_sample(seed + 10, 0, 0);
        let mut rand = move || rng.uniform();
        for k in 0..10_000 {
            let mut rays = [Ray::unit(Vec3::ZERO, Vec3::X); 4];
            for (lane, ray) in rays.iter_mut().enumerate() {
                let scale = if (k + lane) % 2 == 0 { 1.0 } else { 3.0 };
                let origin = Vec3::new(rand() * 2.0 - 1.0, rand() * 2.0 - 1.0, rand() * 2.0 - 1.0) * scale;
                let z = rand() * 2.0 - 1.0;
                let phi = rand() * std::f64::consts::TAU;
                let r = (1.0 - z * z).sqrt();
                *ray = Ray::unit(origin, Vec3::new(r * phi.cos(), r * phi.sin(), z));
                if (k + lane) % 3 == 0 {
                    if let (Some((_, h)), _) = scalar_nearest(&list, ray, f64::INFINITY) {
                        let turn = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5);
                        *ray = Ray::unit(ray.at(h.t), (ray.dir + turn).normalize());
                    }
                }
            }
            let t_max = if k % 4 == 0 { rand() * 3.0 } else { f64::INFINITY };
            let active = if k % 7 == 0 { 0b0101 } else { 0b1111 };
            // SAFETY: the CPU has AVX2 (checked above).
            let answer = unsafe { lanes.closest(&rays, t_max, active) };
            let distance = [0, 1, 2, 3].map(|_| rand() * 3.0);
            // Every 11th round all lanes ignore one object (a light's own
            // shape, which the query then does not test).
            let ignore = [0, 1, 2, 3].map(|lane| match k % 11 {
                0 => 100 + (k / 11 % list.len()) as u32,
                _ if (k + lane) % 5 == 0 => u32::MAX,
                _ => 100 + ((k + lane) % list.len()) as u32,
            });
            // SAFETY: as above.
            let blocking = unsafe { lanes.blocked(&rays, &distance, &ignore, active) };
            // Where the CPU has AVX-512, the queries above ran its compilation:
            // the AVX2 one answers the same.
            // SAFETY: as above.
            let (answer_avx2, blocking_avx2) =
                unsafe { (lanes.closest_avx2(&rays, t_max, active), lanes.blocked_avx2(&rays, &distance, &ignore, active)) };
            assert_eq!(answer_avx2.t.map(f64::to_bits), answer.t.map(f64::to_bits));
            assert_eq!((answer_avx2, blocking_avx2), (answer, blocking), "the AVX2 compilation differs");
            for (lane, ray) in rays.iter().enumerate() {
                let bit = 1u8 << lane;
                if active & bit == 0 {
                    assert_eq!((answer.hit & bit, answer.tie & bit, blocking & bit), (0, 0, 0), "an idle lane answered");
                    continue;
                }
                let (expected, tie) = scalar_nearest(&list, ray, t_max);
                assert_eq!(answer.tie & bit != 0, tie, "tie on {ray:?} up to {t_max}");
                match expected {
                    None => {
                        assert_eq!(answer.hit & bit, 0, "lanes hit where the shapes miss: {ray:?}");
                        misses += 1;
                    }
                    Some(_) if tie => ties += 1,
                    Some((slot, h)) => {
                        assert_ne!(answer.hit & bit, 0, "lanes miss {ray:?}");
                        assert_eq!((answer.slot[lane] as usize, answer.t[lane].to_bits()), (slot, h.t.to_bits()), "{ray:?} up to {t_max}");
                        let normal = lanes.shape(answer.slot[lane]).normal(answer.face[lane] as usize);
                        assert_eq!(normal.to_array().map(f64::to_bits), h.normal.to_array().map(f64::to_bits), "face on {ray:?}");
                        hits += 1;
                    }
                }
                let blocks = |i: usize| built[i].1 && built[i].2 != ignore[lane] && list[i].intersect_p(ray, 0.0, distance[lane]);
                let any = (0..list.len()).any(blocks);
                assert_eq!(blocking & bit != 0, any, "shadow of {ray:?} to {}", distance[lane]);
                blocked += usize::from(any);
            }
        }
    }
    assert!(hits > 50_000 && misses > 20_000 && blocked > 30_000, "{hits} hits, {misses} misses, {blocked} blocked");
    assert!(ties > 0, "no ray found a tie: the test no longer covers them");
}

/// Too many objects, or none, give no lanes.
#[test]
fn lanes_hold_a_handful() {
    let one = (shapes(0, 1)[0].lane().unwrap(), true, 0);
    assert!(ObjectLanes::build(&[]).is_none());
    assert!(ObjectLanes::build(&vec![one; crate::accel::FLAT_MAX + 1]).is_none());
    assert_eq!(ObjectLanes::build(&vec![one; crate::accel::FLAT_MAX]).map(|l| l.len()), Some(crate::accel::FLAT_MAX));
}

/// The queries' two compilations name the feature lists of `cpu.rs` (the
/// attribute takes a literal).
#[test]
fn the_compilations_name_the_detected_features() {
    let source = include_str!("../ray_lanes.rs");
    for (features, names) in
        [(crate::cpu::AVX2_FEATURES, "closest_in, blocked_in"), (crate::cpu::AVX512_FEATURES, "closest_in_avx512, blocked_in_avx512")]
    {
        let invocation = format!("bodies!(\"{features}\", {names});");
        assert!(source.contains(&invocation), "expected `{invocation}` in ray_lanes.rs");
    }
}

/// The lane test of a ball against [`crate::shapes::Sphere`]'s own: over
/// rays that miss, graze, start inside, start on the surface and meet it
/// behind their origin, from near and far (a unit ball seen from 1e6
/// away), and bounds that cut between the roots, the same hits and the
/// same parameters, bit for bit.
#[test]
fn balls_in_lanes_answer_as_the_sphere_test() {
    if !crate::cpu::avx2_features() {
        eprintln!("skipped: this CPU lacks AVX2");
        return;
    }
    use crate::shapes::Sphere;
    use std::arch::x86_64::*;
    let mut rng = crate::sampling::Rng::for_sample(17, 0, 0);
    let mut rand = move || rng.uniform();
    let (mut hits, mut inside) = (0, 0);
    for k in 0..20_000 {
        let scale = [1e-3, 1.0, 1e3][k % 3];
        let ball = Sphere::new(Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * scale, (0.1 + rand()) * scale).unwrap();
        let far = if k % 7 == 0 { 1e6 } else { 4.0 };
        let rays: [Ray; 4] = std::array::from_fn(|l| {
            let origin = match (k + l) % 5 {
                // On the surface, as a ray leaving it.
                0 => ball.center + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5).normalize() * ball.radius,
                1 => ball.center + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * ball.radius,
                _ => ball.center + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5).normalize() * far * scale,
            };
            let aim = ball.center + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 2.4 * ball.radius;
            Ray::unit(origin, (aim - origin).normalize())
        });
        let bounds: [f64; 4] = std::array::from_fn(|l| if (k + l) % 4 == 0 { rand() * far * scale } else { f64::INFINITY });
        let mut t = [0.0; 4];
        // SAFETY: the CPU has AVX2 (checked above).
        let ok = unsafe {
            let (lane_t, lane_ok) = balls::sphere(ball.center, ball.radius, &avx2::rays(&rays), _mm256_loadu_pd(bounds.as_ptr()));
            _mm256_storeu_pd(t.as_mut_ptr(), lane_t);
            _mm256_movemask_pd(lane_ok)
        };
        for l in 0..4 {
            let expected = ball.intersect(&rays[l], 0.0, bounds[l]).map(|h| h.t.to_bits());
            let got = (ok & (1 << l) != 0).then(|| t[l].to_bits());
            assert_eq!(got, expected, "ball {ball:?}, ray {:?} to {}", rays[l], bounds[l]);
            hits += usize::from(expected.is_some());
            inside += usize::from(expected.is_some() && (rays[l].origin - ball.center).length() < ball.radius);
        }
    }
    assert!(hits > 30_000 && inside > 5_000, "{hits} hits, {inside} from inside");
}
