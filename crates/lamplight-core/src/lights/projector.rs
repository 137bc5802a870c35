//! Projector: a point light that throws an image into the scene through a
//! pinhole, the reverse of a perspective camera (Mitsuba 3's `projector`,
//! Blender's spot light with an image behind it).
//!
//! The image lies on the plane one unit in front of the light, spanning the
//! field of view ([`super::slide`] gives the frame and the coordinates). Its
//! values are the **irradiance on that plane**: a surface facing the light at
//! distance `z` along the axis receives `strength T(s, t) / z^2`, however far from
//! the axis, so a constant image lights a facing wall evenly. For that the
//! light arriving at a point at distance `d` whose direction makes the angle
//! `theta` with the axis (`z = d cos theta`) is
//!
//! `Lin = strength T(s, t) / (z^2 cos theta) = strength T(s, t) d / z^3`,
//!
//! and nothing outside the image. As for every delta light, the path tracer
//! reads `Lin` times pi ([`super::DELTA_SCALE`]): the physical irradiance on
//! the facing plane is `pi strength T / z^2`, which is also what Mitsuba's
//! `projector` computes from its `irradiance` texture `T` and `scale`.
//!
//! | parameter | type | default | meaning |
//! |-----------|------|---------|---------|
//! | `position` | point | `[0, 0, 0]` | the pinhole |
//! | `direction` | vector | one of `direction`, `look_at` | the way it shines |
//! | `look_at` | point | | a point on its axis |
//! | `up` | vector | `[0, 1, 0]` (`[0, 0, 1]` for a vertical axis) | the image's up |
//! | `texture` | texture | required | the image `T` (its size gives the aspect) |
//! | `strength` | number | 1 | multiplies `T` |
//! | `fov` | number | 40 | degrees, along `fov_axis` |
//! | `fov_axis` | string | `"x"` | `"x"`, `"y"` or `"diagonal"` of the image |

use std::sync::Arc;

use super::slide::Slide;
use super::spot::default_up;
use super::{Light, LightKind, LightSample};
use crate::materials::Texture;
use crate::math::{Rgb, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::Error;

/// `projector`.
pub const KIND: LightKind = Kind {
    name: "projector",
    summary: "a point light that projects an image through a pinhole (Mitsuba's `projector`); the image is the irradiance one unit ahead",
    params: &[
        Param::new("position", T::Point, "[0, 0, 0]", "", "the pinhole"),
        Param::new("direction", T::Vector, "one of direction, look_at", "", "the way it shines"),
        Param::new("look_at", T::Point, "one of direction, look_at", "", "a point on its axis"),
        Param::new("up", T::Vector, "[0, 1, 0] ([0, 0, 1] for a vertical axis)", "", "the image's up, as seen from the light"),
        Param::new(
            "texture",
            T::Texture,
            "",
            "",
            "the projected image: irradiance on the plane one unit ahead (its size gives the aspect)",
        ),
        Param::new("strength", T::Number, "1", ">= 0", "multiplies the image (`scale` would be the node's transform)"),
        Param::new("fov", T::Number, "40", "degrees, 0 to 180", "field of view along fov_axis"),
        Param::new("fov_axis", T::String, "\"x\"", "", "`\"x\"`, `\"y\"` or `\"diagonal\"`: the image axis `fov` spans"),
    ],
    build: |p, ctx| {
        let position = p.vec3("position")?.unwrap_or(Vec3::ZERO);
        let axis = match (p.vec3("direction")?, p.vec3("look_at")?) {
            (Some(d), None) => d,
            (None, Some(target)) => target - position,
            (None, None) => return Err(p.error("needs `direction` or `look_at`")),
            (Some(_), Some(_)) => return Err(p.error("takes direction or look_at, not both")),
        };
        let up = p.vec3("up")?.unwrap_or_else(|| default_up(axis));
        let texture = ctx.textures.read(p, "texture")?.ok_or_else(|| p.error("needs `texture` (the image it projects)"))?;
        let strength = p.number_or("strength", 1.0)?;
        let fov = p.number_or("fov", 40.0)?;
        let fov_axis = p.choice("fov_axis", &["x", "y", "diagonal"])?;
        let aspect = match &texture {
            Texture::Image(image) => {
                let (w, h) = image.image.size();
                w as f64 / h as f64
            }
            _ => 1.0,
        };
        let (world_position, world_axis, world_up) =
            (ctx.world.transform_point3(position), ctx.world.transform_vector3(axis), ctx.world.transform_vector3(up));
        let light = Projector::new(world_position, world_axis, world_up, texture, strength, fov, fov_axis, aspect);
        Ok(Arc::new(light.map_err(|e| p.core_error(e))?))
    },
};

/// A projector; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Projector {
    /// The pinhole.
    pub position: Vec3,
    /// The image, its frame and its angles.
    pub slide: Slide,
    /// Multiplies the image.
    pub strength: f64,
}

