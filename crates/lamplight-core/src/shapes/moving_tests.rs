use std::f64::consts::FRAC_PI_2;

use super::*;
use crate::shapes::{Cuboid, Sphere};

const INF: f64 = f64::INFINITY;

fn at(origin: Vec3, dir: Vec3, time: f64) -> Ray {
    Ray { origin, dir: dir.normalize(), time }
}

fn unit_sphere() -> Arc<dyn Shape> {
    Arc::new(Sphere::new(Vec3::ZERO, 0.5).unwrap())
}

#[test]
fn a_sphere_at_constant_velocity_is_where_its_time_puts_it() {
    // Moves +2 in x over the shutter [0, 1]: at time s its centre is (2 s, 0, 0).
    let motion = [(0.0, Mat4::IDENTITY), (1.0, Mat4::from_translation(Vec3::new(2.0, 0.0, 0.0)))];
    let moving = MovingInstance::new(unit_sphere(), &motion).unwrap();
    for s in [0.0, 0.25, 0.5, 0.9, 1.0] {
        let centre = Vec3::new(2.0 * s, 0.0, 0.0);
        let hit = moving.intersect(&at(centre + Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, s), 0.0, INF).unwrap();
        assert!((hit.t - 4.5).abs() < 1e-12, "time {s}: t {}", hit.t);
        assert!((hit.normal - Vec3::Z).length() < 1e-12);
        // Off the centre by 0.3 in x: the sphere's height there.
        let hit = moving.intersect(&at(centre + Vec3::new(0.3, 0.0, 5.0), -Vec3::Z, s), 0.0, INF).unwrap();
        assert!((hit.t - (5.0 - 0.4)).abs() < 1e-12, "time {s}: t {}", hit.t);
        assert!((hit.normal - Vec3::new(0.6, 0.0, 0.8)).length() < 1e-12);
    }
    // x = 1.6 is covered from time 0.55 (the near edge, 2 s + 0.5 > 1.6) on.
    let down = |s: f64| at(Vec3::new(1.6, 0.0, 5.0), -Vec3::Z, s);
    assert!(!moving.intersect_p(&down(0.5), 0.0, INF));
    assert!(moving.intersect_p(&down(0.6), 0.0, INF));
    // Times outside the keys hold the ends.
    assert!(moving.intersect_p(&at(Vec3::new(2.0, 0.0, 5.0), -Vec3::Z, 3.0), 0.0, INF));
    assert!(moving.intersect_p(&at(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, -1.0), 0.0, INF));
    // The bounds are the two ends' boxes: x from -0.5 to 2.5.
    let b = moving.bounds();
    assert!((b.min.x + 0.5).abs() < 1e-6 && (b.max.x - 2.5).abs() < 1e-6 && (b.max.y - 0.5).abs() < 1e-6, "{b:?}");
    assert!(moving.moves());
}

#[test]
fn a_turning_box_is_slerped_about_its_centre() {
    // A unit cube centred at (3, 0, 0) turns a quarter about z over [0, 1],
    // about its own centre: at time 0.5 it stands at 45 degrees, its corner
    // reaching x = 3 + sqrt(1/2).
    let cube: Arc<dyn Shape> = Arc::new(Cuboid::new(Vec3::new(2.5, -0.5, -0.5), Vec3::new(3.5, 0.5, 0.5), Mat4::IDENTITY).unwrap());
    let about = |m: Mat4| Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0)) * m * Mat4::from_translation(Vec3::new(-3.0, 0.0, 0.0));
    let motion = [(0.0, Mat4::IDENTITY), (1.0, about(Mat4::from_rotation_z(FRAC_PI_2)))];
    let moving = MovingInstance::new(cube, &motion).unwrap();
    let corner = 3.0 + 0.5f64.sqrt();
    let down = |x: f64, s: f64| at(Vec3::new(x, 0.0, 5.0), -Vec3::Z, s);
    assert!(moving.intersect_p(&down(corner - 1e-6, 0.5), 0.0, INF));
    assert!(!moving.intersect_p(&down(corner + 1e-6, 0.5), 0.0, INF));
    assert!(!moving.intersect_p(&down(3.6, 0.0), 0.0, INF));
    assert!(!moving.intersect_p(&down(3.6, 1.0), 0.0, INF));
    // Sideways at time 0.5 along -x, just above the corner: the face turned to 45 degrees.
    let hit = moving.intersect(&at(Vec3::new(10.0, 0.1, 0.0), -Vec3::X, 0.5), 0.0, INF).unwrap();
    let expected = Vec3::new(1.0, 1.0, 0.0).normalize();
    assert!((hit.normal - expected).length() < 1e-9, "{}", hit.normal);
    // The point is on that face, 1/2 from the centre along its normal: (x - 3) + y = sqrt(1/2).
    let p = Vec3::new(10.0, 0.1, 0.0) - Vec3::X * hit.t;
    assert!(((p.x - 3.0) + p.y - 0.5f64.sqrt()).abs() < 1e-9, "{p}");
}

