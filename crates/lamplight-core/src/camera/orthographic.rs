//! A parallel projection: every ray has the view direction, and the film maps
//! onto a window around the eye.
//!
//! The window is centred on the eye, perpendicular to the view direction `w`, with
//! unit right `r = normalize(w x sky)` and up `u = r x w`. It is given by its
//! half-width `hw` and half-height `hh`; an image of another aspect
//! `a = width / height` widens it along one side so that the whole given window
//! stays in view undistorted (glTF's rule for `xmag`/`ymag`: no crop, no
//! stretch): `(hh a, hh)` when `a >= hw / hh`, else `(hw, hw / a)`. Film point
//! `(x, y)` starts its ray at `eye + alpha hw' r + beta hh' u` ([`super::film_ndc`]).

use std::sync::Arc;

use super::{aspect, film_ndc, Camera, CameraKind};
use crate::math::Vec3;
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `orthographic`: parallel rays from a window around the eye.
pub const KIND: CameraKind = Kind {
    name: "orthographic",
    summary: "parallel rays along `look_at - eye` from a window centred on the eye, at least `half_width x half_height` whatever the image's aspect",
    params: &[
        Param::new("eye", T::Point, "", "", "centre of the window"),
        Param::new("look_at", T::Point, "", "", "a point the view direction goes through"),
        Param::new("up", T::Vector, "[0, 1, 0]", "", "sky direction"),
        Param::new("half_width", T::Number, "half_height", "scene units, > 0", "half the window's width (glTF's xmag)"),
        Param::new("half_height", T::Number, "1", "scene units, > 0", "half the window's height (glTF's ymag)"),
    ],
    build: |p| {
        let (eye, target) = (p.required_vec3("eye")?, p.required_vec3("look_at")?);
        let sky = p.vec3("up")?.unwrap_or(Vec3::Y);
        let half_height = p.number("half_height")?;
        let half_width = p.number("half_width")?;
        let (hw, hh) = match (half_width, half_height) {
            (Some(w), Some(h)) => (w, h),
            (Some(w), None) => (w, w),
            (None, Some(h)) => (h, h),
            (None, None) => (1.0, 1.0),
        };
        Ok(Arc::new(Orthographic::look_at(eye, target, sky, hw, hh).map_err(|e| p.core_error(e))?))
    },
};

/// An orthographic camera.
#[derive(Clone, Debug, PartialEq)]
pub struct Orthographic {
    eye: Vec3,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
    half_width: f64,
    half_height: f64,
}

impl Orthographic {
    /// Looking from `eye` towards `target`, `sky` giving the up direction, seeing
    /// at least the window of half-extents `half_width x half_height` (see the module doc).
    pub fn look_at(eye: Vec3, target: Vec3, sky: Vec3, half_width: f64, half_height: f64) -> Result<Orthographic, Error> {
        if !(eye.is_finite() && target.is_finite() && sky.is_finite()) {
            return Err(Error::invalid("camera", "eye, lookat and up must be finite"));
        }
        for (name, v) in [("half_width", half_width), ("half_height", half_height)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, format!("must be a positive number, got {v}")));
            }
        }
        let dir = (target - eye).try_normalize().ok_or_else(|| Error::invalid("camera", "eye and lookat coincide"))?;
        if sky.try_normalize().is_none() {
            return Err(Error::invalid("up", format!("is the zero vector [{}, {}, {}], expected a direction", sky.x, sky.y, sky.z)));
        }
        let right = dir.cross(sky).try_normalize().ok_or_else(|| Error::invalid("camera", "up is parallel to the viewing direction"))?;
        Ok(Orthographic { eye, dir, right, up: right.cross(dir), half_width, half_height })
    }

    /// A square window of half-extent `scale`: `scale` across the image's shorter
    /// side, `scale * aspect` across the longer (pbrt's default screen window, scaled).
    pub fn with_scale(eye: Vec3, target: Vec3, sky: Vec3, scale: f64) -> Result<Orthographic, Error> {
        Orthographic::look_at(eye, target, sky, scale, scale)
    }

    /// The window's half-extents `(half-width, half-height)` for an image of aspect `aspect`.
    pub fn half_extents(&self, aspect: f64) -> (f64, f64) {
        let (hw, hh) = (self.half_width, self.half_height);
        if aspect >= hw / hh {
            (hh * aspect, hh)
        } else {
            (hw, hw / aspect)
        }
    }
}

impl Camera for Orthographic {
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, _lens: (f64, f64)) -> Ray {
        let (hw, hh) = self.half_extents(aspect(width, height));
        let (alpha, beta) = film_ndc(x, y, width, height);
        Ray::unit(self.eye + self.right * (alpha * hw) + self.up * (beta * hh), self.dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_are_parallel_and_start_across_the_window() {
        let eye = Vec3::new(1.0, 2.0, 3.0);
        let cam = Orthographic::look_at(eye, eye - Vec3::Z, Vec3::Y, 2.0, 1.0).unwrap();
        // A 2:1 image fits the 4 x 2 window exactly.
        let (w, h) = (40, 20);
        for (x, y) in [(0.0, 0.0), (40.0, 20.0), (20.0, 10.0), (3.5, 17.0)] {
            let ray = cam.ray(x, y, w, h, (0.5, 0.5));
            assert_eq!(ray.dir, -Vec3::Z, "parallel to the view direction");
            let expected = eye + Vec3::new(-2.0 + 4.0 * x / 40.0, 1.0 - 2.0 * y / 20.0, 0.0);
            assert!((ray.origin - expected).length() < 1e-14, "({x}, {y}): {} vs {expected}", ray.origin);
        }
    }

    #[test]
    fn other_aspects_widen_the_window_without_stretching() {
        let cam = Orthographic::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, 2.0, 1.0).unwrap();
        // Wider than 2:1: the height stays, the width grows; narrower: the reverse.
        assert_eq!(cam.half_extents(4.0), (4.0, 1.0));
        assert_eq!(cam.half_extents(1.0), (2.0, 2.0));
        for (w, h) in [(400u32, 100u32), (100, 100), (50, 100)] {
            let span = |x0: f64, y0: f64, x1: f64, y1: f64| {
                (cam.ray(x1, y1, w, h, (0.5, 0.5)).origin - cam.ray(x0, y0, w, h, (0.5, 0.5)).origin).length()
            };
            let (across, down) = (span(0.0, 0.0, w as f64, 0.0), span(0.0, 0.0, 0.0, h as f64));
            assert!(across >= 4.0 - 1e-12 && down >= 2.0 - 1e-12, "{w}x{h}: the given window stays in view");
            assert!((across / down - w as f64 / h as f64).abs() < 1e-12, "{w}x{h}: square pixels");
        }
        let square = Orthographic::with_scale(Vec3::ZERO, Vec3::Z, Vec3::Y, 3.0).unwrap();
        assert_eq!((square.half_extents(2.0), square.half_extents(0.5)), ((6.0, 3.0), (3.0, 6.0)));
    }

    #[test]
    fn bad_windows_are_errors() {
        assert!(Orthographic::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, 0.0, 1.0).is_err());
        assert!(Orthographic::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, 1.0, f64::INFINITY).is_err());
        assert!(Orthographic::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y, 1.0, 1.0).is_err());
        assert!(Orthographic::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, 1.0, 1.0).is_err());
    }
}
