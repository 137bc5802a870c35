//! The lecture's pinhole camera: an eye and a window rectangle in world space.
//!
//! The window is centred on `lookat`; `right` points from its centre to its right
//! edge and `up` to its top edge. Film point `(x, y)` maps to the window point
//! `p = lookat + alpha * right + beta * up` (`alpha`, `beta` from
//! [`super::film_ndc`]), and the ray goes from `eye` through `p`.
//!
//! The window follows the image's aspect `a = width / height` at render time, so
//! the camera is built once for every image size:
//! - look-at form: `w = normalize(target - eye)`, `r = normalize(w x sky)`,
//!   `u = r x w`; the window is one unit in front of the eye, `lookat = eye + w`,
//!   with `right = r tan(hfov/2)` and `up = u tan(vfov/2)`, where
//!   `tan(hfov/2) = a tan(vfov/2)` ([`Fov::half_tangents`]);
//! - window form: `lookat`, `right` and `up` as given, with a [`Fit`] saying which
//!   of them the aspect scales.
//!
//! A lens shift `shift = [sx, sy]` (Blender's `shift_x`, `shift_y`) slides the
//! window in its own plane without turning the camera, in units of the image's
//! larger side: `lookat + 2 right sx m / a + 2 up sy m` with `m = max(1, a)`, so
//! `sx = 0.5` moves the view right by half the width of a landscape image and
//! `sy > 0` moves it up. Lines parallel to the window stay parallel (a shifted
//! architectural view), unlike turning the camera.

use std::sync::Arc;

use super::{aspect, film_ndc, Camera, CameraKind, Fov};
use crate::math::Vec3;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};
use crate::ray::Ray;
use crate::Error;

/// The look-at parameters, shared by the kinds built on the look-at form.
pub const LOOK_AT_PARAMS: [Param; 8] = [
    Param::new("eye", T::Point, "", "", "eye position"),
    Param::new("look_at", T::Point, "", "", "point at the image centre"),
    Param::new("up", T::Vector, "[0, 1, 0]", "", "sky direction"),
    Param::new("vfov", T::Number, "one of vfov, hfov, fov", "degrees, 0 to 180", "full vertical field of view"),
    Param::new("hfov", T::Number, "one of vfov, hfov, fov", "degrees, 0 to 180", "full horizontal field of view"),
    Param::new(
        "fov",
        T::Number,
        "one of vfov, hfov, fov",
        "degrees, 0 to 180",
        "full field of view across the image's shorter side, whatever its aspect (pbrt's `fov`)",
    ),
    Param::new("pixel_offset", T::Number, "0.5", "0 to 1", "where in a pixel its sample is (0 = corner, 0.5 = centre)"),
    Param::new(
        "shift",
        T::Pair,
        "[0, 0]",
        "each -100 to 100",
        "lens shift `[x, y]` in units of the image's larger side, `x` right and `y` up (Blender's `shift_x`, `shift_y`; Mitsuba's principal point offset)",
    ),
];

/// `perspective`: the look-at pinhole camera (the default camera type).
pub const PERSPECTIVE_KIND: CameraKind = Kind {
    name: "perspective",
    summary: "a pinhole camera looking from `eye` at `look_at`",
    params: &LOOK_AT_PARAMS,
    build: |p| Ok(Arc::new(read_look_at(p)?)),
};

/// `window`: the lecture's eye and window; a camera table with `window_center`
/// and no `type` is this kind.
pub const WINDOW_KIND: CameraKind = Kind {
    name: "window",
    summary: "the lecture's camera: the window `window_center + a right + b up`, `a, b` in [-1, 1], seen from `eye`",
    params: &[
        Param::new("eye", T::Point, "", "", "eye position"),
        Param::new("window_center", T::Point, "", "", "centre of the window"),
        Param::new("right", T::Vector, "", "", "from the window centre to its right edge"),
        Param::new("up", T::Vector, "", "", "from the window centre to its top edge"),
        Param::new("pixel_offset", T::Number, "0.5", "0 to 1", "as for `perspective`"),
        Param::new(
            "fit",
            T::String,
            "\"none\"",
            "",
            "`\"none\"`: vectors as written; `\"width\"`: written for a square image, `up` is divided by width/height; `\"height\"`: `right` is multiplied by it",
        ),
    ],
    build: |p| {
        let (eye, center) = (p.required_vec3("eye")?, p.required_vec3("window_center")?);
        let (right, up) = (p.required_vec3("right")?, p.required_vec3("up")?);
        let fit = match p.choice("fit", &["none", "width", "height"])? {
            "none" => Fit::None,
            "width" => Fit::Width,
            _ => Fit::Height,
        };
        let camera = Perspective::window(eye, center, right, up, fit).map_err(|e| p.error(e))?;
        Ok(Arc::new(with_offset(p, camera)?))
    },
};

