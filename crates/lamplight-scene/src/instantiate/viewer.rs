//! What a bare mesh gets: the camera and lights of a model viewer, for a mesh
//! or glTF file that has no camera or no lights of its own.
//!
//! - **Framing.** The camera looks at the centre of the model's bounding sphere
//!   (the centre of its bounding box, and the farthest vertex from it) from a
//!   three-quarter view: [`AZIMUTH_DEG`] to the right of the front (`+z`),
//!   [`ELEVATION_DEG`] above, `+y` up (glTF's axes). Its field of view,
//!   [`VFOV_DEG`], spans the image's shorter side, and it stands where the
//!   sphere's outline spans [`FILL`] of that side, at any image size.
//! - **Lighting**, as Blender's and model-viewer's defaults light a model: a
//!   neutral studio environment ([`super::studio`]: a grey floor, a sky
//!   brighter overhead, a soft box above and strip lights at the sides),
//!   seen as the background, mirrored by metals and lighting every surface
//!   under path tracing; the Whitted tracer's diffuse surfaces see it through
//!   the lecture's ambient term (the ambient light is [`AMBIENT`], so that
//!   `ka C La` with the importers' `ka = 0.1 kd` is what a diffuse surface
//!   reflects under an open sky of the studio's mean radiance); and three
//!   directional lights set relative to the camera, so that the model is lit
//!   the same from any file: a key light from the upper left, a weaker fill
//!   from the right, and a rim light from behind. Directional lights make the
//!   lighting independent of the model's size. Their irradiances ([`KEY`],
//!   [`FILL_LIGHT`], [`RIM`]) and the studio add to less than 1 at any
//!   surface a diffuse white (`kd * C = 1`) turns to them, so almost nothing
//!   clips (the tests measure it, here and in [`super::studio`]).
//! - **Which files get it:** a file without lights of its own (no lights, no
//!   emitting material) always; a file with lights keeps them too when they
//!   reach less than [`MIN_LIT_SHARE`] of what the camera sees of the model
//!   ([`super::imported`], [`AutoLights`]).

use lamplight_core::camera::{Fov, Perspective};
use lamplight_core::lights::DirectionalLight;
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::Error;

/// Field of view across the image's shorter side, degrees.
pub const VFOV_DEG: f64 = 40.0;
/// Share of the image's shorter side the bounding sphere's outline spans.
pub const FILL: f64 = 0.8;
/// Angle of the view to the right of the front (`+z`), degrees.
pub const AZIMUTH_DEG: f64 = 35.0;
/// Angle of the view above the horizon, degrees.
pub const ELEVATION_DEG: f64 = 25.0;
/// The ambient light `La`: ten times the studio's mean radiance
/// ([`super::studio::MEAN`], 0.3), for the importers' `ka = 0.1 kd`.
pub const AMBIENT: f64 = 3.0;
/// Irradiance of the key light.
pub const KEY: f64 = 0.5;
/// Irradiance of the fill light.
pub const FILL_LIGHT: f64 = 0.25;
/// Irradiance of the rim light.
pub const RIM: f64 = 0.25;

/// The share of what the camera sees of a model that the file's own lights
/// must reach ([`lamplight_core::scene::lit_share`]: probe rays whose first hit
/// a light reaches, or that emits towards the camera) for the automatic lights
/// to be left out, by default.
pub const MIN_LIT_SHARE: f64 = 0.25;

/// The image size the reach of a file's lights is probed at: the program's default.
pub const PROBE_SIZE: (u32, u32) = (640, 360);

/// Whether a model file that has lights of its own keeps the automatic lights
/// (the studio, key, fill and rim) too: `--keep-auto-lights on|off|auto`,
/// Python `keep_auto_lights=True|False|"auto"`. A file without lights always
/// gets them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum AutoLights {
    /// Kept when the file's lights reach less than [`MIN_LIT_SHARE`] of what
    /// the camera sees (the default).
    #[default]
    Auto,
    /// Always kept.
    On,
    /// Left out whenever the file has lights (the rule before issue 27).
    Off,
}

impl AutoLights {
    /// How the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            AutoLights::Auto => "auto",
            AutoLights::On => "on",
            AutoLights::Off => "off",
        }
    }
}

impl std::str::FromStr for AutoLights {
    type Err = String;

    fn from_str(s: &str) -> Result<AutoLights, String> {
        match s {
            "auto" => Ok(AutoLights::Auto),
            "on" => Ok(AutoLights::On),
            "off" => Ok(AutoLights::Off),
            _ => Err(format!("must be on, off or auto, got {s:?}")),
        }
    }
}

/// A bounding sphere: centre and radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius (positive).
    pub radius: f64,
}

