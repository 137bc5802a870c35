//! Directional light: the same radiance from the same direction everywhere.

use std::sync::Arc;

use super::{Light, LightKind, LightSample};
use crate::math::{Rgb, Vec3};
use crate::params::{Kind, Param, ParamType as T};
use crate::Error;

/// `directional_light`.
pub const KIND: LightKind = Kind {
    name: "directional_light",
    summary: "light from infinitely far",
    params: &[
        Param::new("direction", T::Vector, "", "", "the way the light travels"),
        Param::new("radiance", T::Color, "", "", "incident radiance"),
    ],
    build: |p, ctx| {
        let direction = ctx.world.transform_vector3(p.required_vec3("direction")?);
        let radiance = p.color("radiance")?.ok_or_else(|| p.error("needs `radiance` (a colour)"))?;
        Ok(Arc::new(DirectionalLight::new(direction, radiance).map_err(|e| p.core_error(e))?))
    },
};

/// Light arriving along `direction` (the way the light travels) with constant radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in (from the light towards the scene).
    pub direction: Vec3,
    /// Incident radiance.
    pub radiance: Rgb,
}

impl DirectionalLight {
    /// A directional light; `direction` need not be unit but must not be zero.
    pub fn new(direction: Vec3, radiance: Rgb) -> Result<DirectionalLight, Error> {
        let length = direction.length();
        if !(length > 0.0 && length.is_finite()) {
            return Err(Error::invalid("direction", "must be a non-zero finite vector"));
        }
        if !(radiance.is_finite() && radiance.min_element() >= 0.0) {
            return Err(Error::invalid("radiance", "must be finite and non-negative"));
        }
        Ok(DirectionalLight { direction: direction / length, radiance })
    }
}

impl Light for DirectionalLight {
    fn illuminate(&self, _point: Vec3) -> Option<LightSample> {
        Some(LightSample { wi: -self.direction, distance: f64::INFINITY, radiance: self.radiance })
    }
}
