//! A perspective camera with an aperture: pbrt's `perspective` camera with
//! `lensradius` and `focaldistance` (Pharr, Jakob and Humphreys, *Physically Based
//! Rendering*, 4th ed., section 5.2.3).
//!
//! A thin lens of radius `R` sits at the eye, in the plane spanned by the window's
//! right and up directions; the plane of focus lies parallel to it at distance `f`
//! along the view axis `n` (the window's normal, away from the eye). The pinhole
//! ray through film point `(x, y)`, of unit direction `d`, meets the plane of
//! focus at `q = eye + d f / (d . n)`. Every ray for that film point goes
//! through `q`: it starts at the lens point `eye + R (a r + b u)`, where `(a, b)` is
//! the lens sample mapped onto the unit disk (Shirley and Chiu's concentric map)
//! and `r`, `u` are unit vectors of the lens plane, and points at `q`. So points
//! on the plane of focus are sharp, and a point at distance `d` along the axis is
//! spread over a disk (the circle of confusion) of diameter `2R |d - f| / d` on
//! the plane of focus, `2R |d - f| / (d f)` on the window of a look-at camera
//! (one unit in front of the eye).

use std::sync::Arc;

use super::perspective::{read_look_at, LOOK_AT_PARAMS};
use super::{Camera, CameraKind, Perspective};
use crate::bsdfs::lambertian::concentric_disk;
use crate::math::Vec3;
use crate::params::{Kind, Param, ParamType as T};
use crate::ray::Ray;
use crate::Error;

/// `thin_lens`: the look-at camera with an aperture and a plane of focus
/// (pbrt's `perspective` with `lensradius` and `focaldistance`).
pub const KIND: CameraKind = Kind {
    name: "thin_lens",
    summary: "a look-at camera with a lens: points on the plane of focus are sharp, others blur by their circle of confusion",
    params: &[
        LOOK_AT_PARAMS[0],
        LOOK_AT_PARAMS[1],
        LOOK_AT_PARAMS[2],
        LOOK_AT_PARAMS[3],
        LOOK_AT_PARAMS[4],
        LOOK_AT_PARAMS[5],
        LOOK_AT_PARAMS[6],
        LOOK_AT_PARAMS[7],
        Param::new("lens_radius", T::Number, "", "scene units, >= 0", "radius of the aperture (pbrt's lensradius); 0 is a pinhole"),
        Param::new(
            "focal_distance",
            T::Number,
            "|look_at - eye|",
            "scene units, > 0",
            "distance of the plane of focus along the view axis",
        ),
    ],
    build: |p| {
        let radius = p.required_number("lens_radius")?;
        let focus = p.number("focal_distance")?;
        let default_focus = p.vec3("eye")?.zip(p.vec3("look_at")?).map(|(e, t)| (t - e).length());
        let pinhole = read_look_at(p)?;
        let focus = focus.or(default_focus).unwrap_or(1.0);
        Ok(Arc::new(ThinLens::new(pinhole, radius, focus).map_err(|e| p.core_error(e))?))
    },
};

/// A thin-lens camera: a [`Perspective`] camera's window, an aperture and a plane of focus.
#[derive(Clone, Debug, PartialEq)]
pub struct ThinLens {
    pinhole: Perspective,
    lens_radius: f64,
    focal_distance: f64,
    /// Unit view axis, normal to the lens and to the plane of focus.
    axis: Vec3,
    /// Unit vectors spanning the lens plane.
    lens_right: Vec3,
    lens_up: Vec3,
}

impl ThinLens {
    /// `pinhole` with a lens of radius `lens_radius` (0: a pinhole) focused at
    /// distance `focal_distance` along the view axis.
    pub fn new(pinhole: Perspective, lens_radius: f64, focal_distance: f64) -> Result<ThinLens, Error> {
        if !(lens_radius.is_finite() && lens_radius >= 0.0) {
            return Err(Error::invalid("lens_radius", format!("must be a non-negative number, got {lens_radius}")));
        }
        if !(focal_distance.is_finite() && focal_distance > 0.0) {
            return Err(Error::invalid("focal_distance", format!("must be a positive number, got {focal_distance}")));
        }
        // The window's directions do not depend on the aspect (it only scales them).
        let (lookat, right, up) = pinhole.window_at(1.0);
        let normal = up.cross(right).normalize();
        let ahead = normal.dot(lookat - pinhole.eye());
        if !(ahead != 0.0 && ahead.is_finite()) {
            return Err(Error::invalid("camera", "the eye lies in the window's plane"));
        }
        let axis = if ahead > 0.0 { normal } else { -normal };
        let lens_right = right.normalize();
        let lens_up = lens_right.cross(axis);
        Ok(ThinLens { pinhole, lens_radius, focal_distance, axis, lens_right, lens_up })
    }

