//! `luxo`, the default scene: the lecture's Homework 2, "Luxo Grandpa".
//!
//! An articulated desk lamp (a base, two arms, three joints) whose shade is a
//! paraboloid clipped to a cup, with a point light in its focus, over a checkered
//! table in a dark room. On the table: a mirror sphere, a glass ellipsoid, a cone,
//! a box and a triangle-mesh pyramid. Every number is the one written out in
//! `shared/anchors/povray/SCENES.md` (scene `luxo`), so the image can be compared
//! pixel by pixel with POV-Ray rendering `luxo.pov`.
//!
//! Geometry: the shade is `{P : |P-A|^2 - ((P-A).a)^2 = 4 f (P-A).a, 0 <= (P-A).a <= h}`
//! with apex `A`, unit axis `a` towards the table, focal length `f = 0.1` and depth
//! `h = 0.25`; the light sits at the focus `A + f a`, inside a small emissive bulb
//! that casts no shadow. Arms and the lamp base are tubes with disk caps; the cone
//! is a clipped cone with a base disk; the box is one [`Cuboid`], rotated 25 degrees
//! about +y.

use lamplight_core::math::Mat4;
use lamplight_core::prelude::*;
use lamplight_core::Error;

use super::spheres::pov_mirror;

/// Apex of the lamp shade.
const SHADE_APEX: Vec3 = Vec3::new(-0.45, 1.35, -0.25);
/// The point the shade's axis aims at, on the table.
const SHADE_TARGET: Vec3 = Vec3::new(0.10, 0.0, 0.05);
/// Focal length and depth of the shade's paraboloid.
const SHADE_FOCAL: f64 = 0.10;
const SHADE_DEPTH: f64 = 0.25;

/// Adds a closed cylinder (a tube and its two end disks) from `p0` to `p1`.
fn capped_cylinder(scene: &mut SceneBuilder, p0: Vec3, p1: Vec3, radius: f64, material: usize) -> Result<(), Error> {
    let axis = p1 - p0;
    scene.object(Quadric::cylinder_segment(p0, p1, radius)?, material)?;
    scene.object(Disk::new(p0, -axis, radius)?, material)?;
    scene.object(Disk::new(p1, axis, radius)?, material)?;
    Ok(())
}

