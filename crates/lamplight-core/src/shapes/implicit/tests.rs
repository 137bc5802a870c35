use super::*;
use crate::sampling::Rng;
use crate::shapes::{Sphere, Torus};
use std::sync::atomic::{AtomicUsize, Ordering};

fn unit_vector(rng: &mut Rng) -> Vec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

const CENTER: Vec3 = Vec3::new(0.5, -1.0, 2.0);
const RADIUS: f64 = 1.5;

/// The sphere as a signed distance (`L = 1`).
fn sdf_sphere() -> Implicit {
    let f: ImplicitFn = Arc::new(|p: Vec3| (p - CENTER).length() - RADIUS);
    Implicit::new(f, Aabb::new(CENTER - Vec3::splat(RADIUS), CENTER + Vec3::splat(RADIUS)), 1.0).unwrap()
}

/// The sphere as the quadric `|p - c|^2 - R^2`, whose gradient `2 |p - c|` is at
/// most `2 sqrt(3) R` in the box, with its analytic gradient.
fn quadric_sphere() -> Implicit {
    let f: ImplicitFn = Arc::new(|p: Vec3| (p - CENTER).length_squared() - RADIUS * RADIUS);
    let bounds = Aabb::new(CENTER - Vec3::splat(RADIUS), CENTER + Vec3::splat(RADIUS));
    Implicit::new(f, bounds, 2.0 * 3f64.sqrt() * RADIUS * 1.01).unwrap().with_gradient(Arc::new(|p: Vec3| 2.0 * (p - CENTER)))
}

fn ray_hit(shape: &dyn Shape, origin: Vec3, dir: Vec3) -> Option<SurfaceHit> {
    shape.intersect(&Ray::new(origin, dir), 0.0, f64::INFINITY)
}

#[test]
fn implicit_sphere_equals_the_analytic_sphere() {
    let sphere = Sphere::new(CENTER, RADIUS).unwrap();
    let mut rng = Rng::for_sample(21, 0, 0);
    let mut hits = 0;
    for implicit in [sdf_sphere(), quadric_sphere()] {
        for _ in 0..3000 {
            let origin = CENTER + unit_vector(&mut rng) * (RADIUS * (0.2 + 3.0 * rng.uniform()));
            let dir = (CENTER + unit_vector(&mut rng) * 2.0 * RADIUS * rng.uniform() - origin).normalize();
            // Skip rays within 1e-3 of tangent, where a touch within the tolerance counts as a hit.
            let miss_distance = ((origin - CENTER) - dir * (origin - CENTER).dot(dir)).length();
            if (miss_distance - RADIUS).abs() < 1e-3 {
                continue;
            }
            let (a, b) = (ray_hit(&sphere, origin, dir), ray_hit(&implicit, origin, dir));
            assert_eq!(a.is_some(), b.is_some(), "from {origin} along {dir}: {a:?} vs {b:?}");
            if let (Some(a), Some(b)) = (a, b) {
                hits += 1;
                assert!((a.t - b.t).abs() < 1e-9, "t {} vs {}", a.t, b.t);
                assert!((a.normal - b.normal).length() < 1e-6, "normal {} vs {}", a.normal, b.normal);
                assert!(b.error <= implicit.tolerance());
            }
        }
    }
    assert!(hits > 2000, "{hits}");
}

#[test]
fn ray_starting_inside_finds_the_far_side() {
    for implicit in [sdf_sphere(), quadric_sphere()] {
        let h = ray_hit(&implicit, CENTER, Vec3::X).unwrap();
        assert!((h.t - RADIUS).abs() < 1e-9 && (h.normal - Vec3::X).length() < 1e-6);
        let off_centre = CENTER + Vec3::new(0.3, 0.2, -0.1);
        let h = ray_hit(&implicit, off_centre, -Vec3::Y).unwrap();
        let expected = (off_centre.y - CENTER.y) + (RADIUS * RADIUS - 0.3f64.powi(2) - 0.1f64.powi(2)).sqrt();
        assert!((h.t - expected).abs() < 1e-9, "{} vs {expected}", h.t);
    }
}

#[test]
fn tangent_ray_is_found() {
    for implicit in [sdf_sphere(), quadric_sphere()] {
        let origin = CENTER + Vec3::new(0.0, RADIUS, -5.0);
        let h = ray_hit(&implicit, origin, Vec3::Z).expect("tangent ray must hit");
        // Accepted within the tolerance of the surface: |dt| ~ sqrt(2 R tol).
        let slack = (2.0 * RADIUS * implicit.tolerance()).sqrt() * 2.0;
        assert!((h.t - 5.0).abs() < slack, "t = {}, slack {slack}", h.t);
        assert!((h.normal - Vec3::Y).length() < 0.01, "{}", h.normal);
        // A hair farther out it is a miss.
        assert!(ray_hit(&implicit, origin + Vec3::Y * 1e-3, Vec3::Z).is_none());
    }
}

