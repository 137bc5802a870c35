//! The lecture's pinhole camera: an eye and a window rectangle in world space.
//!
//! The window is centred on `lookat`; `right` points from its centre to its right
//! edge and `up` to its top edge. The film point `(x, y)` (pixels, from the
//! top-left corner, `x` in `[0, W]`, `y` in `[0, H]`) maps to the normalized
//! coordinates `alpha = 2x/W - 1`, `beta = 1 - 2y/H` and the window point
//! `p = lookat + alpha * right + beta * up`; the ray goes from `eye` through `p`.
//! A pixel's single sample sits at `pixel_offset` inside it (0.5: the centre).

use crate::math::Vec3;
use crate::ray::Ray;
use crate::Error;

/// Which angle a field of view measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fov {
    /// Full vertical angle in degrees (POV-Ray's and SCENES.md's `vfov`).
    VerticalDeg(f64),
    /// Full horizontal angle in degrees (POV-Ray's `angle`).
    HorizontalDeg(f64),
}

/// A pinhole camera in the lecture's eye/lookat/right/up form.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position, the origin of every primary ray.
    pub eye: Vec3,
    /// Centre of the window rectangle.
    pub lookat: Vec3,
    /// From the window centre to its right edge.
    pub right: Vec3,
    /// From the window centre to its top edge.
    pub up: Vec3,
    /// Where in a pixel the single sample goes (0.5 = centre; 0 = the corner that
    /// the lecture's `2X/XM - 1` and Heckbert's card use). With several samples per
    /// pixel the strata are shifted by `pixel_offset - 0.5`.
    pub pixel_offset: f64,
}

impl Camera {
    /// A camera at `eye` looking at `target`, `sky` giving the up direction, with a
    /// field of view and the image aspect `width / height`.
    ///
    /// `w = normalize(target - eye)`, `r = normalize(w x sky)`, `u = r x w`; the window
    /// is one unit in front of the eye with half-extents `tan(hfov/2) r` and
    /// `tan(vfov/2) u`, where `tan(hfov/2) = aspect * tan(vfov/2)`.
    pub fn look_at(eye: Vec3, target: Vec3, sky: Vec3, fov: Fov, aspect: f64) -> Result<Camera, Error> {
        if !(eye.is_finite() && target.is_finite() && sky.is_finite()) {
            return Err(Error::invalid("camera", "eye, lookat and up must be finite"));
        }
        let w = (target - eye).try_normalize().ok_or_else(|| Error::invalid("camera", "eye and lookat coincide"))?;
        let r = w.cross(sky).try_normalize().ok_or_else(|| Error::invalid("camera", "up is parallel to the viewing direction"))?;
        let u = r.cross(w);
        if !(aspect.is_finite() && aspect > 0.0) {
            return Err(Error::invalid("aspect", "must be positive"));
        }
        let (tan_h, tan_v) = match fov {
            Fov::VerticalDeg(deg) => {
                let tan_v = half_tan(deg)?;
                (tan_v * aspect, tan_v)
            }
            Fov::HorizontalDeg(deg) => {
                let tan_h = half_tan(deg)?;
                (tan_h, tan_h / aspect)
            }
        };
        Ok(Camera { eye, lookat: eye + w, right: r * tan_h, up: u * tan_v, pixel_offset: 0.5 })
    }

    /// The ray through film point `(x, y)` of a `width x height` image (see the module doc).
    #[inline]
    pub fn ray(&self, x: f64, y: f64, width: u32, height: u32) -> Ray {
        let alpha = 2.0 * x / width as f64 - 1.0;
        let beta = 1.0 - 2.0 * y / height as f64;
        let p = self.lookat + self.right * alpha + self.up * beta;
        Ray::new(self.eye, p - self.eye)
    }
}

fn half_tan(deg: f64) -> Result<f64, Error> {
    if !(deg > 0.0 && deg < 180.0) {
        return Err(Error::invalid("fov", format!("must be between 0 and 180 degrees, got {deg}")));
    }
    Ok((deg.to_radians() / 2.0).tan())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres_camera() -> Camera {
        Camera::look_at(Vec3::new(0.0, 6.5, 10.5), Vec3::new(0.0, 0.0, 0.8), Vec3::Y, Fov::VerticalDeg(40.0), 16.0 / 9.0).unwrap()
    }

    #[test]
    fn centre_ray_points_at_target() {
        let cam = spheres_camera();
        let ray = cam.ray(640.0, 360.0, 1280, 720);
        let expected = (Vec3::new(0.0, 0.0, 0.8) - Vec3::new(0.0, 6.5, 10.5)).normalize();
        assert!((ray.dir - expected).length() < 1e-14);
        assert_eq!(ray.origin, cam.eye);
    }

    #[test]
    fn corner_rays_span_the_field_of_view() {
        // SCENES.md: w = (0, -0.5566749923, -0.8307303732), r = (1,0,0),
        // u = (0, 0.8307303732, -0.5566749923), tan(vfov/2) = 0.3639702343.
        let cam = spheres_camera();
        let w = Vec3::new(0.0, -0.5566749923, -0.8307303732);
        let u = Vec3::new(0.0, 0.8307303732, -0.5566749923);
        let tan_v = 0.3639702343;
        let tan_h = tan_v * 16.0 / 9.0;
        let top_left = cam.ray(0.0, 0.0, 1280, 720).dir;
        let expected = (w - Vec3::X * tan_h + u * tan_v).normalize();
        assert!((top_left - expected).length() < 1e-9, "{top_left} vs {expected}");
        let bottom_right = cam.ray(1280.0, 720.0, 1280, 720).dir;
        let expected = (w + Vec3::X * tan_h - u * tan_v).normalize();
        assert!((bottom_right - expected).length() < 1e-9);
        // The vertical angle between top and bottom edge centres is the vfov.
        let top = cam.ray(640.0, 0.0, 1280, 720).dir;
        let bottom = cam.ray(640.0, 720.0, 1280, 720).dir;
        assert!((top.dot(bottom).acos().to_degrees() - 40.0).abs() < 1e-9);
        let left = cam.ray(0.0, 360.0, 1280, 720).dir;
        let right = cam.ray(1280.0, 360.0, 1280, 720).dir;
        assert!((left.dot(right).acos().to_degrees() - 65.8104350172).abs() < 1e-8);
    }

    #[test]
    fn bad_cameras_are_errors() {
        assert!(Camera::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0), 1.0).is_err());
        assert!(Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, Fov::VerticalDeg(40.0), 1.0).is_err());
        assert!(Camera::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, Fov::VerticalDeg(180.0), 1.0).is_err());
    }
}
