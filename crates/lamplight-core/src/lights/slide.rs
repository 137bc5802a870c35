//! An image projected from a point, as a slide projector throws it: the
//! texture of a textured spot light and of a projector.
//!
//! The light looks along its unit `axis`; `up` (made perpendicular to the axis)
//! and `right = axis x up` complete its frame, as a camera's. A direction `d`
//! leaving the light, with `x = d.right`, `y = d.up`, `z = d.axis > 0`, meets the
//! image at
//!
//! `s = 1/2 + x / (2 z tan_x)`, `t = 1/2 + y / (2 z tan_y)`,
//!
//! so the image spans `[-tan_x, tan_x] x [-tan_y, tan_y]` on the plane one unit
//! in front of the light, its left edge (`s = 0`) on the left and its top row
//! (lamplight's `t = 1`) at the top as seen from the light, the way a camera at
//! the light with the same frame would see it.

use crate::materials::{ShadingPoint, Texture};
use crate::math::{Rgb, Vec3};
use crate::Error;

/// A texture projected from a light; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Slide {
    /// Unit direction the light looks along.
    pub axis: Vec3,
    /// Unit, perpendicular to `axis`: the image's `s` grows along it.
    pub right: Vec3,
    /// Unit, perpendicular to both: the image's `t` grows along it.
    pub up: Vec3,
    /// `tan` of half the image's horizontal angle.
    pub tan_x: f64,
    /// `tan` of half the image's vertical angle.
    pub tan_y: f64,
    /// The projected image (or any texture of `(s, t)`).
    pub texture: Texture,
}

impl Slide {
    /// The frame of a light looking along `axis` (unit) with `up` as its
    /// approximate up; an error where `up` is zero, not finite or parallel to the axis.
    pub fn new(axis: Vec3, up: Vec3, tan_x: f64, tan_y: f64, texture: Texture) -> Result<Slide, Error> {
        let right = axis
            .cross(up)
            .try_normalize()
            .ok_or_else(|| Error::invalid("up", format!("must be a finite vector not parallel to the light's direction, got {up}")))?;
        if !(tan_x.is_finite() && tan_x > 0.0 && tan_y.is_finite() && tan_y > 0.0) {
            return Err(Error::invalid("fov", format!("must give a field of view between 0 and 180 degrees, got tan {tan_x}, {tan_y}")));
        }
        Ok(Slide { axis, right, up: right.cross(axis), tan_x, tan_y, texture })
    }

    /// The image coordinates `(s, t)` the unit direction `d` (away from the
    /// light) meets, or `None` behind the light.
    pub fn coords(&self, d: Vec3) -> Option<[f64; 2]> {
        let z = d.dot(self.axis);
        if !(z > 0.0) {
            return None;
        }
        Some([0.5 + d.dot(self.right) / (2.0 * z * self.tan_x), 0.5 + d.dot(self.up) / (2.0 * z * self.tan_y)])
    }

    /// The texture at `(s, t)` (the texture's own wrap mode applies outside `[0, 1]`).
    pub fn evaluate(&self, st: [f64; 2], at: Vec3) -> Rgb {
        let mut point = ShadingPoint::at(at);
        point.uv = st;
        let value = self.texture.evaluate(&point);
        // A texture may hold anything a file holds; no negative or non-finite light.
        Rgb::new(clean(value.x), clean(value.y), clean(value.z))
    }
}

fn clean(x: f64) -> f64 {
    if x.is_finite() && x > 0.0 {
        x
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::texture::UvChecker;
    use crate::materials::UvTransform;
    use std::sync::Arc;

    /// A light at the origin looking down -z with +y up: right is +x, as a camera's.
    fn slide(texture: Texture) -> Slide {
        Slide::new(-Vec3::Z, Vec3::Y, 0.5, 0.25, texture).unwrap()
    }

    #[test]
    fn directions_meet_the_image_where_a_camera_would_see_them() {
        let s = slide(Texture::Constant(Rgb::ONE));
        assert_eq!(s.right, Vec3::X);
        assert_eq!(s.up, Vec3::Y);
        let at = |x: f64, y: f64| s.coords(Vec3::new(x, y, -1.0).normalize()).unwrap();
        let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12;
        assert!(close(at(0.0, 0.0), [0.5, 0.5]));
        // The image's corners lie at (+-tan_x, +-tan_y) one unit ahead.
        assert!(close(at(-0.5, -0.25), [0.0, 0.0]), "{:?}", at(-0.5, -0.25));
        assert!(close(at(0.5, 0.25), [1.0, 1.0]));
        assert!(close(at(0.25, 0.0), [0.75, 0.5]));
        // The same direction twice as far along is the same image point.
        assert!(close(s.coords(Vec3::new(0.5, 0.25, -2.0).normalize()).unwrap(), [0.75, 0.75]));
        assert_eq!(s.coords(Vec3::Z), None, "behind the light");
        assert_eq!(s.coords(Vec3::X), None, "beside it");
    }

    #[test]
    fn the_texture_is_read_at_the_image_coordinates_and_never_negative() {
        let checker = UvChecker { transform: UvTransform::new([2.0, 2.0], 0.0, [0.0, 0.0]), even: Rgb::ONE, odd: Rgb::splat(-3.0) };
        let s = slide(Texture::UvChecker(Arc::new(checker)));
        // (s, t) in [0, 0.5)^2 is cell (0, 0), even; [0.5, 1) x [0, 0.5) is odd.
        assert_eq!(s.evaluate([0.25, 0.25], Vec3::ZERO), Rgb::ONE);
        assert_eq!(s.evaluate([0.75, 0.25], Vec3::ZERO), Rgb::ZERO);
    }

    #[test]
    fn an_up_along_the_axis_is_an_error() {
        let e = Slide::new(Vec3::Y, Vec3::Y, 1.0, 1.0, Texture::Constant(Rgb::ONE)).unwrap_err();
        assert_eq!(e.to_string(), "invalid up: must be a finite vector not parallel to the light's direction, got [0, 1, 0]");
    }
}
