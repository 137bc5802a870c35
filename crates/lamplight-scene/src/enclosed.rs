//! Lights shut in by geometry: a spot light inside its own emissive cone mesh,
//! a bulb inside a closed lamp. Such a light adds nothing to the image, and the
//! render gives no sign of why; `explain` shows it only pixel by pixel
//! (`shadow ray BLOCKED by object 4`). This probe says it once per light,
//! naming what blocks it (issue 27).
//!
//! The probe points are the first hits of a 16 x 16 grid of camera rays
//! through pixel centres, as [`lamplight_core::scene::reaches_camera_hits`]
//! takes them. For each point, light (point, spot or directional) that sends
//! it light, from the side of the surface the camera sees, casts one shadow
//! ray. A light whose every such shadow ray is blocked, of at least
//! [`MIN_PROBED`], gets a warning naming the object that stopped most of them
//! first. Points the light does not face,
//! or does not send light to (outside a spot's cone), cast no ray and decide
//! nothing: a light that faces nothing the camera sees is the other warning's
//! case ("no light reaches anything the camera sees").

use lamplight_core::camera::Camera;
use lamplight_core::explain::{kind_name, ObjectRef};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::ray::{offset_origin, Ray};
use lamplight_core::scene::Hit;
use lamplight_core::Scene;

/// Camera rays per side of the probe grid.
const GRID: u32 = 16;

/// Lights probed at most: each costs up to `GRID^2` shadow rays, so a scene of
/// thousands of lights is probed for its first ones only.
pub const MAX_PROBED_LIGHTS: usize = 256;

/// Fewest shadow rays a light must cast, all blocked, for a warning. A light
/// that sends light to fewer of the probe points lights little of the view
/// either way, and a few blocked ones are no sign of a light shut in: the
/// viewer's rim light behind a bare `igea.ply` or Suzanne faces one point
/// at the model's silhouette, which the model itself shadows, and was named
/// as shut in ("(1 probed)"), in the viewer's warnings too.
pub const MIN_PROBED: usize = 8;

/// Objects crossed at most while looking for what blocks a shadow ray.
const MAX_CROSSINGS: usize = 64;

/// One warning per delta light of `scene` whose every probe shadow ray is
/// blocked (see the module doc), for a `width x height` image through `camera`:
/// `light 0 (PointLight) lights nothing the camera sees: every shadow ray
/// towards it from what the camera sees (12 probed) is blocked by object 1
/// "shell" (Sphere)`.
pub fn enclosed_light_warnings(scene: &Scene, camera: &dyn Camera, width: u32, height: u32) -> Vec<String> {
    if scene.lights.is_empty() || width == 0 || height == 0 {
        return Vec::new();
    }
    let mut hits = Vec::new();
    for j in 0..GRID {
        for i in 0..GRID {
            let x = (i as f64 + 0.5) / GRID as f64 * width as f64;
            let y = (j as f64 + 0.5) / GRID as f64 * height as f64;
            let ray = camera.ray(x, y, width, height, (0.5, 0.5));
            if let Some(hit) = scene.first_intersect(&ray, f64::INFINITY) {
                hits.push(hit);
            }
        }
    }
    let mut warnings = Vec::new();
    for (index, light) in scene.lights.iter().enumerate().take(MAX_PROBED_LIGHTS) {
        let own = light.own_object();
        // (object, shadow rays it stopped first), in the order first met.
        let mut blockers: Vec<(Option<usize>, usize)> = Vec::new();
        let mut cast = 0;
        let mut reached = false;
        for hit in &hits {
            let Some(s) = light.illuminate(hit.point) else { continue };
            if s.radiance == Rgb::ZERO || hit.geometric_normal.dot(s.wi) <= 0.0 || Some(hit.object) == own {
                continue;
            }
            cast += 1;
            let origin = offset_origin(hit.point, hit.geometric_normal, s.wi, hit.t, hit.error);
            let distance = s.distance - (origin - hit.point).length();
            if scene.transmittance(&hit.spawn(origin, s.wi), distance, own) != Rgb::ZERO {
                reached = true;
                break;
            }
            let first = first_opaque(scene, origin, s.wi, distance, own);
            match blockers.iter_mut().find(|(o, _)| *o == first) {
                Some((_, n)) => *n += 1,
                None => blockers.push((first, 1)),
            }
        }
        if reached || cast < MIN_PROBED {
            continue;
        }
        warnings.push(message(scene, index, cast, &blockers));
    }
    warnings
}

/// The warning for light `index`, all `cast` of whose shadow rays `blockers` stopped.
fn message(scene: &Scene, index: usize, cast: usize, blockers: &[(Option<usize>, usize)]) -> String {
    let light = format!("light {index} ({})", kind_name(&*scene.lights[index]));
    // The object that stopped the most; the first met among equals.
    let (top, count) = blockers.iter().fold((None, 0), |best, &(o, n)| if n > best.1 { (o, n) } else { best });
    let by = match top {
        Some(object) => ObjectRef::new(scene, object).to_string(),
        // Blocked, but by partly clear surfaces whose product reached zero.
        None => "partly clear surfaces".to_string(),
    };
    let head =
        format!("{light} lights nothing the camera sees: every shadow ray towards it from what the camera sees ({cast} probed) is blocked");
    match blockers.len() - 1 {
        0 => format!("{head} by {by}"),
        1 => format!("{head}, {count} of them by {by}, the rest by another object"),
        n => format!("{head}, {count} of them by {by}, the rest by {n} other objects"),
    }
}

