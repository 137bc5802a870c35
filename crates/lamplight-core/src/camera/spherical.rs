//! A full panorama: every direction around the eye, laid out as an
//! equirectangular (latitude-longitude) image, pbrt's `spherical` camera and
//! Blender's panoramic "equirectangular" lens.
//!
//! With the view direction `w`, unit right `r = normalize(w x sky)` and up
//! `u = r x w`, film point `(x, y)` of a `W x H` image has longitude
//! `phi = (2x/W - 1) pi` (0 at the centre, growing to the right) and latitude
//! `theta = (1 - 2y/H) pi/2` (the top row looks straight up), and its ray leaves
//! the eye along `cos(theta) (sin(phi) r + cos(phi) w) + sin(theta) u`.
//!
//! From the origin looking along `-z` with `y` up this is exactly the layout of
//! lamplight's environment maps ([`crate::lights::environment`]), so a
//! panorama rendered there can be read back as an environment map. The mapping
//! fills any image; a 2:1 image has square pixels at the equator.

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::Arc;

use super::{film_ndc, Camera, CameraKind};
use crate::math::Vec3;
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `spherical`: every direction around the eye, equirectangular.
pub const KIND: CameraKind = Kind {
    name: "spherical",
    summary: "a 360 x 180 degree panorama around the eye in equirectangular layout (best at a 2:1 image), pbrt's `spherical`",
    params: &[
        Param::new("eye", T::Point, "", "", "centre of the panorama"),
        Param::new("look_at", T::Point, "", "", "the direction at the image's centre goes through this point"),
        Param::new("up", T::Vector, "[0, 1, 0]", "", "the direction of the image's top row"),
    ],
    build: |p| {
        let (eye, target) = (p.required_vec3("eye")?, p.required_vec3("look_at")?);
        let sky = p.vec3("up")?.unwrap_or(Vec3::Y);
        Ok(Arc::new(Spherical::look_at(eye, target, sky).map_err(|e| p.core_error(e))?))
    },
};

/// An equirectangular panorama camera.
#[derive(Clone, Debug, PartialEq)]
pub struct Spherical {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

impl Spherical {
    /// At `eye`, the image centre looking towards `target`, `sky` giving the up
    /// direction (not parallel to the view direction).
    pub fn look_at(eye: Vec3, target: Vec3, sky: Vec3) -> Result<Spherical, Error> {
        if !(eye.is_finite() && target.is_finite() && sky.is_finite()) {
            return Err(Error::invalid("camera", "eye, lookat and up must be finite"));
        }
        let forward = (target - eye).try_normalize().ok_or_else(|| Error::invalid("camera", "eye and lookat coincide"))?;
        let right = forward
            .cross(sky)
            .try_normalize()
            .ok_or_else(|| Error::invalid("camera", "up is zero or parallel to the viewing direction"))?;
        Ok(Spherical { eye, forward, right, up: right.cross(forward) })
    }
}

impl Camera for Spherical {
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, _lens: (f64, f64)) -> Ray {
        let (alpha, beta) = film_ndc(x, y, width, height);
        let (sin_phi, cos_phi) = (alpha * PI).sin_cos();
        let (sin_theta, cos_theta) = (beta * FRAC_PI_2).sin_cos();
        let dir = (self.right * sin_phi + self.forward * cos_phi) * cos_theta + self.up * sin_theta;
        Ray::unit(self.eye, dir.normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lights::environment::uv_to_direction;

    #[test]
    fn the_default_frame_is_the_environment_maps_layout() {
        // Every pixel centre of a 64 x 32 panorama looks where the environment
        // map's texel of the same (u, v) lies.
        let cam = Spherical::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y).unwrap();
        let (w, h) = (64u32, 32u32);
        for y in 0..h {
            for x in 0..w {
                let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
                let ray = cam.ray(fx, fy, w, h, (0.5, 0.5));
                let expected = uv_to_direction(fx / w as f64, fy / h as f64);
                assert!((ray.dir - expected).length() < 1e-12, "pixel ({x}, {y}): {} vs {expected}", ray.dir);
                assert_eq!(ray.origin, Vec3::ZERO);
            }
        }
    }

    #[test]
    fn centre_edges_and_poles_of_a_turned_panorama() {
        // Looking along +x with z up: right is x cross z = -y.
        let eye = Vec3::new(1.0, 2.0, 3.0);
        let cam = Spherical::look_at(eye, eye + Vec3::X, Vec3::Z).unwrap();
        let (w, h) = (200, 100);
        let dir = |x: f64, y: f64| cam.ray(x, y, w, h, (0.5, 0.5)).dir;
        let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-12;
        assert!(close(dir(100.0, 50.0), Vec3::X), "the centre looks ahead");
        assert!(close(dir(150.0, 50.0), -Vec3::Y), "a quarter turn right");
        assert!(close(dir(50.0, 50.0), Vec3::Y), "a quarter turn left");
        assert!(close(dir(0.0, 50.0), -Vec3::X) && close(dir(200.0, 50.0), -Vec3::X), "both side edges look behind");
        assert!(close(dir(37.0, 0.0), Vec3::Z) && close(dir(123.0, 100.0), -Vec3::Z), "top and bottom rows are the poles");
        // Latitude 45 degrees up, straight ahead.
        assert!(close(dir(100.0, 25.0), (Vec3::X + Vec3::Z).normalize()));
        assert_eq!(cam.ray(3.0, 4.0, w, h, (0.5, 0.5)).origin, eye);
    }

    #[test]
    fn bad_frames_are_errors() {
        let message = |r: Result<Spherical, Error>| r.unwrap_err().to_string();
        assert_eq!(message(Spherical::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y)), "invalid camera: eye and lookat coincide");
        assert_eq!(
            message(Spherical::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y)),
            "invalid camera: up is zero or parallel to the viewing direction"
        );
        assert_eq!(
            message(Spherical::look_at(Vec3::ZERO, Vec3::X, Vec3::ZERO)),
            "invalid camera: up is zero or parallel to the viewing direction"
        );
        assert!(Spherical::look_at(Vec3::new(f64::NAN, 0.0, 0.0), Vec3::X, Vec3::Y).is_err());
    }
}