#[test]
fn misses_end_quickly_and_the_march_is_capped() {
    let evaluations = Arc::new(AtomicUsize::new(0));
    let counter = evaluations.clone();
    let f: ImplicitFn = Arc::new(move |p: Vec3| {
        counter.fetch_add(1, Ordering::Relaxed);
        (p - CENTER).length() - RADIUS
    });
    let bounds = Aabb::new(CENTER - Vec3::splat(RADIUS), CENTER + Vec3::splat(RADIUS));
    let count = |shape: &Implicit, origin: Vec3, dir: Vec3| {
        evaluations.store(0, Ordering::Relaxed);
        let hit = ray_hit(shape, origin, dir);
        (hit, evaluations.load(Ordering::Relaxed))
    };
    let sphere = Implicit::new(f.clone(), bounds, 1.0).unwrap();
    // Through a corner of the box, well clear of the sphere.
    let (hit, n) = count(&sphere, CENTER + Vec3::new(1.4, 1.4, -5.0), Vec3::Z);
    assert!(hit.is_none() && n < 30, "{n} evaluations");
    // Passing 1% of the radius outside: slower, still bounded.
    let (hit, n) = count(&sphere, CENTER + Vec3::new(0.0, RADIUS * 1.01, -5.0), Vec3::Z);
    assert!(hit.is_none() && n < 200, "{n} evaluations");
    // A wildly pessimistic L makes every step tiny: the cap ends the march.
    let slow = Implicit::new(f, bounds, 1e9).unwrap().with_max_steps(500);
    let (hit, n) = count(&slow, CENTER + Vec3::new(1.1, 1.1, -5.0), Vec3::Z);
    assert!(hit.is_none(), "capped march reports no hit");
    // One value per step, plus the slope (2) and gradient (6) of each near-looking sample.
    assert!(n <= 500 * 9 + 2, "{n} evaluations");
}

#[test]
fn implicit_torus_equals_the_torus() {
    let axis = Vec3::new(0.0, 0.6, 0.8);
    let (big, small) = (2.0, 0.4);
    let torus = Torus::new(CENTER, axis, big, small).unwrap();
    let (fx, fy) = crate::math::orthonormal_basis(axis);
    let f: ImplicitFn = Arc::new(move |p: Vec3| {
        let q = p - CENTER;
        let (x, y, z) = (q.dot(fx), q.dot(fy), q.dot(axis));
        (x.hypot(y) - big).hypot(z) - small
    });
    let implicit = Implicit::new(f, torus.bounds(), 1.0).unwrap();
    let mut rng = Rng::for_sample(22, 0, 0);
    let mut hits = 0;
    for _ in 0..3000 {
        let origin = CENTER + unit_vector(&mut rng) * (1.0 + 4.0 * rng.uniform());
        let dir = (CENTER + unit_vector(&mut rng) * 2.5 * rng.uniform() - origin).normalize();
        let (a, b) = (ray_hit(&torus, origin, dir), ray_hit(&implicit, origin, dir));
        match (a, b) {
            (Some(a), Some(b)) => {
                if a.normal.dot(dir).abs() < 0.05 || b.error >= implicit.tolerance() {
                    continue; // grazing: t is only known to ~sqrt(tolerance)
                }
                hits += 1;
                assert!((a.t - b.t).abs() < 1e-9, "t {} vs {} from {origin} along {dir}", a.t, b.t);
                assert!((a.normal - b.normal).length() < 1e-6);
            }
            (None, None) => {}
            (a, b) => {
                // Only a touch within the tolerance may differ.
                let h = a.or(b).unwrap();
                let p = Ray::new(origin, dir).at(h.t);
                assert!(h.normal.dot(dir).abs() < 0.05, "disagree at {p}: torus {a:?} implicit {b:?}");
            }
        }
    }
    assert!(hits > 1000, "{hits}");
}

#[test]
fn gyroid_hits_lie_on_the_surface() {
    // sin x cos y + sin y cos z + sin z cos x: each gradient component is a sum like
    // cos x cos y - sin z sin x, at most sqrt(2) in size, so |grad f| <= sqrt(6) < L = 3.
    // Clipped to a box, so rays also leave without a hit.
    let f: ImplicitFn = Arc::new(|p: Vec3| p.x.sin() * p.y.cos() + p.y.sin() * p.z.cos() + p.z.sin() * p.x.cos());
    let gyroid = Implicit::new(f.clone(), Aabb::new(Vec3::splat(-3.0), Vec3::splat(3.0)), 3.0).unwrap();
    let mut rng = Rng::for_sample(23, 0, 0);
    let mut hits = 0;
    for _ in 0..500 {
        let origin = unit_vector(&mut rng) * 8.0;
        let dir = (unit_vector(&mut rng) * 2.0 - origin).normalize();
        if let Some(h) = ray_hit(&gyroid, origin, dir) {
            hits += 1;
            let p = Ray::new(origin, dir).at(h.t);
            assert!(f(p).abs() <= 3.0 * h.error.max(1e-12), "f = {} at {p}", f(p));
            // Nothing earlier: f keeps its sign from the box entry to the hit.
            let (enter, _) = gyroid.bounds().hit(&Ray::new(origin, dir), 0.0, f64::INFINITY).unwrap();
            let s0 = f(Ray::new(origin, dir).at(enter)).signum();
            for k in 1..200 {
                let t = enter + (h.t - enter) * k as f64 / 200.0 * 0.999;
                assert_eq!(f(Ray::new(origin, dir).at(t)).signum(), s0, "crossing before the reported hit");
            }
        }
    }
    assert!(hits > 400, "{hits}");
}

