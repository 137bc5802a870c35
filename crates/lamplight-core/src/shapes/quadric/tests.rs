//! Ray-intersection tests of [`Quadric`] against analytic values.

use super::*;
use crate::sampling::Rng;
use crate::shapes::Sphere;
use glam::{DQuat, DVec4};
use proptest::prelude::*;

const INF: f64 = f64::INFINITY;
const SQRT2: f64 = std::f64::consts::SQRT_2;

fn unit_sphere() -> Quadric {
    Quadric::new(Mat4::from_diagonal(DVec4::new(1.0, 1.0, 1.0, -1.0))).unwrap()
}

fn close(a: Vec3, b: Vec3, tol: f64) -> bool {
    (a - b).length() < tol
}

fn random_unit(rng: &mut Rng) -> Vec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let r = (1.0 - z * z).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

#[test]
fn miss_tangent_and_near_hit() {
    let s = unit_sphere();
    assert!(s.intersect(&Ray::new(Vec3::new(0.0, 1.0001, -3.0), Vec3::Z), 0.0, INF).is_none());
    let tangent = s.intersect(&Ray::new(Vec3::new(0.0, 1.0, -3.0), Vec3::Z), 0.0, INF).unwrap();
    assert!((tangent.t - 3.0).abs() < 1e-6);
    assert!(close(tangent.normal, Vec3::Y, 1e-6));
    let hit = s.intersect(&Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z), 0.0, INF).unwrap();
    assert_eq!((hit.t, hit.normal, hit.error), (2.0, -Vec3::Z, 0.0));
    assert!(s.intersect(&Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z), 0.0, 1.5).is_none(), "beyond t_max");
    assert!(s.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), Vec3::Z), 0.0, INF).is_none(), "behind the ray");
}

#[test]
fn ray_starting_inside_hits_far_side_with_outward_normal() {
    let hit = unit_sphere().intersect(&Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X), 0.0, INF).unwrap();
    assert!((hit.t - 0.5).abs() < 1e-15);
    assert!(close(hit.normal, Vec3::X, 1e-15), "outward, not flipped towards the ray");
}

#[test]
fn ellipsoid_hit_and_normal_match_the_analytic_gradient() {
    let (c, r) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 1.0, 0.5));
    let e = Quadric::ellipsoid(c, r).unwrap();
    let hit = e.intersect(&Ray::new(Vec3::new(-5.0, 2.0, 3.0), Vec3::X), 0.0, INF).unwrap();
    assert!((hit.t - 4.0).abs() < 1e-14 && close(hit.normal, -Vec3::X, 1e-14));
    // A slanted ray: in the scaled coordinates u = (p - c) / r the ellipsoid is the
    // unit sphere, |u0 + t w|^2 = 1 with u0 = (s - c) / r, w = d / r.
    let ray = Ray::new(Vec3::new(4.0, 5.0, -1.0), Vec3::new(-1.0, -1.2, 1.5));
    let (u0, w) = ((ray.origin - c) / r, ray.dir / r);
    let (a, b, cc) = (w.dot(w), u0.dot(w), u0.dot(u0) - 1.0);
    let t_expected = (-b - (b * b - a * cc).sqrt()) / a;
    let hit = e.intersect(&ray, 0.0, INF).unwrap();
    assert!((hit.t - t_expected).abs() < 1e-12, "{} vs {t_expected}", hit.t);
    let p = ray.at(hit.t);
    let gradient = ((p - c) / (r * r)).normalize(); // grad of sum ((p - c)_i / r_i)^2, halved
    assert!(close(hit.normal, gradient, 1e-12));
}

