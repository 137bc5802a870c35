//! `cornell-box`: the classic Cornell box with an area light in the ceiling.
//!
//! Geometry, colours and light are those of Mitsuba 3's `mitsuba.cornell_box()`
//! (itself the widely used rendition of the Cornell program's box, in a
//! `[-1, 1]^3` room): five walls, a short box turned by -17 degrees and a tall
//! box turned by 18.25 degrees, a 0.46 x 0.38 light at `y = 0.99` facing down
//! with radiance `(18.387, 13.9873, 6.75357)`, and a camera at `z = 3.9` with a
//! 39.3077 degree field of view across the image's smaller side. Every surface is
//! Lambertian; the light's own surface is the white material. Sharing the scene
//! exactly with Mitsuba is what makes `bench/mitsuba_cornell.py` a cross-check.
//!
//! Its default integrator is the path tracer (as the example file's); under
//! `--integrator whitted` the lamp is an area light with soft shadows and no
//! indirect light.

use glam::DMat4;
use lamplight_core::prelude::*;
use lamplight_core::Error;

/// Mitsuba's rectangle `[-1, 1]^2 x {0}` (normal +z) under `m`.
fn rectangle(m: DMat4) -> Result<Rectangle, Error> {
    let corner = m.transform_point3(Vec3::new(-1.0, -1.0, 0.0));
    Rectangle::new(corner, m.transform_vector3(Vec3::new(2.0, 0.0, 0.0)), m.transform_vector3(Vec3::new(0.0, 2.0, 0.0)))
}

fn diffuse(c: Rgb) -> Material {
    Material { color: Texture::Constant(c), ka: Rgb::ZERO, kd: Rgb::ONE, ..Material::default() }
}

/// The Cornell box; the field of view spans the image's shorter side, as in Mitsuba.
pub fn build() -> Result<lamplight_core::Scene, Error> {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 3.9), Vec3::ZERO, Vec3::Y, Fov::SmallerSideDeg(39.3077))?;
    let mut b = SceneBuilder::new(camera);
    b.settings.max_depth = 8;
    let white = b.material(diffuse(Rgb::new(0.885809, 0.698859, 0.666422)))?;
    let green = b.material(diffuse(Rgb::new(0.105421, 0.37798, 0.076425)))?;
    let red = b.material(diffuse(Rgb::new(0.570068, 0.0430135, 0.0443706)))?;
    let light = b.material(Material { emission: Rgb::new(18.387, 13.9873, 6.75357), ..diffuse(Rgb::new(0.885809, 0.698859, 0.666422)) })?;
    let t = |x: f64, y: f64, z: f64| DMat4::from_translation(Vec3::new(x, y, z));
    let rx = |deg: f64| DMat4::from_rotation_x(deg.to_radians());
    let ry = |deg: f64| DMat4::from_rotation_y(deg.to_radians());
    b.object(rectangle(t(0.0, 0.99, 0.01) * rx(90.0) * DMat4::from_scale(Vec3::new(0.23, 0.19, 0.19)))?, light)?;
    b.object(rectangle(t(0.0, -1.0, 0.0) * rx(-90.0))?, white)?;
    b.object(rectangle(t(0.0, 1.0, 0.0) * rx(90.0))?, white)?;
    b.object(rectangle(t(0.0, 0.0, -1.0))?, white)?;
    b.object(rectangle(t(1.0, 0.0, 0.0) * ry(-90.0))?, green)?;
    b.object(rectangle(t(-1.0, 0.0, 0.0) * ry(90.0))?, red)?;
    // Each box is one Cuboid: the cube [-1, 1]^3 placed by T R S, the product the
    // scene file's group { translate, rotate, scale } composes, bit for bit.
    let cube = |m: DMat4| Cuboid::new(-Vec3::ONE, Vec3::ONE, m);
    b.object(cube(t(0.335, -0.7, 0.38) * ry(-17.0) * DMat4::from_scale(Vec3::splat(0.3)))?, white)?;
    b.object(cube(t(-0.33, -0.4, -0.28) * ry(18.25) * DMat4::from_scale(Vec3::new(0.3, 0.61, 0.3)))?, white)?;
    b.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_face_into_the_room_and_box_faces_face_out() {
        let scene = build().unwrap();
        assert_eq!(scene.objects.len(), 6 + 2);
        // Mitsuba's small-box matrix: first row (0.286891, 0, -0.0877115, 0.335).
        let m = DMat4::from_translation(Vec3::new(0.335, -0.7, 0.38))
            * DMat4::from_rotation_y((-17.0f64).to_radians())
            * DMat4::from_scale(Vec3::splat(0.3));
        assert!((m.x_axis.x - 0.286891).abs() < 1e-6 && (m.z_axis.x + 0.0877115).abs() < 1e-6);
        let cube = Cuboid::new(-Vec3::ONE, Vec3::ONE, m).unwrap();
        for (face, axis) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].into_iter().enumerate() {
            let outward = m.transform_vector3(axis).normalize();
            assert!((cube.face_normal(face) - outward).length() < 1e-12, "face {face} points {}", cube.face_normal(face));
        }
        let light = rectangle(DMat4::from_translation(Vec3::new(0.0, 0.99, 0.01)) * DMat4::from_rotation_x(90f64.to_radians())).unwrap();
        assert!((light.normal() + Vec3::Y).length() < 1e-12, "the light faces down");
    }
}