impl Projector {
    /// A projector at `position` looking along `axis` with `up`, throwing
    /// `texture` (of width over height `aspect`, times `strength`) across `fov_deg` degrees of
    /// its `fov_axis` (`"x"`, `"y"` or `"diagonal"`).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        position: Vec3,
        axis: Vec3,
        up: Vec3,
        texture: Texture,
        strength: f64,
        fov_deg: f64,
        fov_axis: &str,
        aspect: f64,
    ) -> Result<Projector, Error> {
        if !position.is_finite() {
            return Err(Error::invalid("position", "must be finite"));
        }
        let axis = axis.try_normalize().ok_or_else(|| Error::invalid("direction", "must be a non-zero finite vector"))?;
        if !(strength.is_finite() && strength >= 0.0) {
            return Err(Error::invalid("strength", format!("must be finite and non-negative, got {strength}")));
        }
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(Error::invalid("fov", format!("must be between 0 and 180 degrees, got {fov_deg}")));
        }
        let t = (fov_deg.to_radians() / 2.0).tan();
        let (tan_x, tan_y) = match fov_axis {
            "x" => (t, t / aspect),
            "y" => (t * aspect, t),
            _ => {
                let diagonal = (1.0 + aspect * aspect).sqrt();
                (t * aspect / diagonal, t / diagonal)
            }
        };
        Ok(Projector { position, slide: Slide::new(axis, up, tan_x, tan_y, texture)?, strength })
    }
}

impl Light for Projector {
    fn illuminate(&self, point: Vec3) -> Option<LightSample> {
        let (wi, distance, _) = super::point::towards(self.position, point)?;
        let st = self.slide.coords(-wi)?;
        if !(0.0..=1.0).contains(&st[0]) || !(0.0..=1.0).contains(&st[1]) {
            return None;
        }
        let z = distance * -wi.dot(self.slide.axis);
        let value = self.slide.evaluate(st, point) * (self.strength * distance / (z * z * z));
        if value == Rgb::ZERO || !value.is_finite() {
            return None;
        }
        Some(LightSample { wi, distance, radiance: value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::texture::UvChecker;
    use crate::materials::UvTransform;

    /// A projector at the origin looking down -z, 90 degrees wide, of a
    /// two-by-two checker (1 and 3) at aspect 2.
    fn projector() -> Projector {
        let cells = UvChecker { transform: UvTransform::new([2.0, 2.0], 0.0, [0.0, 0.0]), even: Rgb::ONE, odd: Rgb::splat(3.0) };
        Projector::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, Texture::UvChecker(Arc::new(cells)), 2.0, 90.0, "x", 2.0).unwrap()
    }

    /// Irradiance on a wall at z = -depth facing the light, at (x, y).
    fn wall_irradiance(light: &Projector, x: f64, y: f64, depth: f64) -> f64 {
        light.illuminate(Vec3::new(x, y, -depth)).map_or(0.0, |s| s.radiance.x * s.wi.dot(Vec3::Z))
    }

    #[test]
    fn a_facing_wall_receives_the_image_over_the_squared_depth() {
        let light = projector();
        for depth in [1.0, 2.5] {
            // Lower left cell (even, 1), lower right (odd, 3), at any distance from the axis.
            for (x, y, value) in [(-0.3, -0.2, 1.0), (-0.9, -0.45, 1.0), (0.3, -0.2, 3.0), (0.9, 0.45, 1.0), (-0.9, 0.45, 3.0)] {
                let expected = 2.0 * value / (depth * depth);
                let got = wall_irradiance(&light, x * depth, y * depth, depth);
                assert!((got - expected).abs() < 1e-12, "depth {depth} at ({x}, {y}): {got} against {expected}");
            }
        }
    }

    #[test]
    fn nothing_outside_the_image_or_behind_it() {
        let light = projector();
        // tan_x = 1, tan_y = 0.5: the image ends at |x| = z and |y| = z / 2.
        assert_eq!(wall_irradiance(&light, 1.01, 0.0, 1.0), 0.0);
        assert_eq!(wall_irradiance(&light, 0.0, 0.51, 1.0), 0.0);
        assert!(wall_irradiance(&light, 0.0, 0.49, 1.0) > 0.0);
        assert!(light.illuminate(Vec3::new(0.0, 0.0, 1.0)).is_none());
    }

    #[test]
    fn the_field_of_view_axis_sets_both_angles() {
        let t = |axis| {
            let p = Projector::new(Vec3::ZERO, Vec3::Z, Vec3::Y, Texture::Constant(Rgb::ONE), 1.0, 90.0, axis, 2.0).unwrap();
            (p.slide.tan_x, p.slide.tan_y)
        };
        let (x, y) = t("x");
        assert!((x - 1.0).abs() < 1e-12 && (y - 0.5).abs() < 1e-12);
        let (x, y) = t("y");
        assert!((x - 2.0).abs() < 1e-12 && (y - 1.0).abs() < 1e-12);
        let (x, y) = t("diagonal");
        assert!((x.hypot(y) - 1.0).abs() < 1e-12 && (x / y - 2.0).abs() < 1e-12);
    }

    #[test]
    fn bad_values_are_errors() {
        let new = |scale, fov| Projector::new(Vec3::ZERO, Vec3::Z, Vec3::Y, Texture::Constant(Rgb::ONE), scale, fov, "x", 1.0);
        assert_eq!(new(1.0, 180.0).unwrap_err().to_string(), "invalid fov: must be between 0 and 180 degrees, got 180");
        assert_eq!(new(-1.0, 40.0).unwrap_err().to_string(), "invalid strength: must be finite and non-negative, got -1");
    }
}