#[test]
fn cylinder_side_hit_and_rays_along_the_axis() {
    let cyl = Quadric::cylinder(Vec3::new(1.0, 0.0, 0.0), Vec3::Y, 0.5).unwrap();
    let hit = cyl.intersect(&Ray::new(Vec3::new(1.0, 7.0, -4.0), Vec3::new(0.0, 0.0, 1.0)), 0.0, INF).unwrap();
    assert!((hit.t - 3.5).abs() < 1e-14 && close(hit.normal, -Vec3::Z, 1e-14));
    let inside = Ray::new(Vec3::new(1.2, 0.0, 0.0), Vec3::Y);
    assert!(cyl.intersect(&inside, 0.0, INF).is_none(), "a = 0 and b = 0: never crosses");
    // A tilted axis gives a = d^T A d a few ulps from 0, not 0, of either sign:
    // no spurious root at t ~ sqrt(c / a) ~ 1e8 may appear.
    let mut rng = Rng::for_sample(3, 0, 0);
    for _ in 0..200 {
        let (axis, base) = (random_unit(&mut rng), random_unit(&mut rng));
        let tilted = Quadric::cylinder(base, axis, 0.5).unwrap();
        let (u, v) = crate::math::orthonormal_basis(axis);
        let origin = base + (u * rng.uniform() + v * rng.uniform()) * 0.3 + axis * (4.0 * rng.uniform() - 2.0);
        assert!(tilted.intersect(&Ray::unit(origin, axis), 0.0, INF).is_none());
        assert!(tilted.intersect(&Ray::unit(origin, -axis), 0.0, INF).is_none());
    }
}

#[test]
fn cone_nappes_segment_and_apex() {
    let cone = Quadric::cone(Vec3::ZERO, Vec3::Y, std::f64::consts::FRAC_PI_4).unwrap();
    let hit = cone.intersect(&Ray::new(Vec3::new(3.0, 1.0, 0.0), -Vec3::X), 0.0, INF).unwrap();
    assert!((hit.t - 2.0).abs() < 1e-14 && close(hit.normal, Vec3::new(1.0, -1.0, 0.0) / SQRT2, 1e-14));
    assert!(cone.intersect(&Ray::new(Vec3::new(3.0, -1.0, 0.0), -Vec3::X), 0.0, INF).is_some(), "lower nappe");
    let segment = Quadric::cone_segment(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 1.0).unwrap();
    let side = segment.intersect(&Ray::new(Vec3::new(3.0, 0.5, 0.0), -Vec3::X), 0.0, INF).unwrap();
    assert!((side.t - 2.5).abs() < 1e-14 && close(side.normal, Vec3::new(1.0, 1.0, 0.0) / SQRT2, 1e-14));
    assert!(segment.intersect(&Ray::new(Vec3::new(3.0, 1.5, 0.0), -Vec3::X), 0.0, INF).is_none(), "other nappe clipped");
    assert!(segment.intersect(&Ray::new(Vec3::new(3.0, -0.5, 0.0), -Vec3::X), 0.0, INF).is_none(), "below the base");
    // Straight down the axis onto the apex, a singular point: finite, unit normal.
    let apex = cone.intersect(&Ray::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y), 0.0, INF).unwrap();
    assert!((apex.t - 2.0).abs() < 1e-7 && (apex.normal.length() - 1.0).abs() < 1e-12);
}

#[test]
fn paraboloid_axis_ray_hits_the_apex_and_parallel_ray_hits_once() {
    // |v_perp|^2 = 4 f h with f = 1/4: y = x^2 + z^2.
    let p = Quadric::paraboloid(Vec3::ZERO, Vec3::Y, 0.25).unwrap();
    let down = p.intersect(&Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y), 0.0, INF).unwrap();
    assert!((down.t - 5.0).abs() < 1e-14 && close(down.normal, -Vec3::Y, 1e-14));
    let up = p.intersect(&Ray::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y), 0.0, INF).unwrap();
    assert!((up.t - 1.0).abs() < 1e-14 && close(up.normal, -Vec3::Y, 1e-14));
    // a == 0: parallel to the axis, off it, one crossing at y = 0.5^2.
    let ray = Ray::new(Vec3::new(0.5, 3.0, 0.0), -Vec3::Y);
    let once = p.intersect(&ray, 0.0, INF).unwrap();
    assert!((once.t - 2.75).abs() < 1e-14);
    assert!(close(once.normal, Vec3::new(1.0, -1.0, 0.0) / SQRT2, 1e-14));
    assert!(p.intersect(&ray, once.t + 1e-9, INF).is_none(), "no second root");
    assert!(p.intersect(&Ray::new(Vec3::new(0.5, 3.0, 0.0), Vec3::Y), 0.0, INF).is_none(), "moving away inside the bowl");
}

