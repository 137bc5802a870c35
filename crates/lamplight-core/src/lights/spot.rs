//! Spot light: a point light whose intensity falls off with the angle from its
//! axis (pbrt-v4's `spot`, glTF `KHR_lights_punctual`'s `spot`).
//!
//! With `theta` the angle between the axis and the direction towards the shaded
//! point, the light arriving at distance `d` is `I * s(cos theta) / d^2`. The
//! profile `s` is 1 inside the inner cone (`theta <= inner_angle`), 0 outside
//! the outer cone (`theta >= outer_angle`) and in between, with
//! `x = (cos theta - cos outer) / (cos inner - cos outer)`:
//! - `"smoothstep"` (pbrt-v4): `s = 3x^2 - 2x^3`;
//! - `"gltf"` (the glTF spec's reference): `s = x^2`;
//! - `"angle"` (Mitsuba 3's `spot`): linear in the angle, `s = (outer - theta) / (outer - inner)`.
//!
//! With a `texture`, the light is also multiplied by an image projected across
//! the outer cone ([`super::slide`]): the image spans `tan(outer_angle)` either
//! side of the axis one unit ahead, upright as seen from the light when `up` is
//! the scene's up (Mitsuba's textured `spot`).
//!
//! pbrt's `coneangle` is `outer_angle` and its `conedelta` is
//! `outer_angle - inner_angle`; glTF's `outerConeAngle` and `innerConeAngle` are
//! the two angles in radians. Both angles are measured from the axis.
//!
//! | parameter | type | default | meaning |
//! |-----------|------|---------|---------|
//! | `position` | point | required | where the light is |
//! | `direction` | vector | one of `direction`, `look_at` | the axis, the way the light shines |
//! | `look_at` | point | | a point on the axis |
//! | `intensity` | colour | required | `I`, radiance at unit distance on the axis |
//! | `outer_angle` | number | 30 | degrees from the axis where the light ends |
//! | `inner_angle` | number | min(25, outer_angle) | degrees from the axis where the falloff starts |
//! | `profile` | string | `"smoothstep"` | `"smoothstep"`, `"gltf"` or `"angle"` |
//! | `texture` | texture | none | an image (or any texture of `(s, t)`) the light projects |
//! | `up` | vector | `[0, 1, 0]` (`[0, 0, 1]` for a vertical axis) | the projected image's up |

use std::sync::Arc;

use super::slide::Slide;
use super::{Light, LightKind, LightSample};
use crate::math::{Rgb, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::Error;

/// How the intensity falls between the inner and the outer cone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpotProfile {
    /// `3x^2 - 2x^3` (pbrt-v4).
    Smoothstep,
    /// `x^2` (glTF `KHR_lights_punctual`).
    Gltf,
    /// Linear in the angle from the axis (Mitsuba 3's `spot`).
    Angle,
}

/// A spot light; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    /// Position in world space.
    pub position: Vec3,
    /// Unit axis, the way the light shines.
    pub axis: Vec3,
    /// Intensity on the axis.
    pub intensity: Rgb,
    /// `cos(inner_angle)`.
    pub cos_inner: f64,
    /// `cos(outer_angle)`.
    pub cos_outer: f64,
    /// The falloff between the cones.
    pub profile: SpotProfile,
    /// A projected image, if any.
    pub slide: Option<Box<Slide>>,
}