/// Builds the scene.
pub fn build() -> Result<Scene, Error> {
    let camera = Perspective::look_at(Vec3::new(1.3, 1.6, 3.0), Vec3::new(-0.15, 0.45, -0.2), Vec3::Y, Fov::VerticalDeg(40.0))?;
    let mut scene = SceneBuilder::new(camera);
    scene.settings.ambient = Rgb::ONE;
    scene.settings.background = Rgb::new(0.02, 0.02, 0.03);
    scene.settings.max_depth = 5;

    // The table: a 5 x 4 checkered top at y = 0, tiles of 0.5.
    let table = scene.material(Material {
        color: Texture::Checker {
            size: 0.5,
            even: Rgb::new(0.80, 0.75, 0.65),
            odd: Rgb::new(0.35, 0.25, 0.18),
            offset: Vec3::new(0.0, 0.25, 0.0),
        },
        ..Material::plastic(Rgb::ONE, 0.1, 0.8, 0.2, 30.0)
    })?;
    scene.object(Rectangle::horizontal(0.0, -2.5, 2.5, -2.0, 2.0)?, table)?;

    // The lamp: base, joints, arms, shade, bulb and the light in the shade's focus.
    let base = scene.material(Material::plastic(Rgb::new(0.15, 0.15, 0.17), 0.1, 0.6, 0.5, 60.0))?;
    let joint = scene.material(Material::plastic(Rgb::new(0.30, 0.30, 0.32), 0.1, 0.6, 0.6, 80.0))?;
    let arm = scene.material(Material::plastic(Rgb::new(0.60, 0.60, 0.62), 0.1, 0.6, 0.6, 80.0))?;
    let shade = scene.material(Material::plastic(Rgb::new(0.85, 0.85, 0.80), 0.1, 0.7, 0.4, 40.0))?;
    let bulb = scene.material(Material {
        color: Texture::Constant(Rgb::ONE),
        ka: Rgb::ZERO,
        kd: Rgb::ZERO,
        ks: Rgb::ZERO,
        emission: Rgb::new(1.0, 0.95, 0.8),
        shadow_transmittance: Rgb::ONE, // the bulb casts no shadow
        ..Material::default()
    })?;
    let axis = (SHADE_TARGET - SHADE_APEX).normalize();
    let focus = SHADE_APEX + axis * SHADE_FOCAL;
    let (j0, j1, j2) = (Vec3::new(-1.4, 0.10, -0.6), Vec3::new(-1.1, 0.95, -0.45), SHADE_APEX - axis * 0.05);
    capped_cylinder(&mut scene, Vec3::new(-1.4, 0.0, -0.6), Vec3::new(-1.4, 0.05, -0.6), 0.30, base)?;
    scene.object(Sphere::new(j0, 0.06)?, joint)?;
    capped_cylinder(&mut scene, j0, j1, 0.025, arm)?;
    scene.object(Sphere::new(j1, 0.05)?, joint)?;
    capped_cylinder(&mut scene, j1, j2, 0.025, arm)?;
    scene.object(Sphere::new(j2, 0.05)?, joint)?;
    scene.object(Quadric::paraboloid_cup(SHADE_APEX, axis, SHADE_FOCAL, SHADE_DEPTH)?, shade)?;
    // The bulb is the point light's body: seen, but lighting only through the
    // point light, as POV-Ray's glowing no_shadow sphere does (sampled as an area
    // light as well, it cost 16 shadow rays per hit for light the shade hides).
    let bulb = scene.object(Sphere::new(focus, 0.035)?, bulb)?;
    scene.light(PointLight { own_object: Some(bulb), ..PointLight::new(focus, Rgb::new(2.0, 1.9, 1.7))? });

    // On the table: a mirror sphere, a glass ellipsoid, a cone, a box, a pyramid.
    let mirror = scene.material(pov_mirror())?;
    scene.object(Sphere::new(Vec3::new(0.75, 0.40, -0.55), 0.40)?, mirror)?;
    let glass = scene.material(Material::glass(1.5, 0.8, 300.0))?;
    scene.object(Quadric::ellipsoid(Vec3::new(-0.05, 0.25, 0.55), Vec3::new(0.40, 0.25, 0.30))?, glass)?;
    let red = scene.material(Material::plastic(Rgb::new(0.75, 0.12, 0.10), 0.1, 0.7, 0.5, 60.0))?;
    let (cone_base, cone_apex) = (Vec3::new(1.20, 0.0, 0.30), Vec3::new(1.20, 0.65, 0.30));
    scene.object(Quadric::cone_segment(cone_apex, cone_base, 0.22)?, red)?;
    scene.object(Disk::new(cone_base, -Vec3::Y, 0.22)?, red)?;
    let blue = scene.material(Material::plastic(Rgb::new(0.15, 0.30, 0.75), 0.1, 0.7, 0.3, 30.0))?;
    let placement = Mat4::from_translation(Vec3::new(-0.75, 0.0, 0.45)) * Mat4::from_rotation_y(25f64.to_radians());
    scene.object(Cuboid::new(Vec3::new(-0.2, 0.0, -0.2), Vec3::new(0.2, 0.4, 0.2), placement)?, blue)?;
    let gold = scene.material(Material::plastic(Rgb::new(0.85, 0.65, 0.15), 0.1, 0.7, 0.4, 50.0))?;
    let (c, half, height) = (Vec3::new(0.05, 0.0, -0.75), 0.22, 0.45);
    let pyramid = TriangleMesh::new(
        vec![
            c + Vec3::new(-half, 0.0, -half),
            c + Vec3::new(half, 0.0, -half),
            c + Vec3::new(half, 0.0, half),
            c + Vec3::new(-half, 0.0, half),
            c + Vec3::new(0.0, height, 0.0),
        ],
        vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [0, 2, 1], [0, 3, 2]],
        None,
    )?;
    scene.object(pyramid, gold)?;
    scene.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_sits_in_the_focus_of_the_shade() {
        // SCENES.md: F = (-0.4130447773, 1.2592917260, -0.2298426058).
        let axis = (SHADE_TARGET - SHADE_APEX).normalize();
        let focus = SHADE_APEX + axis * SHADE_FOCAL;
        assert!((focus - Vec3::new(-0.4130447773, 1.2592917260, -0.2298426058)).length() < 1e-9);
        let scene = build().unwrap();
        let light = scene.lights[0].illuminate(Vec3::ZERO).unwrap();
        assert!((light.distance - focus.length()).abs() < 1e-12);
    }

    #[test]
    fn box_corners_match_the_description() {
        let placement = Mat4::from_translation(Vec3::new(-0.75, 0.0, 0.45)) * Mat4::from_rotation_y(25f64.to_radians());
        let corner = placement.transform_point3(Vec3::new(-0.2, 0.0, -0.2));
        // SCENES.md lists (-1.0157852098, ., 0.3532620949) first among the corners.
        assert!((corner - Vec3::new(-1.0157852098, 0.0, 0.3532620949)).length() < 1e-9, "{corner}");
        let opposite = placement.transform_point3(Vec3::new(0.2, 0.4, 0.2));
        assert!((opposite - Vec3::new(-0.4842147902, 0.4, 0.5467379051)).length() < 1e-9, "{opposite}");
    }

    #[test]
    fn the_light_is_visible_below_the_shade_and_hidden_above_it() {
        let scene = build().unwrap();
        let focus = Vec3::new(-0.4130447773, 1.2592917260, -0.2298426058);
        // A table point on the shade's axis is lit; a point above the lamp is not.
        let below = Vec3::new(0.10, 0.0, 0.05);
        let above = focus + Vec3::new(0.0, 1.0, 0.0);
        let visible = |p: Vec3| {
            let to = focus - p;
            scene.transmittance(&lamplight_core::ray::Ray::unit(p, to.normalize()), to.length(), None)
        };
        assert_eq!(visible(below), Rgb::ONE, "the bulb casts no shadow, the shade opens downwards");
        assert_eq!(visible(above), Rgb::ZERO, "the shade's back blocks the light");
    }

    #[test]
    fn the_glowing_bulb_lights_only_through_its_point_light() {
        let scene = build().unwrap();
        let bulb = scene.lights[0].own_object().expect("the point light owns its bulb");
        assert!(scene.materials[scene.objects[bulb].material].emission.max_element() > 0.0, "object {bulb} is the bulb");
        let lights = scene.light_set();
        assert!(lights.area.is_empty(), "the bulb must not be sampled as an area light too");
        assert!(lights.is_bulb(bulb));
    }
}