/// The bounding sphere of `points` about the centre of their bounding box
/// (`None` for no points or a non-finite one).
pub fn bounding_sphere(points: impl Iterator<Item = Vec3> + Clone) -> Option<Sphere> {
    let (lo, hi) = points.clone().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let center = (lo + hi) / 2.0;
    let radius = points.map(|p| p.distance_squared(center)).fold(0.0f64, f64::max).sqrt();
    Some(Sphere { center, radius: radius.max(1e-9 * center.length().max(1.0)) })
}

/// The viewer's camera: its eye, and the camera framing `sphere`.
pub fn camera(sphere: Sphere) -> Result<(Vec3, Perspective), Error> {
    // The outline of a sphere of radius r seen from distance d has half-angle
    // asin(r / d); its image spans FILL of the side when tan of that angle is
    // FILL * tan(fov / 2).
    let half = (FILL * (VFOV_DEG.to_radians() / 2.0).tan()).atan();
    let distance = sphere.radius / half.sin();
    let (az, el) = (AZIMUTH_DEG.to_radians(), ELEVATION_DEG.to_radians());
    let towards_eye = Vec3::new(az.sin() * el.cos(), el.sin(), az.cos() * el.cos());
    let eye = sphere.center + towards_eye * distance;
    Ok((eye, Perspective::look_at(eye, sphere.center, Vec3::Y, Fov::SmallerSideDeg(VFOV_DEG))?))
}

/// The key, fill and rim lights for a camera at `eye` looking at `target`.
pub fn lights(eye: Vec3, target: Vec3) -> Result<[DirectionalLight; 3], Error> {
    let [key, fill, rim] = light_directions(eye, target);
    Ok([
        DirectionalLight::new(key.0, Rgb::splat(key.1))?,
        DirectionalLight::new(fill.0, Rgb::splat(fill.1))?,
        DirectionalLight::new(rim.0, Rgb::splat(rim.1))?,
    ])
}

/// The directions the key, fill and rim lights travel and their irradiances
/// (what [`lights`] builds them from; a converted scene file writes them).
pub fn light_directions(eye: Vec3, target: Vec3) -> [(Vec3, f64); 3] {
    let forward = (target - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // Each light is given by where it comes from, in the camera's frame; it travels the other way.
    let from = |r: f64, u: f64, f: f64| -(right * r + up * u + forward * f).normalize();
    [(from(-0.7, 0.8, -0.6), KEY), (from(1.0, -0.1, -0.5), FILL_LIGHT), (from(0.3, 0.6, 1.0), RIM)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sphere_is_centred_on_the_box_and_reaches_the_farthest_point() {
        let points = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(1.0, 0.5, 0.0)];
        let s = bounding_sphere(points.iter().copied()).unwrap();
        assert_eq!(s.center, Vec3::new(1.0, 0.25, 0.0));
        assert!((s.radius - (1.0f64 + 0.0625).sqrt()).abs() < 1e-12);
        assert_eq!(bounding_sphere([].iter().copied()), None);
        assert_eq!(bounding_sphere([Vec3::new(f64::NAN, 0.0, 0.0)].iter().copied()), None);
    }

    #[test]
    fn the_outline_spans_the_fill_of_the_shorter_side() {
        use lamplight_core::camera::Camera;
        let sphere = Sphere { center: Vec3::new(1.0, 2.0, 3.0), radius: 2.0 };
        let (eye, camera) = camera(sphere).unwrap();
        // The ray to the outline's top edge makes angle asin(r / d) with the view axis.
        let d = (eye - sphere.center).length();
        let edge = (sphere.radius / d).asin().tan();
        let tan_half = (VFOV_DEG.to_radians() / 2.0).tan();
        assert!((edge / tan_half - FILL).abs() < 1e-12, "{}", edge / tan_half);
        let centre = camera.ray(32.0, 18.0, 64, 36, (0.5, 0.5));
        assert!((centre.dir - (sphere.center - eye).normalize()).length() < 1e-12);
        assert!(eye.y > sphere.center.y && eye.x > sphere.center.x && eye.z > sphere.center.z, "above, right, in front");
    }

    #[test]
    fn the_lights_and_the_ambient_light_add_to_less_than_one_on_any_surface() {
        let lights = lights(Vec3::new(3.0, 2.0, 4.0), Vec3::ZERO).unwrap();
        // The most irradiance a surface can get is the length of the sum of the
        // vectors towards the lights it faces; try every subset.
        let mut most = 0.0f64;
        for mask in 1..8u32 {
            let sum: Vec3 = (0..3).filter(|i| mask & (1 << i) != 0).map(|i| -lights[i].direction * lights[i].radiance.x).sum();
            most = most.max(sum.length());
        }
        assert!((AMBIENT * 0.1 - super::super::studio::MEAN).abs() < 1e-12, "the ambient term is the studio's mean");
        let ambient = AMBIENT * 0.1;
        assert!(most + ambient < 0.92, "{most} + {ambient}: a diffuse white clips under the Whitted tracer");
        assert!(lights[0].direction.y < 0.0, "the key light comes from above");
    }
}