#[test]
fn open_cup_seen_from_the_rim_shows_its_inside() {
    // y = x^2 + z^2 for 0 <= y <= 1; focus (0, 1/4, 0), rim radius 1.
    let cup = Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.25, 1.0).unwrap();
    let focus = Vec3::new(0.0, 0.25, 0.0);
    // The line y = 0.75 - x meets the paraboloid at x = -1.5 (y = 2.25, above the
    // rim: clipped) and at x = 0.5 (y = 0.25, inside the cup).
    let ray = Ray::new(Vec3::new(-3.0, 3.75, 0.0), Vec3::new(1.0, -1.0, 0.0));
    let whole = Quadric::paraboloid(Vec3::ZERO, Vec3::Y, 0.25).unwrap().intersect(&ray, 0.0, INF).unwrap();
    assert!((whole.t - 1.5 * SQRT2).abs() < 1e-13, "unclipped: near root");
    let hit = cup.intersect(&ray, 0.0, INF).unwrap();
    assert!((hit.t - 3.5 * SQRT2).abs() < 1e-13, "clipped: far root, t = {}", hit.t);
    let p = ray.at(hit.t);
    // Convention: the normal is outward (+grad f), away from the focus side, so
    // from inside the cup it points away from the viewer.
    assert!(close(hit.normal, Vec3::new(1.0, -1.0, 0.0) / SQRT2, 1e-12));
    assert!(hit.normal.dot(p - focus) > 0.0 && hit.normal.dot(ray.dir) > 0.0);
    // From below, the outside of the cup shows, normal towards the viewer.
    let below = cup.intersect(&Ray::new(Vec3::new(0.5, -2.0, 0.0), Vec3::Y), 0.0, INF).unwrap();
    assert!((below.t - 2.25).abs() < 1e-14 && below.normal.dot(Vec3::Y) < 0.0);
    // Through the rim opening, past the cup entirely: a miss.
    assert!(cup.intersect(&Ray::new(Vec3::new(-3.0, 1.5, 0.0), Vec3::X), 0.0, INF).is_none());
}

#[test]
fn clipped_cylinder_is_an_open_tube() {
    let tube = Quadric::cylinder_segment(Vec3::ZERO, Vec3::Y, 0.5).unwrap();
    for x in [0.0, 0.2, -0.49] {
        assert!(tube.intersect(&Ray::new(Vec3::new(x, 3.0, 0.0), -Vec3::Y), 0.0, INF).is_none(), "through both ends");
    }
    // x = y - 1: crosses x = 0.5 at y = 1.5 (above the tube) and x = -0.5 at y = 0.5.
    let ray = Ray::new(Vec3::new(1.0, 2.0, 0.0), Vec3::new(-1.0, -1.0, 0.0));
    let hit = tube.intersect(&ray, 0.0, INF).unwrap();
    assert!((hit.t - 1.5 * SQRT2).abs() < 1e-13);
    assert!(close(hit.normal, -Vec3::X, 1e-13) && hit.normal.dot(ray.dir) > 0.0, "inner wall, outward normal");
    let outside = tube.intersect(&Ray::new(Vec3::new(2.0, 0.5, 0.0), -Vec3::X), 0.0, INF).unwrap();
    assert!((outside.t - 1.5).abs() < 1e-14 && close(outside.normal, Vec3::X, 1e-14));
}

#[test]
fn quadric_unit_sphere_agrees_with_sphere() {
    let (q, s) = (unit_sphere(), Sphere::new(Vec3::ZERO, 1.0).unwrap());
    let mut rng = Rng::for_sample(7, 0, 0);
    let mut hits = 0;
    for _ in 0..20_000 {
        let origin = random_unit(&mut rng) * (0.5 + 4.0 * rng.uniform());
        let target = random_unit(&mut rng) * 1.2 * rng.uniform();
        let ray = Ray::new(origin, target - origin);
        match (q.intersect(&ray, 0.0, INF), s.intersect(&ray, 0.0, INF)) {
            (Some(a), Some(b)) => {
                hits += 1;
                assert!((a.t - b.t).abs() < 1e-9, "{ray:?}: {} vs {}", a.t, b.t);
                assert!(close(a.normal, b.normal, 1e-8));
            }
            (None, None) => {}
            (a, b) => panic!("{ray:?}: quadric {a:?}, sphere {b:?}"),
        }
    }
    assert!(hits > 10_000, "{hits}");
}