#[test]
fn spawned_rays_do_not_hit_their_own_surface() {
    let mut rng = Rng::for_sample(24, 0, 0);
    for implicit in [sdf_sphere(), quadric_sphere()] {
        for _ in 0..500 {
            let origin = CENTER + unit_vector(&mut rng) * 4.0;
            let ray = Ray::new(origin, CENTER + unit_vector(&mut rng) * 1.4 - origin);
            let h = implicit.intersect(&ray, 0.0, f64::INFINITY).unwrap();
            let point = ray.at(h.t);
            let reflected = ray.dir - 2.0 * ray.dir.dot(h.normal) * h.normal;
            // Reflected (outside, away) and straight on (inside, towards the far side).
            for dir in [reflected, ray.dir] {
                let spawned = Ray::new(crate::ray::offset_origin(point, h.normal, dir, h.t, h.error), dir);
                if let Some(again) = implicit.intersect(&spawned, 0.0, f64::INFINITY) {
                    assert!(again.t > 1e-3, "self-intersection at t = {} from {point}", again.t);
                }
            }
        }
    }
}

#[test]
fn rejects_bad_parameters() {
    let f: ImplicitFn = Arc::new(|p: Vec3| p.length() - 1.0);
    let b = Aabb::new(-Vec3::ONE, Vec3::ONE);
    assert!(Implicit::new(f.clone(), Aabb::INFINITE, 1.0).is_err());
    assert!(Implicit::new(f.clone(), Aabb::EMPTY, 1.0).is_err());
    assert!(Implicit::new(f.clone(), Aabb::new(Vec3::ONE, Vec3::ONE), 1.0).is_err());
    assert!(Implicit::new(f.clone(), b, 0.0).is_err());
    assert!(Implicit::new(f.clone(), b, f64::NAN).is_err());
    assert!(Implicit::new(f.clone(), b, 1.0).unwrap().with_tolerance(-1.0).is_err());
    let tight = Implicit::new(f, b, 1.0).unwrap().with_tolerance(1e-9).unwrap();
    assert_eq!(tight.tolerance(), 1e-9);
    assert!(tight.bounds().contains(Vec3::ONE) && !tight.bounds().contains(Vec3::splat(1.0 + 1e-6)));
}

#[test]
fn nan_ends_the_march() {
    let f: ImplicitFn = Arc::new(|p: Vec3| if p.z > 0.0 { f64::NAN } else { p.length() - 1.0 });
    let shape = Implicit::new(f, Aabb::new(-Vec3::ONE, Vec3::ONE), 1.0).unwrap();
    assert!(ray_hit(&shape, Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).is_none());
    assert!(ray_hit(&shape, Vec3::new(0.0, 0.0, -5.0), Vec3::Z).is_some());
}

#[test]
fn a_lipschitz_bound_that_is_exceeded_is_reported_with_the_gradient_seen() {
    // 10 (|p - c| - R) changes by 10 per unit; declared 2, the marches see it.
    let steep = |lipschitz: f64| {
        let f: ImplicitFn = Arc::new(|p: Vec3| 10.0 * ((p - CENTER).length() - RADIUS));
        Implicit::new(f, Aabb::new(CENTER - Vec3::splat(2.0), CENTER + Vec3::splat(2.0)), lipschitz).unwrap()
    };
    // Rays from all around towards points near the centre.
    let mut rng = Rng::for_sample(4, 0, 0);
    let rays: Vec<Ray> = (0..200)
        .map(|_| {
            let origin = CENTER + unit_vector(&mut rng) * 6.0;
            Ray::new(origin, (CENTER + unit_vector(&mut rng) * 0.5 - origin).normalize())
        })
        .collect();
    let cast = |shape: &Implicit| rays.iter().filter(|r| shape.intersect(r, 0.0, f64::INFINITY).is_some()).count();
    let loose = steep(2.0);
    assert_eq!(cast(&loose), 0, "too small a bound makes the march jump past the surface");
    let warnings = loose.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let seen: f64 = warnings[0].rsplit(' ').next().unwrap().parse().unwrap();
    assert!(seen > 2.0 && seen <= 10.0 + 1e-9, "a secant slope of 10 |p - c| is at most 10: {}", warnings[0]);
    assert!(warnings[0].starts_with("implicit surface: f changed by "), "{}", warnings[0]);
    assert!(warnings[0].contains("above its lipschitz = 2: rays may miss parts of the surface; set lipschitz to at least"));
    // A clone (as a render's copies are) reports to the same place.
    assert_eq!(loose.clone().warnings(), warnings);
    let safe = steep(10.5);
    assert!(cast(&safe) > 150, "a true bound finds the surface");
    assert!(safe.warnings().is_empty(), "{:?}", safe.warnings());
    assert!(sdf_sphere().warnings().is_empty());
}
