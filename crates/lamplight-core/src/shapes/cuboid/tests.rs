use super::*;
use crate::lights::AreaLight;
use crate::math::Rgb;
use crate::sampling::Rng;
use crate::shapes::Rectangle;
use std::sync::Arc;

const INF: f64 = f64::INFINITY;

fn unit_box() -> Cuboid {
    Cuboid::new(Vec3::ZERO, Vec3::ONE, Mat4::IDENTITY).unwrap()
}

fn unit_vector(rng: &mut Rng) -> Vec3 {
    let z = 2.0 * rng.uniform() - 1.0;
    let phi = std::f64::consts::TAU * rng.uniform();
    let s = (1.0 - z * z).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// A rotated, non-uniformly scaled and translated placement, and a sheared one
/// (both with a positive determinant, so that `Rectangle::box_faces` keeps its
/// normals outward).
fn placements() -> [Mat4; 2] {
    let rotated = Mat4::from_translation(Vec3::new(0.3, -0.7, 1.1))
        * Mat4::from_axis_angle(Vec3::new(1.0, 2.0, -0.5).normalize(), 0.8)
        * Mat4::from_scale(Vec3::new(0.4, 1.3, 0.7));
    let shear = Mat4::from_cols_array_2d(&[[1.0, 0.0, 0.0, 0.0], [0.6, 1.0, 0.0, 0.0], [-0.3, 0.25, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]);
    [rotated, rotated * shear]
}

#[test]
fn axis_rays_into_a_unit_box_hit_at_exact_parameters() {
    let b = unit_box();
    let centre = Vec3::splat(0.5);
    // From two units outside each face, straight at the centre: t = 1.5 exactly,
    // normal = the face's axis; from the centre the ray leaves at t = 0.5.
    for (face, axis) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].into_iter().enumerate() {
        let outside = b.intersect(&Ray::new(centre + axis * 2.0, -axis), 0.0, INF).unwrap();
        assert_eq!((outside.t, outside.normal, outside.shading_normal, outside.error), (1.5, axis, axis, 0.0));
        let inside = b.intersect(&Ray::new(centre, axis), 0.0, INF).unwrap();
        assert_eq!((inside.t, inside.normal), (0.5, axis), "a ray starting inside hits the exit face");
        assert_eq!(b.face_normal(face), axis);
    }
    let near = Ray::new(Vec3::new(0.5, 0.5, -2.0), Vec3::Z);
    assert_eq!(b.intersect(&near, 0.0, INF).unwrap().t, 2.0);
    assert_eq!(b.intersect(&near, 2.5, INF).unwrap().t, 3.0, "past the entry, the exit");
    assert!(b.intersect(&near, 0.0, 2.0).is_none(), "open interval: t_max = entry misses");
    assert!(b.intersect(&near, 3.0, INF).is_none(), "open interval: t_min = exit misses");
    assert!(!b.intersect_p(&near, 3.0, INF) && b.intersect_p(&near, 0.0, INF));
    assert!(b.intersect(&Ray::new(Vec3::new(1.5, 0.5, -2.0), Vec3::Z), 0.0, INF).is_none());
    assert!(b.intersect(&Ray::new(Vec3::new(0.5, 0.5, 2.0), Vec3::Z), 0.0, INF).is_none(), "box behind the ray");
    // Scaled by 2 along x and moved to x in [1, 5]: the parameter stays the world one.
    let placed =
        Cuboid::new(-Vec3::ONE, Vec3::ONE, Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0)) * Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0)))
            .unwrap();
    let hit = placed.intersect(&Ray::new(Vec3::ZERO, Vec3::X), 0.0, INF).unwrap();
    assert_eq!((hit.t, hit.normal), (1.0, -Vec3::X));
    assert_eq!(placed.intersect(&Ray::new(Vec3::new(3.0, 0.0, 0.0), Vec3::X), 0.0, INF).unwrap().t, 2.0);
    assert_eq!(placed.primitive_count(), 1);
}