/// `spot_light`.
pub const KIND: LightKind = Kind {
    name: "spot_light",
    summary: "a point light limited to a cone, falling off between an inner and an outer angle (pbrt's `spot`, glTF's spot)",
    params: &[
        Param::new("position", T::Point, "", "", "where the light is"),
        Param::new("direction", T::Vector, "one of direction, look_at", "", "the axis, the way the light shines"),
        Param::new("look_at", T::Point, "one of direction, look_at", "", "a point on the axis"),
        Param::new(
            "intensity",
            T::Color,
            "",
            "radiance at unit distance",
            "intensity I on the axis: the light arriving at distance d is I s / d^2",
        ),
        Param::new("outer_angle", T::Number, "30", "degrees, 0 to 90", "angle from the axis where the light ends (pbrt's coneangle)"),
        Param::new(
            "inner_angle",
            T::Number,
            "min(25, outer_angle)",
            "degrees, 0 to outer_angle",
            "angle from the axis where the falloff starts (pbrt's coneangle - conedelta)",
        ),
        Param::new(
            "profile",
            T::String,
            "\"smoothstep\"",
            "",
            "`\"smoothstep\"` (pbrt: 3x^2 - 2x^3), `\"gltf\"` (x^2) or `\"angle\"` (linear in the angle, Mitsuba's) between the cones",
        ),
        Param::new("texture", T::Texture, "none", "", "an image projected across the outer cone, multiplying the light"),
        Param::new("up", T::Vector, "[0, 1, 0] ([0, 0, 1] for a vertical axis)", "", "the projected image's up, as seen from the light"),
    ],
    build: |p, ctx| {
        let position = p.required_vec3("position")?;
        let axis = match (p.vec3("direction")?, p.vec3("look_at")?) {
            (Some(d), None) => d,
            (None, Some(target)) => target - position,
            (None, None) => return Err(p.error("needs `direction` or `look_at`")),
            (Some(_), Some(_)) => return Err(p.error("takes direction or look_at, not both")),
        };
        let intensity = p.color("intensity")?.ok_or_else(|| p.error("needs `intensity` (a colour)"))?;
        let outer = p.number_or("outer_angle", 30.0)?;
        let inner = p.number_or("inner_angle", outer.min(25.0))?;
        let profile = match p.choice("profile", &["smoothstep", "gltf", "angle"])? {
            "smoothstep" => SpotProfile::Smoothstep,
            "angle" => SpotProfile::Angle,
            _ => SpotProfile::Gltf,
        };
        let mut light =
            SpotLight::new(ctx.world.transform_point3(position), ctx.world.transform_vector3(axis), intensity, inner, outer, profile)
                .map_err(|e| p.core_error(e))?;
        let up = p.vec3("up")?;
        if let Some(texture) = ctx.textures.read(p, "texture")? {
            let up = ctx.world.transform_vector3(up.unwrap_or_else(|| default_up(axis)));
            let tan = outer.to_radians().tan();
            light.slide = Some(Box::new(Slide::new(light.axis, up, tan, tan, texture).map_err(|e| p.core_error(e))?));
        } else if up.is_some() {
            return Err(p.key_error("up", "orients a projected image: give `texture` too, or remove `up`"));
        }
        Ok(Arc::new(light))
    },
};

impl SpotLight {
    /// A spot light at `position` shining along `axis` (need not be unit), with
    /// cone half-angles `inner_deg <= outer_deg` in degrees, `0 < outer_deg <= 90`.
    pub fn new(
        position: Vec3,
        axis: Vec3,
        intensity: Rgb,
        inner_deg: f64,
        outer_deg: f64,
        profile: SpotProfile,
    ) -> Result<SpotLight, Error> {
        if !position.is_finite() {
            return Err(Error::invalid("position", "must be finite"));
        }
        let axis = axis.try_normalize().ok_or_else(|| Error::invalid("direction", "must be a non-zero finite vector"))?;
        if !(intensity.is_finite() && intensity.min_element() >= 0.0) {
            return Err(Error::invalid("intensity", format!("must be finite and non-negative, got {intensity}")));
        }
        if !(outer_deg > 0.0 && outer_deg <= 90.0) {
            return Err(Error::invalid("outer_angle", format!("must be above 0 and at most 90 degrees, got {outer_deg}")));
        }
        if !(inner_deg >= 0.0 && inner_deg <= outer_deg) {
            return Err(Error::invalid("inner_angle", format!("must be between 0 and outer_angle ({outer_deg}) degrees, got {inner_deg}")));
        }
        let (cos_inner, cos_outer) = (inner_deg.to_radians().cos(), outer_deg.to_radians().cos());
        Ok(SpotLight { position, axis, intensity, cos_inner, cos_outer, profile, slide: None })
    }

    /// The profile `s(cos theta)` of the module documentation.
    pub fn falloff(&self, cos_theta: f64) -> f64 {
        if cos_theta >= self.cos_inner {
            return 1.0;
        }
        if cos_theta <= self.cos_outer {
            return 0.0;
        }
        let x = (cos_theta - self.cos_outer) / (self.cos_inner - self.cos_outer);
        match self.profile {
            SpotProfile::Smoothstep => x * x * (3.0 - 2.0 * x),
            SpotProfile::Gltf => x * x,
            SpotProfile::Angle => {
                let (inner, outer) = (self.cos_inner.acos(), self.cos_outer.acos());
                ((outer - cos_theta.clamp(-1.0, 1.0).acos()) / (outer - inner)).clamp(0.0, 1.0)
            }
        }
    }
}

