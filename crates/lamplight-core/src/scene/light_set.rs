//! The lights a scene's integrators sample ([`LightSet`]): its delta lights,
//! its emitting objects as area lights, and its sky.

use super::Scene;
use crate::lights::{AreaLight, LightSet};

impl Scene {
    /// The scene's [`LightSet`]: an area light for every object whose material
    /// emits, a constant or a texture (one-sided or two-sided as the material, facing as the object),
    /// with the scene's delta lights and sky.
    pub fn light_set(&self) -> LightSet {
        let mut area = Vec::new();
        for (i, object) in self.objects.iter().enumerate() {
            let material = &self.materials[object.material];
            let texture = material.emission_texture();
            if material.emission.max_element() > 0.0 || texture.is_some() {
                if let Some(light) = AreaLight::new(i, object.shape.clone(), material.emission) {
                    let light = light.with_texture(texture.cloned());
                    area.push(light.with_two_sided(material.two_sided).with_reversed(object.reversed));
                }
            }
        }
        let settings = &self.settings;
        LightSet::new(self.lights.clone(), area, settings.environment.clone(), settings.background, self.objects.len())
    }
}
