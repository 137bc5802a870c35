//! Does any light reach what the camera sees? A cheap probe before a render,
//! so that a scene whose only emitter faces away (one-sided, as in pbrt and
//! Mitsuba) says so instead of rendering black.
//!
//! The probe casts a 16 x 16 grid of camera rays through pixel centres. A first
//! hit counts as lit when its material emits towards the camera, or when a
//! delta light or one of 16 points on an area light lies on its side of the
//! surface with nothing opaque between. A sky (environment or non-black
//! background under path tracing) and an ambient term light every surface, so
//! with either the answer is yes without probing.

use super::{Hit, Scene};
use crate::camera::Camera;
use crate::lights::LightSet;
use crate::math::{Rgb, Vec3};
use crate::ray::offset_origin;

/// Camera rays per side of the probe grid.
const GRID: u32 = 16;
/// Points tried on each area light per hit (a 4 x 4 grid of cell centres).
const AREA_POINTS: u32 = 4;

/// Whether some light reaches some first hit of the camera's rays for a
/// `width x height` image (see the module doc). `false` also for an empty view.
pub fn reaches_camera_hits(scene: &Scene, camera: &dyn Camera, width: u32, height: u32) -> bool {
    let lights = scene.light_set();
    if lights.environment.is_some() || scene.settings.ambient.max_element() > 0.0 {
        return true;
    }
    probe_hits(scene, camera, width, height).any(|hit| lit_by_lights(scene, &lights, &hit))
}

/// The share of the probe's first hits (the 16 x 16 grid of the module doc)
/// that the scene's lights reach: a hit that emits towards the camera, or that
/// a delta light or a point of an area light sends light to on its side of
/// the surface with nothing opaque between. The sky and the ambient term are
/// left out: this measures how much of what the camera sees the lights
/// themselves light (a bare model's own lights, issue 27). `None` when no
/// probe ray hits anything.
pub fn lit_share(scene: &Scene, camera: &dyn Camera, width: u32, height: u32) -> Option<f64> {
    let lights = scene.light_set();
    let (mut hits, mut lit) = (0usize, 0usize);
    for hit in probe_hits(scene, camera, width, height) {
        hits += 1;
        lit += usize::from(lit_by_lights(scene, &lights, &hit));
    }
    (hits > 0).then(|| lit as f64 / hits as f64)
}

/// The first hits of the probe grid's camera rays, row by row.
fn probe_hits<'a>(scene: &'a Scene, camera: &'a dyn Camera, width: u32, height: u32) -> impl Iterator<Item = Hit> + 'a {
    (0..GRID * GRID).filter_map(move |k| {
        let (i, j) = (k % GRID, k / GRID);
        let x = (i as f64 + 0.5) / GRID as f64 * width as f64;
        let y = (j as f64 + 0.5) / GRID as f64 * height as f64;
        let ray = camera.ray(x, y, width, height, (0.5, 0.5));
        scene.first_intersect(&ray, f64::INFINITY)
    })
}

/// Whether `hit` emits towards the camera or a delta or area light of `lights` reaches it.
fn lit_by_lights(scene: &Scene, lights: &LightSet, hit: &Hit) -> bool {
    if scene.materials[hit.material].emits_towards(hit.front_face) {
        return true;
    }
    for light in &lights.delta {
        if let Some(s) = light.illuminate(hit.point) {
            if s.radiance != Rgb::ZERO && visible(scene, hit, s.wi, s.distance, light.own_object()) {
                return true;
            }
        }
    }
    for light in &lights.area {
        for k in 0..AREA_POINTS * AREA_POINTS {
            let u = (((k % AREA_POINTS) as f64 + 0.5) / AREA_POINTS as f64, ((k / AREA_POINTS) as f64 + 0.5) / AREA_POINTS as f64);
            if let Some(s) = light.sample(hit.point, u) {
                if visible(scene, hit, s.wi, s.distance, Some(light.object)) {
                    return true;
                }
            }
        }
    }
    false
}

