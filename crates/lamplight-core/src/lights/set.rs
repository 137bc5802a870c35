//! Every light the path tracer samples: the lecture's point and directional lights
//! (delta lights), emitting objects (area lights) and the environment.
//!
//! One light is picked uniformly per light sample, with probability `1 / count`.
//! When the scene has no environment of its own, the ambient light becomes a
//! uniform sky lighting every surface, and rays leaving the camera straight into
//! the sky see the scene's background colour (so lecture scenes keep their look).
//!
//! The sky's radiance is not `La` itself: the lecture's ambient term `ka C La` is
//! what a diffuse surface of albedo `kd C` reflects under an open sky of radiance
//! `(ka / kd) La`. The sky takes `La` times the mean of `ka / kd` over the scene's
//! diffuse materials (0.125 for luxo's table), so a scene keeps the fill light
//! balance its author set against its lamps.

use std::sync::Arc;

use super::{AreaLight, Environment, Light};
use crate::math::Rgb;
use crate::scene::Scene;

/// The lights of a scene in one list.
#[derive(Debug)]
pub struct LightSet {
    /// Point and directional lights.
    pub delta: Vec<Arc<dyn Light>>,
    /// Emitting objects.
    pub area: Vec<AreaLight>,
    /// The sky, if any.
    pub environment: Option<Arc<Environment>>,
    /// What camera rays that hit nothing see.
    pub camera_background: Option<Rgb>,
    by_object: Vec<Option<u32>>,
}

/// A light picked from the set.
#[derive(Clone, Copy, Debug)]
pub enum Picked<'a> {
    /// A point or directional light.
    Delta(&'a dyn Light),
    /// An emitting object.
    Area(&'a AreaLight),
    /// The sky.
    Environment(&'a Environment),
}

impl LightSet {
    /// Collects the lights of `scene`.
    pub fn new(scene: &Scene) -> LightSet {
        let mut by_object = vec![None; scene.objects.len()];
        let mut area = Vec::new();
        for (i, object) in scene.objects.iter().enumerate() {
            let emission = scene.materials[object.material].emission;
            if emission.max_element() > 0.0 {
                if let Some(light) = AreaLight::new(i, object.shape.clone(), emission) {
                    by_object[i] = Some(area.len() as u32);
                    area.push(light);
                }
            }
        }
        let (environment, camera_background) = match &scene.environment {
            Some(env) => (Some(env.clone()), None),
            None if scene.ambient.max_element() > 0.0 => {
                let ratios: Vec<f64> = scene
                    .materials
                    .iter()
                    .filter(|m| m.kd.max_element() > 0.0)
                    .map(|m| (m.ka.max_element() / m.kd.max_element()).min(1.0))
                    .collect();
                let scale = if ratios.is_empty() { 1.0 } else { ratios.iter().sum::<f64>() / ratios.len() as f64 };
                let sky = scene.ambient * scale;
                let env = (sky.max_element() > 0.0).then(|| Arc::new(Environment::Constant(sky)));
                (env, Some(scene.background))
            }
            None => (None, Some(scene.background)),
        };
        LightSet { delta: scene.lights.clone(), area, environment, camera_background, by_object }
    }

    /// Number of lights.
    pub fn count(&self) -> usize {
        self.delta.len() + self.area.len() + usize::from(self.environment.is_some())
    }

    /// Probability of picking any one light.
    pub fn pick_probability(&self) -> f64 {
        1.0 / self.count().max(1) as f64
    }

    /// The light picked by uniform `u`.
    pub fn pick(&self, u: f64) -> Option<Picked<'_>> {
        let n = self.count();
        if n == 0 {
            return None;
        }
        let mut i = ((u * n as f64) as usize).min(n - 1);
        if i < self.delta.len() {
            return Some(Picked::Delta(self.delta[i].as_ref()));
        }
        i -= self.delta.len();
        if i < self.area.len() {
            return Some(Picked::Area(&self.area[i]));
        }
        self.environment.as_deref().map(Picked::Environment)
    }

    /// The area light of object `object`, if it emits.
    pub fn area_light_of(&self, object: usize) -> Option<&AreaLight> {
        self.by_object.get(object).copied().flatten().map(|i| &self.area[i as usize])
    }
}
