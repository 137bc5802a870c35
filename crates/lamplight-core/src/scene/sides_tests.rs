//! [`Sides`]: which normal decides a hit's side where a mesh's shading normal
//! faces away from a ray that the geometry faces.

use super::*;
use crate::camera::{Fov, Perspective};
use crate::materials::Material;
use crate::ray::Ray;
use crate::shapes::TriangleMesh;

/// A triangle in the plane `z = 0`, facing `+z`, whose vertex normals all lean
/// 80 degrees towards `+x`; a ray down from `+z` at 30 degrees from `-x` sees its
/// front by the geometry and its back by the shading normal.
fn leaning(sides: Sides) -> (Scene, Ray) {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut builder = SceneBuilder::new(camera);
    builder.settings.sides = sides;
    let one_sided = builder.material(Material { one_sided: true, ..Material::default() }).unwrap();
    let lean = Vec3::new(80f64.to_radians().sin(), 0.0, 80f64.to_radians().cos());
    let positions = vec![Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let mesh = TriangleMesh::new(positions, vec![[0, 1, 2]], Some(vec![lean; 3])).unwrap();
    builder.object(mesh, one_sided).unwrap();
    let dir = Vec3::new(30f64.to_radians().cos(), 0.0, -30f64.to_radians().sin());
    (builder.build().unwrap(), Ray::unit(Vec3::new(0.0, 0.0, 0.0) - dir * 4.0, dir))
}

#[test]
fn geometric_sides_keep_the_front_and_shade_with_the_geometric_normal() {
    let (scene, ray) = leaning(Sides::Geometric);
    let hit = scene.first_intersect(&ray, f64::INFINITY).unwrap();
    assert!(hit.front_face);
    assert_eq!(hit.normal, Vec3::Z);
    assert_eq!(hit.geometric_normal, Vec3::Z);
    assert!(!crate::scene::surface_bsdf(&scene.materials[hit.material], hit.point, hit.front_face).is_black());
}

#[test]
fn shading_sides_see_the_back_of_a_one_sided_material_as_mitsuba_does() {
    let (scene, ray) = leaning(Sides::Shading);
    let hit = scene.first_intersect(&ray, f64::INFINITY).unwrap();
    assert!(!hit.front_face, "the shading normal faces away from the ray");
    // Turned to face the ray, as Mitsuba's two-sided BSDFs turn their frame.
    assert!(hit.normal.dot(ray.dir) < 0.0);
    let lean = Vec3::new(80f64.to_radians().sin(), 0.0, 80f64.to_radians().cos());
    assert!((hit.normal + lean).length() < 1e-12, "{:?}", hit.normal);
    assert_eq!(hit.geometric_normal, Vec3::Z);
    assert!(crate::scene::surface_bsdf(&scene.materials[hit.material], hit.point, hit.front_face).is_black(), "one-sided: black");
    // Where the shading normal faces the ray both conventions agree.
    let straight = Ray::unit(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, -1.0));
    let a = scene.first_intersect(&straight, f64::INFINITY).unwrap();
    let b = leaning(Sides::Geometric).0.first_intersect(&straight, f64::INFINITY).unwrap();
    assert_eq!(a, b);
}