#[test]
fn matches_the_six_rectangles_of_the_same_box_on_random_rays() {
    let (min, max) = (Vec3::new(-1.0, -0.5, -2.0), Vec3::new(1.5, 0.5, 1.0));
    let mut rng = Rng::for_sample(17, 0, 0);
    for m in placements() {
        let cuboid = Cuboid::new(min, max, m).unwrap();
        let faces = Rectangle::box_faces(min, max, &m).unwrap();
        let (mut hits, mut from_inside) = (0, 0);
        for i in 0..4000 {
            // Aim at a point around the box so that most rays hit; every fourth ray
            // starts inside the box, some start on the far side of t_min.
            let local = |rng: &mut Rng| min + (max - min) * Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
            let target =
                m.transform_point3(min + (max - min) * Vec3::new(1.4 * rng.uniform() - 0.2, 1.4 * rng.uniform() - 0.2, rng.uniform()));
            let origin = if i % 4 == 0 { m.transform_point3(local(&mut rng)) } else { target + unit_vector(&mut rng) * 6.0 };
            let ray = Ray::new(origin, target - origin);
            let t_min = if i % 4 != 0 && i % 7 == 0 { 2.0 } else { 0.0 };
            let expected = faces
                .iter()
                .enumerate()
                .filter_map(|(k, f)| f.intersect(&ray, t_min, INF).map(|h| (h, k)))
                .min_by(|a, b| a.0.t.total_cmp(&b.0.t));
            let got = cuboid.intersect(&ray, t_min, INF);
            assert_eq!(got.is_some(), expected.is_some(), "ray {i} {ray:?}: {got:?} vs {expected:?}");
            assert_eq!(cuboid.intersect_p(&ray, t_min, INF), got.is_some());
            if let (Some(got), Some((want, face))) = (got, expected) {
                hits += 1;
                from_inside += usize::from(i % 4 == 0);
                assert!((got.t - want.t).abs() <= 1e-9 * want.t, "ray {i}: t {} vs {}", got.t, want.t);
                assert!((got.normal - want.normal).length() < 1e-12, "ray {i}: normal {} vs {}", got.normal, want.normal);
                assert_eq!(got.normal, cuboid.face_normal(face));
                // Same answer for a t_max just past the hit, none for one just before.
                assert!(cuboid.intersect(&ray, t_min, got.t * (1.0 + 1e-12)).is_some());
                assert!(cuboid.intersect(&ray, t_min, got.t * (1.0 - 1e-12)).is_none());
            }
        }
        assert!(hits > 2500 && from_inside == 1000, "{hits} hits, {from_inside} from inside");
    }
}

#[test]
fn rays_in_a_face_plane_or_along_an_edge_are_deterministic() {
    let b = Cuboid::new(-Vec3::ONE, Vec3::ONE, Mat4::IDENTITY).unwrap();
    // Zero direction components of either sign (1/d = +inf or -inf), origin exactly
    // on the slab plane (0 * inf): the ray lies in the closed face and enters
    // through the -z face.
    for dir in [Vec3::Z, Vec3::new(-0.0, -0.0, 1.0), Vec3::new(0.0, -0.0, 1.0)] {
        for origin in [Vec3::new(1.0, 0.0, -5.0), Vec3::new(-1.0, 0.3, -5.0), Vec3::new(1.0, 1.0, -5.0), Vec3::new(-1.0, -1.0, -5.0)] {
            let hit = b.intersect(&Ray::unit(origin, dir), 0.0, INF).unwrap();
            assert_eq!((hit.t, hit.normal), (4.0, -Vec3::Z), "{origin} along {dir}");
            assert!(hit.normal.is_finite());
            // From inside the face plane, already within the box's z range: the exit.
            let inside = b.intersect(&Ray::unit(Vec3::new(origin.x, origin.y, 0.0), dir), 0.0, INF).unwrap();
            assert_eq!((inside.t, inside.normal), (1.0, Vec3::Z));
        }
        // In the plane of a face but beside it: a miss, not a NaN.
        assert!(b.intersect(&Ray::unit(Vec3::new(1.0, 2.0, -5.0), dir), 0.0, INF).is_none());
        assert!(b.intersect(&Ray::unit(Vec3::new(1.0 + 1e-12, 0.0, -5.0), dir), 0.0, INF).is_none());
        assert!(b.intersect(&Ray::unit(Vec3::new(1.0 - 1e-12, 0.0, -5.0), dir), 0.0, INF).is_some());
    }
    // Along a face in x (non-zero x component): enters through the -x face.
    let along = b.intersect(&Ray::new(Vec3::new(-5.0, 1.0, 1.0), Vec3::X), 0.0, INF).unwrap();
    assert_eq!((along.t, along.normal), (4.0, -Vec3::X));
    // Through a corner exactly: entry planes x, y and z all at t = 1; the x slab wins the tie.
    let corner = b.intersect(&Ray::unit(Vec3::splat(-2.0), Vec3::splat(1.0)), 0.0, INF).unwrap();
    assert_eq!((corner.t, corner.normal), (1.0, -Vec3::X));
}