#[test]
fn small_ellipsoid_far_away_keeps_precision() {
    let e = Quadric::ellipsoid(Vec3::new(0.0, 0.0, 1e6), Vec3::splat(1e-3)).unwrap();
    let hit = e.intersect(&Ray::new(Vec3::ZERO, Vec3::Z), 0.0, INF).unwrap();
    assert!((hit.t - (1e6 - 1e-3)).abs() < 1e-8, "t = {}", hit.t);
    let side = e.intersect(&Ray::new(Vec3::new(0.0, 0.9e-3, 0.0), Vec3::Z), 0.0, INF).unwrap();
    assert!((side.t - (1e6 - (1e-6f64 - 0.81e-6).sqrt())).abs() < 1e-8, "t = {}", side.t);
}

#[test]
fn transformed_quadric_matches_transformed_ray() {
    let m = Mat4::from_scale_rotation_translation(
        Vec3::new(1.5, 0.7, 2.0),
        DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.4),
        Vec3::new(0.5, -1.0, 2.0),
    ) * Mat4::from_cols_array(&[1.0, 0.0, 0.2, 0.0, 0.3, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let (m_inv, lin_inv) = (m.inverse(), DMat3::from_mat4(m.inverse()));
    let shapes = [
        Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.25, 1.0).unwrap(),
        Quadric::cylinder_segment(Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0), 0.4).unwrap(),
        Quadric::ellipsoid(Vec3::new(0.1, 0.2, 0.3), Vec3::new(1.0, 0.5, 0.8)).unwrap(),
    ];
    let mut rng = Rng::for_sample(11, 0, 0);
    for local in shapes {
        let world = local.transformed(m).unwrap();
        let b = world.bounds();
        let mut hits = 0;
        for _ in 0..2000 {
            let origin = b.centroid() + random_unit(&mut rng) * 2.0 * b.extent().length();
            let ray = Ray::new(origin, b.min + b.extent() * Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - origin);
            let local_ray = Ray::new(m_inv.transform_point3(ray.origin), lin_inv * ray.dir);
            match (world.intersect(&ray, 0.0, INF), local.intersect(&local_ray, 0.0, INF)) {
                (Some(w), Some(l)) => {
                    hits += 1;
                    let p = m.transform_point3(local_ray.at(l.t));
                    assert!(close(ray.at(w.t), p, 1e-9), "{} vs {p}", ray.at(w.t));
                    assert!(close(w.normal, (lin_inv.transpose() * l.normal).normalize(), 1e-7));
                    assert!(world.bounds().contains(p));
                }
                (None, None) => {}
                (w, l) => panic!("{ray:?}: world {w:?}, local {l:?}"),
            }
        }
        assert!(hits > 200, "{hits}");
    }
    assert!(unit_sphere().transformed(Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0))).is_err());
}

/// Random rays aimed at the box; every hit must lie inside it.
fn assert_hits_inside_bounds(q: &Quadric, seed: u64) {
    let b = q.bounds();
    assert!(b.is_finite(), "{b:?}");
    let (centre, size) = (b.centroid(), b.extent().length());
    let mut rng = Rng::for_sample(seed, 0, 0);
    let mut hits = 0;
    for _ in 0..4000 {
        let origin = centre + random_unit(&mut rng) * size * (0.2 + 2.0 * rng.uniform());
        let target = b.min + b.extent() * Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        let ray = Ray::new(origin, target - origin);
        let mut t_min = 0.0;
        while let Some(hit) = q.intersect(&ray, t_min, INF) {
            hits += 1;
            assert!(b.contains(ray.at(hit.t)), "{} outside {b:?}", ray.at(hit.t));
            t_min = hit.t;
        }
    }
    assert!(hits > 500, "{hits}");
}