/// The look-at camera [`LOOK_AT_PARAMS`] describe.
pub fn read_look_at(p: &mut Params<'_>) -> ParamResult<Perspective> {
    let eye = p.required_vec3("eye")?;
    let target = p.required_vec3("look_at")?;
    let sky = p.vec3("up")?.unwrap_or(Vec3::Y);
    let fov = match (p.number("vfov")?, p.number("hfov")?, p.number("fov")?) {
        (Some(v), None, None) => Fov::VerticalDeg(v),
        (None, Some(h), None) => Fov::HorizontalDeg(h),
        (None, None, Some(s)) => Fov::SmallerSideDeg(s),
        (None, None, None) => return Err(p.error("needs vfov, hfov or fov (degrees)")),
        _ => return Err(p.error("takes one of vfov, hfov and fov")),
    };
    let camera = Perspective::look_at(eye, target, sky, fov).map_err(|e| p.core_error(e))?;
    let camera = match p.pair("shift")? {
        Some(shift) => camera.with_shift(shift).map_err(|e| p.core_error(e))?,
        None => camera,
    };
    with_offset(p, camera)
}

fn with_offset(p: &mut Params<'_>, camera: Perspective) -> ParamResult<Perspective> {
    match p.number("pixel_offset")? {
        Some(offset) => camera.with_pixel_offset(offset).map_err(|e| p.core_error(e)),
        None => Ok(camera),
    }
}

/// How a window given as vectors follows the image's aspect `a = width / height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Fit {
    /// The vectors as written, whatever the aspect.
    #[default]
    None,
    /// Written for a square image, keeping its width: `up / a`.
    Width,
    /// Written for a square image, keeping its height: `right * a`.
    Height,
}

/// Where the window comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Window {
    /// Look-at form: the window centre `eye + w`, unit `r` and `u`, the field of
    /// view and `tan(fov/2)` of the side it measures.
    LookAt { lookat: Vec3, r: Vec3, u: Vec3, fov: Fov, tan_half: f64 },
    /// Window form.
    Vectors { lookat: Vec3, right: Vec3, up: Vec3, fit: Fit },
}

/// A pinhole camera in the lecture's eye/lookat/right/up form.
#[derive(Clone, Debug, PartialEq)]
pub struct Perspective {
    eye: Vec3,
    window: Window,
    pixel_offset: f64,
    /// Lens shift `[sx, sy]` in units of the image's larger side (see the module doc).
    shift: [f64; 2],
}

/// Largest lens shift, in image sides: far beyond any lens, small enough that
/// window points stay finite.
pub const MAX_SHIFT: f64 = 100.0;

impl Perspective {
    /// A camera at `eye` looking at `target`, `sky` giving the up direction, with a
    /// field of view (see the module doc for the window it makes).
    pub fn look_at(eye: Vec3, target: Vec3, sky: Vec3, fov: Fov) -> Result<Perspective, Error> {
        if !(eye.is_finite() && target.is_finite() && sky.is_finite()) {
            return Err(Error::invalid("camera", "eye, lookat and up must be finite"));
        }
        let w = (target - eye).try_normalize().ok_or_else(|| Error::invalid("camera", "eye and lookat coincide"))?;
        if sky.try_normalize().is_none() {
            return Err(Error::invalid("up", format!("is the zero vector [{}, {}, {}], expected a direction", sky.x, sky.y, sky.z)));
        }
        let r = w.cross(sky).try_normalize().ok_or_else(|| Error::invalid("camera", "up is parallel to the viewing direction"))?;
        let u = r.cross(w);
        let tan_half = fov.half_tan()?;
        Ok(Perspective { eye, window: Window::LookAt { lookat: eye + w, r, u, fov, tan_half }, pixel_offset: 0.5, shift: [0.0; 2] })
    }