/// The first object with `shadow_transmittance` zero on the segment from
/// `origin` along `dir` over `distance`, stepping over partly clear ones
/// (`explain`'s walk); `None` when the light's `own` object or the end comes first.
fn first_opaque(scene: &Scene, mut origin: Vec3, dir: Vec3, distance: f64, own: Option<usize>) -> Option<usize> {
    let mut remaining = distance;
    for _ in 0..MAX_CROSSINGS {
        let hit: Hit = scene.first_intersect(&Ray::unit(origin, dir), remaining)?;
        if Some(hit.object) == own {
            return None;
        }
        if scene.materials[hit.material].shadow_transmittance == Rgb::ZERO {
            return Some(hit.object);
        }
        let next = offset_origin(hit.point, hit.geometric_normal, dir, hit.t, hit.error);
        remaining -= (next - origin).length();
        origin = next;
        if remaining <= 0.0 {
            return None;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::camera::{Fov, Perspective};
    use lamplight_core::lights::{DirectionalLight, PointLight, SpotLight, SpotProfile};
    use lamplight_core::materials::Material;
    use lamplight_core::shapes::{Rectangle, Sphere};
    use lamplight_core::SceneBuilder;

    fn warnings(scene: &Scene) -> Vec<String> {
        enclosed_light_warnings(scene, scene.settings.camera.as_ref(), 64, 48)
    }

    /// A floor seen from above with `cover(builder, material)` adding what may
    /// block its light.
    fn floor(cover: impl FnOnce(&mut SceneBuilder, usize)) -> Scene {
        let camera = Perspective::look_at(Vec3::new(0.0, 3.0, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let grey = b.material(Material::default()).unwrap();
        b.object(Rectangle::horizontal(0.0, -5.0, 5.0, -5.0, 5.0).unwrap(), grey).unwrap();
        cover(&mut b, grey);
        b.build().unwrap()
    }

    #[test]
    fn a_light_blocked_by_two_objects_names_the_one_that_blocks_most() {
        // Sunlight from straight above, under two roofs meeting at x = 1: the
        // left one covers more of what the camera sees.
        let scene = floor(|b, grey| {
            let left = b.object(Rectangle::horizontal(6.0, -50.0, 1.0, -50.0, 50.0).unwrap(), grey).unwrap();
            b.name_object(left, "left roof");
            b.object(Rectangle::horizontal(6.0, 1.0, 50.0, -50.0, 50.0).unwrap(), grey).unwrap();
            b.light(DirectionalLight::new(Vec3::new(0.0, -1.0, 0.0), Rgb::ONE).unwrap());
        });
        let w = warnings(&scene);
        assert_eq!(w.len(), 1, "{w:?}");
        let (head, tail) = w[0].split_once(" probed) is blocked, ").expect("two blockers");
        assert_eq!(
            head,
            "light 0 (DirectionalLight) lights nothing the camera sees: every shadow ray towards it from what the camera sees (240"
        );
        assert_eq!(tail, "171 of them by object 1 \"left roof\" (Rectangle), the rest by another object");
    }

    #[test]
    fn a_light_that_sends_light_to_few_probe_points_is_not_named_even_when_they_are_blocked() {
        // A spot light shut in a small opaque ball over the floor: how many
        // probe points its cone covers decides.
        let spot = |outer: f64| {
            floor(|b, grey| {
                b.object(Sphere::new(Vec3::new(0.0, 2.0, 0.0), 0.1).unwrap(), grey).unwrap();
                b.light(SpotLight::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y, Rgb::ONE, 0.9 * outer, outer, SpotProfile::Gltf).unwrap());
            })
        };
        // The probe points inside a cone of half-angle `outer` (what the spot casts shadow rays from).
        let covered = |scene: &Scene| {
            let camera = scene.settings.camera.as_ref();
            (0..GRID * GRID)
                .filter_map(|k| {
                    let (x, y) = ((k % GRID) as f64 + 0.5, (k / GRID) as f64 + 0.5);
                    let ray = camera.ray(x / GRID as f64 * 64.0, y / GRID as f64 * 48.0, 64, 48, (0.5, 0.5));
                    scene.first_intersect(&ray, f64::INFINITY)
                })
                .filter(|hit| scene.lights[0].illuminate(hit.point).is_some_and(|s| s.radiance != Rgb::ZERO))
                .count()
        };
        let narrow = spot(10.0);
        let n = covered(&narrow);
        assert!((1..MIN_PROBED).contains(&n), "{n} probe points in the narrow cone");
        assert_eq!(warnings(&narrow), Vec::<String>::new());
        let wide = spot(60.0);
        assert!(covered(&wide) >= MIN_PROBED);
        assert_eq!(warnings(&wide).len(), 1, "{:?}", warnings(&wide));
    }

    #[test]
    fn a_clear_shell_or_the_light_s_own_bulb_blocks_nothing_an_opaque_one_does() {
        let light = || PointLight::new(Vec3::new(0.0, 1.0, 0.0), Rgb::ONE).unwrap();
        let shell = || Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.5).unwrap();
        // Glass lets shadow rays through (shadow_transmittance 1).
        let glass = floor(|b, _| {
            let clear = b.material(Material { shadow_transmittance: Rgb::ONE, ..Material::default() }).unwrap();
            b.object(shell(), clear).unwrap();
            b.light(light());
        });
        assert_eq!(warnings(&glass), Vec::<String>::new());
        // A bulb declared the light's own does not shadow it.
        let bulb = floor(|b, grey| {
            let own = b.object(shell(), grey).unwrap();
            b.light(PointLight { own_object: Some(own), ..light() });
        });
        assert_eq!(warnings(&bulb), Vec::<String>::new());
        // An opaque shell does.
        let shut = floor(|b, grey| {
            b.object(shell(), grey).unwrap();
            b.light(light());
        });
        assert_eq!(warnings(&shut).len(), 1);
        assert!(warnings(&shut)[0].ends_with("is blocked by object 1 (Sphere)"), "{:?}", warnings(&shut));
    }
}
