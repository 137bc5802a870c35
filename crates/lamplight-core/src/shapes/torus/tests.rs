use super::*;
use crate::ray::offset_origin;
use crate::sampling::Rng;
use proptest::prelude::*;

const R: f64 = 2.0;
const TUBE: f64 = 0.5;

/// A tilted torus, with two unit vectors perpendicular to its axis and to each other.
fn tilted() -> (Torus, Vec3, Vec3) {
    let axis = Vec3::new(1.0, 2.0, 2.0) / 3.0;
    let torus = Torus::new(Vec3::new(1.0, -2.0, 3.0), axis, R, TUBE).unwrap();
    let u = axis.cross(Vec3::X).normalize();
    (torus, u, axis.cross(u))
}

fn hit(torus: &Torus, origin: Vec3, dir: Vec3) -> Option<SurfaceHit> {
    torus.intersect(&Ray::new(origin, dir), 0.0, f64::INFINITY)
}

/// The analytic outward normal at a world point of the surface: away from the tube's core circle.
fn analytic_normal(torus: &Torus, p: Vec3) -> Vec3 {
    let local = p - torus.center();
    let radial = (local - torus.axis() * local.dot(torus.axis())).normalize();
    (local - radial * torus.major_radius()).normalize()
}

/// A surface point at angles (around the axis, around the tube), with its normal.
fn surface_point(torus: &Torus, theta: f64, phi: f64) -> (Vec3, Vec3) {
    let (big, small) = (torus.major_radius(), torus.minor_radius());
    let local = Vec3::new((big + small * phi.cos()) * theta.cos(), (big + small * phi.cos()) * theta.sin(), small * phi.sin());
    let normal = torus.world_from_local(Vec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin()));
    (torus.center() + torus.world_from_local(local), normal)
}

#[test]
fn ray_along_the_axis_passes_through_the_hole() {
    let (torus, u, _) = tilted();
    assert!(hit(&torus, torus.center() - torus.axis() * 10.0, torus.axis()).is_none());
    // Parallel to the axis just inside the hole: still a miss.
    assert!(hit(&torus, torus.center() + u * (R - TUBE - 1e-6) - torus.axis() * 10.0, torus.axis()).is_none());
}

#[test]
fn hit_from_outside_at_the_analytic_distance() {
    let (torus, u, v) = tilted();
    for (dist, side) in [(10.0, u), (7.5, -v), (1e5, u)] {
        let h = hit(&torus, torus.center() + side * dist, -side).unwrap();
        let expected = dist - (R + TUBE);
        assert!((h.t - expected).abs() <= 1e-12 * dist.max(10.0), "t = {}, expected {expected}", h.t);
        assert!((h.normal - side).length() < 1e-9, "normal {} vs {side}", h.normal);
        assert_eq!(h.normal, h.shading_normal);
    }
}

#[test]
fn ray_starting_inside_the_tube() {
    let (torus, u, _) = tilted();
    let core = torus.center() + u * R;
    let out = hit(&torus, core, u).unwrap();
    assert!((out.t - TUBE).abs() < 1e-13 && (out.normal - u).length() < 1e-12);
    let inner = hit(&torus, core, -u).unwrap();
    assert!((inner.t - TUBE).abs() < 1e-13);
    assert!((inner.normal + u).length() < 1e-12, "outward at the inner equator points to the axis");
    let up = hit(&torus, core, torus.axis()).unwrap();
    assert!((up.t - TUBE).abs() < 1e-13 && (up.normal - torus.axis()).length() < 1e-12);
}

