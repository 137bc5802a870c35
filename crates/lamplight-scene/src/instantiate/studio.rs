//! The neutral studio environment that lights a bare model (issue 27), as
//! model-viewer's "neutral" environment and Blender's default studio light
//! do: a soft room brighter above and at the sides, so that a metal mirrors
//! something (under a uniform grey surround it mirrors only that grey, and
//! comes out darker than the diffuse parts the key light lights).
//!
//! It is made in code, no image asset: an equirectangular map of
//! [`WIDTH`] x [`HEIGHT`] pixels, looked up bilinearly, of the radiance
//! [`radiance`] gives in the studio's own frame, where the camera stands on
//! `+z` looking along `-z`:
//!
//! - below the horizon, the floor: a flat [`FLOOR`] (the grey surround the
//!   viewer's camera sees behind the model, as before);
//! - above it, a sky rising from [`FLOOR`] at the horizon to [`ZENITH`]
//!   overhead, as the square root of the sine of the elevation;
//! - a round soft box overhead, of radiance [`TOP`] and angular radius
//!   [`TOP_RADIUS_DEG`];
//! - two soft strip lights at the camera's left and right, [`SIDE_ELEVATION_DEG`]
//!   up, of radiance [`SIDE`] and angular radius [`SIDE_RADIUS_DEG`];
//!
//! each light's edge falls off over [`SOFT_DEG`] (a smoothstep). The map is
//! turned about `+y` so that the camera sees the studio from its front
//! whatever its azimuth ([`environment`]). Its mean radiance is [`MEAN`]: the
//! Whitted tracer, whose diffuse surfaces see the environment only through
//! the lecture's ambient term, gets that as its ambient light
//! ([`super::viewer::AMBIENT`]), so both integrators light a diffuse surface
//! alike on average. A scene file names it `environment = { preset = "studio" }`.

use lamplight_core::lights::environment::uv_to_direction;
use lamplight_core::lights::{EnvMap, Environment};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::Error;

/// Map width in pixels.
pub const WIDTH: usize = 256;
/// Map height in pixels (rows at the zenith and the nadir included).
pub const HEIGHT: usize = 129;
/// Radiance of the floor, below the horizon.
pub const FLOOR: f64 = 0.2;
/// Radiance of the sky overhead (rising from [`FLOOR`] at the horizon).
pub const ZENITH: f64 = 0.25;
/// Radiance added by the soft box overhead.
pub const TOP: f64 = 0.6;
/// Angular radius of the soft box overhead, degrees.
pub const TOP_RADIUS_DEG: f64 = 30.0;
/// Radiance added by each side strip.
pub const SIDE: f64 = 0.8;
/// Angular radius of each side strip, degrees.
pub const SIDE_RADIUS_DEG: f64 = 18.0;
/// Elevation of the side strips' centres, degrees.
pub const SIDE_ELEVATION_DEG: f64 = 25.0;
/// Width of each light's soft edge, degrees (half inside, half outside its radius).
pub const SOFT_DEG: f64 = 10.0;
/// Mean radiance over every direction (the tests measure the map's).
pub const MEAN: f64 = 0.3;

/// `0` below `e0`, `1` above `e1`, smooth between.
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A soft disc of angular `radius` (degrees) around the unit direction `centre`, seen from `d`: 1 inside, 0 outside.
fn disc(d: Vec3, centre: Vec3, radius: f64) -> f64 {
    let angle = d.dot(centre).clamp(-1.0, 1.0).acos().to_degrees();
    1.0 - smoothstep(radius - SOFT_DEG / 2.0, radius + SOFT_DEG / 2.0, angle)
}

/// Radiance from the unit direction `d` in the studio's own frame (module doc).
pub fn radiance(d: Vec3) -> f64 {
    if d.y < 0.0 {
        return FLOOR;
    }
    let sky = FLOOR + (ZENITH - FLOOR) * d.y.sqrt();
    let (s, c) = SIDE_ELEVATION_DEG.to_radians().sin_cos();
    let sides = disc(d, Vec3::new(c, s, 0.0), SIDE_RADIUS_DEG) + disc(d, Vec3::new(-c, s, 0.0), SIDE_RADIUS_DEG);
    sky + TOP * disc(d, Vec3::Y, TOP_RADIUS_DEG) + SIDE * sides
}