#[test]
fn the_bounds_hold_the_shape_at_every_instant() {
    // Translation, a turn about a tilted axis and a growing stretch together,
    // over five keys: points of the surface at many instants are inside.
    let sphere: Arc<dyn Shape> = Arc::new(Sphere::new(Vec3::new(1.0, 2.0, -1.0), 0.7).unwrap());
    let axis = Vec3::new(1.0, 2.0, 0.5).normalize();
    let key = |s: f64| {
        Mat4::from_translation(Vec3::new(4.0 * s, -s, 2.0 * s * s))
            * Mat4::from_axis_angle(axis, 2.5 * s)
            * Mat4::from_scale(Vec3::new(1.0 + s, 1.0, 1.0 - 0.5 * s))
    };
    let motion: Vec<(f64, Mat4)> = (0..5).map(|k| (k as f64 * 0.25, key(k as f64 * 0.25))).collect();
    let moving = MovingInstance::new(sphere.clone(), &motion).unwrap();
    let b = moving.bounds();
    let mut rng = crate::sampling::Rng::for_sample(7, 0, 0);
    for _ in 0..20_000 {
        let s = rng.uniform();
        let (p, _) = sphere.sample_area((rng.uniform(), rng.uniform())).unwrap();
        let pose = moving.pose(s);
        let q = moving.centre + pose.translation + pose.linear * (p - moving.centre);
        assert!(q.cmpge(b.min).all() && q.cmple(b.max).all(), "time {s}: {q} outside {b:?}");
        // And a ray at that instant towards the point finds the surface no farther.
        let from = q + Vec3::new(0.0, 0.0, 20.0);
        let hit = moving.intersect(&at(from, q - from, s), 0.0, INF).expect("the point is on the surface");
        assert!(hit.t <= (q - from).length() + 1e-7);
    }
}

#[test]
fn surface_coordinates_are_read_where_the_shape_stood() {
    // A moving sphere's (u, v) at time s equal the still sphere's at the point moved back.
    let still = unit_sphere();
    let motion = [(0.0, Mat4::IDENTITY), (2.0, Mat4::from_translation(Vec3::new(0.0, 4.0, 0.0)))];
    let moving = MovingInstance::new(still.clone(), &motion).unwrap();
    let s = 1.5;
    let ray = at(Vec3::new(0.2, 3.0 + 0.1, 5.0), -Vec3::Z, s);
    let hit = moving.intersect(&ray, 0.0, INF).unwrap();
    let p = ray.at(hit.t);
    let moved = moving.surface_coords_at(p, hit.normal, hit.primitive(), s);
    let back = still.surface_coords(p - Vec3::new(0.0, 3.0, 0.0), hit.normal, hit.primitive());
    assert!((moved.uv[0] - back.uv[0]).abs() < 1e-12 && (moved.uv[1] - back.uv[1]).abs() < 1e-12, "{:?} vs {:?}", moved.uv, back.uv);
}

#[test]
fn bad_motion_is_refused_with_its_reason() {
    let one = [(0.0, Mat4::IDENTITY)];
    let e = MovingInstance::new(unit_sphere(), &one).unwrap_err().to_string();
    assert!(e.contains("needs 2 to 1024 keys, got 1"), "{e}");
    let backwards = [(1.0, Mat4::IDENTITY), (0.0, Mat4::IDENTITY)];
    let e = MovingInstance::new(unit_sphere(), &backwards).unwrap_err().to_string();
    assert!(e.contains("finite and increasing"), "{e}");
    let mirror = [(0.0, Mat4::IDENTITY), (1.0, Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)))];
    let e = MovingInstance::new(unit_sphere(), &mirror).unwrap_err().to_string();
    assert!(e.contains("the motion at time 1 mirrors the shape"), "{e}");
    let flat = [(0.0, Mat4::IDENTITY), (1.0, Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0)))];
    let e = MovingInstance::new(unit_sphere(), &flat).unwrap_err().to_string();
    assert!(e.contains("squashes the shape"), "{e}");
}

#[test]
fn polar_decomposition_splits_turn_and_stretch() {
    let q = Quat::from_axis_angle(Vec3::new(0.3, -1.0, 0.2).normalize(), 1.1);
    let s = Mat3::from_cols(Vec3::new(2.0, 0.3, 0.1), Vec3::new(0.3, 1.5, -0.2), Vec3::new(0.1, -0.2, 0.8));
    let (rotation, stretch) = polar(Mat3::from_quat(q) * s);
    assert!(rotation.dot(q).abs() > 1.0 - 1e-12, "{rotation} vs {q}");
    assert!((stretch - s).to_cols_array().iter().all(|x| x.abs() < 1e-12), "{stretch}");
}