#[test]
fn tangent_rays_still_hit() {
    let (torus, u, v) = tilted();
    let a = torus.axis();
    // (start, direction, tangent point, normal there, tolerance on t). Along a
    // tangent the distance from the surface grows as the square of the offset from
    // the touching point, so rounding of size eps moves t by ~sqrt(eps); along the top
    // circle (a parabolic line, zero normal curvature) it grows as the fourth power
    // and t is only known to ~eps^(1/4).
    let cases = [
        (torus.center() + u * (R + TUBE) - v * 10.0, v, torus.center() + u * (R + TUBE), u, 1e-6), // outer equator
        (torus.center() + u * (R - TUBE) - a * 10.0, a, torus.center() + u * (R - TUBE), -u, 1e-6), // inside the hole
        (torus.center() + u * R + a * TUBE - v * 10.0, v, torus.center() + u * R + a * TUBE, a, 1e-2), // top circle
    ];
    for (origin, dir, touch, normal, tolerance) in cases {
        let h = hit(&torus, origin, dir).unwrap_or_else(|| panic!("tangent ray from {origin} missed"));
        let expected = (touch - origin).length();
        assert!((h.t - expected).abs() < tolerance, "t = {}, expected {expected}", h.t);
        assert!((h.normal - normal).length() < 1e-6, "normal {} vs {normal}", h.normal);
        assert!(h.error < 1e-12, "the point is on the surface: error {}", h.error);
    }
    // Just outside the outer equator: a miss.
    assert!(hit(&torus, torus.center() + u * (R + TUBE + 1e-7) - v * 10.0, v).is_none());
}

#[test]
fn interval_limits_and_far_side() {
    let (torus, u, _) = tilted();
    let origin = torus.center() + u * 10.0;
    // Along -u: tube at 7.5..8.5, hole, tube at 11.5..12.5.
    let ts: Vec<f64> =
        [0.0, 7.6, 8.6, 11.6].iter().map(|&t0| torus.intersect(&Ray::new(origin, -u), t0, f64::INFINITY).unwrap().t).collect();
    for (t, want) in ts.iter().zip([7.5, 8.5, 11.5, 12.5]) {
        assert!((t - want).abs() < 1e-12, "{ts:?}");
    }
    assert!(torus.intersect(&Ray::new(origin, -u), 0.0, 7.5 - 1e-9).is_none());
    assert!(torus.intersect(&Ray::new(origin, -u), 12.6, f64::INFINITY).is_none());
}

#[test]
fn bounds_are_tight() {
    let axis_z = Torus::new(Vec3::ZERO, Vec3::Z, R, TUBE).unwrap();
    assert_eq!(axis_z.bounds(), Aabb::new(Vec3::new(-2.5, -2.5, -0.5), Vec3::new(2.5, 2.5, 0.5)));
    let (torus, _, _) = tilted();
    let mut rng = Rng::for_sample(1, 0, 0);
    let b = torus.bounds();
    let mut reach = Vec3::ZERO;
    for _ in 0..20_000 {
        let (p, _) = surface_point(&torus, std::f64::consts::TAU * rng.uniform(), std::f64::consts::TAU * rng.uniform());
        assert!(b.contains(p));
        reach = reach.max((p - torus.center()).abs());
    }
    assert!(((b.max - torus.center()) - reach).max_element() < 0.01, "tight: {reach} vs {}", b.max - torus.center());
}

#[test]
fn spawned_rays_do_not_hit_their_own_surface() {
    let (torus, _, _) = tilted();
    let mut rng = Rng::for_sample(4, 0, 0);
    for _ in 0..5000 {
        let origin = torus.center() + Vec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 12.0;
        let (target, _) = surface_point(&torus, std::f64::consts::TAU * rng.uniform(), std::f64::consts::TAU * rng.uniform());
        let ray = Ray::new(origin, target - origin);
        let Some(h) = torus.intersect(&ray, 0.0, f64::INFINITY) else { continue };
        let point = ray.at(h.t);
        let reflected = ray.dir - 2.0 * ray.dir.dot(h.normal) * h.normal;
        for dir in [reflected, ray.dir] {
            let spawned = Ray::new(offset_origin(point, h.normal, dir, h.t, h.error), dir);
            if let Some(again) = torus.intersect(&spawned, 0.0, f64::INFINITY) {
                assert!(again.t > 1e-6, "self-intersection at t = {} from {point}", again.t);
            }
        }
    }
}

#[test]
fn rejects_bad_parameters() {
    assert!(Torus::new(Vec3::ZERO, Vec3::ZERO, 2.0, 0.5).is_err());
    assert!(Torus::new(Vec3::ZERO, Vec3::Z, 0.5, 0.5).is_err(), "horn torus");
    assert!(Torus::new(Vec3::ZERO, Vec3::Z, 2.0, 0.0).is_err());
    assert!(Torus::new(Vec3::ZERO, Vec3::Z, f64::INFINITY, 0.5).is_err());
    assert!(Torus::new(Vec3::splat(f64::NAN), Vec3::Z, 2.0, 0.5).is_err());
}