    /// The lens radius.
    pub fn lens_radius(&self) -> f64 {
        self.lens_radius
    }

    /// Distance of the plane of focus from the lens, along the view axis.
    pub fn focal_distance(&self) -> f64 {
        self.focal_distance
    }

    /// The unit view axis.
    pub fn axis(&self) -> Vec3 {
        self.axis
    }
}

impl Camera for ThinLens {
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, lens: (f64, f64)) -> Ray {
        let pinhole = self.pinhole.ray(x, y, width, height, lens);
        // Positive: every window point lies in front of the eye.
        let focus = pinhole.at(self.focal_distance / pinhole.dir.dot(self.axis));
        let (a, b) = concentric_disk(lens);
        let origin = pinhole.origin + self.lens_right * (self.lens_radius * a) + self.lens_up * (self.lens_radius * b);
        Ray::new(origin, focus - origin)
    }

    fn uses_lens_sample(&self) -> bool {
        self.lens_radius > 0.0
    }

    fn pixel_offset(&self) -> f64 {
        self.pinhole.pixel_offset()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fit, Fov};

    const RADIUS: f64 = 0.1;
    const FOCUS: f64 = 5.0;
    const SIZE: (u32, u32) = (200, 100);

    /// Looking down -z from the origin, 40 degrees vertically.
    fn camera() -> ThinLens {
        let pinhole = Perspective::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        ThinLens::new(pinhole, RADIUS, FOCUS).unwrap()
    }

    /// Where `ray` crosses the plane at distance `depth` along the axis.
    fn at_depth(camera: &ThinLens, ray: &Ray, depth: f64) -> Vec3 {
        ray.at((depth - ray.origin.dot(camera.axis())) / ray.dir.dot(camera.axis()))
    }

    fn lens_grid() -> impl Iterator<Item = (f64, f64)> {
        (0..7).flat_map(|i| (0..7).map(move |j| (i as f64 / 7.0 + 0.05, j as f64 / 7.0 + 0.05)))
    }

    #[test]
    fn a_shifted_lens_focuses_the_shifted_pixel() {
        // Looking down -z, hfov 90 at 200x100, focused at 2: the point (1, 0.5, -2)
        // on the plane of focus is at pixel (150, 25) without a shift and at
        // (100, 45) with shift [0.25, 0.1] (see the perspective camera's test);
        // every lens sample's ray through that pixel goes through it.
        let pinhole = Perspective::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, Fov::HorizontalDeg(90.0)).unwrap();
        let lens = ThinLens::new(pinhole.with_shift([0.25, 0.1]).unwrap(), 0.2, 2.0).unwrap();
        let point = Vec3::new(1.0, 0.5, -2.0);
        for u in [(0.1, 0.9), (0.5, 0.5), (0.8, 0.3)] {
            let ray = lens.ray(100.0, 45.0, 200, 100, u);
            let t = (point.z - ray.origin.z) / ray.dir.z;
            assert!((ray.at(t) - point).length() < 1e-12, "{u:?}: {}", ray.at(t));
        }
        assert_eq!(lens.axis(), -Vec3::Z);
    }

    #[test]
    fn points_on_the_plane_of_focus_stay_sharp() {
        let cam = camera();
        let (w, h) = SIZE;
        for (x, y) in [(100.0, 50.0), (0.0, 0.0), (13.5, 87.25), (200.0, 31.0)] {
            let sharp = at_depth(&cam, &cam.ray(x, y, w, h, (0.5, 0.5)), FOCUS);
            let pinhole = cam.pinhole.ray(x, y, w, h, (0.5, 0.5));
            assert!((sharp - at_depth(&cam, &pinhole, FOCUS)).length() < 1e-12, "the lens centre is the pinhole");
            for lens in lens_grid() {
                let ray = cam.ray(x, y, w, h, lens);
                assert!((ray.origin.length() - 0.0).abs() <= RADIUS * (1.0 + 1e-12), "the ray starts on the lens");
                assert!((at_depth(&cam, &ray, FOCUS) - sharp).length() < 1e-12, "film point ({x}, {y}), lens {lens:?}");
            }
        }
    }

    /// The film point whose ray through lens sample `lens` passes through `point`:
    /// the ray's crossing of `point`'s depth plane is affine in the film point, so
    /// three rays fix it.
    fn image_of(cam: &ThinLens, point: Vec3, lens: (f64, f64)) -> (f64, f64) {
        let (w, h) = SIZE;
        let depth = point.dot(cam.axis());
        let hit = |x: f64, y: f64| at_depth(cam, &cam.ray(x, y, w, h, lens), depth);
        let (o, dx, dy) = (hit(0.0, 0.0), hit(1.0, 0.0) - hit(0.0, 0.0), hit(0.0, 1.0) - hit(0.0, 0.0));
        // Solve o + x dx + y dy = point in the lens plane's coordinates.
        let (r, u) = (cam.lens_right, cam.lens_up);
        let (a, b, c, d) = (dx.dot(r), dy.dot(r), dx.dot(u), dy.dot(u));
        let (er, eu) = ((point - o).dot(r), (point - o).dot(u));
        let det = a * d - b * c;
        ((er * d - b * eu) / det, (a * eu - c * er) / det)
    }

    #[test]
    fn blur_off_the_plane_is_the_circle_of_confusion() {
        let cam = camera();
        let (w, h) = SIZE;
        // Film pixels per unit of the window one unit in front of the eye.
        let tan_h = 20f64.to_radians().tan() * w as f64 / h as f64;
        let pixels_per_unit = (w as f64 / 2.0) / tan_h;
        for depth in [2.0, 4.5, 12.0, 80.0] {
            let point = -Vec3::Z * depth;
            let centre = image_of(&cam, point, (0.5, 0.5));
            assert!((centre.0 - 100.0).abs() < 1e-9 && (centre.1 - 50.0).abs() < 1e-9, "{centre:?}");
            let diameter = 2.0 * RADIUS * (depth - FOCUS).abs() / (depth * FOCUS) * pixels_per_unit;
            // Lens samples on the square's edges map to the aperture's rim: their
            // images lie on the circle of confusion.
            for lens in [(0.0, 0.5), (0.999_999_999_999, 0.5), (0.5, 0.0), (0.0, 0.0), (0.3, 0.999_999_999_999), (0.0, 0.8)] {
                let (x, y) = image_of(&cam, point, lens);
                let radius = (x - centre.0).hypot(y - centre.1);
                assert!(
                    (radius - diameter / 2.0).abs() < 1e-9 * diameter.max(1.0),
                    "depth {depth}, lens {lens:?}: {radius} vs {}",
                    diameter / 2.0
                );
            }
            // Opposite rim points image a full diameter apart.
            let (left, right) = (image_of(&cam, point, (0.0, 0.5)), image_of(&cam, point, (0.999_999_999_999, 0.5)));
            assert!(((left.0 - right.0).abs() - diameter).abs() < 1e-6 * diameter, "depth {depth}");
        }
    }

    #[test]
    fn a_zero_radius_lens_is_the_pinhole() {
        let pinhole = Perspective::look_at(Vec3::ONE, Vec3::ZERO, Vec3::Y, Fov::HorizontalDeg(60.0)).unwrap();
        let cam = ThinLens::new(pinhole.clone(), 0.0, 3.0).unwrap();
        assert!(!cam.uses_lens_sample() && camera().uses_lens_sample());
        for lens in lens_grid() {
            let (a, b) = (cam.ray(3.0, 4.0, 16, 9, lens), pinhole.ray(3.0, 4.0, 16, 9, lens));
            assert!((a.dir - b.dir).length() < 1e-15 && a.origin == b.origin);
        }
    }

    #[test]
    fn the_axis_of_a_raw_window_is_its_normal() {
        let window = Perspective::window(Vec3::ZERO, Vec3::new(0.3, 2.0, 0.1), Vec3::X, Vec3::Z, Fit::Width).unwrap();
        assert_eq!(ThinLens::new(window, 0.1, 1.0).unwrap().axis(), Vec3::Y);
        let flat = Perspective::window(Vec3::ZERO, Vec3::X, Vec3::X, Vec3::Z, Fit::None).unwrap();
        assert!(ThinLens::new(flat, 0.1, 1.0).is_err(), "eye in the window's plane");
        let pinhole = || camera().pinhole;
        assert!(ThinLens::new(pinhole(), -1.0, 1.0).is_err());
        assert!(ThinLens::new(pinhole(), 0.1, 0.0).is_err());
        assert!(ThinLens::new(pinhole(), f64::NAN, 1.0).is_err());
    }
}