/// The studio's map, turned by `rotate` degrees about `+y`, looked up bilinearly.
pub fn map(rotate: f64) -> Result<EnvMap, Error> {
    let mut pixels = Vec::with_capacity(WIDTH * HEIGHT);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            // Where the bilinear lookup places pixel (x, y).
            let d = uv_to_direction((x as f64 + 0.5) / WIDTH as f64, y as f64 / (HEIGHT - 1) as f64);
            pixels.push(Rgb::splat(radiance(d)));
        }
    }
    Ok(EnvMap::new(WIDTH, HEIGHT, pixels)?.bilinear()?.with_rotation(rotate))
}

/// The turn about `+y`, degrees, that puts the studio's `+z` (where its camera
/// stands) on the side of `target` where `eye` is.
pub fn rotation_towards(eye: Vec3, target: Vec3) -> f64 {
    let t = eye - target;
    if t.x == 0.0 && t.z == 0.0 {
        return 0.0;
    }
    t.x.atan2(t.z).to_degrees()
}

/// The studio for a camera at `eye` looking at `target`.
pub fn environment(eye: Vec3, target: Vec3) -> Result<Environment, Error> {
    Ok(Environment::Map(map(rotation_towards(eye, target))?))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// The mean of `f` over the sphere of directions (a fine grid in `(cos theta, phi)`, equal areas).
    fn sphere_mean(n: usize, f: impl Fn(Vec3) -> f64) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            for j in 0..2 * n {
                let phi = 2.0 * PI * (j as f64 + 0.5) / (2 * n) as f64;
                sum += f(Vec3::new(r * phi.cos(), y, r * phi.sin()));
            }
        }
        sum / (2 * n * n) as f64
    }

    #[test]
    fn the_map_s_mean_is_the_stated_mean_and_the_floor_is_the_old_surround() {
        let env = Environment::Map(map(0.0).unwrap());
        let mean = sphere_mean(400, |d| env.radiance(d).x);
        assert!((mean - MEAN).abs() < 0.01, "{mean}");
        assert_eq!(env.radiance(Vec3::new(0.3, -0.5, 0.8).normalize()), Rgb::splat(FLOOR));
        // Bright overhead and at the sides, not behind the model.
        let up = env.radiance(Vec3::Y).x;
        assert!((up - (ZENITH + TOP)).abs() < 0.01, "{up}");
        let (s, c) = SIDE_ELEVATION_DEG.to_radians().sin_cos();
        assert!(env.radiance(Vec3::new(c, s, 0.0)).x > FLOOR + 0.9 * SIDE);
        assert!(env.radiance(Vec3::new(0.0, s, -c)).x < ZENITH);
    }

    #[test]
    fn the_turned_studio_puts_its_side_lights_at_the_camera_s_sides() {
        let (eye, target) = (Vec3::new(3.0, 2.0, 4.0), Vec3::new(1.0, 0.0, 1.0));
        let env = environment(eye, target).unwrap();
        let forward = (target - eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let (s, c) = SIDE_ELEVATION_DEG.to_radians().sin_cos();
        for side in [right, -right] {
            let radiance = env.radiance(side * c + Vec3::Y * s).x;
            assert!(radiance > FLOOR + 0.9 * SIDE, "{radiance}");
        }
        let ahead = Vec3::new(forward.x, 0.0, forward.z).normalize() * c + Vec3::Y * s;
        assert!(env.radiance(ahead).x < ZENITH, "behind the model the sky is dim");
    }

    #[test]
    fn a_diffuse_white_lit_by_the_studio_and_the_viewer_s_lights_does_not_clip() {
        // What the path tracer gives a diffuse white (albedo 1) facing `n`:
        // E / pi of the studio plus the directional lights it faces.
        let (eye, target) = (Vec3::new(3.0, 2.0, 4.0), Vec3::ZERO);
        let env = environment(eye, target).unwrap();
        let lights = super::super::viewer::lights(eye, target).unwrap();
        let mut most = 0.0f64;
        for k in 0..200 {
            // A spiral of normals over the sphere.
            let y = 1.0 - 2.0 * (k as f64 + 0.5) / 200.0;
            let phi = k as f64 * 2.399963;
            let n = Vec3::new((1.0 - y * y).sqrt() * phi.cos(), y, (1.0 - y * y).sqrt() * phi.sin());
            let sky = 4.0 * sphere_mean(60, |d| env.radiance(d).x * d.dot(n).max(0.0));
            let direct: f64 = lights.iter().map(|l| l.radiance.x * (-l.direction).dot(n).max(0.0)).sum();
            most = most.max(sky + direct);
        }
        assert!(most < 0.97, "{most}: a diffuse white clips under path tracing");
    }
}
