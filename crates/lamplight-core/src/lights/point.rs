//! Point light: radiance from one position, falling off with the squared distance.

use std::sync::Arc;

use super::{Light, LightKind, LightSample};
use crate::math::{Rgb, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::Error;

/// `point_light`.
pub const KIND: LightKind = Kind {
    name: "point_light",
    summary: "a point light",
    params: &[
        Param::new("position", T::Point, "", "", "position"),
        Param::new("intensity", T::Color, "", "radiance at unit distance", "intensity I: the light arriving at distance d is I / d^2"),
        Param::new("falloff", T::String, "\"inverse_square\"", "", "`\"inverse_square\"` or `\"none\"` (constant, as in Heckbert's card)"),
        Param::new("own_object", T::String, "none", "", "the one shape (its bulb) that does not shadow it"),
    ],
    build: |p, ctx| {
        let position = ctx.world.transform_point3(p.required_vec3("position")?);
        let intensity = p.color("intensity")?.ok_or_else(|| p.error("needs `intensity` (a colour)"))?;
        let mut light = PointLight::new(position, intensity).map_err(|e| p.core_error(e))?;
        light.falloff = match p.choice("falloff", &["inverse_square", "none"])? {
            "inverse_square" => Falloff::InverseSquare,
            _ => Falloff::None,
        };
        if let Some(name) = p.string("own_object")? {
            light.own_object = Some((ctx.object)(name).map_err(|m| p.key_error("own_object", m))?);
        }
        Ok(Arc::new(light))
    },
};

/// How a point light's intensity decreases with distance `d`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Falloff {
    /// `I / d^2`: physical point light.
    InverseSquare,
    /// `I`: constant, as in Heckbert's business-card tracer.
    None,
}

/// A point light at `position` with intensity `intensity`.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// Position in world space.
    pub position: Vec3,
    /// Intensity (radiance at unit distance for inverse-square falloff).
    pub intensity: Rgb,
    /// Distance falloff.
    pub falloff: Falloff,
    /// Scene object that must not shadow this light (its bulb), if any.
    pub own_object: Option<usize>,
}

impl PointLight {
    /// A point light with inverse-square falloff.
    pub fn new(position: Vec3, intensity: Rgb) -> Result<PointLight, Error> {
        if !position.is_finite() {
            return Err(Error::invalid("position", "must be finite"));
        }
        if !(intensity.is_finite() && intensity.min_element() >= 0.0) {
            return Err(Error::invalid("intensity", format!("must be finite and non-negative, got {intensity}")));
        }
        Ok(PointLight { position, intensity, falloff: Falloff::InverseSquare, own_object: None })
    }

    /// The same light with another falloff.
    pub fn with_falloff(mut self, falloff: Falloff) -> PointLight {
        self.falloff = falloff;
        self
    }
}

/// The unit direction from `point` to a light at `position`, the distance and
/// its square; `None` at the light itself.
#[inline]
pub(crate) fn towards(position: Vec3, point: Vec3) -> Option<(Vec3, f64, f64)> {
    let to_light = position - point;
    let d2 = to_light.length_squared();
    if !(d2 > 0.0) {
        return None;
    }
    let distance = d2.sqrt();
    Some((to_light / distance, distance, d2))
}

impl Light for PointLight {
    #[inline]
    fn illuminate(&self, point: Vec3) -> Option<LightSample> {
        let (wi, distance, d2) = towards(self.position, point)?;
        let radiance = match self.falloff {
            Falloff::InverseSquare => self.intensity / d2,
            Falloff::None => self.intensity,
        };
        Some(LightSample { wi, distance, radiance })
    }

    fn point_source(&self) -> Option<Vec3> {
        Some(self.position)
    }

    fn own_object(&self) -> Option<usize> {
        self.own_object
    }

    fn point_light(&self) -> Option<&PointLight> {
        Some(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_square_and_constant_falloff() {
        let light = PointLight::new(Vec3::new(0.0, 2.0, 0.0), Rgb::splat(8.0)).unwrap();
        let s = light.illuminate(Vec3::ZERO).unwrap();
        assert_eq!(s.wi, Vec3::Y);
        assert_eq!(s.distance, 2.0);
        assert_eq!(s.radiance, Rgb::splat(2.0));
        let flat = light.with_falloff(Falloff::None);
        assert_eq!(flat.illuminate(Vec3::ZERO).unwrap().radiance, Rgb::splat(8.0));
        assert!(flat.illuminate(Vec3::new(0.0, 2.0, 0.0)).is_none(), "at the light itself the direction is undefined");
    }
}