#[test]
fn bounds_are_the_box_around_the_placed_corners() {
    let b = Cuboid::new(-Vec3::ONE, Vec3::ONE, Mat4::from_rotation_z(std::f64::consts::FRAC_PI_4)).unwrap().bounds();
    let r2 = 2f64.sqrt();
    assert!((b.min - Vec3::new(-r2, -r2, -1.0)).length() < 1e-15 && (b.max - Vec3::new(r2, r2, 1.0)).length() < 1e-15, "{b:?}");
    let (min, max) = (Vec3::new(-1.0, -0.5, -2.0), Vec3::new(1.5, 0.5, 1.0));
    for m in placements() {
        let b = Cuboid::new(min, max, m).unwrap().bounds();
        let corners: Vec<Vec3> = (0..8)
            .map(|i| m.transform_point3(Vec3::new([min.x, max.x][i & 1], [min.y, max.y][(i >> 1) & 1], [min.z, max.z][i >> 2])))
            .collect();
        for c in &corners {
            assert!(b.contains(*c));
        }
        for axis in 0..3 {
            assert!(corners.iter().any(|c| c[axis] == b.min[axis]) && corners.iter().any(|c| c[axis] == b.max[axis]), "tight on {axis}");
        }
    }
}

#[test]
fn constructor_rejects_bad_input() {
    assert!(Cuboid::new(Vec3::ONE, Vec3::ZERO, Mat4::IDENTITY).is_err());
    assert!(Cuboid::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0), Mat4::IDENTITY).is_err(), "flat box");
    assert!(Cuboid::new(Vec3::new(f64::NAN, 0.0, 0.0), Vec3::ONE, Mat4::IDENTITY).is_err());
    assert!(Cuboid::new(Vec3::ZERO, Vec3::new(INF, 1.0, 1.0), Mat4::IDENTITY).is_err());
    assert!(Cuboid::new(Vec3::ZERO, Vec3::ONE, Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0))).is_err(), "singular");
    let mut projective = Mat4::IDENTITY;
    projective.x_axis.w = 0.5;
    assert!(Cuboid::new(Vec3::ZERO, Vec3::ONE, projective).is_err());
    let mut nan = Mat4::IDENTITY;
    nan.w_axis.x = f64::NAN;
    assert!(Cuboid::new(Vec3::ZERO, Vec3::ONE, nan).is_err());
}