#[test]
fn bounds_hold_every_hit() {
    let luxo_axis = Vec3::new(0.55, -1.35, 0.30).normalize();
    let shade = Quadric::paraboloid_cup(Vec3::new(-0.45, 1.35, -0.25), luxo_axis, 0.10, 0.25).unwrap();
    assert_hits_inside_bounds(&shade, 1);
    assert_hits_inside_bounds(&Quadric::cylinder_segment(Vec3::new(0.1, 0.0, 0.2), Vec3::new(-0.3, 0.9, 0.5), 0.025).unwrap(), 2);
    assert_hits_inside_bounds(&Quadric::cone_segment(Vec3::new(0.5, 1.0, 0.2), Vec3::new(0.4, 0.0, 0.3), 0.3).unwrap(), 3);
    let glass = Quadric::ellipsoid(Vec3::new(0.3, 0.2, -0.1), Vec3::new(0.2, 0.15, 0.1)).unwrap();
    assert_hits_inside_bounds(&glass, 4);
    let rotation = Mat4::from_rotation_translation(DQuat::from_rotation_z(0.7), Vec3::new(1.0, 0.0, 0.0));
    assert_hits_inside_bounds(&glass.transformed(rotation).unwrap(), 5);
    assert_hits_inside_bounds(&shade.transformed(rotation).unwrap(), 6);
    // An infinite cylinder made finite by an ellipsoid clip region.
    let ball = Quadric::ellipsoid(Vec3::new(0.0, 1.0, 0.0), Vec3::splat(2.0)).unwrap();
    let cut = Quadric::cylinder(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), 0.5).unwrap().with_clip(Clip::inside(&ball));
    assert_hits_inside_bounds(&cut, 7);
}

/// Random rays' hits, each in boxes from a billionth to the whole of the
/// shape's size placed around it (the hit at a corner, on a face or inside):
/// `may_meet` must be true for every one.
fn assert_may_meet_every_hit(q: &Quadric, seed: u64) {
    let b = q.bounds();
    let (centre, size) = (b.centroid(), b.extent().length());
    let mut rng = Rng::for_sample(seed, 0, 0);
    let mut hits = 0;
    for _ in 0..1500 {
        let origin = centre + random_unit(&mut rng) * size * (0.2 + 2.0 * rng.uniform());
        let target = b.min + b.extent() * Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        let ray = Ray::new(origin, target - origin);
        let mut t_min = 0.0;
        while let Some(hit) = q.intersect(&ray, t_min, INF) {
            hits += 1;
            let p = ray.at(hit.t);
            for _ in 0..4 {
                let extent = Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * size * 10f64.powf(-9.0 + 9.0 * rng.uniform());
                // Where the hit sits in the box: a corner, a face or inside.
                let at = match (rng.uniform() * 3.0) as u32 {
                    0 => Vec3::ZERO,
                    1 => Vec3::new(0.0, rng.uniform(), rng.uniform()),
                    _ => Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
                };
                let region = Aabb::new(p - extent * at, p - extent * at + extent);
                assert!(q.may_meet(&region), "hit {p} in {region:?}");
            }
            t_min = hit.t;
        }
    }
    assert!(hits > 200, "{hits}");
}