    /// The lecture's raw window: centre `lookat`, half-width vector `right`,
    /// half-height vector `up`, scaled with the aspect as `fit` says.
    pub fn window(eye: Vec3, lookat: Vec3, right: Vec3, up: Vec3, fit: Fit) -> Result<Perspective, Error> {
        if ![eye, lookat, right, up].iter().all(|v| v.is_finite()) {
            return Err(Error::invalid("camera", "eye, window centre, right and up must be finite"));
        }
        if right.cross(up).length_squared() == 0.0 {
            return Err(Error::invalid("camera", "right and up must be non-zero and not parallel"));
        }
        Ok(Perspective { eye, window: Window::Vectors { lookat, right, up, fit }, pixel_offset: 0.5, shift: [0.0; 2] })
    }

    /// The same camera with its single sample at `offset` inside each pixel (0.5 =
    /// centre; 0 = the corner that the lecture's `2X/XM - 1` and Heckbert's card use).
    pub fn with_pixel_offset(self, offset: f64) -> Result<Perspective, Error> {
        if !(0.0..=1.0).contains(&offset) {
            return Err(Error::invalid("pixel_offset", format!("must be between 0 and 1, got {offset}")));
        }
        Ok(Perspective { pixel_offset: offset, ..self })
    }

    /// The same camera with lens shift `shift = [sx, sy]` (see the module doc),
    /// each finite and at most [`MAX_SHIFT`] in magnitude.
    pub fn with_shift(self, shift: [f64; 2]) -> Result<Perspective, Error> {
        if !shift.iter().all(|s| s.is_finite() && s.abs() <= MAX_SHIFT) {
            return Err(Error::invalid(
                "shift",
                format!("must be two finite numbers of at most {MAX_SHIFT} in magnitude, got [{}, {}]", shift[0], shift[1]),
            ));
        }
        Ok(Perspective { shift, ..self })
    }

    /// The eye: the origin of every ray.
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// The window `(lookat, right, up)` for an image of aspect `aspect = width / height`,
    /// its centre moved by the lens shift.
    #[inline]
    pub fn window_at(&self, aspect: f64) -> (Vec3, Vec3, Vec3) {
        let (lookat, right, up) = self.unshifted_window(aspect);
        if self.shift == [0.0; 2] {
            return (lookat, right, up);
        }
        let larger = aspect.max(1.0);
        (lookat + right * (2.0 * self.shift[0] * larger / aspect) + up * (2.0 * self.shift[1] * larger), right, up)
    }

    fn unshifted_window(&self, aspect: f64) -> (Vec3, Vec3, Vec3) {
        match self.window {
            Window::LookAt { lookat, r, u, fov, tan_half } => {
                let (tan_h, tan_v) = fov.half_tangents(tan_half, aspect);
                (lookat, r * tan_h, u * tan_v)
            }
            Window::Vectors { lookat, right, up, fit } => match fit {
                Fit::None => (lookat, right, up),
                Fit::Width => (lookat, right, up / aspect),
                Fit::Height => (lookat, right * aspect, up),
            },
        }
    }
}

impl Camera for Perspective {
    #[inline]
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, _lens: (f64, f64)) -> Ray {
        let (lookat, right, up) = self.window_at(aspect(width, height));
        let (alpha, beta) = film_ndc(x, y, width, height);
        let p = lookat + right * alpha + up * beta;
        Ray::new(self.eye, p - self.eye)
    }

    fn pixel_offset(&self) -> f64 {
        self.pixel_offset
    }

    fn for_image(&self, width: u32, height: u32) -> Option<Box<dyn Camera>> {
        let (lookat, right, up) = self.window_at(aspect(width, height));
        Some(Box::new(SizedPerspective { eye: self.eye, lookat, right, up, width, height, pixel_offset: self.pixel_offset }))
    }
}