/// Whether light from `wi` at `distance` reaches `hit` on the side its ray came from.
fn visible(scene: &Scene, hit: &Hit, wi: Vec3, distance: f64, own: Option<usize>) -> bool {
    if hit.geometric_normal.dot(wi) <= 0.0 {
        return false;
    }
    let origin = offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error);
    scene.transmittance(&hit.spawn(origin, wi), distance - (origin - hit.point).length(), own) != Rgb::ZERO
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::lights::PointLight;
    use crate::materials::Material;
    use crate::shapes::Rectangle;
    use crate::SceneBuilder;

    /// A floor seen from above, lit by a square lamp at height 2 facing `down`
    /// (or up, away from the floor), or by a point light under the floor.
    fn scene(lamp_faces_floor: bool, two_sided: bool, point_below: bool) -> Scene {
        let camera = Perspective::look_at(Vec3::new(0.0, 4.0, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let grey = b.material(Material { ka: Rgb::ZERO, ..Material::default() }).unwrap();
        b.object(Rectangle::horizontal(0.0, -5.0, 5.0, -5.0, 5.0).unwrap(), grey).unwrap();
        let lamp =
            b.material(Material { emission: Rgb::splat(5.0), two_sided, kd: Rgb::ZERO, ka: Rgb::ZERO, ..Material::default() }).unwrap();
        let (u, v) = if lamp_faces_floor { (Vec3::X, Vec3::Z) } else { (Vec3::Z, Vec3::X) };
        // Behind the camera's view, so the probe sees only the floor.
        b.object(Rectangle::new(Vec3::new(-0.5, 2.0, 5.5), u, v).unwrap(), lamp).unwrap();
        if point_below {
            b.light(PointLight::new(Vec3::new(0.0, -1.0, 0.0), Rgb::ONE).unwrap());
        }
        b.settings.ambient = Rgb::ZERO;
        b.settings.background = Rgb::ZERO;
        b.build().unwrap()
    }

    #[test]
    fn a_lamp_facing_away_lights_nothing_the_camera_sees() {
        let reach = |s: &Scene| reaches_camera_hits(s, s.settings.camera.as_ref(), 64, 48);
        assert!(reach(&scene(true, false, false)), "a lamp facing the floor lights it");
        assert!(!reach(&scene(false, false, false)), "one-sided, facing up: nothing lit");
        assert!(reach(&scene(false, true, false)), "two-sided: lit");
        assert!(!reach(&scene(false, false, true)), "a point light under the floor reaches only its back");
        let mut sky = scene(false, false, false);
        sky.settings.ambient = Rgb::splat(0.1);
        assert!(reach(&sky), "an ambient term lights every surface");
    }

    #[test]
    fn the_lit_share_counts_the_hits_a_light_reaches_and_ignores_the_sky() {
        let share = |s: &Scene| lit_share(s, s.settings.camera.as_ref(), 64, 48);
        assert_eq!(share(&scene(true, false, false)), Some(1.0), "the lamp facing the floor lights all of it");
        assert_eq!(share(&scene(false, false, true)), Some(0.0), "a point light under the floor lights none of it");
        let mut sky = scene(false, false, true);
        sky.settings.ambient = Rgb::splat(0.1);
        assert_eq!(share(&sky), Some(0.0), "the ambient term is not a light's reach");
        // Half the floor in shadow: a low light at x = 1 behind a wall at x = 0
        // (seen edge-on from straight above), which shades the floor at x < 0.
        let camera = Perspective::look_at(Vec3::new(0.0, 8.0, 0.0), Vec3::ZERO, -Vec3::Z, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let grey = b.material(Material::default()).unwrap();
        b.object(Rectangle::horizontal(0.0, -20.0, 20.0, -20.0, 20.0).unwrap(), grey).unwrap();
        b.object(Rectangle::new(Vec3::new(0.0, 0.0, -20.0), Vec3::new(0.0, 0.0, 40.0), Vec3::Y).unwrap(), grey).unwrap();
        b.light(PointLight::new(Vec3::new(1.0, 0.5, 0.0), Rgb::ONE).unwrap());
        b.settings.ambient = Rgb::ZERO;
        let half = share(&b.build().unwrap()).unwrap();
        assert!((half - 0.5).abs() <= 1.0 / 16.0, "{half}");
        let mut empty = SceneBuilder::new(Perspective::look_at(Vec3::Y, Vec3::ZERO, Vec3::Z, Fov::VerticalDeg(40.0)).unwrap());
        empty.settings.ambient = Rgb::ZERO;
        assert_eq!(share(&empty.build().unwrap()), None, "nothing seen");
    }
}