#[test]
fn may_meet_holds_every_hit_and_rules_out_boxes_off_the_surface() {
    let luxo_axis = Vec3::new(0.55, -1.35, 0.30).normalize();
    let (apex, focal) = (Vec3::new(-0.45, 1.35, -0.25), 0.10);
    let shade = Quadric::paraboloid_cup(apex, luxo_axis, focal, 0.25).unwrap();
    assert_may_meet_every_hit(&shade, 31);
    let rotation = Mat4::from_rotation_translation(DQuat::from_rotation_z(0.7), Vec3::new(1.0, 0.0, 0.0));
    assert_may_meet_every_hit(&shade.transformed(rotation).unwrap(), 32);
    assert_may_meet_every_hit(&Quadric::cone_segment(Vec3::new(0.5, 1.0, 0.2), Vec3::new(0.4, 0.0, 0.3), 0.3).unwrap(), 33);
    let ball = Quadric::ellipsoid(Vec3::new(0.0, 1.0, 0.0), Vec3::splat(2.0)).unwrap();
    let cut = Quadric::cylinder(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), 0.5).unwrap().with_clip(Clip::inside(&ball));
    assert_may_meet_every_hit(&cut, 34);
    let far = Quadric::ellipsoid(Vec3::new(3e5, -2e5, 1e5), Vec3::new(2.0, 1.0, 0.5)).unwrap();
    assert_may_meet_every_hit(&far, 35);
    // The bulb, at the focus, is a focal length from the surface, and the
    // mouth's middle farther; past the rim the clip rules the surface out.
    let focus = apex + luxo_axis * focal;
    assert!(!shade.may_meet(&Aabb::new(focus - Vec3::splat(0.03), focus + Vec3::splat(0.03))), "the bulb's box");
    let mouth = apex + luxo_axis * 0.25;
    assert!(!shade.may_meet(&Aabb::new(mouth - Vec3::splat(0.06), mouth + Vec3::splat(0.06))), "the mouth's middle");
    let past = apex + luxo_axis * 0.35;
    assert!(!shade.may_meet(&Aabb::new(past - Vec3::splat(0.04), past + Vec3::splat(0.04))), "past the rim");
    assert!(!shade.may_meet(&Aabb::new(Vec3::splat(5.0), Vec3::splat(6.0))), "far away");
    assert!(shade.may_meet(&Aabb::new(apex - Vec3::splat(0.01), apex + Vec3::splat(0.01))), "the apex");
}

#[test]
fn new_validates_and_symmetrizes() {
    assert!(Quadric::new(Mat4::from_diagonal(DVec4::new(1.0, 1.0, f64::NAN, -1.0))).is_err());
    assert!(Quadric::new(Mat4::from_diagonal(DVec4::new(0.0, 0.0, 0.0, -1.0))).is_err(), "constant f");
    assert!(Quadric::new(Mat4::IDENTITY).is_err(), "x^2 + y^2 + z^2 + 1 has no real point");
    // x y = 1 written with the whole coefficient in one corner.
    let mut q = Mat4::ZERO;
    q.y_axis.x = 2.0;
    q.w_axis.w = -2.0;
    let hyperbolic = Quadric::new(q).unwrap();
    let m = hyperbolic.matrix();
    assert_eq!(m, m.transpose());
    let hit = hyperbolic.intersect(&Ray::new(Vec3::new(2.0, 0.0, 5.0), Vec3::Y), 0.0, INF).unwrap();
    assert!((hit.t - 0.5).abs() < 1e-15, "x = 2 meets x y = 1 at y = 1/2");
    assert!(close(hit.normal, Vec3::new(0.5, 2.0, 0.0).normalize(), 1e-14), "grad (x y) = (y, x, 0)");
    assert!(close(
        hyperbolic.gradient(Vec3::new(2.0, 0.5, 0.0)) / hyperbolic.gradient(Vec3::new(2.0, 0.5, 0.0)).length(),
        hit.normal,
        1e-14
    ));
}

proptest! {
    #[test]
    fn hits_lie_on_the_surface_and_in_every_clip(
        entries in prop::array::uniform10(-1.0f64..1.0),
        origin in prop::array::uniform3(-4.0f64..4.0),
        dir in prop::array::uniform3(-1.0f64..1.0),
        clip_point in prop::array::uniform3(-1.0f64..1.0),
        clip_normal in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let [a, b, c, d, e, f, g, h, i, j] = entries;
        let q = Mat4::from_cols_array(&[a, b, c, d, b, e, f, g, c, f, h, i, d, g, i, j]);
        let Ok(quadric) = Quadric::new(q) else { return Ok(()) };
        let dir = Vec3::from_array(dir);
        prop_assume!(dir.length() > 1e-3);
        let quadric = match Clip::half_space(Vec3::from_array(clip_point), Vec3::from_array(clip_normal)) {
            Ok(clip) => quadric.with_clip(clip),
            Err(_) => quadric,
        };
        let ray = Ray::new(Vec3::from_array(origin), dir);
        if let Some(hit) = quadric.intersect(&ray, 1e-6, 100.0) {
            prop_assert!(hit.t > 1e-6 && hit.t < 100.0);
            let p = ray.at(hit.t);
            let scale = p.abs().max_element().max(ray.origin.abs().max_element()).max(1.0);
            let matrix_size = quadric.matrix().abs().to_cols_array().into_iter().fold(0.0, f64::max);
            let tolerance = 1e-9 * quadric.gradient(p).length() * scale + 1e-12 * matrix_size * scale * scale;
            prop_assert!(quadric.value(p).abs() <= tolerance, "f = {} at {p}, tolerance {tolerance}", quadric.value(p));
            prop_assert!(quadric.is_visible(p));
            prop_assert!((hit.normal.length() - 1.0).abs() < 1e-12);
        }
    }
}