fn unit(rng_xyz: (f64, f64, f64)) -> Vec3 {
    Vec3::new(rng_xyz.0, rng_xyz.1, rng_xyz.2).normalize_or(Vec3::Z)
}

proptest! {
    // Seeded: the same cases on every run.
    #![proptest_config(ProptestConfig { cases: 2000, rng_seed: proptest::test_runner::RngSeed::Fixed(0x7040), ..ProptestConfig::default() })]

    /// A ray aimed at a surface point hits no later than that point, on the surface,
    /// with the analytic normal.
    #[test]
    fn rays_aimed_at_surface_points_hit_on_the_surface(
        theta in 0.0..std::f64::consts::TAU,
        phi in 0.0..std::f64::consts::TAU,
        from in (-1.0..1.0, -1.0..1.0, -1.0..1.0),
        dist in 0.3f64..50.0,
        axis in (-1.0..1.0, -1.0..1.0, -1.0..1.0),
        scale in prop::sample::select(vec![1e-3, 1.0, 1e4]),
        tube in prop::sample::select(vec![TUBE, 0.01, 1.9]),
    ) {
        let torus = Torus::new(Vec3::new(3.0, -1.0, 0.5) * scale, unit(axis), R * scale, tube * scale).unwrap();
        let (target, _) = surface_point(&torus, theta, phi);
        let origin = target + unit(from) * dist * scale;
        let ray = Ray::new(origin, target - origin);
        let to_target = (target - origin).length();
        let h = torus.intersect(&ray, 0.0, f64::INFINITY);
        prop_assert!(h.is_some(), "missed {target} from {origin}");
        let h = h.unwrap();
        prop_assert!(h.t <= to_target * (1.0 + 1e-9), "t = {} beyond the target at {to_target}", h.t);
        let p = ray.at(h.t);
        let local = torus.local_from_world(p - torus.center());
        let distance = torus.distance_local(local);
        prop_assert!(distance.abs() <= 1e-9 * scale, "off the surface by {distance}");
        // f itself is ~0 on the scale of its gradient (|grad f| ~ 8 R^2 r near the surface).
        prop_assert!(torus.implicit_local(local).abs() <= 1e-8 * 8.0 * R * R * tube * scale.powi(4));
        prop_assert!((h.normal - analytic_normal(&torus, p)).length() < 1e-6, "normal {}", h.normal);
        prop_assert!(h.error <= 1e-9 * scale);
    }
}

#[test]
fn surface_coordinates_at_known_points_and_their_derivatives() {
    let t = Torus::new(Vec3::new(1.0, -1.0, 2.0), Vec3::new(0.0, 1.0, 1.0), 2.0, 0.5).unwrap();
    let tau = std::f64::consts::TAU;
    let at = |u: f64, v: f64| {
        let (phi, theta) = (u * tau, v * tau);
        let local = Vec3::new((2.0 + 0.5 * theta.cos()) * phi.cos(), (2.0 + 0.5 * theta.cos()) * phi.sin(), 0.5 * theta.sin());
        t.center + t.world_from_local(local)
    };
    for (u, v) in [(0.1, 0.2), (0.6, 0.7), (0.3, 0.95)] {
        let p = at(u, v);
        let c = t.surface_coords(p, Vec3::Z, None);
        assert!((c.uv[0] - u).abs() < 1e-12 && (c.uv[1] - v).abs() < 1e-12, "{:?} vs ({u}, {v})", c.uv);
        let h = 1e-6;
        let (du, dv) = ((at(u + h, v) - at(u - h, v)) / (2.0 * h), (at(u, v + h) - at(u, v - h)) / (2.0 * h));
        assert!((c.dpdu - du).length() < 1e-6 * du.length(), "{} vs {du}", c.dpdu);
        assert!((c.dpdv - dv).length() < 1e-6 * dv.length(), "{} vs {dv}", c.dpdv);
    }
}