#[test]
fn area_sums_the_placed_faces() {
    let scaled = Cuboid::new(Vec3::ZERO, Vec3::ONE, Mat4::from_scale(Vec3::new(2.0, 3.0, 4.0))).unwrap();
    assert!((scaled.area().unwrap() - 52.0).abs() < 1e-12, "2 (6 + 8 + 12)");
    // x += k y: the +-x faces become parallelograms of area sqrt(1 + k^2).
    let k = 0.75;
    let shear = Mat4::from_cols_array_2d(&[[1.0, 0.0, 0.0, 0.0], [k, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [5.0, 0.0, 0.0, 1.0]]);
    let sheared = Cuboid::new(Vec3::ZERO, Vec3::ONE, shear).unwrap();
    assert!((sheared.area().unwrap() - 2.0 * (1.25 + 2.0)).abs() < 1e-12);
    for m in placements() {
        let c = Cuboid::new(Vec3::new(-1.0, -0.5, -2.0), Vec3::new(1.5, 0.5, 1.0), m).unwrap();
        let faces = Rectangle::box_faces(c.min(), c.max(), &m).unwrap();
        let sum: f64 = faces.iter().map(|f| f.area().unwrap()).sum();
        assert!((c.area().unwrap() - sum).abs() < 1e-12 * sum);
    }
}

#[test]
fn area_samples_lie_on_the_surface_with_outward_normals_and_faces_by_area() {
    let (min, max) = (Vec3::new(-1.0, -0.5, -2.0), Vec3::new(1.5, 0.5, 1.0));
    for m in placements() {
        let c = Cuboid::new(min, max, m).unwrap();
        let faces = Rectangle::box_faces(min, max, &m).unwrap();
        let inverse = m.inverse();
        let n = 6000;
        let mut counts = [0usize; 6];
        let mut rng = Rng::for_sample(23, 0, 0);
        for i in 0..n {
            let u = ((i as f64 + 0.5) / n as f64, rng.uniform());
            let (p, normal) = c.sample_area(u).unwrap();
            let local = inverse.transform_point3(p);
            assert!(local.cmpge(min - 1e-12).all() && local.cmple(max + 1e-12).all(), "{local} inside the box");
            let face = (0..6).find(|&k| c.face_normal(k) == normal).unwrap();
            let axis = face / 2;
            let plane = if face % 2 == 0 { max[axis] } else { min[axis] };
            assert!((local[axis] - plane).abs() < 1e-12, "{local} on face {face}");
            assert!((normal - faces[face].normal()).length() < 1e-12, "outward normal of face {face}");
            // A ray back along the normal from just outside meets the box at p.
            let hit = c.intersect(&Ray::unit(p + normal * 1e-3, -normal), 0.0, INF).unwrap();
            assert!((hit.t - 1e-3).abs() < 1e-9 && hit.normal == normal);
            counts[face] += 1;
        }
        let total = c.area().unwrap();
        for (face, count) in counts.into_iter().enumerate() {
            // u.0 is stratified, so each face's share is exact up to one sample.
            let expected = n as f64 * faces[face].area().unwrap() / total;
            assert!((count as f64 - expected).abs() <= 1.0, "face {face}: {count} of {n}, expected {expected}");
        }
    }
}

#[test]
fn emitting_box_light_integrates_the_solid_angle_of_its_visible_face() {
    // From (0, 0, 3), the cube [-1, 1]^3 shows only its +z face, a 2 x 2 square at
    // distance 2: solid angle 4 atan(a b / (d sqrt(d^2 + a^2 + b^2))) with a = b = 1.
    let light = AreaLight::new(0, Arc::new(Cuboid::new(-Vec3::ONE, Vec3::ONE, Mat4::IDENTITY).unwrap()), Rgb::ONE).unwrap();
    assert!((light.area() - 24.0).abs() < 1e-12);
    let x = Vec3::new(0.0, 0.0, 3.0);
    let n = 600;
    let mut omega = 0.0;
    for i in 0..n {
        for j in 0..n {
            if let Some(s) = light.sample(x, ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64)) {
                let hit = light.shape.intersect(&Ray::unit(x, s.wi), 0.0, INF).unwrap();
                assert!((hit.t - s.distance).abs() < 1e-9, "a front-facing point of a convex box is visible");
                assert!((light.pdf(s.wi, hit.t, hit.normal) - s.pdf).abs() < 1e-9 * s.pdf);
                omega += 1.0 / s.pdf;
            }
        }
    }
    omega /= (n * n) as f64;
    let expected = 4.0 * (1.0f64 / (2.0 * 6f64.sqrt())).atan();
    assert!((omega - expected).abs() / expected < 2e-3, "{omega} vs {expected}");
}

#[test]
fn each_face_is_the_unit_square_with_outward_tangents() {
    for m in placements() {
        let b = Cuboid::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 3.0, 3.0), m).unwrap();
        let mut rng = Rng::for_sample(5, 0, 0);
        for _ in 0..200 {
            let (p, n) = b.sample_area((rng.uniform(), rng.uniform())).unwrap();
            let c = b.surface_coords(p, n, None);
            assert!(c.uv.iter().all(|x| (0.0..=1.0).contains(x)), "{:?}", c.uv);
            assert!(c.dpdu.cross(c.dpdv).dot(n) > 0.0, "dp/du x dp/dv must point out of the box");
            // Moving by the tangents reproduces the point from the face's corner: p(u, v) is affine.
            let corner = p - c.dpdu * c.uv[0] - c.dpdv * c.uv[1];
            let again = b.surface_coords(corner + c.dpdu * 0.5 + c.dpdv * 0.25, n, None);
            assert!((again.uv[0] - 0.5).abs() < 1e-9 && (again.uv[1] - 0.25).abs() < 1e-9, "{:?}", again.uv);
        }
    }
}