/// `(u, v)` of the named quadrics at points built from the parametrization, and
/// `dp/du`, `dp/dv` against central differences of it.
#[test]
fn named_quadrics_have_surface_coordinates_of_revolution() {
    use crate::math::orthonormal_basis;
    use crate::shapes::Shape;
    let tau = std::f64::consts::TAU;
    let (p0, p1, r) = (Vec3::new(1.0, 0.0, -1.0), Vec3::new(1.0, 3.0, 1.0), 0.5);
    let axis = (p1 - p0).normalize();
    let (x, y) = orthonormal_basis(axis);
    let tube = Quadric::cylinder_segment(p0, p1, r).unwrap();
    let on_tube = |u: f64, v: f64| p0 + (p1 - p0) * v + (x * (u * tau).cos() + y * (u * tau).sin()) * r;
    let e = Quadric::ellipsoid(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let on_ellipsoid = |u: f64, v: f64| {
        let (phi, theta) = (u * tau, std::f64::consts::PI * (1.0 - v));
        Vec3::new(0.0, 1.0, 0.0) + Vec3::new(theta.sin() * phi.cos(), 2.0 * theta.sin() * phi.sin(), 3.0 * theta.cos())
    };
    let moved = tube
        .transformed(Mat4::from_scale_rotation_translation(Vec3::new(2.0, 1.0, 1.0), glam::DQuat::from_rotation_x(0.3), Vec3::X))
        .unwrap();
    let m = Mat4::from_scale_rotation_translation(Vec3::new(2.0, 1.0, 1.0), glam::DQuat::from_rotation_x(0.3), Vec3::X);
    let on_moved = |u: f64, v: f64| m.transform_point3(on_tube(u, v));
    type Parametrization<'a> = &'a dyn Fn(f64, f64) -> Vec3;
    let cases: [(&Quadric, Parametrization); 3] = [(&tube, &on_tube), (&e, &on_ellipsoid), (&moved, &on_moved)];
    for (q, at) in cases {
        for (u, v) in [(0.1, 0.2), (0.55, 0.5), (0.8, 0.9)] {
            let p = at(u, v);
            let n = q.gradient(p).normalize();
            let c = q.surface_coords(p, n, None);
            assert!((c.uv[0] - u).abs() < 1e-9 && (c.uv[1] - v).abs() < 1e-9, "{:?} vs ({u}, {v})", c.uv);
            let h = 1e-6;
            let (du, dv) = ((at(u + h, v) - at(u - h, v)) / (2.0 * h), (at(u, v + h) - at(u, v - h)) / (2.0 * h));
            assert!((c.dpdu - du).length() < 1e-6 * du.length(), "{} vs {du}", c.dpdu);
            assert!((c.dpdv - dv).length() < 1e-6 * dv.length(), "{} vs {dv}", c.dpdv);
        }
    }
}

/// The first visible crossing with both roots polished and tried in order: what
/// [`Quadric::crossing`] must answer, bit for bit, while polishing less.
fn crossing_polishing_both(q: &Quadric, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let (t0, t1) = q.roots(ray)?;
    [t0, t1].into_iter().find(|&t| t > t_min && t < t_max && q.is_visible(ray.at(t)))
}

#[test]
fn polishing_only_the_roots_that_matter_gives_the_same_bits() {
    let tilt = Mat4::from_rotation_translation(DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.2, 1.3), Vec3::new(3.0, -2.0, 0.5));
    let shapes = [
        Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.1, 0.25).unwrap(),
        Quadric::cylinder_segment(Vec3::ZERO, Vec3::new(0.3, 0.85, 0.15), 0.025).unwrap(),
        Quadric::cone_segment(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0), 0.5).unwrap(),
        Quadric::hyperboloid(Vec3::ZERO, Vec3::Z, 0.5, 1.0, Sheets::One).unwrap(),
        Quadric::hyperboloid(Vec3::ZERO, Vec3::Z, 0.5, 1.0, Sheets::Two).unwrap(),
        Quadric::ellipsoid(Vec3::new(0.1, 0.2, 0.3), Vec3::new(1.0, 0.5, 0.8)).unwrap(),
        Quadric::cylinder(Vec3::ZERO, Vec3::X, 1.0).unwrap(),
        Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.1, 0.25).unwrap().transformed(tilt).unwrap(),
        Quadric::cylinder_segment(Vec3::ZERO, Vec3::Y, 1e-3).unwrap().transformed(Mat4::from_translation(Vec3::splat(1e6))).unwrap(),
        Quadric::ellipsoid(Vec3::ZERO, Vec3::splat(1e4)).unwrap(),
    ];
    let mut rng = Rng::for_sample(24, 0, 0);
    let (mut hits, mut near_bounds) = (0, 0);
    for q in &shapes {
        let b = q.bounds();
        let (centre, size) = if b.is_finite() { ((b.min + b.max) * 0.5, (b.max - b.min).length()) } else { (Vec3::ZERO, 2.0) };
        for i in 0..6000 {
            // Origins from inside the box to far away; targets in the box, some
            // on the box's faces so that rays graze the surface and the clips.
            let scale = [0.1, 1.0, 10.0, 1e3][i % 4];
            let origin = centre + random_unit(&mut rng) * size * scale * rng.uniform();
            let mut target = centre + (Vec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5) * size;
            if i % 3 == 0 {
                target[i % 3] = if rng.uniform() < 0.5 { b.min[i % 3] } else { b.max[i % 3] };
            }
            let Some(ray) = Some(Ray::new(origin, target - origin)).filter(|r| r.dir.is_finite()) else { continue };
            let reference = crossing_polishing_both(q, &ray, 0.0, INF);
            assert_eq!(q.crossing(&ray, 0.0, INF).map(f64::to_bits), reference.map(f64::to_bits), "{ray:?}");
            // The AVX2 compilation that `Shape::intersect` takes where it can
            // answers as the baseline one, the normal included.
            #[cfg(target_arch = "x86_64")]
            if crate::cpu::avx2_features() {
                let bits = |h: Option<SurfaceHit>| h.map(|h| (h.t.to_bits(), h.normal.to_array().map(f64::to_bits)));
                // SAFETY: the CPU has AVX2 (checked above).
                let avx2 = unsafe { q.intersect_avx2(&ray, 0.0, INF) };
                assert_eq!(bits(avx2), bits(q.intersect_in(&ray, 0.0, INF)), "{ray:?}");
            }
            // Windows whose ends sit a few ulps from each polished root, where a
            // root's polishing decides whether it is inside.
            if let Some((t0, t1)) = q.roots(&ray) {
                for t in [t0, t1] {
                    for k in [-3.0, -1.0, 0.0, 1.0, 3.0] {
                        let edge = t * (1.0 + k * f64::EPSILON) + k * f64::MIN_POSITIVE;
                        for (lo, hi) in [(edge, INF), (0.0, edge), (edge, t1.abs() * 2.0 + 1.0)] {
                            let reference = crossing_polishing_both(q, &ray, lo, hi);
                            near_bounds += 1;
                            assert_eq!(q.crossing(&ray, lo, hi).map(f64::to_bits), reference.map(f64::to_bits), "{ray:?} in ({lo}, {hi})");
                        }
                    }
                }
            }
            hits += usize::from(reference.is_some());
        }
    }
    assert!(hits > 10_000 && near_bounds > 100_000, "{hits} hits, {near_bounds} windows at a root");
}
