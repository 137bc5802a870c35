//! Point light: radiance from one position, falling off with the squared distance.

use super::{Light, LightSample};
use crate::math::{Rgb, Vec3};
use crate::Error;

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

impl Light for PointLight {
    fn illuminate(&self, point: Vec3) -> Option<LightSample> {
        let to_light = self.position - point;
        let d2 = to_light.length_squared();
        if !(d2 > 0.0) {
            return None;
        }
        let distance = d2.sqrt();
        let radiance = match self.falloff {
            Falloff::InverseSquare => self.intensity / d2,
            Falloff::None => self.intensity,
        };
        Some(LightSample { wi: to_light / distance, distance, radiance })
    }

    fn own_object(&self) -> Option<usize> {
        self.own_object
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