/// A [`Perspective`] camera's window worked out for one image size.
#[derive(Clone, Debug, PartialEq)]
struct SizedPerspective {
    eye: Vec3,
    lookat: Vec3,
    right: Vec3,
    up: Vec3,
    width: u32,
    height: u32,
    pixel_offset: f64,
}

impl Camera for SizedPerspective {
    #[inline]
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, _lens: (f64, f64)) -> Ray {
        debug_assert_eq!((width, height), (self.width, self.height), "a sized camera serves one image size");
        let (alpha, beta) = film_ndc(x, y, self.width, self.height);
        let p = self.lookat + self.right * alpha + self.up * beta;
        Ray::new(self.eye, p - self.eye)
    }

    fn pixel_offset(&self) -> f64 {
        self.pixel_offset
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres_camera() -> Perspective {
        Perspective::look_at(Vec3::new(0.0, 6.5, 10.5), Vec3::new(0.0, 0.0, 0.8), Vec3::Y, Fov::VerticalDeg(40.0)).unwrap()
    }

    const CENTRE: (f64, f64) = (0.5, 0.5);

    #[test]
    fn centre_ray_points_at_target() {
        let cam = spheres_camera();
        let ray = cam.ray(640.0, 360.0, 1280, 720, CENTRE);
        let expected = (Vec3::new(0.0, 0.0, 0.8) - Vec3::new(0.0, 6.5, 10.5)).normalize();
        assert!((ray.dir - expected).length() < 1e-14);
        assert_eq!(ray.origin, cam.eye());
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
        let top_left = cam.ray(0.0, 0.0, 1280, 720, CENTRE).dir;
        let expected = (w - Vec3::X * tan_h + u * tan_v).normalize();
        assert!((top_left - expected).length() < 1e-9, "{top_left} vs {expected}");
        let bottom_right = cam.ray(1280.0, 720.0, 1280, 720, CENTRE).dir;
        let expected = (w + Vec3::X * tan_h - u * tan_v).normalize();
        assert!((bottom_right - expected).length() < 1e-9);
        // The vertical angle between top and bottom edge centres is the vfov.
        let top = cam.ray(640.0, 0.0, 1280, 720, CENTRE).dir;
        let bottom = cam.ray(640.0, 720.0, 1280, 720, CENTRE).dir;
        assert!((top.dot(bottom).acos().to_degrees() - 40.0).abs() < 1e-9);
        let left = cam.ray(0.0, 360.0, 1280, 720, CENTRE).dir;
        let right = cam.ray(1280.0, 360.0, 1280, 720, CENTRE).dir;
        assert!((left.dot(right).acos().to_degrees() - 65.8104350172).abs() < 1e-8);
    }

    #[test]
    fn the_aspect_is_applied_per_image() {
        // One camera, two image shapes: the vertical field stays 40 degrees and the
        // horizontal one follows each aspect.
        let cam = spheres_camera();
        for (w, h) in [(1280u32, 720u32), (300, 600), (7, 7)] {
            let top = cam.ray(w as f64 / 2.0, 0.0, w, h, CENTRE).dir;
            let bottom = cam.ray(w as f64 / 2.0, h as f64, w, h, CENTRE).dir;
            assert!((top.dot(bottom).acos().to_degrees() - 40.0).abs() < 1e-9, "{w}x{h}");
            let left = cam.ray(0.0, h as f64 / 2.0, w, h, CENTRE).dir;
            let right = cam.ray(w as f64, h as f64 / 2.0, w, h, CENTRE).dir;
            let hfov = 2.0 * (20f64.to_radians().tan() * w as f64 / h as f64).atan();
            assert!((left.dot(right).acos() - hfov).abs() < 1e-9, "{w}x{h}");
        }
    }

    #[test]
    fn the_smaller_side_keeps_the_field_of_view() {
        let cam = Perspective::look_at(Vec3::Z, Vec3::ZERO, Vec3::Y, Fov::SmallerSideDeg(30.0)).unwrap();
        let angle = |a: Ray, b: Ray| a.dir.dot(b.dir).acos().to_degrees();
        // Wide: the vertical angle is the field; tall: the horizontal one.
        let wide = angle(cam.ray(10.0, 0.0, 20, 10, CENTRE), cam.ray(10.0, 10.0, 20, 10, CENTRE));
        let tall = angle(cam.ray(0.0, 10.0, 10, 20, CENTRE), cam.ray(10.0, 10.0, 10, 20, CENTRE));
        assert!((wide - 30.0).abs() < 1e-9 && (tall - 30.0).abs() < 1e-9, "{wide} {tall}");
    }

    #[test]
    fn a_lens_shift_moves_a_point_by_the_shift_times_the_larger_side() {
        // Looking down -z, hfov 90 at 200x100: tan(hfov/2) = 1, tan(vfov/2) = 1/2, so
        // the point (0.5, 0.25, -1) is at alpha = beta = 1/2, pixel (150, 25). A shift
        // of [0.25, 0.1] moves the view right by 0.25 * 200 and up by 0.1 * 200 pixels,
        // so the point lands 50 pixels left and 20 lower: (100, 45).
        let cam = Perspective::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, Fov::HorizontalDeg(90.0)).unwrap();
        let point = Vec3::new(0.5, 0.25, -1.0);
        let through = |c: &Perspective, x, y| c.ray(x, y, 200, 100, CENTRE).dir.normalize();
        assert!((through(&cam, 150.0, 25.0) - point.normalize()).length() < 1e-14);
        let shifted = cam.clone().with_shift([0.25, 0.1]).unwrap();
        assert!((through(&shifted, 100.0, 45.0) - point.normalize()).length() < 1e-14);
        // A tall image: the larger side is the height (100 of 50x100), so the same
        // shift moves it 25 pixels left and 10 lower.
        let tall = |c: &Perspective| {
            let (lookat, right, up) = c.window_at(0.5);
            let d = point * (1.0 / -point.z) - lookat;
            let (alpha, beta) = (d.dot(right) / right.length_squared(), d.dot(up) / up.length_squared());
            ((alpha + 1.0) * 25.0, (1.0 - beta) * 50.0)
        };
        let (x0, y0) = tall(&cam);
        let (x1, y1) = tall(&shifted);
        assert!((x0 - x1 - 25.0).abs() < 1e-12 && (y1 - y0 - 10.0).abs() < 1e-12, "{x0} {y0} {x1} {y1}");
        assert_eq!(
            cam.with_shift([f64::NAN, 0.0]).unwrap_err().to_string(),
            "invalid shift: must be two finite numbers of at most 100 in magnitude, got [NaN, 0]"
        );
    }

    #[test]
    fn window_fits_scale_one_vector_by_the_aspect() {
        let window = |fit| Perspective::window(Vec3::ZERO, Vec3::Y, Vec3::X, Vec3::Z, fit).unwrap();
        assert_eq!(window(Fit::None).window_at(2.0), (Vec3::Y, Vec3::X, Vec3::Z));
        assert_eq!(window(Fit::Width).window_at(2.0), (Vec3::Y, Vec3::X, Vec3::Z / 2.0));
        assert_eq!(window(Fit::Height).window_at(2.0), (Vec3::Y, Vec3::X * 2.0, Vec3::Z));
        // The film's top-left corner looks through the window's top-left corner.
        let ray = window(Fit::Width).ray(0.0, 0.0, 4, 2, CENTRE);
        assert!((ray.dir - Vec3::new(-1.0, 1.0, 0.5).normalize()).length() < 1e-15);
    }

    #[test]
    fn bad_cameras_are_errors() {
        assert!(Perspective::look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).is_err());
        assert!(Perspective::look_at(Vec3::ZERO, Vec3::Y, Vec3::Y, Fov::VerticalDeg(40.0)).is_err());
        assert!(Perspective::look_at(Vec3::ZERO, Vec3::Z, Vec3::Y, Fov::VerticalDeg(180.0)).is_err());
        assert!(Perspective::window(Vec3::ZERO, Vec3::Y, Vec3::X, Vec3::X, Fit::None).is_err());
        assert!(Perspective::window(Vec3::ZERO, Vec3::Y, Vec3::X * f64::NAN, Vec3::Z, Fit::None).is_err());
        assert!(spheres_camera().with_pixel_offset(1.5).is_err());
    }
}