impl Light for SpotLight {
    fn illuminate(&self, point: Vec3) -> Option<LightSample> {
        let (wi, distance, d2) = super::point::towards(self.position, point)?;
        let s = self.falloff(-wi.dot(self.axis));
        if s == 0.0 {
            return None;
        }
        let mut radiance = self.intensity * (s / d2);
        if let Some(slide) = &self.slide {
            radiance *= slide.coords(-wi).map_or(Rgb::ZERO, |st| slide.evaluate(st, point));
        }
        Some(LightSample { wi, distance, radiance })
    }

    fn point_source(&self) -> Option<Vec3> {
        Some(self.position)
    }
}

/// The scene's up, `+y`, or `+z` for an axis along `y` (light's own frame).
pub(super) fn default_up(axis: Vec3) -> Vec3 {
    if axis.normalize_or_zero().y.abs() > 0.999 {
        Vec3::Z
    } else {
        Vec3::Y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spot 2 above the origin shining down, inner 20, outer 40 degrees.
    fn spot(profile: SpotProfile) -> SpotLight {
        SpotLight::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y, Rgb::splat(8.0), 20.0, 40.0, profile).unwrap()
    }

    /// The floor point seen from the light at `deg` degrees off the axis.
    fn floor_at(deg: f64) -> Vec3 {
        Vec3::new(2.0 * deg.to_radians().tan(), 0.0, 0.0)
    }

    /// Irradiance on the floor (normal +y) at `deg` off the axis: `I s cos(theta) / d^2`.
    fn irradiance(light: &SpotLight, deg: f64) -> f64 {
        light.illuminate(floor_at(deg)).map_or(0.0, |s| s.radiance.x * s.wi.dot(Vec3::Y))
    }

    #[test]
    fn inside_the_inner_cone_it_is_a_point_light() {
        let light = spot(SpotProfile::Smoothstep);
        for deg in [0.0f64, 10.0, 19.9] {
            let d2 = 4.0 / deg.to_radians().cos().powi(2);
            let expected = 8.0 * deg.to_radians().cos() / d2;
            assert!((irradiance(&light, deg) - expected).abs() < 1e-12, "{deg}");
        }
    }

    #[test]
    fn across_the_falloff_it_follows_the_profile() {
        for profile in [SpotProfile::Smoothstep, SpotProfile::Gltf] {
            let light = spot(profile);
            let (ci, co) = (20f64.to_radians().cos(), 40f64.to_radians().cos());
            for deg in [25.0f64, 30.0, 35.0] {
                let c = deg.to_radians().cos();
                let x = (c - co) / (ci - co);
                let s = if profile == SpotProfile::Smoothstep { 3.0 * x * x - 2.0 * x * x * x } else { x * x };
                let expected = 8.0 * s * c / (4.0 / (c * c));
                assert!((irradiance(&light, deg) - expected).abs() < 1e-12, "{profile:?} {deg}");
            }
            // Continuous at both cones, and decreasing in between.
            assert!((light.falloff(ci) - 1.0).abs() < 1e-12 && light.falloff(co) == 0.0);
            assert!(irradiance(&light, 26.0) > irradiance(&light, 30.0) && irradiance(&light, 30.0) > irradiance(&light, 39.0));
        }
    }

    #[test]
    fn the_angle_profile_is_linear_in_the_angle() {
        let light = spot(SpotProfile::Angle);
        for (deg, expected) in [(25.0f64, 0.75), (30.0, 0.5), (35.0, 0.25)] {
            assert!((light.falloff(deg.to_radians().cos()) - expected).abs() < 1e-12, "{deg}");
        }
    }

    #[test]
    fn outside_the_outer_cone_and_behind_it_is_dark() {
        let light = spot(SpotProfile::Smoothstep);
        assert_eq!(irradiance(&light, 40.5), 0.0);
        assert_eq!(irradiance(&light, 80.0), 0.0);
        assert!(light.illuminate(Vec3::new(0.0, 5.0, 0.0)).is_none(), "behind the light");
    }

    #[test]
    fn bad_cones_are_errors() {
        let new = |i, o| SpotLight::new(Vec3::ZERO, Vec3::Y, Rgb::ONE, i, o, SpotProfile::Smoothstep);
        assert_eq!(new(10.0, 0.0).unwrap_err().to_string(), "invalid outer_angle: must be above 0 and at most 90 degrees, got 0");
        assert_eq!(new(50.0, 40.0).unwrap_err().to_string(), "invalid inner_angle: must be between 0 and outer_angle (40) degrees, got 50");
        assert!(SpotLight::new(Vec3::ZERO, Vec3::ZERO, Rgb::ONE, 1.0, 2.0, SpotProfile::Gltf).is_err());
    }
}
